#include <talus/materials/exceptions.h>
#include <talus/materials/neo_hookean.h>

#include <cmath>
#include <string>

namespace Talus
{
  namespace Materials
  {
    NeoHookean::NeoHookean(const double youngs_modulus,
                           const double poissons_ratio)
      : elastic(youngs_modulus, poissons_ratio)
    {}



    std::string
    NeoHookean::name() const
    {
      return "neo-Hookean";
    }



    namespace
    {
      /** det F, or throw if the material point is inverted. */
      double
      checked_jacobian(const dealii::Tensor<2, 3> &F)
      {
        const double J = dealii::determinant(F);
        if (!(J > 0.) || !std::isfinite(J))
          throw ExcInvertedMaterialPoint("neo-Hookean", J);
        return J;
      }
    } // namespace



    void
    NeoHookean::compute_stress(
      const dealii::Tensor<2, 3> & /*F_old*/,
      const dealii::Tensor<2, 3> &F,
      const dealii::ArrayView<const double> & /*history_old*/,
      const dealii::ArrayView<double> & /*history_new*/,
      const double /*time_step*/,
      dealii::Tensor<2, 3> &P,
      dealii::Tensor<4, 3> *A) const
    {
      const double               lnJ    = std::log(checked_jacobian(F));
      const double               lambda = elastic.lambda;
      const double               mu     = elastic.mu;
      const dealii::Tensor<2, 3> F_inv  = dealii::invert(F);

      // P = mu (F - F^{-T}) + lambda ln J F^{-T}
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          P[i][J] = mu * F[i][J] + (lambda * lnJ - mu) * F_inv[J][i];

      // A_iJkL = mu d_ik d_JL + (mu - lambda ln J) F^-1_Li F^-1_Jk
      //          + lambda F^-1_Ji F^-1_Lk
      if (A != nullptr)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int J = 0; J < 3; ++J)
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int L = 0; L < 3; ++L)
                (*A)[i][J][k][L] =
                  (i == k && J == L ? mu : 0.) +
                  (mu - lambda * lnJ) * F_inv[L][i] * F_inv[J][k] +
                  lambda * F_inv[J][i] * F_inv[L][k];
    }



    double
    NeoHookean::energy_density(
      const dealii::Tensor<2, 3> &F,
      const dealii::ArrayView<const double> & /*history*/) const
    {
      const double lnJ = std::log(checked_jacobian(F));
      const double trC = dealii::scalar_product(F, F);
      return 0.5 * elastic.mu * (trC - 3.) - elastic.mu * lnJ +
             0.5 * elastic.lambda * lnJ * lnJ;
    }



    double
    NeoHookean::p_wave_modulus() const
    {
      return elastic.p_wave_modulus();
    }



    const IsotropicElasticity &
    NeoHookean::elasticity() const
    {
      return elastic;
    }
  } // namespace Materials
} // namespace Talus
