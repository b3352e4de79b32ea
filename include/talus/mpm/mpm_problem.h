#ifndef talus_mpm_mpm_problem_h
#define talus_mpm_mpm_problem_h

#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/materials/constitutive_model.h>
#include <talus/mpm/adaptive_grid.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/initial_stress.h>
#include <talus/mpm/load_balancing.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/memory_estimate.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <memory>
#include <ostream>
#include <string>

namespace Talus
{
  namespace MPM
  {
    /**
     * What a committed step lost: material points that left the
     * background grid (removed) and boundary particles that did so, per
     * boundary. Reported by the caller (MPMProblem::take_losses()).
     */
    template <int dim>
    struct StepLosses
    {
      unsigned int n_points = 0;
      double       mass     = 0.; ///< [kg]
      /** Bounding box of the lost points' last positions [m]. */
      std::pair<dealii::Point<dim>, dealii::Point<dim>> region;
      std::vector<unsigned int> boundary_particles; ///< per boundary
    };

    /**
     * What a load-balancing check between two steps did
     * (MPMProblem::balance_load()).
     */
    struct RepartitionRecord
    {
      /** Whether the grid was repartitioned. */
      bool repartitioned = false;
      /** Whether a pass of the adaptive grid changed the grid. */
      bool adapted = false;
      /**
       * Imbalance of the material points before and after (the largest
       * rank's points over the mean; LoadBalancing::imbalance()) [-].
       */
      double imbalance_before = 1.;
      double imbalance_after  = 1.;
      /** Largest and smallest number of points on a rank, after. */
      unsigned long long max_points = 0;
      unsigned long long min_points = 0;
    };

    /**
     * The soil problem of Talus: the implicit material point method
     * (founding paper, section 2) on one parameter file, as an object that
     * a time loop or a coupling scheme drives from outside.
     *
     * It owns every object of the MPM side (background grid, constitutive
     * model, material points, initial stress, boundary particles and the
     * MPMSolver) and builds them from their subsections (`Background
     * grid`, `Material`, `Body`, `Initial stress`, `Solver`, `Boundary
     * particles`). A time step is
     *
     *   prepare_step(t_{n+1}, dt)  P2G, constraints, active set start
     *   solve_step()               Newton on the grid increment; repeatable,
     *                              no side effect on the committed state
     *                              (points, boundary particles, friction
     *                              states, energy accounts)
     *   commit_step()              G2P, the points move, the step's
     *                              reactions and energies are booked
     *
     * so that a rejected step or a coupling iteration just calls
     * prepare_step() and solve_step() again (a coupling iteration that
     * only moved the interface calls update_boundary_displacement()
     * instead of prepare_step()). save_state() and
     * restore_state() copy everything a committed step changes (the
     * points with their history, the boundary particles with gaps,
     * reactions, states and multipliers, the grid friction states, the
     * energy accounts) so that a committed step can be undone as well
     * (the coupled problem rejects both fields when the interface does not
     * converge after the MPM committed).
     *
     * The time integrator (Newmark-beta) belongs to the caller, who owns
     * the time control shared by all fields of a coupled problem.
     */
    template <int dim>
    class MPMProblem
    {
    public:
      MPMProblem(const MPI_Comm       communicator,
                 const NewmarkBeta   &newmark,
                 dealii::TimerOutput &timer);

      /**
       * Declare the subsections of every object the problem owns, with
       * @p n_boundaries subsections `Boundary N` of `Boundary particles`
       * (Boundaries::BoundaryParticles::n_boundaries_in_file()).
       */
      static void
      declare_parameters(
        dealii::ParameterHandler &prm,
        const unsigned int        n_boundaries =
          Boundaries::BoundaryParticles<dim>::default_boundary_slots);

      /**
       * Build the grid (refined @p refinement times, for convergence
       * studies), the model, the points, the solver and the boundaries
       * from @p prm. Nothing is generated yet: see setup().
       */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const unsigned int        refinement = 0);

