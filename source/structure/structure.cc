#include <talus/structure/structure.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
    using dealii::types::global_dof_index;

    LineMesh &
    Structure::add_line_mesh(const std::string                        &name,
                             const std::shared_ptr<const LineElement> &element)
    {
      line_meshes.push_back(std::make_unique<LineMesh>());
      line_meshes.back()->name    = name;
      line_meshes.back()->element = element;
      return *line_meshes.back();
    }


    LineMesh &
    Structure::add_sliding_cable(
      const std::string                         &name,
      const std::shared_ptr<const SlidingCable> &cable)
    {
      line_meshes.push_back(std::make_unique<LineMesh>());
      line_meshes.back()->name          = name;
      line_meshes.back()->sliding_cable = cable;
      return *line_meshes.back();
    }


    MembraneMesh &
    Structure::add_membrane(const std::string                     &name,
                            const std::shared_ptr<const Membrane> &membrane)
    {
      membrane_meshes.push_back(std::make_unique<MembraneMesh>());
      membrane_meshes.back()->name     = name;
      membrane_meshes.back()->membrane = membrane;
      return *membrane_meshes.back();
    }


    SolidMesh &
    Structure::add_solid(const std::string                              &name,
                         const std::shared_ptr<const ContinuumSolid<3>> &solid)
    {
      solid_meshes.push_back(std::make_unique<SolidMesh>());
      solid_meshes.back()->name  = name;
      solid_meshes.back()->solid = solid;
      solid_meshes.back()->fe =
        std::make_unique<dealii::FESystem<3>>(dealii::FE_Q<3>(solid->degree),
                                              3);
      return *solid_meshes.back();
    }


    PlaneSolidMesh &
    Structure::add_plane_solid(
      const std::string                              &name,
      const std::shared_ptr<const ContinuumSolid<2>> &solid,
      const double                                    thickness,
      const dealii::Triangulation<2>                 &plane)
    {
      plane_solid_meshes.push_back(std::make_unique<PlaneSolidMesh>());
      auto &mesh     = *plane_solid_meshes.back();
      mesh.name      = name;
      mesh.solid     = solid;
      mesh.thickness = thickness;
      mesh.fe        = std::make_unique<dealii::FESystem<2, 3>>(
        dealii::FE_Q<2, 3>(solid->degree), 3);
      // The cells of the plane in order, at z = 0, with their boundary ids
      // (GridGenerator::flatten_triangulation keeps neither the order of
      // refined meshes nor all ids reliably).
      std::vector<dealii::Point<3>> vertices(plane.n_vertices());
      for (unsigned int v = 0; v < plane.n_vertices(); ++v)
        vertices[v] = dealii::Point<3>(plane.get_vertices()[v][0],
                                       plane.get_vertices()[v][1],
                                       0.);
      std::vector<dealii::CellData<2>> cells;
      dealii::SubCellData              boundary;
      for (const auto &cell : plane.active_cell_iterators())
        {
          dealii::CellData<2> c;
          for (const unsigned int v : cell->vertex_indices())
            c.vertices[v] = cell->vertex_index(v);
          cells.push_back(c);
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) && cell->face(f)->boundary_id() != 0)
              {
                dealii::CellData<1> line;
                line.vertices    = {cell->face(f)->vertex_index(0),
                                    cell->face(f)->vertex_index(1)};
                line.boundary_id = cell->face(f)->boundary_id();
                boundary.boundary_lines.push_back(line);
              }
        }
      mesh.triangulation.create_triangulation(vertices, cells, boundary);
      return mesh;
    }


    namespace
    {
      /** Direction of every DoF of a mesh, into @p dof_component. */
      template <int dim>
      void
      record_components(const dealii::DoFHandler<dim, 3> &dof_handler,
                        const global_dof_index            offset,
                        std::vector<unsigned char>       &dof_component)
      {
        const auto                   &fe = dof_handler.get_fe();
        std::vector<global_dof_index> indices(fe.n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(indices);
            for (unsigned int i = 0; i < indices.size(); ++i)
              dof_component[offset + indices[i]] =
                fe.system_to_component_index(i).first;
          }
      }

      struct VertexEntry
      {
        dealii::Point<3>                X;
        std::array<global_dof_index, 3> dofs;
      };

      template <int dim>
      void
      collect_vertices(const dealii::DoFHandler<dim, 3> &dof_handler,
                       const global_dof_index            offset,
                       std::vector<VertexEntry>         &entries)
      {
        std::vector<bool> seen(dof_handler.get_triangulation().n_vertices(),
                               false);
        for (const auto &cell : dof_handler.active_cell_iterators())
          for (const unsigned int v : cell->vertex_indices())
            if (!seen[cell->vertex_index(v)])
              {
                seen[cell->vertex_index(v)] = true;
                VertexEntry e;
                e.X = cell->vertex(v);
                for (unsigned int c = 0; c < 3; ++c)
                  e.dofs[c] = offset + cell->vertex_dof_index(v, c);
                entries.push_back(e);
              }
      }

      unsigned int
      find_root(std::vector<unsigned int> &parent, unsigned int i)
      {
        while (parent[i] != i)
          i = parent[i] = parent[parent[i]];
        return i;
      }
    } // namespace


    void
    Structure::setup_dofs(const double tolerance)
    {
      total_dofs = 0;
      std::vector<VertexEntry> entries;
      for (auto &mesh : line_meshes)
        {
          if (mesh->triangulation.n_active_cells() == 0)
            throw std::runtime_error("The line mesh <" + mesh->name +
                                     "> has no cells.");
          mesh->dof_handler.reinit(mesh->triangulation);
          mesh->dof_handler.distribute_dofs(line_fe);
          mesh->offset = total_dofs;
          total_dofs += mesh->dof_handler.n_dofs();
          const unsigned int n_cells = mesh->triangulation.n_active_cells();
          mesh->state.assign(n_cells, LineState());
          mesh->trial_state = mesh->state;
          mesh->force.assign(n_cells, 0.);
          collect_vertices(mesh->dof_handler, mesh->offset, entries);
        }
      for (auto &mesh : membrane_meshes)
        {
          if (mesh->triangulation.n_active_cells() == 0)
            throw std::runtime_error("The membrane mesh <" + mesh->name +
                                     "> has no cells.");
          mesh->dof_handler.reinit(mesh->triangulation);
          mesh->dof_handler.distribute_dofs(membrane_fe);
          mesh->offset = total_dofs;
          total_dofs += mesh->dof_handler.n_dofs();
          mesh->cell_output.assign(mesh->triangulation.n_active_cells(),
                                   MembraneCellOutput());
          collect_vertices(mesh->dof_handler, mesh->offset, entries);
        }
      for_each_solid_mesh([&](auto &mesh) {
        if (mesh.triangulation.n_active_cells() == 0)
          throw std::runtime_error("The solid mesh <" + mesh.name +
                                   "> has no cells.");
        mesh.dof_handler.reinit(mesh.triangulation);
        mesh.dof_handler.distribute_dofs(*mesh.fe);
        mesh.offset = total_dofs;
        total_dofs += mesh.dof_handler.n_dofs();
        mesh.cell_output.assign(mesh.triangulation.n_active_cells(),
                                SolidCellOutput());
        collect_vertices(mesh.dof_handler, mesh.offset, entries);
      });
      dof_component.assign(total_dofs, 0);
      for (const auto &mesh : line_meshes)
        record_components(mesh->dof_handler, mesh->offset, dof_component);
      for (const auto &mesh : membrane_meshes)
        record_components(mesh->dof_handler, mesh->offset, dof_component);
      for_each_solid_mesh([&](const auto &mesh) {
        record_components(mesh.dof_handler, mesh.offset, dof_component);
      });

      // Merge coincident vertices (sweep over x).
      dealii::Point<3> lo = entries[0].X, hi = entries[0].X;
      for (const auto &e : entries)
        for (unsigned int d = 0; d < 3; ++d)
          {
            lo[d] = std::min(lo[d], e.X[d]);
            hi[d] = std::max(hi[d], e.X[d]);
          }
      const double tol = tolerance * std::max(lo.distance(hi), 1e-300);
      std::vector<unsigned int> order(entries.size());
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
        return entries[a].X[0] < entries[b].X[0];
      });
      std::vector<unsigned int> parent(entries.size());
      std::iota(parent.begin(), parent.end(), 0u);
      for (unsigned int a = 0; a < order.size(); ++a)
        for (unsigned int b = a + 1;
             b < order.size() &&
             entries[order[b]].X[0] - entries[order[a]].X[0] <= tol;
             ++b)
          if (entries[order[a]].X.distance(entries[order[b]].X) <= tol)
            {
              const unsigned int ra = find_root(parent, order[a]);
              const unsigned int rb = find_root(parent, order[b]);
              // The entry that comes first (earlier mesh) is the master.
              parent[std::max(ra, rb)] = std::min(ra, rb);
            }

      nodes.clear();
      dof_to_node.assign(total_dofs, dealii::numbers::invalid_unsigned_int);
      std::map<unsigned int, unsigned int> root_to_node;
      for (unsigned int i = 0; i < entries.size(); ++i)
        {
          const unsigned int root = find_root(parent, i);
          auto               it   = root_to_node.find(root);
          if (it == root_to_node.end())
            {
              // Roots come first: i == root for the first entry of a group.
              Node n;
              n.X    = entries[root].X;
              n.dofs = entries[root].dofs;
              nodes.push_back(n);
              it = root_to_node.emplace(root, nodes.size() - 1).first;
            }
          Node &n = nodes[it->second];
          if (entries[i].dofs != n.dofs)
            n.slaves.push_back(entries[i].dofs);
          for (unsigned int c = 0; c < 3; ++c)
            dof_to_node[entries[i].dofs[c]] = it->second;
        }

      // Sliding cables: nodes in cable order.
      for (auto &mesh : line_meshes)
        if (mesh->sliding_cable)
          {
            const auto                            &tria = mesh->triangulation;
            std::vector<std::vector<unsigned int>> vertex_cells(
              tria.n_vertices());
            std::vector<decltype(mesh->dof_handler.begin_active())> cells;
            for (const auto &cell : mesh->dof_handler.active_cell_iterators())
              {
                cells.push_back(cell);
                for (const unsigned int v : cell->vertex_indices())
                  vertex_cells[cell->vertex_index(v)].push_back(cells.size() -
                                                                1);
              }
            unsigned int start = dealii::numbers::invalid_unsigned_int;
            for (unsigned int v = 0; v < tria.n_vertices(); ++v)
              {
                if (vertex_cells[v].size() > 2)
                  throw std::runtime_error("The sliding cable <" + mesh->name +
                                           "> branches at a vertex.");
                if (vertex_cells[v].size() == 1 &&
                    start == dealii::numbers::invalid_unsigned_int)
                  start = v;
              }
            if (start == dealii::numbers::invalid_unsigned_int)
              throw std::runtime_error("The sliding cable <" + mesh->name +
                                       "> is closed (it has no end).");
            mesh->chain.clear();
            mesh->chain_X.clear();
            mesh->chain_cells.clear();
            std::vector<bool> used(cells.size(), false);
            unsigned int      v = start;
            while (true)
              {
                unsigned int next_cell = dealii::numbers::invalid_unsigned_int;
                for (const unsigned int c : vertex_cells[v])
                  if (!used[c])
                    next_cell = c;
                const auto &cell =
                  cells[next_cell == dealii::numbers::invalid_unsigned_int ?
                          vertex_cells[v][0] :
                          next_cell];
                const unsigned int local = cell->vertex_index(0) == v ? 0 : 1;
                std::array<global_dof_index, 3> d;
                for (unsigned int c = 0; c < 3; ++c)
                  d[c] = mesh->offset + cell->vertex_dof_index(local, c);
                mesh->chain.push_back(d);
                mesh->chain_X.push_back(cell->vertex(local));
                if (next_cell == dealii::numbers::invalid_unsigned_int)
                  break;
                used[next_cell] = true;
                mesh->chain_cells.push_back(
                  cells[next_cell]->active_cell_index());
                v = cells[next_cell]->vertex_index(1 - local);
              }
            if (mesh->chain.size() != tria.n_active_cells() + 1)
              throw std::runtime_error("The sliding cable <" + mesh->name +
                                       "> is not one connected chain.");
          }

      external_forces.reinit(total_dofs);
      prescribed.clear();
      point_loads.clear();
      // Plane-strain solids: no out-of-plane displacement (on the masters,
      // each once; prescribe_dof() would search the list every time).
      std::set<global_dof_index> fixed;
      for (const auto &mesh : plane_solid_meshes)
        for (global_dof_index i = 0; i < mesh->dof_handler.n_dofs(); ++i)
          {
            const global_dof_index dof = mesh->offset + i;
            if (dof_component[dof] != 2)
              continue;
            const unsigned int     node = dof_to_node[dof];
            const global_dof_index master =
              node == dealii::numbers::invalid_unsigned_int ?
                dof :
                nodes[node].dofs[2];
            if (fixed.insert(master).second)
              prescribed.emplace_back(master, 0.);
          }
    }


    unsigned int
    Structure::find_node(const dealii::Point<3> &p,
                         const double            tolerance) const
    {
      unsigned int best   = dealii::numbers::invalid_unsigned_int;
      double       best_d = tolerance;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const double d = nodes[i].X.distance(p);
          if (d <= best_d)
            {
              best   = i;
              best_d = d;
            }
        }
      return best;
    }


    std::vector<unsigned int>
    Structure::find_nodes(
      const std::function<bool(const dealii::Point<3> &)> &predicate) const
    {
      std::vector<unsigned int> result;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (predicate(nodes[i].X))
          result.push_back(i);
      return result;
    }


    unsigned int
    Structure::n_nodes() const
    {
      return nodes.size();
    }


    const dealii::Point<3> &
    Structure::node_position(const unsigned int node) const
    {
      return nodes[node].X;
    }


    global_dof_index
    Structure::node_dof(const unsigned int node, const unsigned int c) const
    {
      return nodes[node].dofs[c];
    }


    void
    Structure::prescribe(const unsigned int node,
                         const unsigned int c,
                         const double       value)
    {
      const global_dof_index dof = nodes[node].dofs[c];
      for (auto &p : prescribed)
        if (p.first == dof)
          {
            p.second = value;
            return;
          }
      prescribed.emplace_back(dof, value);
    }


    void
    Structure::prescribe_dof(const global_dof_index dof, const double value)
    {
      AssertIndexRange(dof, total_dofs);
      const unsigned int     node = dof_to_node[dof];
      const global_dof_index master =
        node == dealii::numbers::invalid_unsigned_int ?
          dof :
          nodes[node].dofs[dof_component[dof]];
      for (auto &p : prescribed)
        if (p.first == master)
          {
            p.second = value;
            return;
          }
      prescribed.emplace_back(master, value);
    }


    unsigned int
    Structure::prescribe_solid_boundary(const unsigned int       mesh,
                                        const unsigned int       boundary_id,
                                        const std::vector<bool> &components)
    {
      AssertIndexRange(mesh, solid_meshes.size());
      return prescribe_solid_boundary(*solid_meshes[mesh],
                                      boundary_id,
                                      components);
    }


    template <int dim>
    unsigned int
    Structure::prescribe_solid_boundary(const SolidMeshT<dim>   &m,
                                        const unsigned int       boundary_id,
                                        const std::vector<bool> &components)
    {
      const auto                   &fe = *m.fe;
      std::vector<global_dof_index> face_dofs(fe.n_dofs_per_face());
      std::vector<bool>             done(m.dof_handler.n_dofs(), false);
      unsigned int                  count = 0;
      for (const auto &cell : m.dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->at_boundary(f) &&
              cell->face(f)->boundary_id() == boundary_id)
            {
              cell->face(f)->get_dof_indices(face_dofs);
              for (unsigned int i = 0; i < face_dofs.size(); ++i)
                if (!done[face_dofs[i]] &&
                    components[fe.face_system_to_component_index(i).first])
                  {
                    done[face_dofs[i]] = true;
                    prescribe_dof(m.offset + face_dofs[i]);
                    ++count;
                  }
            }
      return count;
    }


    unsigned int
    Structure::prescribe_solid_box(const unsigned int       mesh,
                                   const dealii::Point<3>  &lower,
                                   const dealii::Point<3>  &upper,
                                   const std::vector<bool> &components)
    {
      AssertIndexRange(mesh, solid_meshes.size());
      return prescribe_solid_box(*solid_meshes[mesh], lower, upper, components);
    }


    template <int dim>
    unsigned int
    Structure::prescribe_solid_box(const SolidMeshT<dim>   &m,
                                   const dealii::Point<3>  &lower,
                                   const dealii::Point<3>  &upper,
                                   const std::vector<bool> &components)
    {
      std::vector<dealii::Point<3>> support(m.dof_handler.n_dofs());
      dealii::DoFTools::map_dofs_to_support_points(dealii::MappingQ1<dim, 3>(),
                                                   m.dof_handler,
                                                   support);
      const double tol =
        1e-10 * std::max(1., dealii::GridTools::diameter(m.triangulation));
      unsigned int count = 0;
      for (global_dof_index i = 0; i < support.size(); ++i)
        {
          const unsigned int c      = dof_component[m.offset + i];
          bool               inside = components[c];
          for (unsigned int d = 0; d < 3 && inside; ++d)
            inside = support[i][d] >= lower[d] - tol &&
                     support[i][d] <= upper[d] + tol;
          if (inside)
            {
              prescribe_dof(m.offset + i);
              ++count;
            }
        }
      return count;
    }


    template unsigned int
    Structure::prescribe_solid_boundary(const SolidMeshT<2> &,
                                        const unsigned int,
                                        const std::vector<bool> &);
    template unsigned int
    Structure::prescribe_solid_boundary(const SolidMeshT<3> &,
                                        const unsigned int,
                                        const std::vector<bool> &);
    template unsigned int
    Structure::prescribe_solid_box(const SolidMeshT<2> &,
                                   const dealii::Point<3> &,
                                   const dealii::Point<3> &,
                                   const std::vector<bool> &);
    template unsigned int
    Structure::prescribe_solid_box(const SolidMeshT<3> &,
                                   const dealii::Point<3> &,
                                   const dealii::Point<3> &,
                                   const std::vector<bool> &);


    std::vector<StructurePart>
    Structure::parts() const
    {
      // Union-find over the global DoFs: every cell joins its DoFs, every
      // tie joins a copy to its master.
      std::vector<unsigned int> parent(total_dofs);
      std::iota(parent.begin(), parent.end(), 0u);
      const auto join = [&](const std::vector<global_dof_index> &dofs) {
        for (const auto d : dofs)
          {
            const unsigned int ra    = find_root(parent, dofs[0]);
            const unsigned int rb    = find_root(parent, d);
            parent[std::max(ra, rb)] = std::min(ra, rb);
          }
      };
      std::vector<global_dof_index> indices;
      const auto                    join_mesh = [&](const auto            &dof_handler,
                                 const global_dof_index offset) {
        indices.resize(dof_handler.get_fe().n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(indices);
            for (auto &i : indices)
              i += offset;
            join(indices);
          }
      };
      for (const auto &mesh : line_meshes)
        if (mesh->sliding_cable)
          {
            indices.clear();
            for (const auto &d : mesh->chain)
              indices.insert(indices.end(), d.begin(), d.end());
            join(indices);
          }
        else
          join_mesh(mesh->dof_handler, mesh->offset);
      for (const auto &mesh : membrane_meshes)
        join_mesh(mesh->dof_handler, mesh->offset);
      for_each_solid_mesh(
        [&](const auto &mesh) { join_mesh(mesh.dof_handler, mesh.offset); });
      for (const auto &node : nodes)
        for (const auto &slave : node.slaves)
          for (unsigned int c = 0; c < 3; ++c)
            join({node.dofs[c], slave[c]});

      std::map<unsigned int, unsigned int> root_to_part;
      std::vector<StructurePart>           result;
      const auto part_of = [&](const global_dof_index dof) -> StructurePart & {
        const unsigned int root = find_root(parent, dof);
        auto               it   = root_to_part.find(root);
        if (it == root_to_part.end())
          {
            result.emplace_back();
            it = root_to_part.emplace(root, result.size() - 1).first;
          }
        return result[it->second];
      };
      const auto add_mesh = [&](const std::string     &name,
                                const global_dof_index offset,
                                const global_dof_index n) {
        for (global_dof_index i = offset; i < offset + n; ++i)
          {
            auto &part = part_of(i);
            if (std::find(part.meshes.begin(), part.meshes.end(), name) ==
                part.meshes.end())
              part.meshes.push_back(name);
          }
      };
      for (const auto &mesh : line_meshes)
        add_mesh(mesh->name, mesh->offset, mesh->dof_handler.n_dofs());
      for (const auto &mesh : membrane_meshes)
        add_mesh(mesh->name, mesh->offset, mesh->dof_handler.n_dofs());
      for_each_solid_mesh([&](const auto &mesh) {
        add_mesh(mesh.name, mesh.offset, mesh.dof_handler.n_dofs());
      });
      for (const auto &node : nodes)
        {
          auto &part = part_of(node.dofs[0]);
          if (part.n_nodes == 0)
            part.a_node = node.X;
          ++part.n_nodes;
        }
      for (const auto &p : prescribed)
        part_of(p.first).held[dof_component[p.first]] = true;
      for (global_dof_index i = 0; i < total_dofs; ++i)
        if (dof_component[i] == 0 && i < mass.size())
          part_of(i).mass += mass[i];
      for (const auto &mesh : membrane_meshes)
        if (mesh->dof_handler.n_dofs() > 0)
          part_of(mesh->offset).has_continuum = true;
      for_each_solid_mesh([&](const auto &mesh) {
        if (mesh.dof_handler.n_dofs() > 0)
          part_of(mesh.offset).has_continuum = true;
      });
      find_rotation_mechanisms(result,
                               [&](const global_dof_index dof) -> unsigned int {
                                 return root_to_part.at(find_root(parent, dof));
                               });
      return result;
    }


    void
    Structure::find_rotation_mechanisms(
      std::vector<StructurePart>                          &parts,
      const std::function<unsigned int(global_dof_index)> &part_index) const
    {
      // Position of every prescribed DoF: its node, or for DoFs of solids
      // that are not at a vertex their support point.
      std::map<global_dof_index, dealii::Point<3>> position;
      for (const auto &p : prescribed)
        if (dof_to_node[p.first] != dealii::numbers::invalid_unsigned_int)
          position[p.first] = nodes[dof_to_node[p.first]].X;
      for_each_solid_mesh([&](const auto &mesh) {
        constexpr int dim = std::decay_t<decltype(mesh)>::dimension;
        std::vector<dealii::Point<3>> support(mesh.dof_handler.n_dofs());
        dealii::DoFTools::map_dofs_to_support_points(
          dealii::MappingQ1<dim, 3>(), mesh.dof_handler, support);
        for (const auto &p : prescribed)
          if (p.first >= mesh.offset &&
              p.first < mesh.offset + mesh.dof_handler.n_dofs() &&
              position.find(p.first) == position.end())
            position[p.first] = support[p.first - mesh.offset];
      });
      // Centroid and size of each part (from its nodes).
      const unsigned int            n_parts = parts.size();
      std::vector<dealii::Point<3>> centre(n_parts);
      std::vector<double>           size(n_parts, 0.);
      std::vector<unsigned int>     count(n_parts, 0);
      std::vector<unsigned int>     node_part(nodes.size());
      for (unsigned int n = 0; n < nodes.size(); ++n)
        {
          node_part[n] = part_index(nodes[n].dofs[0]);
          centre[node_part[n]] += nodes[n].X;
          ++count[node_part[n]];
        }
      for (unsigned int k = 0; k < n_parts; ++k)
        if (count[k] > 0)
          centre[k] /= count[k];
      for (unsigned int n = 0; n < nodes.size(); ++n)
        size[node_part[n]] =
          std::max(size[node_part[n]],
                   (nodes[n].X - centre[node_part[n]]).norm());
      // Gram matrices A^T A of the rigid-body modes (translations, and
      // rotations about the centroid divided by the size) evaluated at the
      // nodes (3 rows each) and at the prescribed DoFs (1 row each).
      using Gram = std::array<std::array<double, 6>, 6>;
      std::vector<Gram> all(n_parts), held(n_parts);
      const auto        add_row = [&](Gram                   &G,
                               const unsigned int      k,
                               const dealii::Point<3> &x,
                               const unsigned int      c) {
        std::array<double, 6> row{};
        row[c] = 1.;
        const dealii::Tensor<1, 3> r =
          (x - centre[k]) / std::max(size[k], 1e-300);
        for (unsigned int a = 0; a < 3; ++a)
          {
            dealii::Tensor<1, 3> axis;
            axis[a]    = 1.;
            row[3 + a] = dealii::cross_product_3d(axis, r)[c];
          }
        for (unsigned int i = 0; i < 6; ++i)
          for (unsigned int j = 0; j < 6; ++j)
            G[i][j] += row[i] * row[j];
      };
      for (unsigned int n = 0; n < nodes.size(); ++n)
        for (unsigned int c = 0; c < 3; ++c)
          add_row(all[node_part[n]], node_part[n], nodes[n].X, c);
      for (const auto &p : prescribed)
        {
          const unsigned int k = part_index(p.first);
          add_row(held[k], k, position.at(p.first), dof_component[p.first]);
        }
      std::vector<double>           spread(n_parts, 0.);
      std::vector<bool>             first_seen(n_parts, false);
      std::vector<dealii::Point<3>> first(n_parts);
      for (const auto &p : prescribed)
        {
          const unsigned int k = part_index(p.first);
          if (!first_seen[k])
            {
              first_seen[k] = true;
              first[k]      = position.at(p.first);
            }
          spread[k] =
            std::max(spread[k], (position.at(p.first) - first[k]).norm());
        }
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          parts[k].held_at_one_point =
            first_seen[k] && spread[k] <= 1e-8 * std::max(size[k], 1e-300);
          if (!(parts[k].held[0] && parts[k].held[1] && parts[k].held[2]))
            continue;
          // Null space of the held modes, then the largest motion of the
          // nodes within it.
          dealii::LAPACKFullMatrix<double> G(6, 6);
          double                           trace = 0.;
          for (unsigned int i = 0; i < 6; ++i)
            {
              trace += held[k][i][i];
              for (unsigned int j = 0; j < 6; ++j)
                G(i, j) = held[k][i][j];
            }
          dealii::Vector<double>     values;
          dealii::FullMatrix<double> vectors;
          G.compute_eigenvalues_symmetric(
            -1., 2. * trace + 1., 1e-14 * trace, values, vectors);
          std::vector<unsigned int> null;
          for (unsigned int i = 0; i < values.size(); ++i)
            if (values[i] < 1e-10 * trace)
              null.push_back(i);
          if (null.empty())
            continue;
          double total = 0.;
          for (unsigned int i = 0; i < 6; ++i)
            total += all[k][i][i];
          dealii::LAPACKFullMatrix<double> M(null.size(), null.size());
          for (unsigned int a = 0; a < null.size(); ++a)
            for (unsigned int b = 0; b < null.size(); ++b)
              {
                double m = 0.;
                for (unsigned int i = 0; i < 6; ++i)
                  for (unsigned int j = 0; j < 6; ++j)
                    m +=
                      vectors(i, null[a]) * all[k][i][j] * vectors(j, null[b]);
                M(a, b) = m;
              }
          dealii::Vector<double>     moved;
          dealii::FullMatrix<double> directions;
          M.compute_eigenvalues_symmetric(
            -1., 2. * total + 1., 1e-14 * total, moved, directions);
          if (moved.size() == 0 || !(moved[moved.size() - 1] > 1e-8 * total))
            continue;
          // The motion t + omega x (x - c)/size: axis along omega, through
          // c + size omega x t / |omega|^2.
          dealii::Tensor<1, 3> t, omega;
          for (unsigned int a = 0; a < null.size(); ++a)
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double w = directions(a, moved.size() - 1);
                t[i] += w * vectors(i, null[a]);
                omega[i] += w * vectors(3 + i, null[a]);
              }
          if (!(omega.norm() > 1e-8))
            continue;
          parts[k].can_rotate    = true;
          parts[k].rotation_axis = omega / omega.norm();
          parts[k].axis_point =
            parts[k].held_at_one_point ?
              first[k] :
              centre[k] + size[k] * dealii::cross_product_3d(omega, t) /
                            omega.norm_square();
        }
    }


    void
    Structure::release(const unsigned int node, const unsigned int c)
    {
      const global_dof_index dof = nodes[node].dofs[c];
      prescribed.erase(std::remove_if(prescribed.begin(),
                                      prescribed.end(),
                                      [&](const auto &p) {
                                        return p.first == dof;
                                      }),
                       prescribed.end());
    }


    void
    Structure::add_point_load(const unsigned int          node,
                              const dealii::Tensor<1, 3> &F)
    {
      point_loads.emplace_back(node, F);
    }


    void
    Structure::setup_system()
    {
      ties.clear();
      for (const auto &node : nodes)
        for (const auto &slave : node.slaves)
          for (unsigned int c = 0; c < 3; ++c)
            {
              ties.add_line(slave[c]);
              ties.add_entry(slave[c], node.dofs[c], 1.);
            }
      ties.close();

      constraints.clear();
      for (const auto &node : nodes)
        for (const auto &slave : node.slaves)
          for (unsigned int c = 0; c < 3; ++c)
            {
              constraints.add_line(slave[c]);
              constraints.add_entry(slave[c], node.dofs[c], 1.);
            }
      for (const auto &p : prescribed)
        constraints.add_line(p.first);
      constraints.close();

      dealii::DynamicSparsityPattern dsp(total_dofs);
      std::vector<global_dof_index>  indices;
      for (const auto &mesh : line_meshes)
        if (mesh->sliding_cable)
          {
            indices.clear();
            for (const auto &d : mesh->chain)
              indices.insert(indices.end(), d.begin(), d.end());
            constraints.add_entries_local_to_global(indices, dsp, false);
          }
        else
          {
            indices.resize(line_fe.n_dofs_per_cell());
            for (const auto &cell : mesh->dof_handler.active_cell_iterators())
              {
                cell->get_dof_indices(indices);
                for (auto &i : indices)
                  i += mesh->offset;
                constraints.add_entries_local_to_global(indices, dsp, false);
              }
          }
      indices.resize(membrane_fe.n_dofs_per_cell());
      for (const auto &mesh : membrane_meshes)
        for (const auto &cell : mesh->dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(indices);
            for (auto &i : indices)
              i += mesh->offset;
            constraints.add_entries_local_to_global(indices, dsp, false);
          }
      for_each_solid_mesh([&](auto &solid_mesh) {
        auto *const mesh = &solid_mesh;

        indices.resize(mesh->fe->n_dofs_per_cell());
        for (const auto &cell : mesh->dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(indices);
            for (auto &i : indices)
              i += mesh->offset;
            constraints.add_entries_local_to_global(indices, dsp, false);
          }
      });
      // Diagonal entries for every DoF (constrained rows too).
      for (global_dof_index i = 0; i < total_dofs; ++i)
        dsp.add(i, i);
      sparsity.copy_from(dsp);
      raw_residual.reinit(total_dofs);

      // Lumped mass, onto the master DoFs.
      dealii::Vector<double> raw_mass(total_dofs);
      for (const auto &mesh : line_meshes)
        {
          if (mesh->sliding_cable)
            {
              const double rhoA =
                mesh->sliding_cable->density * mesh->sliding_cable->area;
              for (unsigned int k = 0; k + 1 < mesh->chain.size(); ++k)
                {
                  const double m =
                    0.5 * rhoA *
                    (mesh->chain_X[k + 1] - mesh->chain_X[k]).norm();
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      raw_mass[mesh->chain[k][c]] += m;
                      raw_mass[mesh->chain[k + 1][c]] += m;
                    }
                }
              continue;
            }
          for (const auto &cell : mesh->dof_handler.active_cell_iterators())
            {
              const double m = 0.5 * mesh->element->mass_per_length() *
                               cell->vertex(0).distance(cell->vertex(1));
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  raw_mass[mesh->offset + cell->vertex_dof_index(v, c)] += m;
            }
        }
      if (!membrane_meshes.empty())
        {
          const dealii::QGauss<2>       quadrature(2);
          dealii::FEValues<2, 3>        fe_values(membrane_fe,
                                           quadrature,
                                           dealii::update_values |
                                             dealii::update_JxW_values);
          std::vector<global_dof_index> indices(membrane_fe.n_dofs_per_cell());
          for (const auto &mesh : membrane_meshes)
            {
              const double rho_t =
                mesh->membrane->density * mesh->membrane->material.thickness;
              for (const auto &cell : mesh->dof_handler.active_cell_iterators())
                {
                  fe_values.reinit(cell);
                  cell->get_dof_indices(indices);
                  for (unsigned int i = 0; i < indices.size(); ++i)
                    {
                      const unsigned int c =
                        membrane_fe.system_to_component_index(i).first;
                      for (unsigned int q = 0; q < quadrature.size(); ++q)
                        raw_mass[mesh->offset + indices[i]] +=
                          rho_t * fe_values.shape_value_component(i, q, c) *
                          fe_values.JxW(q);
                    }
                }
            }
        }
      // Solids: row sums rho int N_I dV0; tractions int N_I t dA0.
      traction_forces.reinit(total_dofs);
      for_each_solid_mesh([&](auto &solid_mesh) {
        auto *const   mesh = &solid_mesh;
        constexpr int dim  = std::decay_t<decltype(solid_mesh)>::dimension;

        const auto               &fe = *mesh->fe;
        const dealii::QGauss<dim> quadrature(fe.degree + 1);
        dealii::FEValues<dim, 3>  fe_values(
          fe, quadrature, dealii::update_values | dealii::update_JxW_values);
        const dealii::QGauss<dim - 1> face_quadrature(fe.degree + 1);
        dealii::FEFaceValues<dim, 3>  fe_face_values(
          fe,
          face_quadrature,
          dealii::update_values | dealii::update_JxW_values);
        std::vector<global_dof_index> indices(fe.n_dofs_per_cell());
        const double rho = mesh->solid->density * mesh->thickness;
        for (const auto &cell : mesh->dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            cell->get_dof_indices(indices);
            for (unsigned int i = 0; i < indices.size(); ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                for (const unsigned int q :
                     fe_values.quadrature_point_indices())
                  raw_mass[mesh->offset + indices[i]] +=
                    rho * fe_values.shape_value_component(i, q, c) *
                    fe_values.JxW(q);
              }
            for (const auto &[id, t] : mesh->tractions)
              for (const unsigned int f : cell->face_indices())
                if (cell->at_boundary(f) && cell->face(f)->boundary_id() == id)
                  {
                    fe_face_values.reinit(cell, f);
                    for (unsigned int i = 0; i < indices.size(); ++i)
                      {
                        const unsigned int c =
                          fe.system_to_component_index(i).first;
                        for (const unsigned int q :
                             fe_face_values.quadrature_point_indices())
                          traction_forces[mesh->offset + indices[i]] +=
                            mesh->thickness * t[c] *
                            fe_face_values.shape_value_component(i, q, c) *
                            fe_face_values.JxW(q);
                      }
                  }
          }
      });
      // Onto the master DoFs (DoFs of solids that are not at a vertex are
      // their own masters).
      mass = raw_mass;
      for (const auto &node : nodes)
        for (const auto &slave : node.slaves)
          for (unsigned int c = 0; c < 3; ++c)
            {
              mass[node.dofs[c]] += raw_mass[slave[c]];
              mass[slave[c]] = 0.;
            }
    }


    void
    Structure::commit_state()
    {
      for (auto &mesh : line_meshes)
        mesh->state = mesh->trial_state;
    }


    dealii::Tensor<1, 3>
    Structure::reaction(const unsigned int node) const
    {
      dealii::Tensor<1, 3> R;
      for (unsigned int c = 0; c < 3; ++c)
        {
          R[c] = raw_residual[nodes[node].dofs[c]];
          for (const auto &s : nodes[node].slaves)
            R[c] += raw_residual[s[c]];
        }
      return R;
    }


    dealii::Tensor<1, 3>
    Structure::node_displacement(const dealii::Vector<double> &u,
                                 const unsigned int            node) const
    {
      dealii::Tensor<1, 3> d;
      for (unsigned int c = 0; c < 3; ++c)
        d[c] = u[nodes[node].dofs[c]];
      return d;
    }


    dealii::Point<3>
    Structure::node_current_position(const dealii::Vector<double> &u,
                                     const unsigned int            node) const
    {
      return nodes[node].X + node_displacement(u, node);
    }


    namespace
    {
      template <int dim>
      std::vector<unsigned int>
      vertex_nodes(const dealii::DoFHandler<dim, 3> &dof_handler,
                   const global_dof_index            offset,
                   const std::vector<unsigned int>  &dof_to_node)
      {
        std::vector<unsigned int> result(
          dof_handler.get_triangulation().n_vertices(),
          dealii::numbers::invalid_unsigned_int);
        for (const auto &cell : dof_handler.active_cell_iterators())
          for (const unsigned int v : cell->vertex_indices())
            result[cell->vertex_index(v)] =
              dof_to_node[offset + cell->vertex_dof_index(v, 0)];
        return result;
      }

      /** vertex_nodes() of mesh @p mesh of @p meshes. */
      template <typename Mesh>
      std::vector<unsigned int>
      vertex_nodes(const std::vector<std::unique_ptr<Mesh>> &meshes,
                   const unsigned int                        mesh,
                   const std::vector<unsigned int>          &dof_to_node)
      {
        AssertIndexRange(mesh, meshes.size());
        return vertex_nodes(meshes[mesh]->dof_handler,
                            meshes[mesh]->offset,
                            dof_to_node);
      }
    } // namespace


    std::vector<unsigned int>
    Structure::membrane_vertex_nodes(const unsigned int mesh) const
    {
      return vertex_nodes(membrane_meshes, mesh, dof_to_node);
    }


    std::vector<unsigned int>
    Structure::line_vertex_nodes(const unsigned int mesh) const
    {
      return vertex_nodes(line_meshes, mesh, dof_to_node);
    }


    std::vector<unsigned int>
    Structure::solid_vertex_nodes(const unsigned int mesh) const
    {
      return vertex_nodes(solid_meshes, mesh, dof_to_node);
    }


    std::vector<unsigned int>
    Structure::plane_solid_vertex_nodes(const unsigned int mesh) const
    {
      return vertex_nodes(plane_solid_meshes, mesh, dof_to_node);
    }


    void
    Structure::set_external_force(const unsigned int          node,
                                  const dealii::Tensor<1, 3> &F)
    {
      AssertIndexRange(node, nodes.size());
      for (unsigned int c = 0; c < 3; ++c)
        external_forces[nodes[node].dofs[c]] = F[c];
    }


    dealii::Tensor<1, 3>
    Structure::external_force(const unsigned int node) const
    {
      dealii::Tensor<1, 3> F;
      for (unsigned int c = 0; c < 3; ++c)
        F[c] = external_forces[nodes[node].dofs[c]];
      return F;
    }


    void
    Structure::clear_external_forces()
    {
      external_forces = 0.;
    }


    namespace
    {
      template <int dim>
      void
      write_mesh(
        const dealii::DoFHandler<dim, 3> &dof_handler,
        const global_dof_index            offset,
        const dealii::Vector<double>     &u,
        const std::vector<std::pair<std::string, dealii::Vector<double>>>
                          &cell_data,
        const std::string &filename,
        const unsigned int subdivisions = 1)
      {
        dealii::Vector<double> local(dof_handler.n_dofs());
        for (global_dof_index i = 0; i < local.size(); ++i)
          local[i] = u[offset + i];
        dealii::DataOut<dim, 3> data_out;
        data_out.attach_dof_handler(dof_handler);
        const std::vector<std::string> names(3, "displacement");
        const std::vector<
          dealii::DataComponentInterpretation::DataComponentInterpretation>
          interpretation(
            3,
            dealii::DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(local,
                                 names,
                                 dealii::DataOut<dim, 3>::type_dof_data,
                                 interpretation);
        for (const auto &[name, values] : cell_data)
          data_out.add_data_vector(values, name);
        data_out.build_patches(subdivisions);
        std::ofstream out(filename);
        if (!out)
          throw std::runtime_error("Cannot write the file <" + filename + ">.");
        data_out.write_vtu(out);
      }
    } // namespace


    void
    Structure::write_vtu(const dealii::Vector<double> &u,
                         const std::string            &directory,
                         const unsigned int            step,
                         const double                  time)
    {
      const std::string suffix =
        "_" + dealii::Utilities::int_to_string(step, 5) + ".vtu";
      pvd_records.emplace_back(time, suffix);
      const auto write_pvd = [&](const std::string &name) {
        std::vector<std::pair<double, std::string>> records;
        for (const auto &[t, s] : pvd_records)
          records.emplace_back(t, name + s);
        std::ofstream pvd(directory + "/" + name + ".pvd");
        dealii::DataOutBase::write_pvd_record(pvd, records);
      };
      for (const auto &mesh : line_meshes)
        {
          dealii::Vector<double> force(mesh->force.begin(), mesh->force.end());
          std::vector<std::pair<std::string, dealii::Vector<double>>> data = {
            {"axial_force", force}};
          if (mesh->element && mesh->element->name() == "brake")
            {
              dealii::Vector<double> stroke(mesh->state.size());
              for (unsigned int k = 0; k < stroke.size(); ++k)
                stroke[k] = mesh->state[k].plastic;
              data.emplace_back("stroke", stroke);
            }
          write_mesh(mesh->dof_handler,
                     mesh->offset,
                     u,
                     data,
                     directory + "/" + mesh->name + suffix);
          write_pvd(mesh->name);
        }
      for (const auto &mesh : membrane_meshes)
        {
          const unsigned int     n = mesh->cell_output.size();
          dealii::Vector<double> mean(n), smax(n), smin(n), state(n);
          for (unsigned int k = 0; k < n; ++k)
            {
              mean[k]  = mesh->cell_output[k].mean_stress;
              smax[k]  = mesh->cell_output[k].max_principal;
              smin[k]  = mesh->cell_output[k].min_principal;
              state[k] = mesh->cell_output[k].n_slack > 0 ?
                           2. :
                           (mesh->cell_output[k].n_wrinkled > 0 ? 1. : 0.);
            }
          write_mesh(mesh->dof_handler,
                     mesh->offset,
                     u,
                     {{"mean_stress", mean},
                      {"max_principal_stress", smax},
                      {"min_principal_stress", smin},
                      {"wrinkling_state", state}},
                     directory + "/" + mesh->name + suffix);
          write_pvd(mesh->name);
        }
      for_each_solid_mesh([&](auto &solid_mesh) {
        auto *const mesh = &solid_mesh;

        const unsigned int     n = mesh->cell_output.size();
        dealii::Vector<double> von_mises(n), mean(n), energy(n);
        for (unsigned int k = 0; k < n; ++k)
          {
            von_mises[k] = mesh->cell_output[k].von_mises;
            mean[k]      = mesh->cell_output[k].mean_stress;
            energy[k]    = mesh->cell_output[k].strain_energy;
          }
        write_mesh(mesh->dof_handler,
                   mesh->offset,
                   u,
                   {{"von_mises_stress", von_mises},
                    {"mean_stress", mean},
                    {"strain_energy", energy}},
                   directory + "/" + mesh->name + suffix,
                   mesh->fe->degree);
        write_pvd(mesh->name);
      });
    }


    double
    Structure::strain_energy() const
    {
      return last_strain_energy;
    }


    double
    Structure::dissipated_energy() const
    {
      double D = 0.;
      for (const auto &mesh : line_meshes)
        if (mesh->element && !mesh->sliding_cable)
          for (const auto &cell : mesh->dof_handler.active_cell_iterators())
            {
              dealii::Tensor<1, 3> X[2];
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  X[v][c] = cell->vertex(v)[c];
              D += mesh->element->dissipated_energy(
                X[0], X[1], mesh->state[cell->active_cell_index()]);
            }
      return D;
    }


    const dealii::Vector<double> &
    Structure::lumped_mass() const
    {
      return mass;
    }


    global_dof_index
    Structure::n_dofs() const
    {
      return total_dofs;
    }


    const dealii::AffineConstraints<double> &
    Structure::get_constraints() const
    {
      return constraints;
    }


    const dealii::SparsityPattern &
    Structure::get_sparsity_pattern() const
    {
      return sparsity;
    }
  } // namespace Structure
} // namespace Talus
