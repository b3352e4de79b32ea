#ifndef talus_structure_structure_problem_h
#define talus_structure_structure_problem_h

#include <talus/structure/dynamic_solver.h>
#include <talus/structure/line_elements.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <vector>

namespace boost
{
  namespace archive
  {
    class binary_oarchive;
    class binary_iarchive;
  } // namespace archive
} // namespace boost

namespace Talus
{
  namespace Structure
  {
    /**
     * What builds a structure: its meshes, supports and loads (the
     * verification models of the structure application, a barrier of
     * BarrierBuilder, a test). StructureProblem::setup() calls build() on
     * an empty Structure, then Structure::setup_system().
     */
    class StructureBuilder
    {
    public:
      virtual ~StructureBuilder() = default;

      /** Add meshes, call Structure::setup_dofs(), add supports and loads
       * (refinement level @p level of a convergence study). */
      virtual void
      build(Structure &structure, const unsigned int level) = 0;

      /** Start of the first Newton iteration (e.g. a bulge for a flat,
       * unstressed membrane); zero by default. */
      virtual void
      initial_guess(const Structure &, dealii::Vector<double> &) const
      {}
    };


    /**
     * The barrier structure as a sub-solver of a partitioned coupling
     * (doc/architecture.md, "The structure module"): owns the Structure
     * (meshes, elements, DoFs, history), the StaticSolver (Newton with
     * UMFPACK, line search, load stepping, arc length) and the
     * DynamicSolver (Bossak-Newmark), and offers the contract the coupling
     * needs:
     *
     *  - prepare_step(t, dt), solve_step(), commit_step(). solve_step()
     *    starts from the committed state and changes nothing of it, so it
     *    can be repeated (coupling iterations) with other interface forces;
     *    from the same committed state with the same interface forces it
     *    gives bitwise the same displacement. commit_step() accepts the
     *    last solve_step(): displacement, velocity, acceleration and the
     *    element history (plastic strain of trusses, brake strokes,
     *    material lengths of stick-slip sliding cables).
     *  - save_state() / restore_state(): a snapshot of the committed state
     *    (also the force scale of the Newton tolerance), for a rejected
     *    coupled step.
     *  - set_interface_forces(): nodal forces per global DoF (not scaled by
     *    the load factor, Structure::external_forces), set before
     *    solve_step(); displacement() and velocity(): the trial state after
     *    solve_step() (the committed one after commit_step() or
     *    restore_state()).
     *
     * Two modes (subsection Structure/Dynamics, 'dynamic'):
     *  - static (quasi-static load stepping): the time t is the load
     *    factor; solve_step() finds the equilibrium
     *    f_int(u) = (t + dt) f_ext + f_interface from the committed
     *    displacement by one Newton solve (StaticSolver::solve()).
     *  - dynamic: one Bossak-Newmark step of size dt under the loads of load
     *    factor 1 and the interface forces (DynamicSolver::solve_step()).
     *
     * For the structure application's own load stepping (step cuts, secant
     * predictor) and arc length, solve_load_step() and
     * solve_arc_length_step() wrap the StaticSolver and commit on success.
     */
    class StructureProblem
    {
    public:
      /** Subsections "Solver" and "Dynamics" (of the entered subsection,
       * "Structure" in the application). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection "Solver" (prm entered in "Structure"). */
      void
      parse_solver_parameters(dealii::ParameterHandler &prm);

      /** Read subsection "Dynamics" (prm entered in "Structure"). */
      void
      parse_dynamics_parameters(dealii::ParameterHandler &prm);

      /**
       * Build the structure with @p builder (refinement level @p level)
       * and set up its system (constraints, sparsity). The solvers are
       * set up by setup_solvers().
       */
      void
      build(StructureBuilder &builder, const unsigned int level = 0);

      /** Allocate the solvers' matrices and vectors, and the initial
       * displacement of @p builder (StructureBuilder::initial_guess()). */
      void
      setup_solvers(const StructureBuilder &builder);

      /**
       * The current displacement is the committed initial state (after any
       * form finding): in dynamic mode the initial acceleration
       * M^-1 (f_ext - f_int) and zero velocity. Time 0.
       */
      void
      initialize();

      /** Dynamic (Bossak-Newmark) rather than static mode. */
      bool
      is_dynamic() const;

      /** @name Sub-solver contract
       * @{ */

      /** The next step goes from time (static: load factor) @p t to
       * @p t + @p dt. */
      void
      prepare_step(const double t, const double dt);

      /** Solve the step of prepare_step() from the committed state, with
       * the current interface forces. No side effect on the committed
       * state: repeatable. */
      NewtonStatus
      solve_step();

      /** Accept the last solve_step(). */
      void
      commit_step();

      /** Store the committed state (one snapshot; a new call replaces it). */
      void
      save_state();

