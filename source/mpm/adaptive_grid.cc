#include <talus/base/input.h>
#include <talus/mpm/adaptive_grid.h>

#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>
#include <set>
#include <string>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    void
    AdaptiveGrid<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Adaptive grid");
      {
        prm.declare_entry(
          "enable",
          "false",
          Patterns::Bool(),
          "Refine the background grid where the material points are and "
          "coarsen it where they are not (see doc/adaptive_grids.md) [-]. "
          "The run starts on the background grid refined uniformly to the "
          "maximum level, generates the points there and coarsens the empty "
          "cells before the first step. Needs linear shape functions, the "
          "lumped mass, no APIC, no ghost penalty, no grid friction "
          "boundaries, and boundary particles with the 'penalty' or "
          "'augmented Lagrangian' method on the grid side.");
        prm.declare_entry("minimum level",
                          "0",
                          Patterns::Integer(0, 10),
                          "Coarsest refinement level of the cells far from "
                          "the material, counted from the background grid "
                          "of subsection Background grid [-].");
        prm.declare_entry("maximum level",
                          "2",
                          Patterns::Integer(0, 10),
                          "Refinement level of the cells with material "
                          "points and their neighbours, counted from the "
                          "background grid [-]; at least the minimum level. "
                          "The uniform grid with the same cell size is the "
                          "background grid refined this many times.");
        prm.declare_entry("refine every steps",
                          "1",
                          Patterns::Integer(0),
                          "Adapt the grid after every this many accepted "
                          "time steps [-] (one level per cell and pass); 0: "
                          "only at the start.");
        prm.declare_entry("neighbour layers",
                          "1",
                          Patterns::Integer(0, 8),
                          "Layers of cells around the cells with material "
                          "points that are refined as well (cells that "
                          "share a vertex with them, layer by layer) [-]. "
                          "The points may move this many fine cells between "
                          "two adaptations without reaching a coarse cell.");
        prm.declare_entry(
          "refine at boundary particles",
          "true",
          Patterns::Bool(),
          "Refine the cells that hold boundary particles (subsection "
          "Boundary particles: terrain, walls, the coupled interface) to the "
          "maximum level as well, with their 'neighbour layers', whether or "
          "not material is near [-]: the contact forces then act on the "
          "finest cells, and material that reaches a boundary meets fine "
          "cells there. 'false': only the material points decide.");
        prm.declare_entry(
          "refine at boundaries",
          "",
          Patterns::List(Patterns::Integer(0, 255)),
          "Boundary ids of the background grid (box grid: 0 x-min, 1 x-max, "
          "2 y-min, 3 y-max, 4 z-min, 5 z-max; Gmsh: the physical ids) whose "
          "cells are refined to the maximum level where material is near "
          "[-]: a cell that touches a face of one of them counts as near "
          "the material also within 'neighbour layers' + 1 more layers of "
          "the near cells, counted along those faces, so that the fine band "
          "along a wall or floor reaches 2 n + 1 cells beyond the material "
          "(n = 'neighbour layers'). Empty: the grid's faces are no "
          "criterion.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    AdaptiveGrid<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptive grid");
      enable    = prm.get_bool("enable");
      min_level = prm.get_integer("minimum level");
      max_level = prm.get_integer("maximum level");
      every     = prm.get_integer("refine every steps");
      layers    = prm.get_integer("neighbour layers");
      refine_at_boundary_particles =
        prm.get_bool("refine at boundary particles");
      refine_boundaries.clear();
      for (const auto &id : dealii::Utilities::split_string_list(
             prm.get("refine at boundaries")))
        refine_boundaries.push_back(
          static_cast<dealii::types::boundary_id>(std::stoi(id)));
      std::sort(refine_boundaries.begin(), refine_boundaries.end());
      refine_boundaries.erase(std::unique(refine_boundaries.begin(),
                                          refine_boundaries.end()),
                              refine_boundaries.end());
      prm.leave_subsection();
      if (enable && max_level < min_level)
        InputFile::reject("Adaptive grid",
                          "maximum level",
                          std::to_string(max_level),
                          "it must be at least the minimum level (" +
                            std::to_string(min_level) + ")");
    }


    template <int dim>
    void
    AdaptiveGrid<dim>::check_refined_boundaries(
      const BackgroundGrid<dim> &grid) const
    {
      if (!enable || refine_boundaries.empty())
        return;
      std::set<dealii::types::boundary_id> grid_ids;
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              grid_ids.insert(face->boundary_id());
      std::vector<unsigned int> local_ids(grid_ids.begin(), grid_ids.end());
      std::set<unsigned int>    all_ids;
      for (const auto &part :
           dealii::Utilities::MPI::all_gather(grid.mpi_communicator, local_ids))
        all_ids.insert(part.begin(), part.end());
      std::string list;
      for (const unsigned int id : all_ids)
        list += (list.empty() ? "" : ", ") + std::to_string(id);
      for (unsigned int k = 0; k < refine_boundaries.size(); ++k)
        if (all_ids.count(refine_boundaries[k]) == 0)
          InputFile::reject("Adaptive grid",
                            "refine at boundaries",
                            std::to_string(refine_boundaries[k]),
                            "a boundary id of the background grid (its "
                            "faces carry the ids " +
                              list + ")");
    }


    template <int dim>
    std::vector<bool>
    AdaptiveGrid<dim>::near_cells(
      const BackgroundGrid<dim>                     &grid,
      const dealii::Particles::ParticleHandler<dim> &points,
      const dealii::Particles::ParticleHandler<dim> &boundary) const
    {
      using Vector     = dealii::TrilinosWrappers::MPI::Vector;
      const auto &dofs = grid.dof_handler;
      // marks at the vertices (their x dof) of the occupied/near cells
      Vector            marks(grid.locally_owned_dofs, grid.mpi_communicator);
      Vector            ghosted(grid.locally_owned_dofs,
                     grid.locally_relevant_dofs,
                     grid.mpi_communicator);
      std::vector<bool> near(grid.triangulation.n_active_cells(), false);
      // the owned cells that touch a face of `refine at boundaries`
      std::vector<bool> at_face(grid.triangulation.n_active_cells(), false);
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const typename dealii::Triangulation<dim>::active_cell_iterator
              tria_cell(cell);
            near[cell->active_cell_index()] =
              points.n_particles_in_cell(tria_cell) > 0 ||
              (refine_at_boundary_particles &&
               boundary.n_particles_in_cell(tria_cell) > 0);
            if (!refine_boundaries.empty())
              for (const auto &face : cell->face_iterators())
                if (face->at_boundary() &&
                    std::binary_search(refine_boundaries.begin(),
                                       refine_boundaries.end(),
                                       face->boundary_id()))
                  at_face[cell->active_cell_index()] = true;
          }
      // the layers around the occupied cells, then (with `refine at
      // boundaries`) n + 1 more layers of cells at those faces
      const unsigned int face_layers =
        refine_boundaries.empty() ? 0 : layers + 1;
      for (unsigned int layer = 0; layer < layers + face_layers; ++layer)
        {
          const bool faces_only = layer >= layers;
          marks                 = 0.;
          std::vector<dealii::types::global_dof_index> indices;
          for (const auto &cell : dofs.active_cell_iterators())
            if (cell->is_locally_owned() && near[cell->active_cell_index()])
              for (const unsigned int v : cell->vertex_indices())
                indices.push_back(cell->vertex_dof_index(v, 0));
          const std::vector<double> ones(indices.size(), 1.);
          marks.add(indices, ones);
          marks.compress(dealii::VectorOperation::add);
          ghosted = marks;
          for (const auto &cell : dofs.active_cell_iterators())
            if (cell->is_locally_owned() &&
                (!faces_only || at_face[cell->active_cell_index()]))
              for (const unsigned int v : cell->vertex_indices())
                if (ghosted(cell->vertex_dof_index(v, 0)) > 0.)
                  near[cell->active_cell_index()] = true;
        }
      return near;
    }


    template <int dim>
    bool
    AdaptiveGrid<dim>::flag_cells(
      BackgroundGrid<dim>                           &grid,
      const dealii::Particles::ParticleHandler<dim> &points,
      const dealii::Particles::ParticleHandler<dim> &boundary,
      const unsigned int                             base_level) const
    {
      const std::vector<bool> near    = near_cells(grid, points, boundary);
      const int               lowest  = base_level + min_level;
      const int               highest = base_level + max_level;
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->clear_refine_flag();
            cell->clear_coarsen_flag();
            const int level = cell->level();
            if (level < lowest ||
                (near[cell->active_cell_index()] && level < highest))
              cell->set_refine_flag();
            else if (!near[cell->active_cell_index()] && level > lowest)
              cell->set_coarsen_flag();
          }
      grid.triangulation.prepare_coarsening_and_refinement();
      bool changed = false;
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned() &&
            (cell->refine_flag_set() || cell->coarsen_flag_set()))
          changed = true;
      return dealii::Utilities::MPI::logical_or(changed, grid.mpi_communicator);
    }


    template <int dim>
    std::pair<unsigned int, unsigned int>
    AdaptiveGrid<dim>::boundary_cells_at_maximum_level(
      const BackgroundGrid<dim>                     &grid,
      const dealii::Particles::ParticleHandler<dim> &boundary,
      const unsigned int                             base_level) const
    {
      unsigned int with = 0, finest = 0;
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && boundary.n_particles_in_cell(cell) > 0)
          {
            ++with;
            finest += cell->level() == static_cast<int>(base_level + max_level);
          }
      return {dealii::Utilities::MPI::sum(with, grid.mpi_communicator),
              dealii::Utilities::MPI::sum(finest, grid.mpi_communicator)};
    }


    template <int dim>
    std::pair<unsigned int, unsigned int>
    AdaptiveGrid<dim>::boundary_face_cells_at_maximum_level(
      const BackgroundGrid<dim>                     &grid,
      const dealii::Particles::ParticleHandler<dim> &points,
      const dealii::Particles::ParticleHandler<dim> &boundary,
      const unsigned int                             base_level) const
    {
      const std::vector<bool> near = near_cells(grid, points, boundary);
      unsigned int            with = 0, finest = 0;
      for (const auto &cell : grid.triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && near[cell->active_cell_index()])
          {
            bool touches = false;
            for (const auto &face : cell->face_iterators())
              touches =
                touches || (face->at_boundary() &&
                            std::binary_search(refine_boundaries.begin(),
                                               refine_boundaries.end(),
                                               face->boundary_id()));
            if (!touches)
              continue;
            ++with;
            finest += cell->level() == static_cast<int>(base_level + max_level);
          }
      return {dealii::Utilities::MPI::sum(with, grid.mpi_communicator),
              dealii::Utilities::MPI::sum(finest, grid.mpi_communicator)};
    }


    template class AdaptiveGrid<2>;
    template class AdaptiveGrid<3>;
  } // namespace MPM
} // namespace Talus
