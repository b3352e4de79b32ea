#ifndef talus_materials_drucker_prager_h
#define talus_materials_drucker_prager_h

#include <talus/materials/granular_plasticity.h>

#include <deal.II/base/tensor.h>

#include <string>

namespace Talus
{
  namespace Materials
  {
    /**
     * Finite-strain Drucker-Prager plasticity with a mean-stress tension
     * cut-off and exponential softening, the cone matched to the
     * Mohr-Coulomb parameters.
     *
     * Kinematics, elasticity (Hencky), softening and history: see
     * GranularPlasticity. Kirchhoff stresses, <b>tension positive</b>,
     * @f$p = \operatorname{tr}\boldsymbol\tau/3@f$,
     * @f$J_2 = \frac12\mathbf s:\mathbf s@f$:
     * @f[
     *   f = \sqrt{J_2} + \eta\,p - \xi\,c \le 0,\qquad
     *   g = \sqrt{J_2} + \bar\eta\,p,\qquad p \le t,
     * @f]
     * with (de Souza Neto et al. 2008, section 6.4.2) for the cone fit
     * - plane strain: @f$\eta = 3\tan\phi/\sqrt{9+12\tan^2\phi}@f$,
     *   @f$\xi = 3/\sqrt{9+12\tan^2\phi}@f$;
     * - triaxial compression (outer cone): @f$\eta = 6\sin\phi/
     *   (\sqrt3(3-\sin\phi))@f$, @f$\xi = 6\cos\phi/(\sqrt3(3-\sin\phi))@f$;
     * - triaxial extension (inner cone): the same with @f$3+\sin\phi@f$;
     *
     * and @f$\bar\eta@f$ the same function of @f$\psi@f$ as @f$\eta@f$ of
     * @f$\phi@f$. For all fits the apex lies at @f$p = c\cot\phi@f$. For
     * @f$c = 0@f$ the cone is @f$\sqrt{J_2}/(-p) = \eta@f$: at
     * @f$\phi = 19.8^\circ@f$ 0.332 (plane strain), 0.441 (triaxial
     * compression), 0.351 (triaxial extension).
     *
     * The tension cut-off @f$t@f$ limits the <b>mean stress</b>
     * @f$p \le t@f$ (a plane normal to the hydrostatic axis, associative),
     * not the maximum principal stress as in MohrCoulomb.
     *
     * Return mapping (de Souza Neto et al. 2008, section 8.3, with softening,
     * in principal logarithmic strains): cone (type 1: the deviatoric
     * direction is kept, @f$\sqrt{J_2} = \sqrt{J_2^{tr}} - \mu\Delta\gamma@f$,
     * @f$p = p^{tr} - K\bar\eta\Delta\gamma@f$, solved with the accumulated
     * plastic strain by a local Newton method); if the trial mean stress
     * exceeds @f$t@f$: cap (@f$p = t@f$, deviator kept, type 4) or the
     * cap-cone corner (@f$p = t@f$, @f$\sqrt{J_2} = \xi c - \eta t@f$, type
     * 4); else the apex @f$p = \min(c\cot\phi, t)@f$, @f$\mathbf s = 0@f$
     * (type 3). Consistent tangents by implicit differentiation.
     *
     * With a rate-dependent strength (GranularStrength::rate_dependent(),
     * the @f$\mu(I)@f$ friction) the cone coefficients are those of
     * @f$\phi(\bar\varepsilon^p, \Delta\bar\varepsilon^p, P^{tr},
     * \Delta t)@f$ in the cone return (unknowns Δγ and the increment of the
     * plastic strain); cap and apex keep the static friction.
     */
    class DruckerPrager : public GranularPlasticity
    {
    public:
      /** How the cone is matched to the Mohr-Coulomb pyramid. */
      enum class ConeFit
      {
        plane_strain,
        triaxial_compression,
        triaxial_extension
      };

      /**
       * @param elastic  Young's modulus and Poisson's ratio
       * @param strength  strength parameters (angles in radians)
       * @param fit  cone fit
       */
      DruckerPrager(const IsotropicElasticity &elastic,
                    const GranularStrength    &strength,
                    const ConeFit              fit);

      /** Returns "Drucker-Prager". */
      std::string
      name() const override;

      /**
       * The model and its parameters in one line, with the cone fit and
       * the resulting ratio sqrt(J2)/(-p) for c = 0.
       */
      std::string
      description() const override;

      /** See the class documentation. */
      PrincipalReturn
      principal_return(const dealii::Tensor<1, 3> &eps_trial,
                       const double                plastic_strain_old,
                       const double                time_step) const override;

      /** Yield function f [Pa] at the accumulated plastic strain eps_p. */
      double
      yield_function(const dealii::Tensor<1, 3> &tau, const double eps_p) const;

      /**
       * Cone coefficient eta for the angle @p angle [rad] (friction angle:
       * eta; dilatancy angle: eta bar) and its derivative.
       */
      GranularStrength::Value
      eta(const double angle) const;

      /** Cone coefficient xi for the friction angle @p phi [rad]. */
      GranularStrength::Value
      xi(const double phi) const;

    private:
      const ConeFit fit;
    };
  } // namespace Materials
} // namespace Talus

#endif
