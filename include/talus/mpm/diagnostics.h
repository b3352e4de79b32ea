#ifndef talus_mpm_diagnostics_h
#define talus_mpm_diagnostics_h

#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/tensor.h>

#include <vector>

namespace Talus
{
  namespace MPM
  {
    /** Global integrals over the material points. */
    template <int dim>
    struct Diagnostics
    {
      double                 mass = 0.;
      dealii::Tensor<1, dim> momentum;
      double                 kinetic_energy = 0.;
      /**
       * Per body (several bodies only, else empty): mass [kg], momentum
       * [kg m/s], kinetic and strain energy [J] of its points.
       */
      std::vector<double>                 body_mass;
      std::vector<dealii::Tensor<1, dim>> body_momentum;
      std::vector<double>                 body_kinetic_energy;
      std::vector<double>                 body_strain_energy;
      /**
       * Kinetic energy of the grid velocity at the points [J],
       * sum_p m_p |sum_I N_I(x_p) v_I|^2 / 2 with the nodal velocities v_I
       * at the end of the last step: the velocity that moves the points.
       * kinetic_energy minus this includes the FLIP update's particle
       * velocity modes that the grid does not see (and that move nothing);
       * before the first step it equals kinetic_energy.
       */
      double grid_kinetic_energy = 0.;
      /** Largest speed of the grid velocity at a point [m/s] (as above). */
      double max_grid_speed       = 0.;
      double strain_energy        = 0.;
      double gravitational_energy = 0.;
      /**
       * Energy dissipated by plastic flow since the start [J]: the sum
       * over the points of V_0 times the history variable named "plastic
       * dissipation" (0 for models without it).
       */
      double plastic_dissipation = 0.;
      /** Current volume of the material, sum of V_0 det F [m^3]. */
      double volume = 0.;
      /**
       * Energy dissipated by friction on the grid's friction boundaries
       * since the start [J]: minus the work of the tangential contact
       * forces on the nodal displacement increments.
       */
      double friction_dissipation = 0.;
      /**
       * Kinetic energy the essential conditions of the grid remove at the
       * start of each step since the start [J]: sum over the steps and the
       * constrained dofs with mass of m_I v_I^2 / 2 (the inelastic impact
       * of the reset onto fixed, slip and friction boundaries; the
       * tangential part of a frictional impact is in friction_dissipation).
       */
      double reset_dissipation = 0.;
      /**
       * Kinetic energy the velocity update removes from the points relative
       * to FLIP since the start [J]: sum over the steps and points of
       * m_p (|v_FLIP|^2 - |v_p^{n+1}|^2) / 2, with v_FLIP = v_p^n + the
       * interpolated grid increment (zero with pure FLIP; the numerical
       * dissipation of a PIC blend or XPIC; not APIC's loss, which sits in
       * the projection of the affine field and is not booked).
       */
      double transfer_dissipation = 0.;
      /**
       * Energy the time integrator dissipates since the start [J]: per step
       * sum_I (du_I (f_I^n + m_I a_I^{n+1}) / 2 - m_I (|v_I^{n+1}|^2 -
       * |v_I^n|^2) / 2) over the nodes with mass (lumped masses), the work
       * of the forces by the trapezoidal rule minus the grid's kinetic
       * energy change, with f^n = f_ext - f_int(u_n) at the free nodes and
       * M a^n at the constrained ones. Newmark with gamma > 1/2 damps the
       * high frequencies and books it here (zero for gamma = 1/2, beta =
       * 1/4); so does a start acceleration a^n other than M^-1 f^n ('start
       * acceleration = projected'), by du (f^n - M a^n) / 2. Not booked
       * (zero) with the consistent mass matrix.
       */
      double integrator_dissipation = 0.;
      /**
       * Resultant force of all friction boundaries on the material at the
       * end of the last step [N] (normal and tangential contact forces).
       */
      dealii::Tensor<1, dim> contact_force;
      /** Resultants of the boundaries imposed by boundary particles. */
      std::vector<Boundaries::BoundaryResultant<dim>> boundaries;
      /**
       * Friction dissipation of each boundary of boundary particles since
       * the start [J] (the boundaries' share of friction_dissipation: the
       * work of their contact forces on the slip, without the change of
       * the springs' elastic energy).
       */
      std::vector<double> boundary_friction_dissipation;

      /**
       * Elastic energy of the boundaries' penalty springs [J]: sum over the
       * boundaries of their committed gaps' beta w |g|^2 / 2 (zero for
       * multipliers and for grid boundaries).
       */
      double
      spring_energy() const
      {
        double e = 0.;
        for (const auto &b : boundaries)
          e += b.spring_energy;
        return e;
      }

      /**
       * Multi-velocity-field contact between bodies: energy the contact
       * has dissipated since the start [J], minus the work of the contact
       * forces on the bodies (the penalty springs start every step
       * unloaded: the inelastic part of the nodal impacts and the friction
       * between bodies; zero with one velocity field).
       */
      double body_contact_dissipation = 0.;
      /** Multi-velocity field: nodes in contact at the end of the step. */
      unsigned int body_contact_nodes = 0;

      /** Kinetic + strain + gravitational + spring energy [J]. */
      double
      mechanical_energy() const
      {
        return kinetic_energy + strain_energy + gravitational_energy +
               spring_energy();
      }

      /**
       * Plastic + friction + reset + transfer + integrator + body contact
       * dissipation [J].
       */
      double
      dissipated_energy() const
      {
        return plastic_dissipation + friction_dissipation + reset_dissipation +
               transfer_dissipation + integrator_dissipation +
               body_contact_dissipation;
      }

      /**
       * mechanical_energy() + dissipated_energy() [J]: constant in time if
       * every energy the scheme moves is booked; its change is the
       * unbooked remainder (the CSV column energy_balance).
       */
      double
      energy_balance() const
      {
        return mechanical_energy() + dissipated_energy();
      }

      /** Read or write with a boost archive (checkpoints). */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int /*version*/)
      {
        ar &mass &momentum &kinetic_energy &grid_kinetic_energy &max_grid_speed
          &strain_energy &gravitational_energy &plastic_dissipation &volume
            &friction_dissipation &reset_dissipation &transfer_dissipation
              &integrator_dissipation &contact_force &boundaries
                &boundary_friction_dissipation &body_contact_dissipation;
      }
    };
  } // namespace MPM
} // namespace Talus

#endif
