#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>
#include <talus/materials/constitutive_model.h>
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
                                        const unsigned int n_slots,
                                        const bool         with_body)
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
      if (with_body)
        n.emplace_back("body");
      return n;
    }


    template <int dim>
    std::vector<
      dealii::DataComponentInterpretation::DataComponentInterpretation>
    MaterialPointProperties<dim>::interpretation(const unsigned int n_history,
                                                 const unsigned int n_slots,
                                                 const bool         with_body)
    {
      using namespace dealii::DataComponentInterpretation;
      std::vector<DataComponentInterpretation> r(n_properties(n_history,
                                                              n_slots) +
                                                   (with_body ? 1 : 0),
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
      , history_size(0)
      , lost_mass(0.)
      , lost_count(0)
    {}


    template <int dim>
    std::string
    MaterialPoints<dim>::body_subsection(const unsigned int index)
    {
      return index == 0 ? std::string("Body") :
                          "Body " + std::to_string(index + 1);
    }


    template <int dim>
    void
    MaterialPoints<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      for (unsigned int b = 0; b < max_bodies; ++b)
        declare_body(prm, b);
    }


    template <int dim>
    void
    MaterialPoints<dim>::declare_body(dealii::ParameterHandler &prm,
                                      const unsigned int        index)
    {
      using namespace dealii;
      prm.enter_subsection(body_subsection(index));
      {
        if (index == 0)
          prm.declare_entry(
            "number of bodies",
            "1",
            Patterns::Integer(),
            "Number N of bodies of material points [-], 1 to " +
              std::to_string(max_bodies) +
              ": this subsection is body 1, subsections 'Body 2' ... "
              "'Body N' (the same parameters) the others. Each body has "
              "its own material ('material') and initial velocity; by "
              "default all share the background grid and its one velocity "
              "field, so bodies that meet stick together (standard MPM "
              "contact; subsection Body contact for one velocity field per "
              "body with separation and friction). Box "
              "and polygon bodies must not overlap. With N > 1 the points "
              "carry a property 'body' (0 for body 1, 1 for body 2, ...).");
        prm.declare_entry(
          "material",
          "Material",
          Patterns::Anything(),
          "Material subsection of the body's points: 'Material' or "
          "'Material 2' ... 'Material " +
            std::to_string(Materials::max_materials) +
            "' (each with the parameters of subsection Material: model, "
            "density, elastic constants, ...).");
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
    std::vector<unsigned int>
    MaterialPoints<dim>::body_materials(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Body");
      const long n = prm.get_integer("number of bodies");
      prm.leave_subsection();
      if (n < 1 || n > static_cast<long>(max_bodies))
        InputFile::reject("Body",
                          "number of bodies",
                          std::to_string(n),
                          "it must be between 1 and " +
                            std::to_string(max_bodies) +
                            " (subsections 'Body', 'Body 2', ...)");
      std::vector<unsigned int> materials(n, 0);
      for (unsigned int b = 0; b < materials.size(); ++b)
        {
          const std::string sub = body_subsection(b);
          prm.enter_subsection(sub);
          const std::string material = prm.get("material");
          prm.leave_subsection();
          bool found = false;
          for (unsigned int m = 0; m < Materials::max_materials; ++m)
            if (material == Materials::material_subsection(m))
              {
                materials[b] = m;
                found        = true;
              }
          if (!found)
            InputFile::reject(sub,
                              "material",
                              material,
                              "it must name a material subsection: "
                              "'Material' or 'Material 2' ... 'Material " +
                                std::to_string(Materials::max_materials) + "'");
        }
      return materials;
    }


    template <int dim>
    void
    MaterialPoints<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      const auto materials = body_materials(prm);
      bodies.clear();
      bodies.resize(materials.size());
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          bodies[b].subsection = body_subsection(b);
          bodies[b].material   = materials[b];
          parse_body(prm, bodies[b]);
        }
    }


    template <int dim>
    void
    MaterialPoints<dim>::parse_body(dealii::ParameterHandler &prm,
                                    Body                     &body) const
    {
      const std::string sub = body.subsection;
      prm.enter_subsection(sub);
      auto &geometry             = body.geometry;
      auto &points_per_direction = body.points_per_direction;
      auto &clip_to_body         = body.clip_to_body;
      auto &box_lower            = body.box_lower;
      auto &box_upper            = body.box_upper;
      auto &polygon              = body.polygon;
      auto &mesh_file            = body.mesh_file;
      auto &initial_velocity     = body.initial_velocity;
      geometry                   = prm.get("geometry");
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
      parse_function(prm, *initial_velocity, sub + "/Initial velocity");
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
      const Body                                            &body,
      const std::function<bool(const dealii::Point<dim> &)> &inside,
      std::vector<dealii::Point<dim>>                       &points,
      std::vector<double>                                   &volumes,
      std::vector<typename dealii::Triangulation<dim>::active_cell_iterator>
                                      &cells,
      std::vector<dealii::Point<dim>> &reference_points) const
    {
      const auto &geometry             = body.geometry;
      const auto &polygon              = body.polygon;
      const auto &box_lower            = body.box_lower;
      const auto &box_upper            = body.box_upper;
      const auto &points_per_direction = body.points_per_direction;
      const bool  clip_to_body         = body.clip_to_body;
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
      const Body                      &body_description,
      std::vector<dealii::Point<dim>> &points,
      std::vector<double>             &volumes) const
    {
      const auto &mesh_file            = body_description.mesh_file;
      const auto &points_per_direction = body_description.points_per_direction;
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
          InputFile::reject(body_description.subsection,
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
    bool
    MaterialPoints<dim>::Body::contains(const dealii::Point<dim> &p,
                                        const double tolerance) const
    {
      if (geometry == "box")
        {
          for (unsigned int d = 0; d < dim; ++d)
            if (p[d] <= box_lower[d] + tolerance ||
                p[d] >= box_upper[d] - tolerance)
              return false;
          return true;
        }
      if (geometry == "polygon")
        {
          if (!inside_polygon(polygon, p))
            return false;
          // more than the tolerance from every edge
          for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size();
               j = i++)
            {
              const dealii::Tensor<1, dim> e = polygon[i] - polygon[j];
              const double                 L = e.norm();
              if (L == 0.)
                continue;
              double t = ((p - polygon[j]) * e) / (L * L);
              t        = std::max(0., std::min(1., t));
              if ((p - (polygon[j] + t * e)).norm() <= tolerance)
                return false;
            }
          return true;
        }
      return false;
    }


    template <int dim>
    void
    MaterialPoints<dim>::generate(
      const double       density,
      const unsigned int n_history,
      const std::function<void(const dealii::ArrayView<double> &)>
        &initialize_history)
    {
      generate(std::vector<double>(Materials::max_materials, density),
               n_history,
               [&](const unsigned int, const dealii::ArrayView<double> &h) {
                 initialize_history(h);
               });
    }


    template <int dim>
    void
    MaterialPoints<dim>::generate(
      const std::vector<double> &density,
      const unsigned int         n_history,
      const std::function<void(const unsigned int,
                               const dealii::ArrayView<double> &)>
        &initialize_history)
    {
      Assert(!bodies.empty(), dealii::ExcMessage("parse_parameters() first"));
      history_size                 = n_history;
      const unsigned int n_props   = n_properties();
      const bool         with_body = has_body_property();
      const unsigned int body_prop = body_index();
      handler.initialize(grid.triangulation, grid.mapping, n_props);
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

      dealii::types::particle_index next_id = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const Body                     &body = bodies[b];
          std::vector<dealii::Point<dim>> points;
          std::vector<double>             volumes;
          std::vector<typename dealii::Triangulation<dim>::active_cell_iterator>
                                          cells;
          std::vector<dealii::Point<dim>> reference_points;
          if (body.geometry == "box")
            generate_from_background_cells(
              body,
              [&body](const dealii::Point<dim> &p) {
                for (unsigned int d = 0; d < dim; ++d)
                  if (p[d] < body.box_lower[d] || p[d] > body.box_upper[d])
                    return false;
                return true;
              },
              points,
              volumes,
              cells,
              reference_points);
          else if (body.geometry == "polygon")
            generate_from_background_cells(
              body,
              [&body](const dealii::Point<dim> &p) {
                return inside_polygon(body.polygon, p);
              },
              points,
              volumes,
              cells,
              reference_points);
          else
            generate_from_gmsh(body, points, volumes);

          const auto n_total =
            dealii::Utilities::MPI::sum(points.size(), grid.mpi_communicator);
          if (n_total == 0)
            throw ExcInvalidInput(
              "Invalid input" +
              (InputFile::name().empty() ?
                 std::string() :
                 " in file <" + InputFile::name() + ">") +
              ":\n  the body in subsection <" + body.subsection +
              "> (geometry = " + body.geometry +
              ") contains no material point: it is empty or smaller than "
              "the spacing of the points (cell size / points per cell per "
              "direction).");

          // Overlap with an earlier box or polygon body: a point of this
          // body strictly inside it (a tolerance of 1e-9 cell sizes keeps
          // bodies that share an edge apart).
          {
            const double tolerance = 1e-9 * grid.minimal_cell_diameter;
            int          overlap   = -1;
            for (const auto &x : points)
              for (unsigned int c = 0; c < b && overlap < 0; ++c)
                if (bodies[c].contains(x, tolerance))
                  overlap = c;
            overlap =
              dealii::Utilities::MPI::max(overlap, grid.mpi_communicator);
            if (overlap >= 0)
              {
                InputFile::reject(
                  body.subsection,
                  "geometry",
                  body.geometry,
                  "the body overlaps the body of subsection <" +
                    bodies[overlap].subsection +
                    ">: bodies must not overlap (each material point "
                    "belongs to one body); move or shrink one of them");
              }
          }

          const unsigned int material = body.material;
          AssertIndexRange(material, density.size());
          std::vector<std::vector<double>> properties(points.size());
          dealii::Vector<double>           v0(dim);
          for (unsigned int i = 0; i < points.size(); ++i)
            {
              auto &prop = properties[i];
              prop.assign(n_props, 0.);
              prop[Properties::mass]           = density[material] * volumes[i];
              prop[Properties::initial_volume] = volumes[i];
              body.initial_velocity->vector_value(points[i], v0);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  prop[Properties::velocity + d]              = v0[d];
                  prop[Properties::initial_position + d]      = points[i][d];
                  prop[Properties::deformation + d * dim + d] = 1.;
                }
              if (n_history > 0)
                initialize_history(
                  material,
                  dealii::ArrayView<double>(prop.data() + Properties::history,
                                            n_history));
              if (with_body)
                prop[body_prop] = b;
            }

          const auto n_before = handler.n_global_particles();
          if (body.geometry != "gmsh")
            {
              // The points were made in locally owned cells: insert them
              // there directly (no search), with globally unique ids.
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
              if (dealii::Utilities::MPI::this_mpi_process(
                    grid.mpi_communicator) == 0)
                offset = 0;
              for (unsigned int i = 0; i < points.size(); ++i)
                handler.insert_particle(
                  points[i],
                  reference_points[i],
                  next_id + offset + i,
                  cells[i],
                  dealii::ArrayView<const double>(properties[i].data(),
                                                  properties[i].size()));
              handler.update_cached_numbers();
            }
          else
            {
              // Points of a body mesh: distribute them to the owners of
              // their cells (a few merged boxes per rank keep the search
              // cheap).
              const auto global_boxes = grid.global_bounding_boxes();
              // (deal.II numbers them after the largest id so far; with
              // explicit ids deal.II 9.4 hung on 2 ranks here: rank 0 in
              // the exchange of the ids, the other rank past it)
              handler.insert_global_particles(points, global_boxes, properties);
            }
          next_id += n_total;

          const auto n_inserted = handler.n_global_particles() - n_before;
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
                  << " material points of the body in subsection <"
                  << body.subsection
                  << "> lie outside the background grid; the body must lie "
                     "inside the grid.";
              throw ExcInvalidInput(msg.str());
            }
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
    unsigned int
    MaterialPoints<dim>::count_lost() const
    {
      return dealii::Utilities::MPI::sum(lost_count, grid.mpi_communicator);
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
    template <int dim>
    unsigned int
    MaterialPoints<dim>::points_per_cell_direction() const
    {
      AssertThrow(!bodies.empty(),
                  dealii::ExcMessage("parse_parameters() first"));
      const unsigned int n = bodies.front().points_per_direction;
      for (const auto &b : bodies)
        if (b.points_per_direction != n)
          InputFile::reject(b.subsection,
                            "points per cell per direction",
                            std::to_string(b.points_per_direction),
                            "the same number as in <" +
                              bodies.front().subsection + "> (" +
                              std::to_string(n) +
                              ") with 'shape functions = uGIMP', "
                              "'cpGIMP' or 'CPDI', whose (initial) particle "
                              "size "
                              "h/(2 n) is one for the grid");
      return n;
    }


    template class MaterialPoints<2>;
    template class MaterialPoints<3>;
  } // namespace MPM
} // namespace Talus
