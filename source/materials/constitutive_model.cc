#include <talus/base/input.h>
#include <talus/materials/constitutive_model.h>
#include <talus/materials/hencky_elastic.h>
#include <talus/materials/linear_elastic.h>
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



    std::vector<std::string>
    ConstitutiveModel::history_names() const
    {
      return {};
    }



    void
    ConstitutiveModel::initialize_history(
      const dealii::ArrayView<double> & /*history*/) const
    {}



    namespace
    {
      const std::string subsection_name = "Material";

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



    void
    declare_parameters(dealii::ParameterHandler &prm)
    {
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
          "strain, tau = lambda tr(eps) I + 2 mu eps with eps = 1/2 ln(F F^T).");
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



    std::unique_ptr<ConstitutiveModel>
    create_model(dealii::ParameterHandler &prm)
    {
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
