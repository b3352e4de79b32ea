#include <talus/base/input.h>
#include <talus/structure/dynamic_solver.h>

#include <deal.II/lac/sparse_direct.h>

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace Talus
{
  namespace Structure
  {
    DynamicSolver::DynamicSolver(Structure &structure, StaticSolver &newton)
      : structure(structure)
      , newton(newton)
    {}


    void
    DynamicSolver::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Dynamics");
      prm.declare_entry("dynamic",
                        "false",
                        Patterns::Bool(),
                        "Solve the equations of motion in time (Bossak-"
                        "Newmark, lumped mass) instead of static load "
                        "steps. Supported by models 'square membrane' (free "
                        "vibration), 'vibrating string' and 'barrier' (form "
                        "finding, then the loads act suddenly; with damping "
                        "a static solve follows the motion: dynamic "
                        "relaxation; without, the energy is checked).");
      prm.declare_entry("end time",
                        "1",
                        Patterns::Double(),
                        "End time [s], > 0.");
      prm.declare_entry("time step",
                        "0.01",
                        Patterns::Double(),
                        "Time step [s], > 0.");
      prm.declare_entry("Bossak alpha",
                        "0",
                        Patterns::Double(-1. / 3., 0.),
                        "alpha in [-1/3, 0]: 0 is the average acceleration "
                        "rule (no numerical damping), < 0 damps high "
                        "frequencies [-].");
      prm.declare_entry("mass matrix",
                        "lumped",
                        Patterns::Selection("lumped|consistent"),
                        "Lumped (row sums, diagonal) or consistent mass "
                        "matrix (sliding cables are always lumped).");
      prm.declare_entry("mass damping",
                        "0",
                        Patterns::Double(0),
                        "Rayleigh coefficient a_M of C = a_M M + a_K K [1/s].");
      prm.declare_entry("stiffness damping",
                        "0",
                        Patterns::Double(0),
                        "Rayleigh coefficient a_K (K: tangent at the start "
                        "of the step) [s].");
      prm.leave_subsection();
    }


    void
    DynamicSolver::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Dynamics");
      enabled = prm.get_bool("dynamic");
      if (enabled)
        {
          end_time  = get_positive(prm, "Structure/Dynamics", "end time");
          time_step = get_positive(prm, "Structure/Dynamics", "time step");
        }
      alpha             = prm.get_double("Bossak alpha");
      mass_damping      = prm.get_double("mass damping");
      stiffness_damping = prm.get_double("stiffness damping");
      consistent_mass   = prm.get("mass matrix") == "consistent";
      prm.leave_subsection();
    }


    void
    DynamicSolver::update_step_start()
    {
      u_n = newton.displacement;
      if (stiffness_damping > 0.)
        {
          dealii::Vector<double> r;
          K_n.reinit(structure.get_sparsity_pattern());
          structure.assemble(u_n, 1., r, &K_n);
        }
    }


    void
    DynamicSolver::initialize()
    {
      const unsigned int n = structure.n_dofs();
      velocity.reinit(n);
      acceleration.reinit(n);
      damping_force.reinit(n);
      damping_work = 0.;
      dealii::Vector<double> r;
      structure.assemble(newton.displacement, 1., r, nullptr);
      const auto &M = structure.lumped_mass();
      if (consistent_mass)
        {
          structure.assemble_consistent_mass(M_c);
          dealii::SparseDirectUMFPACK direct;
          direct.initialize(M_c);
          acceleration = r;
          acceleration *= -1.;
          direct.solve(acceleration);
          structure.get_constraints().distribute(acceleration);
        }
      else
        for (unsigned int i = 0; i < n; ++i)
          if (M[i] > 0. && !structure.get_constraints().is_constrained(i))
            acceleration[i] = -r[i] / M[i];
      update_step_start();
      if (std::getenv("TALUS_DEBUG"))
        {
          unsigned int n_massless = 0;
          for (unsigned int i = 0; i < n; ++i)
            if (!structure.get_constraints().is_constrained(i) && !(M[i] > 0.))
              ++n_massless;
          std::cerr << "    dynamics: " << n_massless
                    << " unconstrained DoFs without mass" << std::endl;
        }
    }


    NewtonStatus
    DynamicSolver::solve_step(const double dt)
    {
      const double       beta        = 0.25 * (1. - alpha) * (1. - alpha);
      const double       gamma       = 0.5 - alpha;
      const auto        &M           = structure.lumped_mass();
      const auto        &constraints = structure.get_constraints();
      const unsigned int n           = structure.n_dofs();
      dt_last                        = dt;
      a_trial.reinit(n);
      v_trial.reinit(n);
      damping_trial.reinit(n);
      // the external forces' acceleration a^c = M^-1 F when they act with
      // their end value (lumped mass; the condensed forces, as assemble()
      // applies them; nodes without mass keep F in their static balance)
      dealii::Vector<double> a_c(n), F_c(n);
      if (interface_force_at_end)
        {
          AssertThrow(!consistent_mass,
                      dealii::ExcMessage("interface_force_at_end needs the "
                                         "lumped mass"));
          std::vector<dealii::types::global_dof_index> one(1);
          dealii::Vector<double>                       value(1);
          for (unsigned int i = 0; i < n; ++i)
            if (structure.external_forces[i] != 0.)
              {
                one[0]   = i;
                value[0] = structure.external_forces[i];
                constraints.distribute_local_to_global(value, one, F_c);
              }
          for (unsigned int i = 0; i < n; ++i)
            if (constraints.is_constrained(i) || !(M[i] > 0.))
              F_c[i] = 0.;
            else
              a_c[i] = F_c[i] / M[i];
        }

      const auto extra = [&](const dealii::Vector<double> &u,
                             dealii::Vector<double>       &r,
                             dealii::SparseMatrix<double> *K) {
        for (unsigned int i = 0; i < n; ++i)
          {
            // (with a^c: Newmark's acceleration of the increment less
            // a^c/(2 beta), the velocity with dt a^c)
            a_trial[i] = (u[i] - u_n[i] - dt * velocity[i]) / (beta * dt * dt) -
                         (0.5 - beta) / beta * acceleration[i] -
                         a_c[i] / (2. * beta);
            v_trial[i] = velocity[i] + dt * ((1. - gamma) * acceleration[i] +
                                             gamma * a_trial[i] + a_c[i]);
          }
        dealii::Vector<double> Kv;
        if (stiffness_damping > 0.)
          {
            Kv.reinit(n);
            K_n.vmult(Kv, v_trial);
          }
        // M [(1 - alpha) a + alpha a_n + a_M v].
        dealii::Vector<double> w(n), Mw(n);
        for (unsigned int i = 0; i < n; ++i)
          w[i] = (1. - alpha) * a_trial[i] + alpha * acceleration[i] +
                 mass_damping * v_trial[i];
        mass_vmult(Mw, w);
        if (mass_damping > 0. || stiffness_damping > 0.)
          {
            dealii::Vector<double> Mv(n);
            if (mass_damping > 0.)
              mass_vmult(Mv, v_trial);
            for (unsigned int i = 0; i < n; ++i)
              damping_trial[i] =
                constraints.is_constrained(i) ?
                  0. :
                  mass_damping * Mv[i] +
                    (stiffness_damping > 0. ? stiffness_damping * Kv[i] : 0.);
          }
        const double mass_factor =
          (1. - alpha) / (beta * dt * dt) + mass_damping * gamma / (beta * dt);
        for (unsigned int i = 0; i < n; ++i)
          if (!constraints.is_constrained(i))
            {
              // (+ F_c: the forces act through a^c, not as assemble()'s
              // load)
              r[i] += Mw[i] + F_c[i];
              if (stiffness_damping > 0.)
                r[i] += stiffness_damping * Kv[i];
              if (K != nullptr)
                {
                  if (consistent_mass)
                    for (auto it = M_c.begin(i); it != M_c.end(i); ++it)
                      K->add(i, it->column(), mass_factor * it->value());
                  else
                    K->diag_element(i) += mass_factor * M[i];
                }
            }
        if (K != nullptr && stiffness_damping > 0.)
          {
            // + gamma/(beta dt) a_K K_n on the unconstrained rows.
            const double f = stiffness_damping * gamma / (beta * dt);
            for (unsigned int i = 0; i < n; ++i)
              if (!constraints.is_constrained(i))
                for (auto it = K_n.begin(i); it != K_n.end(i); ++it)
                  K->add(i, it->column(), f * it->value());
          }
      };
      // Predictor: constant velocity (the constant-acceleration predictor
      // overshoots when a pre-stressed structure starts out of balance).
      newton.displacement = u_n;
      for (unsigned int i = 0; i < n; ++i)
        if (!constraints.is_constrained(i))
          newton.displacement[i] += dt * velocity[i];
      const NewtonStatus status = newton.solve(1., extra, false);
      // Make a_trial, v_trial those of the final iterate.
      if (status.converged)
        {
          dealii::Vector<double> r(n);
          extra(newton.displacement, r, nullptr);
        }
      return status;
    }


    void
    DynamicSolver::commit_step()
    {
      structure.commit_state();
      if (damping_force.size() != damping_trial.size())
        damping_force.reinit(damping_trial.size());
      for (unsigned int i = 0; i < damping_trial.size(); ++i)
        damping_work += (newton.displacement[i] - u_n[i]) * 0.5 *
                        (damping_force[i] + damping_trial[i]);
      damping_force = damping_trial;
      velocity      = v_trial;
      acceleration  = a_trial;
      for (unsigned int i = 0; i < velocity.size(); ++i)
        if (structure.get_constraints().is_constrained(i))
          velocity[i] = acceleration[i] = 0.;
      update_step_start();
    }


    void
    DynamicSolver::mass_vmult(dealii::Vector<double>       &y,
                              const dealii::Vector<double> &x) const
    {
      if (consistent_mass)
        {
          M_c.vmult(y, x);
          return;
        }
      const auto &M = structure.lumped_mass();
      for (unsigned int i = 0; i < x.size(); ++i)
        y[i] = M[i] * x[i];
    }


    double
    DynamicSolver::interface_force_factor() const
    {
      if (!enabled || !interface_force_at_end)
        return 1.;
      return (1. - alpha) / (2. * 0.25 * (1. - alpha) * (1. - alpha));
    }


    const dealii::Vector<double> &
    DynamicSolver::trial_velocity() const
    {
      return v_trial;
    }


    double
    DynamicSolver::kinetic_energy() const
    {
      dealii::Vector<double> Mv(velocity.size());
      mass_vmult(Mv, velocity);
      double T = 0.;
      for (unsigned int i = 0; i < velocity.size(); ++i)
        if (!structure.get_constraints().is_constrained(i))
          T += 0.5 * velocity[i] * Mv[i];
      return T;
    }
  } // namespace Structure
} // namespace Talus
