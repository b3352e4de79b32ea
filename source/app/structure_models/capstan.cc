// Structure verification model: capstan (Euler-Eytelwein) (set problem =
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
       * Capstan (Euler-Eytelwein): a SlidingCable with friction coefficient
       * mu from the fixed end A = (-R, 0, -1) up to a drum (fixed nodes on
       * the circle of radius R in the x-z plane), around it by the wrap
       * angle theta and off tangentially to the free end B, pulled along the
       * cable by F = |point load|. The cable slides towards B: T_B = F and
       * T_A = F exp(-mu theta), whatever the number of drum nodes (the
       * deviation angles add up to theta).
       *
       * Stick-slip law, load path up to F_max and then down (one reversal):
       * the segments between the fixed drum nodes keep their length, so
       * T_A changes only when slip reaches the first node. Loading: T_A = F
       * exp(-mu theta). Unloading: the nodes stick, then slip backwards
       * from B, node by node; the first node slips when F = T_A exp(-mu
       * theta), so T_A = F_max exp(-mu theta) while F >= F_max exp(-2 mu
       * theta), and T_A = F exp(mu theta) below.
       */
      class Capstan : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "capstan: cable with friction around a drum";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          auto cable                  = sliding_cable();
          cable->friction_coefficient = p.friction;
          cable->stick_slip           = p.stick_slip;
          const double          R     = p.drum_radius;
          const double          theta = p.wrap_angle * numbers::PI / 180.;
          const unsigned int    n     = p.elements;
          std::vector<Point<3>> x     = {Point<3>(-R, 0, -1.)};
          for (unsigned int k = 0; k <= n; ++k)
            {
              const double phi = numbers::PI - k * theta / n;
              x.emplace_back(R * std::cos(phi), 0., R * std::sin(phi));
            }
          const double phi_n = numbers::PI - theta;
          direction = Tensor<1, 3>({std::sin(phi_n), 0., -std::cos(phi_n)});
          x.push_back(x.back() + direction);
          make_polyline(s.add_sliding_cable("cable", cable).triangulation, x);
          s.setup_dofs();
          for (unsigned int k = 0; k + 1 < x.size(); ++k)
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(node_at(s, x[k]), c);
          end = node_at(s, x.back());
          s.prescribe(end, 1);
          s.add_point_load(end, p.point_load.norm() * direction);
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          // A taut start: the free end 0.1 mm further out.
          for (unsigned int c = 0; c < 3; ++c)
            u[s.node_dof(end, c)] = 1e-4 * direction[c];
        }

        bool
        prestress_step() const override
        {
          return false;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure &s,
                const Vector<double> &,
                const double lambda) override
        {
          const auto  &mesh  = *s.line_meshes[0];
          const double T_A   = mesh.force[mesh.chain_cells.front()];
          const double T_B   = mesh.force[mesh.chain_cells.back()];
          const double F     = lambda * p.point_load.norm();
          const double theta = p.wrap_angle * numbers::PI / 180.;
          const double e     = std::exp(p.friction * theta);
          F_last             = F;
          double T_A_ref     = F / e;
          if (p.stick_slip)
            {
              F_max = std::max(F_max, F);
              T_A_ref =
                F >= F_max ? F / e : (F >= F_max / (e * e) ? F_max / e : F * e);
              path_error = std::max({path_error,
                                     std::abs(T_A - T_A_ref) / F_max,
                                     std::abs(T_B - F) / F_max});
            }
          return {{"force_F", F},
                  {"T_A", T_A},
                  {"T_A_reference", T_A_ref},
                  {"T_B", T_B}};
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &) override
        {
          const auto  &mesh  = *s.line_meshes[0];
          const double T_A   = mesh.force[mesh.chain_cells.front()];
          const double T_B   = mesh.force[mesh.chain_cells.back()];
          const double F     = F_last;
          const double theta = p.wrap_angle * numbers::PI / 180.;
          const double e     = std::exp(p.friction * theta);
          if (!p.stick_slip)
            return {{"tension at the pulled end T_B [N]", T_B, F},
                    {"tension at the fixed end T_A [N]", T_A, F / e},
                    {"T_B / T_A", T_B / T_A, e}};
          return {{"largest F [N]", F_max, 0., false},
                  {"final F [N]", F, 0., false},
                  {"final T_A [N]", T_A, 0., false},
                  {"final T_B / T_A", T_B / T_A, 0., false},
                  {"exp(mu theta)", e, 0., false},
                  {"max over the path |T_A - T_A,ref|, |T_B - F| / F_max",
                   path_error,
                   0.,
                   true,
                   true}};
        }

      private:
        unsigned int end = 0;
        Tensor<1, 3> direction;
        double       F_max = 0., F_last = 0., path_error = 0.;
      };
    } // namespace


    std::unique_ptr<Model>
    create_capstan(const Parameters &p)
    {
      return std::make_unique<Capstan>(p);
    }


  } // namespace StructureModels
} // namespace Talus
