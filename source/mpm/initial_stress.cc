#include <talus/base/input.h>
#include <talus/materials/granular_plasticity.h>
#include <talus/mpm/initial_stress.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace Talus
{
  namespace MPM
  {
    namespace
    {
      const std::string section = "Initial stress";

      std::string
      format(const double x)
      {
        std::ostringstream o;
        o.precision(6);
        o << x;
        return o.str();
      }
    } // namespace


    template <int dim>
    void
    InitialStress<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection(section);
      prm.declare_entry(
        "type",
        "none",
        Patterns::Selection("none|geostatic"),
        "Initial stress of the material points [-]: 'none' (stress free) or "
        "'geostatic': sigma_v = -rho |g| (z_s - z) along gravity and K0 "
        "sigma_v across it, for a body at rest with a horizontal free "
        "surface at level z_s (levels z measured upwards, against "
        "gravity). Needs gravity and a model that stores an elastic strain "
        "(Mohr-Coulomb, Drucker-Prager); a state outside the yield surface "
        "is rejected.");
      prm.declare_entry("lateral stress ratio",
                        "0",
                        Patterns::Double(0),
                        "Coefficient of earth pressure at rest K0 = "
                        "sigma_h / sigma_v [-], >= 0; 0: Jaky's 1 - sin(phi) "
                        "of the material's peak friction angle.");
      prm.declare_entry("free surface level",
                        "",
                        Patterns::Anything(),
                        "Level z_s of the free surface, measured upwards "
                        "(along -g) from the origin [m]; empty: the top of "
                        "the body, i.e. the highest material point plus "
                        "half its spacing (exact for a body with a "
                        "horizontal top generated on the grid).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    InitialStress<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection(section);
      type                      = prm.get("type");
      lateral_ratio             = prm.get_double("lateral stress ratio");
      const std::string surface = prm.get("free surface level");
      surface_given = surface.find_first_not_of(" \t") != std::string::npos;
      surface_level = 0.;
      if (surface_given && !parse_double(surface, surface_level))
        InputFile::reject(section,
                          "free surface level",
                          surface,
                          "it must be a number [m] or empty (the top of the "
                          "body)");
      prm.leave_subsection();
    }


    template <int dim>
    void
    InitialStress<dim>::apply(MaterialPoints<dim>                &points,
                              const Materials::ConstitutiveModel &model,
                              const dealii::Tensor<1, dim>       &gravity,
                              const MPI_Comm                      communicator,
                              const double load_ramp_time) const
    {
      if (!enabled())
        return;
      if (load_ramp_time > 0.)
        InputFile::reject(section,
                          "type",
                          type,
                          "a geostatic stress balances the full gravity from "
                          "the start, so it cannot be combined with a load "
                          "ramp (subsection Solver, 'load ramp time' = " +
                            format(load_ramp_time) + " s: set it to 0)");
      using Properties = MaterialPointProperties<dim>;
      const double g   = gravity.norm();
      if (!(g > 0.))
        InputFile::reject(section,
                          "type",
                          type,
                          "a geostatic stress needs gravity (subsection "
                          "Solver, 'gravity' is zero)");
      // Upward unit vector in 3D (plane strain: z is horizontal).
      dealii::Tensor<1, 3> up;
      for (unsigned int d = 0; d < dim; ++d)
        up[d] = -gravity[d] / g;

      used_ratio = lateral_ratio;
      if (used_ratio == 0.)
        {
          const auto *granular =
            dynamic_cast<const Materials::GranularPlasticity *>(&model);
          if (granular == nullptr)
            InputFile::reject(section,
                              "lateral stress ratio",
                              "0",
                              "Jaky's K0 = 1 - sin(phi) needs a friction "
                              "angle: the material '" +
                                model.name() + "' has none, give K0 > 0");
          used_ratio = 1. - std::sin(granular->strength().phi(0.).value);
        }

      auto &handler = points.particle_handler();
      used_surface  = surface_level;
      if (!surface_given)
        {
          double top = -std::numeric_limits<double>::max();
          for (const auto &p : handler)
            {
              const auto   props = p.get_properties();
              const double d =
                std::pow(props[Properties::initial_volume], 1. / dim);
              double z = 0.;
              for (unsigned int c = 0; c < dim; ++c)
                z += p.get_location()[c] * up[c];
              top = std::max(top, z + 0.5 * d);
            }
          used_surface = dealii::Utilities::MPI::max(top, communicator);
        }

      const dealii::SymmetricTensor<2, 3> I =
        dealii::unit_symmetric_tensor<3>();
      const dealii::SymmetricTensor<2, 3> vertical =
        dealii::symmetrize(dealii::outer_product(up, up));
      std::string failure;
      for (auto &p : handler)
        {
          auto   props = p.get_properties();
          double z     = 0.;
          for (unsigned int c = 0; c < dim; ++c)
            z += p.get_location()[c] * up[c];
          const double depth = used_surface - z;
          const double rho =
            props[Properties::mass] / props[Properties::initial_volume];
          if (depth < 0. && failure.empty())
            failure = "a material point lies " + format(-depth) +
                      " m above the free surface level " +
                      format(used_surface) + " m";
          const double sigma_v = -rho * g * std::max(depth, 0.);
          const dealii::SymmetricTensor<2, 3> sigma =
            used_ratio * sigma_v * (I - vertical) + sigma_v * vertical;
          const dealii::ArrayView<double> history(props.data() +
                                                    Properties::history,
                                                  points.n_history());
          if (!model.initialize_history_for_stress(sigma, history) &&
              failure.empty())
            {
              if (dynamic_cast<const Materials::GranularPlasticity *>(&model) ==
                  nullptr)
                failure = "the material '" + model.name() +
                          "' cannot start from a stress: it keeps no "
                          "elastic strain in its history (Mohr-Coulomb and "
                          "Drucker-Prager do)";
              else
                failure =
                  "at depth " + format(depth) +
                  " m the stress (sigma_v = " + format(sigma_v) +
                  " Pa, sigma_h = " + format(used_ratio * sigma_v) +
                  " Pa, K0 = " + format(used_ratio) +
                  ") lies outside the yield surface of " + "the material '" +
                  model.name() +
                  "': K0 must lie between the active and the passive ratio " +
                  "(Mohr-Coulomb with c = 0: (1 - sin phi)/(1 + sin phi) < " +
                  "K0 < (1 + sin phi)/(1 - sin phi))";
            }
          Properties::store_stress(props, sigma);
        }
      // Every rank stops with the same message.
      const auto all =
        dealii::Utilities::MPI::all_gather(communicator, failure);
      for (const auto &f : all)
        if (!f.empty())
          InputFile::reject(section, "type", type, f);
    }


    template <int dim>
    std::string
    InitialStress<dim>::description() const
    {
      if (!enabled())
        return "none";
      return "geostatic, K0 = " + format(used_ratio) + ", free surface level " +
             format(used_surface) + " m";
    }


    template class InitialStress<2>;
    template class InitialStress<3>;
  } // namespace MPM
} // namespace Talus
