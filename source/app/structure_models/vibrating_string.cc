// Structure verification model: vibrating string (set problem = structure).

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
       * A pre-stressed Cable of span L in two elements (ends fixed), its
       * middle node released from the deflection A (y fixed): for small A
       * one degree of freedom with k = 4 N/L (N = A sigma_0, the lateral
       * stiffness of the two taut halves) and the lumped mass m = rho A L/2,
       * omega^2 = 8 sigma_0/(rho L^2). Reference: the scalar Bossak-Newmark
       * recurrence for m a + k u = 0 with the same alpha and dt, iterated
       * here independently: (1 - alpha) a_{n+1} + alpha a_n + omega^2
       * u_{n+1} = 0 with the Newmark updates (beta = (1-alpha)^2/4, gamma =
       * 1/2 - alpha). The largest difference over the run checks the time
       * integration including its numerical damping; for alpha = 0 the
       * period is also compared with 2 pi/omega.
       */
      class VibratingString : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "vibrating pre-stressed cable, one degree of freedom";
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        bool
        prestress_step() const override
        {
          return false;
        }

        void
        build(Structure &s, const unsigned int) override
        {
          const double L = p.span;
          make_line(s.add_line_mesh("cable", line_element()).triangulation,
                    Point<3>(-0.5 * L, 0, 0),
                    Point<3>(0.5 * L, 0, 0),
                    2);
          s.setup_dofs();
          for (const double x : {-0.5 * L, 0.5 * L})
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(node_at(s, Point<3>(x, 0, 0)), c);
          mid = node_at(s, Point<3>());
          s.prescribe(mid, 1);
          omega = std::sqrt(8. * p.prestress / (p.density * L * L));
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          u[s.node_dof(mid, 2)] = p.string_amplitude;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure      &s,
                const Vector<double> &u,
                const double) override
        {
          const double w = u[s.node_dof(mid, 2)];
          if (samples.empty())
            {
              // The reference starts from the same state (rest, w = A).
              ref_u = w;
              ref_v = 0.;
              ref_a = -omega * omega * w;
            }
          else
            {
              const double dt = time - times.back(), al = p.bossak_alpha;
              const double beta  = 0.25 * (1. - al) * (1. - al),
                           gamma = 0.5 - al;
              const double ubar =
                ref_u + dt * ref_v + dt * dt * (0.5 - beta) * ref_a;
              // (1 - al) a1 + al a + c v1 + omega^2 u1 = 0 with the
              // Rayleigh damping per unit mass c = a_M + a_K omega^2.
              const double c =
                p.mass_damping + p.stiffness_damping * omega * omega;
              const double vbar = ref_v + dt * (1. - gamma) * ref_a;
              const double a1 =
                -(al * ref_a + c * vbar + omega * omega * ubar) /
                ((1. - al) + c * gamma * dt + omega * omega * beta * dt * dt);
              const double u1 = ubar + beta * dt * dt * a1;
              ref_v           = vbar + gamma * dt * a1;
              ref_u           = u1;
              ref_a           = a1;
            }
          max_difference = std::max(max_difference, std::abs(w - ref_u));
          if (!samples.empty() && (w > 0.) != (samples.back() > 0.))
            crossings.push_back(time - (time - times.back()) * w /
                                         (w - samples.back()));
          // Positive maxima (parabola through the three samples).
          if (samples.size() >= 2)
            {
              const double w0 = samples[samples.size() - 2],
                           w1 = samples.back();
              if (w1 > 0. && w1 >= w0 && w1 > w)
                {
                  const double curvature = w0 - 2. * w1 + w;
                  peaks.push_back(w1 - 0.125 * (w - w0) * (w - w0) / curvature);
                }
            }
          samples.push_back(w);
          times.push_back(time);
          return {{"time", time},
                  {"middle_deflection", w},
                  {"bossak_recurrence", ref_u}};
        }

        std::vector<Result>
        results(const Structure &, const Vector<double> &) override
        {
          std::vector<Result> r = {
            {"max |w - w_Bossak| / A over the run",
             max_difference / std::abs(p.string_amplitude),
             0.,
             true,
             true},
            {"|w_Bossak(T_end)| / A (end of the run)",
             std::abs(ref_u) / std::abs(p.string_amplitude),
             0.,
             false}};
          if (crossings.size() >= 2)
            {
              const double period =
                2. * (crossings.back() - crossings[0]) / (crossings.size() - 1);
              const double wdt = omega * p.dynamic_time_step;
              // Average acceleration: period elongation (omega dt)^2/12.
              const double c =
                p.mass_damping + p.stiffness_damping * omega * omega;
              r.push_back({"period [s]",
                           period,
                           2. * numbers::PI / omega *
                             (p.bossak_alpha == 0. ? 1. + wdt * wdt / 12. : 1.),
                           p.bossak_alpha == 0. && c == 0.});
            }
          if (peaks.size() >= 2 &&
              (p.stiffness_damping > 0. || p.mass_damping > 0.))
            {
              // Logarithmic decrement over the positive maxima:
              // zeta = delta / sqrt(4 pi^2 + delta^2); exact zeta = c/(2
              // omega) = a_K omega/2 + a_M/(2 omega). The scheme's own
              // error is of order (omega dt)^2.
              const double delta =
                std::log(peaks.front() / peaks.back()) / (peaks.size() - 1);
              const double zeta =
                delta /
                std::sqrt(4. * numbers::PI * numbers::PI + delta * delta);
              const double wdt = omega * p.dynamic_time_step;
              Result       z{"damping ratio from the decay",
                       zeta,
                       0.5 * p.stiffness_damping * omega +
                         0.5 * p.mass_damping / omega};
              z.tolerance = wdt * wdt;
              r.push_back(
                {"number of maxima", double(peaks.size()), 0., false});
              r.push_back(z);
            }
          return r;
        }

      private:
        unsigned int        mid   = 0;
        double              omega = 0.;
        double              ref_u = 0., ref_v = 0., ref_a = 0.;
        double              max_difference = 0.;
        std::vector<double> samples, times, crossings, peaks;
      };
    } // namespace


    std::unique_ptr<Model>
    create_vibrating_string(const Parameters &p)
    {
      return std::make_unique<VibratingString>(p);
    }


  } // namespace StructureModels
} // namespace Talus
