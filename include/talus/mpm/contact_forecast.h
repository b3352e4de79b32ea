#ifndef talus_mpm_contact_forecast_h
#define talus_mpm_contact_forecast_h

#include <talus/base/contact_onset.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/boundaries/material_behind_boundaries.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <functional>
#include <utility>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * When the material points will first touch a boundary they do not
     * touch yet: the forecast behind the contact onset event
     * (ContactOnsetEvent, 'contact onset forecast'), so that a step is
     * shortened before an impact instead of being rejected after it.
     *
     * For every material point p in front of boundary b (signed depth
     * d_b(x_p) < 0 behind its surface, MaterialBehindBoundaries), the gap
     * is the distance of the surface to the point's extent, s = -d - r_p
     * with r_p = (V_p^(1/dim))/2 the half width of its current volume, and
     * the point approaches with the speed v_a = v_p . m and the
     * acceleration a_a = g . m along the direction m = grad d_b into the
     * boundary (gravity g alone: the other forces on the point are not
     * known before the step). Its arrival time is the smallest t > 0 with
     *
     *   s = v_a t + a_a t^2 / 2,   t = 2 s / (v_a + sqrt(v_a^2 + 2 a_a s)),
     *
     * infinite where the point never arrives (v_a + sqrt(...) <= 0 or a
     * negative discriminant). The forecast of boundary b is the earliest
     * arrival over the points; none (infinity) once the extent of any
     * point overlaps the surface (s <= 0): then the contact has begun (or
     * a body rests on an initial overlap), and later contacts on the same
     * surface are the event's check after the step. The forecast keeps no
     * state: a resumed run forecasts as the uninterrupted one.
     *
     * On the boundary particles' side ('contact side = boundary
     * particles') the reaction begins when material reaches the cells of
     * the boundary particles: a particle's cell takes part as soon as one
     * of its nodes carries mass, which with linear shape functions is
     * when a point enters one of the cells around that node. The halo of
     * a boundary is therefore the union of its particles' cells, each
     * widened by its own width on every side (the 3^dim cells around it
     * on a uniform grid; on an adaptive grid a coarser neighbour reaches
     * further, and the forecast is then late, which the event's check
     * after the step catches). A point's arrival is the first t in which
     * its path x + v t + g t^2 / 2 enters a halo box (box_entry_time()),
     * searched among the boxes its path crosses within the planned step;
     * none once a point lies in the halo. The step is made to end a
     * thousandth of the arrival time after the entry, so that the next
     * step starts with the point in the halo (the reaction begins in it)
     * and is the onset step (ContactOnsetEvent::forecast() with
     * onset_in_next_step). With the other shape functions (uGIMP,
     * cpGIMP, CPDI) a point gives mass to a node as soon as its domain
     * overlaps the node's support: the point enters the halo when the
     * box of its domain does, i.e. its path enters the halo box widened
     * by the domain's half-extent l_p (MPMSolver::
     * point_domain_half_extent(), from the committed F). For CPDI's
     * parallelepiped this bounding box is reached at most a corner's
     * way before the domain itself (a forecast slightly early, never
     * late).
     *
     * The depth of a fixed plane, line, box or circle is its analytic
     * signed distance (m by central differences); the other boundaries
     * (moving, coupled, 'mesh', 'external') are taken at the tangent plane
     * of the boundary particle nearest to the point, at rest, where the
     * point lies within one cell of it along the surface. A surface that
     * moves towards the material (the barrier's net swinging back) is
     * therefore seen late; the event's check after the step still
     * catches it.
     */
    template <int dim>
    class ContactForecast
    {
    public:
      /**
       * The half-extent per direction [m] of a point's domain, given its
       * committed deformation gradient (zero with linear shape
       * functions).
       */
      using PointHalfExtent =
        std::function<dealii::Tensor<1, dim>(const dealii::Tensor<2, dim> &)>;

      /**
       * The forecast for the boundaries of @p boundaries, whose analytic
       * depths @p behind gives; @p cell_size is the smallest cell of the
       * background grid; @p point_half_extent the reach of a point's
       * domain for the boundaries checked on the boundary particles' side
       * (MPMSolver::point_domain_half_extent()).
       */
      ContactForecast(const Boundaries::BoundaryParticles<dim> &boundaries,
                      const Boundaries::MaterialBehindBoundaries<dim> &behind,
                      const double    cell_size,
                      PointHalfExtent point_half_extent);

      /**
       * The earliest arrival time [s] of the points of @p points at each
       * boundary b with @p watched[b] (infinity where none arrives, where a
       * point already touches it and for the boundaries not watched). The
       * points carry their velocity, initial volume and deformation gradient at
       * the property indices of MaterialPointProperties. The boundaries
       * checked on the boundary particles' side are searched within
       * @p horizon [s] only (the planned step). Collective.
       */
      std::vector<double>
      arrival_times(const dealii::Particles::ParticleHandler<dim> &points,
                    const std::vector<bool>                       &watched,
                    const dealii::Tensor<1, dim>                  &gravity,
                    const double                                   horizon,
                    const MPI_Comm communicator) const;

      /**
       * Before a step: when @p event forecasts (ContactOnsetEvent::
       * forecasting()), all boundaries are watched, and the
       * planned step of @p time_control is shortened ahead of the earliest
       * arrival (ContactOnsetEvent::forecast()). Returns whether it was.
       * Collective.
       */
      bool
      shorten_ahead(ContactOnsetEvent                             &event,
                    TimeControl                                   &time_control,
                    const dealii::Particles::ParticleHandler<dim> &points,
                    const dealii::Tensor<1, dim>                  &gravity,
                    const MPI_Comm communicator) const;

      /**
       * The smallest t > 0 with @p gap = @p speed t + @p acceleration t^2 /
       * 2 (infinity if there is none; 0 for a gap <= 0).
       */
      static double
      arrival_time(const double gap,
                   const double speed,
                   const double acceleration);

      /**
       * The first t in [0, @p horizon] at which x(t) = @p x + @p v t +
       * @p a t^2 / 2 lies in @p box (infinity if none): the smallest of 0
       * and the roots of x_d(t) = lower and upper corner of the box in
       * each direction d at which x(t) lies in the box.
       */
      static double
      box_entry_time(const dealii::Point<dim>       &x,
                     const dealii::Tensor<1, dim>   &v,
                     const dealii::Tensor<1, dim>   &a,
                     const dealii::BoundingBox<dim> &box,
                     const double                    horizon);

    private:
      /**
       * The halo boxes of the boundary particles of every boundary b with
       * @p sides[b] (their cells widened by their own width; all ranks'),
       * as pairs (box, b). Collective.
       */
      std::vector<std::pair<dealii::BoundingBox<dim>, unsigned int>>
      halo_boxes(const std::vector<bool> &sides,
                 const MPI_Comm           communicator) const;

      const Boundaries::BoundaryParticles<dim>        &boundaries;
      const Boundaries::MaterialBehindBoundaries<dim> &behind;
      const double                                     cell_size;
      const PointHalfExtent                            point_half_extent;
    };
  } // namespace MPM
} // namespace Talus

#endif
