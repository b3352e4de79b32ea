#ifndef talus_boundaries_material_behind_boundaries_h
#define talus_boundaries_material_behind_boundaries_h

#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/numerics/rtree.h>

#include <deal.II/particles/particle_handler.h>

#include <string>
#include <vector>

namespace Talus
{
  namespace Boundaries
  {
    /**
     * Material that has crossed a rigid boundary: the material points whose
     * centre lies behind the surface of a boundary of BoundaryParticles.
     *
     * The boundary-particle methods (penalty, Nitsche, Lagrange
     * multipliers; Singer et al., the founding paper, section 3) impose the
     * condition on the grid's velocity at the boundary particles, not on
     * the material points. A point whose centre crosses the surface (by the
     * compliance of a penalty, in a corner where two boundaries squeeze
     * the material, or where the surface lies on faces of the grid so that
     * the cells behind it carry no boundary particle) is no longer held by
     * it: it sinks through the cells behind the surface and may leave the
     * grid. The penetration the boundary particles report, max(-g . n) of
     * their gaps, does not see it. This survey does: per boundary, the
     * number and mass of the points at x_p with depth d(x_p) > 0 and the
     * largest depth, with d the signed distance behind the undisplaced
     * surface,
     * - plane (3D): d = -(x - p0) . n on the parallelogram p0, p1, p2
     *   (points whose projection lies outside it are not behind it);
     * - line (2D): the same on the nearest segment of the polyline;
     * - box and circle: the distance into the side without material;
     * - moving boundaries (a displacement function or the coupling's
     *   surface, e.g. the net) and 'mesh' and 'external' surfaces: by their
     *   boundary particles at their current positions, d = -(x - x_b) . n_b
     *   with x_b and n_b the position and normal of the particle nearest to
     *   x, counted only where x lies within one cell of x_b along the
     *   surface (a point beyond the surface's edge, e.g. over the top of
     *   the net, is not behind it).
     */
    template <int dim>
    class MaterialBehindBoundaries
    {
    public:
      /** What lies behind one boundary. */
      struct Survey
      {
        unsigned int n_points      = 0;
        double       mass          = 0.; ///< [kg] (per unit thickness in 2D)
        double       largest_depth = 0.; ///< [m]
      };

      /**
       * Survey the boundaries of @p boundaries on @p grid, whose smallest
       * cell sets the depth steps at which a growing penetration is
       * reported again.
       */
      MaterialBehindBoundaries(const BoundaryParticles<dim>   &boundaries,
                               const MPM::BackgroundGrid<dim> &grid);

      /**
       * Whether the surface of boundary @p b lies on faces of the
       * (Cartesian) grid: a plane or line normal to a coordinate axis at a
       * multiple of the finest cell extent from the grid's corner. A point
       * that crosses such a surface at once leaves the cells of its
       * boundary particles; the warnings then say so.
       */
      bool
      on_grid_faces(const unsigned int b) const;

      /**
       * Whether boundary @p b is surveyed by its analytic geometry (a fixed
       * plane, line, box or circle); the others are surveyed by their
       * boundary particles (see the class documentation).
       */
      bool
      analytic(const unsigned int b) const;

      /**
       * Signed distance of @p x behind the undisplaced surface of boundary
       * @p b [m] for the analytic geometries (fixed plane, line, box,
       * circle): positive behind it, negative in front of it or beside a
       * finite plane or segment; -infinity for the boundaries surveyed by
       * their particles.
       */
      double
      depth(const unsigned int b, const dealii::Point<dim> &x) const;

      /**
       * For a boundary surveyed by its particles (not analytic()): calls
       * @p f(point, d, n_b) for every point of @p points that lies within
       * one cell of the nearest particle of boundary @p b along the
       * surface, with d = -(x - x_b) . n_b its depth behind that
       * particle's tangent plane (x_b, n_b its current position and
       * normal; every rank gathers the whole surface). Collective.
       */
      template <class Function>
      void
      for_points_near_particles(
        const unsigned int                             b,
        const dealii::Particles::ParticleHandler<dim> &points,
        const Function                                &f) const
      {
        const auto  surface = boundaries.gather_surface(b);
        const auto &x_b     = surface.x;
        const auto &n_b     = surface.n;
        if (x_b.empty())
          return;
        const auto tree = dealii::pack_rtree_of_indices(x_b);
        for (const auto &p : points)
          {
            const auto                x = p.get_location();
            std::vector<unsigned int> nearest;
            tree.query(boost::geometry::index::nearest(x, 1),
                       std::back_inserter(nearest));
            const unsigned int           j            = nearest[0];
            const dealii::Tensor<1, dim> r            = x - x_b[j];
            const double                 along_normal = r * n_b[j];
            if ((r - along_normal * n_b[j]).norm() <= cell_size)
              f(p, -along_normal, n_b[j]);
          }
      }

      /**
       * The points of @p points behind each boundary, with their mass in
       * property @p mass_index (all ranks; collective).
       */
      std::vector<Survey>
      survey(const dealii::Particles::ParticleHandler<dim> &points,
             const unsigned int                             mass_index,
             const MPI_Comm                                 communicator) const;

      /**
       * The warnings of a step at time @p time for the survey @p s: one line
       * per boundary when material first lies behind it and again each time
       * the number of points doubles or the largest depth grows by a
       * quarter of a cell (empty when there is nothing new). Keeps the
       * largest values for summary().
       */
      std::string
      assess(const std::vector<Survey> &s, const double time);

      /**
       * One line per boundary that ever had material behind it: the most
       * points, their mass and the largest depth over the run (empty if
       * none).
       */
      std::string
      summary() const;

    private:
      const BoundaryParticles<dim> &boundaries;
      const double                  cell_size;
      std::vector<bool>             on_faces;
      /** Per boundary: the largest survey so far and at the last warning. */
      std::vector<Survey> largest, reported;
      std::vector<double> time_of_largest;
    };
  } // namespace Boundaries
} // namespace Talus

#endif
