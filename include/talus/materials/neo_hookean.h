#ifndef talus_materials_neo_hookean_h
#define talus_materials_neo_hookean_h

#include <talus/materials/constitutive_model.h>
#include <talus/materials/linear_elastic.h>

#include <string>

namespace Talus
{
  namespace Materials
  {
    /**
     * Compressible neo-Hookean hyperelasticity, with the stored energy per
     * unit reference volume
     * @f[
     *   \psi(\mathbf F) = \frac\mu2(\operatorname{tr}\mathbf C - 3)
     *                     - \mu\ln J + \frac\lambda2(\ln J)^2,
     *   \qquad \mathbf C = \mathbf F^T\mathbf F,\quad J = \det\mathbf F,
     * @f]
     * the first Piola-Kirchhoff stress
     * @f[
     *   \mathbf P = \partial\psi/\partial\mathbf F
     *   = \mu(\mathbf F - \mathbf F^{-T}) + \lambda\ln J\,\mathbf F^{-T}
     * @f]
     * and the exact tangent
     * @f[
     *   \mathbb A_{iJkL} = \mu\delta_{ik}\delta_{JL}
     *     + (\mu - \lambda\ln J) F^{-1}_{Li} F^{-1}_{Jk}
     *     + \lambda F^{-1}_{Ji} F^{-1}_{Lk}.
     * @f]
     * It is objective and reduces to isotropic linear elasticity with Lamé
     * constants @f$\lambda,\mu@f$ for small strains. This is the material
     * of the manufactured-solution benchmark of Karamelo (de Vaucorbeil et
     * al.), whose body force
     * @f$b_i = \frac{\pi^2 u_i}{\rho}\left[\frac{\lambda}{F_{ii}^2}
     * (1 - \ln(F_{11}F_{22}F_{33})) + \mu(1 + \frac1{F_{ii}^2}) -
     * E\right]@f$ follows from this @f$\mathbf P@f$ for diagonal
     * @f$\mathbf F@f$.
     *
     * Throws ExcInvertedMaterialPoint if @f$\det\mathbf F \le 0@f$.
     *
     * Reference: J. Bonet, R.D. Wood, Nonlinear Continuum Mechanics for
     * Finite Element Analysis, 2nd ed., Cambridge University Press 2008,
     * sections 6.4.3 and 6.5.
     */
    class NeoHookean : public ConstitutiveModel
    {
    public:
      /**
       * @param youngs_modulus  Young's modulus E [Pa]; > 0
       * @param poissons_ratio  Poisson's ratio nu [-]; -1 < nu < 0.5
       */
      NeoHookean(const double youngs_modulus, const double poissons_ratio);

      /** Returns "neo-Hookean". */
      std::string
      name() const override;

      /** P(F_new) and its exact tangent; F_old and the history are unused. */
      void
      compute_stress(const dealii::Tensor<2, 3>            &F_old,
                     const dealii::Tensor<2, 3>            &F_new,
                     const dealii::ArrayView<const double> &history_old,
                     const dealii::ArrayView<double>       &history_new,
                     const double                           time_step,
                     dealii::Tensor<2, 3>                  &P,
                     dealii::Tensor<4, 3>                  *A) const override;

      /** psi(F) [J/m^3]. */
      double
      energy_density(
        const dealii::Tensor<2, 3>            &F,
        const dealii::ArrayView<const double> &history) const override;

      /** lambda + 2 mu [Pa] (the modulus at F = I). */
      double
      p_wave_modulus() const override;

      /** The elastic constants. */
      const IsotropicElasticity &
      elasticity() const;

    private:
      const IsotropicElasticity elastic;
    };
  } // namespace Materials
} // namespace Talus

#endif
