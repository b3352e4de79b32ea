#ifndef talus_mpm_mpm_solver_h
#define talus_mpm_mpm_solver_h

#include <talus/base/eisenstat_walker.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/materials/constitutive_model.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/body_contact.h>
#include <talus/mpm/boundary_contact_state.h>
#include <talus/mpm/contact_time_integration.h>
#include <talus/mpm/diagnostics.h>
#include <talus/mpm/energy_accounts.h>
#include <talus/mpm/material_points.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <boost/serialization/vector.hpp>

#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    /** Outcome of one Newton solve of a time step. */
    struct NewtonResult
    {
      bool         converged         = false;
      unsigned int iterations        = 0;
      unsigned int linear_iterations = 0;
      double       residual          = 0.; ///< last relative residual
      /** Multiplier (Uzawa) updates of augmented Lagrangian boundaries. */
      unsigned int multiplier_updates = 0;
      /** Largest gap left on augmented Lagrangian boundaries [m]. */
      double constraint_gap = 0.;
      /**
       * Converged on the residual alone: from an iterate that met the
       * residual tolerance, no step of the line search along the next
       * correction lowered the residual (see MPMSolver::solve_step()).
       */
      bool        accepted_without_descent = false;
      std::string failure; ///< why it did not converge
    };

    /**
     * Implicit Material Point Method (founding paper §3): an updated
     * Lagrangian finite element step on the fixed background grid with the
     * material points as integration points.
     *
     * Each time step is split as
     *  1. prepare_step(): initialization phase. Mass, momentum and
     *     acceleration are projected from the points to the grid
     *     (m_I = sum_p N_I m_p, v_I = sum_p N_I m_p v_p / m_I, likewise
     *     a_I), the external forces are assembled and the degrees of
     *     freedom of nodes without mass are constrained to zero, so only
     *     cells holding material points carry active unknowns.
     *  2. solve_step(): Lagrangian phase. Newton-Raphson on the grid
     *     displacement increment du for
     *     R(du) = f_ext - f_int(du) - M a_{n+1}(du) = 0 with Newmark-beta,
     *     f_int,I = sum_p V0_p P(F_p) grad_X0 N_I and the consistent
     *     tangent K = sum_p V0_p G^T A G + M/(beta dt^2), A = dP/dF (it
     *     contains the geometric stiffness). The particles are not
     *     touched: the solve can be repeated with other data (coupling
     *     iterations, rejected steps).
     *  3. commit_step(): convective phase. Positions, velocities (FLIP
     *     increment of the grid velocity), accelerations, F, stress and
     *     history of the points are updated, the points are re-sorted into
     *     cells, and the grid is reset (nothing of it is kept).
     */
    template <int dim>
    class MPMSolver
    {
    public:
      MPMSolver(BackgroundGrid<dim>                &grid,
                MaterialPoints<dim>                &points,
                const Materials::ConstitutiveModel &model,
                const NewmarkBeta                  &newmark,
                dealii::TimerOutput                &timer);

      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * The constitutive model of each material subsection (index 0:
       * "Material", ...; null for materials no body uses). Without this
       * call every point uses the model of the constructor.
       */
      void
      set_materials(
        const std::vector<const Materials::ConstitutiveModel *> &models)
      {
        materials = models;
      }

      /** The constitutive model of the point with properties @p props. */
      template <class View>
      const Materials::ConstitutiveModel &
      model_of(const View &props) const
      {
        return materials.empty() ? model :
                                   *materials[points.material_of(props)];
      }

      /** Parse subsection "Solver". */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Contact between bodies (subsection Body contact; after
       * parse_parameters()): with 'multi-velocity field' each body moves
       * on its own grid velocity field (the grid has one per body, see
       * BackgroundGrid::set_velocity_fields()) and the fields interact by
       * the penalty contact of BodyContact at the nodes they share.
       * Rejects the options it is not implemented with.
       */
      void
      set_body_contact(const BodyContact &contact);

      /** Whether each body has its own velocity field. */
      bool
      multi_velocity_field() const
      {
        return multi_field;
      }

      /**
       * Multi-velocity field: the nodes where two bodies carry mass in the
       * last step and those of them in contact at its end (all ranks).
       */
      std::pair<unsigned int, unsigned int>
      body_contact_nodes() const
      {
        return {dealii::Utilities::MPI::sum(static_cast<unsigned int>(
                                              contact_nodes.size()),
                                            grid.mpi_communicator),
                n_active_contact_nodes};
      }

      /** Sparsity pattern, matrix and boundary dofs of the grid. */
      void
      setup();

      /**
       * Initial accelerations of the points: lumped M a = f_ext - f_int at
       * the initial state, so that a body released under gravity starts
       * with a = g.
       */
      void
      initialize_acceleration(const double time);

      /** Initialization phase of the step from t to t + dt. */
      void
      prepare_step(const double new_time, const double dt);

      /**
       * Prepare the step of the last prepare_step() again after only the
       * boundaries' prescribed displacements changed (the coupling's
       * iterations of one step after the first, see doc/coupling.md):
       * keeps the P2G of the points (cells, shape data, nodal mass,
       * velocity, acceleration and external forces), which depends on the
       * committed state, t and dt only, and the contact surfaces gathered
       * for material-point contact; redoes the boundary particles and the
       * points in reach of a contact surface, ghost penalty, sparsity
       * pattern (kept if unchanged), impact friction, friction states,
       * constraints and the reset of the constrained grid velocities. The
       * following solve_step() is bitwise that after prepare_step() with
       * the same t and dt. Nothing but the boundaries' prescribed
       * displacement may have changed since that prepare_step() (no
       * change of the points or boundary particles); after commit_step(),
       * restore_state(), setup() or attach_boundary_particles() this is
       * the full prepare_step() of the last t and dt.
       */
      void
      update_boundary_displacement();

      /** Lagrangian phase: Newton iteration; no side effect on the points. */
      NewtonResult
      solve_step();

      /** Convective phase: update and move the points, reset the grid. */
      void
      commit_step();

      /**
       * The grid norms of the solved step (after solve_step(), before
       * commit_step()) for the estimate of its truncation error
       * (TruncationErrorControl): the mass weighted RMS over the grid
       * dofs with mass of the acceleration change a_{n+1} - a_n (a_{n+1}
       * from the increment by the Newmark formula, a_n that of the P2G
       * after the constraints) and of the increment du. Zero in a
       * quasi-static analysis. Collective.
       */
      TruncationErrorNorms
      truncation_error_norms() const;

      /** Integrals over all points (all ranks). */
      Diagnostics<dim>
      compute_diagnostics() const;

      /**
       * Nodal grid velocity at the end of the last committed step [m/s]
       * (ghosted, on grid.dof_handler; zero where a node had no mass). The
       * velocity the points were moved with (v_p = sum_I N_I v_I), for the
       * grid output. Empty before the first step.
       */
      const dealii::TrilinosWrappers::MPI::Vector &
      grid_velocity() const
      {
        return committed_grid_velocity;
      }

      /** Gravity vector [m/s^2]. */
      const dealii::Tensor<1, dim> &
      gravity() const
      {
        return gravity_vector;
      }

      /** Time over which gravity and body forces are ramped up [s] (0: none).
       */
      double
      load_ramp() const
      {
        return load_ramp_time;
      }

      /** Number of active (not constrained) degrees of freedom. */
      dealii::types::global_dof_index
      n_active_dofs() const
      {
        return n_active;
      }

      /**
       * Ghost penalty (small-cut stabilisation): the factor of gamma = factor
       * * M (0: off) and the number of stabilised faces in the last step.
       */
      double
      ghost_penalty() const
      {
        return ghost_penalty_factor;
      }
      unsigned int
      n_ghost_penalty_faces() const
      {
        return n_ghost_faces;
      }

      /**
       * Whether 'shape functions = cpGIMP' or 'CPDI' (convected point
       * domains).
       */
      bool
      convected_point_domains() const
      {
        return convected_domain || cpdi;
      }
      /**
       * The half-extent per direction [m] of the domain of a point whose
       * committed deformation gradient is @p F, as the next step's weights
       * use it: zero with linear shape functions (the point itself); the
       * uGIMP half-width l0; cpGIMP's |F_dd| l0_d (sum_e |F_de| l0_e with
       * 'cpGIMP domain = bounding box'); with CPDI the bounding box of
       * the parallelepiped spanned by F_n r_i^0, sum_e |F_de| l0_e; capped
       * at the cell size (the reach of the node patch). A grid node
       * receives mass from the point as soon as its support overlaps this
       * box (ContactForecast).
       */
      dealii::Tensor<1, dim>
      point_domain_half_extent(const dealii::Tensor<2, dim> &F) const;

      /** The chosen 'shape functions' (linear, uGIMP, cpGIMP or CPDI). */
      const std::string &
      shape_functions() const
      {
        return shape_name;
      }
      /**
       * cpGIMP: the point evaluations (one per point and prepared step,
       * rejected attempts included) whose half-width reached the cap, the
       * cell size, in some direction; CPDI: those whose domain was scaled
       * down to keep its corners in the 4^dim node patch and the grid;
       * and all evaluations, summed over the ranks (collective).
       */
      std::pair<unsigned long long, unsigned long long>
      capped_point_domains() const;

      /**
       * The reactions of the boundary particles at the converged iterate
       * of the last solve_step() [N], the force each exerts on the
       * boundary (minus the force on the material), for the locally
       * owned boundary particles in cells with material, by particle
       * index; particles not listed carry none. With material-point
       * contact the points' reactions, booked on the boundary particles
       * they touch, which may live on another rank: a particle's reaction
       * is the sum of its entries over the ranks. Trial state: available
       * after solve_step() and equal to the `reaction` property that
       * commit_step() then writes (the coupling sends them to the
       * structure before the step is committed).
       */
      std::vector<
        std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>
      boundary_reactions() const;

      /**
       * The force balance of the boundary particles at the converged
       * iterate of the last solve_step(), summed over all ranks
       * (collective): first the sum of their forces on the grid's nodes
       * that carry mass, assembled node by node (f_i = sum_p N_i(x_p) f_p)
       * and condensed through the hanging-node constraints by deal.II
       * (AffineConstraints::distribute_local_to_global), second the sum of
       * their reactions boundary_reactions() (with material-point contact
       * the pressed points' forces and reactions). The two add up to zero to
       * round-off when the reactions are conservative: on a locally
       * refined grid a hanging node passes its share c_hj N_h of a
       * particle's force to its masters j, and the part that acts on the
       * material is that of the masters with mass.
       */
      std::pair<dealii::Tensor<1, dim>, dealii::Tensor<1, dim>>
      boundary_force_balance() const;

      /**
       * The linearised response of boundary_reactions() to a change of the
       * boundary particles' prescribed increments, at the converged iterate
       * of the last solve_step() (the interface stiffness of a coupling).
       * For each of @p n_columns columns c, @p delta_bar(id, c) is the
       * change of the prescribed increment of the boundary particle with
       * index id [m]; returned are the changes of the reactions, in the
       * format of boundary_reactions() (this rank's entries; a particle's
       * change is the sum over the ranks).
       *
       * With the penalty force F_p = D_p (N_p du - du_bar_p) + ... on the
       * material (D_p = dF_p/du, -beta w n n^T for slip and contact, the
       * converged states held) and the step's tangent K (which contains
       * N^T (-D) N): du = K^-1 sum_p N_p^T (-D_p) d_bar_p, dF_p =
       * D_p (N_p du - d_bar_p), and the reaction changes by -dF_p. The
       * tangent is that of the last Newton iteration; with the direct
       * solver it is factorised once and the columns are back-substituted.
       * Penalty and augmented Lagrangian boundaries (multipliers held);
       * Nitsche's stress terms and Lagrange multiplier boundaries are not
       * linearised (an error). Collective.
       */
      std::vector<std::vector<
        std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>>
      linearised_boundary_reactions(const std::function<dealii::Tensor<1, dim>(
                                      const dealii::types::particle_index,
                                      const unsigned int)> &delta_bar,
                                    const unsigned int      n_columns);

      /** Whether the MPM solves for equilibrium without inertia. */
      bool
      is_quasi_static() const
      {
        return quasi_static;
      }

      /**
       * Warm start for an outer iteration that repeats the step (the
       * coupling's Dirichlet-Neumann iterations): with @p on, the next
       * solve_step() starts Newton from the increment of the last
       * converged solve_step() instead of zero (or the Newmark
       * predictor), at the nodes that are free and carry mass; the
       * convergence test keeps the residual at zero increment as its
       * reference. Off by default and after commit_step(); the result
       * agrees with a cold start to the Newton tolerance, not bitwise.
       */
      void
      set_warm_start(const bool on)
      {
        warm_start = on;
      }

      /**
       * Material-point contact: the reactions of this rank's pressed
       * points, summed per boundary particle they touch (that particle may
       * live on another rank); part of boundary_reactions().
       */
      std::vector<
        std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>
      point_contact_reactions() const;

      /**
       * Keep a copy of what commit_step() changes in the solver: the
       * energy accounts (EnergyAccounts), the committed grid velocity and its
       * kinetic energy, the grid friction states the next step starts from. The
       * points and boundary particles are saved by their owners
       * (MPMProblem::save_state()).
       */
      void
      save_state();

      /** Go back to the copy of the last save_state(). */
      void
      restore_state();

      /**
       * Read or write, with a boost archive, the committed scalars a
       * checkpoint needs (MPMProblem::save_checkpoint()): the energy
       * accounts (friction, reset, transfer, integrator and body contact
       * dissipation; EnergyAccounts::serialize()), the grid
       * kinetic energy and largest grid speed of the last commit, the
       * friction boundaries' resultant and the carried forces between
       * bodies (carried_contact). The same on every rank.
       */
      template <class Archive>
      void
      serialize_committed_scalars(Archive &ar)
      {
        ar &accounts &grid_kinetic_energy &max_grid_speed &contact_force
          &carried_contact;
      }

      /**
       * The committed grid state as two ghosted grid vectors, which a
       * checkpoint carries with the triangulation
       * (parallel::distributed::SolutionTransfer, so that any number of
       * ranks can read them): the grid velocity of the last commit and an
       * indicator that is 1 at the normal dof of every grid friction node
       * that ended the last committed step stuck (0 elsewhere).
       */
      std::vector<dealii::TrilinosWrappers::MPI::Vector>
      committed_grid_vectors() const;

      /**
       * Set the committed grid state from the vectors of
       * committed_grid_vectors() (after setup() on the loaded grid).
       */
      void
      set_committed_grid_vectors(
        const std::vector<dealii::TrilinosWrappers::MPI::Vector> &vectors);

      /** Throw an error instead of a warning when points leave the grid. */
      bool abort_on_lost_points = false;

      /**
       * The hanging-node constraints of the present grid (closed, on the
       * locally relevant dofs; empty on a conforming grid), built by
       * setup(). On a locally refined grid the MPM system lives on the
       * conforming space: P2G condenses the nodal masses, momenta and
       * forces of hanging nodes to their masters, the tangent and residual
       * are condensed with them (they are part of the step's constraints)
       * and every value a point reads at a hanging node is interpolated
       * from its masters.
       */
      const dealii::AffineConstraints<double> &
      hanging_node_constraints() const
      {
        return hanging_constraints;
      }

      /**
       * Reject the options that are not implemented on a locally refined
       * (adaptive) background grid, naming the parameters: uGIMP, APIC,
       * the consistent mass matrix, grid friction boundaries and the ghost
       * penalty. (Boundary particles are rejected by MPMProblem.)
       */
      void
      check_local_refinement_support() const;

      /**
       * Impose the boundaries of @p boundaries (weakly, on their particles)
       * from the next step on. Call after setup().
       */
      void
      attach_boundary_particles(Boundaries::BoundaryParticles<dim> &boundaries);

      /**
       * A warning (with its newline), or an empty string: a dynamic run
       * with a frictional boundary of particles at rest but without
       * numerical damping (Newmark gamma = 0.5) or without the ghost
       * penalty, where a body meant to stay at rest may slip and creep in
       * cut cells (doc/verification.md, "A block at rest whatever the
       * cut"); and friction between bodies without Newton's line search,
       * where sticking bodies make Newton cycle (doc/verification.md,
       * "Several bodies and materials"). The time loops print it outside
       * test mode.
       */
      std::string
      friction_at_rest_warning() const;

    private:
      /** The part of friction_at_rest_warning() on boundary particles. */
      std::string
      boundary_friction_at_rest_warning() const;

      /** Material points of one cell with cached shape data. */
      struct CellCache
      {
        typename dealii::DoFHandler<dim>::active_cell_iterator cell;
        std::vector<dealii::types::global_dof_index>           dofs;
        unsigned int                                           first;
        unsigned int                                           n;
        /** Boundary particles of the cell in boundary_points. */
        unsigned int first_boundary = 0;
        unsigned int n_boundary     = 0;
        /** Whether one of its boundary particles uses Nitsche's method. */
        bool nitsche = false;
        /**
         * Whether its boundary points are material points in contact
         * (contact side = material points) rather than boundary particles.
         */
        bool point_contact = false;
        /**
         * Multi-velocity field: the body of the cache's points (the cell
         * has one cache per body in it; dofs are those of this body's
         * field, in the order of FE_Q(1)^dim); 0 otherwise.
         */
        unsigned int field = 0;
        /**
         * uGIMP, cpGIMP, CPDI: the lattice index of each node of the
         * cache (the patch nodes inside the grid, in the order of dofs,
         * dim dofs each); empty with linear shape functions, whose nodes
         * are the cell's vertices.
         */
        std::vector<long long> lattice_nodes;
      };

      /**
       * Multi-velocity field: a node where bodies a < b both carry mass
       * (owned by this rank) for one step: the dofs of field a then of
       * field b (dim each), the unit normal from a to b, the normal gap at
       * the start of the step [m] and the penalty stiffness [N/m].
       */
      struct ContactNode
      {
        std::vector<dealii::types::global_dof_index> dofs;
        dealii::Tensor<1, dim>                       normal;
        double                                       gap       = 0.;
        double                                       stiffness = 0.;
        /** The node and pair: carried_key(). */
        std::vector<double> key;
        /**
         * The force on b committed at the end of the last step ('carry
         * contact forces'; zero if the node was not in contact).
         */
        dealii::Tensor<1, dim> carried;
      };
      /** The force of a contact node on body b (on a: its negative). */
      struct ContactForce
      {
        bool                   active   = false;
        bool                   slip     = false;
        double                 pressure = 0.;
        dealii::Tensor<1, dim> force;
        /** Derivative with respect to the jump du_b - du_a. */
        dealii::Tensor<2, dim> dforce;
      };
      std::vector<ContactNode> contact_nodes;
      bool                     multi_field            = false;
      double                   body_friction          = 0.;
      double                   body_penalty           = 100.;
      bool                     body_carry             = false;
      double                   body_normal_margin     = 0.05;
      unsigned int             n_active_contact_nodes = 0;
      /**
       * Committed state of 'carry contact forces': the force on b of every
       * node in contact at the end of the last step, on every rank, as
       * entries of carried_entry_size numbers: the vertex, a, b
       * (carried_key()) and the force.
       */
      std::vector<double>           carried_contact;
      static constexpr unsigned int carried_entry_size = 2 * dim + 2;

      /** What identifies a contact node: its vertex and the pair a < b. */
      static std::vector<double>
      carried_key(const dealii::Point<dim> &vertex,
                  const unsigned int        a,
                  const unsigned int        b);

      /** Contact nodes, normals and gaps of the step (after the P2G). */
      void
      prepare_body_contact();

      /** Contact force of @p node at the increment @p du (ghosted). */
      ContactForce
      body_contact_force(const ContactNode                           &node,
                         const dealii::TrilinosWrappers::MPI::Vector &du) const;

      /** Contact force of @p node at the jump du_b - du_a @p jump. */
      ContactForce
      body_contact_force(const ContactNode            &node,
                         const dealii::Tensor<1, dim> &jump) const;

      /** Add the contact forces (and tangent) of the contact nodes. */
      void
      assemble_body_contact(const dealii::TrilinosWrappers::MPI::Vector &du,
                            const bool with_matrix);

      /** Book the contact work of the converged step (commit_step()). */
      void
      commit_body_contact();

      /** A boundary particle in a cell with material, for one step. */
      using BoundaryPoint = MPM::BoundaryPoint<dim>;
      /** Force of a boundary particle on the material and its state. */
      using BoundaryForce = MPM::BoundaryForce<dim>;

      /**
       * Penalty force of boundary particle @p b for the material
       * displacement increment @p du at the particle (see doc/theory.md):
       * f = -beta w g with the gap g = g_old + du - du_bar (all components
       * for fixed, the normal part for slip and for contact in
       * compression), Coulomb return mapping of the tangential part for
       * friction; with its exact derivative.
       */
      BoundaryForce
      boundary_force(const BoundaryPoint          &b,
                     const dealii::Tensor<1, dim> &du) const;

      /**
       * Nodal forces of the boundary points whose contact force acts with
       * its end value (ContactTimeIntegration) at the increment @p du
       * (ghosted; nullptr: zero), unscaled; and the factor 1/(2 beta) with
       * which they enter the residual of Newmark's acceleration.
       */
      void
      end_contact_force(const dealii::TrilinosWrappers::MPI::Vector *du,
                        dealii::TrilinosWrappers::MPI::Vector       &f) const;
      double
      end_contact_factor() const;
      /** Whether some boundary may use the end-of-step contact force. */
      bool
      uses_end_contact_force() const;
      /** Whether the points of boundary @p desc use the end-of-step force. */
      bool
      end_of_step_contact(
        const Boundaries::BoundaryDescription<dim> &desc) const;
      /** Reject contact-time options that @p boundaries cannot use. */
      void
      check_contact_time_integration(
        const Boundaries::BoundaryParticles<dim> &boundaries) const;

      /**
       * Nitsche's method: the traction T = -sigma n the material exerts
       * on itself across the boundary at particle @p b for the cell's
       * increments @p du_local, with sigma = sigma_n + C : grad du (the
       * stress at the start of the step, projected to the nodes and
       * interpolated, plus the elastic increment with the tangent C of the
       * undeformed material), and its derivatives @p dT with respect to
       * the cell's degrees of freedom.
       */
      void
      boundary_traction(const BoundaryPoint                 &b,
                        const std::vector<double>           &du_local,
                        dealii::Tensor<1, dim>              &T,
                        std::vector<dealii::Tensor<1, dim>> &dT) const;

      /** Trial state of the boundary particles (evaluate_boundary_trial()). */
      using BoundaryParticleTrial = MPM::BoundaryParticleTrial<dim>;
      /** Trial state of the material points in contact. */
      using PointContactTrial = MPM::PointContactTrial<dim>;
      std::vector<BoundaryParticleTrial> boundary_trial;
      std::vector<PointContactTrial>     point_contact_trial;
      /**
       * Work dissipated by each boundary of boundary particles in the step
       * (all ranks) [J].
       */
      std::vector<double> boundary_trial_work;

      /** Evaluate the boundary trial state at the converged increment. */
      void
      evaluate_boundary_trial();

      /** Write the boundary trial state into the particles (commit). */
      void
      commit_boundary_trial();

      /** Newton (with Uzawa updates) of solve_step(). */
      NewtonResult
      solve_increment();

      /** Project the points' Cauchy stresses to the nodes (Nitsche). */
      void
      project_stress_to_grid();

      /**
       * Uzawa update of the augmented Lagrangian boundary particles at the
       * current increment: lambda <- f (the force they exert). Returns the
       * largest gap they had (all ranks) [m].
       */
      double
      update_multipliers();

      /**
       * Newton-Raphson on the current contact data from the increment
       * @p du; @p reference is the residual that relative tolerances refer
       * to (set by the first solve of the step when zero).
       */
      void
      newton_solve(dealii::TrilinosWrappers::MPI::Vector &du,
                   const double                           f_ext_norm,
                   double                                &reference,
                   NewtonResult                          &result);

      /**
       * Record the force f_n = f_ext - f_int(u_n) at the free nodes with
       * mass from the residual at du = 0 (which holds -M a(du = 0)): the
       * start force of the step, booked by commit_step() in the
       * integrator's dissipation (the work of M a_n - f_n).
       */
      void
      record_start_force();

      /**
       * Initial accelerations @p a (owned) that obey the conditions of the
       * boundary particles (called by initialize_acceleration()).
       */
      void
      initial_acceleration_with_boundaries(
        dealii::TrilinosWrappers::MPI::Vector &a);

      /** Boundary particles in the cells with material (prepare_step). */
      void
      cache_boundary_particles();

      /**
       * The material points that may touch a boundary with contact side =
       * material points in this step, as boundary points of their cells
       * (called by cache_boundary_particles()).
       */
      void
      cache_point_contacts();

      void
      cache_particles();

      /**
       * Multi-velocity field: one cache per body with points in @p cell,
       * on the dofs of that body's field (cache_particles()).
       */
      void
      cache_cell_per_body(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell);

      /**
       * Complete the cache @p c (cell, first, n and, with linear shape
       * functions, dofs set) with @p points_of_cache: append them to
       * particles, their shape values and gradients (GIMP: also the patch
       * dofs of the cache's field), and move it to cells.
       */
      void
      append_cell_cache(
        const std::vector<typename dealii::Particles::ParticleIterator<dim>>
                  &points_of_cache,
        CellCache &c);

      /**
       * Linear shape functions: append the values and gradients of the
       * cell's Q1 functions at @p reference_points (unit cell coordinates)
       * to @p values and @p gradients, point by point (the gradients
       * scaled by the extent of this cell, on any level, on Cartesian
       * grids, through the mapping otherwise). The material points'
       * transfer (shape_values, shape_gradients) and the boundary
       * particles use it.
       */
      void
      append_q1_shapes(
        const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
        const std::vector<dealii::Point<dim>> &reference_points,
        std::vector<double>                   &values,
        std::vector<dealii::Tensor<1, dim>>   &gradients) const;

      /**
       * uGIMP and cpGIMP: the patch dofs of a material cell into @p c and
       * the weights and gradients of its points (at @p reference_points,
       * the unit cell coordinates; the points are particles[c.first ...],
       * cpGIMP reads their committed deformation gradient) onto
       * shape_values and shape_gradients.
       */
      void
      cache_gimp_cell(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const std::vector<dealii::Point<dim>> &reference_points,
        CellCache                             &c);

      /**
       * uGIMP, cpGIMP and CPDI: check the grid, fill lattice_dofs and the
       * (initial) half-widths.
       */
      void
      setup_gimp_lattice();

      void
      project_to_grid();

      /**
       * The part of prepare_step() after the P2G, which depends on the
       * boundaries: boundary particles, ghost penalty, sparsity pattern,
       * impact friction, friction states, constraints and the reset of the
       * constrained grid velocity and acceleration.
       */
      void
      prepare_boundaries();

      /**
       * Whether the P2G data of the last prepare_step() (cells, shape
       * data, nodal mass, external forces, velocity_p2g,
       * acceleration_p2g) are those of the committed state at time and dt
       * (update_boundary_displacement()); cleared by whatever changes the
       * committed state or the grid.
       */
      bool p2g_current = false;
      /**
       * Material-point contact: the surface of each such boundary as every
       * rank gathers it from the boundary particles (positions, normals,
       * reference positions, particle ids; cache_point_contacts()), kept
       * for update_boundary_displacement() (the particles move only in
       * commit_step()).
       */
      using ContactSurface = Boundaries::GatheredSurface<dim>;
      std::vector<ContactSurface> contact_surfaces;
      /** Set while update_boundary_displacement() prepares. */
      bool updating_boundaries = false;
      /** Nodal acceleration of the P2G, before the constraints reset it. */
      dealii::TrilinosWrappers::MPI::Vector acceleration_p2g;
      /**
       * Degrees of freedom of the cells, boundary cells and ghost faces
       * (each block preceded by its size) that the current step sparsity
       * pattern was built with (make_step_sparsity_pattern()); whether
       * there is one (not after setup()).
       */
      std::vector<dealii::types::global_dof_index> pattern_blocks;
      bool                                         pattern_current = false;
      /**
       * Whether the next numeric factorisation of the direct solver pivots
       * anew (the first of a preparation; later ones reuse its pivots).
       */
      bool direct_pivoting = true;

      void
      make_constraints();

      /**
       * XPIC(m) (Hammerquist and Nairn 2017): @p w = (I - P)^m v^n for the
       * points of the step, with P the mass-weighted projection of point
       * velocities to the nodes and back at the old positions. The XPIC
       * velocity is the FLIP velocity minus @p w.
       */
      void
      compute_xpic_correction(std::vector<dealii::Tensor<1, dim>> &w) const;

      /**
       * Assemble the residual (and the tangent if @p with_matrix) at the
       * increment @p du (ghosted). Returns false if a constitutive update
       * failed on any rank (message in @p failure).
       *
       * With @p same_iterate the caller asserts that @p du, the step and
       * the material state are those of the previous assembly, which was
       * with the matrix, and that only the constraints or the contact
       * states of the friction nodes changed (a contact state update in
       * the Newton loop). The material cells' contributions, stored by that
       * assembly before the friction rows and the constraints act on them,
       * are then distributed again without evaluating the material points
       * (the results are bitwise those of a full assembly). Cells whose
       * inertia changed (a node released from contact gets a new velocity)
       * are evaluated again.
       */
      bool
      assemble(const dealii::TrilinosWrappers::MPI::Vector &du,
               const bool                                   with_matrix,
               const bool                                   with_inertia,
               std::string                                 &failure,
               const bool same_iterate = false);

      /**
       * Newton correction: solve the tangent system for @p increment (and,
       * with Lagrange multiplier boundaries, the multiplier corrections
       * dlambda of the boundary points); returns the linear iterations.
       * The Krylov solve of the displacement system stops at the relative
       * residual @p relative_tolerance (the multipliers' inner solves at
       * 'linear solver tolerance').
       */
      unsigned int
      solve_linear(dealii::TrilinosWrappers::MPI::Vector &increment,
                   const double                           relative_tolerance);

      /**
       * Saddle-point system of the Lagrange multiplier boundaries,
       * [A C; D E] [x; y] = [r; s] with A the assembled tangent (which
       * contains the k N^T D N of the trial force), C = -N^T D,
       * D_b = D N, E = (I - D) / k and s = (f - lambda) / k, solved by
       * GMRES on the Schur complement E - D A^-1 C with k as diagonal
       * preconditioner; every application solves with A (factorised once
       * with the direct solver, AMG-preconditioned Krylov otherwise), or
       * ('saddle-point solver = block preconditioned') by FGMRES on the
       * whole system with a block upper-triangular preconditioner (one
       * AMG V-cycle for A, the point-wise Schur approximation for the
       * multipliers; Benzi, Golub & Liesen 2005, Acta Numerica 14, §10).
       */
      unsigned int
      solve_saddle_point(dealii::TrilinosWrappers::MPI::Vector &increment);

      /**
       * Build the preconditioner of the tangent @p matrix: the ML AMG
       * hierarchy with the rigid body modes as near null space (into amg),
       * or the Ifpack ILU or Jacobi preconditioner ('preconditioner').
       */
      void
      build_amg();

      /** Whether the preconditioner of 'preconditioner' exists. */
      bool
      preconditioner_built() const;

      /** The preconditioner of 'preconditioner' (built). */
      const dealii::TrilinosWrappers::PreconditionBase &
      preconditioner() const;

      /**
       * With TALUS_DEBUG_LINEAR: the convergence history of a failed
       * Krylov solve of A x = b and the tangent's diagonal range and
       * non-symmetry, on stderr.
       */
      void
      print_linear_diagnostics(const dealii::SolverControl &control,
                               const dealii::TrilinosWrappers::MPI::Vector &b,
                               const std::string &label) const;

      /**
       * Solve A x = b with the assembled tangent @p matrix (direct or
       * AMG-preconditioned Krylov, see 'Linear solver'); returns the
       * linear iterations. A Krylov solve stops at the relative residual
       * @p relative_tolerance.
       */
      unsigned int
      solve_with_tangent(dealii::TrilinosWrappers::MPI::Vector       &x,
                         const dealii::TrilinosWrappers::MPI::Vector &b,
                         const double relative_tolerance);

      /** Whether a boundary point of this step uses Lagrange multipliers
       * (all ranks). */
      bool with_lagrange_multipliers = false;
      /**
       * Largest constraint residual |lambda - f| / k of the Lagrange
       * multiplier points at the last assembly (this rank) [m].
       */
      double multiplier_residual = 0.;
      /** Factorisation of the tangent for the saddle-point solve. */
      std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> factorisation;
      /**
       * Direct solver of the tangent (Amesos KLU) for the sparsity pattern
       * of the current step: the symbolic analysis (block triangular form,
       * AMD ordering) is done once per pattern (which steps and coupling
       * iterations with the same cells keep), the numeric factorisation
       * in every Newton iteration, the first after each preparation with
       * partial pivoting, the later ones reusing its pivot sequence where
       * it stays accurate (Amesos' "Refactorize"). Released with the
       * pattern.
       */
      std::unique_ptr<Epetra_LinearProblem> direct_problem;
      std::unique_ptr<Amesos_BaseSolver>    direct_solver;

      dealii::Tensor<1, dim>
      external_acceleration(const dealii::Point<dim> &X, const double t) const;

      /**
       * Record the return branch of material point @p k (index into
       * particles) from its trial @p history in a Newton assembly, and
       * count a change against the previous assembly.
       */
      void
      record_branch(const unsigned int                     k,
                    const dealii::ArrayView<const double> &history) const;

      /** Return branch of every point at the last Newton assembly (-1:
       * none yet in this solve), and the number of changes counted by the
       * current assembly. */
      mutable std::vector<int> point_branches;
      mutable unsigned int     branch_changes = 0;

      /**
       * Internal force and (if @p k_local is not nullptr) its derivative
       * for the points of cell @p c with the F-bar treatment: the
       * incremental deformation gradient f_p = I + grad(du) of every point
       * is replaced by (J_bar/J_p)^(1/dim) f_p with the volume-weighted
       * cell average J_bar of J_p = det f_p; the derivative (Sacado forward
       * AD around the model's analytic tangent) is exact. Returns false
       * (and @p failure) if a constitutive update fails.
       */
      bool
      fbar_cell(const CellCache            &c,
                const std::vector<double>  &du_local,
                dealii::Vector<double>     &r_local,
                dealii::FullMatrix<double> *k_local,
                std::string                &failure) const;

      /**
       * Deformation gradients F_bar of the points of cell @p c for the
       * displacement increment @p du_local (F-bar or plain).
       */
      void
      cell_deformation_gradients(
        const CellCache                     &c,
        const std::vector<double>           &du_local,
        std::vector<dealii::Tensor<2, dim>> &F_new) const;

      /** Grid nodes on friction boundaries; see setup(). */
      void
      setup_friction_nodes();

      /**
       * Friction of the impact at the grid reset: a friction node whose
       * projected velocity v approaches its boundary (v_n = n.v < 0, n the
       * inward normal) loses the normal velocity when the constraint sets
       * it to zero (a perfectly inelastic impact, normal impulse
       * m |v_n|). Coulomb's law bounds the tangential impulse by mu times
       * that: v_t <- v_t max(0, 1 - mu |v_n| / |v_t|) (Bardenhagen et al.
       * 2000, J. Comput. Phys. 160, eq. 14). Without it the impulse the
       * reset removes carries no friction, and the floor's friction
       * depends on how often the grid is reset (the time step). The
       * kinetic energy lost tangentially is added to the friction
       * dissipation.
       */
      void
      apply_impact_friction();

      /** Contact states at the beginning of a step. */
      void
      initialize_friction_states();

      /**
       * Update the contact states from the unconstrained residual and the
       * displacement increment; returns the number of changed nodes (all
       * ranks) and, if any, updates the constraints. The increments the
       * new states prescribe are not written into @p du: they become
       * inhomogeneities of the constraints (target - du), which the next
       * Newton correction satisfies together with the free nodes
       * (#contact_targets).
       */
      unsigned int
      update_friction_states(dealii::TrilinosWrappers::MPI::Vector &du);

      /** Send the owners' states to the ranks that see the node. */
      void
      exchange_friction_states();

      /** Tangential velocity at t_{n+1} of dof i for increment du_i. */
      double
      new_velocity(const dealii::types::global_dof_index i,
                   const double                          du_i) const;

      /** Increment that makes the velocity of dof i zero at t_{n+1}. */
      double
      resting_increment(const dealii::types::global_dof_index i) const;

      BackgroundGrid<dim>                &grid;
      MaterialPoints<dim>                &points;
      const Materials::ConstitutiveModel &model;
      /** Per material subsection (set_materials()); empty: model. */
      std::vector<const Materials::ConstitutiveModel *> materials;
      const NewmarkBeta                                &newmark;
      dealii::TimerOutput                              &timer;

      // Parameters.
      bool                   quasi_static;
      bool                   consistent_mass;
      ContactTimeIntegration contact_time_integration;
      dealii::Tensor<1, dim> gravity_vector;
      std::unique_ptr<dealii::Functions::ParsedFunction<dim>> body_force;
      double                                                  load_ramp_time;
      unsigned int max_newton_iterations;
      unsigned int max_state_change_newton_iterations;
      double       residual_tolerance;
      double       absolute_residual_tolerance;
      double       increment_tolerance;
      /** 'increment test = estimated error' (else 'last correction'). */
      bool        estimated_increment_error = false;
      std::string linear_solver_type;
      double      linear_tolerance;
      /** Inexact Newton: the tolerance of each Krylov solve. */
      EisenstatWalkerForcing linear_forcing;
      unsigned int           max_linear_iterations;
      /** Amesos package of 'linear solver = direct' ("Amesos_Klu" or
       * "Amesos_Mumps"). */
      std::string direct_package = "Amesos_Klu";
      /** Preconditioner of CG and GMRES: "AMG", "ILU" or "Jacobi". */
      std::string preconditioner_type = "AMG";
      /** GMRES restart length (deal.II keeps it + 2 vectors). */
      unsigned int gmres_restart = 28;
      /** ML smoother sweeps per level and aggregation threshold. */
      unsigned int amg_sweeps    = 2;
      double       amg_threshold = 0.02;
      /** ML: smoothed aggregation for symmetric (true, "SA") or
       * non-symmetric (false, "NSSA", Petrov-Galerkin) operators. */
      bool amg_elliptic = true;
      /** ML: W-cycle instead of the V-cycle. */
      bool amg_w_cycle = false;
      /** ML: largest coarse problem, solved with KLU ("coarse: max size"). */
      unsigned int amg_coarse_size = 2000;
      /** Fill level (ILU(k)) of 'preconditioner = ILU'. */
      unsigned int ilu_fill = 0;

      // Step data.
      double time;
      double dt;

      std::vector<CellCache>                                         cells;
      std::vector<typename dealii::Particles::ParticleIterator<dim>> particles;
      /**
       * Nitsche: the nodal Cauchy stress, column j in nodal_stress[j]
       * (entry of node I, component i: sigma_ij), ghosted; and the
       * elastic tangent dP/dF of the undeformed material.
       */
      std::vector<dealii::TrilinosWrappers::MPI::Vector> nodal_stress;
      dealii::Tensor<4, dim>                             elastic_tangent;
      bool                                               with_nitsche = false;
      std::vector<double>                                shape_values;
      std::vector<dealii::Tensor<1, dim>>                shape_gradients;
      std::vector<dealii::Tensor<1, dim>> particle_forces; ///< m_p b_p [N]

      dealii::AffineConstraints<double> constraints;
      /** See hanging_node_constraints(). */
      dealii::AffineConstraints<double> hanging_constraints;
      /** Whether any rank's grid has hanging nodes. */
      bool has_hanging_nodes = false;

      /**
       * The value of the ghosted grid vector @p v at @p dof, interpolated
       * from the masters if @p dof is a hanging node (its own entry is
       * not used: the solver's vectors hold values at the free dofs).
       */
      double
      conforming_value(const dealii::TrilinosWrappers::MPI::Vector &v,
                       const dealii::types::global_dof_index        dof) const
      {
        if (!has_hanging_nodes || !hanging_constraints.is_constrained(dof))
          return v(dof);
        double value = 0.;
        for (const auto &e : *hanging_constraints.get_constraint_entries(dof))
          value += e.second * v(e.first);
        return value;
      }

      /**
       * The share of a boundary force at node @p dof that acts on the
       * material: 1 if the node carries mass, else 0; a hanging node h
       * passes it to its masters j, sum_j c_hj [m_j > 0] (the nodal mass
       * vector must be ghosted).
       */
      double
      mass_share(const dealii::types::global_dof_index dof) const
      {
        if (!has_hanging_nodes || !hanging_constraints.is_constrained(dof))
          return nodal_mass(dof) > 0. ? 1. : 0.;
        double share = 0.;
        for (const auto &e : *hanging_constraints.get_constraint_entries(dof))
          if (nodal_mass(e.first) > 0.)
            share += e.second;
        return share;
      }

      /** Add the cell vector @p local to @p v, condensing hanging nodes. */
      void
      add_condensed(const std::vector<dealii::types::global_dof_index> &dofs,
                    const dealii::Vector<double>                       &local,
                    dealii::TrilinosWrappers::MPI::Vector              &v) const
      {
        if (has_hanging_nodes)
          hanging_constraints.distribute_local_to_global(local, dofs, v);
        else
          v.add(dofs, local);
      }
      dealii::IndexSet                                           fixed_dofs;
      std::vector<dealii::IndexSet>                              slip_dofs;
      dealii::TrilinosWrappers::SparseMatrix                     matrix;
      std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
      /** The Ifpack preconditioner of 'preconditioner = ILU' or 'Jacobi'
       * (built like the AMG hierarchy: once per step, in build_amg()). */
      std::unique_ptr<dealii::TrilinosWrappers::PreconditionBase>
           ifpack_preconditioner;
      bool amg_current = false;
      /** Whether a boundary particle's contact state changed in the last
       * assembly of the matrix (the AMG hierarchy is then rebuilt). */
      bool boundary_states_changed = false;
      /**
       * The contact state of each boundary point (in the order of
       * boundary_points, -2: not assembled) at the last assembly of the
       * matrix; cleared by newton_solve() unless the preconditioner is kept
       * for a coupling iteration.
       */
      std::vector<int> assembled_states;
      /**
       * Set by make_step_sparsity_pattern() when a coupling iteration
       * (update_boundary_displacement()) left the sparsity pattern as it
       * was: the preconditioner of the last Newton solve is kept for the
       * next one; consumed by newton_solve().
       */
      bool preconditioner_kept_for_window = false;
      std::unique_ptr<Epetra_MultiVector> rigid_body_modes;
      std::vector<dealii::Point<dim>>     owned_support_points;
      std::vector<unsigned int>           owned_components;
      bool                                reuse_preconditioner = true;
      std::string                         amg_smoother         = "Chebyshev";
      std::vector<std::vector<bool>>      constant_modes;

      /**
       * Ghost penalty (small-cut stabilisation): the factor of gamma =
       * factor * M, and the face matrices gamma h int_F [grad N_i . n]
       * [grad N_j . n] of the present step with their interface dofs.
       */
      double ghost_penalty_factor = 0.;
      struct GhostFace
      {
        std::vector<dealii::types::global_dof_index> dofs;
        dealii::FullMatrix<double>                   matrix;
      };
      std::vector<GhostFace> ghost_faces;
      unsigned int           n_ghost_faces = 0;
      /** Find the faces to stabilise and compute their matrices. */
      void
      setup_ghost_penalty();

      /**
       * Sparsity pattern of the step's tangent: the couplings of the cells
       * with material points, of the cells with boundary particles and of
       * the ghost-penalty faces, and the diagonal of every other degree of
       * freedom (the empty grid's, constrained to zero). The pattern of the
       * whole grid would make the direct solver factorise the empty part
       * of the grid as well (its zeros are stored entries). The pattern,
       * the matrix and the symbolic factorisation of the direct solver are
       * kept if the blocks of the cells, boundary cells and ghost faces
       * are those of the last pattern on every rank (the assembly zeroes
       * the matrix; the first factorisation of the step pivots anew).
       */
      void
      make_step_sparsity_pattern();

      /** Anti-locking treatment ("none" or "F-bar"). */
      bool use_fbar = false;

      /**
       * 'shape functions = uGIMP': a material point influences the nodes of
       * the 3^dim cells around its cell with the uGIMP weights (particle
       * half-width l_p = h / (2 n) per direction, n points per cell per
       * direction); else the Q1 shape functions of its cell. Also true
       * with 'shape functions = cpGIMP' (convected_domain).
       */
      bool gimp = false;
      /**
       * 'shape functions = cpGIMP' (contiguous-particle GIMP, Bardenhagen
       * and Kober 2004, with the domain update of Wallstedt and Guilkey
       * 2008): the half-widths follow the point's deformation
       * gradient F_n committed at the end of the last step, frozen over a
       * step; capped at the cell size h (the 4^dim patch's reach).
       */
      bool convected_domain = false;
      /**
       * cpGIMP's stretch of the half-widths: true for the bounding box of
       * the deformed domain, l_i = sum_j |F_ij| l0_j; false for the
       * diagonal, l_i = |F_ii| l0_i (Wallstedt and Guilkey 2008).
       */
      bool domain_bounding_box = false;
      /**
       * 'shape functions = CPDI' (convected particle domain interpolation,
       * CPDI1 of Sadeghirad, Brannon and Burghardt 2011, IJNME 86): the
       * point's domain is the parallelogram (parallelepiped in 3D) spanned
       * by r_i = F_n r_i^0, r_i^0 = l0_i e_i, frozen over a step; the
       * weights average the Q1 functions over its 2^dim corners. Uses the
       * uGIMP patch (gimp is true with it); corners are kept in the patch
       * and the grid by scaling the domain down (internal::cpdi_weights()).
       */
      bool cpdi = false;
      /** The chosen 'shape functions' (for messages). */
      std::string shape_name = "linear";
      /**
       * cpGIMP: point-steps whose half-width reached the cap h in some
       * direction, and all point-steps, summed over the run on this rank.
       */
      unsigned long long n_capped_domains = 0, n_domain_evaluations = 0;
      /**
       * Nodes per point in shape_values and shape_gradients: 2^dim (linear)
       * or 4^dim (uGIMP; the entries of patch nodes outside the grid are
       * zero). A material cell's dofs are node-major (internal::
       * component_and_node()), c.dofs.size() / dim of its nodes are used.
       */
      unsigned int shape_stride = 1u << dim;
      /**
       * uGIMP half-width of the points per direction [m]; cpGIMP's
       * undeformed one l0.
       */
      dealii::Tensor<1, dim> gimp_half_width;
      /**
       * uGIMP: the dofs of every locally relevant grid vertex by its
       * lattice index (integer coordinates of the vertex, linearised):
       * component d of velocity field f at entry f dim + d (one field
       * unless multi-velocity field); see setup().
       */
      std::unordered_map<long long,
                         std::vector<dealii::types::global_dof_index>>
        lattice_dofs;
      /** Vertices per direction of the lattice (uGIMP). */
      std::array<long long, dim> lattice_size;

      /** Backtracking line search in Newton's method. */
      bool line_search = false;
      /**
       * Newton's initial guess: "zero", "constant acceleration" (du = dt v_n
       * + dt^2/2 a_n) or "automatic" (the latter without boundary
       * particles, zero with them).
       */
      std::string predictor = "automatic";
      /**
       * Start acceleration a_n of the grid's Newmark step: "projected" (the
       * points' accelerations projected like their velocities) or "from
       * forces" (a_n = M^-1 (f_ext - f_int) at the start of the step, the
       * acceleration the trapezoidal rule's energy identity needs; lumped
       * mass only).
       */
      bool start_acceleration_from_forces = false;
      /**
       * Grid dofs whose friction contact state changed in the current Newton
       * iteration, with the value their increment must take in the new state
       * (normal 0; tangential: the resting increment of a stuck node).
       * make_constraints() imposes target - du as the inhomogeneity of their
       * constraints, so that the next correction moves the free nodes with
       * them (instead of writing the target into the iterate, which shears
       * the cells at the node and sends stiff plastic points far past the
       * yield surface).
       */
      std::vector<std::pair<dealii::types::global_dof_index, double>>
        contact_targets;
      /** target - du at the dofs of #contact_targets (ghosted). */
      dealii::TrilinosWrappers::MPI::Vector contact_jump;
      /** Whether #contact_jump holds jumps to impose. */
      bool   contact_jump_active = false;
      double flip_fraction       = 1.;
      /**
       * 'FLIP fraction reference step' [s]: a step of size dt blends with
       * flip_fraction^(dt / flip_reference_step); 0: flip_fraction per step.
       */
      double flip_reference_step = 0.;
      /** Affine particle-in-cell velocity update instead of FLIP. */
      bool apic = false;
      /** Order m of the XPIC velocity update; 0: not used. */
      unsigned int xpic_order      = 0;
      unsigned int max_line_search = 4;
      /** Saddle-point systems by block-preconditioned FGMRES (else Schur). */
      bool block_saddle_point = false;

      /** Contact state of a grid node on a friction boundary. */
      enum class ContactState
      {
        free,  ///< separated: no constraint
        stick, ///< normal and tangential increments prescribed
        slip   ///< normal prescribed, Coulomb force tangentially
      };

      /** A grid node on a friction boundary (seen by this rank). */
      struct FrictionNode
      {
        dealii::types::global_dof_index normal_dof;
        unsigned int                    normal_component;
        /** Tangential dofs not constrained by other boundaries. */
        std::vector<dealii::types::global_dof_index> tangential_dofs;
        /** Direction (component) of each tangential dof. */
        std::vector<unsigned int> tangential_components;
        double                    inward; ///< +1 or -1
        double                    mu;
        bool                      owned;
        ContactState              state;
        dealii::Tensor<1, dim>    slip_direction;
        unsigned int              switches;
        /** Held in its state after too many changes in this step. */
        bool held = false;
      };
      std::vector<FrictionNode> friction_nodes;
      /** normal dof -> index in friction_nodes */
      std::map<dealii::types::global_dof_index, unsigned int> friction_node_of;
      /** Cells (active_cell_index) with a friction node. */
      std::vector<bool> cell_touches_friction;
      /** Dofs of nodes on two friction boundaries: fixed. */
      dealii::IndexSet friction_corner_dofs;
      /** Residual without constraints at the friction nodes (owned). */
      dealii::TrilinosWrappers::MPI::Vector raw_residual;
      /**
       * The material cells' local tangents and residuals of the last
       * assembly with the matrix, before friction rows and constraints
       * (cells.size() blocks of dofs_per_cell^2 + dofs_per_cell values; kept
       * only with friction boundaries, whose contact state updates
       * re-assemble at the same iterate): see assemble().
       */
      std::vector<double> cell_contributions;
      /** Whether cell_contributions holds the last assembly's values. */
      bool cell_contributions_current = false;
      /**
       * Dofs whose inertia changed since cell_contributions was stored
       * (nodes released from contact; sorted): their cells are evaluated
       * again by a same-iterate assembly.
       */
      std::vector<dealii::types::global_dof_index> inertia_changed_dofs;
      /**
       * Committed grid friction state: for every entry of friction_nodes,
       * whether the node ended the last committed step (or the initial
       * acceleration) stuck. initialize_friction_states() reads it for
       * 'friction state guess = previous step', never the trial states
       * of a rejected attempt or of an earlier coupling iteration.
       */
      std::vector<bool> committed_stuck;

      /** The accumulated energy accounts (committed steps only). */
      EnergyAccounts accounts;

      /** What commit_step() changes in the solver (save_state()). */
      struct CommittedState
      {
        EnergyAccounts                        accounts;
        double                                grid_kinetic_energy = -1.;
        double                                max_grid_speed      = -1.;
        dealii::Tensor<1, dim>                contact_force;
        dealii::TrilinosWrappers::MPI::Vector grid_velocity;
        std::vector<bool>                     stuck;
        bool                                  saved = false;
      };
      CommittedState saved_state;

      /** Record the friction nodes' states as the committed ones. */
      void
      commit_friction_states();

      /**
       * The present step's impact friction and reset dissipation [J] (all
       * ranks): set by prepare_step() (and the velocity restore of released
       * nodes in the Newton loop), added to the totals by commit_step(), so
       * that rejected attempts and repeated coupling iterations of a step
       * are not booked.
       */
      double                 step_impact_dissipation = 0.;
      double                 step_reset_dissipation  = 0.;
      dealii::Tensor<1, dim> contact_force;
      unsigned int           frozen_nodes = 0;
      /** Grid kinetic energy and speed at the points of the last commit
       * (negative: no step yet); see Diagnostics. */
      double grid_kinetic_energy = -1.;
      double max_grid_speed      = -1.;
      /**
       * Boundary particles held in stick at the present Newton iterate
       * because their slip direction reversed (the iterate is then not
       * accepted as converged).
       */
      unsigned int reversed_boundary_points = 0;

      dealii::TrilinosWrappers::MPI::Vector nodal_mass; // ghosted
      dealii::TrilinosWrappers::MPI::Vector velocity_n; // ghosted
      /** The projected velocity before the constraints (FLIP). */
      dealii::TrilinosWrappers::MPI::Vector velocity_p2g;     // ghosted
      dealii::TrilinosWrappers::MPI::Vector acceleration_n;   // ghosted
      dealii::TrilinosWrappers::MPI::Vector external_force;   // owned
      dealii::TrilinosWrappers::MPI::Vector residual;         // owned
      dealii::TrilinosWrappers::MPI::Vector increment;        // owned
      dealii::TrilinosWrappers::MPI::Vector displacement;     // ghosted du
      dealii::TrilinosWrappers::MPI::Vector acceleration_new; // ghosted
      /** f_ext - f_int(u_n) at the free nodes with mass (owned), recorded
       * by the step's last solve (record_start_force()). */
      dealii::TrilinosWrappers::MPI::Vector start_force;
      bool                                  start_force_recorded = false;
      /** v_n + dv of the last committed step (ghosted); grid_velocity(). */
      dealii::TrilinosWrappers::MPI::Vector committed_grid_velocity;

      Boundaries::BoundaryParticles<dim> *boundary_particles = nullptr;
      std::vector<BoundaryPoint>          boundary_points;
      /** Cells with boundary particles and a node that carries mass. */
      std::vector<CellCache> boundary_cells;

      dealii::types::global_dof_index n_active;
      bool                            prepared;
      /** Set while initialize_acceleration() prepares its step. */
      bool initializing = false;
      bool solved;
      /** set_warm_start(); the increment of the last converged solve. */
      bool                                  warm_start = false;
      dealii::TrilinosWrappers::MPI::Vector last_increment;
    };
  } // namespace MPM
} // namespace Talus

#endif
