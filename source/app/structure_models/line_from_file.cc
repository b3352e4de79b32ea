// Structure verification model: line or membrane mesh from a Gmsh file (set
// problem = structure).

#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/base/input.h>
#include <talus/structure/barrier_builder.h>
#include <talus/structure/continuum_solid.h>
#include <talus/structure/dynamic_solver.h>
#include <talus/structure/mesh_input.h>
#include <talus/structure/plane_string.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_values.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace StructureModels
  {
    namespace
    {
      using namespace dealii;

      // ------------------------------------------------------------------
      /**
       * A line mesh from a Gmsh file (cables or trusses), the vertices of
       * only one cell (the ends) fixed, under gravity; or a membrane mesh
       * (quadrilaterals), its boundary fixed, under pressure and gravity.
       * The largest nodal displacement is reported, and compared with
       * 'reference largest displacement' if that is set (e.g. the
       * taut-string sag, the square membrane's w_max).
       */
      class LineFromFile : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return p.mesh_is_membrane ?
                   "membrane mesh from a file, boundary fixed, pressure and "
                   "gravity" :
                   "line mesh from a file, ends fixed, gravity";
        }

        template <int dim>
        void
        read(Triangulation<dim, 3> &tria, const std::string &what) const
        {
          Talus::Structure::read_gmsh_mesh(tria,
                                           p.mesh_file,
                                           structure_section + "/Geometry",
                                           "mesh file",
                                           what);
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          return {{structure_section + "/Geometry", "mesh file", p.mesh_file}};
        }

        void
        build(Structure &s, const unsigned int) override
        {
          if (p.mesh_is_membrane)
            {
              auto &mesh = s.add_membrane("mesh", membrane());
              read(mesh.triangulation, "quadrilaterals");
              s.setup_dofs();
              // Fix the boundary: vertices of faces without a neighbour.
              for (const auto &cell :
                   mesh.triangulation.active_cell_iterators())
                for (const unsigned int f : cell->face_indices())
                  if (cell->at_boundary(f))
                    for (unsigned int v = 0; v < 2; ++v)
                      for (unsigned int c = 0; c < 3; ++c)
                        s.prescribe(node_at(s, cell->face(f)->vertex(v)), c);
              s.gravity = p.gravity;
              return;
            }
          auto &mesh = s.add_line_mesh("mesh", line_element());
          read(mesh.triangulation, "line elements");
          s.setup_dofs();
          // Fix the two ends (vertices of one cell only).
          std::vector<unsigned int> count(mesh.triangulation.n_vertices(), 0);
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              ++count[cell->vertex_index(v)];
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              if (count[cell->vertex_index(v)] == 1)
                for (unsigned int c = 0; c < 3; ++c)
                  s.prescribe(node_at(s, cell->vertex(v)), c);
          s.gravity = p.gravity;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          double umax = 0.;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            umax = std::max(umax, s.node_displacement(u, k).norm());
          if (p.reference_displacement > 0.)
            return {
              {"largest displacement [m]", umax, p.reference_displacement}};
          return {{"largest displacement [m]", umax, 0., false}};
        }
      };
    } // namespace


    std::unique_ptr<Model>
    create_line_from_file(const Parameters &p)
    {
      return std::make_unique<LineFromFile>(p);
    }


  } // namespace StructureModels
} // namespace Talus
