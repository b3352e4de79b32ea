// Structure verification model: continuum cantilever (set problem = structure).

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
       * Cantilever: the generated box of subsection Solid (length L along
       * x, width b along y, height h along z) clamped at x = x_min
       * (boundary id 0: every DoF of the face fixed) and loaded on x = x_max
       * (id 1) by the uniform dead shear traction P/(b h) along z, P the
       * z component of 'point load', and by its own weight (gravity along
       * z, the distributed load q = rho g b h per length). The tip
       * deflection is the work-conjugate of the end load, the mean of u_z
       * over the end face, delta = int u_z dA / (b h). Reference:
       * Timoshenko's beam, w(x) = w_P(x) + w_q(x),
       *   w_P(x) = P x^2 (3 L - x)/(6 E I) + P x/(kappa G b h),
       *   w_q(x) = q x^2 (6 L^2 - 4 L x + x^2)/(24 E I)
       *            + q (L x - x^2/2)/(kappa G b h),
       *   I = b h^3/12, kappa = 10 (1 + nu)/(12 + 11 nu) (rectangle, Cowper
       * 1966), so delta = w(L) = P L^3/(3 E I) + P L/(kappa G b h) + q L^4/
       * (8 E I) + q L^2/(2 kappa G b h); Euler-Bernoulli (the terms with I)
       * is printed. With a weight also the mean deflection of the last
       * column of cells,
       * int u_z dV / V over the cells next to x = L (x >= L - a, a the
       * cells' length), against the mean of w over [L - a, L]: the
       * quantity a coupled run measures on the material points of its last
       * column of grid cells (tests/coupled/split_cantilever*). The load
       * must be small (delta << h) for the linear beam theories to apply.
       * 'plane cantilever': the rectangle in the x-y plane (height h along
       * y, width b = the thickness t), load 'point load' (0, P, 0) and
       * gravity (0, g, 0), and the plane-strain beam: E' = E/(1 - nu^2) and
       * nu' = nu/(1 - nu) in the formulas above.
       */
      class Cantilever : public SolidModel
      {
      public:
        using SolidModel::SolidModel;

        std::string
        description() const override
        {
          return std::string(p.plane_solid ? "plane-strain " : "") +
                 "cantilever: continuum solid (" + p.solid.law_name() +
                 ", FE_Q(" + std::to_string(p.solid.degree) +
                 ")) clamped at x_min, end shear load; Timoshenko beam";
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        /** In time: the end face's mean displacement, the end region's
         * mean deflection ('tip region length') and the energies. */
        std::vector<std::pair<std::string, double>>
        monitor(const Structure &s, const Vector<double> &u, double) override
        {
          if (!p.dynamic)
            return {};
          const auto  &g  = p.solid_geometry;
          const double x0 = g.lower_corner[0];
          const double L  = g.upper_corner[0] - x0;
          const double a =
            p.tip_region_length > 0. ? p.tip_region_length : last_cell(s);
          double mean = 0.;
          on_solid(s, [&](const auto &mesh) {
            mean = region_mean(mesh, u, x0 + L - a, vertical());
          });
          return {{"time", time},
                  {"tip_u_x", solid_face_mean(s, u, 1, 0)},
                  {"tip_u_y", solid_face_mean(s, u, 1, vertical())},
                  {"end_region_u_y", mean},
                  {"kinetic_energy", kinetic_energy},
                  {"total_energy", total_energy}};
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          Tensor<1, 3> traction;
          traction[vertical()] =
            p.point_load[vertical()] / (width() * height());
          add_solid_mesh(s, "cantilever", level).emplace_back(1, traction);
          s.setup_dofs();
          on_solid(s, [&](const auto &mesh) {
            s.prescribe_solid_boundary(mesh, 0);
          });
          s.gravity = p.gravity;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const auto  &g   = p.solid_geometry;
          const double x0  = g.lower_corner[0];
          const double L   = g.upper_corner[0] - x0;
          const double b   = width();
          const double h   = height();
          const double E   = effective_modulus();
          const double nu  = effective_poisson();
          const double P   = p.point_load[vertical()];
          const double q   = p.solid.density * p.gravity[vertical()] * b * h;
          const double I   = b * h * h * h / 12.;
          const double G   = E / (2. * (1. + nu));
          const double kap = 10. * (1. + nu) / (12. + 11. * nu);
          const double kGA = kap * G * b * h;
          // Timoshenko's deflection at x (from the clamp) and its
          // Euler-Bernoulli part
          const auto bending = [&](const double x) {
            return P * x * x * (3. * L - x) / (6. * E * I) +
                   q * x * x * (6. * L * L - 4. * L * x + x * x) /
                     (24. * E * I);
          };
          const auto w = [&](const double x) {
            return bending(x) + P * x / kGA + q * (L * x - 0.5 * x * x) / kGA;
          };
          // the last column of cells: x >= L - a
          const double a = last_cell(s);
          // mean of w over [L - a, L]: 3-point Gauss (w is a quartic)
          double w_mean = 0.;
          for (const auto &[xi, weight] :
               std::vector<std::pair<double, double>>{
                 {-std::sqrt(0.6), 5. / 9.},
                 {0., 8. / 9.},
                 {std::sqrt(0.6), 5. / 9.}})
            w_mean += 0.5 * weight * w(L - 0.5 * a * (1. - xi));
          double u_mean = 0.;
          on_solid(s, [&](const auto &mesh) {
            u_mean = region_mean(mesh, u, x0 + L - a, vertical());
          });
          if (p.dynamic)
            // (in time: the CSV holds the history; no closed form)
            return {{"tip deflection at the end time [m]",
                     solid_face_mean(s, u, 1, vertical()),
                     0.,
                     false}};
          std::vector<Result> r = {
            {"tip deflection [m]", solid_face_mean(s, u, 1, vertical()), w(L)},
            {"Euler-Bernoulli deflection [m]", bending(L), 0., false}};
          if (q != 0.)
            r.push_back(
              {"mean deflection of the end cells [m]", u_mean, w_mean});
          return r;
        }

      private:
        /** Length of the cells at the free end x = x_max [m]. */
        double
        last_cell(const Structure &s) const
        {
          const auto  &g  = p.solid_geometry;
          const double x1 = g.upper_corner[0];
          const double L  = x1 - g.lower_corner[0];
          double       a  = 0.;
          on_solid(s, [&](const auto &mesh) {
            for (const auto &cell : mesh.triangulation.active_cell_iterators())
              if (cell->center()[0] + 0.5 * cell->extent_in_direction(0) >
                  x1 - 1e-12 * L)
                a = std::max(a, cell->extent_in_direction(0));
          });
          return a;
        }
      };
    } // namespace


    std::unique_ptr<Model>
    create_cantilever(const Parameters &p)
    {
      return std::make_unique<Cantilever>(p);
    }


  } // namespace StructureModels
} // namespace Talus
