#ifndef talus_mpm_energy_accounts_h
#define talus_mpm_energy_accounts_h

#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * The energies the implicit MPM scheme has taken out of the mechanical
     * energy since the start [J], as MPMSolver books them at every
     * committed step (the same on every rank); see Diagnostics for the
     * definition of each term. With the plastic dissipation of the points
     * they close the energy balance
     * E_kin + E_strain + E_grav + E_spring + sum of the dissipations
     * = const (Diagnostics::energy_balance(); doc/theory.md, "Newton's
     * method: line search and energy balance").
     */
    struct EnergyAccounts
    {
      double friction_dissipation   = 0.;
      double reset_dissipation      = 0.;
      double transfer_dissipation   = 0.;
      double integrator_dissipation = 0.;
      /**
       * Multi-velocity field: energy the contact between bodies has
       * dissipated [J], minus the work of the contact forces on the
       * bodies.
       */
      double body_contact_dissipation = 0.;
      /**
       * Friction dissipation of each boundary of boundary particles
       * (part of friction_dissipation).
       */
      std::vector<double> boundary_friction_dissipation;

      /** Read or write with a boost archive (checkpoints). */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int /*version*/)
      {
        ar &friction_dissipation &reset_dissipation &transfer_dissipation
          &integrator_dissipation &body_contact_dissipation
            &boundary_friction_dissipation;
      }
    };
  } // namespace MPM
} // namespace Talus

#endif
