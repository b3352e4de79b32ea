#include <talus/materials/linear_elastic.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <string>

namespace Talus
{
  namespace Materials
  {
    IsotropicElasticity::IsotropicElasticity(const double youngs_modulus,
                                             const double poissons_ratio)
      : youngs_modulus(youngs_modulus)
      , poissons_ratio(poissons_ratio)
      , lambda(youngs_modulus * poissons_ratio /
               ((1. + poissons_ratio) * (1. - 2. * poissons_ratio)))
      , mu(youngs_modulus / (2. * (1. + poissons_ratio)))
    {
      AssertThrow(youngs_modulus > 0. && std::isfinite(youngs_modulus),
                  dealii::ExcMessage(
                    "Young's modulus must be positive and finite, but it is " +
                    std::to_string(youngs_modulus) + "."));
      AssertThrow(poissons_ratio > -1. && poissons_ratio < 0.5,
                  dealii::ExcMessage(
                    "Poisson's ratio must lie strictly between -1 and 0.5, "
                    "but it is " +
                    std::to_string(poissons_ratio) + "."));
    }



    LinearElastic::LinearElastic(const double youngs_modulus,
                                 const double poissons_ratio)
      : elastic(youngs_modulus, poissons_ratio)
    {}



    std::string
    LinearElastic::name() const
    {
      return "linear elastic";
    }



    namespace
    {
      dealii::Tensor<2, 3>
      small_strain(const dealii::Tensor<2, 3> &F)
      {
        dealii::Tensor<2, 3> eps;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            eps[i][j] = 0.5 * (F[i][j] + F[j][i]) - (i == j ? 1. : 0.);
        return eps;
      }


      dealii::Tensor<2, 3>
      small_strain_stress(const IsotropicElasticity  &e,
                          const dealii::Tensor<2, 3> &eps)
      {
        const double         tr = dealii::trace(eps);
        dealii::Tensor<2, 3> sigma;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            sigma[i][j] = 2. * e.mu * eps[i][j] + (i == j ? e.lambda * tr : 0.);
        return sigma;
      }
    } // namespace



    void
    LinearElastic::compute_stress(
      const dealii::Tensor<2, 3> & /*F_old*/,
      const dealii::Tensor<2, 3> &F_new,
      const dealii::ArrayView<const double> & /*history_old*/,
      const dealii::ArrayView<double> & /*history_new*/,
      const double /*time_step*/,
      dealii::Tensor<2, 3> &P,
      dealii::Tensor<4, 3> *A) const
    {
      P = small_strain_stress(elastic, small_strain(F_new));

      if (A != nullptr)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int J = 0; J < 3; ++J)
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int L = 0; L < 3; ++L)
                (*A)[i][J][k][L] = (i == J && k == L ? elastic.lambda : 0.) +
                                   (i == k && J == L ? elastic.mu : 0.) +
                                   (i == L && J == k ? elastic.mu : 0.);
    }



    double
    LinearElastic::energy_density(
      const dealii::Tensor<2, 3> &F,
      const dealii::ArrayView<const double> & /*history*/) const
    {
      const dealii::Tensor<2, 3> eps = small_strain(F);
      return 0.5 *
             dealii::scalar_product(small_strain_stress(elastic, eps), eps);
    }



    double
    LinearElastic::p_wave_modulus() const
    {
      return elastic.p_wave_modulus();
    }



    const IsotropicElasticity &
    LinearElastic::elasticity() const
    {
      return elastic;
    }
  } // namespace Materials
} // namespace Talus
