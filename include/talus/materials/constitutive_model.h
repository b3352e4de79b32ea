#ifndef talus_materials_constitutive_model_h
#define talus_materials_constitutive_model_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  /**
   * Constitutive models evaluated at material points.
   */
  namespace Materials
  {
    /**
     * Interface of every constitutive model at a material point.
     *
     * Models are written in three dimensions. Plane-strain problems
     * (dim = 2) pass a deformation gradient with F(2,2) = 1 and zero
     * out-of-plane shear; the solver uses the in-plane block of the
     * returned stress and tangent.
     *
     * The solver works with the total deformation gradient
     * @f$\mathbf F_{n+1}@f$ of the step being solved, the first
     * Piola-Kirchhoff stress @f$\mathbf P = \partial\psi/\partial\mathbf F@f$
     * and its derivative @f$\mathbb A = \partial\mathbf P/\partial\mathbf
     * F@f$ (the consistent tangent, which already contains the geometric
     * stiffness). The internal force of a material point with initial
     * volume @f$V_0@f$ on grid node I is
     * @f$f_I = V_0\,\mathbf P\,\nabla_{X_0}N_I@f$.
     *
     * History variables are stored on the material point; compute_stress()
     * reads those of the last accepted step and writes trial values
     * without side effects, so that a Newton iteration, a coupling
     * iteration or a rejected step can evaluate it any number of times.
     */
    class ConstitutiveModel
    {
    public:
      virtual ~ConstitutiveModel() = default;

      /** Name of the model as written in the parameter file. */
      virtual std::string
      name() const = 0;

      /**
       * One line describing the model and its parameters, for the log of a
       * run. The default returns name().
       */
      virtual std::string
      description() const;

      /**
       * Restrict the consistent tangent of compute_stress() to the entries
       * A_iJkL with all indices below @p dimension (1 to 3; default 3):
       * a plane-strain analysis (dimension 2) uses only the in-plane
       * block, and the finite-strain models then skip the other 65 of
       * the 81 entries. Entries outside the block are zero or exact,
       * depending on the model. The stress is always complete.
       */
      void
      set_tangent_dimension(const unsigned int dimension);

      /** The dimension set by set_tangent_dimension(). */
      unsigned int
      tangent_dimension() const;

      /** Number of history variables per material point (may be 0). */
      virtual unsigned int
      n_history_variables() const;

      /** Write the history of a stress-free, undeformed material point. */
      virtual void
      initialize_history(const dealii::ArrayView<double> &history) const;

      /**
       * Write the history of an undeformed material point (F = I) that
       * carries the Cauchy (= Kirchhoff) stress @p stress [Pa], tension
       * positive: an initial stress such as the geostatic one. Returns
       * false if the model cannot hold such a state elastically: the
       * default (models without an elastic strain in their history, whose
       * stress at F = I is zero) always; a plastic model when @p stress
       * lies outside its yield surface. The history is then unspecified.
       */
      virtual bool
      initialize_history_for_stress(
        const dealii::SymmetricTensor<2, 3> &stress,
        const dealii::ArrayView<double>     &history) const;

      /**
       * Names of the history variables (identifiers without spaces, for
       * output), n_history_variables() of them. The default returns an
       * empty vector (no names: the solver numbers them). The solver adds
       * the variable named "plastic_dissipation" [J/m^3 of reference
       * volume] to the energy balance.
       */
      virtual std::vector<std::string>
      history_names() const;

      /**
       * Stress update.
       *
       * @param F_old  deformation gradient of the last accepted step
       * @param F_new  trial deformation gradient
       * @param history_old  history of the last accepted step (read only)
       * @param history_new  trial history (written)
       * @param time_step  length of the step from F_old to F_new [s], for
       *   rate-dependent models (the inertial number of the mu(I)
       *   friction); a value <= 0 means "no rate": rate-dependent models
       *   then return their rate-independent (static) response
       * @param P  first Piola-Kirchhoff stress [Pa]
       * @param A  if not nullptr: consistent tangent dP/dF [Pa]
       */
      virtual void
      compute_stress(const dealii::Tensor<2, 3>            &F_old,
                     const dealii::Tensor<2, 3>            &F_new,
                     const dealii::ArrayView<const double> &history_old,
                     const dealii::ArrayView<double>       &history_new,
                     const double                           time_step,
                     dealii::Tensor<2, 3>                  &P,
                     dealii::Tensor<4, 3>                  *A) const = 0;

      /**
       * Branch of the return mapping taken by the stress update that wrote
       * @p history (0: elastic; plastic models number their branches, e.g.
       * plane, edge, apex). The Newton iteration counts the material points
       * whose branch changes from one iterate to the next: iterations with
       * such changes do not count toward the ordinary iteration limit
       * (MPMSolver, 'maximum Newton iterations with state changes'). The
       * default returns 0 (one branch).
       */
      virtual unsigned int
      return_branch(const dealii::ArrayView<const double> &history) const;

      /**
       * Stored (elastic) energy per unit reference volume [J/m^3] at the
       * accepted state (F, history).
       */
      virtual double
      energy_density(const dealii::Tensor<2, 3>            &F,
                     const dealii::ArrayView<const double> &history) const = 0;

      /**
       * P-wave (constrained) modulus of the undeformed material [Pa]:
       * used to scale penalties and to estimate wave speeds.
       */
      virtual double
      p_wave_modulus() const = 0;

    private:
      /** See set_tangent_dimension(). */
      unsigned int tangent_block_dimension = 3;
    };

    /**
     * Number of material subsections: "Material", "Material 2", ...,
     * "Material max_materials" (the bodies of an MPM run name theirs,
     * MPM::MaterialPoints).
     */
    constexpr unsigned int max_materials = 4;

    /** "Material" for @p index 0, "Material 2" for 1, ... */
    std::string
    material_subsection(const unsigned int index);

    /**
     * Declare the parameters of the subsections "Material" ...
     * "Material max_materials" (model name, density, elastic constants and
     * the subsections of every registered model).
     */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Declare the parameters of one material subsection @p subsection. */
    void
    declare_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection);

    /**
     * Create the model named in subsection "Material" of @p prm, with its
     * parameters checked. Throws Talus::ExcInvalidInput (see
     * talus/base/input.h) for invalid values.
     */
    std::unique_ptr<ConstitutiveModel>
    create_model(dealii::ParameterHandler &prm);

    /** Create the model of the material subsection @p subsection. */
    std::unique_ptr<ConstitutiveModel>
    create_model(dealii::ParameterHandler &prm, const std::string &subsection);

    /** Names of all available models, separated by '|'. */
    std::string
    model_names();
  } // namespace Materials
} // namespace Talus

#endif
