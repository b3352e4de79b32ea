// Structure verification model: cable with brake (set problem = structure).

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
       * A brake in series with a cable: anchor (0,0,0), brake to
       * (L_b,0,0), cable to (L_b + L_c,0,0), whose end is pulled along x
       * by lambda U (displacement control, following the load path). At
       * every step: force N on the plateau = F_a + H s, dissipated energy
       * D = F_a s + H s^2/2, and the closed form of the series: for end
       * displacement U on the plateau, N = F_a + H s, U = N/k_e + s +
       * d_c(N), with the cable elongation d_c from N = EA lambda (lambda^2 -
       * 1)/2, lambda = 1 + d_c/L_c.
       */
      class BrakeTest : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "brake in series with a cable, pulled and released";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          const auto     brake = brake_element();
          const Point<3> a(0, 0, 0), b(p.brake_length, 0, 0),
            c(p.brake_length + p.cable_length, 0, 0);
          make_line(s.add_line_mesh("brake", brake).triangulation, a, b, 1);
          make_line(s.add_line_mesh("cable", line_element()).triangulation,
                    b,
                    c,
                    p.elements);
          s.setup_dofs();
          anchor = node_at(s, a);
          end    = node_at(s, c);
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            {
              s.prescribe(k, 1);
              s.prescribe(k, 2);
            }
          for (unsigned int c2 = 0; c2 < 3; ++c2)
            s.prescribe(anchor, c2);
          s.prescribe(end, 0, p.prescribed_displacement);
        }

        bool
        prestress_step() const override
        {
          return false;
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          (void)s;
          (void)u;
        }

        /** Elongation of the cable under force N: EA lambda (lambda^2 -
         * 1)/2 + A sigma_0 lambda = N, d_c = L_c (lambda - 1). */
        double
        cable_elongation(const double N) const
        {
          const double EA = p.E * p.A;
          return p.cable_length * (bisect(
                                     [&](const double lambda) {
                                       return EA * lambda *
                                                (lambda * lambda - 1.) / 2. +
                                              p.A * p.prestress * lambda - N;
                                     },
                                     0.5,
                                     2.) -
                                   1.);
        }

        /** Closed-form stroke and force on the plateau for end pull U. */
        std::pair<double, double>
        plateau(const double U) const
        {
          const double s = bisect(
            [&](const double s) {
              const double N = p.brake_Fa + p.brake_H * s;
              return N / p.brake_k + s + cable_elongation(N) - U;
            },
            0.,
            U);
          return {s, p.brake_Fa + p.brake_H * s};
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure &s, const Vector<double> &u, double) override
        {
          const auto  &brake   = *s.line_meshes[0];
          const double N       = brake.force[0];
          const double st      = brake.state[0].plastic;
          const double D       = brake.state[0].accumulated;
          const double U       = s.node_displacement(u, end)[0];
          const double D_exact = p.brake_Fa * st + 0.5 * p.brake_H * st * st;
          max_D_error =
            std::max(max_D_error,
                     std::abs(D - D_exact) / std::max(D_exact, 1e-300));
          const bool blocked =
            p.brake_smax > 0. && st >= p.brake_smax * (1. - 1e-12);
          if (st > last_stroke * (1. + 1e-12) && st > 0. && !blocked)
            {
              // Loading on the plateau: N = F_a + H s and the series.
              const auto [s_ex, N_ex] = plateau(U);
              max_plateau_error =
                std::max(max_plateau_error, std::abs(N - N_ex) / N_ex);
              max_stroke_error =
                std::max(max_stroke_error, std::abs(st - s_ex) / s_ex);
            }
          last_stroke = st;
          rows.push_back({{U, N, st, D}});
          return {{"end_displacement", U},
                  {"brake_force", N},
                  {"stroke", st},
                  {"dissipated_energy", D}};
        }

        std::vector<Result>
        results(const Structure &, const Vector<double> &) override
        {
          std::cout << "  path (U: end displacement [m], N: force [N], s: "
                       "stroke [m], D: dissipated energy [J]):\n";
          for (const auto &r : rows)
            std::cout << "    U = " << std::setw(8) << std::setprecision(5)
                      << r[0] << "  N = " << std::setw(11) << r[1]
                      << "  s = " << std::setw(9) << r[2]
                      << "  D = " << std::setw(11) << r[3] << '\n';
          // Final state: on the plateau or blocked at the stroke limit,
          // N = k_e (d_b - s_max), U = N/k_e + s_max + d_c(N).
          const double U = rows.back()[0], N = rows.back()[1],
                       st = rows.back()[2];
          double N_exact = 0., s_exact = 0.;
          if (p.brake_smax > 0. && st >= p.brake_smax * (1. - 1e-12))
            {
              s_exact = p.brake_smax;
              N_exact = bisect(
                [&](const double N) {
                  return N / p.brake_k + p.brake_smax + cable_elongation(N) - U;
                },
                0.,
                p.brake_k * U);
            }
          else
            std::tie(s_exact, N_exact) = plateau(U);
          return {
            {"max |D - (F_a s + H s^2/2)| / D", max_D_error, 0., true, true},
            {"max |N - N_exact| / N_exact on the plateau",
             max_plateau_error,
             0.,
             true,
             true},
            {"max |s - s_exact| / s_exact on the plateau",
             max_stroke_error,
             0.,
             true,
             true},
            {"final force [N]", N, N_exact},
            {"final stroke [m]", st, s_exact}};
        }

        double max_D_error = 0., max_plateau_error = 0., max_stroke_error = 0.;

      private:
        unsigned int                       anchor = 0, end = 0;
        double                             last_stroke = 0.;
        std::vector<std::array<double, 4>> rows;
      };
    } // namespace


    std::unique_ptr<Model>
    create_brake_test(const Parameters &p)
    {
      return std::make_unique<BrakeTest>(p);
    }


  } // namespace StructureModels
} // namespace Talus
