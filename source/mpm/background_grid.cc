#include <talus/base/input.h>
#include <talus/mpm/background_grid.h>

#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    dealii::Point<dim>
    parse_point(const dealii::ParameterHandler &prm,
                const std::string              &subsection,
                const std::string              &entry)
    {
      std::vector<double> values;
      try
        {
          values = dealii::Utilities::string_to_double(
            dealii::Utilities::split_string_list(prm.get(entry), ','));
        }
      catch (...)
        {
          values.clear();
        }
      if (values.size() != dim)
        InputFile::reject(
          subsection,
          entry,
          prm.get(entry),
          "it must be a list of " + std::to_string(dim) +
            " numbers (one per coordinate) separated by commas");
      dealii::Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = values[d];
      return p;
    }


    template <int dim>
    std::pair<dealii::Point<dim>, dealii::Point<dim>>
    parse_box(const dealii::ParameterHandler &prm,
              const std::string              &subsection)
    {
      const auto lower = parse_point<dim>(prm, subsection, "lower corner");
      const auto upper = parse_point<dim>(prm, subsection, "upper corner");
      for (unsigned int d = 0; d < dim; ++d)
        if (!(upper[d] > lower[d]))
          InputFile::reject(subsection,
                            "upper corner",
                            prm.get("upper corner"),
                            "every coordinate must be larger than the lower "
                            "corner's (" +
                              prm.get("lower corner") + ")");
      return {lower, upper};
    }


    template <int dim>
    BackgroundGrid<dim>::BackgroundGrid(const MPI_Comm communicator)
      : mpi_communicator(communicator)
      , triangulation(communicator)
      , fe(dealii::FE_Q<dim>(1), dim)
      , dof_handler(triangulation)
      , is_cartesian(false)
      , minimal_cell_diameter(0.)
    {}


    template <int dim>
    void
    BackgroundGrid<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Anything;
      using dealii::Patterns::Double;
      using dealii::Patterns::FileName;
      using dealii::Patterns::Integer;
      using dealii::Patterns::List;
      using dealii::Patterns::Selection;
      prm.enter_subsection("Background grid");
      {
        prm.declare_entry(
          "type",
          "box",
          Selection("box|gmsh"),
          "How the fixed background grid is made: 'box' is an "
          "axis-aligned box subdivided into equal cells, 'gmsh' "
          "reads a quadrilateral (2D) or hexahedral (3D) mesh "
          "from 'mesh file'.");
        prm.declare_entry("lower corner",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Anything(),
                          "Lower corner of the box [m], one coordinate per "
                          "dimension separated by commas.");
        prm.declare_entry(
          "upper corner",
          dim == 2 ? "1, 1" : "1, 1, 1",
          Anything(),
          "Upper corner of the box [m]; each coordinate must be "
          "larger than the lower corner's.");
        prm.declare_entry("subdivisions",
                          dim == 2 ? "10, 10" : "10, 10, 10",
                          List(Integer(1), dim, dim, ","),
                          "Number of cells of the box per direction [-], "
                          ">= 1 each.");
        prm.declare_entry("mesh file",
                          "",
                          FileName(),
                          "Gmsh (.msh) file of the background grid for type = "
                          "gmsh; relative paths are relative to the working "
                          "directory.");
        prm.declare_entry(
          "fixed boundaries",
          "",
          List(Integer(0, 255), 0, 255, ","),
          "Boundary ids on which all displacement components are zero "
          "(conforming Dirichlet condition). Box ids: 0/1 x-min/x-max, "
          "2/3 y-min/y-max, 4/5 z-min/z-max.");
        prm.declare_entry(
          "fixed region lower corner",
          "",
          Anything(),
          "Lower corner of a box of fixed grid nodes [m], one coordinate per "
          "dimension separated by commas: if given (with 'fixed region upper "
          "corner'), every grid node inside the box, on the grid's boundary "
          "or inside it, is fixed (all displacement components zero), in "
          "addition to the nodes of the 'fixed boundaries'. Example: the "
          "root face of a clamped beam, x = 0 and 0 <= y <= H, in a grid "
          "that extends to x < 0 (only the root is held, not a whole wall). "
          "A box of zero width in a direction (lower = upper coordinate) is "
          "a line or face of nodes. Empty (default): none. The box must "
          "enclose at least one grid node.");
        prm.declare_entry("fixed region upper corner",
                          "",
                          Anything(),
                          "Upper corner of the box of fixed nodes [m] (see "
                          "'fixed region lower corner'); no coordinate below "
                          "the lower corner's.");
        prm.declare_entry(
          "slip boundaries",
          "",
          List(Integer(0, 255), 0, 255, ","),
          "Boundary ids on which the normal displacement is zero and the "
          "tangential motion is free (frictionless slip); the faces must be "
          "axis aligned.");
        prm.declare_entry(
          "friction boundaries",
          "",
          Anything(),
          "Axis-aligned boundaries with Coulomb friction, as a comma-separated "
          "list of 'id: mu' pairs (boundary id, friction coefficient mu >= 0 "
          "[-]), e.g. '2: 0.3'. On the grid nodes of these faces the normal "
          "displacement is zero while the contact force is compressive (the "
          "node is released when the boundary would have to pull); "
          "tangentially a node sticks (zero velocity) while the tangential "
          "reaction stays within mu times the normal force, and otherwise "
          "slips with the friction force mu times the normal force opposing "
          "its velocity. The states are updated inside the Newton iteration "
          "(doc/theory.md, 'Coulomb friction on grid boundaries'). Nodes on two "
          "such boundaries (corners) are fixed.");
        prm.declare_entry(
          "friction separation",
          "velocity",
          Selection("pressure|velocity"),
          "When a node of a friction boundary leaves it [-]. 'velocity': a "
          "node whose projected velocity leaves the boundary fast enough to "
          "lift off by a resolved height, v_n^2 / (2 g_n) > 'separation lift "
          "height' x h (g_n: the part of gravity pushing into the boundary, h "
          "the cell size), and faster than gravity brings it back within the "
          "step (v_n > dt g_n / 2), starts the step free, as in explicit MPM "
          "contact (Bardenhagen et al. 2000); every other node with mass "
          "starts in contact. 'pressure': every node with mass starts in "
          "contact (its normal velocity is reset to zero). In both, a node is "
          "released during the step when the boundary would have to pull. "
          "'pressure' removes separating velocity without friction, so "
          "rebounds are too frictional (impact test: tangential impulse 2.5x "
          "mu times the normal one; doc/theory.md, 'Impact and separation on "
          "friction floors').");
        prm.declare_entry(
          "friction state guess",
          "velocity",
          Selection("velocity|previous step"),
          "The contact state a node of a friction boundary starts a step in, "
          "the first guess of the active set that the Newton iteration then "
          "corrects [-]. 'velocity': slipping if its projected velocity (or "
          "acceleration) has a tangential part, stuck only at rest. 'previous "
          "step' (the active set warm-started from the last step): a node "
          "that ended the previous step stuck starts stuck if friction under "
          "its weight can stop its projected tangential velocity within the "
          "step (|v_t| <= mu g_n dt, g_n the part of gravity into the "
          "boundary); the others as with 'velocity'. Under material at rest "
          "the projected velocity is never exactly zero, so 'velocity' starts "
          "those nodes slipping and the iteration sticks them again. The "
          "converged states obey Coulomb's law either way, within the "
          "tolerances of the state updates (doc/theory.md); at the kink of "
          "the law both states can be admissible, and a node keeps the state "
          "it started in. 'previous step' saves a third of the Newton "
          "iterations of the granular collapse benchmarks (which use it), but "
          "the bouncing layer of tests/granular/cohesive_layer_at_rest (sudden "
          "gravity, no step halvings) fails to converge with it, hence not "
          "the default (doc/performance.md, 'Granular collapse: time to "
          "solution').");
        prm.declare_entry(
          "separation lift height",
          "0.05",
          Double(0.),
          "With 'friction separation = velocity': the smallest ballistic "
          "lift-off height v_n^2 / (2 g_n), as a fraction of the cell size, "
          "for which a node starts a step free [-]. Smaller lifts are below "
          "the grid's resolution; the projected normal velocity of floor "
          "nodes under a granular flow is noisy at this level, and a zero "
          "value makes the collapse runout grow as the step shrinks. Without "
          "gravity into the boundary every separating node starts free.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    BackgroundGrid<dim>::parse_parameters_and_create(
      dealii::ParameterHandler &prm)
    {
      const std::string sub = "Background grid";
      prm.enter_subsection(sub);
      type           = prm.get("type");
      const auto ids = [&](const std::string &entry) {
        std::set<dealii::types::boundary_id> result;
        for (const auto &s :
             dealii::Utilities::split_string_list(prm.get(entry), ','))
          result.insert(dealii::Utilities::string_to_int(s));
        return result;
      };
      fixed_boundaries = ids("fixed boundaries");
      {
        const std::string lower = prm.get("fixed region lower corner");
        const std::string upper = prm.get("fixed region upper corner");
        fixed_region_given      = !lower.empty() || !upper.empty();
        if (fixed_region_given)
          {
            if (lower.empty() || upper.empty())
              InputFile::reject(sub,
                                lower.empty() ? "fixed region lower corner" :
                                                "fixed region upper corner",
                                "",
                                "give both corners of the box of fixed nodes "
                                "or neither");
            fixed_region_lower =
              parse_point<dim>(prm, sub, "fixed region lower corner");
            fixed_region_upper =
              parse_point<dim>(prm, sub, "fixed region upper corner");
            for (unsigned int d = 0; d < dim; ++d)
              if (!(fixed_region_upper[d] >= fixed_region_lower[d]))
                InputFile::reject(sub,
                                  "fixed region upper corner",
                                  upper,
                                  "no coordinate may be below the 'fixed "
                                  "region lower corner' (" +
                                    lower + ")");
          }
      }
      friction_separation_by_velocity =
        prm.get("friction separation") == "velocity";
      separation_lift_height = prm.get_double("separation lift height");
      friction_guess_from_previous_step =
        prm.get("friction state guess") == "previous step";
      slip_boundaries = ids("slip boundaries");
      friction_boundaries.clear();
      {
        const std::string value = prm.get("friction boundaries");
        for (const auto &pair :
             dealii::Utilities::split_string_list(value, ','))
          {
            const auto parts = dealii::Utilities::split_string_list(pair, ':');
            bool       valid = parts.size() == 2;
            int        id    = -1;
            double     mu    = -1.;
            if (valid)
              try
                {
                  id = dealii::Utilities::string_to_int(parts[0]);
                  mu = dealii::Utilities::string_to_double(parts[1]);
                }
              catch (...)
                {
                  valid = false;
                }
            if (!valid || id < 0 || id > 255)
              InputFile::reject(sub,
                                "friction boundaries",
                                value,
                                "a comma-separated list of 'id: mu' pairs with "
                                "a boundary id from 0 to 255 and a friction "
                                "coefficient mu >= 0 is expected; '" +
                                  pair + "' is not such a pair");
            if (!(mu >= 0.) || !std::isfinite(mu))
              InputFile::reject(sub,
                                "friction boundaries",
                                value,
                                "the friction coefficient of boundary " +
                                  std::to_string(id) +
                                  " must be finite and >= 0");
            const auto b = static_cast<dealii::types::boundary_id>(id);
            if (friction_boundaries.count(b) || fixed_boundaries.count(b) ||
                slip_boundaries.count(b))
              InputFile::reject(sub,
                                "friction boundaries",
                                value,
                                "boundary id " + std::to_string(id) +
                                  " appears twice or is already a fixed or "
                                  "slip boundary");
            friction_boundaries[b] = mu;
          }
      }
      for (const auto id : fixed_boundaries)
        if (slip_boundaries.count(id))
          InputFile::reject(sub,
                            "slip boundaries",
                            prm.get("slip boundaries"),
                            "boundary id " + std::to_string(id) +
                              " is already in 'fixed boundaries'");

      if (type == "box")
        {
          std::tie(lower_corner, upper_corner) = parse_box<dim>(prm, sub);
          subdivisions.clear();
          for (const auto &s :
               dealii::Utilities::split_string_list(prm.get("subdivisions"),
                                                    ','))
            subdivisions.push_back(dealii::Utilities::string_to_int(s));
          dealii::GridGenerator::subdivided_hyper_rectangle(
            triangulation, subdivisions, lower_corner, upper_corner, true);
          is_cartesian = true;
          for (unsigned int d = 0; d < dim; ++d)
            cell_extent[d] =
              (upper_corner[d] - lower_corner[d]) / subdivisions[d];
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
          dealii::GridIn<dim> grid_in(triangulation);
          try
            {
              grid_in.read_msh(in);
            }
          catch (const dealii::ExceptionBase &e)
            {
              std::ostringstream what;
              e.print_info(what);
              InputFile::reject(sub,
                                "mesh file",
                                mesh_file,
                                "it is not a readable Gmsh mesh of " +
                                  std::to_string(dim) +
                                  "D quadrilaterals/hexahedra: " +
                                  dealii::Utilities::trim(what.str()));
            }
          is_cartesian = false;
          const auto box =
            dealii::GridTools::compute_bounding_box(triangulation);
          lower_corner = box.get_boundary_points().first;
          upper_corner = box.get_boundary_points().second;
        }
      prm.leave_subsection();

      minimal_cell_diameter =
        dealii::GridTools::minimal_cell_diameter(triangulation, mapping);

      // Every requested boundary id must exist somewhere in the grid.
      std::vector<dealii::types::boundary_id> existing =
        triangulation.get_boundary_ids();
      const auto check = [&](const std::set<dealii::types::boundary_id> &set,
                             const std::string &entry) {
        for (const auto id : set)
          if (std::find(existing.begin(), existing.end(), id) == existing.end())
            {
              prm.enter_subsection(sub);
              const std::string value = prm.get(entry);
              prm.leave_subsection();
              InputFile::reject(sub,
                                entry,
                                value,
                                "the grid has no boundary with id " +
                                  std::to_string(id));
            }
      };
      check(fixed_boundaries, "fixed boundaries");
      check(slip_boundaries, "slip boundaries");
      {
        std::set<dealii::types::boundary_id> friction_ids;
        for (const auto &f : friction_boundaries)
          friction_ids.insert(f.first);
        check(friction_ids, "friction boundaries");
      }

      setup_dofs();
    }


    template <int dim>
    void
    BackgroundGrid<dim>::setup_dofs()
    {
      dof_handler.distribute_dofs(system_fe());
      locally_owned_dofs = dof_handler.locally_owned_dofs();
      dealii::DoFTools::extract_locally_relevant_dofs(dof_handler,
                                                      locally_relevant_dofs);
    }


    template <int dim>
    void
    BackgroundGrid<dim>::set_velocity_fields(const unsigned int n)
    {
      AssertThrow(n >= 1, dealii::ExcInternalError());
      n_fields = n;
      if (n == 1)
        multi_field_fe.reset();
      else
        multi_field_fe =
          std::make_unique<dealii::FESystem<dim>>(dealii::FE_Q<dim>(1),
                                                  dim * n);
    }


    template <int dim>
    dealii::ComponentMask
    BackgroundGrid<dim>::component_mask(
      const std::vector<bool> &directions) const
    {
      AssertDimension(directions.size(), dim);
      std::vector<bool> mask(dim * n_fields, false);
      for (unsigned int f = 0; f < n_fields; ++f)
        for (unsigned int d = 0; d < dim; ++d)
          mask[f * dim + d] = directions[d];
      return dealii::ComponentMask(mask);
    }


    template <int dim>
    std::vector<std::vector<dealii::BoundingBox<dim>>>
    BackgroundGrid<dim>::global_bounding_boxes() const
    {
      std::vector<dealii::BoundingBox<dim>> local;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto box = cell->bounding_box();
            if (local.empty())
              local.push_back(box);
            else
              local[0].merge_with(box);
          }
      return dealii::Utilities::MPI::all_gather(mpi_communicator, local);
    }


    template class BackgroundGrid<2>;
    template class BackgroundGrid<3>;
    template std::pair<dealii::Point<2>, dealii::Point<2>>
    parse_box<2>(const dealii::ParameterHandler &, const std::string &);
    template std::pair<dealii::Point<3>, dealii::Point<3>>
    parse_box<3>(const dealii::ParameterHandler &, const std::string &);
    template dealii::Point<2>
    parse_point<2>(const dealii::ParameterHandler &,
                   const std::string &,
                   const std::string &);
    template dealii::Point<3>
    parse_point<3>(const dealii::ParameterHandler &,
                   const std::string &,
                   const std::string &);
  } // namespace MPM
} // namespace Talus
