#ifndef talus_materials_mohr_coulomb_h
#define talus_materials_mohr_coulomb_h

#include <talus/materials/granular_plasticity.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace Talus
{
  namespace Materials
  {
    /**
     * Finite-strain Mohr-Coulomb plasticity with a Rankine tension cut-off
     * and exponential softening, for granular materials.
     *
     * Kinematics, elasticity (Hencky) and history: see GranularPlasticity.
     * Stresses are Kirchhoff stresses, <b>tension positive</b>, with the
     * principal values ordered @f$\tau_1\ge\tau_2\ge\tau_3@f$. The yield
     * function is
     * @f[
     *   f = (\tau_1 - \tau_3) + (\tau_1 + \tau_3)\sin\phi
     *       - 2c\cos\phi \le 0,
     * @f]
     * i.e. for compression (@f$\sigma_I = -\tau_3 \ge \sigma_{III} =
     * -\tau_1@f$, compression positive) @f$\sigma_I = \sigma_{III}N_\phi +
     * 2c\sqrt{N_\phi}@f$, @f$N_\phi = (1+\sin\phi)/(1-\sin\phi)@f$. The
     * plastic potential is the same with the dilatancy angle
     * @f$\psi\le\phi@f$ (non-associative for @f$\psi<\phi@f$). The tension
     * cut-off is a Rankine surface on the maximum principal stress,
     * @f$\tau_1 \le t@f$, with associative flow.
     *
     * Return mapping (E.A. de Souza Neto, D. Peric, D.R.J. Owen,
     * Computational Methods for Plasticity, Wiley 2008, section 8.2, boxes
     * 8.1-8.5, in
     * principal logarithmic elastic strains as in ch. 14): the trial
     * state is returned to the first admissible of: the main plane
     * (return type 1); the right edge (@f$\tau_2 = \tau_3@f$) or the left
     * edge (@f$\tau_1 = \tau_2@f$), the first one tried being selected by
     * the sign of @f$(1-\sin\psi)\tau^{tr}_1 - 2\tau^{tr}_2 +
     * (1+\sin\psi)\tau^{tr}_3@f$ (type 2); if the trial state violates the
     * cut-off, the cut-off plane(s) alone and together with the main plane
     * and an edge (type 4); else the apex @f$\tau_a = \min(c\cot\phi,
     * t)@f$ (type 3, or 4 if the cut-off is lower). A return is
     * admissible if its plastic multipliers are non-negative, the order of
     * the principal stresses is kept, and no yield surface is violated.
     * With softening the returns are solved by a local Newton method in
     * the plastic multipliers and the accumulated plastic strain (which
     * enters @f$\phi, c, \psi@f$); the consistent tangent follows by
     * implicit differentiation of the converged local equations. The apex
     * return prescribes the stress @f$\tau_a(\bar\varepsilon^p)@f$ and
     * takes the whole difference to the trial strain as plastic strain
     * (also for @f$\psi = 0@f$), with zero tangent if there is no
     * softening; for @f$c = 0@f$ every tensile trial state is returned to
     * @f$\boldsymbol\tau = 0@f$.
     *
     * With a rate-dependent strength (GranularStrength::rate_dependent(),
     * the @f$\mu(I)@f$ friction) the friction angle of the main plane and
     * the edges is @f$\phi(\bar\varepsilon^p, \bar\varepsilon^p_n,
     * P^{tr}, \Delta t)@f$: the local Newton iteration solves for the
     * plastic strain of the step together with the multipliers, and the
     * tangent includes the dependence on the trial pressure. The elastic
     * check uses the static friction (no plastic rate), the apex return the
     * static apex.
     *
     * The accumulated plastic strain (hardening variable) is the
     * equivalent plastic strain @f$\sum\sqrt{2/3}\|\Delta
     * \boldsymbol\varepsilon^p\|@f$, not de Souza Neto's
     * @f$2\cos\phi\sum\Delta\gamma@f$, which is undefined at the apex for
     * @f$\psi = 0@f$.
     */
    class MohrCoulomb : public GranularPlasticity
    {
    public:
      /**
       * @param elastic  Young's modulus and Poisson's ratio
       * @param strength  strength parameters (angles in radians)
       */
      MohrCoulomb(const IsotropicElasticity &elastic,
                  const GranularStrength    &strength);

      /** Returns "Mohr-Coulomb". */
      std::string
      name() const override;

      /** The model and all its parameters in one line. */
      std::string
      description() const override;

      /** See the class documentation. */
      PrincipalReturn
      principal_return(const dealii::Tensor<1, 3> &eps_trial,
                       const double                plastic_strain_old,
                       const double                time_step) const override;

      /**
       * Mohr-Coulomb yield function f [Pa] for the principal stresses
       * @p tau (any order) at the accumulated plastic strain @p eps_p
       * (the tension cut-off is not included).
       */
      double
      yield_function(const dealii::Tensor<1, 3> &tau, const double eps_p) const;

      /** The planes of the multisurface model in sorted principal space. */
      enum class Plane
      {
        main,
        right_edge,
        left_edge,
        cutoff_1,
        cutoff_2,
        cutoff_3
      };

    private:
      /**
       * Solve the return to the planes @p planes (all active); returns
       * false if the result is not admissible. @p converged is false if
       * the local Newton iteration of a rate-dependent friction did not
       * converge (then the return is false as well; without rate
       * dependence this throws).
       */
      bool
      return_to_planes(const dealii::ArrayView<const Plane> &planes,
                       const dealii::Tensor<1, 3>           &eps_trial,
                       const double                          plastic_strain_old,
                       const double                          time_step,
                       const double                          stress_scale,
                       PrincipalReturn                      &result,
                       bool                                 &converged) const;
    };
  } // namespace Materials
} // namespace Talus

#endif
