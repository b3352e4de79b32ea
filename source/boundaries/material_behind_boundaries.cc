#include <talus/boundaries/material_behind_boundaries.h>

#include <deal.II/base/mpi.h>

#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace Talus
{
  namespace Boundaries
  {
    namespace
    {
      /**
       * Distance of @p x behind the segment a..b with the unit normal @p n
       * into the material; -infinity where x projects beside the segment.
       */
      template <int dim>
      double
      depth_behind_segment(const dealii::Point<dim>     &x,
                           const dealii::Point<dim>     &a,
                           const dealii::Point<dim>     &b,
                           const dealii::Tensor<1, dim> &n)
      {
        const dealii::Tensor<1, dim> t = b - a;
        const double                 s = ((x - a) * t) / t.norm_square();
        if (s < 0. || s > 1.)
          return -std::numeric_limits<double>::infinity();
        return -((x - a) * n);
      }
    } // namespace


    template <int dim>
    MaterialBehindBoundaries<dim>::MaterialBehindBoundaries(
      const BoundaryParticles<dim>   &boundaries,
      const MPM::BackgroundGrid<dim> &grid)
      : boundaries(boundaries)
      , cell_size(grid.minimal_cell_diameter)
      , on_faces(boundaries.n_boundaries(), false)
      , largest(boundaries.n_boundaries())
      , reported(boundaries.n_boundaries())
      , time_of_largest(boundaries.n_boundaries(), 0.)
    {
      if (!grid.is_cartesian)
        return;
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &desc = boundaries.boundary(b);
          if (!analytic(b) ||
              (desc.geometry != "plane" && desc.geometry != "line"))
            continue;
          for (unsigned int d = 0; d < dim && !on_faces[b]; ++d)
            {
              const double h  = grid.cell_extent[d];
              bool         on = true;
              for (const auto &v : desc.vertices)
                {
                  const double r = (v[d] - grid.lower_corner[d]) / h;
                  on             = on && std::abs(r - std::round(r)) < 1e-6 &&
                       std::abs(v[d] - desc.vertices[0][d]) < 1e-6 * h;
                }
              on_faces[b] = on;
            }
        }
    }


    template <int dim>
    bool
    MaterialBehindBoundaries<dim>::on_grid_faces(const unsigned int b) const
    {
      return b < on_faces.size() && on_faces[b];
    }


    template <int dim>
    bool
    MaterialBehindBoundaries<dim>::analytic(const unsigned int b) const
    {
      const auto &desc = boundaries.boundary(b);
      if (desc.moving || desc.external_displacement)
        return false;
      return ((desc.geometry == "plane" || desc.geometry == "line") &&
              desc.vertices.size() >= 2) ||
             desc.geometry == "box" || (dim == 2 && desc.geometry == "circle");
    }


    template <int dim>
    double
    MaterialBehindBoundaries<dim>::depth(const unsigned int        b,
                                         const dealii::Point<dim> &x) const
    {
      constexpr double none = -std::numeric_limits<double>::infinity();
      if (!analytic(b))
        return none;
      const auto  &desc = boundaries.boundary(b);
      const double flip = desc.flip_normals ? -1. : 1.;
      const auto  &v    = desc.vertices;
      if (desc.geometry == "plane" || desc.geometry == "line")
        {
          if constexpr (dim == 3)
            {
              // the parallelogram p0, p1, p2 (BoundaryParticles::orient)
              const dealii::Tensor<1, dim> a = v[1] - v[0], c = v[2] - v[0];
              dealii::Tensor<1, dim>       n = dealii::cross_product_3d(a, c);
              n *= flip / n.norm();
              const dealii::Tensor<1, dim> r  = x - v[0];
              const double                 aa = a * a, ac = a * c, cc = c * c;
              const double                 det = aa * cc - ac * ac;
              const double s = ((r * a) * cc - (r * c) * ac) / det;
              const double t = ((r * c) * aa - (r * a) * ac) / det;
              if (s < 0. || s > 1. || t < 0. || t > 1.)
                return none;
              return -(r * n);
            }
          else
            {
              // the polyline: the normal left of each segment's direction
              // (BoundaryParticles::generate); the nearest segment decides
              double result  = none,
                     nearest = std::numeric_limits<double>::max();
              for (unsigned int i = 0; i + 1 < v.size(); ++i)
                {
                  const dealii::Tensor<1, dim> t = v[i + 1] - v[i];
                  dealii::Tensor<1, dim>       n;
                  n[0] = -t[1];
                  n[1] = t[0];
                  n *= flip / n.norm();
                  const double d = depth_behind_segment(x, v[i], v[i + 1], n);
                  if (std::isfinite(d) && std::abs(d) < nearest)
                    {
                      nearest = std::abs(d);
                      result  = d;
                    }
                }
              return result;
            }
        }
      // box or circle: the distance into the side without material
      const bool material_inside = desc.material_inside != desc.flip_normals;
      double     outside         = 0.; // signed distance from the surface
      if (desc.geometry == "circle")
        outside = x.distance(desc.center) - desc.radius;
      else
        {
          double largest_inner = -std::numeric_limits<double>::max();
          double outer         = 0.;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double below = desc.lower_corner[d] - x[d];
              const double above = x[d] - desc.upper_corner[d];
              const double e     = std::max(below, above);
              largest_inner      = std::max(largest_inner, e);
              if (e > 0.)
                outer += e * e;
            }
          outside = largest_inner > 0. ? std::sqrt(outer) : largest_inner;
        }
      return material_inside ? outside : -outside;
    }


    template <int dim>
    std::vector<typename MaterialBehindBoundaries<dim>::Survey>
    MaterialBehindBoundaries<dim>::survey(
      const dealii::Particles::ParticleHandler<dim> &points,
      const unsigned int                             mass_index,
      const MPI_Comm                                 communicator) const
    {
      const unsigned int  n = boundaries.n_boundaries();
      std::vector<double> count(n, 0.), mass(n, 0.), deepest(n, 0.);
      const auto          add =
        [&](const unsigned int b, const double d, const double m) {
          if (d > 0.)
            {
              count[b] += 1.;
              mass[b] += m;
              deepest[b] = std::max(deepest[b], d);
            }
        };
      std::vector<unsigned int> checked;
      for (unsigned int b = 0; b < n; ++b)
        if (analytic(b))
          checked.push_back(b);
      if (!checked.empty())
        for (const auto &p : points)
          for (const unsigned int b : checked)
            add(b, depth(b, p.get_location()), p.get_properties()[mass_index]);

      // the other boundaries by their particles: every rank gets the whole
      // surface (positions and normals), the nearest particle decides
      for (unsigned int b = 0; b < n; ++b)
        {
          if (analytic(b))
            continue;
          for_points_near_particles(b,
                                    points,
                                    [&](const auto  &p,
                                        const double d,
                                        const dealii::Tensor<1, dim> &) {
                                      add(b, d, p.get_properties()[mass_index]);
                                    });
        }
      dealii::Utilities::MPI::sum(count, communicator, count);
      dealii::Utilities::MPI::sum(mass, communicator, mass);
      dealii::Utilities::MPI::max(deepest, communicator, deepest);
      std::vector<Survey> s(n);
      for (unsigned int b = 0; b < n; ++b)
        {
          s[b].n_points      = static_cast<unsigned int>(count[b] + 0.5);
          s[b].mass          = mass[b];
          s[b].largest_depth = deepest[b];
        }
      return s;
    }


    template <int dim>
    std::string
    MaterialBehindBoundaries<dim>::assess(const std::vector<Survey> &s,
                                          const double               time)
    {
      std::ostringstream out;
      for (unsigned int b = 0; b < s.size() && b < largest.size(); ++b)
        {
          const Survey &now = s[b];
          if (now.n_points == 0)
            continue;
          if (now.n_points > largest[b].n_points)
            time_of_largest[b] = time;
          largest[b].n_points = std::max(largest[b].n_points, now.n_points);
          largest[b].mass     = std::max(largest[b].mass, now.mass);
          largest[b].largest_depth =
            std::max(largest[b].largest_depth, now.largest_depth);
          Survey &last = reported[b];
          if (now.n_points < 2 * std::max(last.n_points, 1u) &&
              now.largest_depth < last.largest_depth + 0.25 * cell_size &&
              last.n_points > 0)
            continue;
          out << "  Warning: " << now.n_points << " material point(s) with a "
              << "mass of " << now.mass << " kg lie behind boundary '"
              << boundaries.name(b) << "' at t = " << time << " s, the deepest "
              << now.largest_depth
              << " m (a penalty lets material in by about sigma h / "
                 "(factor M); points that sink past the cells of the "
                 "boundary particles are no longer held and may leave the "
                 "grid"
              << (on_faces[b] ?
                    "; this surface lies on faces of the grid, so a point "
                    "that crosses it at once leaves those cells: shift the "
                    "grid by half a cell across it" :
                    "")
              << ")\n";
          last = now;
        }
      return out.str();
    }


    template <int dim>
    std::string
    MaterialBehindBoundaries<dim>::summary() const
    {
      std::ostringstream out;
      for (unsigned int b = 0; b < largest.size(); ++b)
        if (largest[b].n_points > 0)
          out << "  Material behind boundary '" << boundaries.name(b)
              << "': at most " << largest[b].n_points
              << " point(s) (at t = " << time_of_largest[b] << " s), at most "
              << largest[b].mass << " kg, the deepest "
              << largest[b].largest_depth << " m\n";
      return out.str();
    }


    template class MaterialBehindBoundaries<2>;
    template class MaterialBehindBoundaries<3>;
  } // namespace Boundaries
} // namespace Talus
