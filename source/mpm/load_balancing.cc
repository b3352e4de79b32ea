#include <talus/base/input.h>
#include <talus/mpm/load_balancing.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    void
    LoadBalancing<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Load balancing");
      {
        prm.declare_entry(
          "repartition every steps",
          "0",
          Patterns::Integer(0),
          "Repartition the background grid between the MPI ranks with the "
          "cell weights below at the start and after every this many "
          "accepted time steps [-]; 0: not by steps. The committed state "
          "(material points, boundary particles, the grid velocity and the "
          "stuck friction nodes) is carried to the new partition; the "
          "run's log reports the imbalance before and after (problems "
          "mpm and coupled).");
        prm.declare_entry(
          "imbalance threshold",
          "0",
          Patterns::Double(0),
          "Repartition at the start and after every step at which the "
          "imbalance of the material points, the largest rank's number of "
          "points over the mean per rank, exceeds this value [-]; 0: not by "
          "imbalance, else a number above 1 (e.g. 1.2). Both criteria may be "
          "set. With one rank the imbalance is always 1. When a "
          "repartition leaves an imbalance A above the threshold (the "
          "weights balance the cost, not the points), the next one by "
          "imbalance waits until it exceeds A + (threshold - 1) / 2.");
        prm.declare_entry(
          "weight per cell",
          "1",
          Patterns::Double(),
          "Cost of a cell of the background grid in the weights of the "
          "partition [-] (relative to the two weights below; must be "
          "positive): the partition balances the sum over a rank's cells of "
          "this plus the weights of the cell's particles.");
        prm.declare_entry(
          "weight per material point",
          "100",
          Patterns::Double(),
          "Cost of a material point in the weights of the partition [-] "
          "(relative to 'weight per cell'; 0 or more): its constitutive "
          "update and assembly, by far the largest part of a step's work "
          "outside the linear solver (an empty cell costs little: its "
          "degrees of freedom are constrained).");
        prm.declare_entry(
          "weight per boundary particle",
          "10",
          Patterns::Double(),
          "Cost of a boundary particle in the weights of the partition [-] "
          "(relative to 'weight per cell'; 0 or more): its contribution "
          "is assembled only in cells with material.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    LoadBalancing<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      const std::string section = "Load balancing";
      prm.enter_subsection(section);
      every_steps = prm.get_integer("repartition every steps");
      threshold   = prm.get_double("imbalance threshold");
      if (threshold != 0. && !(threshold > 1.))
        InputFile::reject(section,
                          "imbalance threshold",
                          prm.get("imbalance threshold"),
                          "0 (no repartition by imbalance) or a number above "
                          "1 is expected: the imbalance is the largest rank's "
                          "number of material points over the mean, never "
                          "below 1");
      cell_cost  = get_positive(prm, section, "weight per cell");
      point_cost = get_non_negative(prm, section, "weight per material point");
      boundary_cost =
        get_non_negative(prm, section, "weight per boundary particle");
      prm.leave_subsection();
    }


    template <int dim>
    bool
    LoadBalancing<dim>::due(const unsigned int step,
                            const double       imbalance) const
    {
      return (every_steps > 0 && step % every_steps == 0) ||
             (threshold > 0. && imbalance > threshold &&
              imbalance >
                imbalance_after_last + std::max(0., 0.5 * (threshold - 1.)));
    }


    template <int dim>
    double
    LoadBalancing<dim>::imbalance(
      const dealii::Particles::ParticleHandler<dim> &points,
      const MPI_Comm                                 communicator)
    {
      const double local   = points.n_locally_owned_particles();
      const double largest = dealii::Utilities::MPI::max(local, communicator);
      const double total   = dealii::Utilities::MPI::sum(local, communicator);
      if (total <= 0.)
        return 1.;
      return largest /
             (total / dealii::Utilities::MPI::n_mpi_processes(communicator));
    }


    template <int dim>
    unsigned int
    LoadBalancing<dim>::cell_weight(
      const typename dealii::parallel::distributed::Triangulation<
        dim>::cell_iterator                                &cell,
      const typename dealii::Triangulation<dim>::CellStatus status,
      const dealii::Particles::ParticleHandler<dim>        &points,
      const dealii::Particles::ParticleHandler<dim> &boundary_particles) const
    {
      // (step-68's cell_weight(): a coarsened cell has its children's
      // particles, a refined one its parent's; the grid of Talus is only
      // repartitioned, every cell persists)
      unsigned int n_points = 0, n_boundary = 0;
      switch (status)
        {
          case dealii::Triangulation<dim>::CELL_PERSIST:
          case dealii::Triangulation<dim>::CELL_REFINE:
            n_points   = points.n_particles_in_cell(cell);
            n_boundary = boundary_particles.n_particles_in_cell(cell);
            break;
          case dealii::Triangulation<dim>::CELL_COARSEN:
            for (const auto &child : cell->child_iterators())
              {
                n_points += points.n_particles_in_cell(child);
                n_boundary += boundary_particles.n_particles_in_cell(child);
              }
            break;
          default:
            break;
        }
      // integers with the cell at 100 (only the ratios matter)
      const double w =
        100. *
        (1. + (point_cost * n_points + boundary_cost * n_boundary) / cell_cost);
      return static_cast<unsigned int>(std::min(
        std::round(w),
        static_cast<double>(std::numeric_limits<unsigned int>::max() / 1024)));
    }


    template class LoadBalancing<2>;
    template class LoadBalancing<3>;
  } // namespace MPM
} // namespace Talus
