// Structure verification model: pre-stressed square membrane (set problem =
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
       * Pre-stressed square membrane (side a, isotropic pre-stress N0 = t
       * sigma_0) under a small pressure q, edges clamped: w_max = k q
       * a^2/N0 with k = 0.07367135 (contrib/reference/square_membrane.py).
       */
      class SquareMembrane : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "pre-stressed square membrane under small pressure";
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          if (std::abs(p.membrane_prestress[0] - p.membrane_prestress[1]) >
                1e-12 * std::abs(p.membrane_prestress[0]) ||
              p.membrane_prestress[2] != 0. || !(p.membrane_prestress[0] > 0.))
            InputFile::reject(structure_section + "/Membrane",
                              "prestress",
                              "",
                              "the square membrane model needs an isotropic "
                              "tensile pre-stress S11 = S22 > 0, S12 = 0");
          make_flat_mesh(s.add_membrane("membrane", membrane()).triangulation,
                         false,
                         p.side,
                         p.refinements + level);
          s.setup_dofs();
          for (const unsigned int n : s.find_nodes([&](const Point<3> &x) {
                 return std::max(std::abs(x[0]), std::abs(x[1])) >
                        0.5 * p.side * (1. - 1e-10);
               }))
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(n, c);
          centre = node_at(s, Point<3>());
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          if (!p.dynamic)
            return;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            {
              const Point<3> &x   = s.node_position(k);
              u[s.node_dof(k, 2)] = p.mode_amplitude *
                                    std::cos(numbers::PI * x[0] / p.side) *
                                    std::cos(numbers::PI * x[1] / p.side);
            }
        }

        bool
        prestress_step() const override
        {
          return !p.dynamic;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure      &s,
                const Vector<double> &u,
                const double) override
        {
          if (!p.dynamic)
            return {};
          const double w = u[s.node_dof(centre, 2)];
          if (times.empty())
            energy0 = total_energy;
          if (!times.empty() && (w > 0.) != (w_last > 0.))
            crossings.push_back(time -
                                (time - times.back()) * w / (w - w_last));
          max_drift =
            std::max(max_drift,
                     std::abs(total_energy - energy0) / std::abs(energy0));
          times.push_back(time);
          deflections.push_back(w);
          w_last = w;
          return {{"time", time},
                  {"centre_deflection", w},
                  {"total_energy", total_energy}};
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const double N0 = p.thickness * p.membrane_prestress[0];
          if (p.dynamic)
            {
              // w = A cos(omega t): omega = (pi/a) sqrt(2 N0/(rho t)).
              const double omega =
                numbers::PI / p.side *
                std::sqrt(2. * N0 / (p.membrane_density * p.thickness));
              if (crossings.size() < 2)
                throw ExcSimulationFailed(
                  "the centre of the membrane crossed zero fewer than twice: "
                  "run longer to measure the period");
              const double period =
                2. * (crossings.back() - crossings[0]) / (crossings.size() - 1);
              // The linear frequency is the reference only for small
              // amplitudes (stretching stiffens the membrane).
              const bool linear = std::abs(p.mode_amplitude) < 1e-3 * p.side;
              if (p.mass_damping > 0.)
                {
                  // Mass-proportional damping C = a_M M damps every mode
                  // by exp(-a_M t/2): the first maximum after t = 0 (by
                  // parabolic interpolation of the samples) must be
                  // A exp(-a_M t_1/2).
                  double t1 = 0., w1 = 0.;
                  for (unsigned int k = 1; k + 1 < deflections.size(); ++k)
                    if (deflections[k] > deflections[k - 1] &&
                        deflections[k] >= deflections[k + 1])
                      {
                        const double wm = deflections[k - 1],
                                     w0 = deflections[k],
                                     wp = deflections[k + 1];
                        const double h  = times[k + 1] - times[k];
                        const double d  = 0.5 * (wm - wp) / (wm - 2. * w0 + wp);
                        t1              = times[k] + d * h;
                        w1              = w0 - 0.25 * (wm - wp) * d;
                        break;
                      }
                  if (t1 == 0.)
                    throw ExcSimulationFailed(
                      "no maximum of the centre deflection after t = 0: "
                      "run longer to measure the damping");
                  return {{"period of the first mode [s]",
                           period,
                           2. * numbers::PI / omega,
                           linear},
                          {"amplitude after one period / initial",
                           w1 / deflections[0],
                           std::exp(-0.5 * p.mass_damping * t1)}};
                }
              return {{linear ? "period of the first mode [s]" :
                                "period (large amplitude, not checked) [s]",
                       period,
                       2. * numbers::PI / omega,
                       linear},
                      {"max |E - E0| / E0 (energy drift)",
                       max_drift,
                       0.,
                       true,
                       true}};
            }
          return {{"centre deflection w_max [m]",
                   u[s.node_dof(centre, 2)],
                   0.07367135 * p.pressure * p.side * p.side / N0}};
        }

      private:
        unsigned int        centre = 0;
        std::vector<double> times, crossings, deflections;
        double              w_last = 0., energy0 = 0., max_drift = 0.;
      };
    } // namespace


    std::unique_ptr<Model>
    create_square_membrane(const Parameters &p)
    {
      return std::make_unique<SquareMembrane>(p);
    }


  } // namespace StructureModels
} // namespace Talus
