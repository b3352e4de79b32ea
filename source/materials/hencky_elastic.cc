#include <talus/materials/exceptions.h>
#include <talus/materials/hencky_elastic.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace Talus
{
  namespace Materials
  {
    namespace LogarithmicStrain
    {
      SpectralDecomposition
      spectral_decomposition(const dealii::Tensor<2, 3> &b)
      {
        // Cyclic Jacobi method (W.H. Press et al., Numerical Recipes, 3rd
        // ed., section 11.1) on a symmetric copy of b. Each rotation zeroes
        // one off-diagonal entry; convergence is quadratic, and the result
        // is accurate to round-off relative to |b| also for repeated
        // eigenvalues.
        double a[3][3];
        double v[3][3] = {{1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            a[i][j] = a[j][i] = b[i][j];

        constexpr unsigned int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
        bool                   converged   = false;
        for (unsigned int sweep = 0; sweep < 50 && !converged; ++sweep)
          {
            converged = true;
            for (const auto &pair : pairs)
              {
                const unsigned int p   = pair[0];
                const unsigned int q   = pair[1];
                const double       apq = a[p][q];
                if (apq == 0.)
                  continue;
                // An entry below round-off of both diagonal entries is
                // dropped (its effect on the eigenvalues is ~ apq^2).
                const double small =
                  1e-18 * (std::abs(a[p][p]) + std::abs(a[q][q]));
                if (std::abs(apq) <= small)
                  {
                    a[p][q] = a[q][p] = 0.;
                    continue;
                  }
                converged = false;

                // rotation angle: t = tan(phi) of the smaller root
                const double theta = (a[q][q] - a[p][p]) / (2. * apq);
                double       t;
                if (std::abs(theta) > 1e150)
                  t = 0.5 / theta;
                else
                  t = (theta >= 0. ? 1. : -1.) /
                      (std::abs(theta) + std::sqrt(theta * theta + 1.));
                const double c   = 1. / std::sqrt(t * t + 1.);
                const double s   = t * c;
                const double tau = s / (1. + c);

                a[p][p] -= t * apq;
                a[q][q] += t * apq;
                a[p][q] = a[q][p] = 0.;
                for (unsigned int r = 0; r < 3; ++r)
                  if (r != p && r != q)
                    {
                      const double g = a[r][p];
                      const double h = a[r][q];
                      a[r][p] = a[p][r] = g - s * (h + g * tau);
                      a[r][q] = a[q][r] = h + s * (g - h * tau);
                    }
                for (unsigned int r = 0; r < 3; ++r)
                  {
                    const double g = v[r][p];
                    const double h = v[r][q];
                    v[r][p]        = g - s * (h + g * tau);
                    v[r][q]        = h + s * (g - h * tau);
                  }
              }
          }
        AssertThrow(converged,
                    dealii::ExcMessage(
                      "Jacobi eigenvalue iteration did not converge (is the "
                      "tensor finite?)."));

        SpectralDecomposition result;
        for (unsigned int a_ = 0; a_ < 3; ++a_)
          {
            result.eigenvalues[a_] = a[a_][a_];
            for (unsigned int r = 0; r < 3; ++r)
              result.eigenvectors[a_][r] = v[r][a_];
          }
        return result;
      }



      ElasticState
      elastic_state(const std::string          &model,
                    const dealii::Tensor<2, 3> &F,
                    const dealii::Tensor<2, 3> &G)
      {
        const double J = dealii::determinant(F);
        if (!(J > 0.) || !std::isfinite(J))
          throw ExcInvertedMaterialPoint(model, J);
        ElasticState               s;
        const dealii::Tensor<2, 3> FG = F * G;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              double sum = 0.;
              for (unsigned int k = 0; k < 3; ++k)
                sum += FG[i][k] * F[j][k];
              s.b_e[i][j] = s.b_e[j][i] = sum;
            }
        s.spectral = spectral_decomposition(s.b_e);
        for (unsigned int a = 0; a < 3; ++a)
          {
            // b_e is positive definite in exact arithmetic; a non-positive
            // eigenvalue means F is numerically singular.
            if (!(s.spectral.eigenvalues[a] > 0.))
              throw ExcInvertedMaterialPoint(model, J);
            s.eps[a] = 0.5 * std::log(s.spectral.eigenvalues[a]);
          }
        return s;
      }



      void
      principal_kirchhoff_to_piola(const dealii::Tensor<2, 3>  &F,
                                   const dealii::Tensor<2, 3>  &b_e,
                                   const SpectralDecomposition &spectral,
                                   const std::array<double, 3> &tau,
                                   const dealii::Tensor<2, 3>  &dtau_deps,
                                   dealii::Tensor<2, 3>        &P,
                                   dealii::Tensor<4, 3>        *A,
                                   const unsigned int           n_t)
      {
        const auto &b = spectral.eigenvalues;
        const auto &n = spectral.eigenvectors;

        // tau = sum_a tau_a n_a (x) n_a, P = tau F^{-T}
        dealii::Tensor<2, 3> tau_tensor;
        for (unsigned int a = 0; a < 3; ++a)
          tau_tensor += tau[a] * dealii::outer_product(n[a], n[a]);
        const dealii::Tensor<2, 3> F_inv = dealii::invert(F);
        P = tau_tensor * dealii::transpose(F_inv);

        if (A == nullptr)
          return;

        // dtau_a/db_c = dtau_a/deps_c deps_c/db_c = dtau_deps[a][c] / (2 b_c)
        double dtau_db[3][3];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            dtau_db[a][c] = dtau_deps[a][c] / (2. * b[c]);

        // The spatial modulus D = dtau/db_e (minor symmetric in its last
        // two indices) is
        //   D = sum_ac dtau_a/db_c (n_a x n_a) x (n_c x n_c)
        //     + sum_(a != c) theta_ac (n_a x n_c) x sym(n_a x n_c),
        // theta_ac = (tau_a - tau_c)/(b_a - b_c), or its limit
        // dtau_a/db_a - dtau_a/db_c for coinciding eigenvalues (symmetrized
        // in a and c, which share the limit). With db_e = dF H^T + H dF^T,
        // H = b_e F^{-T}, and d(F^{-T}) = -F^{-T} dF^T F^{-T}:
        //   A_iJkL = 2 D_ipkm F^-1_Jp H_mL - P_iL F^-1_Jk.
        // D is never formed: with g_a = F^{-1} n_a and h_a = H^T n_a the
        // first part is a sum of rank-one products of 3x3 matrices,
        //   2 sum_a (n_a x g_a) x Z_a,  Z_a = sum_c dtau_a/db_c n_c x h_c,
        //   + sum_(a < c) theta_ac (n_a x g_c + n_c x g_a)
        //                          x (n_a x h_c + n_c x h_a),
        // 6 products of 81 entries instead of the 4th-order algebra.
        // Only the indices below n_t (tangent_dimension) are needed: the
        // first two and the last two indices of A run over n_t values.
        const dealii::Tensor<2, 3> H = b_e * dealii::transpose(F_inv);
        double                     g[3][3], h[3][3];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int i = 0; i < n_t; ++i)
            {
              double gi = 0., hi = 0.;
              for (unsigned int p = 0; p < 3; ++p)
                {
                  gi += F_inv[i][p] * n[a][p];
                  hi += H[p][i] * n[a][p];
                }
              g[a][i] = gi;
              h[a][i] = hi;
            }

        double left[6][3][3], right[6][3][3];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int i = 0; i < n_t; ++i)
            for (unsigned int j = 0; j < n_t; ++j)
              {
                left[a][i][j] = 2. * n[a][i] * g[a][j];
                double z      = 0.;
                for (unsigned int c = 0; c < 3; ++c)
                  z += dtau_db[a][c] * n[c][i] * h[c][j];
                right[a][i][j] = z;
              }
        static constexpr unsigned int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
        for (unsigned int q = 0; q < 3; ++q)
          {
            const unsigned int a = pairs[q][0], c = pairs[q][1];
            double             theta;
            if (std::abs(b[a] - b[c]) > 1e-8 * std::max(b[a], b[c]))
              theta = (tau[a] - tau[c]) / (b[a] - b[c]);
            else
              theta = 0.5 * ((dtau_db[a][a] - dtau_db[a][c]) +
                             (dtau_db[c][c] - dtau_db[c][a]));
            for (unsigned int i = 0; i < n_t; ++i)
              for (unsigned int j = 0; j < n_t; ++j)
                {
                  left[3 + q][i][j] =
                    theta * (n[a][i] * g[c][j] + n[c][i] * g[a][j]);
                  right[3 + q][i][j] = n[a][i] * h[c][j] + n[c][i] * h[a][j];
                }
          }

        if (n_t < 3)
          *A = 0.;
        for (unsigned int i = 0; i < n_t; ++i)
          for (unsigned int J = 0; J < n_t; ++J)
            for (unsigned int k = 0; k < n_t; ++k)
              for (unsigned int L = 0; L < n_t; ++L)
                {
                  double sum = -P[i][L] * F_inv[J][k];
                  for (unsigned int t = 0; t < 6; ++t)
                    sum += left[t][i][J] * right[t][k][L];
                  (*A)[i][J][k][L] = sum;
                }
      }
    } // namespace LogarithmicStrain



    namespace
    {
      dealii::Tensor<2, 3>
      identity()
      {
        dealii::Tensor<2, 3> I;
        for (unsigned int i = 0; i < 3; ++i)
          I[i][i] = 1.;
        return I;
      }
    } // namespace



    HenckyElastic::HenckyElastic(const double youngs_modulus,
                                 const double poissons_ratio)
      : elastic(youngs_modulus, poissons_ratio)
    {}



    std::string
    HenckyElastic::name() const
    {
      return "Hencky";
    }



    std::array<double, 3>
    HenckyElastic::principal_stress(const std::array<double, 3> &eps) const
    {
      const double          tr = eps[0] + eps[1] + eps[2];
      std::array<double, 3> tau;
      for (unsigned int a = 0; a < 3; ++a)
        tau[a] = elastic.lambda * tr + 2. * elastic.mu * eps[a];
      return tau;
    }



    dealii::Tensor<2, 3>
    HenckyElastic::principal_moduli() const
    {
      dealii::Tensor<2, 3> D;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = 0; c < 3; ++c)
          D[a][c] = elastic.lambda + (a == c ? 2. * elastic.mu : 0.);
      return D;
    }



    void
    HenckyElastic::compute_stress(
      const dealii::Tensor<2, 3> & /*F_old*/,
      const dealii::Tensor<2, 3> &F,
      const dealii::ArrayView<const double> & /*history_old*/,
      const dealii::ArrayView<double> & /*history_new*/,
      const double /*time_step*/,
      dealii::Tensor<2, 3> &P,
      dealii::Tensor<4, 3> *A) const
    {
      const auto s = LogarithmicStrain::elastic_state(name(), F, identity());
      LogarithmicStrain::principal_kirchhoff_to_piola(F,
                                                      s.b_e,
                                                      s.spectral,
                                                      principal_stress(s.eps),
                                                      principal_moduli(),
                                                      P,
                                                      A,
                                                      tangent_dimension());
    }



    double
    HenckyElastic::energy_density(
      const dealii::Tensor<2, 3> &F,
      const dealii::ArrayView<const double> & /*history*/) const
    {
      const auto   s  = LogarithmicStrain::elastic_state(name(), F, identity());
      const double tr = s.eps[0] + s.eps[1] + s.eps[2];
      return 0.5 * elastic.lambda * tr * tr +
             elastic.mu * (s.eps[0] * s.eps[0] + s.eps[1] * s.eps[1] +
                           s.eps[2] * s.eps[2]);
    }



    double
    HenckyElastic::p_wave_modulus() const
    {
      return elastic.p_wave_modulus();
    }



    const IsotropicElasticity &
    HenckyElastic::elasticity() const
    {
      return elastic;
    }
  } // namespace Materials
} // namespace Talus
