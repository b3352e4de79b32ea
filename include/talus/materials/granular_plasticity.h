#ifndef talus_materials_granular_plasticity_h
#define talus_materials_granular_plasticity_h

#include <talus/materials/constitutive_model.h>
#include <talus/materials/exceptions.h>
#include <talus/materials/linear_elastic.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace Talus
{
  namespace Materials
  {
    /**
     * Strength parameters of the granular (Mohr-Coulomb type) models, with
     * exponential softening of the friction angle, the cohesion and the
     * dilatancy angle in the accumulated (equivalent) plastic strain
     * @f$\bar\varepsilon^p@f$:
     * @f[
     *   X(\bar\varepsilon^p) = X_r + (X_p - X_r)
     *     \exp(-\bar\varepsilon^p/\eta_s),\qquad X\in\{\phi, c, \psi\},
     * @f]
     * with peak values @f$X_p@f$, residual values @f$X_r \le X_p@f$ and the
     * softening plastic strain @f$\eta_s > 0@f$. With @f$X_r = X_p@f$ for
     * all three the material is perfectly plastic.
     *
     * *Rate-dependent friction* (optional; the @f$\mu(I)@f$ rheology of
     * G.D.R. MiDi, EPJ E 14 (2004) 341 and P. Jop, Y. Forterre, O. Pouliquen,
     * Nature 441 (2006) 727, in the elastoplastic form of S. Dunatunga,
     * K. Kamrin, JFM 779 (2015) 483): the friction coefficient grows with
     * the inertial number @f$I@f$ from its static (softened) value to a
     * limit,
     * @f[
     *   \tan\phi = \tan\phi_s(\bar\varepsilon^p) + \Delta\mu\,
     *     \frac{I}{I_0 + I},\qquad
     *   I = \frac{\dot\gamma^p d}{\sqrt{P/\rho_s}},\qquad
     *   \dot\gamma^p = \sqrt3\,\frac{\bar\varepsilon^p -
     *     \bar\varepsilon^p_n}{\Delta t},
     * @f]
     * with @f$\Delta\mu = \tan\phi_2 - \tan\phi_p@f$ (limiting friction
     * angle @f$\phi_2@f$), grain diameter @f$d@f$, grain density
     * @f$\rho_s@f$ and the pressure @f$P = -\operatorname{tr}
     * \boldsymbol\tau^{tr}/3@f$ of the trial state (exact for the plane
     * and edge returns of an isochoric flow, @f$\psi = 0@f$, whose
     * returns keep the pressure). @f$\dot\gamma^p@f$ is the plastic shear
     * rate (@f$\sqrt2\|\dot{\boldsymbol\varepsilon}^p\|@f$; in simple
     * shear the engineering shear rate). For @f$P \le 0@f$ and
     * @f$\dot\gamma^p > 0@f$, @f$I = \infty@f$. The rate-independent
     * model is @f$\Delta\mu = 0@f$ or @f$\Delta t \le 0@f$.
     */
    struct GranularStrength
    {
      /** Peak friction angle [rad]; 0 < phi < pi/2. */
      double friction_angle;
      /** Peak cohesion [Pa]; >= 0. */
      double cohesion;
      /** Peak dilatancy angle [rad]; 0 <= psi <= phi. */
      double dilatancy_angle;
      /** Residual friction angle [rad]; 0 < phi_r <= phi. */
      double residual_friction_angle;
      /** Residual cohesion [Pa]; 0 <= c_r <= c. */
      double residual_cohesion;
      /** Residual dilatancy angle [rad]; 0 <= psi_r <= min(psi, phi_r). */
      double residual_dilatancy_angle;
      /** Softening plastic strain eta_s [-]; > 0 if softening is active. */
      double softening_strain;
      /** Tension cut-off t [Pa]; >= 0 (its meaning depends on the model). */
      double tension_cutoff;
      /**
       * Whether the volume a point gains beyond the apex (stress-free
       * separation of the grains) is recovered without stress when it is
       * compressed again (true: the "disconnected" state of Dunatunga &
       * Kamrin, JFM 779 (2015) 483) or kept as plastic dilation (false).
       */
      bool recoverable_separation = false;
      /**
       * Increment of the friction coefficient of the rate-dependent
       * friction, tan(phi_2) - tan(phi) [-]; 0: rate-independent.
       */
      double friction_coefficient_increment = 0.;
      /** Reference inertial number I_0 [-]; > 0. */
      double reference_inertial_number = 0.279;
      /** Grain diameter d [m]; > 0 if the friction is rate-dependent. */
      double grain_diameter = 0.;
      /** Grain (solid) density rho_s [kg/m^3]. */
      double grain_density = 0.;

      /** Whether any residual value differs from its peak value. */
      bool
      softening() const;

      /** Whether the friction depends on the inertial number. */
      bool
      rate_dependent() const;

      /** A softened value and its derivative with respect to eps_p. */
      struct Value
      {
        double value;
        double derivative;
      };

      /** phi(eps_p) [rad] and d phi/d eps_p. */
      Value
      phi(const double eps_p) const;

      /** A friction angle of the rate-dependent friction and its
       * derivatives. */
      struct RateValue
      {
        /** phi [rad] */
        double value;
        /** sin(phi) [-] */
        double sin;
        /** cos(phi) [-] */
        double cos;
        /** d phi/d eps_p [rad] (softening and rate) */
        double d_plastic_strain;
        /** d phi/d P [rad/Pa] */
        double d_pressure;
      };

      /**
       * The friction angle of the rate-dependent friction at the
       * accumulated plastic strain @p eps_p, reached with the increment
       * @p plastic_strain_increment over @p time_step [s] under the
       * pressure @p pressure [Pa] (compression positive). Equals
       * phi(eps_p) if rate_dependent() is false or @p time_step <= 0.
       * With @p compute_angle false, the rate-dependent angle itself
       * (value, an arctangent) is left NaN; its sine, cosine and
       * derivatives are always set.
       * d_plastic_strain is the derivative along eps_p =
       * eps_p_old + increment.
       */
      RateValue
      phi(const double eps_p,
          const double plastic_strain_increment,
          const double pressure,
          const double time_step,
          const bool   compute_angle = true) const;

      /** c(eps_p) [Pa] and dc/d eps_p. */
      Value
      c(const double eps_p) const;

      /** psi(eps_p) [rad] and d psi/d eps_p. */
      Value
      psi(const double eps_p) const;

      /**
       * Mean stress of the apex, p = min(c cot(phi), t) [Pa], and its
       * derivative with respect to eps_p (the cut-off t does not soften).
       */
      Value
      apex_pressure(const double eps_p) const;

      /** One line with all values (angles in degrees). */
      std::string
      to_string() const;

      /** Sine and cosine of an angle. */
      struct SinCos
      {
        double sin;
        double cos;
      };

      /**
       * sin and cos of @p angle [rad]. The peak and residual friction and
       * dilatancy angles are looked up in the table that
       * tabulate_trigonometry() fills (the return mappings need them at
       * every point in every Newton iteration); any other angle, or all of
       * them before the table is filled, is computed. The table is keyed
       * by the exact angle, so a changed parameter is never served a stale
       * value.
       */
      SinCos
      sin_cos(const double angle) const;

      /** tan(@p angle), from the same table as sin_cos(). */
      double
      tan(const double angle) const;

      /**
       * Fill the table of sin_cos() and tan() for the current peak and
       * residual angles (the models call it once at construction).
       */
      void
      tabulate_trigonometry();

      /**
       * The table of sin_cos() and tan(), filled by tabulate_trigonometry()
       * (public so that the struct stays an aggregate). Rows: angle [rad],
       * sin, cos, tan; the angle NaN while unfilled.
       */
      std::array<std::array<double, 4>, 4> trigonometry_table{
        {{{std::numeric_limits<double>::quiet_NaN(), 0., 1., 0.}},
         {{std::numeric_limits<double>::quiet_NaN(), 0., 1., 0.}},
         {{std::numeric_limits<double>::quiet_NaN(), 0., 1., 0.}},
         {{std::numeric_limits<double>::quiet_NaN(), 0., 1., 0.}}}};
    };


    /**
     * Result of the return mapping in principal space, with the principal
     * values ordered @f$\tau_1\ge\tau_2\ge\tau_3@f$ (tension positive).
     */
    struct PrincipalReturn
    {
      /** Returned principal Kirchhoff stresses [Pa] (sorted). */
      dealii::Tensor<1, 3> tau;
      /**
       * Consistent tangent d tau_a / d eps^trial_c [Pa] (sorted indices).
       */
      dealii::Tensor<2, 3> dtau_deps;
      /** Accumulated plastic strain at the end of the step [-]. */
      double plastic_strain;
      /** 0 elastic, 1 plane/cone, 2 edge, 3 apex, 4 tension cut-off. */
      unsigned int return_type;
    };


    /**
     * Common part of the finite-strain elastoplastic models for granular
     * materials (MohrCoulomb, DruckerPrager): Hencky elasticity and
     * multiplicative plasticity with the return mapping in principal
     * logarithmic elastic strains (E.A. de Souza Neto, D. Peric, D.R.J.
     * Owen, Computational Methods for Plasticity, Wiley 2008, ch. 14;
     * J.C. Simo, CMAME 99 (1992) 61-112).
     *
     * With @f$\mathbf G = \mathbf C_p^{-1}@f$ of the last accepted step
     * (history), the trial elastic left Cauchy-Green tensor is
     * @f$\mathbf b^e_{tr} = \mathbf F_{n+1}\mathbf G_n\mathbf F_{n+1}^T =
     * \sum_a b_a\mathbf n_a\otimes\mathbf n_a@f$ and the trial elastic
     * logarithmic strains are @f$\varepsilon^{tr}_a = \frac12\ln b_a@f$.
     * The derived class maps the trial principal Kirchhoff stresses
     * @f$\tau^{tr}_a = \lambda\sum_c\varepsilon^{tr}_c + 2\mu
     * \varepsilon^{tr}_a@f$ back to the yield surface exactly as in the
     * small-strain theory (principal_return()), which also gives the
     * consistent principal tangent @f$\partial\tau_a/\partial
     * \varepsilon^{tr}_c@f$. Then
     * @f$\mathbf b^e_{n+1} = \sum_a \exp(2\varepsilon_a)\mathbf n_a\otimes
     * \mathbf n_a@f$, @f$\varepsilon_a = \mathbb D^{-1}\tau@f$,
     * @f$\mathbf G_{n+1} = \mathbf F^{-1}\mathbf b^e_{n+1}\mathbf F^{-T}@f$,
     * @f$\mathbf P = \boldsymbol\tau\mathbf F^{-T}@f$, and the exact
     * @f$\partial\mathbf P/\partial\mathbf F@f$ follows from
     * LogarithmicStrain::principal_kirchhoff_to_piola().
     *
     * History (10 values): @f$\mathbf G@f$ as xx, yy, zz, xy, yz, xz;
     * the accumulated equivalent plastic strain
     * @f$\bar\varepsilon^p = \sum\sqrt{2/3}\,\|\Delta\boldsymbol
     * \varepsilon^p\|@f$ (principal logarithmic plastic strain increments
     * of every step); the plastic dissipation per unit reference volume
     * @f$\sum\boldsymbol\tau_{n+1}:\Delta\boldsymbol\varepsilon^p@f$
     * [J/m^3] (backward Euler); the return type of the last step
     * (0 elastic, 1 plane or cone, 2 edge, 3 apex, 4 tension cut-off);
     * the open volumetric strain @f$\varepsilon_o@f$.
     *
     * *Recoverable separation* (GranularStrength::recoverable_separation):
     * a return to the hydrostatic apex normally stores all of the trial
     * volumetric strain beyond the apex's in @f$\mathbf C_p@f$, so a point
     * that was stretched while stress-free (grains separating at a free
     * surface or a spreading front) resists compression from its dilated
     * volume on and never recompacts. With recoverable separation the
     * excess @f$\varepsilon_o = \max(0, \operatorname{tr}
     * \varepsilon^{tr} - \operatorname{tr}\mathbb D^{-1}\tau_a)@f$ stays
     * in @f$\mathbf b^e@f$ as an isotropic, stress-free opening: the next
     * trial state starts from it, and the point carries the apex stress
     * until it is compressed back to the apex volume (the "disconnected"
     * state of Dunatunga & Kamrin, JFM 779 (2015) 483, in a Hencky
     * setting). The stress, the tangent and the plastic strain of the
     * step are those of the ordinary apex return; the stored energy
     * excludes @f$\varepsilon_o@f$.
     */
    class GranularPlasticity : public ConstitutiveModel
    {
    public:
      /** Index of the accumulated plastic strain in the history. */
      static constexpr unsigned int plastic_strain_index = 6;
      /** Index of the plastic dissipation [J/m^3] in the history. */
      static constexpr unsigned int dissipation_index = 7;
      /** Index of the return type in the history. */
      static constexpr unsigned int return_type_index = 8;
      /**
       * Index of the open (separated) volumetric logarithmic strain in the
       * history: the part of the elastic volumetric strain beyond the apex
       * that carries no stress (0 unless recoverable separation is on).
       */
      static constexpr unsigned int open_strain_index = 9;

      /**
       * @param elastic  the elastic constants
       * @param strength  strength parameters (angles in radians)
       */
      GranularPlasticity(const IsotropicElasticity &elastic,
                         const GranularStrength    &strength);

      /** 10. */
      unsigned int
      n_history_variables() const override;

      /** G = I, all other values 0. */
      void
      initialize_history(
        const dealii::ArrayView<double> &history) const override;

      /**
       * G = b^e = exp(2 eps^e) with the Hencky elastic strain
       * eps^e = D^-1 : stress of the given stress at F = I, all other
       * values 0; false if the stress lies outside the yield surface (the
       * return mapping of F = I from that state is not elastic).
       */
      bool
      initialize_history_for_stress(
        const dealii::SymmetricTensor<2, 3> &stress,
        const dealii::ArrayView<double>     &history) const override;

      /** Names of the 10 history values. */
      std::vector<std::string>
      history_names() const override;

      /**
       * The return type stored in the history: 0 elastic, then plane,
       * edges and apex of the yield surface (see principal_return()).
       */
      unsigned int
      return_branch(
        const dealii::ArrayView<const double> &history) const override;

      /** Return mapping, P and (if A is not nullptr) the consistent dP/dF. */
      void
      compute_stress(const dealii::Tensor<2, 3>            &F_old,
                     const dealii::Tensor<2, 3>            &F_new,
                     const dealii::ArrayView<const double> &history_old,
                     const dealii::ArrayView<double>       &history_new,
                     const double                           time_step,
                     dealii::Tensor<2, 3>                  &P,
                     dealii::Tensor<4, 3>                  *A) const override;

      /**
       * Hencky energy of the elastic logarithmic strain of
       * @f$\mathbf b^e = \mathbf F\mathbf G\mathbf F^T@f$ [J/m^3].
       */
      double
      energy_density(
        const dealii::Tensor<2, 3>            &F,
        const dealii::ArrayView<const double> &history) const override;

      /** lambda + 2 mu [Pa]. */
      double
      p_wave_modulus() const override;

      /** The elastic constants. */
      const IsotropicElasticity &
      elasticity() const;

      /** The strength parameters (angles in radians). */
      const GranularStrength &
      strength() const;

      /**
       * The return mapping in principal space: trial principal elastic
       * logarithmic strains @p eps_trial (sorted, largest first) and the
       * accumulated plastic strain @p plastic_strain_old of the last step;
       * @p time_step [s] is the length of the step (<= 0: no rate, the
       * static friction of a rate-dependent strength is used).
       * Throws ExcReturnMappingFailed if it fails.
       */
      virtual PrincipalReturn
      principal_return(const dealii::Tensor<1, 3> &eps_trial,
                       const double                plastic_strain_old,
                       const double                time_step) const = 0;

    protected:
      const IsotropicElasticity elastic;
      const GranularStrength    strength_parameters;
      /** Principal elastic moduli lambda + 2 mu delta_ac. */
      dealii::Tensor<2, 3> D;
      /** Their inverse (principal compliance). */
      dealii::Tensor<2, 3> C;

      /**
       * Return to a stress prescribed as a function of the plastic strain
       * and the trial strain (apex, cap, corner): solve
       * @f$\bar\varepsilon^p = \bar\varepsilon^p_n + \sqrt{2/3}\,
       * \|\varepsilon^{tr} - \mathbb D^{-1}T(\bar\varepsilon^p,
       * \varepsilon^{tr})\|@f$ for @f$\bar\varepsilon^p@f$ by Newton's
       * method and differentiate the result consistently.
       *
       * @p stress(eps_p, eps_trial, T, dT_deps_p, dT_deps) gives the stress
       * and its partial derivatives.
       */
      PrincipalReturn
      prescribed_stress_return(
        const dealii::Tensor<1, 3>                        &eps_trial,
        const double                                       plastic_strain_old,
        const std::function<void(const double,
                                 const dealii::Tensor<1, 3> &,
                                 dealii::Tensor<1, 3> &,
                                 dealii::Tensor<1, 3> &,
                                 dealii::Tensor<2, 3> &)> &stress,
        const unsigned int                                 return_type,
        const std::string                                 &what) const;

      /** Throw ExcReturnMappingFailed with a message naming @p what. */
      [[noreturn]] void
      fail(const std::string          &what,
           const dealii::Tensor<1, 3> &eps_trial,
           const double                plastic_strain_old,
           const std::string          &reason) const;
    };


    /**
     * Declare the strength parameters shared by MohrCoulomb and
     * DruckerPrager (friction angle, cohesion, dilatancy angle, tension
     * cut-off, residual values, softening plastic strain) in the current
     * subsection of @p prm. @p tension_cutoff_meaning completes the doc
     * string of the tension cut-off.
     */
    void
    declare_granular_strength(dealii::ParameterHandler &prm,
                              const std::string        &tension_cutoff_meaning);

    /**
     * Read and check the parameters declared by declare_granular_strength()
     * from the current subsection of @p prm; @p subsection_path (e.g.
     * "Material/Mohr-Coulomb") is used in error messages. Throws
     * ExcInvalidInput for values out of range.
     */
    GranularStrength
    read_granular_strength(const dealii::ParameterHandler &prm,
                           const std::string              &subsection_path);
  } // namespace Materials
} // namespace Talus

#endif
