#ifndef talus_mpm_load_balancing_h
#define talus_mpm_load_balancing_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <deal.II/distributed/tria.h>

namespace Talus
{
  namespace MPM
  {
    /**
     * Load balancing of the MPM between the MPI ranks (subsection `Load
     * balancing`, issue 39): when to repartition the background grid and
     * with which cell weights.
     *
     * The work of a step grows with the material points of a rank (P2G,
     * the constitutive updates and the assembly), not with its cells: a
     * body that fills a corner of the grid sits on one rank of deal.II's
     * default partition, which balances the cells. The weight of a cell
     * for parallel::distributed::Triangulation::repartition() (its signal
     * `weight`, deal.II 9.4, as in step-68 and ASPECT) is
     *
     *   w = weight per cell + weight per material point * (its points)
     *       + weight per boundary particle * (its boundary particles),
     *
     * scaled to integers (the cell weight becomes 100). The run
     * repartitions between steps (after a commit, never inside a Newton
     * or coupling iteration) every `repartition every steps` steps and
     * whenever the imbalance, the largest rank's number of material points
     * over the mean, exceeds `imbalance threshold`; both are checked at
     * the start as well. MPMProblem::repartition() carries the committed
     * state (CommittedStateTransfer).
     *
     * Off by default. The class does not touch the problem: it decides
     * and weighs.
     */
    template <int dim>
    class LoadBalancing
    {
    public:
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse subsection `Load balancing` and check the values. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Whether the run repartitions at all (by steps or imbalance). */
      bool
      enabled() const
      {
        return every_steps > 0 || threshold > 0.;
      }

      /**
       * Whether to repartition after step @p step (0: the start) at the
       * imbalance @p imbalance (imbalance()): by the schedule, or above
       * the threshold. The weights balance the cost, not the points, and a
       * repartition may leave an imbalance A above the threshold (cells
       * of several points, the weight of the empty cells); the next
       * repartition by imbalance then waits until it exceeds A + (threshold
       * - 1) / 2, instead of repeating the same partition every step.
       */
      bool
      due(const unsigned int step, const double imbalance) const;

      /** Record the imbalance @p after a repartition (for due()). */
      void
      record_repartition(const double after)
      {
        imbalance_after_last = after;
      }

      /**
       * The imbalance of @p points: the largest rank's number of
       * particles over the mean number per rank (1: perfectly balanced,
       * the number of ranks: all on one). 1 when there are none.
       * Collective.
       */
      static double
      imbalance(const dealii::Particles::ParticleHandler<dim> &points,
                const MPI_Comm                                 communicator);

      /**
       * The weight of @p cell with @p status (the signature of the
       * triangulation's signal `weight`) for the material points
       * @p points and the boundary particles @p boundary_particles.
       */
      unsigned int
      cell_weight(const typename dealii::parallel::distributed::Triangulation<
                    dim>::cell_iterator                                &cell,
                  const typename dealii::Triangulation<dim>::CellStatus status,
                  const dealii::Particles::ParticleHandler<dim>        &points,
                  const dealii::Particles::ParticleHandler<dim>
                    &boundary_particles) const;

    private:
      unsigned int every_steps   = 0;
      double       threshold     = 0.;
      double       cell_cost     = 1.;
      double       point_cost    = 100.;
      double       boundary_cost = 10.;
      /** Imbalance after the last repartition (1: none yet). */
      double imbalance_after_last = 1.;
    };
  } // namespace MPM
} // namespace Talus

#endif
