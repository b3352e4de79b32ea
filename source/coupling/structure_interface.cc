#include <talus/base/input.h>
#include <talus/coupling/structure_interface.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/fe/fe_q.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace Coupling
  {
    namespace
    {
      const std::string section = "Coupling/Interface";

      /** The key of a reference position (its exact coordinates). */
      template <int dim>
      std::vector<double>
      key(const dealii::Point<dim> &X)
      {
        return std::vector<double>(X.begin_raw(), X.end_raw());
      }
    } // namespace


    template <int dim>
    void
    StructureInterface<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry(
        "structure mesh",
        "",
        dealii::Patterns::Anything(),
        "Name of the mesh of the structure that the material touches: a "
        "membrane (3D), a line mesh in the plane z = 0 (2D, a string), or a "
        "continuum solid (its boundary). Its Gauss points become the "
        "boundary particles of the MPM boundaries listed in 'boundaries'.");
      prm.declare_entry(
        "boundaries",
        "",
        dealii::Patterns::List(dealii::Patterns::Anything()),
        "Names (entry 'name' of subsection Boundary particles/Boundary N) "
        "of the MPM boundaries with 'geometry = external' that the "
        "interface mesh becomes; two of them (one with 'flip normals') let "
        "the material hit both faces of a net.");
      prm.declare_entry(
        "structure boundary ids",
        "",
        dealii::Patterns::List(dealii::Patterns::Integer(0, 255)),
        "Only for a continuum solid as 'structure mesh': the boundary ids of "
        "its faces that form the interface (a generated box has ids 0 to 5 "
        "on x_min, x_max, y_min, y_max, z_min, z_max, a plane rectangle 0 "
        "to 3); empty: its whole boundary.");
    }


    template <int dim>
    void
    StructureInterface<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      mesh = prm.get("structure mesh");
      boundary_names.clear();
      for (const auto &name :
           dealii::Utilities::split_string_list(prm.get("boundaries")))
        if (!name.empty())
          boundary_names.push_back(name);
      structure_boundary_ids.clear();
      for (const auto &id : dealii::Utilities::split_string_list(
             prm.get("structure boundary ids")))
        if (!id.empty())
          structure_boundary_ids.insert(static_cast<dealii::types::boundary_id>(
            dealii::Utilities::string_to_int(id)));
      if (mesh.empty())
        InputFile::reject(section,
                          "structure mesh",
                          "",
                          "a coupled problem needs an interface: the name "
                          "of a mesh of the structure");
      if (boundary_names.empty())
        InputFile::reject(section,
                          "boundaries",
                          prm.get("boundaries"),
                          "a coupled problem needs an interface: the name "
                          "of at least one MPM boundary with geometry = "
                          "external");
    }


    template <int dim>
    void
    StructureInterface<dim>::attach(
      const Structure::Structure         &structure,
      Boundaries::BoundaryParticles<dim> &boundaries)
    {
      // The surface in the MPM's space, from the mesh's vertices and cells.
      std::vector<dealii::Point<dim>>        vertices;
      std::vector<dealii::CellData<dim - 1>> cells;
      std::vector<std::string>               names;
      bool                                   found = false;
      const auto                             take  = [&](const auto &tria) {
        std::map<unsigned int, unsigned int> index;
        for (const auto &cell : tria.active_cell_iterators())
          {
            dealii::CellData<dim - 1> c;
            c.vertices.resize(cell->n_vertices());
            for (unsigned int v = 0; v < cell->n_vertices(); ++v)
              {
                const auto g = cell->vertex_index(v);
                if (index.count(g) == 0)
                  {
                    const dealii::Point<3> &x = cell->vertex(v);
                    dealii::Point<dim>      y;
                    for (unsigned int d = 0; d < dim; ++d)
                      y[d] = x[d];
                    if (dim == 2 && std::abs(x[2]) > 1e-12 * (1. + x.norm()))
                      InputFile::reject(
                        section,
                        "structure mesh",
                        mesh,
                        "the interface of a 2D problem must lie in the plane "
                                                     "z = 0 of the structure (a string of the 2D problem); "
                                                     "this mesh has a vertex at z = " +
                          std::to_string(x[2]));
                    index[g] = vertices.size();
                    vertices.push_back(y);
                  }
                c.vertices[v] = index[g];
              }
            cells.push_back(c);
          }
        found = true;
      };
      const auto reject_ids = [&](const std::string &what) {
        if (!structure_boundary_ids.empty())
          InputFile::reject(section,
                            "structure boundary ids",
                            ids_text(),
                            "empty: the interface mesh <" + mesh + "> is " +
                              what + ", not a continuum solid");
      };
      for (const auto &m : structure.line_meshes)
        {
          names.push_back(m->name);
          if (m->name == mesh)
            {
              reject_ids("a line mesh");
              if constexpr (dim == 2)
                take(m->triangulation);
              else
                InputFile::reject(section,
                                  "structure mesh",
                                  mesh,
                                  "a 3D interface is a surface: a membrane "
                                  "or a solid, not the line mesh <" +
                                    mesh + ">");
            }
        }
      for (const auto &m : structure.membrane_meshes)
        {
          names.push_back(m->name);
          if (m->name == mesh)
            {
              reject_ids("a membrane");
              if constexpr (dim == 3)
                take(m->triangulation);
              else
                InputFile::reject(section,
                                  "structure mesh",
                                  mesh,
                                  "a 2D interface is a line in the plane "
                                  "z = 0 (a string), not the membrane <" +
                                    mesh + ">");
            }
        }
      const auto take_solid = [&](const auto &m) {
        names.push_back(m.name);
        if (m.name != mesh)
          return;
        using Mesh = std::decay_t<decltype(m)>;
        if constexpr (Mesh::dimension != dim)
          InputFile::reject(section,
                            "structure mesh",
                            mesh,
                            "the solid <" + mesh + "> is " +
                              std::to_string(Mesh::dimension) + "D, the MPM " +
                              std::to_string(dim) + "D");
        else
          {
            // the transfer's FE_Q(1) surface has DoFs at the vertices only
            if (m.fe->degree != 1)
              InputFile::reject("Structure/Solid",
                                "degree",
                                std::to_string(m.fe->degree),
                                "1 for the solid <" + mesh +
                                  ">, the coupling interface (the interface "
                                  "transfer is linear between the vertices "
                                  "of the solid's faces)");
            // its boundary faces (those with the listed ids), as a mesh of
            // their own
            std::set<dealii::types::boundary_id> present;
            for (const auto &face : m.triangulation.active_face_iterators())
              if (face->at_boundary())
                present.insert(face->boundary_id());
            for (const auto id : structure_boundary_ids)
              if (present.count(id) == 0)
                {
                  std::string list;
                  for (const auto p : present)
                    list += (list.empty() ? "" : ", ") + std::to_string(p);
                  InputFile::reject(section,
                                    "structure boundary ids",
                                    ids_text(),
                                    "boundary ids of faces of the solid <" +
                                      mesh + "> (it has: " + list +
                                      "); there is no face with id " +
                                      std::to_string(id));
                }
            dealii::Triangulation<dim - 1, 3> boundary;
            dealii::GridGenerator::extract_boundary_mesh(
              m.triangulation, boundary, structure_boundary_ids);
            take(boundary);
          }
      };
      structure.for_each_solid_mesh(take_solid);
      if (!found)
        {
          std::string list;
          for (const auto &n : names)
            list += (list.empty() ? "" : ", ") + n;
          InputFile::reject(section,
                            "structure mesh",
                            mesh,
                            "the name of a mesh of the structure (it has: " +
                              list + ")");
        }
      surface.clear();
      dealii::SubCellData none;
      surface.create_triangulation(vertices, cells, none);
      dof_handler.reinit(surface);
      dof_handler.distribute_dofs(fe);

      // Each surface DoF is a DoF of the structure node at its vertex.
      structure_dofs.assign(dof_handler.n_dofs(),
                            dealii::numbers::invalid_dof_index);
      double size = 0.;
      for (const auto &v : vertices)
        size = std::max(size, v.norm());
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (unsigned int v = 0; v < cell->n_vertices(); ++v)
          {
            dealii::Point<3> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = cell->vertex(v)[d];
            const unsigned int node =
              structure.find_node(x, 1e-9 * (1. + size));
            AssertThrow(node != dealii::numbers::invalid_unsigned_int,
                        dealii::ExcMessage("internal: no structure node at an "
                                           "interface vertex"));
            for (unsigned int c = 0; c < dim; ++c)
              structure_dofs[cell->vertex_dof_index(v, c)] =
                structure.node_dof(node, c);
          }

      // The boundaries that the surface becomes.
      boundary_ids.clear();
      for (const auto &name : boundary_names)
        {
          unsigned int b = 0;
          while (b < boundaries.n_boundaries() && boundaries.name(b) != name)
            ++b;
          if (b == boundaries.n_boundaries())
            {
              std::string list;
              for (unsigned int k = 0; k < boundaries.n_boundaries(); ++k)
                list += (list.empty() ? "" : ", ") + boundaries.name(k);
              InputFile::reject(section,
                                "boundaries",
                                name,
                                "names of boundaries of subsection Boundary "
                                "particles (it has: " +
                                  (list.empty() ? std::string("none") : list) +
                                  ")");
            }
          if (boundaries.boundary(b).geometry != "external")
            InputFile::reject("Boundary particles",
                              "geometry",
                              boundaries.boundary(b).geometry,
                              "'external' for boundary '" + name +
                                "', the coupling interface (its surface is "
                                "the structure mesh '" +
                                mesh + "')");
          if (std::find(boundary_ids.begin(), boundary_ids.end(), b) !=
              boundary_ids.end())
            InputFile::reject(section,
                              "boundaries",
                              name,
                              "each boundary at most once");
          boundary_ids.push_back(b);
          boundaries.set_surface(b, surface);
          boundaries.set_displacement(b,
                                      [this](const dealii::Point<dim> &X,
                                             const double              t) {
                                        return displacement_at(X, t);
                                      });
        }
    }


    template <int dim>
    void
    StructureInterface<dim>::setup(
      const Boundaries::BoundaryParticles<dim> &boundaries,
      const MPI_Comm                            communicator)
    {
      using BP = Boundaries::BoundaryParticleProperties<dim>;
      // (particle index, boundary, X) of this rank's interface particles
      std::vector<double> local;
      for (const auto &p : boundaries.particle_handler())
        {
          const auto         props = p.get_properties();
          const unsigned int b = static_cast<unsigned int>(props[BP::boundary]);
          if (std::find(boundary_ids.begin(), boundary_ids.end(), b) ==
              boundary_ids.end())
            continue;
          local.push_back(static_cast<double>(p.get_id()));
          local.push_back(b);
          local.push_back(props[BP::weight]);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(props[BP::reference_position + d]);
        }
      const auto gathered =
        dealii::Utilities::MPI::all_gather(communicator, local);
      std::vector<dealii::Point<dim>> points;
      std::vector<unsigned int>       per_boundary(boundary_ids.size(), 0);
      point_of_particle.clear();
      point_of_position.clear();
      std::vector<
        std::tuple<dealii::types::particle_index, dealii::Point<dim>, double>>
        all;
      for (const auto &rank : gathered)
        for (unsigned int k = 0; k < rank.size(); k += 3 + dim)
          {
            dealii::Point<dim> X;
            for (unsigned int d = 0; d < dim; ++d)
              X[d] = rank[k + 3 + d];
            all.emplace_back(static_cast<dealii::types::particle_index>(
                               rank[k]),
                             X,
                             rank[k + 2]);
            const auto b = static_cast<unsigned int>(rank[k + 1]);
            ++per_boundary[std::find(
                             boundary_ids.begin(), boundary_ids.end(), b) -
                           boundary_ids.begin()];
          }
      // the same order on every rank
      std::sort(all.begin(), all.end(), [](const auto &a, const auto &b) {
        return std::get<0>(a) < std::get<0>(b);
      });
      point_weights.clear();
      for (const auto &[id, X, w] : all)
        {
          point_of_particle[id] = points.size();
          point_of_position.emplace(key(X), points.size());
          points.push_back(X);
          point_weights.push_back(w);
        }
      for (unsigned int k = 0; k < boundary_ids.size(); ++k)
        if (per_boundary[k] == 0)
          InputFile::reject(section,
                            "boundaries",
                            boundary_names[k],
                            "a boundary with boundary particles: the "
                            "interface mesh '" +
                              mesh +
                              "' lies outside the MPM's background grid "
                              "(move the structure or enlarge the grid)");
      transfer.reinit(dof_handler, points, 1e-8);
      u_start.assign(points.size(), dealii::Tensor<1, dim>());
      u_end = u_start;
    }


    template <int dim>
    void
    StructureInterface<dim>::set_step_displacement(
      const dealii::Vector<double> &U_start,
      const dealii::Vector<double> &U_end,
      const double                  t0,
      const double                  t1)
    {
      u_start = point_displacements(U_start);
      u_end   = point_displacements(U_end);
      t_start = t0;
      t_end   = t1;
    }


    template <int dim>
    std::vector<dealii::Tensor<1, dim>>
    StructureInterface<dim>::point_displacements(
      const dealii::Vector<double> &U) const
    {
      dealii::Vector<double> local(dof_handler.n_dofs());
      for (unsigned int i = 0; i < local.size(); ++i)
        local[i] = U[structure_dofs[i]];
      return transfer.interpolate(local);
    }


    template <int dim>
    dealii::Tensor<1, dim>
    StructureInterface<dim>::displacement_at(const dealii::Point<dim> &X,
                                             const double              t) const
    {
      // Before setup() (the particles are being made): the reference
      // configuration.
      if (point_of_position.empty())
        return dealii::Tensor<1, dim>();
      const auto it = point_of_position.find(key(X));
      AssertThrow(it != point_of_position.end(),
                  dealii::ExcMessage("internal: a boundary particle of the "
                                     "interface is not an interface point"));
      const unsigned int p = it->second;
      if (!(t_end > t_start) || t <= t_start)
        return t > t_start && t_end > t_start ? u_end[p] : u_start[p];
      if (t >= t_end)
        return u_end[p];
      const double s = (t - t_start) / (t_end - t_start);
      return u_start[p] + s * (u_end[p] - u_start[p]);
    }


    template <int dim>
    dealii::Vector<double>
    StructureInterface<dim>::structure_forces(
      const std::vector<std::pair<dealii::types::particle_index,
                                  dealii::Tensor<1, dim>>> &reactions,
      const unsigned int                                    n_dofs,
      const MPI_Comm                                        communicator) const
    {
      // The point forces of all points (zero where this rank has none),
      // summed over the ranks: one reduction of the interface vector.
      std::vector<double> f(dim * transfer.n_points(), 0.);
      for (const auto &[id, R] : reactions)
        {
          const auto it = point_of_particle.find(id);
          if (it == point_of_particle.end())
            continue;
          for (unsigned int d = 0; d < dim; ++d)
            f[dim * it->second + d] += R[d];
        }
      dealii::Utilities::MPI::sum(f, communicator, f);
      last_point_forces.assign(transfer.n_points(), dealii::Tensor<1, dim>());
      last_total_force = dealii::Tensor<1, dim>();
      for (unsigned int p = 0; p < transfer.n_points(); ++p)
        for (unsigned int d = 0; d < dim; ++d)
          {
            last_point_forces[p][d] = f[dim * p + d];
            last_total_force[d] += f[dim * p + d];
          }
      return to_structure(last_point_forces, n_dofs);
    }


    template <int dim>
    dealii::Vector<double>
    StructureInterface<dim>::to_structure(
      const std::vector<dealii::Tensor<1, dim>> &f,
      const unsigned int                         n_dofs) const
    {
      dealii::Vector<double> local(dof_handler.n_dofs());
      transfer.distribute(f, local);
      dealii::Vector<double> F(n_dofs);
      for (unsigned int i = 0; i < local.size(); ++i)
        F[structure_dofs[i]] += local[i];
      return F;
    }


    template <int dim>
    dealii::Vector<double>
    StructureInterface<dim>::covered_area(
      const std::vector<std::pair<dealii::types::particle_index,
                                  dealii::Tensor<1, dim>>> &reactions,
      const unsigned int                                    n_dofs,
      const MPI_Comm                                        communicator,
      const bool                                            normal_only) const
    {
      // the reaction of every point, summed over the ranks (a point's
      // reaction may be booked on several ranks by the points touching it)
      std::vector<double> reaction(transfer.n_points() * dim, 0.);
      for (const auto &entry : reactions)
        {
          const auto it = point_of_particle.find(entry.first);
          if (it != point_of_particle.end())
            for (unsigned int d = 0; d < dim; ++d)
              reaction[it->second * dim + d] += entry.second[d];
        }
      dealii::Utilities::MPI::sum(reaction, communicator, reaction);
      std::vector<dealii::Tensor<1, dim>> w(transfer.n_points());
      for (unsigned int p = 0; p < w.size(); ++p)
        {
          dealii::Tensor<1, dim> f;
          for (unsigned int d = 0; d < dim; ++d)
            f[d] = reaction[p * dim + d];
          const double norm = f.norm();
          if (!(norm > 0.))
            continue;
          for (unsigned int d = 0; d < dim; ++d)
            w[p][d] =
              point_weights[p] *
              (normal_only ? dealii::Utilities::fixed_power<2>(f[d] / norm) :
                             1.);
        }
      return to_structure(w, n_dofs);
    }


    template <int dim>
    std::vector<dealii::types::global_dof_index>
    StructureInterface<dim>::interface_structure_dofs() const
    {
      std::vector<dealii::types::global_dof_index> dofs(structure_dofs);
      std::sort(dofs.begin(), dofs.end());
      dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
      return dofs;
    }


    template <int dim>
    unsigned int
    StructureInterface<dim>::point_of(
      const dealii::types::particle_index id) const
    {
      const auto it = point_of_particle.find(id);
      return it == point_of_particle.end() ?
               dealii::numbers::invalid_unsigned_int :
               it->second;
    }


    template <int dim>
    std::vector<dealii::Vector<double>>
    StructureInterface<dim>::linearised_structure_forces(
      const std::vector<std::vector<
        std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>>
                        &columns,
      const unsigned int n_dofs,
      const MPI_Comm     communicator) const
    {
      const unsigned int  n_points = transfer.n_points();
      std::vector<double> f(columns.size() * dim * n_points, 0.);
      for (unsigned int c = 0; c < columns.size(); ++c)
        for (const auto &[id, R] : columns[c])
          {
            const auto it = point_of_particle.find(id);
            if (it == point_of_particle.end())
              continue;
            for (unsigned int d = 0; d < dim; ++d)
              f[(c * n_points + it->second) * dim + d] += R[d];
          }
      dealii::Utilities::MPI::sum(f, communicator, f);
      std::vector<dealii::Vector<double>> F(columns.size());
      std::vector<dealii::Tensor<1, dim>> point_forces(n_points);
      for (unsigned int c = 0; c < columns.size(); ++c)
        {
          for (unsigned int p = 0; p < n_points; ++p)
            for (unsigned int d = 0; d < dim; ++d)
              point_forces[p][d] = f[(c * n_points + p) * dim + d];
          F[c] = to_structure(point_forces, n_dofs);
        }
      return F;
    }


    template <int dim>
    std::vector<bool>
    StructureInterface<dim>::loaded_points() const
    {
      std::vector<bool> loaded(last_point_forces.size());
      for (unsigned int p = 0; p < loaded.size(); ++p)
        loaded[p] = last_point_forces[p].norm() > 0.;
      return loaded;
    }


    template <int dim>
    std::pair<double, double>
    StructureInterface<dim>::interface_work(
      const dealii::Vector<double> &U,
      const dealii::Vector<double> &F) const
    {
      const auto u      = point_displacements(U);
      double     points = 0.;
      for (unsigned int p = 0; p < u.size() && p < last_point_forces.size();
           ++p)
        points += u[p] * last_point_forces[p];
      return {U * F, points};
    }


    template <int dim>
    std::string
    StructureInterface<dim>::ids_text() const
    {
      std::string text;
      for (const auto id : structure_boundary_ids)
        text += (text.empty() ? "" : ", ") + std::to_string(id);
      return text;
    }


    template class StructureInterface<2>;
    template class StructureInterface<3>;
  } // namespace Coupling
} // namespace Talus
