// Structure verification model: von Mises truss (set problem = structure).

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
       * Von Mises two-bar truss (VERIFICATION.md 3): supports (-b,0,0),
       * (b,0,0), apex (0,0,h), apex displacement -v prescribed
       * (displacement control). Green-Lagrange bar, exact:
       * P(v) = EA/L0^3 v (2h - v)(h - v), P_max = 2 EA h^3/(3 sqrt(3) L0^3)
       * at v* = h (1 - 1/sqrt(3)).
       */
      class VonMisesTruss : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return std::string("von Mises two-bar truss") +
                 (p.spring_EA > 0. ? " with a soft spring on the apex" : "") +
                 (p.arc_length_control ?
                    ", arc-length control" :
                    (p.point_load.norm() > 0. ? ", load control" :
                                                ", displacement control"));
        }

        void
        build(Structure &s, const unsigned int) override
        {
          const auto     element = line_element();
          const Point<3> left(-p.half_span, 0, 0), right(p.half_span, 0, 0),
            apex(0, 0, p.rise);
          make_line(s.add_line_mesh("bar_left", element).triangulation,
                    left,
                    apex,
                    p.elements);
          make_line(s.add_line_mesh("bar_right", element).triangulation,
                    apex,
                    right,
                    p.elements);
          spring_top = Point<3>(0, 0, p.rise + p.spring_length);
          if (spring())
            {
              auto k            = std::make_shared<Talus::Structure::Truss>();
              k->youngs_modulus = p.spring_EA;
              k->area           = 1.;
              make_line(s.add_line_mesh("spring", k).triangulation,
                        apex,
                        spring_top,
                        1);
            }
          s.setup_dofs();
          for (unsigned int c = 0; c < 3; ++c)
            {
              s.prescribe(node_at(s, left), c);
              s.prescribe(node_at(s, right), c);
            }
          // Plane problem: every node stays in y = 0.
          for (unsigned int n = 0; n < s.n_nodes(); ++n)
            s.prescribe(n, 1);
          apex_node = node_at(s, apex);
          load_node = apex_node;
          if (spring())
            {
              // Soft vertical spring (a Truss with E A = spring EA) on the
              // apex, loaded at its top, which is guided vertically.
              load_node = node_at(s, spring_top);
              s.prescribe(load_node, 0);
              s.prescribe(apex_node, 0);
            }
          if (load_control())
            s.add_point_load(load_node, p.point_load);
          else
            s.prescribe(apex_node, 2, -p.prescribed_displacement);
          L0 = std::sqrt(p.half_span * p.half_span + p.rise * p.rise);
        }

        bool
        spring() const
        {
          return p.spring_EA > 0.;
        }

        /** Top of the spring, after the bars (it must exist before
         * setup_dofs(): see build()). */
        Point<3> spring_top;

        /** A load at the apex instead of its displacement. */
        bool
        load_control() const
        {
          return p.point_load.norm() > 0.;
        }

        std::vector<double>
        extra_load_factors() const override
        {
          if (load_control())
            return {};
          const double v_star = p.rise * (1. - 1. / std::sqrt(3.));
          if (v_star < p.prescribed_displacement)
            return {v_star / p.prescribed_displacement};
          return {};
        }

        double
        exact(const double v) const
        {
          return p.E * p.A / (L0 * L0 * L0) * v * (2. * p.rise - v) *
                 (p.rise - v);
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure      &s,
                const Vector<double> &u,
                const double          lambda) override
        {
          const double v = -s.node_displacement(u, apex_node)[2];
          // The load that holds the apex: P = -(f_int)_z (downwards).
          const double P     = load_control() ? -lambda * p.point_load[2] :
                                                -s.reaction(apex_node)[2];
          const double P_max = 2. * p.E * p.A * std::pow(p.rise, 3) /
                               (3. * std::sqrt(3.) * L0 * L0 * L0);
          max_error = std::max(max_error, std::abs(P - exact(v)) / P_max);
          if (spring())
            {
              // Spring: E A lambda (lambda^2 - 1)/2 = -P(v), the top moves
              // by w = v + L_s (1 - lambda).
              const double Pv       = exact(v);
              const double lambda_s = bisect(
                [&](const double l) {
                  return p.spring_EA * l * (l * l - 1.) / 2. + Pv;
                },
                1. / std::sqrt(3.),
                3.);
              const double w_exact = v + p.spring_length * (1. - lambda_s);
              const double w       = -s.node_displacement(u, load_node)[2];
              max_spring_error =
                std::max(max_spring_error, std::abs(w - w_exact) / p.rise);
              w_min      = std::min(w_min, w);
              w_max_seen = std::max(w_max_seen, w);
              snap_back  = snap_back || (w < w_max_seen - 1e-3 * p.rise);
            }
          if (P > P_peak)
            {
              P_peak = P;
              v_peak = v;
            }
          table.emplace_back(v, P);
          return {{"apex_displacement", v},
                  {"load", P},
                  {"load_exact", exact(v)}};
        }

        std::vector<Result>
        results(const Structure &, const Vector<double> &) override
        {
          const double P_max = 2. * p.E * p.A * std::pow(p.rise, 3) /
                               (3. * std::sqrt(3.) * L0 * L0 * L0);
          std::cout << "  load path (v: apex displacement down [m], P: load "
                       "down [N]):\n"
                    << "        v            P            P exact\n";
          for (const auto &[v, P] : table)
            std::cout << "    " << std::setw(11) << std::setprecision(5)
                      << std::scientific << v << "  " << std::setw(11) << P
                      << "  " << std::setw(11) << exact(v) << '\n'
                      << std::defaultfloat;
          if (load_control() && p.arc_length_control)
            {
              // Arc length: the whole path through the limit point.
              const double v_end = table.back().first;
              if (spring())
                return {{"largest load on the path P_max [N]", P_peak, P_max},
                        {"final apex displacement [m]", v_end, 0., false},
                        {"max |P - P(v)| / P_max over the path",
                         max_error,
                         0.,
                         true,
                         true},
                        {"max |w - w(v)| / h over the path (spring top)",
                         max_spring_error,
                         0.,
                         true,
                         true},
                        {"snap-back traced (the spring top moved back up)",
                         snap_back ? 1. : 0.,
                         1.}};
              return {{"largest load on the path P_max [N]", P_peak, P_max},
                      {"apex displacement at the largest load [m]",
                       v_peak,
                       p.rise * (1. - 1. / std::sqrt(3.)),
                       false},
                      {"final apex displacement [m]", v_end, 0., false},
                      {"max |P - P_exact| / P_max over the path",
                       max_error,
                       0.,
                       true,
                       true}};
            }
          if (load_control())
            {
              // Load control: the apex displacement at the final load, the
              // root of P(v) = P below the limit point.
              const double P      = -p.point_load[2];
              const double v_star = p.rise * (1. - 1. / std::sqrt(3.));
              if (!(P > 0. && P < P_max) || p.point_load[0] != 0. ||
                  p.point_load[1] != 0.)
                InputFile::reject(structure_section + "/Loads",
                                  "point load",
                                  "",
                                  "the von Mises truss under load control "
                                  "needs a downward load 0 < -P_z < P_max = " +
                                    std::to_string(P_max) + " N");
              const double v_exact =
                bisect([&](const double v) { return exact(v) - P; },
                       0.,
                       v_star);
              return {{"apex displacement at the final load [m]",
                       table.back().first,
                       v_exact},
                      {"max |P - P_exact| / P_max over the path",
                       max_error,
                       0.,
                       true,
                       true}};
            }
          return {{"largest load P_max [N]", P_peak, P_max},
                  {"apex displacement at P_max [m]",
                   v_peak,
                   p.rise * (1. - 1. / std::sqrt(3.))},
                  {"max |P - P_exact| / P_max over the path",
                   max_error,
                   0.,
                   true,
                   true}};
        }

      private:
        unsigned int                           apex_node = 0;
        double                                 L0        = 0.;
        double                                 max_error = 0.;
        double                                 P_peak = -1e300, v_peak = 0.;
        std::vector<std::pair<double, double>> table;
        unsigned int                           load_node        = 0;
        double                                 max_spring_error = 0.;
        double w_min = 1e300, w_max_seen = -1e300;
        bool   snap_back = false;
      };
    } // namespace


    std::unique_ptr<Model>
    create_von_mises_truss(const Parameters &p)
    {
      return std::make_unique<VonMisesTruss>(p);
    }


  } // namespace StructureModels
} // namespace Talus
