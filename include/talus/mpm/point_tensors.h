#ifndef talus_mpm_point_tensors_h
#define talus_mpm_point_tensors_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <utility>

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

      /**
       * Component and node of local dof @p i of a material cell's cache
       * (MPMSolver::CellCache): i = node * dim + component, the vertex-major
       * order of FESystem<FE_Q(1)^dim> on a cell and the order of the
       * uGIMP patch nodes.
       */
      template <int dim>
      inline std::pair<unsigned int, unsigned int>
      component_and_node(const unsigned int i)
      {
        return {i % dim, i / dim};
      }

      /**
       * The 1D uGIMP weight function (Bardenhagen and Kober 2004; Steffen,
       * Kirby and Berzins 2008, eq. 17) of a node at distance @p r = x_p -
       * x_I from a point of half-width @p l < h/2, grid spacing @p h, and
       * its derivative with respect to x_p in @p dS.
       */
      inline double
      ugimp_weight(const double r, const double h, const double l, double &dS)
      {
        const double a = std::abs(r);
        const double s = r < 0. ? -1. : 1.;
        if (a < l)
          {
            dS = -r / (h * l);
            return 1. - (r * r + l * l) / (2. * h * l);
          }
        if (a < h - l)
          {
            dS = -s / h;
            return 1. - a / h;
          }
        if (a < h + l)
          {
            dS = -s * (h + l - a) / (2. * h * l);
            return (h + l - a) * (h + l - a) / (4. * h * l);
          }
        dS = 0.;
        return 0.;
      }

      /**
       * The 1D GIMP weight function of a node at distance @p r = x_p - x_I
       * from a point of any half-width 0 <= @p l <= @p h (cpGIMP's
       * convected domains; Wallstedt and Guilkey 2008): the grid's hat
       * function N(s) = max(0, 1 - |s|/h) averaged over the point's domain,
       * S = (Phi(r + l) - Phi(r - l)) / (2 l) with Phi the antiderivative
       * of N, and its derivative dS/dx_p = (N(r + l) - N(r - l)) / (2 l)
       * in @p dS. For l <= h/2 it is ugimp_weight() (the same closed form,
       * bit for bit); beyond, the antiderivative form.
       */
      inline double
      gimp_weight(const double r, const double h, const double l, double &dS)
      {
        if (l <= 0.5 * h)
          return ugimp_weight(r, h, l, dS);
        const auto Phi = [h](const double y) {
          if (y <= -h)
            return 0.;
          if (y <= 0.)
            return (y + h) * (y + h) / (2. * h);
          if (y < h)
            return h - (h - y) * (h - y) / (2. * h);
          return h;
        };
        const auto N = [h](const double s) {
          return std::max(0., 1. - std::abs(s) / h);
        };
        dS = (N(r + l) - N(r - l)) / (2. * l);
        return (Phi(r + l) - Phi(r - l)) / (2. * l);
      }
    } // namespace internal
  }   // namespace MPM
} // namespace Talus

#endif
