// Structure verification model: block hanging under its own weight (set problem
// = structure).

#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/app/structure_models/solid_model.h>
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
       * A block hanging on a cable: the generated box of subsection Solid
       * (subdivisions even along x and y, so that the centre of its top
       * face is a vertex) and a vertical cable (subsection Line members,
       * 'elements per member' elements) from the anchor at 'cable length'
       * above that point down to it, tied to the block there. Symmetry
       * supports: u_x = 0 on the plane x = x_c and u_y = 0 on y = y_c of the
       * block and on every cable node (exact for this symmetric problem;
       * they hold the block's rotations, which a cable through one node
       * does not). Under gravity (0, 0, -g), reference by hand: the block
       * weighs W = rho g V (consistent gravity integrates it exactly), the
       * cable element k from the bottom (length l = L_c/n, lumped weights)
       * carries N_k = W + w l (k + 1/2), w = rho_c A_c g, and stretches by
       * (lambda_k - 1) l with EA lambda (lambda^2 - 1)/2 = N_k (the
       * element's law); the attachment point drops by their sum and the
       * anchor carries W + w L_c. 'plane hanging block': the rectangle in
       * the x-y plane (V = its area times the thickness) on a 2D string
       * (PlaneString) along y, gravity (0, -g, 0), u_x = 0 on the string
       * and on the line x = x_c of the block.
       */
      class HangingBlock : public SolidModel
      {
      public:
        using SolidModel::SolidModel;

        std::string
        description() const override
        {
          return p.plane_solid ?
                   "plane-strain block (continuum solid, FE_Q(" +
                     std::to_string(p.solid.degree) +
                     ")) hanging on a 2D string tied to the centre of its "
                     "top edge" :
                   "block (continuum solid, FE_Q(" +
                     std::to_string(p.solid.degree) +
                     ")) hanging on a cable tied to the centre of its top "
                     "face";
        }

        bool
        supports_dynamics() const override
        {
          return false;
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          const auto &n = p.solid_geometry.subdivisions;
          return {{structure_section + "/Solid",
                   "subdivisions",
                   std::to_string(n[0]) + ", " + std::to_string(n[1]) + ", " +
                     std::to_string(n[2])}};
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const auto  &g   = p.solid_geometry;
          const double big = 1. + g.lower_corner.distance(g.upper_corner);
          if (p.plane_solid)
            {
              // The block in the x-y plane on a 2D string along y.
              attach_point =
                Point<3>(0.5 * (g.lower_corner[0] + g.upper_corner[0]),
                         g.upper_corner[1],
                         0.);
              anchor_point = attach_point + Point<3>(0., p.cable_length, 0.);
              std::vector<Point<2>>    x(p.elements + 1);
              std::vector<CellData<1>> cells(p.elements);
              for (unsigned int k = 0; k <= p.elements; ++k)
                x[k] =
                  Point<2>(anchor_point[0],
                           anchor_point[1] - p.cable_length * k / p.elements);
              for (unsigned int k = 0; k < p.elements; ++k)
                cells[k].vertices = {k, k + 1};
              string.triangulation.create_triangulation(x,
                                                        cells,
                                                        SubCellData());
              string.add_to(s, "cable", line_element());
              add_solid_mesh(s, "block", level);
              s.setup_dofs();
              string.setup(s);
              anchor = string.node(0);
              string.fix(s, 0);
              // Symmetry: u_x = 0 on the string and on the line x = x_c.
              for (unsigned int k = 0; k <= p.elements; ++k)
                s.prescribe(string.node(k), 0);
              s.prescribe_solid_box(
                *s.plane_solid_meshes[0],
                Point<3>(attach_point[0], attach_point[1] - big, -big),
                Point<3>(attach_point[0], attach_point[1] + big, big),
                {true, false, false});
              s.gravity = p.gravity;
              return;
            }
          const Point<3> top(0.5 * (g.lower_corner[0] + g.upper_corner[0]),
                             0.5 * (g.lower_corner[1] + g.upper_corner[1]),
                             g.upper_corner[2]);
          anchor_point = top + Point<3>(0., 0., p.cable_length);
          attach_point = top;
          make_line(s.add_line_mesh("cable", line_element()).triangulation,
                    anchor_point,
                    top,
                    p.elements);
          add_solid_mesh(s, "block", level);
          s.setup_dofs();
          anchor = node_at(s, anchor_point);
          for (unsigned int c = 0; c < 3; ++c)
            s.prescribe(anchor, c);
          for (const unsigned int k : s.line_vertex_nodes(0))
            for (unsigned int c = 0; c < 2; ++c)
              s.prescribe(k, c);
          s.prescribe_solid_box(0,
                                Point<3>(top[0], top[1] - big, top[2] - big),
                                Point<3>(top[0], top[1] + big, top[2] + big),
                                {true, false, false});
          s.prescribe_solid_box(0,
                                Point<3>(top[0] - big, top[1], top[2] - big),
                                Point<3>(top[0] + big, top[1], top[2] + big),
                                {false, true, false});
          s.gravity = p.gravity;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const auto &g = p.solid_geometry;
          // Volume: the box, or the rectangle times the thickness.
          const double V =
            (g.upper_corner[0] - g.lower_corner[0]) * width() * height();
          const unsigned int up   = vertical();
          const double       gz   = -p.gravity[up];
          const double       W    = p.solid.density * gz * V;
          const double       w    = p.density * p.A * gz;
          const double       l    = p.cable_length / p.elements;
          const double       EA   = p.E * p.A;
          double             drop = 0.;
          for (unsigned int k = 0; k < p.elements; ++k)
            {
              const double N      = W + w * l * (k + 0.5);
              const double lambda = bisect(
                [&](const double x) { return EA * x * (x * x - 1.) / 2. - N; },
                1.,
                2. + N / EA);
              drop += (lambda - 1.) * l;
            }
          // The cable element next to the block carries N_0.
          const auto &cable    = *s.line_meshes[0];
          double      N_bottom = 0.;
          for (const auto &cell : cable.triangulation.active_cell_iterators())
            if (cell->center().distance(attach_point) < 0.6 * l)
              N_bottom = cable.force[cell->active_cell_index()];
          const unsigned int attach = node_at(s, attach_point);
          Point<3>           bottom = attach_point;
          bottom[up]                = g.lower_corner[up];
          return {{"anchor force [N]",
                   s.reaction(anchor)[up],
                   W + w * p.cable_length},
                  {"cable force at the block [N]", N_bottom, W + 0.5 * w * l},
                  {"drop of the attachment point [m]",
                   -s.node_displacement(u, attach)[up],
                   drop},
                  {"drop of the block's bottom centre [m]",
                   -s.node_displacement(u, node_at(s, bottom))[up],
                   0.,
                   false}};
        }

      private:
        Point<3>                      anchor_point, attach_point;
        unsigned int                  anchor = 0;
        Talus::Structure::PlaneString string; ///< the plane model's cable
      };
    } // namespace


    std::unique_ptr<Model>
    create_hanging_block(const Parameters &p)
    {
      return std::make_unique<HangingBlock>(p);
    }


  } // namespace StructureModels
} // namespace Talus