      /**
       * Generate the material points and the boundary particles, apply the
       * initial stress and set up the solver.
       */
      void
      setup();

      /**
       * Initial accelerations at @p time (M a = f_ext - f_int with the
       * boundary conditions): the state a first step starts from.
       */
      void
      initialize(const double time);

      /** Initialization phase of the step to @p new_time (P2G). */
      void
      prepare_step(const double new_time, const double dt);

      /**
       * Prepare the step of the last prepare_step() again after only the
       * boundaries' prescribed displacement changed (a coupling iteration
       * after the first of a step): MPMSolver::update_boundary_displacement(),
       * which reuses the P2G and, where the boundary cells are unchanged,
       * the sparsity pattern; solve_step() then gives bitwise the result of
       * a full prepare_step().
       */
      void
      update_boundary_displacement();

      /** Newton on the grid increment; no side effect on committed state. */
      NewtonResult
      solve_step();

      /** Convective phase: G2P, move and sort the points. */
      void
      commit_step();

      /**
       * The losses of the last commit_step() (and any before that were
       * not taken yet); resets the counters.
       */
      StepLosses<dim>
      take_losses();

      /** Copy the committed state (see the class documentation). */
      void
      save_state();

      /** Go back to the state of the last save_state(). */
      void
      restore_state();

      /**
       * Write the committed state into the directory @p directory (a
       * checkpoint; collective): the parallel::distributed triangulation
       * (Triangulation::save(), files `mpm_grid*`) carrying the material
       * points and the boundary particles with all their properties
       * (ParticleHandler::prepare_for_serialization(), one after the
       * other on the same triangulation) and, through
       * parallel::distributed::SolutionTransfer, the committed grid
       * velocity and the stuck grid friction nodes; and a boost archive
       * `mpm_state` (rank 0) with what identifies the problem (dimension,
       * property counts, cells, points) and the solver's energy accounts.
       * Call it between steps (after commit_step()).
       */
      void
      save_checkpoint(const std::string &directory);

      /**
       * Replace the committed state by that of the checkpoint in
       * @p directory, written by save_checkpoint() with any number of
       * ranks. Call it after setup() (which builds everything the file
       * describes) instead of initialize(). Throws ExcInvalidInput when
       * the checkpoint does not belong to this problem (another
       * dimension, grid, material model or number of boundaries) or its
       * files cannot be read.
       */
      void
      load_checkpoint(const std::string &directory);

      /**
       * Repartition the background grid between the ranks with the cell
       * weights of subsection `Load balancing`
       * (LoadBalancing::cell_weight(), connected to the triangulation's
       * signal `weight` for this call only), carrying the committed state
       * (CommittedStateTransfer: both particle handlers, the committed
       * grid velocity and stuck friction nodes) and rebuilding the
       * solver's partition-dependent data. Call it between steps only
       * (after commit_step() or initialize()); a copy of save_state() is
       * discarded (restore_state() then throws). Collective.
       */
      void
      repartition();

      /**
       * The load-balancing check after step @p step (0: the start): the
       * imbalance of the material points and, when LoadBalancing::due(),
       * repartition(), reported on @p log (the step, the imbalance before
       * and after, the points per rank). Does nothing (and reports no
       * repartition) when load balancing is off. Between steps only.
       * Collective.
       */
      RepartitionRecord
      balance_load(const unsigned int                step,
                   const dealii::ConditionalOStream &log);

      /**
       * One pass of the adaptive grid (subsection `Adaptive grid`,
       * AdaptiveGrid): flag the cells, refine and coarsen them, carrying
       * the committed state like repartition() (CommittedStateTransfer:
       * both particle handlers and the committed grid vectors, whose
       * hanging nodes are then interpolated from their masters) and
       * rebuilding the solver's grid-dependent data (hanging-node
       * constraints included). Returns whether the grid changed. Between
       * steps only; a copy of save_state() is discarded. Collective.
       */
      bool
      adapt_grid();

