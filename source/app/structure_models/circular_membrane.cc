// Structure verification model: Hencky circular membrane (set problem =
// structure).

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

      /**
       * Hencky's clamped circular membrane under uniform (follower)
       * pressure q: w0 = c_w a (q a/(E t))^(1/3), sigma_centre = c_sigma (E
       * q^2 a^2/t^2)^(1/3); c_w, c_sigma from contrib/reference/
       * hencky_membrane.py (nu = 0.25, 0.3, 0.5). The mean Cauchy stress of
       * the cells around the centre is compared with sigma_centre.
       */
      class CircularMembrane : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "Hencky clamped circular membrane under pressure";
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          make_flat_mesh(s.add_membrane("membrane", membrane()).triangulation,
                         true,
                         p.radius,
                         p.refinements + level);
          s.setup_dofs();
          for (const unsigned int n : s.find_nodes([&](const Point<3> &x) {
                 return x.norm() > p.radius * (1. - 1e-10);
               }))
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(n, c);
          centre = node_at(s, Point<3>());
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            {
              const Point<3> &x = s.node_position(k);
              u[s.node_dof(k, 2)] =
                p.initial_deflection *
                std::max(0., 1. - x.norm_square() / (p.radius * p.radius));
            }
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          double c_w = 0., c_s = 0.;
          if (std::abs(p.membrane_nu - 0.3) < 1e-12)
            {
              c_w = 0.653443;
              c_s = 0.431101;
            }
          else if (std::abs(p.membrane_nu - 0.25) < 1e-12)
            {
              c_w = 0.665791;
              c_s = 0.425612;
            }
          else if (std::abs(p.membrane_nu - 0.5) < 1e-12)
            {
              c_w = 0.594879;
              c_s = 0.461328;
            }
          else
            InputFile::reject(structure_section + "/Membrane",
                              "Poisson's ratio",
                              std::to_string(p.membrane_nu),
                              "the circular membrane model has reference "
                              "values for 0.25, 0.3 and 0.5 only");
          const double Q = p.pressure * p.radius / (p.membrane_E * p.thickness);
          const double w0 = c_w * p.radius * std::cbrt(Q);
          const double sc =
            c_s * std::cbrt(p.membrane_E * p.pressure * p.pressure * p.radius *
                            p.radius / (p.thickness * p.thickness));
          // Mean stress of the cells that touch the centre.
          const auto &mesh = *s.membrane_meshes[0];
          double      sum = 0., area = 0.;
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              if (cell->vertex(v).norm() < 1e-12 * p.radius)
                {
                  const auto &o = mesh.cell_output[cell->active_cell_index()];
                  sum += o.mean_stress * o.area;
                  area += o.area;
                }
          return {{"centre deflection w0 [m]", u[s.node_dof(centre, 2)], w0},
                  {"centre stress [Pa]", sum / area, sc}};
        }

      private:
        unsigned int centre = 0;
      };
    } // namespace


    std::unique_ptr<Model>
    create_circular_membrane(const Parameters &p)
    {
      return std::make_unique<CircularMembrane>(p);
    }


  } // namespace StructureModels
} // namespace Talus
