#ifndef talus_materials_linear_elastic_h
#define talus_materials_linear_elastic_h

#include <talus/materials/constitutive_model.h>

#include <string>

namespace Talus
{
  namespace Materials
  {
    /**
     * The constants of isotropic linear elasticity, computed from Young's
     * modulus @f$E@f$ and Poisson's ratio @f$\nu@f$:
     * @f[
     *   \lambda = \frac{E\nu}{(1+\nu)(1-2\nu)},\qquad
     *   \mu = \frac{E}{2(1+\nu)},\qquad
     *   M = \lambda + 2\mu \text{ (P-wave modulus)}.
     * @f]
     * Shared by all models whose elastic response is isotropic
     * (LinearElastic, NeoHookean, HenckyElastic and the elastoplastic
     * models built on HenckyElastic).
     */
    struct IsotropicElasticity
    {
      /**
       * @param youngs_modulus  Young's modulus E [Pa]; > 0
       * @param poissons_ratio  Poisson's ratio nu [-]; -1 < nu < 0.5
       *
       * Throws a dealii::ExceptionBase (an std::exception) if a value is out
       * of range. Values coming from the parameter file are checked before
       * (by create_model()) with messages that point at the input file.
       */
      IsotropicElasticity(const double youngs_modulus,
                          const double poissons_ratio);

      /** Young's modulus E [Pa]. */
      double youngs_modulus;
      /** Poisson's ratio nu [-]. */
      double poissons_ratio;
      /** First Lamé constant lambda [Pa]. */
      double lambda;
      /** Shear modulus mu (second Lamé constant) [Pa]. */
      double mu;

      /** Bulk modulus K = lambda + 2 mu / 3 [Pa]. */
      double
      bulk_modulus() const
      {
        return lambda + 2. * mu / 3.;
      }

      /** P-wave (constrained) modulus M = lambda + 2 mu [Pa]. */
      double
      p_wave_modulus() const
      {
        return lambda + 2. * mu;
      }
    };


    /**
     * Isotropic linear elasticity, geometrically linear (small strain):
     * @f[
     *   \boldsymbol\varepsilon = \operatorname{sym}(\mathbf F - \mathbf I),
     *   \qquad
     *   \mathbf P := \boldsymbol\sigma
     *     = \lambda \operatorname{tr}(\boldsymbol\varepsilon)\mathbf I
     *       + 2\mu\boldsymbol\varepsilon,
     *   \qquad
     *   \psi = \tfrac12\boldsymbol\sigma:\boldsymbol\varepsilon,
     * @f]
     * with the tangent (the elasticity tensor, symmetrized in the index of
     * @f$\mathbf F@f$ since only sym(F) enters)
     * @f[
     *   \mathbb A_{iJkL} = \partial P_{iJ}/\partial F_{kL}
     *   = \lambda\delta_{iJ}\delta_{kL}
     *     + \mu(\delta_{ik}\delta_{JL} + \delta_{iL}\delta_{Jk}).
     * @f]
     *
     * @warning This model is <b>not objective</b>: a rigid rotation
     * @f$\mathbf F = \mathbf Q@f$ produces a non-zero, spurious stress
     * @f$\boldsymbol\sigma = (\lambda\operatorname{tr}(\mathbf Q - \mathbf
     * I)) \mathbf I + 2\mu\operatorname{sym}(\mathbf Q - \mathbf I)@f$ of
     * order @f$\mu\theta^2@f$ for a rotation angle @f$\theta@f$. Use it
     * only for small displacements and small rotations (verification
     * against linear elastic solutions). For large rotations use
     * HenckyElastic (identical to this model for small strains) or
     * NeoHookean.
     *
     * Reference: any text on linear elasticity, e.g. T.J.R. Hughes, The
     * Finite Element Method, Dover 2000, ch. 2.
     */
    class LinearElastic : public ConstitutiveModel
    {
    public:
      /**
       * @param youngs_modulus  Young's modulus E [Pa]; > 0
       * @param poissons_ratio  Poisson's ratio nu [-]; -1 < nu < 0.5
       */
      LinearElastic(const double youngs_modulus, const double poissons_ratio);

      /** Returns "linear elastic". */
      std::string
      name() const override;

      /** P = sigma(sym(F_new - I)); F_old and the history are not used. */
      void
      compute_stress(const dealii::Tensor<2, 3>            &F_old,
                     const dealii::Tensor<2, 3>            &F_new,
                     const dealii::ArrayView<const double> &history_old,
                     const dealii::ArrayView<double>       &history_new,
                     const double                           time_step,
                     dealii::Tensor<2, 3>                  &P,
                     dealii::Tensor<4, 3>                  *A) const override;

      /** psi = 1/2 sigma : eps [J/m^3]. */
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

    private:
      const IsotropicElasticity elastic;
    };
  } // namespace Materials
} // namespace Talus

#endif
