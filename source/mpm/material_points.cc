#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>
#include <talus/mpm/material_points.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    std::vector<std::string>
    MaterialPointProperties<dim>::names(const unsigned int n_history,
                                        const unsigned int n_slots)
    {
      std::vector<std::string> n;
      n.emplace_back("mass");
      n.emplace_back("initial_volume");
      for (unsigned int d = 0; d < dim; ++d)
        n.emplace_back("velocity");
      for (unsigned int d = 0; d < dim; ++d)
        n.emplace_back("acceleration");
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          n.emplace_back("F_" + std::to_string(i) + std::to_string(j));
      for (const std::string s : {"xx", "yy", "zz", "xy", "yz", "xz"})
        n.emplace_back("stress_" + s);
      for (unsigned int d = 0; d < dim; ++d)
        n.emplace_back("initial_position");
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          n.emplace_back("C_" + std::to_string(i) + std::to_string(j));
      for (unsigned int i = 0; i < n_history; ++i)
        n.emplace_back("history_" + std::to_string(i));
      for (unsigned int b = 0; b < n_slots; ++b)
        for (unsigned int d = 0; d < dim; ++d)
          n.emplace_back("contact_gap_" + std::to_string(b + 1));
      for (unsigned int b = 0; b < n_slots; ++b)
        n.emplace_back("contact_offset_" + std::to_string(b + 1));
      return n;
    }


    template <int dim>
    std::vector<
      dealii::DataComponentInterpretation::DataComponentInterpretation>
    MaterialPointProperties<dim>::interpretation(const unsigned int n_history,
                                                 const unsigned int n_slots)
    {
      using namespace dealii::DataComponentInterpretation;
      std::vector<DataComponentInterpretation> r(n_properties(n_history,
                                                              n_slots),
                                                 component_is_scalar);
      for (unsigned int d = 0; d < dim; ++d)
        {
          r[velocity + d]         = component_is_part_of_vector;
          r[acceleration + d]     = component_is_part_of_vector;
          r[initial_position + d] = component_is_part_of_vector;
          for (unsigned int b = 0; b < n_slots; ++b)
            r[contact_gap(n_history, b) + d] = component_is_part_of_vector;
        }
      return r;
    }


    template <int dim>
    MaterialPoints<dim>::MaterialPoints(const BackgroundGrid<dim> &grid)
      : grid(grid)
      , points_per_direction(2)
      , history_size(0)
      , lost_mass(0.)
      , lost_count(0)
    {}


    template <int dim>
    void
    MaterialPoints<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Body");
      {
        prm.declare_entry(
          "geometry",
          "box",
          Patterns::Selection(dim == 2 ? "box|polygon|gmsh" : "box|gmsh"),
          "Shape of the body of material points: 'box' (axis aligned, "
          "corners below), 'polygon' (2D only: closed polygon through "
          "'vertices'), 'gmsh' (the cells of a Gmsh mesh of the body in "
          "'mesh file'). For box and polygon the points of the background "
          "cells that fall inside the shape are kept.");
        prm.declare_entry("lower corner",
                          dim == 2 ? "0.25, 0.25" : "0.25, 0.25, 0.25",
                          Patterns::Anything(),
                          "Lower corner of a box body [m].");
        prm.declare_entry("upper corner",
                          dim == 2 ? "0.75, 0.75" : "0.75, 0.75, 0.75",
                          Patterns::Anything(),
                          "Upper corner of a box body [m].");
        prm.declare_entry("vertices",
                          "0.25, 0.25; 0.75, 0.25; 0.5, 0.75",
                          Patterns::Anything(),
                          "Vertices of a polygon body [m], 'x, y' pairs "
                          "separated by ';', in order around the polygon "
                          "(at least 3).");
        prm.declare_entry("mesh file",
                          "",
                          Patterns::FileName(),
                          "Gmsh (.msh) mesh of the body for geometry = gmsh.");
        prm.declare_entry("points per cell per direction",
                          "2",
                          Patterns::Integer(1, 10),
                          "n: each cell holds n^dim material points at the "
                          "centres of an n^dim subdivision of the cell [-], "
                          "1 to 10.");
        prm.declare_entry(
          "clip points to the body",
          "false",
          Patterns::Bool(),
          "Box and polygon bodies on a Cartesian grid: each point stands for "
          "its sub-cell (1/n^dim of a background cell). false: a point is "
          "kept with the whole sub-cell volume if the sub-cell centre lies "
          "inside the body. true: the sub-cell is clipped to the body; a "
          "point is kept if the clipped part holds more than 1e-6 of the "
          "sub-cell, with that volume (and mass) and at its centroid. Then "
          "the points' volumes sum to the body's volume and every cell "
          "holds exactly the body's part of it, which removes the O(1) "
          "stress error in cells cut by a boundary that is not a grid line "
          "(the point volume beyond the boundary otherwise carries weight "
          "past the stress into the boundary); the cut cells then hold "
          "small points: combine with 'ghost penalty factor' (Solver).");
        prm.enter_subsection("Initial velocity");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    MaterialPoints<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      const std::string sub = "Body";
      prm.enter_subsection(sub);
      geometry             = prm.get("geometry");
      points_per_direction = prm.get_integer("points per cell per direction");
      clip_to_body         = prm.get_bool("clip points to the body");
      if (clip_to_body && geometry == "gmsh")
        InputFile::reject(sub,
                          "clip points to the body",
                          "true",
                          "clipping applies to box and polygon bodies; the "
                          "points of a Gmsh body carry their cells' exact "
                          "volumes already");
      if (clip_to_body && !grid.is_cartesian)
        InputFile::reject(sub,
                          "clip points to the body",
                          "true",
                          "clipping needs a Cartesian background grid (a "
                          "subdivided box), not a grid read from a file");
      if (geometry == "box")
        {
          std::tie(box_lower, box_upper) = parse_box<dim>(prm, sub);
          for (unsigned int d = 0; d < dim; ++d)
            if (box_lower[d] < grid.lower_corner[d] - 1e-12 ||
                box_upper[d] > grid.upper_corner[d] + 1e-12)
              {
                std::ostringstream allowed;
                allowed << "the body [" << box_lower << "] - [" << box_upper
                        << "] must lie inside the background grid ["
                        << grid.lower_corner << "] - [" << grid.upper_corner
                        << "]";
                InputFile::reject(sub,
                                  box_lower[d] < grid.lower_corner[d] - 1e-12 ?
                                    "lower corner" :
                                    "upper corner",
                                  prm.get(box_lower[d] <
                                              grid.lower_corner[d] - 1e-12 ?
                                            "lower corner" :
                                            "upper corner"),
                                  allowed.str());
              }
        }
      else if (geometry == "polygon")
        {
          polygon.clear();
          const std::string text = prm.get("vertices");
          for (const auto &pair :
               dealii::Utilities::split_string_list(text, ';'))
            {
              std::vector<double> xy;
              try
                {
                  xy = dealii::Utilities::string_to_double(
                    dealii::Utilities::split_string_list(pair, ','));
                }
              catch (...)
                {
                  xy.clear();
                }
              if (xy.size() != 2)
                InputFile::reject(sub,
                                  "vertices",
                                  text,
                                  "each vertex must be an 'x, y' pair and "
                                  "vertices are separated by ';'");
              dealii::Point<dim> p;
              p[0] = xy[0];
              p[1] = xy[1];
              for (unsigned int d = 0; d < 2; ++d)
                if (p[d] < grid.lower_corner[d] - 1e-12 ||
                    p[d] > grid.upper_corner[d] + 1e-12)
                  InputFile::reject(sub,
                                    "vertices",
                                    text,
                                    "every vertex must lie inside the "
                                    "background grid");
              polygon.push_back(p);
            }
          if (polygon.size() < 3)
            InputFile::reject(sub,
                              "vertices",
                              text,
                              "a polygon needs at least 3 vertices");
        }
      else
        {
          mesh_file = prm.get("mesh file");
          std::ifstream in(mesh_file);
          if (!in)
            InputFile::reject(sub,
                              "mesh file",
                              mesh_file,
                              "the file cannot be opened for reading");
        }
      prm.enter_subsection("Initial velocity");
      initial_velocity =
        std::make_unique<dealii::Functions::ParsedFunction<dim>>(dim);
      parse_function(prm, *initial_velocity, "Body/Initial velocity");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    namespace
    {
      // Even-odd rule; the points are never on the polygon's edges in
      // practice (they sit at sub-cell centres).
      template <int dim>
      bool
      inside_polygon(const std::vector<dealii::Point<dim>> &poly,
                     const dealii::Point<dim>              &p)
      {
        bool inside = false;
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
          {
            const auto &a = poly[i];
            const auto &b = poly[j];
            if (((a[1] > p[1]) != (b[1] > p[1])) &&
                (p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]))
              inside = !inside;
          }
        return inside;
      }

      /**
       * Area of the intersection of the simple polygon @p poly with the
       * rectangle [lo, hi], and its centroid: Sutherland-Hodgman clipping
       * of the polygon by the rectangle's four half planes (the clip region
       * is convex, so the area and centroid are exact for any simple
       * polygon; a concave one may leave zero-area edges, which the
       * shoelace formula ignores).
       */
      template <int dim>
      double
      clip_polygon_to_box(const std::vector<dealii::Point<dim>> &poly,
                          const dealii::Point<dim>              &lo,
                          const dealii::Point<dim>              &hi,
                          dealii::Point<dim>                    &centroid)
      {
        std::vector<std::array<double, 2>> current, next;
        for (const auto &p : poly)
          current.push_back({{p[0], p[1]}});
        for (unsigned int edge = 0; edge < 4 && !current.empty(); ++edge)
          {
            const unsigned int d     = edge / 2;
            const bool         lower = edge % 2 == 0;
            const double       bound = lower ? lo[d] : hi[d];
            const auto         in    = [&](const std::array<double, 2> &p) {
              return lower ? p[d] >= bound : p[d] <= bound;
            };
            next.clear();
            for (std::size_t i = 0; i < current.size(); ++i)
              {
                const auto &a = current[i];
                const auto &b = current[(i + 1) % current.size()];
                if (in(a))
                  next.push_back(a);
                if (in(a) != in(b))
                  {
                    const double t = (bound - a[d]) / (b[d] - a[d]);
                    next.push_back(
                      {{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])}});
                  }
              }
            current.swap(next);
          }
        double area = 0., cx = 0., cy = 0.;
        for (std::size_t i = 0; i < current.size(); ++i)
          {
            const auto  &a     = current[i];
            const auto  &b     = current[(i + 1) % current.size()];
            const double cross = a[0] * b[1] - b[0] * a[1];
            area += cross;
            cx += (a[0] + b[0]) * cross;
            cy += (a[1] + b[1]) * cross;
          }
        area *= 0.5;
        if (std::abs(area) > 0.)
          {
            centroid[0] = cx / (6. * area);
            centroid[1] = cy / (6. * area);
          }
        return std::abs(area);
      }
    } // namespace


    template <int dim>
    void
    MaterialPoints<dim>::generate_from_background_cells(
      const std::function<bool(const dealii::Point<dim> &)> &inside,
      std::vector<dealii::Point<dim>>                       &points,
      std::vector<double>                                   &volumes,
      std::vector<typename dealii::Triangulation<dim>::active_cell_iterator>
                                      &cells,
      std::vector<dealii::Point<dim>> &reference_points) const
    {
      const dealii::QIterated<dim> quadrature(dealii::QMidpoint<1>(),
                                              points_per_direction);
      dealii::FE_Q<dim>            fe(1);
      dealii::FEValues<dim>        fe_values(grid.mapping,
                                      fe,
                                      quadrature,
                                      dealii::update_quadrature_points |
                                        dealii::update_JxW_values);
      // Clipped sub-cells (Cartesian grid): volume of body and sub-cell,
      // and its centroid.
      const auto clipped_volume = [&](const dealii::Point<dim> &lo,
                                      const dealii::Point<dim> &hi,
                                      dealii::Point<dim>       &centroid) {
        if (geometry == "polygon")
          return clip_polygon_to_box(polygon, lo, hi, centroid);
        double volume = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double a = std::max(lo[d], box_lower[d]);
            const double b = std::min(hi[d], box_upper[d]);
            volume *= std::max(0., b - a);
            centroid[d] = 0.5 * (a + b);
          }
        return volume;
      };
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            if (clip_to_body)
              {
                dealii::Tensor<1, dim> sub;
                for (unsigned int d = 0; d < dim; ++d)
                  sub[d] = grid.cell_extent[d] / points_per_direction;
                const dealii::Point<dim> origin = cell->vertex(0);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  {
                    const auto        &xi = quadrature.point(q);
                    dealii::Point<dim> lo, hi, centroid;
                    double             full = 1.;
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        const unsigned int k = static_cast<unsigned int>(
                          std::floor(xi[d] * points_per_direction));
                        lo[d] = origin[d] + k * sub[d];
                        hi[d] = lo[d] + sub[d];
                        full *= sub[d];
                      }
                    const double volume = clipped_volume(lo, hi, centroid);
                    if (!(volume > 1e-6 * full))
                      continue;
                    dealii::Point<dim> reference;
                    for (unsigned int d = 0; d < dim; ++d)
                      reference[d] =
                        (centroid[d] - origin[d]) / grid.cell_extent[d];
                    points.push_back(centroid);
                    volumes.push_back(volume);
                    cells.push_back(cell);
                    reference_points.push_back(reference);
                  }
                continue;
              }
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              if (inside(fe_values.quadrature_point(q)))
                {
                  points.push_back(fe_values.quadrature_point(q));
                  volumes.push_back(fe_values.JxW(q));
                  cells.push_back(cell);
                  reference_points.push_back(quadrature.point(q));
                }
          }
    }


    template <int dim>
    void
    MaterialPoints<dim>::generate_from_gmsh(
      std::vector<dealii::Point<dim>> &points,
      std::vector<double>             &volumes) const
    {
      // Every rank reads the mesh, so that a bad file is an error on all
      // ranks; rank 0 alone generates the points (they are distributed by
      // insert_global_particles).
      dealii::Triangulation<dim> body;
      dealii::GridIn<dim>        grid_in(body);
      std::ifstream              in(mesh_file);
      try
        {
          grid_in.read_msh(in);
        }
      catch (const dealii::ExceptionBase &e)
        {
          std::ostringstream what;
          e.print_info(what);
          InputFile::reject("Body",
                            "mesh file",
                            mesh_file,
                            "it is not a readable Gmsh mesh: " +
                              dealii::Utilities::trim(what.str()));
        }
      if (dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) != 0)
        return;
      const dealii::QIterated<dim> quadrature(dealii::QMidpoint<1>(),
                                              points_per_direction);
      dealii::FE_Q<dim>            fe(1);
      dealii::MappingQ1<dim>       mapping;
      dealii::FEValues<dim>        fe_values(mapping,
                                      fe,
                                      quadrature,
                                      dealii::update_quadrature_points |
                                        dealii::update_JxW_values);
      for (const auto &cell : body.active_cell_iterators())
        {
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              points.push_back(fe_values.quadrature_point(q));
              volumes.push_back(fe_values.JxW(q));
            }
        }
    }


    template <int dim>
    void
    MaterialPoints<dim>::generate(
      const double       density,
      const unsigned int n_history,
      const std::function<void(const dealii::ArrayView<double> &)>
        &initialize_history)
    {
      history_size = n_history;
      handler.initialize(grid.triangulation,
                         grid.mapping,
                         Properties::n_properties(n_history, contact_slots));
      handler.signals.particle_lost.connect(
        [this](
          const typename dealii::Particles::ParticleIterator<dim> &p,
          const typename dealii::Triangulation<dim>::active_cell_iterator &) {
          lost_mass += p->get_properties()[Properties::mass];
          const dealii::Point<dim> x = p->get_location();
          for (unsigned int d = 0; d < dim; ++d)
            {
              lost_lower[d] =
                lost_count == 0 ? x[d] : std::min(lost_lower[d], x[d]);
              lost_upper[d] =
                lost_count == 0 ? x[d] : std::max(lost_upper[d], x[d]);
            }
          ++lost_count;
        });

      std::vector<dealii::Point<dim>> points;
      std::vector<double>             volumes;
      std::vector<typename dealii::Triangulation<dim>::active_cell_iterator>
                                      cells;
      std::vector<dealii::Point<dim>> reference_points;
      if (geometry == "box")
        generate_from_background_cells(
          [this](const dealii::Point<dim> &p) {
            for (unsigned int d = 0; d < dim; ++d)
              if (p[d] < box_lower[d] || p[d] > box_upper[d])
                return false;
            return true;
          },
          points,
          volumes,
          cells,
          reference_points);
      else if (geometry == "polygon")
        generate_from_background_cells(
          [this](const dealii::Point<dim> &p) {
            return inside_polygon(polygon, p);
          },
          points,
          volumes,
          cells,
          reference_points);
      else
        generate_from_gmsh(points, volumes);

      const auto n_total =
        dealii::Utilities::MPI::sum(points.size(), grid.mpi_communicator);
      if (n_total == 0)
        throw ExcInvalidInput(
          "Invalid input" +
          (InputFile::name().empty() ? std::string() :
                                       " in file <" + InputFile::name() + ">") +
          ":\n  the body in subsection <Body> (geometry = " + geometry +
          ") contains no material point: it is empty or smaller than the "
          "spacing of the points (cell size / points per cell per "
          "direction).");

      std::vector<std::vector<double>> properties(points.size());
      const unsigned int               n_properties =
        Properties::n_properties(n_history, contact_slots);
      dealii::Vector<double> v0(dim);
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          auto &prop = properties[i];
          prop.assign(n_properties, 0.);
          prop[Properties::mass]           = density * volumes[i];
          prop[Properties::initial_volume] = volumes[i];
          initial_velocity->vector_value(points[i], v0);
          for (unsigned int d = 0; d < dim; ++d)
            {
              prop[Properties::velocity + d]              = v0[d];
              prop[Properties::initial_position + d]      = points[i][d];
              prop[Properties::deformation + d * dim + d] = 1.;
            }
          if (n_history > 0)
            initialize_history(
              dealii::ArrayView<double>(prop.data() + Properties::history,
                                        n_history));
        }

      if (geometry != "gmsh")
        {
          // The points were made in locally owned cells: insert them there
          // directly (no search), with globally unique ids.
          const dealii::types::particle_index n_local = points.size();
          dealii::types::particle_index       offset  = 0;
          MPI_Exscan(
            &n_local,
            &offset,
            1,
            dealii::Utilities::MPI::internal::MPIDataTypes::mpi_type_id(
              &n_local),
            MPI_SUM,
            grid.mpi_communicator);
          if (dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) ==
              0)
            offset = 0;
          for (unsigned int i = 0; i < points.size(); ++i)
            handler.insert_particle(
              points[i],
              reference_points[i],
              offset + i,
              cells[i],
              dealii::ArrayView<const double>(properties[i].data(),
                                              properties[i].size()));
          handler.update_cached_numbers();
        }
      else
        {
          // Points of a body mesh: distribute them to the owners of their
          // cells (a few merged boxes per rank keep the search cheap).
          const auto global_boxes = grid.global_bounding_boxes();
          handler.insert_global_particles(points, global_boxes, properties);
        }

      const auto n_inserted = handler.n_global_particles();
      if (n_inserted != n_total)
        {
          // Points of a Gmsh body outside the background grid are not
          // inserted: report them instead of losing mass silently.
          std::ostringstream msg;
          msg << "Invalid input"
              << (InputFile::name().empty() ?
                    std::string() :
                    " in file <" + InputFile::name() + ">")
              << ":\n  " << (n_total - n_inserted) << " of " << n_total
              << " material points of the body in subsection <Body> lie "
                 "outside the background grid; the body must lie inside "
                 "the grid.";
          throw ExcInvalidInput(msg.str());
        }
    }


    template <int dim>
    dealii::Particles::ParticleHandler<dim> &
    MaterialPoints<dim>::particle_handler()
    {
      return handler;
    }


    template <int dim>
    const dealii::Particles::ParticleHandler<dim> &
    MaterialPoints<dim>::particle_handler() const
    {
      return handler;
    }


    template <int dim>
    dealii::types::particle_index
    MaterialPoints<dim>::n_global_points() const
    {
      return handler.n_global_particles();
    }


    template <int dim>
    double
    MaterialPoints<dim>::take_lost_mass()
    {
      const double m =
        dealii::Utilities::MPI::sum(lost_mass, grid.mpi_communicator);
      lost_mass = 0.;
      return m;
    }


    template <int dim>
    unsigned int
    MaterialPoints<dim>::take_lost_count()
    {
      const unsigned int n =
        dealii::Utilities::MPI::sum(lost_count, grid.mpi_communicator);
      lost_count = 0;
      return n;
    }


    template <int dim>
    std::pair<dealii::Point<dim>, dealii::Point<dim>>
    MaterialPoints<dim>::take_lost_region()
    {
      const MPI_Comm     comm = grid.mpi_communicator;
      const unsigned int n    = dealii::Utilities::MPI::sum(lost_count, comm);
      std::pair<dealii::Point<dim>, dealii::Point<dim>> region;
      if (n == 0)
        return region;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double big = std::numeric_limits<double>::max();
          region.first[d] =
            dealii::Utilities::MPI::min(lost_count > 0 ? lost_lower[d] : big,
                                        comm);
          region.second[d] =
            dealii::Utilities::MPI::max(lost_count > 0 ? lost_upper[d] : -big,
                                        comm);
        }
      return region;
    }


    template <int dim>
    void
    MaterialPoints<dim>::save_state()
    {
      backup.copy_from(handler);
    }


    template <int dim>
    void
    MaterialPoints<dim>::restore_state()
    {
      handler.copy_from(backup);
    }


    template <int dim>
    unsigned int
    MaterialPoints<dim>::n_history() const
    {
      return history_size;
    }


    template struct MaterialPointProperties<2>;
    template struct MaterialPointProperties<3>;
    template class MaterialPoints<2>;
    template class MaterialPoints<3>;
  } // namespace MPM
} // namespace Talus
