#ifndef talus_coupling_gauss_seidel_coupling_h
#define talus_coupling_gauss_seidel_coupling_h

#include <talus/coupling/accelerators.h>
#include <talus/coupling/coupling_parameters.h>
#include <talus/coupling/structure_interface.h>
#include <talus/mpm/mpm_problem.h>
#include <talus/structure/structure_problem.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace Coupling
  {
    /** Outcome of one coupled step (GaussSeidelCoupling::solve_step()). */
    template <int dim>
    struct CoupledStepResult
    {
      /** The interface converged (strong) or the one pass was made (weak),
       * and both solvers converged in every iteration. */
      bool converged = false;
      /** Evaluations of the fixed point: solves of both fields. */
      unsigned int iterations = 0;
      /** The last iteration's convergence test and what the accelerator did
       * before it. */
      ConvergenceStatus status;
      /** Relaxation factor of the last accelerated iteration (0: a
       * quasi-Newton step or none). */
      double relaxation = 0.;
      /** Newton iterations summed over the coupling iterations. */
      unsigned int mpm_newton = 0, structure_newton = 0;
      /** Safeguarded restarts of the accelerator (iterate_window()). */
      unsigned int restarts = 0;
      /** Restarts of the accelerator at a change of the active set
       * (CouplingParameters::restart_at_contact_change). */
      unsigned int contact_restarts = 0;
      /** The MPM's result of the last iteration (the accepted one). */
      MPM::NewtonResult mpm;
      /** Sum of the interface forces on the structure [N]. */
      dealii::Tensor<1, dim> interface_force;
      /** Interface work of the structure's vectors U . F and of the points
       * sum u_p . f_p at the accepted iterate [J] (equal to round-off). */
      double work_structure = 0., work_points = 0.;
      /**
       * Work of the interface force on the structure in the step [J]: with
       * its end value F_{n+1} . du ('interface force in time = end of
       * step'), else (F_n + F_{n+1})/2 . du, the work that the structure's
       * Newmark scheme sees (du: the structure's increment).
       */
      double interface_work = 0.;
      /** Why the step failed (empty if it converged). */
      std::string failure;
    };


    /**
     * The partitioned coupling of the MPM and the barrier structure
     * (founding paper, section 4): Dirichlet-Neumann Gauss-Seidel per time
     * step, the structure's displacement imposed on the MPM's boundary
     * particles of the interface, the MPM's reactions sent back to the
     * structure as nodal forces, iterated with convergence acceleration
     * until the interface is in equilibrium (doc/coupling.md).
     *
     * One coupled step from t to t + dt:
     * @code
     * x = predictor(t + dt)               (structure first: x = S(F_n))
     * repeat                              (iterate_window())
     *   MPM:       u_bar(t..t+dt) = U_n .. x on the interface particles,
     *              prepare_step, solve_step  -> reactions f_p
     *   transfer:  F = sum_p N(X_p) f_p, MPI-summed
     *   structure: prepare_step, solve_step with F  -> x̃
     *   converged? else x = accelerator(x, x̃)
     * @endcode
     * Neither field commits inside the iteration (their solve_step() is
     * repeatable); commit_step() commits both, so a step that does not
     * converge (the interface, or either Newton) is rejected on both sides
     * by not committing it: the caller halves dt and calls solve_step()
     * again. Both fields always take the same dt.
     *
     * The structure is dynamic (Bossak-Newmark over dt) or static (the
     * equilibrium under its full loads, load factor 1, and the interface
     * forces at every step: a massless barrier).
     */
    template <int dim>
    class GaussSeidelCoupling
    {
    public:
      GaussSeidelCoupling(MPM::MPMProblem<dim>        &mpm,
                          Structure::StructureProblem &structure,
                          StructureInterface<dim>     &interface,
                          const CouplingParameters    &parameters,
                          dealii::TimerOutput         &timer,
                          const MPI_Comm               communicator);

      /**
       * The initial state at time @p t0: the interface at the structure's
       * committed displacement (the boundary particles are moved there),
       * the MPM's initial accelerations, the predictor's first value.
       */
      void
      initialize(const double t0);

      /** Iterate the step from @p t to @p t + @p dt; commits nothing. */
      CoupledStepResult<dim>
      solve_step(const double t, const double dt);

      /** Commit both fields (the last solve_step() must have converged). */
      void
      commit_step();

      /** Forget what the accelerator learned (after a rejected step: the
       * repeated step is shorter). */
      void
      reject_step();

      /**
       * Keep a copy of the committed state of both fields and the coupling
       * (MPM::MPMProblem::save_state(), Structure::StructureProblem::
       * save_state(), the committed interface displacement and force, the
       * predictor's windows), before a commit_step() that may be undone
       * (a step rejected for its energy jump, EnergyJumpMonitor).
       */
      void
      save_state();

      /**
       * Undo the commit_step() after the last save_state(): both fields
       * and the coupling are back at the state committed at time @p t,
       * the interface at its committed displacement, and the accelerator's
       * history is dropped as for a rejected step (reject_step()).
       */
      void
      restore_state(const double t);

      /** The interface force of the last solve_step() (structure DoFs). */
      const dealii::Vector<double> &
      interface_forces() const
      {
        return force;
      }

      const InterfaceAccelerator &
      accelerator() const
      {
        return *acceleration;
      }

      /**
       * Write the committed state of the coupled problem into the
       * checkpoint directory @p directory (collective; doc/checkpoint.md):
       * the MPM's files (MPM::MPMProblem::save_checkpoint()), then on rank
       * 0 the archive `structure_state` (what identifies the structure:
       * @p model, its DoFs, dynamic or static, its line meshes; then its
       * committed state, Structure::StructureProblem::
       * save_committed_state()) and the archive `coupling_state` (the
       * committed interface displacement and forces, the predictor's
       * windows, the convergence criterion's last force and the
       * accelerator's history: Aitken's factor, the IQN-ILS columns of the
       * reused windows, the IQN-IMVJ inverse Jacobian).
       */
      void
      save_checkpoint(const std::string &directory,
                      const std::string &model) const;

      /**
       * Replace initialize(): the committed state of the checkpoint
       * @p directory (written by save_checkpoint() with any number of
       * ranks) becomes that of both fields and of the coupling, and the
       * interface is set up again for the boundary particles loaded.
       * Throws ExcInvalidInput naming the checkpoint, the file and what is
       * wrong if it does not belong to this problem (another MPM, another
       * structure model or number of DoFs, another accelerator).
       * Collective.
       */
      void
      load_checkpoint(const std::string &directory, const std::string &model);

    private:
      MPM::MPMProblem<dim>        &mpm;
      Structure::StructureProblem &structure;
      StructureInterface<dim>     &interface;
      const CouplingParameters    &parameters;
      dealii::TimerOutput         &timer;
      MPI_Comm                     communicator;

      std::unique_ptr<InterfaceAccelerator> acceleration;
      ConvergenceCriterion                  criterion;
      InterfacePredictor                    predictor;

      /** The structure's committed displacement (start of the step). */
      dealii::Vector<double> committed;
      /** Interface force of the last iteration and of the last committed
       * step (structure DoFs) [N]. */
      dealii::Vector<double> force, committed_force;
      double                 step_end = 0.;

      /** The copy of save_state(). */
      dealii::Vector<double> saved_committed, saved_committed_force;
      InterfacePredictor     saved_predictor;

      /** k_R of the Robin springs for the step @p dt [Pa/m]
       * (CouplingParameters::robin_stiffness). */
      double
      robin_stiffness(const double dt) const;

      /** Whether the Robin springs act along the reactions only
       * (CouplingParameters::robin_directions). */
      bool
      normal_springs() const;

      /**
       * 'initial Jacobian = interface stiffness': after the window's first
       * evaluation of H (MPM and structure solved at x_0, Robin springs
       * @p springs), the Jacobian of H, A = C (k - K_D) with the
       * structure's compliance C = (K_S + k)^-1 (its last tangent) and the
       * MPM's interface stiffness K_D = -dF/dx (one back-substitution per
       * interface DoF), kept as U = A restricted to the columns S of the
       * interface DoFs it acts on (n x m) and M = (I - U_S)^-1 (m x m);
       * then J0 = A (A - I)^-1 = -U M P_S^T (Woodbury), and x~ - J0 r is
       * the Newton step of the linearised interface equilibrium. Returns
       * false if the MPM transmits no force (no J0).
       */
      bool
      compute_interface_jacobian(const dealii::Vector<double> &springs);

      /** J0 v (after compute_interface_jacobian()). */
      void
      apply_initial_jacobian(const dealii::Vector<double> &v,
                             dealii::Vector<double>       &result) const;

      std::vector<dealii::types::global_dof_index> jacobian_dofs;
      dealii::FullMatrix<double>                   jacobian_U, jacobian_M;

      /** The structure's step from @p t to @p t + @p dt with @p F; adds
       * its Newton iterations (returned) to @p result, throws when it
       * does not converge. */
      unsigned int
      solve_structure(const double                  t,
                      const double                  dt,
                      const dealii::Vector<double> &F,
                      CoupledStepResult<dim>       &result);
    };
  } // namespace Coupling
} // namespace Talus

#endif