      /** The parameters of subsection `Adaptive grid`. */
      const AdaptiveGrid<dim> &
      adaptive_grid() const
      {
        return adaptive;
      }

      /** The parameters of subsection `Load balancing`. */
      const LoadBalancing<dim> &
      load_balancing() const
      {
        return balancing;
      }

      /** Integrals over all points (all ranks). */
      Diagnostics<dim>
      diagnostics() const
      {
        return mpm_solver->compute_diagnostics();
      }

      /**
       * Print the description of the problem (grid, points, boundaries) on
       * @p out. Collective: call it on every rank.
       */
      void
      print_summary(const dealii::ConditionalOStream &out) const;

      /**
       * With an adaptive grid and boundary particles: the grid's cells and
       * DoFs, the cells that hold boundary particles and how many of them
       * are at the maximum level (one line); with `refine at boundaries`
       * the same for the cells at those faces that are near the material
       * (one line; nothing otherwise).
       */
      void
      print_adaptive_grid(const dealii::ConditionalOStream &out) const;

      BackgroundGrid<dim> &
      grid()
      {
        return *background_grid;
      }

      const BackgroundGrid<dim> &
      grid() const
      {
        return *background_grid;
      }

      MaterialPoints<dim> &
      points()
      {
        return *material_points;
      }

      const MaterialPoints<dim> &
      points() const
      {
        return *material_points;
      }

      Boundaries::BoundaryParticles<dim> &
      boundaries()
      {
        return *boundary_particles;
      }

      const Boundaries::BoundaryParticles<dim> &
      boundaries() const
      {
        return *boundary_particles;
      }

      MPMSolver<dim> &
      solver()
      {
        return *mpm_solver;
      }

      const MPMSolver<dim> &
      solver() const
      {
        return *mpm_solver;
      }

      const Materials::ConstitutiveModel &
      model() const
      {
        return *constitutive_model;
      }

      /** Density of the material of body 1 [kg/m^3]. */
      double
      density() const
      {
        return material_density;
      }

      const InitialStress<dim> &
      initial_stress() const
      {
        return initial_stress_field;
      }

      /** The time integrator of the caller. */
      const NewmarkBeta &
      time_integrator() const
      {
        return newmark;
      }

      /** The memory estimate made before the grid was created. */
      const MemoryEstimate<dim> &
      memory_estimate() const
      {
        return memory;
      }

      MPI_Comm
      get_communicator() const
      {
        return communicator;
      }

    private:
      MPI_Comm             communicator;
      const NewmarkBeta   &newmark;
      dealii::TimerOutput &timer;

      std::unique_ptr<BackgroundGrid<dim>> background_grid;
      /** The model of each material subsection a body uses (else null). */
      std::vector<std::unique_ptr<Materials::ConstitutiveModel>> materials;
      /** Density of each material subsection a body uses [kg/m^3]. */
      std::vector<double> material_densities;
      /** The material of body 1 (model(), density()). */
      const Materials::ConstitutiveModel  *constitutive_model = nullptr;
      double                               material_density   = 0.;
      std::unique_ptr<MaterialPoints<dim>> material_points;
      InitialStress<dim>                   initial_stress_field;
      std::unique_ptr<MPMSolver<dim>>      mpm_solver;
      std::unique_ptr<Boundaries::BoundaryParticles<dim>> boundary_particles;
      LoadBalancing<dim>                                  balancing;
      AdaptiveGrid<dim>                                   adaptive;
      /** The global refinement of the background grid (convergence
       * studies), the level the adaptive grid counts from. */
      unsigned int        base_refinement = 0;
      MemoryEstimate<dim> memory;
      /** Whether save_state() holds a copy on the present partition. */
      bool saved_state_valid = false;
      /** The end of the step of the last prepare_step() [s]. */
      double step_end_time = 0.;
    };
  } // namespace MPM
} // namespace Talus

#endif
