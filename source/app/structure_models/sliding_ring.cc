// Structure verification model: sliding ring (set problem = structure).

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
       * Frictionless ring on a cable (sliding cable through 3 nodes):
       * supports A = (-b,0,0), B = (b,0,0), unstretched length L_u, load P
       * at the ring (any direction in the x-z plane). The ring lies on the
       * ellipse with foci A, B and l = |x - A| + |x - B|, where its normal
       * is parallel to P; one tension T = EA lambda (lambda^2 - 1)/2,
       * lambda = l/L_u, on both sides (engineering law: T = EA (lambda -
       * 1), AxialLaw), and T |e_A + e_B| = |P|.
       */
      class SlidingRing : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "frictionless ring on a cable (sliding cable)";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          auto         cable = sliding_cable();
          const double b     = p.half_span;
          // Reference: the ring below the middle, chords adding up to L_u.
          const double L = p.unstretched_length;
          if (!(L > 2. * b))
            InputFile::reject(structure_section + "/Geometry",
                              "unstretched length",
                              std::to_string(L),
                              "the sliding ring needs a cable longer than the "
                              "span 2 * 'half span'");
          const double f0 = std::sqrt(0.25 * L * L - b * b);
          make_polyline(s.add_sliding_cable("cable", cable).triangulation,
                        {Point<3>(-b, 0, 0),
                         Point<3>(0, 0, -f0),
                         Point<3>(b, 0, 0)});
          s.setup_dofs();
          A    = node_at(s, Point<3>(-b, 0, 0));
          B    = node_at(s, Point<3>(b, 0, 0));
          ring = node_at(s, Point<3>(0, 0, -f0));
          for (unsigned int c = 0; c < 3; ++c)
            {
              s.prescribe(A, c);
              s.prescribe(B, c);
            }
          s.prescribe(ring, 1);
          s.add_point_load(ring, p.point_load);
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          // 1 % lower than the stress-free position: a taut start (a
          // stress-free cable has no lateral stiffness).
          u[s.node_dof(ring, 2)] = 0.01 * s.node_position(ring)[2];
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const double       b = p.half_span, EA = p.E * p.A;
          const Tensor<1, 3> P        = p.point_load;
          const Tensor<1, 3> d        = P / P.norm();
          const auto         position = [&](const double l) {
            const double alpha = 0.5 * l;
            const double beta  = std::sqrt(alpha * alpha - b * b);
            const double t = 1. / std::sqrt(alpha * alpha * d[0] * d[0] +
                                            beta * beta * d[2] * d[2]);
            return Point<3>(alpha * alpha * d[0] * t,
                            0,
                            beta * beta * d[2] * t);
          };
          const Talus::Structure::AxialLaw law{p.strain_measure,
                                               p.E,
                                               p.A,
                                               p.prestress};
          const auto                       tension = [&](const double l) {
            const double lambda = l / p.unstretched_length;
            if (p.strain_measure ==
                Talus::Structure::StrainMeasure::engineering)
              return law.force(lambda);
            return EA * lambda * (lambda * lambda - 1.) / 2. +
                   p.prestress * p.A * lambda;
          };
          const auto balance = [&](const double l) {
            const Point<3>     x = position(l);
            const Tensor<1, 3> eA =
              (Point<3>(-b, 0, 0) - x) / (x.distance(Point<3>(-b, 0, 0)));
            const Tensor<1, 3> eB =
              (Point<3>(b, 0, 0) - x) / (x.distance(Point<3>(b, 0, 0)));
            return tension(l) * (eA + eB).norm() - P.norm();
          };
          const double l_root =
            bisect(balance,
                   std::max(2. * b, p.unstretched_length) * (1. + 1e-14),
                   10. * p.unstretched_length);
          const Point<3> x_ref = position(l_root);
          const Point<3> x =
            s.node_position(ring) + s.node_displacement(u, ring);
          const double T = s.line_meshes[0]->force[0];
          return {{"cable tension T [N]", T, tension(l_root)},
                  {"ring position x [m]", x[0], x_ref[0], false},
                  {"ring position z [m]", x[2], x_ref[2]},
                  {"|ring position - exact| / b",
                   x.distance(x_ref) / b,
                   0.,
                   true,
                   true}};
        }

        bool
        prestress_step() const override
        {
          return false;
        }

      private:
        unsigned int A = 0, B = 0, ring = 0;
      };
    } // namespace


    std::unique_ptr<Model>
    create_sliding_ring(const Parameters &p)
    {
      return std::make_unique<SlidingRing>(p);
    }


  } // namespace StructureModels
} // namespace Talus