      /** Make the snapshot of save_state() the committed and the current
       * state again. */
      void
      restore_state();

      /**
       * Write the committed state, what save_state() keeps (time,
       * displacement, velocity, acceleration, damping force and work of the
       * dynamic solver, the element history of every line mesh, the
       * static solver's history), into a checkpoint archive
       * (doc/checkpoint.md).
       */
      void
      save_committed_state(boost::archive::binary_oarchive &archive) const;

      /**
       * Make the state of save_committed_state() the committed and the
       * current one. The structure must be the one that wrote it (the
       * caller checks the model and the numbers of DoFs and elements);
       * throws ExcInvalidInput (message @p where first) if the sizes do not
       * match.
       */
      void
      load_committed_state(boost::archive::binary_iarchive &archive,
                           const std::string               &where);

      /** Interface forces [N] per global DoF (size n_dofs(); a tied DoF's
       * force acts on its node). */
      void
      set_interface_forces(const dealii::Vector<double> &forces);

      const dealii::Vector<double> &
      interface_forces() const;

      /**
       * Let the interface forces act with their end value over the step
       * (DynamicSolver::interface_force_at_end; 'interface force in time =
       * end of step' in subsection Coupling). A dynamic structure needs
       * the lumped mass (else the input is rejected); a static one solves
       * for the end value anyway.
       */
      void
      set_interface_force_at_end();

      /** DynamicSolver::interface_force_factor(): how many times the
       * interface forces count in the step's residual. */
      double
      interface_force_factor() const;

      /** Robin interface springs [N/m] per global DoF towards @p anchor
       * (Structure::interface_springs); empty vectors remove them. */
      void
      set_interface_springs(const dealii::Vector<double> &stiffness,
                            const dealii::Vector<double> &anchor);

      /** Displacement [m]: the trial after solve_step(), the committed one
       * after commit_step() and restore_state(). */
      const dealii::Vector<double> &
      displacement() const;

      /** Velocity [m/s] (dynamic mode; zero in static mode), trial after
       * solve_step(). */
      const dealii::Vector<double> &
      velocity() const;

      /** Time (static: load factor) of the committed state. */
      double
      time() const;
      /** @} */

      /** @name Load stepping of the structure application (commit on
       * success)
       * @{ */

      /** Newton for load factor @p load_factor from the current
       * displacement (StaticSolver::solve()). */
      NewtonStatus
      solve_load_factor(const double load_factor);

      /** From load factor @p from to @p to with step cuts
       * (StaticSolver::solve_with_cuts()). */
      NewtonStatus
      solve_load_step(const double from, const double to);

      /** One arc-length step (StaticSolver::solve_arc_length()). */
      NewtonStatus
      solve_arc_length_step(double                 &load_factor,
                            dealii::Vector<double> &direction);
      /** @} */

      /** Energy dissipated up to the committed state [J]: by the
       * elements (brakes, truss plasticity; Structure::
       * dissipated_energy()) and by Rayleigh damping (DynamicSolver::
       * damping_work). */
      double
      dissipated_energy() const;

      /** Kinetic energy of the committed state (dynamic mode) [J]. */
      double
      kinetic_energy() const;

      Structure &
      get_structure();

      const Structure &
      get_structure() const;

      StaticSolver &
      get_static_solver();

      const StaticSolver &
      get_static_solver() const;

      DynamicSolver &
      get_dynamic_solver();

      const DynamicSolver &
      get_dynamic_solver() const;

    private:
      /** Everything a rejected step must undo. */
      struct State
      {
        double                              time = 0.;
        dealii::Vector<double>              displacement;
        dealii::Vector<double>              velocity;
        dealii::Vector<double>              acceleration;
        dealii::Vector<double>              damping_force;
        double                              damping_work = 0.;
        std::vector<std::vector<LineState>> line_states;
        StaticSolver::History               solver_history;
      };

      Structure     structure;
      StaticSolver  static_solver{structure};
      DynamicSolver dynamic_solver{structure, static_solver};

      /** The committed state and the snapshot of save_state(). */
      State committed, saved;
      bool  saved_valid = false;
      /** Trial history of the last solve_step(), committed by
       * commit_step(). */
      std::vector<std::vector<LineState>> trial_line_states;

      double step_start = 0., step_size = 0.;
      bool   solved = false;

      /** The committed state from the solvers and the structure. */
      void
      store(State &state) const;

      /** After a load step of the application that committed itself: if
       * it converged, the solvers' state at @p time is the committed one.
       * Returns @p status. */
      NewtonStatus
      accept_load_step(const NewtonStatus &status, const double time);

      /** Make @p state the solvers' and the structure's state. */
      void
      load(const State &state);
    };
  } // namespace Structure
} // namespace Talus

#endif
