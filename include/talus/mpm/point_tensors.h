#ifndef talus_mpm_point_tensors_h
#define talus_mpm_point_tensors_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/tensor.h>

namespace Talus
{
  namespace MPM
  {
    /**
     * Small tensor conversions shared by the phases of the MPM step
     * (transfer, assembly, boundary imposition): the constitutive models
     * work in 3x3, the solver in dim x dim, and the points store tensors
     * row by row in their property arrays.
     */
    namespace internal
    {
      /**
       * Embed an in-plane (dim x dim) deformation gradient in 3D (plane
       * strain: F_33 = 1, no out-of-plane shear).
       */
      template <int dim>
      inline dealii::Tensor<2, 3>
      embed(const dealii::Tensor<2, dim> &F)
      {
        dealii::Tensor<2, 3> F3;
        for (unsigned int i = 0; i < 3; ++i)
          F3[i][i] = 1.;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            F3[i][j] = F[i][j];
        return F3;
      }

      /**
       * The dim x dim tensor stored row by row in @p p from index
       * @p first on.
       */
      template <int dim>
      inline dealii::Tensor<2, dim>
      read_tensor(const dealii::ArrayView<const double> &p,
                  const unsigned int                     first)
      {
        dealii::Tensor<2, dim> t;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            t[i][j] = p[first + i * dim + j];
        return t;
      }
    } // namespace internal
  }   // namespace MPM
} // namespace Talus

#endif
