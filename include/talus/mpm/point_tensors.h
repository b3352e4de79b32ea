#ifndef talus_mpm_point_tensors_h
#define talus_mpm_point_tensors_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

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
      /**
       * The CPDI1 weights and gradients (convected particle domain
       * interpolation; Sadeghirad, Brannon and Burghardt 2011, IJNME 86)
       * of a point whose domain is the parallelogram (2D) or
       * parallelepiped (3D) x_p + R xi, xi in [-1, 1]^dim, spanned by the
       * half-vectors r_i, the columns of @p R [m] (r_i = F r_i^0). N_I is
       * replaced by its multilinear interpolant through the 2^dim corners
       * x_c = x_p + R s_c (s_c in {-1, 1}^dim) and averaged over the
       * domain:
       *   S_I = 2^-dim sum_c N_I(x_c),
       *   grad S_I = 2^-dim sum_c N_I(x_c) R^-T s_c,
       * in 2D eq. (31)-(32) of the paper (R^-T s_c / 4 = the corner vectors
       * over the volume 4 det R). Partition of unity, sum grad S_I = 0 and
       * the reproduction of linear fields (sum S_I x_I = x_p, sum x_I (x)
       * grad S_I = I) hold for any R with det R > 0.
       *
       * Coordinates in cell units: @p xi the point's position relative to
       * the lowest vertex of its cell (of size @p h), @p nodes the nodes'
       * integer offsets, N_I the Q1 hat of the Cartesian grid. The corners
       * must lie in [@p lowest, @p highest] per direction (the node patch
       * and the grid); otherwise R is scaled down uniformly about x_p until
       * they do, and the scale (1: not scaled) is returned. A domain scaled
       * to (nearly) nothing, scale <= 1e-6, or with det R <= 0 falls back to
       * the Q1 functions at x_p, CPDI's limit for a vanishing domain.
       * Writes one value and gradient per node into @p values and
       * @p gradients.
       */
      template <int dim>
      inline double
      cpdi_weights(const dealii::Point<dim>                &xi,
                   const dealii::Tensor<2, dim>            &R,
                   const dealii::Tensor<1, dim>            &h,
                   const dealii::Tensor<1, dim>            &lowest,
                   const dealii::Tensor<1, dim>            &highest,
                   const std::vector<std::array<int, dim>> &nodes,
                   double                                  *values,
                   dealii::Tensor<1, dim>                  *gradients)
      {
        constexpr unsigned int n_corners = 1u << dim;
        const auto             sign      = [](const unsigned int k) {
          dealii::Tensor<1, dim> s;
          for (unsigned int d = 0; d < dim; ++d)
            s[d] = (k >> d) & 1u ? 1. : -1.;
          return s;
        };
        // corner offsets R s_c in cell units and the scale that keeps
        // every corner in [lowest, highest]
        std::array<dealii::Tensor<1, dim>, n_corners> offset;
        double                                        scale = 1.;
        for (unsigned int k = 0; k < n_corners; ++k)
          {
            const dealii::Tensor<1, dim> o = R * sign(k);
            for (unsigned int d = 0; d < dim; ++d)
              {
                offset[k][d] = o[d] / h[d];
                if (xi[d] + offset[k][d] > highest[d])
                  scale = std::min(scale, (highest[d] - xi[d]) / offset[k][d]);
                else if (xi[d] + offset[k][d] < lowest[d])
                  scale = std::min(scale, (lowest[d] - xi[d]) / offset[k][d]);
              }
          }
        scale = std::max(0., scale);
        for (unsigned int j = 0; j < nodes.size(); ++j)
          {
            values[j]    = 0.;
            gradients[j] = dealii::Tensor<1, dim>();
          }
        if (!(scale > 1e-6) || !(dealii::determinant(R) > 0.))
          {
            // the Q1 functions at x_p
            for (unsigned int j = 0; j < nodes.size(); ++j)
              {
                double S[dim], dS[dim];
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double r = xi[d] - nodes[j][d];
                    S[d]           = std::max(0., 1. - std::abs(r));
                    dS[d] = std::abs(r) < 1. ? (r < 0. ? 1. : -1.) / h[d] : 0.;
                  }
                values[j] = 1.;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    values[j] *= S[d];
                    double g = dS[d];
                    for (unsigned int e = 0; e < dim; ++e)
                      if (e != d)
                        g *= S[e];
                    gradients[j][d] = g;
                  }
              }
            return scale;
          }
        const double                 mean  = 1. / n_corners;
        const dealii::Tensor<2, dim> RinvT = transpose(invert(scale * R));
        for (unsigned int k = 0; k < n_corners; ++k)
          {
            const dealii::Tensor<1, dim> g = mean * (RinvT * sign(k));
            for (unsigned int j = 0; j < nodes.size(); ++j)
              {
                double N = 1.;
                for (unsigned int d = 0; d < dim && N > 0.; ++d)
                  N *= std::max(0.,
                                1. - std::abs(xi[d] + scale * offset[k][d] -
                                              nodes[j][d]));
                if (N == 0.)
                  continue;
                values[j] += mean * N;
                gradients[j] += N * g;
              }
          }
        return scale;
      }
    } // namespace internal
  }   // namespace MPM
} // namespace Talus

#endif
