#include <talus/base/input.h>
#include <talus/structure/structure_problem.h>

#include <deal.II/base/exceptions.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

namespace Talus
{
  namespace Structure
  {
    void
    StructureProblem::declare_parameters(dealii::ParameterHandler &prm)
    {
      StaticSolver::declare_parameters(prm);
      DynamicSolver::declare_parameters(prm);
    }


    void
    StructureProblem::parse_solver_parameters(dealii::ParameterHandler &prm)
    {
      static_solver.parse_parameters(prm);
    }


    void
    StructureProblem::parse_dynamics_parameters(dealii::ParameterHandler &prm)
    {
      dynamic_solver.parse_parameters(prm);
    }


    void
    StructureProblem::build(StructureBuilder &builder, const unsigned int level)
    {
      builder.build(structure, level);
      structure.setup_system();
    }


    void
    StructureProblem::setup_solvers(const StructureBuilder &builder)
    {
      static_solver.setup();
      builder.initial_guess(structure, static_solver.displacement);
    }


    void
    StructureProblem::initialize()
    {
      if (dynamic_solver.enabled)
        dynamic_solver.initialize();
      else
        {
          dynamic_solver.velocity.reinit(structure.n_dofs());
          dynamic_solver.acceleration.reinit(structure.n_dofs());
          dynamic_solver.damping_force.reinit(structure.n_dofs());
        }
      store(committed);
      committed.time = 0.;
      step_start     = 0.;
      step_size      = 0.;
      solved         = false;
      saved_valid    = false;
    }


    bool
    StructureProblem::is_dynamic() const
    {
      return dynamic_solver.enabled;
    }


    void
    StructureProblem::prepare_step(const double t, const double dt)
    {
      AssertThrow(dt > 0. || !dynamic_solver.enabled,
                  dealii::ExcMessage("The time step must be positive."));
      step_start = t;
      step_size  = dt;
      solved     = false;
    }


    NewtonStatus
    StructureProblem::solve_step()
    {
      // Back to the committed state: the solvers' own state (the
      // displacement Newton starts from, the force scale of its tolerance)
      // may have changed in an earlier solve_step() of the same step.
      static_solver.set_history(committed.solver_history);
      NewtonStatus status;
      if (dynamic_solver.enabled)
        status = dynamic_solver.solve_step(step_size);
      else
        {
          static_solver.displacement = committed.displacement;
          status = static_solver.solve(step_start + step_size,
                                       StaticSolver::ExtraTerms(),
                                       /*commit=*/false);
        }
      trial_line_states.clear();
      for (const auto &mesh : structure.line_meshes)
        trial_line_states.push_back(mesh->trial_state);
      solved = true;
      return status;
    }


    void
    StructureProblem::commit_step()
    {
      AssertThrow(solved,
                  dealii::ExcMessage("commit_step() needs a solve_step()."));
      // The history of the last solve_step(), whatever was assembled since.
      for (unsigned int m = 0; m < structure.line_meshes.size(); ++m)
        structure.line_meshes[m]->trial_state = trial_line_states[m];
      if (dynamic_solver.enabled)
        dynamic_solver.commit_step();
      else
        structure.commit_state();
      store(committed);
      committed.time = step_start + step_size;
      solved         = false;
    }


    void
    StructureProblem::save_state()
    {
      saved       = committed;
      saved_valid = true;
    }


    void
    StructureProblem::restore_state()
    {
      AssertThrow(saved_valid,
                  dealii::ExcMessage("restore_state() needs a save_state()."));
      committed = saved;
      load(committed);
      solved = false;
    }


    void
    StructureProblem::set_interface_forces(const dealii::Vector<double> &forces)
    {
      AssertThrow(forces.size() == structure.n_dofs(),
                  dealii::ExcDimensionMismatch(forces.size(),
                                               structure.n_dofs()));
      structure.external_forces = forces;
    }


    void
    StructureProblem::set_interface_force_at_end()
    {
      if (dynamic_solver.enabled && dynamic_solver.consistent_mass)
        InputFile::reject("Structure/Dynamics",
                          "mass matrix",
                          "consistent",
                          "'lumped' with 'interface force in time = end of "
                          "step' in subsection Coupling");
      dynamic_solver.interface_force_at_end = true;
    }


    double
    StructureProblem::interface_force_factor() const
    {
      return dynamic_solver.interface_force_factor();
    }


    void
    StructureProblem::set_interface_springs(
      const dealii::Vector<double> &stiffness,
      const dealii::Vector<double> &anchor)
    {
      AssertThrow(
        stiffness.size() == anchor.size() &&
          (stiffness.size() == 0 || stiffness.size() == structure.n_dofs()),
        dealii::ExcDimensionMismatch(stiffness.size(), structure.n_dofs()));
      structure.interface_springs = stiffness;
      structure.interface_anchor  = anchor;
    }


    const dealii::Vector<double> &
    StructureProblem::interface_forces() const
    {
      return structure.external_forces;
    }


    const dealii::Vector<double> &
    StructureProblem::displacement() const
    {
      return static_solver.displacement;
    }


    const dealii::Vector<double> &
    StructureProblem::velocity() const
    {
      if (solved && dynamic_solver.enabled)
        return dynamic_solver.trial_velocity();
      return dynamic_solver.velocity;
    }


    double
    StructureProblem::time() const
    {
      return committed.time;
    }


