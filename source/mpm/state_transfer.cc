#include <talus/mpm/state_transfer.h>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    CommittedStateTransfer<dim>::CommittedStateTransfer(
      BackgroundGrid<dim>                &grid,
      MaterialPoints<dim>                &points,
      Boundaries::BoundaryParticles<dim> &boundaries,
      MPMSolver<dim>                     &solver,
      const Mode                          mode)
      : grid(grid)
      , points(points)
      , boundaries(boundaries)
      , solver(solver)
      , mode(mode)
    {}


    template <int dim>
    void
    CommittedStateTransfer<dim>::prepare()
    {
      vectors = solver.committed_grid_vectors();
      std::vector<const dealii::TrilinosWrappers::MPI::Vector *> pointers;
      for (const auto &v : vectors)
        pointers.push_back(&v);
      transfer =
        std::make_unique<dealii::parallel::distributed::SolutionTransfer<
          dim,
          dealii::TrilinosWrappers::MPI::Vector>>(grid.dof_handler);
      // the order of registration is the order of unpacking
      if (mode == Mode::serialization)
        {
          points.particle_handler().prepare_for_serialization();
          boundaries.particle_handler().prepare_for_serialization();
          transfer->prepare_for_serialization(pointers);
        }
      else
        {
          points.particle_handler().prepare_for_coarsening_and_refinement();
          boundaries.particle_handler().prepare_for_coarsening_and_refinement();
          transfer->prepare_for_coarsening_and_refinement(pointers);
        }
    }


    template <int dim>
    void
    CommittedStateTransfer<dim>::unpack()
    {
      grid.setup_dofs();
      std::vector<dealii::TrilinosWrappers::MPI::Vector>   owned(2);
      std::vector<dealii::TrilinosWrappers::MPI::Vector *> pointers;
      for (auto &v : owned)
        {
          v.reinit(grid.locally_owned_dofs, grid.mpi_communicator);
          pointers.push_back(&v);
        }
      if (mode == Mode::serialization)
        {
          points.particle_handler().deserialize();
          boundaries.particle_handler().deserialize();
          // a loaded triangulation: a transfer object on the new grid
          transfer =
            std::make_unique<dealii::parallel::distributed::SolutionTransfer<
              dim,
              dealii::TrilinosWrappers::MPI::Vector>>(grid.dof_handler);
          transfer->deserialize(pointers);
        }
      else
        {
          Assert(transfer, dealii::ExcMessage("prepare() first"));
          points.particle_handler().unpack_after_coarsening_and_refinement();
          boundaries.particle_handler()
            .unpack_after_coarsening_and_refinement();
          transfer->interpolate(pointers);
        }
      transfer.reset();
      vectors.clear();

      // Everything that depends on the partition of the grid.
      solver.setup();
      std::vector<dealii::TrilinosWrappers::MPI::Vector> ghosted(2);
      for (unsigned int i = 0; i < 2; ++i)
        {
          // (a locally refined grid: the hanging nodes from their masters)
          solver.hanging_node_constraints().distribute(owned[i]);
          ghosted[i].reinit(grid.locally_owned_dofs,
                            grid.locally_relevant_dofs,
                            grid.mpi_communicator);
          ghosted[i] = owned[i];
        }
      solver.set_committed_grid_vectors(ghosted);
    }


    template class CommittedStateTransfer<2>;
    template class CommittedStateTransfer<3>;
  } // namespace MPM
} // namespace Talus
