#include <talus/base/input.h>
#include <talus/materials/constitutive_model.h>
#include <talus/materials/drucker_prager.h>
#include <talus/materials/granular_plasticity.h>
#include <talus/materials/hencky_elastic.h>
#include <talus/materials/linear_elastic.h>
#include <talus/materials/mohr_coulomb.h>
#include <talus/materials/neo_hookean.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace Materials
  {
    unsigned int
    ConstitutiveModel::n_history_variables() const
    {
      return 0;
    }



    void
    ConstitutiveModel::initialize_history(
      const dealii::ArrayView<double> & /*history*/) const
    {}



    bool
    ConstitutiveModel::initialize_history_for_stress(
      const dealii::SymmetricTensor<2, 3> & /*stress*/,
      const dealii::ArrayView<double> & /*history*/) const
    {
      return false;
    }



    std::string
    ConstitutiveModel::description() const
    {
      return name();
    }



    unsigned int
    ConstitutiveModel::return_branch(
      const dealii::ArrayView<const double> & /*history*/) const
    {
      return 0;
    }


    std::vector<std::string>
    ConstitutiveModel::history_names() const
    {
      return {};
    }



    namespace
    {
      /**
       * The material subsection being declared or read ("Material",
       * "Material 2", ...): set by declare_parameters() and create_model()
       * for the messages of the model factories.
       */
      std::string subsection_name = "Material";

      /**
       * How to declare and create one model.
       */
      struct ModelEntry
      {
        /**
         * Declare the parameters specific to the model (typically in a
         * subsection of "Material" named after it). Called while @p prm is
         * in subsection "Material". May be empty.
         */
        std::function<void(dealii::ParameterHandler &prm)> declare_parameters;

        /**
         * Read and check the parameters and create the model. Called while
         * @p prm is in subsection "Material".
         */
        std::function<std::unique_ptr<ConstitutiveModel>(
          dealii::ParameterHandler &prm)>
          create;
      };


      /**
       * The registry of constitutive models: name (as written in the
       * parameter file) -> declaration and factory.
       */
      class ModelRegistry
      {
      public:
        void
        add(const std::string &name, const ModelEntry &entry)
        {
          const bool inserted = entries.emplace(name, entry).second;
          (void)inserted;
          Assert(inserted,
                 dealii::ExcMessage("Model <" + name +
                                    "> is registered twice."));
          names.push_back(name);
        }

        const ModelEntry *
        find(const std::string &name) const
        {
          const auto it = entries.find(name);
          return it == entries.end() ? nullptr : &it->second;
        }

        /** Names in order of registration. */
        std::vector<std::string> names;

      private:
        std::map<std::string, ModelEntry> entries;
      };


      /**
       * Young's modulus and Poisson's ratio, read from subsection
       * "Material" and checked (with messages pointing at the input file).
       */
      IsotropicElasticity
      read_isotropic_elasticity(const dealii::ParameterHandler &prm)
      {
        const double E  = get_positive(prm, subsection_name, "Young's modulus");
        const double nu = get_in_open_interval(
          prm, subsection_name, "Poisson's ratio", -1., 0.5);
        return IsotropicElasticity(E, nu);
      }


      void
      no_parameters(dealii::ParameterHandler &)
      {}


      template <class Model>
      std::unique_ptr<ConstitutiveModel>
      create_elastic(dealii::ParameterHandler &prm)
      {
        const IsotropicElasticity e = read_isotropic_elasticity(prm);
        return std::make_unique<Model>(e.youngs_modulus, e.poissons_ratio);
      }


      void
      declare_mohr_coulomb(dealii::ParameterHandler &prm)
      {
        prm.enter_subsection("Mohr-Coulomb");
        declare_granular_strength(
          prm,
          "Rankine cut-off of the maximum principal (Kirchhoff) stress, "
          "tension positive: sigma_max <= t.");
        prm.leave_subsection();
      }


      std::unique_ptr<ConstitutiveModel>
      create_mohr_coulomb(dealii::ParameterHandler &prm)
      {
        const IsotropicElasticity e = read_isotropic_elasticity(prm);
        prm.enter_subsection("Mohr-Coulomb");
        try
          {
            GranularStrength s =
              read_granular_strength(prm, subsection_name + "/Mohr-Coulomb");
            prm.leave_subsection();
            if (s.rate_dependent() && s.grain_density == 0.)
              s.grain_density = prm.get_double("density");
            return std::make_unique<MohrCoulomb>(e, s);
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
      }


      void
      declare_drucker_prager(dealii::ParameterHandler &prm)
      {
        prm.enter_subsection("Drucker-Prager");
        prm.declare_entry(
          "cone fit",
          "plane strain",
          dealii::Patterns::Selection(
            "plane strain|triaxial compression|triaxial extension"),
          "How the Drucker-Prager cone sqrt(J2) + eta p = xi c (p mean "
          "stress, tension positive) is matched to the Mohr-Coulomb "
          "parameters phi, c (and psi for the plastic potential) [no unit]: "
          "'plane strain': same plane-strain limit load, eta = 3 tan(phi)/"
          "sqrt(9 + 12 tan^2(phi)), xi = 3/sqrt(9 + 12 tan^2(phi)); "
          "'triaxial compression' (outer cone, through the compressive "
          "meridian of the Mohr-Coulomb pyramid): eta = 6 sin(phi)/"
          "(sqrt(3) (3 - sin(phi))), xi = 6 cos(phi)/(sqrt(3) (3 - "
          "sin(phi))); 'triaxial extension' (inner cone, through the "
          "extension meridian): the same with 3 + sin(phi). At phi = 19.8 "
          "deg, c = 0 the ratio sqrt(J2)/(-p) is 0.332, 0.441 and 0.351.");
        declare_granular_strength(
          prm,
          "Cut-off of the mean stress (tension positive): p = tr(tau)/3 <= "
          "t (a plane normal to the hydrostatic axis, not a Rankine "
          "surface).");
        prm.leave_subsection();
      }


      std::unique_ptr<ConstitutiveModel>
      create_drucker_prager(dealii::ParameterHandler &prm)
      {
        const IsotropicElasticity e = read_isotropic_elasticity(prm);
        prm.enter_subsection("Drucker-Prager");
        try
          {
            GranularStrength s =
              read_granular_strength(prm, subsection_name + "/Drucker-Prager");
            const std::string fit = prm.get("cone fit");
            prm.leave_subsection();
            if (s.rate_dependent() && s.grain_density == 0.)
              s.grain_density = prm.get_double("density");
            return std::make_unique<DruckerPrager>(
              e,
              s,
              fit == "plane strain" ?
                DruckerPrager::ConeFit::plane_strain :
                (fit == "triaxial compression" ?
                   DruckerPrager::ConeFit::triaxial_compression :
                   DruckerPrager::ConeFit::triaxial_extension));
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
      }


      /**
       * All available models. To add a model (e.g. "Mohr-Coulomb"), include
       * its header above and add one entry here: a function declaring its
       * own parameters (in a subsection of "Material" named after the
       * model) and a factory that reads them (read_isotropic_elasticity()
       * gives the elastic constants). The other models are not affected.
       */
      const ModelRegistry &
      registry()
      {
        static const ModelRegistry models = [] {
          ModelRegistry r;
          r.add("linear elastic",
                {&no_parameters, &create_elastic<LinearElastic>});
          r.add("neo-Hookean", {&no_parameters, &create_elastic<NeoHookean>});
          r.add("Hencky", {&no_parameters, &create_elastic<HenckyElastic>});
          r.add("Mohr-Coulomb", {&declare_mohr_coulomb, &create_mohr_coulomb});
          r.add("Drucker-Prager",
                {&declare_drucker_prager, &create_drucker_prager});
          return r;
        }();
        return models;
      }


      /** Leaves a subsection of a ParameterHandler also on exceptions. */
      class SubsectionScope
      {
      public:
        SubsectionScope(dealii::ParameterHandler &prm, const std::string &name)
          : prm(prm)
        {
          prm.enter_subsection(name);
        }

        ~SubsectionScope()
        {
          prm.leave_subsection();
        }

        SubsectionScope(const SubsectionScope &) = delete;
        SubsectionScope &
        operator=(const SubsectionScope &) = delete;

      private:
        dealii::ParameterHandler &prm;
      };
    } // namespace



    std::string
    model_names()
    {
      std::string result;
      for (const std::string &name : registry().names)
        result += (result.empty() ? "" : "|") + name;
      return result;
    }



    std::string
    material_subsection(const unsigned int index)
    {
      return index == 0 ? std::string("Material") :
                          "Material " + std::to_string(index + 1);
    }



    void
    declare_parameters(dealii::ParameterHandler &prm)
    {
      for (unsigned int m = 0; m < max_materials; ++m)
        declare_parameters(prm, material_subsection(m));
    }



    void
    declare_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection)
    {
      subsection_name = subsection;
      SubsectionScope scope(prm, subsection_name);

      prm.declare_entry(
        "model",
        "linear elastic",
        dealii::Patterns::Selection(model_names()),
        "Constitutive model of the material [no unit]; one of: " +
          model_names() +
          ". 'linear elastic': small-strain isotropic linear elasticity, "
          "NOT objective (spurious stresses under large rotations; use it "
          "only for small displacements and rotations). 'neo-Hookean': "
          "compressible neo-Hookean hyperelasticity, "
          "psi = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2. 'Hencky': "
          "hyperelasticity linear between Kirchhoff stress and logarithmic "
          "strain, tau = lambda tr(eps) I + 2 mu eps with eps = 1/2 ln(F F^T). "
          "'Mohr-Coulomb': finite-strain elastoplasticity for granular "
          "materials, Hencky elasticity with multiplicative plasticity "
          "(return mapping in principal logarithmic elastic strains), "
          "Mohr-Coulomb yield surface with dilatancy angle, Rankine tension "
          "cut-off and exponential softening (parameters in subsection "
          "Material/Mohr-Coulomb). 'Drucker-Prager': the same with a "
          "Drucker-Prager cone matched to the Mohr-Coulomb parameters "
          "(subsection Material/Drucker-Prager, 'cone fit').");
      prm.declare_entry(
        "density",
        "1000",
        dealii::Patterns::Double(),
        "Mass density of the material in the reference configuration "
        "[kg/m^3]; > 0.");
      prm.declare_entry(
        "Young's modulus",
        "1e6",
        dealii::Patterns::Double(),
        "Young's modulus E of the isotropic elastic response [Pa]; > 0. "
        "With Poisson's ratio nu it gives the Lame constants "
        "lambda = E nu/((1+nu)(1-2nu)) and mu = E/(2(1+nu)).");
      prm.declare_entry(
        "Poisson's ratio",
        "0.3",
        dealii::Patterns::Double(),
        "Poisson's ratio nu of the isotropic elastic response [-]; strictly "
        "between -1 and 0.5 (0.5, incompressibility, is not allowed).");

      for (const std::string &name : registry().names)
        registry().find(name)->declare_parameters(prm);
    }



    void
    ConstitutiveModel::set_tangent_dimension(const unsigned int dimension)
    {
      AssertThrow(dimension >= 1 && dimension <= 3,
                  dealii::ExcMessage("The tangent dimension must be 1, 2 "
                                     "or 3."));
      tangent_block_dimension = dimension;
    }



    unsigned int
    ConstitutiveModel::tangent_dimension() const
    {
      return tangent_block_dimension;
    }



    std::unique_ptr<ConstitutiveModel>
    create_model(dealii::ParameterHandler &prm)
    {
      return create_model(prm, material_subsection(0));
    }



    std::unique_ptr<ConstitutiveModel>
    create_model(dealii::ParameterHandler &prm, const std::string &subsection)
    {
      subsection_name = subsection;
      SubsectionScope scope(prm, subsection_name);

      const std::string name  = prm.get("model");
      const ModelEntry *entry = registry().find(name);
      if (entry == nullptr)
        InputFile::reject(subsection_name,
                          "model",
                          name,
                          "it must be one of " + model_names());
      return entry->create(prm);
    }
  } // namespace Materials
} // namespace Talus
