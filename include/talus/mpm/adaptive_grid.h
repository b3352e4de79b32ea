#ifndef talus_mpm_adaptive_grid_h
#define talus_mpm_adaptive_grid_h

#include <talus/mpm/background_grid.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * Adaptive refinement of the MPM background grid (subsection `Adaptive
     * grid`, issue 39): the grid is fine where the material is and coarse
     * where it is not.
     *
     * Levels count from the grid of subsection `Background grid` (after
     * the global refinement of a convergence study). The run starts on the
     * grid refined uniformly to the maximum level, where the material
     * points are generated (the same points as the uniform run at that
     * level), and coarsens the empty cells down to the minimum level
     * before the first step. Afterwards, every `refine every steps`
     * accepted steps, one pass of the criterion
     *
     *  - a cell is *occupied* if it holds a material point, or, with
     *    `refine at boundary particles` (the default), a boundary particle
     *    (terrain, walls, the coupled interface: subsection Boundary
     *    particles), so that the contact forces act on the finest cells;
     *  - a cell is *near* the material if it shares a vertex with an
     *    occupied cell, or, with `neighbour layers` n > 1, with a cell
     *    near the material at layer n - 1 (n = 0: occupied cells only);
     *  - with `refine at boundaries` (a list of grid boundary ids), a
     *    cell that touches a face of one of them is near the material
     *    also if it is within `neighbour layers` + 1 more layers of a
     *    near cell, counted through the cells that touch those faces:
     *    along a wall or floor the fine band reaches 2 n + 1 cells
     *    beyond the material (n = `neighbour layers`), so that material
     *    that slides along it meets fine cells there;
     *  - near cells below the maximum level are refined, cells below the
     *    minimum level are refined, all other cells above the minimum
     *    level are coarsened (p4est coarsens a parent only if all its
     *    children are flagged and keeps the 2:1 balance across faces);
     *
     * flags the cells; MPMProblem::adapt_grid() then carries the committed
     * state (points with all properties, grid vectors) to the new grid,
     * like a repartition. One pass changes a cell by one level; a point
     * never reaches a coarse cell if it moves less than `neighbour layers`
     * fine cells between two passes.
     *
     * On the locally refined grid the MPM system uses the hanging-node
     * constraints (MPMSolver::hanging_node_constraints()). Off by default.
     */
    template <int dim>
    class AdaptiveGrid
    {
    public:
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse subsection "Adaptive grid". */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      bool
      enabled() const
      {
        return enable;
      }

      /** Levels of refinement of the initial grid beyond the background
       * grid (the maximum level); 0 when disabled. */
      unsigned int
      initial_refinement() const
      {
        return enable ? max_level : 0;
      }

      /** Passes that bring the initial (uniform) grid to its final state. */
      unsigned int
      initial_passes() const
      {
        return enable ? max_level - min_level + 1 : 0;
      }

      /** Whether a pass is due after accepted step @p step. */
      bool
      due(const unsigned int step) const
      {
        return enable && every > 0 && step > 0 && step % every == 0;
      }

      /**
       * Set the refine and coarsen flags of the criterion (class
       * documentation) on the locally owned cells, with the levels offset
       * by @p base_level (the global refinement of the background grid),
       * and let the triangulation prepare them. Returns whether any rank's
       * grid changes. Collective.
       */
      bool
      flag_cells(BackgroundGrid<dim>                           &grid,
                 const dealii::Particles::ParticleHandler<dim> &points,
                 const dealii::Particles::ParticleHandler<dim> &boundary,
                 const unsigned int base_level) const;

      /**
       * The active cells that hold boundary particles of @p boundary, and
       * how many of them are at the maximum level (offset by @p
       * base_level), over all ranks. Collective.
       */
      std::pair<unsigned int, unsigned int>
      boundary_cells_at_maximum_level(
        const BackgroundGrid<dim>                     &grid,
        const dealii::Particles::ParticleHandler<dim> &boundary,
        const unsigned int                             base_level) const;

      /**
       * The active cells that touch a face of a boundary of `refine at
       * boundaries` and are near the material (class documentation), and
       * how many of them are at the maximum level (offset by @p
       * base_level), over all ranks. Collective.
       */
      std::pair<unsigned int, unsigned int>
      boundary_face_cells_at_maximum_level(
        const BackgroundGrid<dim>                     &grid,
        const dealii::Particles::ParticleHandler<dim> &points,
        const dealii::Particles::ParticleHandler<dim> &boundary,
        const unsigned int                             base_level) const;

      /**
       * Reject (ExcInvalidInput naming `refine at boundaries`) a boundary
       * id that no face of @p grid carries. Collective.
       */
      void
      check_refined_boundaries(const BackgroundGrid<dim> &grid) const;

      /** The grid boundary ids of `refine at boundaries` (sorted). */
      const std::vector<dealii::types::boundary_id> &
      refined_boundaries() const
      {
        return refine_boundaries;
      }

      /** `neighbour layers`. */
      unsigned int
      neighbour_layers() const
      {
        return layers;
      }

      /** `refine every steps`. */
      unsigned int
      refine_every() const
      {
        return every;
      }

      /** The maximum level (counted from the background grid). */
      unsigned int
      maximum_level() const
      {
        return max_level;
      }

    private:
      /** Whether each active cell (by active cell index) is near the
       * material (class documentation); owned cells only. Collective. */
      std::vector<bool>
      near_cells(const BackgroundGrid<dim>                     &grid,
                 const dealii::Particles::ParticleHandler<dim> &points,
                 const dealii::Particles::ParticleHandler<dim> &boundary) const;

      /** `refine at boundaries`. */
      std::vector<dealii::types::boundary_id> refine_boundaries;

      bool         enable                       = false;
      unsigned int min_level                    = 0;
      unsigned int max_level                    = 0;
      unsigned int every                        = 1;
      unsigned int layers                       = 1;
      bool         refine_at_boundary_particles = true;
    };
  } // namespace MPM
} // namespace Talus

#endif
