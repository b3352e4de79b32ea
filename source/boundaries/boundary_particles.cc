#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>
#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q1.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace Talus
{
  namespace Boundaries
  {
    namespace
    {
      std::string
      slot_name(const unsigned int k)
      {
        return "Boundary " + std::to_string(k + 1);
      }

      /**
       * Whether subsection `Boundary k+1` of the current subsection was
       * declared (declare_parameters() declared as many as the file
       * needs).
       */
      bool
      declared_slot(const dealii::ParameterHandler &prm, const unsigned int k)
      {
        return prm.subsection_path_exists({slot_name(k)});
      }

      bool
      has_stl_extension(const std::string &file_name)
      {
        const auto dot = file_name.rfind('.');
        if (dot == std::string::npos)
          return false;
        std::string extension = file_name.substr(dot + 1);
        for (auto &c : extension)
          c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return extension == "stl";
      }


      /**
       * Boundary particles on a triangle for 'particles per cell' = n: the
       * centroid for n = 1, else the symmetric Witherden-Vincent rule of even
       * order n - 1 (3, 6, 12, 16, 25, 33, 42 points for n = 2 ... 8). A
       * triangle is about half a square of its diameter, so this is 1.3 to
       * 1.5 times the density of the n x n points of a quadrilateral.
       * Symmetric, so the points do not depend on the vertex order;
       * positive weights, so each point carries a positive area.
       */
      dealii::Quadrature<2>
      triangle_quadrature(const unsigned int n)
      {
        if (n == 1)
          return dealii::QGaussSimplex<2>(1);
        return dealii::QWitherdenVincentSimplex<2>(n - 1, false);
      }


      template <int spacedim>
      std::string
      describe_cell(
        const typename dealii::Triangulation<spacedim - 1,
                                             spacedim>::cell_iterator &cell)
      {
        std::ostringstream text;
        text << "cell " << cell->index() + 1 << " at (" << cell->center()
             << ")";
        return text.str();
      }


      /**
       * Check that the cells of a surface mesh, in their vertex order as
       * read, are oriented consistently, so that the normals deal.II
       * computes from that order point to one side of the surface.
       *
       * Each cell's boundary is traversed in its vertex order: a line
       * v0 -> v1 starts at v0 and ends at v1; a triangle runs v0 v1 v2, a
       * quadrilateral (deal.II's lexicographic numbering) v0 v1 v3 v2. Two
       * neighbours are consistently oriented when they traverse their
       * common edge in opposite directions (lines: the common vertex ends
       * one and starts the other). GridIn makes the cells of a
       * quadrilateral mesh consistent by itself through the cells'
       * direction flags, and leaves triangles as they are; this check looks
       * at the vertex order as read, so both are rejected alike instead of
       * being re-oriented to the first cell without a word.
       *
       * @return an empty string, or which cells disagree (an orientation
       * conflict, or an edge shared by more than two cells).
       */
      template <int spacedim>
      std::string
      orientation_conflict(
        const dealii::Triangulation<spacedim - 1, spacedim> &surface)
      {
        constexpr int dim = spacedim - 1;
        using Cell =
          typename dealii::Triangulation<dim, spacedim>::cell_iterator;
        // edge (sorted vertex indices) -> the cells that traverse it, with
        // +1 for the direction of increasing vertex index, -1 for the other
        std::map<std::vector<unsigned int>, std::vector<std::pair<Cell, int>>>
          edges;
        for (const auto &cell : surface.cell_iterators_on_level(0))
          {
            std::vector<unsigned int> cycle;
            if (dim == 1)
              cycle = {0, 1};
            else if (cell->n_vertices() == 3)
              cycle = {0, 1, 2};
            else
              cycle = {0, 1, 3, 2};
            if (dim == 1)
              {
                edges[{cell->vertex_index(0)}].emplace_back(cell, -1);
                edges[{cell->vertex_index(1)}].emplace_back(cell, +1);
                continue;
              }
            for (unsigned int i = 0; i < cycle.size(); ++i)
              {
                const unsigned int a = cell->vertex_index(cycle[i]);
                const unsigned int b =
                  cell->vertex_index(cycle[(i + 1) % cycle.size()]);
                edges[{std::min(a, b), std::max(a, b)}].emplace_back(
                  cell, a < b ? +1 : -1);
              }
          }
        for (const auto &[key, users] : edges)
          {
            (void)key;
            if (users.size() > 2)
              return std::string(dim == 1 ? "a vertex" : "an edge") + " of " +
                     describe_cell<spacedim>(users[0].first) +
                     " is shared by " + std::to_string(users.size()) +
                     " cells: split a branching surface into several "
                     "boundaries";
            if (users.size() == 2 && users[0].second == users[1].second)
              return describe_cell<spacedim>(users[0].first) + " and " +
                     describe_cell<spacedim>(users[1].first) +
                     " have opposite normals: " +
                     (dim == 1 ?
                        "a line must start where its neighbour ends" :
                        "neighbours must run through their common edge in "
                        "opposite directions") +
                     "; reverse the vertex order of the inverted cells";
          }
        return "";
      }

      template <int dim>
      std::vector<dealii::Point<dim>>
      parse_point_list(const dealii::ParameterHandler &prm,
                       const std::string              &subsection,
                       const std::string              &entry)
      {
        std::vector<dealii::Point<dim>> points;
        const std::string               text = prm.get(entry);
        for (const auto &item : dealii::Utilities::split_string_list(text, ';'))
          {
            std::vector<double> values;
            try
              {
                values = dealii::Utilities::string_to_double(
                  dealii::Utilities::split_string_list(item, ','));
              }
            catch (...)
              {
                values.clear();
              }
            if (values.size() != dim)
              InputFile::reject(subsection,
                                entry,
                                text,
                                "a list of points separated by ';', each " +
                                  std::to_string(dim) +
                                  " coordinates separated by ','");
            dealii::Point<dim> p;
            for (unsigned int d = 0; d < dim; ++d)
              p[d] = values[d];
            points.push_back(p);
          }
        return points;
      }
    } // namespace


    template <int dim>
    BoundaryParticles<dim>::BoundaryParticles(
      const MPM::BackgroundGrid<dim> &grid)
      : grid(grid)
    {}


    template <int dim>
    unsigned int
    BoundaryParticles<dim>::n_boundaries_in_file(const std::string &filename)
    {
      unsigned int  n = default_boundary_slots;
      std::ifstream in(filename);
      std::string   line;
      while (std::getline(in, line))
        {
          std::istringstream words(line);
          std::string        keyword, name;
          unsigned int       number = 0;
          if (words >> keyword >> name >> number && keyword == "subsection" &&
              name == "Boundary")
            n = std::max(n, number);
        }
      return n;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                               const unsigned int n_slots)
    {
      using dealii::Patterns::Anything;
      using dealii::Patterns::Bool;
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::Selection;
      prm.enter_subsection("Boundary particles");
      prm.declare_entry(
        "multiplier tolerance",
        "1e-5",
        Double(0.),
        "Augmented Lagrangian boundaries: the multiplier (Uzawa) updates "
        "of a step stop when no active boundary particle has a gap larger "
        "than this times the smallest background cell size (normal gap for "
        "contact and slip, the whole relative displacement of the step for "
        "fixed and sticking particles); 'Lagrange multiplier' boundaries: "
        "Newton converges only when the constraint residual "
        "(lambda - f) / (beta w) of every multiplier is below it [-].");
      prm.declare_entry(
        "maximum multiplier updates",
        "20",
        Integer(1, 1000),
        "Augmented Lagrangian boundaries: the most multiplier updates in "
        "one step; a step that needs more fails like a non-converged Newton "
        "solve (and is retried with a smaller step if allowed) [-].");
      for (unsigned int k = 0; k < n_slots; ++k)
        {
          prm.enter_subsection(slot_name(k));
          prm.declare_entry(
            "geometry",
            "none",
            Selection(dim == 2 ? "none|line|circle|box|mesh|external" :
                                 "none|plane|box|mesh|external"),
            "Shape of this boundary that does not follow the grid: 'none' "
            "(unused slot), " +
              std::string(dim == 2 ?
                            "'line' (polyline through 'vertices'; the "
                            "material is on the left of the direction of "
                            "travel), 'circle' ('center', 'radius'), " :
                            "'plane' (the parallelogram p0 + s (p1 - p0) + "
                            "t (p2 - p0), s, t in [0, 1], through the three "
                            "'vertices'; the material is on the side of "
                            "(p1 - p0) x (p2 - p0)), ") +
              "'box' (the surface of the box between 'lower corner' and "
              "'upper corner'), 'mesh' (a surface mesh of dimension " +
              std::to_string(dim - 1) +
              " in 'mesh file', material on the side of the normals deal.II "
              "computes from the cell orientation), 'external' (a surface "
              "mesh handed over by the program, as the structure coupling "
              "does through BoundaryParticles::set_surface(); the talus "
              "application alone has none to give).");
          prm.declare_entry("name",
                            "boundary" + std::to_string(k + 1),
                            Anything(),
                            "Name of the boundary in the log and in the CSV "
                            "time series columns (<name>_force_x, ...) [-].");
          prm.declare_entry("vertices",
                            "",
                            Anything(),
                            "Points of a 'line' (at least 2, 2D) or of a "
                            "'plane' (exactly 3, 3D) [m]: coordinates "
                            "separated by ',', points by ';'.");
          prm.declare_entry("center",
                            dim == 2 ? "0, 0" : "0, 0, 0",
                            Anything(),
                            "Center of a 'circle' [m].");
          prm.declare_entry("radius",
                            "1",
                            Double(0.),
                            "Radius of a 'circle' [m].");
          prm.declare_entry("lower corner",
                            dim == 2 ? "0, 0" : "0, 0, 0",
                            Anything(),
                            "Lower corner of a 'box' [m].");
          prm.declare_entry("upper corner",
                            dim == 2 ? "1, 1" : "1, 1, 1",
                            Anything(),
                            "Upper corner of a 'box' [m].");
          prm.declare_entry("material side",
                            "inside",
                            Selection("inside|outside"),
                            "For 'circle' and 'box': whether the material "
                            "is inside (a container) or outside (an "
                            "obstacle) [-].");
          prm.declare_entry(
            "flip normals",
            "false",
            Bool(),
            "Reverse the normals of a 'line', 'plane', 'mesh' or "
            "'external' (the material is then on the other "
            "side) [-].");
          prm.declare_entry("mesh file",
                            "",
                            Anything(),
                            "Surface mesh of a 'mesh' boundary, read by "
                            "deal.II's GridIn as Triangulation<dim-1, dim>: "
                            "Gmsh .msh, VTK .vtk or UCD .inp (lines in 2D; "
                            "quadrilaterals or triangles in 3D), or STL "
                            "(3D, triangles, opened through the Gmsh API). "
                            "The normals follow each cell's vertex order (in "
                            "2D: to the left of the direction from the first "
                            "to the second vertex; in 3D: right-handed in the "
                            "order of the cell's vertices around it, as "
                            "Gmsh and STL list them) and must point into the "
                            "material, otherwise set 'flip normals'. A mesh "
                            "whose neighbouring cells have opposite normals "
                            "(an edge run through in the same direction by "
                            "both), or with an edge shared by more than two "
                            "cells, is rejected [-].");
          prm.declare_entry(
            "condition",
            "fixed",
            Selection("fixed|slip|contact|friction"),
            "What the boundary imposes on the material at its particles: "
            "'fixed' (u = u_bar), 'slip' ((u - u_bar).n = 0), 'contact' "
            "((u - u_bar).n >= 0: pushes only, releases on separation), "
            "'friction' (contact with Coulomb friction, stick or slip) [-].");
          prm.declare_entry("friction coefficient",
                            "0",
                            Double(0.),
                            "Coulomb friction coefficient mu of a "
                            "'friction' boundary [-].");
          prm.declare_entry(
            "method",
            "penalty",
            Selection(
              "penalty|augmented Lagrangian|Lagrange multiplier|Nitsche"),
            "How the condition is imposed: 'penalty' (Chandra et al. 2021: "
            "a spring of stiffness beta per unit surface on the "
            "accumulated gap; the gap scales with 1/beta), or 'augmented "
            "Lagrangian' (a Lagrange multiplier per boundary particle, or "
            "per cell with constraint = per cell, added to the same spring "
            "and updated by Uzawa iterations after each converged Newton "
            "solve until the gap is below 'multiplier tolerance': the "
            "constraint holds independently of beta, at the cost of more "
            "Newton solves per step), or 'Lagrange multiplier' (the "
            "multipliers, per particle or per cell with constraint = per "
            "cell, are unknowns of the Newton iteration next to the "
            "displacements: the saddle-point system of each iteration is "
            "solved through its Schur complement on the multipliers with "
            "GMRES, the constraint holds to 'multiplier tolerance' at "
            "convergence whatever beta, which only sets the Alart-Curnier "
            "trial force lambda - beta w g of the contact and friction "
            "decisions), or 'Nitsche' (the traction of the "
            "material at the boundary particle, -S n from the mean nominal "
            "stress of the material points of its cell, plus the penalty "
            "beta (the stabilisation, beta = factor M / h) on the gap and "
            "'Nitsche symmetry' times the adjoint term; for contact and "
            "friction the active set and the Coulomb return act on the "
            "trial force -w S n - beta w g, Chouly and Hild 2013; "
            "consistent, so the gap does not scale with 1/beta; a cell "
            "without material points falls back to penalty) [-].");
          prm.declare_entry(
            "contact side",
            "boundary particles",
            Selection("boundary particles|material points"),
            "Where a 'contact' or 'friction' condition is checked: "
            "'boundary particles' (the penalty spring of each boundary "
            "particle on the gap accumulated since material reached its "
            "cell), or 'material points' (node-to-surface contact with the "
            "material as the slave side: the lowest point x_c = x_p - r_p n "
            "of every material point's extent, the circle (sphere) of its "
            "current volume, r_p = (V0^(1/dim)/2) (det F)^(1/dim), against "
            "the tangent line or plane of the nearest boundary "
            "particle, with the geometric gap g = (x_c - x_b) . n at the "
            "start of the step plus the increment interpolated at x_c from "
            "the point's own cell, whose nodes all carry mass; penalty beta "
            "on the surface V0^((dim-1)/dim) of the point; the tangential "
            "stick spring is kept on the point). A body then touches the "
            "boundary where its material is, not where its cells are: use "
            "it for rolling bodies whose points resolve their surface (a "
            "lattice of points rolls like a polygon and bounces; see "
            "doc/verification.md). Only with method = penalty and "
            "condition = contact or friction [-].");
          prm.declare_entry(
            "contact point motion",
            "default",
            Selection("default|interpolated|with the point"),
            "contact side = material points: how the contact point x_c = "
            "x_p - r n of a material point moves within a step. 'default': "
            "'with the point' on a boundary at rest and on a coupling "
            "interface with 'interface force in time = end of step' "
            "(subsection Coupling), 'interpolated' on another moving one (a "
            "prescribed 'Displacement' or geometry = external, a coupling "
            "interface, whose kinks follow the load). "
            "'interpolated': its increment is interpolated at x_c from the "
            "nodes of the point's cell and r follows the point's current "
            "volume; the gap is measured again from the point's position at "
            "the start of every step, which differs from the gap the last "
            "step ended with where the material deforms under the contact "
            "(a granular mass sliding on the boundary: energy enters and "
            "the energy balance does not close in runs without a moving "
            "boundary, see doc/verification.md). 'with the point': x_c "
            "moves with the material point (its increment is x_p's, r = "
            "V0^(1/dim)/2 from the initial volume), so every step starts "
            "from the gap the last one ended with; a point's friction then "
            "acts at its centre, so a lattice body rolls with less torque "
            "(the rolling cylinder: 2.1 % instead of 1.0 % off at 0.4 s) "
            "[-].");
          prm.declare_entry(
            "contact damping",
            "0",
            Double(0.),
            "contact side = material points: a normal dashpot next to the "
            "penalty spring, eta [-]: a point pressed against the boundary "
            "gets the force k (-g_n - eta dg_n) with dg_n the change of its "
            "normal gap in the step (a Kelvin-Voigt contact with viscosity "
            "eta k dt), ramped in over the first 0.01 h of penetration so "
            "that the force is continuous at first contact. Meant to damp "
            "the rebound of new contacts; in the rolling-cylinder study it "
            "did not (doc/verification.md). The dissipated energy is booked "
            "with the friction. 0: the elastic spring alone.");
          prm.declare_entry(
            "Nitsche symmetry",
            "-1",
            Double(-1., 1.),
            "theta of Nitsche's method, the weight of the adjoint term: -1 "
            "skew-symmetric (stable for any stabilisation factor; the "
            "default, robust in all the rotated-incline tests), 0 "
            "incomplete, 1 symmetric (consistent and adjoint consistent, "
            "coercive only for a stabilisation above a threshold that grows "
            "without bound in small cuts: use it with the 'ghost penalty "
            "factor' of subsection Solver, e.g. 1, and penalty factor >= "
            "10; without the ghost penalty it failed in Newton on the "
            "rotated inclines, see doc/verification.md) [-].");
          prm.declare_entry(
            "penalty factor",
            "100",
            Double(0.),
            "Automatic penalty beta = factor * M / h, with M the P-wave "
            "modulus of the material and h the smallest background cell "
            "size; the penetration under a normal stress sigma is about "
            "sigma h / (factor M) [-].");
          prm.declare_entry(
            "constraint",
            "default",
            Selection("default|per particle|per cell"),
            "Where the condition holds: 'per particle' (at every boundary "
            "particle) or 'per cell' (for the weighted mean gap of the "
            "particles of one boundary in one background cell: one "
            "constraint per cell, the penalty form of cell-wise constant "
            "Lagrange multipliers, Singer et al. 2024; avoids the "
            "over-constraint of bilinear fields by many points on a "
            "boundary inclined to the grid); 'default' is per cell for "
            "method = Lagrange multiplier (which does not allow per "
            "particle) and per particle for the other methods [-].");
          prm.declare_entry("penalty parameter",
                            "0",
                            Double(0.),
                            "Penalty beta given directly [Pa/m]; 0 uses the "
                            "automatic value of 'penalty factor'.");
          prm.declare_entry(
            "particles per cell",
            "2",
            Integer(1, 10),
            "Boundary particles per background cell length: the surface "
            "mesh is refined to the smallest background cell size and this "
            "many Gauss points are placed per surface cell and direction "
            "(on triangles of a 3D mesh: 1, 3, 6, 12, 16, 25, 33, 42 points "
            "for 1 to 8, symmetric Witherden-Vincent rules; at most 8). "
            "On curved walls use 1: two particles with different normals "
            "in one cell lock rotations of the material along the wall "
            "(doc/verification.md) [-].");
          prm.enter_subsection("Displacement");
          dealii::Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
          prm.set("Function expression", dim == 2 ? "0; 0" : "0; 0; 0");
          prm.leave_subsection();
          prm.leave_subsection();
        }
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryParticles<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      boundaries.clear();
      prm.enter_subsection("Boundary particles");
      relative_gap_tolerance = prm.get_double("multiplier tolerance");
      if (!(relative_gap_tolerance > 0.))
        InputFile::reject("Boundary particles",
                          "multiplier tolerance",
                          prm.get("multiplier tolerance"),
                          "a positive number");
      max_updates = prm.get_integer("maximum multiplier updates");
      for (unsigned int k = 0; declared_slot(prm, k); ++k)
        {
          const std::string sub = "Boundary particles/" + slot_name(k);
          prm.enter_subsection(slot_name(k));
          BoundaryDescription<dim> b;
          b.slot     = k;
          b.geometry = prm.get("geometry");
          if (b.geometry == "none")
            {
              prm.leave_subsection();
              continue;
            }
          b.name = prm.get("name");
          if (b.name.empty() ||
              b.name.find_first_of(", \t\"") != std::string::npos)
            InputFile::reject(sub,
                              "name",
                              b.name,
                              "a non-empty name without spaces, commas or "
                              "quotes (it names CSV columns)");
          for (const auto &other : boundaries)
            if (other.name == b.name)
              InputFile::reject(sub,
                                "name",
                                b.name,
                                "a name not used by another boundary");
          const std::string condition = prm.get("condition");
          b.condition            = condition == "fixed"   ? Condition::fixed :
                                   condition == "slip"    ? Condition::slip :
                                   condition == "contact" ? Condition::contact :
                                                            Condition::friction;
          b.friction_coefficient = prm.get_double("friction coefficient");
          if (b.condition == Condition::friction &&
              !(b.friction_coefficient > 0.))
            InputFile::reject(sub,
                              "friction coefficient",
                              prm.get("friction coefficient"),
                              "a positive number for condition = friction "
                              "(use 'contact' for frictionless contact)");
          b.method              = prm.get("method");
          b.augmented           = b.method == "augmented Lagrangian";
          b.lagrange_multiplier = b.method == "Lagrange multiplier";
          b.nitsche             = b.method == "Nitsche";
          b.nitsche_theta       = prm.get_double("Nitsche symmetry");
          b.material_point_contact =
            prm.get("contact side") == "material points";
          b.contact_damping = prm.get_double("contact damping");
          const std::string contact_point_motion =
            prm.get("contact point motion");
          if (contact_point_motion != "default" && !b.material_point_contact)
            InputFile::reject(sub,
                              "contact point motion",
                              contact_point_motion,
                              "'default' unless contact side = material "
                              "points");
          if (b.contact_damping > 0. && !b.material_point_contact)
            InputFile::reject(sub,
                              "contact damping",
                              prm.get("contact damping"),
                              "0 unless contact side = material points");
          if (b.material_point_contact && (b.condition == Condition::fixed ||
                                           b.condition == Condition::slip))
            InputFile::reject(sub,
                              "contact side",
                              prm.get("contact side"),
                              "'boundary particles' for condition = " +
                                condition +
                                " ('material points' needs condition = "
                                "contact or friction)");
          if (b.material_point_contact && b.method != "penalty")
            InputFile::reject(sub,
                              "contact side",
                              prm.get("contact side"),
                              "'boundary particles' for method = " + b.method +
                                " ('material points' needs method = "
                                "penalty)");
          b.penalty_factor    = prm.get_double("penalty factor");
          b.penalty_parameter = prm.get_double("penalty parameter");
          if (!(b.penalty_factor > 0.))
            InputFile::reject(sub,
                              "penalty factor",
                              prm.get("penalty factor"),
                              "a positive number");
          b.particles_per_cell = prm.get_integer("particles per cell");
          // Lagrange multipliers are cell-wise constant: one multiplier per
          // boundary particle over-determines the bilinear field of a cut
          // cell (two constraints on a cell with one massive node), and
          // the saddle-point system becomes singular.
          if (b.lagrange_multiplier && prm.get("constraint") == "per particle")
            InputFile::reject(
              sub,
              "constraint",
              prm.get("constraint"),
              "method = Lagrange multiplier needs 'per cell' or 'default' "
              "(cell-wise constant multipliers, Singer et al. 2024: one per "
              "boundary particle makes the saddle-point system singular in "
              "cut cells)");
          b.cellwise =
            prm.get("constraint") == "per cell" ||
            (prm.get("constraint") == "default" && b.lagrange_multiplier);
          if (b.cellwise && b.material_point_contact)
            InputFile::reject(sub,
                              "constraint",
                              prm.get("constraint"),
                              "'default' or 'per particle' for contact side "
                              "= material points (the contact is checked at "
                              "the material points, not at the boundary "
                              "particles of a cell)");
          b.flip_normals    = prm.get_bool("flip normals");
          b.material_inside = prm.get("material side") == "inside";

          if (b.geometry == "line" || b.geometry == "plane")
            {
              b.vertices = parse_point_list<dim>(prm, sub, "vertices");
              if (b.geometry == "line" && b.vertices.size() < 2)
                InputFile::reject(sub,
                                  "vertices",
                                  prm.get("vertices"),
                                  "a line needs at least 2 points");
              if (b.geometry == "plane" && b.vertices.size() != 3)
                InputFile::reject(sub,
                                  "vertices",
                                  prm.get("vertices"),
                                  "a plane needs exactly 3 points p0; p1; p2");
              for (unsigned int i = 1; i < b.vertices.size(); ++i)
                if (b.vertices[i].distance(b.vertices[i - 1]) <= 0. ||
                    (b.geometry == "plane" &&
                     b.vertices[i].distance(b.vertices[0]) <= 0.))
                  InputFile::reject(sub,
                                    "vertices",
                                    prm.get("vertices"),
                                    "distinct points (a segment or an edge "
                                    "of zero length has no normal)");
              if (dim == 3 && b.geometry == "plane")
                {
                  const dealii::Tensor<1, dim> n =
                    dealii::cross_product_3d(b.vertices[1] - b.vertices[0],
                                             b.vertices[2] - b.vertices[0]);
                  if (!(n.norm() >
                        1e-12 * (b.vertices[1] - b.vertices[0]).norm_square()))
                    InputFile::reject(sub,
                                      "vertices",
                                      prm.get("vertices"),
                                      "three points that are not on one line");
                }
            }
          else if (b.geometry == "circle")
            {
              b.center = MPM::parse_point<dim>(prm, sub, "center");
              b.radius = prm.get_double("radius");
              if (!(b.radius > 0.))
                InputFile::reject(sub,
                                  "radius",
                                  prm.get("radius"),
                                  "a positive radius");
            }
          else if (b.geometry == "box")
            {
              const auto box = MPM::parse_box<dim>(prm, sub);
              b.lower_corner = box.first;
              b.upper_corner = box.second;
            }
          else if (b.geometry == "mesh")
            {
              b.mesh_file = prm.get("mesh file");
              std::ifstream in(b.mesh_file);
              if (!in)
                InputFile::reject(sub,
                                  "mesh file",
                                  b.mesh_file,
                                  "a readable surface mesh file");
            }

          prm.enter_subsection("Displacement");
          b.displacement =
            std::make_unique<dealii::Functions::ParsedFunction<dim>>(dim);
          parse_function(prm, *b.displacement, sub + "/Displacement");
          b.moving =
            prm.get("Function expression") != (dim == 2 ? "0; 0" : "0; 0; 0");
          b.contact_point_with_point =
            b.material_point_contact &&
            (contact_point_motion == "with the point" ||
             (contact_point_motion == "default" && !b.moving &&
              b.geometry != "external"));
          b.contact_point_motion_default = contact_point_motion == "default";
          prm.leave_subsection();
          prm.leave_subsection();
          boundaries.push_back(std::move(b));
        }
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryParticles<dim>::make_surface(
      const BoundaryDescription<dim>      &b,
      const unsigned int                   index,
      dealii::Triangulation<dim - 1, dim> &surface) const
    {
      const std::string sub = "Boundary particles/" + slot_name(index);
      if (b.geometry == "line" || b.geometry == "plane")
        {
          std::vector<dealii::CellData<dim - 1>> cells;
          std::vector<dealii::Point<dim>>        vertices = b.vertices;
          if (dim == 2)
            for (unsigned int i = 0; i + 1 < vertices.size(); ++i)
              {
                dealii::CellData<dim - 1> c;
                c.vertices[0] = i;
                c.vertices[1] = i + 1;
                cells.push_back(c);
              }
          else
            {
              vertices.push_back(vertices[1] + (vertices[2] - vertices[0]));
              dealii::CellData<dim - 1> c;
              for (unsigned int v = 0; v < 4; ++v)
                c.vertices[v] = v;
              cells.push_back(c);
            }
          surface.create_triangulation(vertices, cells, dealii::SubCellData());
        }
      else if (b.geometry == "circle")
        {
          if constexpr (dim == 2)
            dealii::GridGenerator::hyper_sphere(surface, b.center, b.radius);
        }
      else if (b.geometry == "box")
        {
          dealii::Triangulation<dim> volume;
          dealii::GridGenerator::hyper_rectangle(volume,
                                                 b.lower_corner,
                                                 b.upper_corner);
          dealii::GridGenerator::extract_boundary_mesh(volume, surface);
        }
      else if (b.geometry == "external")
        {
          if (b.external_surface == nullptr)
            InputFile::reject(sub,
                              "geometry",
                              b.geometry,
                              "a geometry this input can describe: "
                              "'external' needs a surface that the program "
                              "hands over with "
                              "BoundaryParticles::set_surface(), as the "
                              "structure coupling does; the talus "
                              "application alone has none");
          surface.copy_triangulation(*b.external_surface);
        }
      else
        {
          dealii::GridIn<dim - 1, dim> in(surface);
          const bool                   stl = has_stl_extension(b.mesh_file);
          if (stl && dim == 2)
            InputFile::reject(sub,
                              "mesh file",
                              b.mesh_file,
                              "in 2D a mesh of lines (Gmsh .msh, .vtk, "
                              ".inp); STL files hold triangles, for 3D");
          try
            {
              if (stl)
                {
#ifdef DEAL_II_GMSH_WITH_API
                  // Gmsh opens the STL as a discrete surface of triangles
                  // and merges the facets' shared vertices.
                  in.read_msh(b.mesh_file);
#else
                  InputFile::reject(sub,
                                    "mesh file",
                                    b.mesh_file,
                                    "a Gmsh .msh, .vtk or .inp file (this "
                                    "deal.II has no Gmsh API to read STL)");
#endif
                }
              else
                // format from the file name's extension (.msh, .vtk, .inp)
                in.read(b.mesh_file);
            }
          catch (const dealii::ExceptionBase &e)
            {
              std::ostringstream info;
              e.print_info(info);
              InputFile::reject(
                sub,
                "mesh file",
                b.mesh_file,
                "a surface mesh deal.II can read (Gmsh .msh, "
                ".vtk, .inp) with cells of dimension " +
                  std::to_string(dim - 1) + " (" +
                  dealii::Utilities::trim(info.str()).substr(0, 300) + ")");
            }
          catch (const std::exception &e)
            {
              InputFile::reject(
                sub,
                "mesh file",
                b.mesh_file,
                "a surface mesh deal.II can read (Gmsh .msh, "
                ".vtk, .inp) with cells of dimension " +
                  std::to_string(dim - 1) + " (" +
                  dealii::Utilities::trim(e.what()).substr(0, 300) + ")");
            }
          if (surface.n_active_cells() == 0)
            InputFile::reject(sub,
                              "mesh file",
                              b.mesh_file,
                              "a surface mesh with at least one cell");
        }
      if (b.geometry == "mesh" || b.geometry == "external")
        {
          const bool        read     = b.geometry == "mesh";
          const std::string conflict = orientation_conflict(surface);
          if (!conflict.empty())
            InputFile::reject(sub,
                              read ? "mesh file" : "geometry",
                              read ? b.mesh_file : b.geometry,
                              "a surface mesh with consistent normals, each "
                              "edge shared by at most two cells (" +
                                std::string(read ? "" :
                                                   "the surface given to "
                                                   "set_surface(): ") +
                                conflict + ")");
        }
      // Refine until no surface cell is larger than the smallest grid cell.
      // The built-in shapes are refined globally (their cells have one
      // size); a mesh of the user or the program cell by cell, so that the
      // small cells of a graded mesh (a terrain, a net refined at its
      // edges) are not refined with the largest ones (the particles need
      // no conforming surface, hanging nodes are harmless).
      double h = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        h = std::min(h,
                     grid.is_cartesian ? grid.cell_extent[d] :
                                         grid.minimal_cell_diameter);
      const bool graded = b.geometry == "mesh" || b.geometry == "external";
      for (unsigned int level = 0; level < 20; ++level)
        {
          bool too_large = false;
          for (const auto &cell : surface.active_cell_iterators())
            if (cell->diameter() > 1.0001 * h)
              {
                too_large = true;
                if (graded)
                  cell->set_refine_flag();
              }
          if (!too_large)
            break;
          if (graded)
            surface.execute_coarsening_and_refinement();
          else
            surface.refine_global(1);
        }
    }


    template <int dim>
    dealii::Tensor<1, dim>
    BoundaryParticles<dim>::orient(const BoundaryDescription<dim> &b,
                                   const dealii::Point<dim>       &x,
                                   const dealii::Tensor<1, dim>   &n_mesh) const
    {
      // (a line's normal is oriented per segment in generate())
      dealii::Tensor<1, dim> n = n_mesh / n_mesh.norm();
      if (b.geometry == "circle" || b.geometry == "box")
        {
          // Outward from the center, then into the material.
          const dealii::Point<dim> c =
            b.geometry == "circle" ?
              b.center :
              dealii::Point<dim>(0.5 * (b.lower_corner + b.upper_corner));
          if (n * (x - c) < 0.)
            n = -n;
          if (b.material_inside)
            n = -n;
        }
      else if (b.geometry == "plane")
        {
          const dealii::Tensor<1, dim> m =
            dealii::cross_product_3d(b.vertices[1] - b.vertices[0],
                                     b.vertices[2] - b.vertices[0]);
          if (n * m < 0.)
            n = -n;
        }
      if (b.flip_normals)
        n = -n;
      return n;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::generate(const double p_wave_modulus)
    {
      using Properties = BoundaryParticleProperties<dim>;
      handler.initialize(grid.triangulation,
                         grid.mapping,
                         Properties::n_properties);
      handler.signals.particle_lost.connect(
        [this](
          const typename dealii::Particles::ParticleIterator<dim> &particle,
          const typename dealii::Triangulation<dim>::active_cell_iterator &) {
          ++lost;
          const unsigned int b = static_cast<unsigned int>(
            particle->get_properties()[Properties::boundary]);
          if (b < lost_per_boundary.size())
            ++lost_per_boundary[b];
        });
      lost_per_boundary.assign(boundaries.size(), 0);
      if (boundaries.empty())
        return;

      double h = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        h = std::min(h,
                     grid.is_cartesian ? grid.cell_extent[d] :
                                         grid.minimal_cell_diameter);

      gap_tolerance = relative_gap_tolerance * h;
      const bool root =
        dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) == 0;
      std::vector<dealii::Point<dim>>  points;
      std::vector<std::vector<double>> properties;
      std::vector<unsigned int>        n_made(boundaries.size(), 0);
      for (unsigned int b = 0; b < boundaries.size(); ++b)
        {
          auto &desc = boundaries[b];
          desc.beta  = desc.penalty_parameter > 0. ?
                         desc.penalty_parameter :
                         desc.penalty_factor * p_wave_modulus / h;
          // Every rank builds the (small) surface; rank 0 inserts it.
          dealii::Triangulation<dim - 1, dim> surface;
          make_surface(desc, b, surface);
          const auto flags = dealii::update_quadrature_points |
                             dealii::update_JxW_values |
                             dealii::update_normal_vectors;
          const dealii::QGauss<dim - 1>   quadrature(desc.particles_per_cell);
          dealii::FE_Q<dim - 1, dim>      fe(1);
          dealii::MappingQ1<dim - 1, dim> mapping;
          dealii::FEValues<dim - 1, dim>  fe_values(mapping,
                                                   fe,
                                                   quadrature,
                                                   flags);
          // Triangles of a triangulated surface (3D only): P1 geometry.
          std::unique_ptr<dealii::FiniteElement<dim - 1, dim>> fe_triangle;
          std::unique_ptr<dealii::Mapping<dim - 1, dim>>       mapping_triangle;
          std::unique_ptr<dealii::FEValues<dim - 1, dim>>      values_triangle;
          if constexpr (dim == 3)
            if (!surface.all_reference_cells_are_hyper_cube())
              {
                if (desc.particles_per_cell > 8)
                  InputFile::reject("Boundary particles/" + slot_name(b),
                                    "particles per cell",
                                    std::to_string(desc.particles_per_cell),
                                    "at most 8 on a surface mesh of "
                                    "triangles");
                fe_triangle =
                  std::make_unique<dealii::FE_SimplexP<dim - 1, dim>>(1);
                mapping_triangle =
                  std::make_unique<dealii::MappingFE<dim - 1, dim>>(
                    *fe_triangle);
                values_triangle =
                  std::make_unique<dealii::FEValues<dim - 1, dim>>(
                    *mapping_triangle,
                    *fe_triangle,
                    triangle_quadrature(desc.particles_per_cell),
                    flags);
              }
          for (const auto &cell : surface.active_cell_iterators())
            {
              dealii::FEValues<dim - 1, dim> &values =
                cell->reference_cell().is_hyper_cube() ? fe_values :
                                                         *values_triangle;
              values.reinit(cell);
              for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
                {
                  const auto            &x = values.quadrature_point(q);
                  dealii::Tensor<1, dim> n = values.normal_vector(q);
                  if (desc.geometry == "line")
                    {
                      // left of the direction of travel of this segment
                      const dealii::Tensor<1, dim> t =
                        cell->vertex(1) - cell->vertex(0);
                      dealii::Tensor<1, dim> left;
                      left[0] = -t[1];
                      left[1] = t[0];
                      if (n * left < 0.)
                        n = -n;
                    }
                  n = orient(desc, x, n);
                  ++n_made[b];
                  if (!root)
                    continue;
                  const dealii::Point<dim> X =
                    off_faces(x + prescribed_displacement(b, x, 0.), n);
                  std::vector<double> prop(Properties::n_properties, 0.);
                  prop[Properties::boundary] = b;
                  prop[Properties::weight]   = values.JxW(q);
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      prop[Properties::normal + d]             = n[d];
                      prop[Properties::reference_position + d] = x[d];
                    }
                  points.push_back(X);
                  properties.push_back(std::move(prop));
                }
            }
        }

      // Boxes of level 1, or of level 0 on an unrefined grid: deal.II
      // asserts (Debug) that the level exists.
      const auto global_boxes = grid.global_bounding_boxes();
      handler.insert_global_particles(points, global_boxes, properties);
      handler.update_cached_numbers();

      // Count the inserted particles per boundary.
      std::vector<unsigned int> inserted(boundaries.size(), 0);
      for (const auto &p : handler)
        ++inserted[static_cast<unsigned int>(
          p.get_properties()[Properties::boundary])];
      MPI_Allreduce(MPI_IN_PLACE,
                    inserted.data(),
                    inserted.size(),
                    MPI_UNSIGNED,
                    MPI_SUM,
                    grid.mpi_communicator);
      for (unsigned int b = 0; b < boundaries.size(); ++b)
        {
          if (inserted[b] == 0)
            InputFile::reject("Boundary particles/" + slot_name(b),
                              "geometry",
                              boundaries[b].geometry,
                              "a boundary that lies (at least partly) inside "
                              "the background grid: none of its " +
                                std::to_string(n_made[b]) +
                                " particles is in a grid cell");
          if (root && inserted[b] < n_made[b])
            std::cout << "  boundary " << boundaries[b].name << ": "
                      << n_made[b] - inserted[b] << " of " << n_made[b]
                      << " particles lie outside the background grid and "
                         "are ignored"
                      << std::endl;
        }
    }


    template <int dim>
    dealii::Point<dim>
    BoundaryParticles<dim>::off_faces(const dealii::Point<dim>     &x,
                                      const dealii::Tensor<1, dim> &n) const
    {
      if (!grid.is_cartesian)
        return x;
      // A particle on a face of the Cartesian grid would belong to either
      // cell (deal.II picks one); move it by 1e-6 h into the material so
      // that it acts in the cell the material fills.
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double r = (x[d] - grid.lower_corner[d]) / grid.cell_extent[d];
          if (std::abs(r - std::round(r)) < 1e-6)
            return x + 1e-6 * grid.cell_extent.norm() * n;
        }
      return x;
    }


    template <int dim>
    dealii::Tensor<1, dim>
    BoundaryParticles<dim>::prescribed_displacement(const unsigned int        b,
                                                    const dealii::Point<dim> &X,
                                                    const double t) const
    {
      dealii::Tensor<1, dim> u;
      if (!boundaries[b].moving)
        return u;
      if (boundaries[b].external_displacement)
        return boundaries[b].external_displacement(X, t);
      boundaries[b].displacement->set_time(t);
      for (unsigned int d = 0; d < dim; ++d)
        u[d] = boundaries[b].displacement->value(X, d);
      return u;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::set_displacement(
      const unsigned int                                         b,
      const std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &,
                                                 const double)> &u)
    {
      AssertThrow(b < boundaries.size() && u,
                  dealii::ExcMessage("set_displacement() needs an existing "
                                     "boundary and a callable function"));
      boundaries[b].external_displacement = u;
      boundaries[b].moving                = true;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::set_end_of_step_force(const unsigned int b)
    {
      AssertThrow(b < boundaries.size(),
                  dealii::ExcMessage("set_end_of_step_force() needs an "
                                     "existing boundary"));
      boundaries[b].end_of_step_force = true;
      if (boundaries[b].contact_point_motion_default &&
          boundaries[b].material_point_contact)
        boundaries[b].contact_point_with_point = true;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::set_surface(
      const unsigned int                         b,
      const dealii::Triangulation<dim - 1, dim> &surface)
    {
      AssertThrow(b < boundaries.size() && boundaries[b].geometry == "external",
                  dealii::ExcMessage("set_surface() needs a boundary with "
                                     "geometry = external"));
      AssertThrow(surface.n_active_cells() > 0,
                  dealii::ExcMessage("set_surface() needs a surface with "
                                     "at least one cell"));
      auto flat = std::make_shared<dealii::Triangulation<dim - 1, dim>>();
      dealii::GridGenerator::flatten_triangulation(surface, *flat);
      boundaries[b].external_surface = flat;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::move_to(const double t)
    {
      using Properties = BoundaryParticleProperties<dim>;
      bool any_moving  = false;
      for (const auto &b : boundaries)
        any_moving = any_moving || b.moving;
      if (!any_moving)
        return;
      for (auto &p : handler)
        {
          const auto         props = p.get_properties();
          const unsigned int b =
            static_cast<unsigned int>(props[Properties::boundary]);
          if (!boundaries[b].moving)
            continue;
          dealii::Point<dim> X;
          for (unsigned int d = 0; d < dim; ++d)
            X[d] = props[Properties::reference_position + d];
          dealii::Tensor<1, dim> n;
          for (unsigned int d = 0; d < dim; ++d)
            n[d] = props[Properties::normal + d];
          p.set_location(off_faces(X + prescribed_displacement(b, X, t), n));
        }
      handler.sort_particles_into_subdomains_and_cells();
    }


    template <int dim>
    std::vector<unsigned int>
    BoundaryParticles<dim>::take_lost_per_boundary()
    {
      std::vector<unsigned int> n(lost_per_boundary.size(), 0);
      for (unsigned int b = 0; b < n.size(); ++b)
        n[b] = dealii::Utilities::MPI::sum(lost_per_boundary[b],
                                           grid.mpi_communicator);
      std::fill(lost_per_boundary.begin(), lost_per_boundary.end(), 0u);
      return n;
    }


    template <int dim>
    std::vector<BoundaryResultant<dim>>
    BoundaryParticles<dim>::resultants() const
    {
      using Properties = BoundaryParticleProperties<dim>;
      std::vector<BoundaryResultant<dim>> r(boundaries.size());
      std::vector<dealii::Tensor<1, dim>> tangential(boundaries.size());
      for (const auto &p : handler)
        {
          const auto         props = p.get_properties();
          const unsigned int b =
            static_cast<unsigned int>(props[Properties::boundary]);
          if (props[Properties::state] == 0.)
            continue;
          dealii::Tensor<1, dim> R, n, g;
          for (unsigned int d = 0; d < dim; ++d)
            {
              R[d] = props[Properties::reaction + d];
              n[d] = props[Properties::normal + d];
              g[d] = props[Properties::gap + d];
            }
          r[b].force += R;
          r[b].normal_force -= R * n;
          tangential[b] += R - (R * n) * n;
          r[b].penetration = std::max(r[b].penetration, -(g * n));
          r[b].spring_energy +=
            0.5 * boundaries[b].beta * props[Properties::weight] * (g * g);
          ++r[b].active;
        }
      for (unsigned int b = 0; b < point_contact.size() && b < r.size(); ++b)
        {
          r[b].force += point_contact[b].force;
          r[b].normal_force += point_contact[b].normal_force;
          tangential[b] += point_contact_tangential[b];
          r[b].penetration =
            std::max(r[b].penetration, point_contact[b].penetration);
          r[b].active += point_contact[b].active;
          r[b].spring_energy += point_contact[b].spring_energy;
        }
      const MPI_Comm comm = grid.mpi_communicator;
      for (unsigned int b = 0; b < boundaries.size(); ++b)
        {
          r[b].force = dealii::Utilities::MPI::sum(r[b].force, comm);
          r[b].normal_force =
            dealii::Utilities::MPI::sum(r[b].normal_force, comm);
          r[b].tangential_force =
            dealii::Utilities::MPI::sum(tangential[b], comm).norm();
          r[b].penetration =
            dealii::Utilities::MPI::max(r[b].penetration, comm);
          r[b].active = dealii::Utilities::MPI::sum(r[b].active, comm);
          r[b].spring_energy =
            dealii::Utilities::MPI::sum(r[b].spring_energy, comm);
        }
      return r;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::clear_point_contact()
    {
      point_contact.assign(boundaries.size(), BoundaryResultant<dim>());
      point_contact_tangential.assign(boundaries.size(),
                                      dealii::Tensor<1, dim>());
    }


    template <int dim>
    void
    BoundaryParticles<dim>::record_point_contact(
      const unsigned int            b,
      const dealii::Tensor<1, dim> &reaction,
      const dealii::Tensor<1, dim> &normal,
      const double                  penetration,
      const double                  spring_energy)
    {
      if (point_contact.size() != boundaries.size())
        clear_point_contact();
      AssertIndexRange(b, boundaries.size());
      point_contact[b].force += reaction;
      point_contact[b].normal_force -= reaction * normal;
      point_contact_tangential[b] += reaction - (reaction * normal) * normal;
      point_contact[b].penetration =
        std::max(point_contact[b].penetration, penetration);
      point_contact[b].spring_energy += spring_energy;
      ++point_contact[b].active;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::save_state()
    {
      backup.copy_from(handler);
      backup_lost              = lost;
      backup_lost_per_boundary = lost_per_boundary;
      saved                    = true;
    }


    template <int dim>
    void
    BoundaryParticles<dim>::restore_state()
    {
      AssertThrow(saved,
                  dealii::ExcMessage("BoundaryParticles::restore_state() "
                                     "without a preceding save_state()"));
      handler.copy_from(backup);
      lost              = backup_lost;
      lost_per_boundary = backup_lost_per_boundary;
    }


    template <int dim>
    GatheredSurface<dim>
    BoundaryParticles<dim>::gather_surface(const unsigned int b) const
    {
      using Properties = BoundaryParticleProperties<dim>;
      std::vector<double> local;
      for (const auto &p : handler)
        {
          const auto props = p.get_properties();
          if (static_cast<unsigned int>(props[Properties::boundary]) != b)
            continue;
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(p.get_location()[d]);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(props[Properties::normal + d]);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(props[Properties::reference_position + d]);
          local.push_back(static_cast<double>(p.get_id()));
        }
      GatheredSurface<dim>   surface;
      constexpr unsigned int stride = 3 * dim + 1;
      for (const auto &part :
           dealii::Utilities::MPI::all_gather(grid.mpi_communicator, local))
        for (unsigned int k = 0; k + stride <= part.size(); k += stride)
          {
            dealii::Point<dim>     x, X;
            dealii::Tensor<1, dim> n;
            for (unsigned int d = 0; d < dim; ++d)
              {
                x[d] = part[k + d];
                n[d] = part[k + dim + d];
                X[d] = part[k + 2 * dim + d];
              }
            surface.x.push_back(x);
            surface.n.push_back(n);
            surface.X.push_back(X);
            surface.id.push_back(
              static_cast<dealii::types::particle_index>(part[k + 3 * dim]));
          }
      return surface;
    }


    template class BoundaryParticles<2>;
    template class BoundaryParticles<3>;
  } // namespace Boundaries
} // namespace Talus
