#include <talus/mpm/contact_forecast.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/point_tensors.h>

#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    ContactForecast<dim>::ContactForecast(
      const Boundaries::BoundaryParticles<dim>        &boundaries,
      const Boundaries::MaterialBehindBoundaries<dim> &behind,
      const double                                     cell_size)
      : boundaries(boundaries)
      , behind(behind)
      , cell_size(cell_size)
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
    std::vector<double>
    ContactForecast<dim>::arrival_times(
      const dealii::Particles::ParticleHandler<dim> &points,
      const std::vector<bool>                       &watched,
      const dealii::Tensor<1, dim>                  &gravity,
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
      for (unsigned int b = 0; b < n && b < watched.size(); ++b)
        {
          if (!watched[b])
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
      std::vector<bool> watched(boundaries.n_boundaries());
      for (unsigned int b = 0; b < watched.size(); ++b)
        watched[b] = boundaries.boundary(b).material_point_contact;
      const auto arrivals =
        arrival_times(points, watched, gravity, communicator);
      return event.forecast(time_control,
                            *std::min_element(arrivals.begin(),
                                              arrivals.end()));
    }


    template class ContactForecast<2>;
    template class ContactForecast<3>;
  } // namespace MPM
} // namespace Talus
