#ifndef talus_mpm_state_transfer_h
#define talus_mpm_state_transfer_h

#include <talus/boundaries/boundary_particles.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/distributed/solution_transfer.h>

#include <memory>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * The committed state of the MPM problem carried through a change of
     * the grid's partition: both particle handlers (material points and
     * boundary particles, with all their properties) and, through
     * parallel::distributed::SolutionTransfer, the grid vectors the solver
     * keeps across steps (MPMSolver::committed_grid_vectors(): the grid
     * velocity of the last commit and the stuck grid friction nodes).
     * Afterwards the degrees of freedom are distributed again and the
     * solver rebuilds everything that depends on the partition
     * (MPMSolver::setup(): sparsity, matrix, vectors, boundary and
     * friction dofs) before it gets the vectors back.
     *
     * Two uses, one sequence (register, change the triangulation, unpack):
     *  - Mode::serialization, the checkpoints
     *    (MPMProblem::save_checkpoint() / load_checkpoint()):
     *    prepare() before Triangulation::save(); unpack() after
     *    Triangulation::load() on any number of ranks (there with a
     *    transfer object of its own, built on the loaded grid);
     *  - Mode::repartition, the load balancing (MPMProblem::repartition()):
     *    prepare(), parallel::distributed::Triangulation::repartition(),
     *    unpack() with the same object.
     *
     * Only a committed state may be carried (between steps, after
     * MPMSolver::commit_step() or the initial acceleration).
     */
    template <int dim>
    class CommittedStateTransfer
    {
    public:
      enum class Mode
      {
        serialization,
        repartition
      };

      CommittedStateTransfer(BackgroundGrid<dim>                &grid,
                             MaterialPoints<dim>                &points,
                             Boundaries::BoundaryParticles<dim> &boundaries,
                             MPMSolver<dim>                     &solver,
                             const Mode                          mode);

      /**
       * Register the particles of both handlers and the committed grid
       * vectors with the triangulation (in this order, which is the order
       * in which unpack() reads them). Collective.
       */
      void
      prepare();

      /**
       * After the triangulation was loaded or repartitioned: distribute
       * the degrees of freedom, unpack both particle handlers and the
       * grid vectors, set up the solver on the new partition and hand it
       * the vectors. Collective.
       */
      void
      unpack();

    private:
      BackgroundGrid<dim>                &grid;
      MaterialPoints<dim>                &points;
      Boundaries::BoundaryParticles<dim> &boundaries;
      MPMSolver<dim>                     &solver;
      const Mode                          mode;

      /** The vectors registered by prepare(): they must live until used. */
      std::vector<dealii::TrilinosWrappers::MPI::Vector> vectors;
      std::unique_ptr<dealii::parallel::distributed::SolutionTransfer<
        dim,
        dealii::TrilinosWrappers::MPI::Vector>>
        transfer;
    };
  } // namespace MPM
} // namespace Talus

#endif
