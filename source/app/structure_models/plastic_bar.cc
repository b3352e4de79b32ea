// Structure verification model: truss bar beyond yield (set problem =
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
       * A straight truss of length L ('span') along x in 'elements per
       * member' elements, fixed at x = 0, u_y = u_z = 0 everywhere, its end
       * loaded by F = lambda F_x ('point load' (F_x, 0, 0)) along the load
       * path. Every element carries N = F, so the stretch lambda_s is
       * uniform and solves (Truss: Green-Lagrange strain
       * eps = (lambda_s^2 - 1)/2, S = E (eps - eps_p) + sigma_0,
       * N = A S lambda_s, yield |S| <= sigma_y + H alpha)
       *   elastic: A (E (eps - eps_p) + sigma_0) lambda_s = F,
       *   on yield (loading): S = sign (sigma_y + H alpha),
       *     alpha = alpha_old + Dgamma, eps_p = eps_p,old + sign Dgamma,
       *     Dgamma = (|S_trial| - sigma_y - H alpha_old)/(E + H),
       *   i.e. A S(lambda_s) lambda_s = F, a scalar monotone equation solved
       *   here by bisection, the history (eps_p, alpha) carried from step to
       *   step independently of the finite elements. The end displacement
       *   is U = L (lambda_s - 1); after unloading to F = 0 (sigma_0 = 0)
       *   the residual elongation is exactly L (sqrt(1 + 2 eps_p) - 1).
       */
      class PlasticBar : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "elasto-plastic bar with linear hardening, loaded along "
                 "the load path";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          make_line(s.add_line_mesh("bar", line_element()).triangulation,
                    Point<3>(),
                    Point<3>(p.span, 0, 0),
                    p.elements);
          s.setup_dofs();
          end = node_at(s, Point<3>(p.span, 0, 0));
          for (unsigned int n = 0; n < s.n_nodes(); ++n)
            {
              s.prescribe(n, 1);
              s.prescribe(n, 2);
            }
          s.prescribe(node_at(s, Point<3>()), 0);
          s.add_point_load(end, p.point_load);
        }

        bool
        prestress_step() const override
        {
          return false;
        }

        /** Return-mapped PK2 stress at stretch @p l from the history
         * (eps_p, alpha); @p new_eps_p, @p new_alpha the updated one. */
        double
        stress(const double l, double &new_eps_p, double &new_alpha) const
        {
          const double eps = 0.5 * (l * l - 1.);
          double       S   = p.E * (eps - eps_p) + p.prestress;
          new_eps_p        = eps_p;
          new_alpha        = alpha;
          const double phi =
            std::abs(S) - (p.yield_stress + p.hardening * alpha);
          if (p.yield_stress > 0. && phi > 0.)
            {
              const double dgamma = phi / (p.E + p.hardening),
                           sign   = S > 0. ? 1. : -1.;
              new_eps_p += sign * dgamma;
              new_alpha += dgamma;
              S -= p.E * sign * dgamma;
            }
          return S;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure      &s,
                const Vector<double> &u,
                const double          lambda) override
        {
          const double F = lambda * p.point_load[0];
          double       e = 0., a = 0.;
          const double l =
            bisect([&](
                     const double l) { return p.A * stress(l, e, a) * l - F; },
                   0.5,
                   2.);
          stress(l, eps_p, alpha);
          const auto  &mesh              = *s.line_meshes[0];
          const double U                 = s.node_displacement(u, end)[0];
          const double U_ex              = p.span * (l - 1.);
          double       max_plastic_error = 0.;
          for (const auto &state : mesh.state)
            max_plastic_error =
              std::max(max_plastic_error, std::abs(state.plastic - eps_p));
          U_max       = std::max(U_max, std::abs(U_ex));
          path_error  = std::max(path_error, std::abs(U - U_ex));
          plastic_err = std::max(plastic_err, max_plastic_error);
          F_last      = F;
          U_last      = U;
          rows.push_back({{F, U, U_ex, mesh.state[0].plastic, eps_p}});
          return {{"force_F", F},
                  {"end_displacement", U},
                  {"end_displacement_reference", U_ex},
                  {"plastic_strain", mesh.state[0].plastic},
                  {"plastic_strain_reference", eps_p}};
        }

        std::vector<Result>
        results(const Structure &, const Vector<double> &) override
        {
          std::cout << "  path (F [N], U and U_ref [m], eps_p and its "
                       "closed form [-]):\n";
          for (const auto &r : rows)
            std::cout << "    F = " << std::setw(9) << std::setprecision(6)
                      << r[0] << "  U = " << std::setw(12)
                      << std::setprecision(8) << r[1]
                      << "  U_ref = " << std::setw(12) << r[2]
                      << "  eps_p = " << std::setw(12) << r[3]
                      << "  ref = " << std::setw(12) << r[4] << '\n';
          std::vector<Result> r = {
            {"max over the path |U - U_ref| / max |U_ref|",
             path_error / std::max(U_max, 1e-300),
             0.,
             true,
             true},
            {"max over the path |eps_p - eps_p,ref|",
             plastic_err,
             0.,
             true,
             true}};
          if (F_last == 0. && p.prestress == 0.)
            r.push_back({"residual elongation at F = 0 [m]",
                         U_last,
                         p.span * (std::sqrt(1. + 2. * eps_p) - 1.)});
          return r;
        }

      private:
        unsigned int end   = 0;
        double       eps_p = 0., alpha = 0.;
        double       U_max = 0., path_error = 0., plastic_err = 0., F_last = 0.,
               U_last = 0.;
        std::vector<std::array<double, 5>> rows;
      };
    } // namespace


    std::unique_ptr<Model>
    create_plastic_bar(const Parameters &p)
    {
      return std::make_unique<PlasticBar>(p);
    }


  } // namespace StructureModels
} // namespace Talus