    NewtonStatus
    StructureProblem::solve_load_factor(const double load_factor)
    {
      return accept_load_step(static_solver.solve(load_factor), load_factor);
    }


    NewtonStatus
    StructureProblem::solve_load_step(const double from, const double to)
    {
      return accept_load_step(static_solver.solve_with_cuts(from, to), to);
    }


    NewtonStatus
    StructureProblem::solve_arc_length_step(double                 &load_factor,
                                            dealii::Vector<double> &direction)
    {
      const NewtonStatus status =
        static_solver.solve_arc_length(load_factor,
                                       static_solver.arc_length,
                                       direction);
      return accept_load_step(status, load_factor);
    }


    double
    StructureProblem::dissipated_energy() const
    {
      return structure.dissipated_energy() +
             (dynamic_solver.enabled ? dynamic_solver.damping_work : 0.);
    }


    double
    StructureProblem::kinetic_energy() const
    {
      return dynamic_solver.kinetic_energy();
    }


    Structure &
    StructureProblem::get_structure()
    {
      return structure;
    }


    const Structure &
    StructureProblem::get_structure() const
    {
      return structure;
    }


    StaticSolver &
    StructureProblem::get_static_solver()
    {
      return static_solver;
    }


    const StaticSolver &
    StructureProblem::get_static_solver() const
    {
      return static_solver;
    }


    DynamicSolver &
    StructureProblem::get_dynamic_solver()
    {
      return dynamic_solver;
    }


    const DynamicSolver &
    StructureProblem::get_dynamic_solver() const
    {
      return dynamic_solver;
    }


    NewtonStatus
    StructureProblem::accept_load_step(const NewtonStatus &status,
                                       const double        time)
    {
      if (status.converged)
        {
          store(committed);
          committed.time = time;
        }
      return status;
    }


    void
    StructureProblem::store(State &state) const
    {
      state.displacement   = static_solver.displacement;
      state.velocity       = dynamic_solver.velocity;
      state.acceleration   = dynamic_solver.acceleration;
      state.damping_force  = dynamic_solver.damping_force;
      state.damping_work   = dynamic_solver.damping_work;
      state.solver_history = static_solver.get_history();
      state.line_states.clear();
      for (const auto &mesh : structure.line_meshes)
        state.line_states.push_back(mesh->state);
    }


    void
    StructureProblem::load(const State &state)
    {
      for (unsigned int m = 0; m < structure.line_meshes.size(); ++m)
        {
          structure.line_meshes[m]->state       = state.line_states[m];
          structure.line_meshes[m]->trial_state = state.line_states[m];
        }
      static_solver.set_history(state.solver_history);
      static_solver.displacement   = state.displacement;
      dynamic_solver.velocity      = state.velocity;
      dynamic_solver.acceleration  = state.acceleration;
      dynamic_solver.damping_force = state.damping_force;
      dynamic_solver.damping_work  = state.damping_work;
      // The start of the next step (u_n, and the tangent K_n of stiffness
      // damping, which depends on the restored history).
      if (dynamic_solver.enabled)
        dynamic_solver.update_step_start();
    }


    void
    StructureProblem::save_committed_state(
      boost::archive::binary_oarchive &archive) const
    {
      const State &s = committed;
      archive << s.time << s.displacement << s.velocity << s.acceleration
              << s.damping_force << s.damping_work;
      const std::size_t n_meshes = s.line_states.size();
      archive << n_meshes;
      for (const auto &mesh : s.line_states)
        {
          const std::size_t n = mesh.size();
          archive << n;
          for (const auto &state : mesh)
            archive << state.plastic << state.accumulated;
        }
      const auto &h = s.solver_history;
      archive << h.force_scale << h.previous_displacement
              << h.previous_load_factor << h.previous_valid;
    }


    void
    StructureProblem::load_committed_state(
      boost::archive::binary_iarchive &archive,
      const std::string               &where)
    {
      State s;
      archive >> s.time >> s.displacement >> s.velocity >> s.acceleration >>
        s.damping_force >> s.damping_work;
      const auto check = [&](const std::string       &what,
                             const unsigned long long stored,
                             const unsigned long long here) {
        if (stored != here)
          throw ExcInvalidInput(
            where + "it holds " + what + " " + std::to_string(stored) +
            ", the parameter file's structure has " + std::to_string(here) +
            " (subsection <Structure>).");
      };
      check("a structure state of DoFs",
            s.displacement.size(),
            structure.n_dofs());
      std::size_t n_meshes = 0;
      archive >> n_meshes;
      check("line meshes", n_meshes, structure.line_meshes.size());
      s.line_states.resize(n_meshes);
      for (unsigned int m = 0; m < n_meshes; ++m)
        {
          std::size_t n = 0;
          archive >> n;
          check("line mesh '" + structure.line_meshes[m]->name +
                  "' with element states",
                n,
                structure.line_meshes[m]->state.size());
          s.line_states[m].resize(n);
          for (auto &state : s.line_states[m])
            archive >> state.plastic >> state.accumulated;
        }
      auto &h = s.solver_history;
      archive >> h.force_scale >> h.previous_displacement >>
        h.previous_load_factor >> h.previous_valid;
      committed = s;
      load(committed);
      saved_valid = false;
      solved      = false;
      step_start  = committed.time;
      step_size   = 0.;
    }
  } // namespace Structure
} // namespace Talus
