#ifndef talus_mpm_initial_stress_h
#define talus_mpm_initial_stress_h

#include <talus/materials/constitutive_model.h>
#include <talus/mpm/material_points.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>

namespace Talus
{
  namespace MPM
  {
    /**
     * Initial stress of the material points (subsection "Initial
     * stress"): none (stress free, the default) or geostatic.
     *
     * Geostatic: a body at rest under gravity g with a horizontal free
     * surface at level z_s, measured along the upward direction
     * e = -g/|g|, carries at a point of level z = x . e
     * @f[ \sigma_v = -\rho |g| (z_s - z), \qquad
     *     \boldsymbol\sigma = K_0\sigma_v(\mathbf I - \mathbf e\otimes
     *     \mathbf e) + \sigma_v\,\mathbf e\otimes\mathbf e @f]
     * (tension positive; in plane strain the out-of-plane stress is
     * horizontal too), with the coefficient of earth pressure at rest
     * K_0 given or, by default, Jaky's K_0 = 1 - sin(phi) of the peak
     * friction angle of a Mohr-Coulomb or Drucker-Prager material (J.
     * Jaky, J. Soc. Hung. Archit. Eng. 78 (1944) 355). rho is each
     * point's mass over its initial volume. This state is in equilibrium
     * in a laterally confined layer for any K_0 and is the usual start of
     * a slope or landslide computation (no elastic settlement under the
     * first load step). The model stores it as an elastic strain in its
     * history (ConstitutiveModel::initialize_history_for_stress()), so
     * only models with an elastic strain in their history accept it
     * (Mohr-Coulomb, Drucker-Prager), and a state outside the yield
     * surface (K_0 beyond the active or passive ratio) is rejected.
     */
    template <int dim>
    class InitialStress
    {
    public:
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** True unless the type is 'none'. */
      bool
      enabled() const
      {
        return type != "none";
      }

      /**
       * Set the history and the stress of every local point (collective).
       * Throws ExcInvalidInput naming the parameter for a model that
       * cannot hold the stress, zero gravity, a load ramp
       * (@p load_ramp_time > 0: the stress balances the full gravity), a
       * point above the free surface, or a state outside the yield
       * surface.
       */
      void
      apply(MaterialPoints<dim>                &points,
            const Materials::ConstitutiveModel &model,
            const dealii::Tensor<1, dim>       &gravity,
            const MPI_Comm                      communicator,
            const double                        load_ramp_time) const;

      /** One line for the log. */
      std::string
      description() const;

    private:
      std::string type = "none";
      double      lateral_ratio;
      bool        surface_given;
      double      surface_level;
      // Resolved in apply() (for the description):
      mutable double used_ratio   = 0.;
      mutable double used_surface = 0.;
    };
  } // namespace MPM
} // namespace Talus

#endif
