// Structure verification model: elastic catenary (3D and plane) (set problem =
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

      // ------------------------------------------------------------------
      /**
       * Elastic catenary (Irvine 1981): supports at (+-l/2, 0, 0),
       * unstretched length L0, weight w = rho A g per unstretched length.
       * Irvine (Hooke's law T = EA (lambda - 1)): H solves l = H L0/EA +
       * (2H/w) asinh(w L0/(2H)); mid-span sag f = w L0^2/(8 EA) + (H/w)
       * (sqrt(1 + (V/H)^2) - 1), V = w L0/2; support tension T = sqrt(H^2 +
       * V^2). The cable element's law is T = EA lambda (lambda^2 - 1)/2
       * (Green-Lagrange strain), so the reference is the same catenary
       * integral with that stretch (span_and_sag()); Irvine's values are
       * printed beside it. The reference (stress-free) shape is a parabola
       * whose chords add up to L0.
       */
      class Catenary : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return plane() ? "elastic catenary (Irvine), cable under self "
                           "weight, 2D string (Triangulation<1,2>)" :
                           "elastic catenary (Irvine), cable under self weight";
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const unsigned int n = p.elements << level;
          if (n % 2 != 0)
            InputFile::reject(structure_section + "/Line members",
                              "elements per member",
                              std::to_string(p.elements),
                              "the catenary needs an even number of elements "
                              "(a node at mid-span)");
          const double l = p.span;
          // Parabola z = -f0 (1 - (2x/l)^2) with sum of chords = L0.
          const auto points = [&](const double f0) {
            std::vector<Point<3>> x(n + 1);
            for (unsigned int i = 0; i <= n; ++i)
              {
                const double xi = -0.5 * l + l * i / n;
                x[i] = Point<3>(xi, 0, -f0 * (1. - 4. * xi * xi / (l * l)));
              }
            return x;
          };
          const auto length = [&](const double f0) {
            const auto x   = points(f0);
            double     sum = 0.;
            for (unsigned int i = 0; i < n; ++i)
              sum += x[i].distance(x[i + 1]);
            return sum - p.unstretched_length;
          };
          const double f0 = bisect(length, 0., p.unstretched_length);
          sag0            = f0;
          s.gravity       = p.gravity;
          if (plane())
            {
              // The 2D string: a Triangulation<1,2> in the (x, y) plane,
              // sag along -y.
              std::vector<Point<2>>    x2;
              std::vector<CellData<1>> cells(n);
              for (const auto &x : points(f0))
                x2.emplace_back(x[0], x[2]);
              for (unsigned int i = 0; i < n; ++i)
                cells[i].vertices = {i, i + 1};
              string.triangulation.create_triangulation(x2,
                                                        cells,
                                                        SubCellData());
              string.add_to(s, "cable", line_element());
              s.setup_dofs();
              string.setup(s);
              left  = string.node(0);
              right = string.node(n);
              mid   = string.node(n / 2);
              string.fix(s, 0);
              string.fix(s, n);
              return;
            }
          make_polyline(s.add_line_mesh("cable", line_element()).triangulation,
                        points(f0));
          s.setup_dofs();
          left  = node_at(s, Point<3>(-0.5 * l, 0, 0));
          right = node_at(s, Point<3>(0.5 * l, 0, 0));
          mid   = node_at(s, Point<3>(0, 0, -f0));
          for (unsigned int c = 0; c < 3; ++c)
            {
              s.prescribe(left, c);
              s.prescribe(right, c);
            }
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            s.prescribe(k, 1);
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          // Deepen the stress-free parabola by 1 %: a taut start for Newton
          // (a stress-free chain has no lateral stiffness).
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            if (k != left && k != right)
              u[s.node_dof(k, up())] = 0.01 * s.node_position(k)[up()];
        }

        bool
        prestress_step() const override
        {
          return false;
        }

        /**
         * Span and mid-span sag of a catenary with horizontal tension H
         * for the stretch law lambda(T), integrated over the unstretched
         * arc length s0 (tension T = sqrt(H^2 + (V - w s0)^2)):
         *   l = int_0^L0 lambda(T) H/T ds0,
         *   f = int_0^(L0/2) lambda(T) (V - w s0)/T ds0,
         * by 5-point Gauss-Legendre on 400 panels. With lambda = 1 + T/EA
         * this is Irvine's closed form.
         */
        std::pair<double, double>
        span_and_sag(const double                         H,
                     const std::function<double(double)> &stretch) const
        {
          const double        w  = p.density * p.A * p.gravity.norm();
          const double        L0 = p.unstretched_length, V = 0.5 * w * L0;
          static const double xg[5] = {-0.9061798459386640,
                                       -0.5384693101056831,
                                       0.,
                                       0.5384693101056831,
                                       0.9061798459386640};
          static const double wg[5] = {0.2369268850561891,
                                       0.4786286704993665,
                                       0.5688888888888889,
                                       0.4786286704993665,
                                       0.2369268850561891};
          double              l = 0., f = 0.;
          const unsigned int  n  = 400;
          const double        ds = L0 / n;
          for (unsigned int k = 0; k < n; ++k)
            for (unsigned int q = 0; q < 5; ++q)
              {
                const double s0 = (k + 0.5 + 0.5 * xg[q]) * ds;
                const double Vs = V - w * s0;
                const double T  = std::sqrt(H * H + Vs * Vs);
                const double lt = stretch(T);
                l += 0.5 * ds * wg[q] * lt * H / T;
                if (s0 < 0.5 * L0)
                  f += 0.5 * ds * wg[q] * lt * Vs / T;
              }
          return {l, f};
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const double w  = p.density * p.A * p.gravity.norm();
          const double EA = p.E * p.A;
          const double L0 = p.unstretched_length;
          const double l  = p.span;
          const double V  = 0.5 * w * L0;
          // Irvine (Hooke's law T = EA (lambda - 1)), closed form.
          const double H_irvine = bisect(
            [&](const double H) {
              return H * L0 / EA + 2. * H / w * std::asinh(w * L0 / (2. * H)) -
                     l;
            },
            1e-12 * w * L0,
            1e3 * w * L0 + EA);
          const double f_irvine =
            w * L0 * L0 / (8. * EA) +
            H_irvine / w * (std::sqrt(1. + V * V / (H_irvine * H_irvine)) - 1.);
          // The element's law: T = EA lambda (lambda^2 - 1)/2 (+ A sigma_0
          // lambda), solved for lambda by Newton.
          const auto stretch_gl = [&](const double T) {
            double lambda = 1. + T / EA;
            for (unsigned int i = 0; i < 50; ++i)
              {
                const double g = EA * lambda * (lambda * lambda - 1.) / 2. +
                                 p.prestress * p.A * lambda - T;
                const double dg =
                  EA * (3. * lambda * lambda - 1.) / 2. + p.prestress * p.A;
                lambda -= g / dg;
              }
            return lambda;
          };
          const double H = bisect(
            [&](const double H) {
              return span_and_sag(H, stretch_gl).first - l;
            },
            1e-12 * w * L0,
            1e3 * w * L0 + EA);
          const double f = span_and_sag(H, stretch_gl).second;
          // Check of the quadrature: Hooke's law reproduces Irvine.
          const auto   hooke = [&](const double T) { return 1. + T / EA; };
          const double quadrature_check =
            std::abs(span_and_sag(H_irvine, hooke).first - l) / l;
          Tensor<1, 3> R   = s.reaction(left);
          double       sag = -(s.node_position(mid)[2] + u[s.node_dof(mid, 2)]);
          if (plane())
            {
              // Read through the 2D interface.
              const unsigned int n  = string.triangulation.n_vertices() - 1;
              const Tensor<1, 2> R2 = string.reaction(s, 0);
              R                     = Tensor<1, 3>({R2[0], R2[1], 0.});
              sag                   = -string.current_position(s, u, n / 2)[1];
            }
          return {{"horizontal tension H [N]", std::abs(R[0]), H},
                  {"mid-span sag [m]", sag, f},
                  {"support tension T [N]", R.norm(), std::sqrt(H * H + V * V)},
                  {"Irvine (Hooke's law) H [N]", H_irvine, 0., false},
                  {"Irvine (Hooke's law) sag [m]", f_irvine, 0., false},
                  {"quadrature check: |l(H_Irvine) - l| / l",
                   quadrature_check < 1e-12 ? 0. : quadrature_check,
                   0.,
                   false}};
        }

      private:
        unsigned int                  left = 0, right = 0, mid = 0;
        double                        sag0 = 0.;
        Talus::Structure::PlaneString string;

        /** The 2D string (model 'plane catenary'). */
        bool
        plane() const
        {
          return p.model == "plane catenary";
        }

        /** The component along which the cable sags. */
        unsigned int
        up() const
        {
          return plane() ? 1 : 2;
        }
      };
    } // namespace


    std::unique_ptr<Model>
    create_catenary(const Parameters &p)
    {
      return std::make_unique<Catenary>(p);
    }


  } // namespace StructureModels
} // namespace Talus
