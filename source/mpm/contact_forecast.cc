#include <talus/mpm/contact_forecast.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/point_tensors.h>

#include <deal.II/numerics/rtree.h>

#include <deal.II/boost_adaptors/bounding_box.h>
#include <deal.II/boost_adaptors/point.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    ContactForecast<dim>::ContactForecast(
      const Boundaries::BoundaryParticles<dim>        &boundaries,
      const Boundaries::MaterialBehindBoundaries<dim> &behind,
      const double                                     cell_size,
      PointHalfExtent                                  point_half_extent)
      : boundaries(boundaries)
      , behind(behind)
      , cell_size(cell_size)
      , point_half_extent(std::move(point_half_extent))
    {}


    template <int dim>
    double
    ContactForecast<dim>::arrival_time(const double gap,
                                       const double speed,
                                       const double acceleration)
    {
      constexpr double never = std::numeric_limits<double>::infinity();
      if (!(gap > 0.))
        return 0.;
      const double discriminant = speed * speed + 2. * acceleration * gap;
      if (discriminant < 0.)
        return never;
      // the smaller positive root of a t^2 / 2 + v t - s = 0, without
      // cancellation
      const double denominator = speed + std::sqrt(discriminant);
      return denominator > 0. ? 2. * gap / denominator : never;
    }


    template <int dim>
    double
    ContactForecast<dim>::box_entry_time(const dealii::Point<dim>       &x,
                                         const dealii::Tensor<1, dim>   &v,
                                         const dealii::Tensor<1, dim>   &a,
                                         const dealii::BoundingBox<dim> &box,
                                         const double horizon)
    {
      const auto &[lower, upper] = box.get_boundary_points();
      // inside up to round-off of the box's size
      const double tolerance = 1e-12 * (upper - lower).norm();
      const auto   inside    = [&](const double t) {
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double y = x[d] + v[d] * t + 0.5 * a[d] * t * t;
            if (y < lower[d] - tolerance || y > upper[d] + tolerance)
              return false;
          }
        return true;
      };
      // 0 and the roots of x_d(t) = c in (0, horizon]
      std::vector<double> candidates = {0.};
      const auto          add        = [&](const double t) {
        if (t > 0. && t <= horizon)
          candidates.push_back(t);
      };
      for (unsigned int d = 0; d < dim; ++d)
        for (const double c : {lower[d], upper[d]})
          {
            // a t^2 / 2 + v t + (x - c) = 0
            const double s = c - x[d];
            if (a[d] == 0.)
              {
                if (v[d] != 0.)
                  add(s / v[d]);
                continue;
              }
            const double discriminant = v[d] * v[d] + 2. * a[d] * s;
            if (discriminant < 0.)
              continue;
            // both roots without cancellation: q = -(v + sign(v) sqrt(D)),
            // t_1 = q / a, t_2 = -2 s / q
            const double root = std::sqrt(discriminant);
            const double q    = -(v[d] + (v[d] >= 0. ? root : -root));
            add(q / a[d]);
            if (q != 0.)
              add(-2. * s / q);
          }
      std::sort(candidates.begin(), candidates.end());
      for (const double t : candidates)
        if (inside(t))
          return t;
      return std::numeric_limits<double>::infinity();
    }


    template <int dim>
    std::vector<std::pair<dealii::BoundingBox<dim>, unsigned int>>
    ContactForecast<dim>::halo_boxes(const std::vector<bool> &sides,
                                     const MPI_Comm communicator) const
    {
      using BP = Boundaries::BoundaryParticleProperties<dim>;
      // the cells of the local particles of each boundary (once each)
      std::set<std::pair<unsigned int, dealii::CellId>> seen;
      // lower corner, upper corner, boundary
      std::vector<std::array<double, 2 * dim + 1>> local;
      const auto &handler = boundaries.particle_handler();
      for (const auto &p : handler)
        {
          const unsigned int b =
            static_cast<unsigned int>(p.get_properties()[BP::boundary]);
          if (b >= sides.size() || !sides[b])
            continue;
          const auto cell = p.get_surrounding_cell();
          if (!seen.emplace(b, cell->id()).second)
            continue;
          const auto box             = cell->bounding_box();
          const auto &[lower, upper] = box.get_boundary_points();
          std::array<double, 2 * dim + 1> entry;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double width = upper[d] - lower[d];
              entry[d]           = lower[d] - width;
              entry[dim + d]     = upper[d] + width;
            }
          entry[2 * dim] = b;
          local.push_back(entry);
        }
      std::vector<std::pair<dealii::BoundingBox<dim>, unsigned int>> boxes;
      for (const auto &from_rank :
           dealii::Utilities::MPI::all_gather(communicator, local))
        for (const auto &entry : from_rank)
          {
            dealii::Point<dim> lower, upper;
            for (unsigned int d = 0; d < dim; ++d)
              {
                lower[d] = entry[d];
                upper[d] = entry[dim + d];
              }
            boxes.emplace_back(dealii::BoundingBox<dim>({lower, upper}),
                               static_cast<unsigned int>(entry[2 * dim]));
          }
      return boxes;
    }


    template <int dim>
    std::vector<double>
    ContactForecast<dim>::arrival_times(
      const dealii::Particles::ParticleHandler<dim> &points,
      const std::vector<bool>                       &watched,
      const dealii::Tensor<1, dim>                  &gravity,
      const double                                   horizon,
      const MPI_Comm                                 communicator) const
    {
      using MP                  = MaterialPointProperties<dim>;
      constexpr double    never = std::numeric_limits<double>::infinity();
      const unsigned int  n     = boundaries.n_boundaries();
      std::vector<double> earliest(n, never);
      // 1 where a point's extent already overlaps the surface
      std::vector<unsigned int> touching(n, 0);
      const auto                arrive = [&](const unsigned int                              b,
                              const dealii::Particles::ParticleAccessor<dim> &p,
                              const double                  depth,
                              const dealii::Tensor<1, dim> &m) {
        const auto   props = p.get_properties();
        const auto   F = internal::read_tensor<dim>(props, MP::deformation);
        const double r =
          0.5 * std::pow(props[MP::initial_volume] * dealii::determinant(F),
                         1. / dim);
        const double gap = -depth - r;
        if (!(gap > 0.))
          {
            touching[b] = 1;
            return;
          }
        dealii::Tensor<1, dim> v;
        for (unsigned int d = 0; d < dim; ++d)
          v[d] = props[MP::velocity + d];
        earliest[b] =
          std::min(earliest[b], arrival_time(gap, v * m, gravity * m));
      };
      // the boundaries checked on the boundary particles' side: the
      // entry of the points into the halo of their particles' cells
      std::vector<bool> halo_side(n, false);
      bool              any_halo = false;
      for (unsigned int b = 0; b < n && b < watched.size(); ++b)
        {
          halo_side[b] =
            watched[b] && !boundaries.boundary(b).material_point_contact;
          any_halo = any_halo || halo_side[b];
        }
      if (any_halo)
        {
          const auto boxes = halo_boxes(halo_side, communicator);
          std::vector<dealii::BoundingBox<dim>> box_list;
          for (const auto &box : boxes)
            box_list.push_back(box.first);
          const auto tree = dealii::pack_rtree_of_indices(box_list);
          // the step ends this share of the arrival time after the entry
          // (the next step starts with the point in the halo)
          constexpr double margin = 1e-3;
          for (const auto &p : points)
            {
              const auto             x     = p.get_location();
              const auto             props = p.get_properties();
              dealii::Tensor<1, dim> v;
              for (unsigned int d = 0; d < dim; ++d)
                v[d] = props[MP::velocity + d];
              // the reach of the point's domain: its path enters a halo
              // box widened by it
              const dealii::Tensor<1, dim> l = point_half_extent(
                internal::read_tensor<dim>(props, MP::deformation));
              const auto widened = [&](const dealii::BoundingBox<dim> &box) {
                auto [lower, upper] = box.get_boundary_points();
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    lower[d] -= l[d];
                    upper[d] += l[d];
                  }
                return dealii::BoundingBox<dim>({lower, upper});
              };
              // the box the path spans within the horizon (its ends and
              // the turning point of each direction), widened by the reach
              dealii::Point<dim> lower = x, upper = x;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  std::vector<double> ts = {horizon};
                  if (gravity[d] != 0. && -v[d] / gravity[d] > 0. &&
                      -v[d] / gravity[d] < horizon)
                    ts.push_back(-v[d] / gravity[d]);
                  for (const double t : ts)
                    {
                      const double y =
                        x[d] + v[d] * t + 0.5 * gravity[d] * t * t;
                      lower[d] = std::min(lower[d], y);
                      upper[d] = std::max(upper[d], y);
                    }
                }
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lower[d] -= l[d];
                  upper[d] += l[d];
                }
              std::vector<unsigned int> crossed;
              tree.query(boost::geometry::index::intersects(
                           dealii::BoundingBox<dim>({lower, upper})),
                         std::back_inserter(crossed));
              for (const unsigned int i : crossed)
                {
                  const unsigned int b = boxes[i].second;
                  const double       t = box_entry_time(
                    x, v, gravity, widened(boxes[i].first), horizon);
                  if (t == 0.)
                    touching[b] = 1;
                  else
                    earliest[b] = std::min(earliest[b], (1. + margin) * t);
                }
            }
        }
      for (unsigned int b = 0; b < n && b < watched.size(); ++b)
        {
          if (!watched[b] || halo_side[b])
            continue;
          if (behind.analytic(b))
            {
              const double h = 1e-4 * cell_size;
              for (const auto &p : points)
                {
                  const auto   x = p.get_location();
                  const double d = behind.depth(b, x);
                  if (!std::isfinite(d))
                    continue;
                  // the direction into the boundary, grad d
                  dealii::Tensor<1, dim> m;
                  bool                   finite = true;
                  for (unsigned int k = 0; k < dim; ++k)
                    {
                      dealii::Point<dim> plus = x, minus = x;
                      plus[k] += h;
                      minus[k] -= h;
                      const double dp = behind.depth(b, plus);
                      const double dm = behind.depth(b, minus);
                      finite = finite && std::isfinite(dp) && std::isfinite(dm);
                      m[k]   = (dp - dm) / (2. * h);
                    }
                  if (finite && m.norm() > 0.)
                    arrive(b, p, d, m / m.norm());
                }
              continue;
            }
          // by the particles: the tangent plane of the nearest one
          behind.for_points_near_particles(
            b,
            points,
            [&](const auto                   &p,
                const double                  d,
                const dealii::Tensor<1, dim> &n) { arrive(b, p, d, -n); });
        }
      dealii::Utilities::MPI::min(earliest, communicator, earliest);
      dealii::Utilities::MPI::max(touching, communicator, touching);
      for (unsigned int b = 0; b < n; ++b)
        if (touching[b] > 0)
          earliest[b] = never;
      return earliest;
    }


    template <int dim>
    bool
    ContactForecast<dim>::shorten_ahead(
      ContactOnsetEvent                             &event,
      TimeControl                                   &time_control,
      const dealii::Particles::ParticleHandler<dim> &points,
      const dealii::Tensor<1, dim>                  &gravity,
      const MPI_Comm                                 communicator) const
    {
      if (!event.forecasting() || boundaries.n_boundaries() == 0)
        return false;
      std::vector<bool> watched(boundaries.n_boundaries(), true);
      const auto        arrivals = arrival_times(
        points, watched, gravity, time_control.next_step(), communicator);
      const auto first = std::min_element(arrivals.begin(), arrivals.end());
      // on the boundary particles' side the reaction begins in the step
      // after the entry into the halo
      const bool halo_side =
        first != arrivals.end() && std::isfinite(*first) &&
        !boundaries.boundary(first - arrivals.begin()).material_point_contact;
      return event.forecast(time_control,
                            first != arrivals.end() ?
                              *first :
                              std::numeric_limits<double>::infinity(),
                            halo_side);
    }


    template class ContactForecast<2>;
    template class ContactForecast<3>;
  } // namespace MPM
} // namespace Talus
