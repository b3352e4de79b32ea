#include <talus/structure/axial_law.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
    StrainMeasure
    strain_measure_from_string(const std::string &name)
    {
      if (name == "engineering")
        return StrainMeasure::engineering;
      if (name == "Green-Lagrange")
        return StrainMeasure::green_lagrange;
      throw std::runtime_error("Unknown strain measure '" + name +
                               "' (allowed: " + strain_measure_names + ").");
    }


    std::string
    to_string(const StrainMeasure measure)
    {
      return measure == StrainMeasure::engineering ? "engineering" :
                                                     "Green-Lagrange";
    }


    double
    AxialLaw::unstretched_ratio() const
    {
      const double r = 1. + prestress / youngs_modulus;
      if (!(r > 0.))
        throw std::runtime_error(
          "An engineering-strain cable or bar needs prestress > -E (an "
          "unstretched length l0 = L/(1 + sigma_0/E) > 0).");
      return 1. / r;
    }


    double
    AxialLaw::force(const double lambda) const
    {
      if (measure == StrainMeasure::engineering)
        return youngs_modulus * area * (lambda / unstretched_ratio() - 1.);
      return area *
             (0.5 * youngs_modulus * (lambda * lambda - 1.) + prestress) *
             lambda;
    }


    double
    AxialLaw::stiffness(const double lambda) const
    {
      const double EA = youngs_modulus * area, As0 = area * prestress;
      if (measure == StrainMeasure::engineering)
        return EA / unstretched_ratio();
      return 0.5 * EA * (3. * lambda * lambda - 1.) + As0;
    }


    double
    AxialLaw::energy(const double lambda) const
    {
      if (measure == StrainMeasure::engineering)
        {
          const double lambda_0 = unstretched_ratio();
          return 0.5 * youngs_modulus * area * (lambda - lambda_0) *
                 (lambda - lambda_0) / lambda_0;
        }
      const double eps = 0.5 * (lambda * lambda - 1.);
      return area * (0.5 * youngs_modulus * eps * eps + prestress * eps);
    }


    double
    AxialLaw::slack_energy() const
    {
      if (measure == StrainMeasure::engineering)
        return 0.;
      return -area * prestress * prestress / (2. * youngs_modulus);
    }


    double
    AxialLaw::stretch(const double N) const
    {
      const double EA = youngs_modulus * area, As0 = area * prestress;
      if (measure == StrainMeasure::engineering)
        return unstretched_ratio() * (1. + N / EA);
      // EA (lambda^3 - lambda)/2 + A s0 lambda = N, Newton from above.
      double lambda = std::max(1. + N / EA, 1.);
      for (unsigned int k = 0; k < 60; ++k)
        {
          const double g =
            0.5 * EA * (lambda * lambda - 1.) * lambda + As0 * lambda - N;
          const double dg   = 0.5 * EA * (3. * lambda * lambda - 1.) + As0;
          const double step = g / dg;
          lambda -= step;
          if (std::abs(step) < 1e-15 * lambda)
            break;
        }
      return lambda;
    }
  } // namespace Structure
} // namespace Talus
