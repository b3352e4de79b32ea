#include <talus/app/simulation.h>
#include <talus/app/structure_simulation.h>
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
  namespace StructureSimulation
  {
    namespace
    {
      using namespace dealii;
      using Talus::Structure::Structure;
      using Talus::Structure::StructurePart;

      const std::string S = "Structure";

      /** Find x in [a, b] with f(x) = 0 by bisection (f(a) f(b) <= 0). */
      double
      bisect(const std::function<double(double)> &f, double a, double b)
      {
        double fa = f(a);
        for (unsigned int i = 0; i < 200; ++i)
          {
            const double m  = 0.5 * (a + b);
            const double fm = f(m);
            if ((fm <= 0.) == (fa <= 0.))
              {
                a  = m;
                fa = fm;
              }
            else
              b = m;
          }
        return 0.5 * (a + b);
      }


      Tensor<1, 3>
      get_vector(ParameterHandler  &prm,
                 const std::string &subsection,
                 const std::string &entry)
      {
        const auto v = Utilities::string_to_double(
          Utilities::split_string_list(prm.get(entry)));
        if (v.size() != 3)
          InputFile::reject(subsection,
                            entry,
                            prm.get(entry),
                            "it must have three components x, y, z");
        return Tensor<1, 3>({v[0], v[1], v[2]});
      }


      /** Everything read from subsection Structure. */
      struct Parameters
      {
        std::string model;
        /** The model as written in the file ('plane cantilever'); model
         * holds the name without 'plane ' for the plane-strain solids. */
        std::string model_text;
        /** A 'plane' solid model: Triangulation<2,2> in the x-y plane. */
        bool        plane_solid = false;
        std::string solid_traction_text; ///< as written, for messages
        // Line members.
        std::string  line_element;
        double       E = 0., A = 0., prestress = 0., density = 0.;
        double       yield_stress = 0., hardening = 0.;
        unsigned int elements    = 1;
        double       slack_ratio = 1e-8;
        // Membrane.
        double membrane_E = 0., membrane_nu = 0., membrane_E2 = 0.,
               membrane_G = 0., thickness = 0., membrane_density = 0.;
        bool         orthotropic = false, wrinkling = false;
        Tensor<1, 3> membrane_prestress;
        double       initial_deflection = 0.;
        // Brake.
        double brake_k = 0., brake_Fa = 0., brake_H = 0., brake_smax = 0.,
               brake_length = 0.;
        // Geometry.
        double half_span = 0., rise = 0., span = 0., unstretched_length = 0.,
               radius = 0., side = 0., cable_length = 0.;
        unsigned int refinements = 0;
        std::string  mesh_file;
        // Loads.
        Tensor<1, 3>        gravity, point_load;
        double              pressure = 0., prescribed_displacement = 0.;
        std::vector<double> load_path;
        // Output and verification.
        std::string directory;
        bool        write_vtu = false, test_mode = false;
        double      tolerance = 0., reference_displacement = 0.;
        bool        dynamic = false;
        double bossak_alpha = 0., dynamic_time_step = 0., string_amplitude = 0.;
        bool   mesh_is_membrane = false;
        double mass_damping = 0., stiffness_damping = 0.;
        bool   arc_length_control = false;
        double shear_strain       = 0.;
        /** Model 'stretched membrane': engineering strains along x, y. */
        double stretch_x = 0., stretch_y = 0.;
        bool   uniaxial_stress = false;
        double friction = 0., wrap_angle = 180., drum_radius = 0.5;
        bool   stick_slip = false;
        double spring_EA = 0., spring_length = 1.;
        Talus::Structure::BarrierBuilder barrier;
        // Continuum solid.
        Talus::Structure::ContinuumSolid<3> solid;
        Talus::Structure::SolidGeometry     solid_geometry;
        double                              mode_amplitude = 0.;
        unsigned int                        n_levels = 1, first_level = 0;
        double                              minimum_rate = 0.;
      };


      /** A computed quantity and its closed-form value. */
      struct Result
      {
        std::string name;
        double      computed  = 0.;
        double      reference = 0.;
        bool        checked   = true; ///< counts for the tolerance
        /** The computed value is itself a relative error (reference 0). */
        bool is_error = false;
        /** Tolerance of this result; 0: the file's 'tolerance'. */
        double tolerance = 0.;
        double
        error() const
        {
          if (is_error)
            return std::abs(computed);
          return std::abs(computed - reference) /
                 std::max(std::abs(reference), 1e-300);
        }
      };


      /**
       * A structural model built from the parameters, with its closed-form
       * reference. build() creates the meshes, supports and loads of the
       * given refinement level.
       */
      class Model
      {
      public:
        explicit Model(const Parameters &p)
          : p(p)
        {}
        virtual ~Model() = default;

        virtual void
        build(Structure &s, const unsigned int level) = 0;

        /** Start of Newton (e.g. a bulge for a flat, unstressed membrane). */
        virtual void
        initial_guess(const Structure &, Vector<double> &) const
        {}

        /** Extra load factors to visit (inserted into the load path). */
        virtual std::vector<double>
        extra_load_factors() const
        {
          return {};
        }

        /** Values written to the CSV (and checked) after every step. */
        virtual std::vector<std::pair<std::string, double>>
        monitor(const Structure &, const Vector<double> &, double)
        {
          return {};
        }

        /** Results compared with the closed form at the end. */
        virtual std::vector<Result>
        results(const Structure &s, const Vector<double> &u) = 0;

        /**
         * The parameter that decides how the model is held (subsection,
         * entry, value), named when a part of the structure is connected
         * to no support.
         */
        virtual std::array<std::string, 3>
        support_parameter() const
        {
          return {{S, "model", p.model_text}};
        }

        /** Solve the pre-stress equilibrium (lambda = 0) first. */
        virtual bool
        prestress_step() const
        {
          return p.prestress != 0. || p.membrane_prestress.norm() != 0.;
        }

        virtual std::string
        description() const = 0;

        /** The model can run with 'dynamic = true'. */
        virtual bool
        supports_dynamics() const
        {
          return false;
        }

        /** After a dynamic run: solve the static equilibrium from its end
         * state (dynamic relaxation: damped motion to rest, then Newton). */
        virtual bool
        relax_to_equilibrium() const
        {
          return false;
        }

        /**
         * Called once before the load steps (after the pre-stress step):
         * e.g. staged form finding. Returns false if it failed.
         */
        virtual void
        before_load_steps(Structure &, Talus::Structure::StaticSolver &)
        {}

        /** Set by the time loop before monitor(): time [s], total
         * energy (kinetic + strain + load potential) and kinetic energy
         * [J]. */
        double time = 0., total_energy = 0., kinetic_energy = 0.;

        /** With 'dynamic = true': find the pre-stressed equilibrium
         * (load factor 0 and before_load_steps()) before the motion. */
        virtual bool
        form_finding_before_dynamics() const
        {
          return false;
        }

      protected:
        const Parameters &p;

        /** The line parameters every line element shares. */
        template <typename Element>
        std::shared_ptr<Element>
        line_parameters() const
        {
          auto e                   = std::make_shared<Element>();
          e->youngs_modulus        = p.E;
          e->area                  = p.A;
          e->prestress             = p.prestress;
          e->density               = p.density;
          e->slack_stiffness_ratio = p.slack_ratio;
          return e;
        }

        std::shared_ptr<Talus::Structure::LineElement>
        line_element() const
        {
          if (p.line_element == "cable")
            return line_parameters<Talus::Structure::Cable>();
          auto t          = line_parameters<Talus::Structure::Truss>();
          t->yield_stress = p.yield_stress;
          t->hardening    = p.hardening;
          return t;
        }

        /** A sliding cable with the line parameters of the file. */
        std::shared_ptr<Talus::Structure::SlidingCable>
        sliding_cable() const
        {
          return line_parameters<Talus::Structure::SlidingCable>();
        }

        std::shared_ptr<Talus::Structure::Membrane>
        membrane() const
        {
          auto m = std::make_shared<Talus::Structure::Membrane>();
          m->material.thickness = p.thickness;
          m->material.set_isotropic(p.membrane_E, p.membrane_nu);
          if (p.orthotropic)
            {
              m->material.youngs_modulus_2 = p.membrane_E2;
              m->material.shear_modulus    = p.membrane_G;
            }
          m->material.prestress = p.membrane_prestress;
          m->material.wrinkling = p.wrinkling;
          m->density            = p.membrane_density;
          m->pressure           = p.pressure;
          return m;
        }

        unsigned int
        node_at(const Structure &s, const Point<3> &x) const
        {
          const unsigned int n = s.find_node(x, 1e-9 * (1. + x.norm()));
          AssertThrow(n != numbers::invalid_unsigned_int,
                      ExcMessage("internal: no node at a model point"));
          return n;
        }
      };


      /** A straight line mesh from a to b with n cells. */
      void
      make_line(Triangulation<1, 3> &tria,
                const Point<3>      &a,
                const Point<3>      &b,
                const unsigned int   n)
      {
        std::vector<Point<3>>    vertices(n + 1);
        std::vector<CellData<1>> cells(n);
        for (unsigned int i = 0; i <= n; ++i)
          vertices[i] = a + (b - a) * (static_cast<double>(i) / n);
        for (unsigned int i = 0; i < n; ++i)
          cells[i].vertices = {i, i + 1};
        tria.create_triangulation(vertices, cells, SubCellData());
      }

      void
      make_polyline(Triangulation<1, 3> &tria, const std::vector<Point<3>> &x)
      {
        std::vector<CellData<1>> cells(x.size() - 1);
        for (unsigned int i = 0; i + 1 < x.size(); ++i)
          cells[i].vertices = {i, i + 1};
        tria.create_triangulation(x, cells, SubCellData());
      }


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
                InputFile::reject(S + "/Loads",
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
            InputFile::reject(S + "/Line members",
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


      // ------------------------------------------------------------------
      /** A disk or square membrane mesh (flattened from a 2D mesh). */
      void
      make_flat_mesh(Triangulation<2, 3> &tria,
                     const bool           disk,
                     const double         size,
                     const unsigned int   refinements)
      {
        Triangulation<2> flat;
        if (disk)
          GridGenerator::hyper_ball(flat, Point<2>(), size);
        else
          GridGenerator::hyper_cube(flat, -0.5 * size, 0.5 * size);
        flat.refine_global(refinements);
        GridGenerator::flatten_triangulation(flat, tria);
      }


      /**
       * Hencky's clamped circular membrane under uniform (follower)
       * pressure q: w0 = c_w a (q a/(E t))^(1/3), sigma_centre = c_sigma (E
       * q^2 a^2/t^2)^(1/3); c_w, c_sigma from contrib/reference/
       * hencky_membrane.py (nu = 0.25, 0.3, 0.5). The mean Cauchy stress of
       * the cells around the centre is compared with sigma_centre.
       */
      class CircularMembrane : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "Hencky clamped circular membrane under pressure";
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          make_flat_mesh(s.add_membrane("membrane", membrane()).triangulation,
                         true,
                         p.radius,
                         p.refinements + level);
          s.setup_dofs();
          for (const unsigned int n : s.find_nodes([&](const Point<3> &x) {
                 return x.norm() > p.radius * (1. - 1e-10);
               }))
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(n, c);
          centre = node_at(s, Point<3>());
        }

        void
        initial_guess(const Structure &s, Vector<double> &u) const override
        {
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            {
              const Point<3> &x = s.node_position(k);
              u[s.node_dof(k, 2)] =
                p.initial_deflection *
                std::max(0., 1. - x.norm_square() / (p.radius * p.radius));
            }
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          double c_w = 0., c_s = 0.;
          if (std::abs(p.membrane_nu - 0.3) < 1e-12)
            {
              c_w = 0.653443;
              c_s = 0.431101;
            }
          else if (std::abs(p.membrane_nu - 0.25) < 1e-12)
            {
              c_w = 0.665791;
              c_s = 0.425612;
            }
          else if (std::abs(p.membrane_nu - 0.5) < 1e-12)
            {
              c_w = 0.594879;
              c_s = 0.461328;
            }
          else
            InputFile::reject(S + "/Membrane",
                              "Poisson's ratio",
                              std::to_string(p.membrane_nu),
                              "the circular membrane model has reference "
                              "values for 0.25, 0.3 and 0.5 only");
          const double Q = p.pressure * p.radius / (p.membrane_E * p.thickness);
          const double w0 = c_w * p.radius * std::cbrt(Q);
          const double sc =
            c_s * std::cbrt(p.membrane_E * p.pressure * p.pressure * p.radius *
                            p.radius / (p.thickness * p.thickness));
          // Mean stress of the cells that touch the centre.
          const auto &mesh = *s.membrane_meshes[0];
          double      sum = 0., area = 0.;
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              if (cell->vertex(v).norm() < 1e-12 * p.radius)
                {
                  const auto &o = mesh.cell_output[cell->active_cell_index()];
                  sum += o.mean_stress * o.area;
                  area += o.area;
                }
          return {{"centre deflection w0 [m]", u[s.node_dof(centre, 2)], w0},
                  {"centre stress [Pa]", sum / area, sc}};
        }

      private:
        unsigned int centre = 0;
      };


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
            InputFile::reject(S + "/Membrane",
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


      // ------------------------------------------------------------------
      /**
       * Frictionless ring on a cable (sliding cable through 3 nodes):
       * supports A = (-b,0,0), B = (b,0,0), unstretched length L_u, load P
       * at the ring (any direction in the x-z plane). The ring lies on the
       * ellipse with foci A, B and l = |x - A| + |x - B|, where its normal
       * is parallel to P; one tension T = EA lambda (lambda^2 - 1)/2,
       * lambda = l/L_u, on both sides, and T |e_A + e_B| = |P|.
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
            InputFile::reject(S + "/Geometry",
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
          const auto tension = [&](const double l) {
            const double lambda = l / p.unstretched_length;
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
          auto brake              = std::make_shared<Talus::Structure::Brake>();
          brake->stiffness        = p.brake_k;
          brake->activation_force = p.brake_Fa;
          brake->hardening        = p.brake_H;
          brake->stroke_limit     = p.brake_smax;
          brake->slack_stiffness_ratio = p.slack_ratio;
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


      // ------------------------------------------------------------------
      /**
       * A line mesh from a Gmsh file (cables or trusses), the vertices of
       * only one cell (the ends) fixed, under gravity; or a membrane mesh
       * (quadrilaterals), its boundary fixed, under pressure and gravity.
       * The largest nodal displacement is reported, and compared with
       * 'reference largest displacement' if that is set (e.g. the
       * taut-string sag, the square membrane's w_max).
       */
      class LineFromFile : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return p.mesh_is_membrane ?
                   "membrane mesh from a file, boundary fixed, pressure and "
                   "gravity" :
                   "line mesh from a file, ends fixed, gravity";
        }

        template <int dim>
        void
        read(Triangulation<dim, 3> &tria, const std::string &what) const
        {
          Talus::Structure::read_gmsh_mesh(
            tria, p.mesh_file, S + "/Geometry", "mesh file", what);
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          return {{S + "/Geometry", "mesh file", p.mesh_file}};
        }

        void
        build(Structure &s, const unsigned int) override
        {
          if (p.mesh_is_membrane)
            {
              auto &mesh = s.add_membrane("mesh", membrane());
              read(mesh.triangulation, "quadrilaterals");
              s.setup_dofs();
              // Fix the boundary: vertices of faces without a neighbour.
              for (const auto &cell :
                   mesh.triangulation.active_cell_iterators())
                for (const unsigned int f : cell->face_indices())
                  if (cell->at_boundary(f))
                    for (unsigned int v = 0; v < 2; ++v)
                      for (unsigned int c = 0; c < 3; ++c)
                        s.prescribe(node_at(s, cell->face(f)->vertex(v)), c);
              s.gravity = p.gravity;
              return;
            }
          auto &mesh = s.add_line_mesh("mesh", line_element());
          read(mesh.triangulation, "line elements");
          s.setup_dofs();
          // Fix the two ends (vertices of one cell only).
          std::vector<unsigned int> count(mesh.triangulation.n_vertices(), 0);
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              ++count[cell->vertex_index(v)];
          for (const auto &cell : mesh.triangulation.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              if (count[cell->vertex_index(v)] == 1)
                for (unsigned int c = 0; c < 3; ++c)
                  s.prescribe(node_at(s, cell->vertex(v)), c);
          s.gravity = p.gravity;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          double umax = 0.;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            umax = std::max(umax, s.node_displacement(u, k).norm());
          if (p.reference_displacement > 0.)
            return {
              {"largest displacement [m]", umax, p.reference_displacement}};
          return {{"largest displacement [m]", umax, 0., false}};
        }
      };


      /**
       * The standard barrier (BarrierBuilder) under pre-stress, gravity and
       * a field load F. Reference: global equilibrium. The reactions at all
       * supports must balance the total weight W = g (sum rho A L of posts,
       * cables and ropes + rho t A of the net), computed from the geometry,
       * and F. Active brakes must carry F_a + H s.
       */
      class Barrier : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "standard three-field barrier under pre-stress, gravity "
                 "and a field load";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          builder            = p.barrier;
          builder.net        = *membrane();
          builder.brake_k    = p.brake_k;
          builder.brake_Fa   = p.brake_Fa;
          builder.brake_H    = p.brake_H;
          builder.brake_smax = p.brake_smax;
          builder.build(s);
          // The self weight acts from the start (the barrier is erected
          // under gravity): it is part of the form finding, and the load
          // factor scales the field load only.
          s.gravity       = p.gravity;
          s.scale_gravity = false;
          // Stage 1 of the form finding: post heads held, so that the net
          // and the support cables find their pre-stressed shape under
          // their weight first.
          for (const unsigned int n : builder.post_heads)
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(n, c);
        }

        void
        before_load_steps(Structure                      &s,
                          Talus::Structure::StaticSolver &solver) override
        {
          // Stage 2: release the heads (posts and ropes take over) and find
          // the pre-stressed equilibrium of the whole barrier under its
          // weight. Without the weight this state is degenerate: the net
          // and the top cable pull the inner heads along the post axis,
          // which the post alone carries, and their retaining ropes are
          // left without force (and their rope-brake nodes without
          // stiffness).
          const Vector<double> u = solver.displacement;
          for (const unsigned int n : builder.post_heads)
            for (unsigned int c = 0; c < 3; ++c)
              s.release(n, c);
          s.setup_system();
          solver.setup();
          solver.displacement = u;
          const auto status   = solver.solve(0.);
          std::cout << "  stage 2 (post heads released, pre-stress and "
                       "gravity): "
                    << (status.converged ? "converged" : "FAILED") << " in "
                    << status.iterations << " Newton iterations\n";
          if (!status.converged)
            throw ExcSimulationFailed("the pre-stressed barrier with free "
                                      "post heads did not converge: " +
                                      status.failure);
        }

        bool
        prestress_step() const override
        {
          return true;
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        /** Damped motion ends with a static solve from the state reached
         * (dynamic relaxation); undamped motion is checked for its energy. */
        bool
        relax_to_equilibrium() const override
        {
          return p.mass_damping > 0. || p.stiffness_damping > 0.;
        }

        bool
        form_finding_before_dynamics() const override
        {
          return true;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure &s,
                const Vector<double> &,
                const double) override
        {
          // CSV: the force on each group of supports (sum of the reactions,
          // x, y, z) and the axial force of every post.
          std::vector<std::pair<std::string, double>> columns;
          const unsigned int n_posts = builder.n_fields + 1;
          const std::vector<
            std::pair<std::string, std::pair<unsigned, unsigned>>>
            groups = {{"post_bases", {0, n_posts}},
                      {"bottom_cable_anchors", {n_posts, n_posts + 2}},
                      {"top_cable_anchors", {n_posts + 2, n_posts + 4}},
                      {"lateral_anchors", {n_posts + 4, n_posts + 6}},
                      {"retaining_anchors",
                       {n_posts + 6,
                        static_cast<unsigned>(builder.supports.size())}}};
          for (const auto &[name, range] : groups)
            {
              Tensor<1, 3> R;
              for (unsigned int k = range.first; k < range.second; ++k)
                R += s.reaction(builder.supports[k]);
              for (unsigned int c = 0; c < 3; ++c)
                columns.emplace_back(name + "_R" + "xyz"[c], R[c]);
            }
          const auto &posts = s.line_meshes[builder.post_meshes[0]]->force;
          for (unsigned int i = 0; i < posts.size(); ++i)
            columns.emplace_back("post_" + std::to_string(i) + "_force",
                                 posts[i]);
          if (time == 0.)
            initial_energy = total_energy;
          max_kinetic = std::max(max_kinetic, kinetic_energy);
          max_drift =
            std::max(max_drift, std::abs(total_energy - initial_energy));
          columns.insert(columns.begin(),
                         {{"time", time},
                          {"total_energy", total_energy},
                          {"kinetic_energy", kinetic_energy}});
          return columns;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          // Weight from the geometry of the parameters (not from the
          // structure's lumped masses).
          const auto    &b     = builder;
          const double   Hs    = b.post_length();
          const double   L     = b.n_fields * b.field_width;
          const Point<3> head0 = b.net_point(0., Hs);
          const Point<3> top_left(-b.end_anchor_offset, head0[1], 0.);
          const Point<3> lateral_left(-b.lateral_anchor_offset,
                                      head0[1] - b.lateral_anchor_downslope,
                                      0.);
          double mass = (b.n_fields + 1) * b.post_density * b.post_A * Hs;
          mass += b.cable_density * b.cable_A *
                  (2. * top_left.distance(head0) + L + // top
                   L + 2. * b.end_anchor_offset +      // bottom
                   2. * Hs);                           // edges
          mass +=
            b.lateral_density * b.lateral_A * 2. * lateral_left.distance(head0);
          for (unsigned int i = 0; i <= b.n_fields; ++i)
            for (const double side : {-1., 1.})
              {
                const Point<3> head = b.net_point(i * b.field_width, Hs);
                const Point<3> anchor(i * b.field_width +
                                        side * b.anchor_spread,
                                      b.anchor_distance,
                                      0.);
                mass += b.rope_density * b.rope_A *
                        (head.distance(anchor) - b.brake_length);
              }
          mass += p.membrane_density * p.thickness * L * Hs;
          const Tensor<1, 3> W = mass * p.gravity;
          const Tensor<1, 3> F = b.field_load;
          Tensor<1, 3>       R;
          for (const unsigned int n : b.supports)
            R += s.reaction(n);
          // R: sum of reaction() = f_int - f_ext over the supports. The
          // residual vanishes at the free nodes and the internal forces of
          // every element sum to zero, so R = -(sum of all external forces)
          // = -(W + F) in equilibrium.
          const double scale = (W.norm() + F.norm());
          double       umax  = 0.;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            umax = std::max(umax, s.node_displacement(u, k).norm());
          const auto max_force = [&](const std::vector<unsigned int> &meshes) {
            double f = 0.;
            for (const unsigned int mesh : meshes)
              for (const double x : s.line_meshes[mesh]->force)
                f = std::max(f, std::abs(x));
            return f;
          };
          const auto min_force = [&](const std::vector<unsigned int> &meshes) {
            double f = std::numeric_limits<double>::max();
            for (const unsigned int mesh : meshes)
              for (const double x : s.line_meshes[mesh]->force)
                f = std::min(f, x);
            return f;
          };
          double max_stroke = 0.;
          for (const auto &st : s.line_meshes[b.brake_meshes[0]]->state)
            max_stroke = std::max(max_stroke, st.plastic);
          // Active brakes (stroke > 0, not blocked) carry F_a + H s.
          double       brake_law_error = 0.;
          unsigned int n_active        = 0;
          {
            const auto &m = *s.line_meshes[b.brake_meshes[0]];
            for (unsigned int c = 0; c < m.state.size(); ++c)
              if (m.state[c].plastic > 0. &&
                  (b.brake_smax == 0. || m.state[c].plastic < b.brake_smax))
                {
                  ++n_active;
                  brake_law_error =
                    std::max(brake_law_error,
                             std::abs(
                               m.force[c] -
                               (b.brake_Fa + b.brake_H * m.state[c].plastic)) /
                               b.brake_Fa);
                }
          }
          unsigned int n_slack_ropes = 0;
          for (const double x : s.line_meshes[b.rope_meshes[0]]->force)
            n_slack_ropes += (x <= 0.);
          std::vector<Result> r = {
            {"|R + W + F| / (|W| + |F|)",
             (R + W + F).norm() / scale,
             0.,
             true,
             true},
            {"total weight [N]", W.norm(), 0., false},
            {"field load [N]", F.norm(), 0., false},
            {"sum of reactions y [N]", R[1], 0., false},
            {"sum of reactions z [N]", R[2], 0., false},
            {"largest displacement [m]", umax, 0., false},
            {"top cable tension [N]",
             max_force({b.support_cable_meshes[0]}),
             0.,
             false},
            {"bottom cable tension [N]",
             max_force({b.support_cable_meshes[1]}),
             0.,
             false},
            {"edge cable tension [N]",
             max_force({b.support_cable_meshes[2], b.support_cable_meshes[3]}),
             0.,
             false},
            {"lateral rope force [N]",
             max_force(b.lateral_rope_meshes),
             0.,
             false},
            {"largest retaining rope force [N]",
             max_force(b.rope_meshes),
             0.,
             false},
            {"smallest retaining rope force [N]",
             min_force(b.rope_meshes),
             0.,
             false},
            {"slack retaining ropes", double(n_slack_ropes), 0., false},
            {"largest brake force [N]", max_force(b.brake_meshes), 0., false},
            {"largest post compression [N]",
             -min_force(b.post_meshes),
             0.,
             false},
            {"largest brake stroke [m]", max_stroke, 0., false},
            {"active brakes", double(n_active), 0., false}};
          if (n_active > 0)
            r.push_back({"active brakes: max |N - (F_a + H s)| / F_a",
                         brake_law_error,
                         0.,
                         true,
                         true});
          if (p.dynamic && !relax_to_equilibrium() && max_kinetic > 0.)
            {
              // Undamped motion: energy (kinetic + strain + load potential)
              // against its initial value, relative to the largest kinetic
              // energy.
              r.push_back(
                {"largest kinetic energy [J]", max_kinetic, 0., false});
              r.push_back({"max |E(t) - E(0)| / max kinetic energy",
                           max_drift / max_kinetic,
                           0.,
                           true,
                           true});
              r[0].checked = false; // not in equilibrium while moving
            }
          // Post forces one by one.
          const auto &posts = s.line_meshes[b.post_meshes[0]]->force;
          for (unsigned int i = 0; i < posts.size(); ++i)
            r.push_back({"post " + std::to_string(i) + " axial force [N]",
                         posts[i],
                         0.,
                         false});
          return r;
        }

      private:
        Talus::Structure::BarrierBuilder builder;
        double initial_energy = 0., max_kinetic = 0., max_drift = 0.;
      };


      /**
       * Columns of the CSV common to all models: the stored elastic energy,
       * the largest axial force of every line mesh (the tension of a sliding
       * cable), and for brakes the largest stroke and the dissipated energy.
       */
      std::vector<std::pair<std::string, double>>
      structure_columns(const Structure &s)
      {
        std::vector<std::pair<std::string, double>> c = {
          {"strain_energy", s.strain_energy()}};
        for (const auto &m : s.line_meshes)
          {
            double f = 0.;
            for (const double x : m->force)
              f = std::max(f, std::abs(x));
            c.emplace_back(m->name + "_max_force", f);
            if (m->element && m->element->name() == "brake")
              {
                double stroke = 0., D = 0.;
                for (const auto &st : m->state)
                  {
                    stroke = std::max(stroke, st.plastic);
                    D += st.accumulated;
                  }
                c.emplace_back(m->name + "_max_stroke", stroke);
                c.emplace_back(m->name + "_dissipated_energy", D);
              }
          }
        return c;
      }


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


      /**
       * A flat square membrane (side a, centred at the origin, in the x-y
       * plane, 'refinements' + level times refined) loaded in its plane:
       * u_z = 0 at every node (a flat membrane has no stiffness normal to
       * itself before it is stressed); no pre-stress step.
       */
      class InPlaneSquareMembrane : public Model
      {
      public:
        using Model::Model;

        bool
        prestress_step() const override
        {
          return false;
        }

      protected:
        /** The mesh, setup_dofs() and u_z = 0 everywhere. */
        void
        build_square(Structure &s, const unsigned int level) const
        {
          make_flat_mesh(s.add_membrane("membrane", membrane()).triangulation,
                         false,
                         p.side,
                         p.refinements + level);
          s.setup_dofs();
          for (unsigned int n = 0; n < s.n_nodes(); ++n)
            s.prescribe(n, 2);
        }
      };


      /**
       * A square membrane (side a, isotropic, no pre-stress) in simple
       * shear, in its plane (u_z = 0 everywhere): every boundary node
       * displaced by u_x = lambda gamma (y + a/2).
       * The homogeneous state is the solution. Taut (no wrinkling): shear
       * stress G gamma. With the wrinkling law the compressive principal
       * stress vanishes (tension field): uniaxial tension E gamma/2 along
       * the diagonal, shear stress E gamma/4 (the law gives exactly this:
       * doc/verification.md). Measured: the x-reactions of the boundary
       * nodes with y > 0 (top edge; the side edges' normal tractions
       * cancel), F = tau t a, to first order in gamma.
       */
      class ShearedMembrane : public InPlaneSquareMembrane
      {
      public:
        using InPlaneSquareMembrane::InPlaneSquareMembrane;

        std::string
        description() const override
        {
          return std::string("square membrane in simple shear") +
                 (p.wrinkling ? ", wrinkling (tension field)" : ", taut");
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          build_square(s, level);
          boundary = s.find_nodes([&](const Point<3> &x) {
            return std::max(std::abs(x[0]), std::abs(x[1])) >
                   0.5 * p.side * (1. - 1e-10);
          });
          for (const unsigned int n : boundary)
            {
              s.prescribe(
                n, 0, p.shear_strain * (s.node_position(n)[1] + 0.5 * p.side));
              s.prescribe(n, 1);
            }
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &) override
        {
          double F = 0.;
          for (const unsigned int n : boundary)
            if (s.node_position(n)[1] > 1e-10 * p.side)
              F += s.reaction(n)[0];
          double min_principal = 1e300, max_principal = -1e300;
          for (const auto &o : s.membrane_meshes[0]->cell_output)
            {
              min_principal = std::min(min_principal, o.min_principal);
              max_principal = std::max(max_principal, o.max_principal);
            }
          const double E = p.membrane_E, nu = p.membrane_nu;
          const double tau = p.wrinkling ?
                               E * p.shear_strain / 4. :
                               E / (2. * (1. + nu)) * p.shear_strain;
          return {{"shear force on the top edge [N]",
                   F,
                   tau * p.thickness * p.side},
                  {"largest principal stress [Pa]",
                   max_principal,
                   p.wrinkling ? E * p.shear_strain / 2. : tau,
                   true},
                  {p.wrinkling ? "compression: max(0, -sigma_min) / sigma_max" :
                                 "sigma_min / sigma_max (taut: -1)",
                   p.wrinkling ? std::max(0., -min_principal / max_principal) :
                                 min_principal / max_principal,
                   p.wrinkling ? 0. : -1.,
                   true,
                   p.wrinkling}};
        }

      private:
        std::vector<unsigned int> boundary;
      };


      /**
       * A square membrane (side a, centred at the origin, in the x-y plane,
       * u_z = 0) under a homogeneous stretch imposed on its boundary:
       * biaxial, u_x = lambda e_x x and u_y = lambda e_y y on every boundary
       * node, or uniaxial stress, u_x = lambda e_x x on the edges x = +-a/2,
       * u_y = 0 on the line y = 0, the edges y = +-a/2 free. Material axis
       * 1 is x (orthotropic or isotropic MembraneMaterial). Closed form
       * with lambda_1 = 1 + e_x, E_11 = (lambda_1^2 - 1)/2 and (biaxial)
       * lambda_2 = 1 + e_y, E_22 = (lambda_2^2 - 1)/2:
       *   S = C E + S_0 (E_12 = 0), D = 1 - nu12^2 E2/E1,
       *   S_11 = (E1 E_11 + nu12 E2 E_22)/D, S_22 = (nu12 E2 E_11 + E2
       * E_22)/D; uniaxial stress: S_22 = 0, so E_22 = -nu12 E_11 (no
       * pre-stress) and S_11 = E1 E_11. Cauchy stresses sigma_11 = lambda_1
       * S_11 / lambda_2, sigma_22 = lambda_2 S_22 / lambda_1 (J = lambda_1
       * lambda_2, thickness constant), and the edge forces (reactions)
       * F_x = t a lambda_1 S_11 on x = a/2, F_y = t a lambda_2 S_22 on
       * y = a/2.
       */
      class StretchedMembrane : public InPlaneSquareMembrane
      {
      public:
        using InPlaneSquareMembrane::InPlaneSquareMembrane;

        std::string
        description() const override
        {
          return std::string("square ") +
                 (p.orthotropic ? "orthotropic" : "isotropic") +
                 " membrane under " +
                 (p.uniaxial_stress ? "uniaxial stress" : "biaxial stretch");
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          build_square(s, level);
          const double h = 0.5 * p.side * (1. - 1e-10);
          x_edge = s.find_nodes([&](const Point<3> &x) { return x[0] > h; });
          y_edge = s.find_nodes([&](const Point<3> &x) { return x[1] > h; });
          for (unsigned int n = 0; n < s.n_nodes(); ++n)
            {
              const Point<3> X = s.node_position(n);
              const bool on_x = std::abs(X[0]) > h, on_y = std::abs(X[1]) > h;
              if (on_x)
                s.prescribe(n, 0, p.stretch_x * X[0]);
              if (p.uniaxial_stress ? std::abs(X[1]) < 1e-10 * p.side :
                                      on_y || on_x)
                s.prescribe(n, 1, p.uniaxial_stress ? 0. : p.stretch_y * X[1]);
              if (!p.uniaxial_stress && on_y && !on_x)
                s.prescribe(n, 0, p.stretch_x * X[0]);
            }
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &) override
        {
          const auto  &m  = s.membrane_meshes[0]->membrane->material;
          const double E1 = m.youngs_modulus_1, E2 = m.youngs_modulus_2,
                       nu = m.poissons_ratio, t = m.thickness;
          const double D  = 1. - nu * nu * E2 / E1;
          const double l1 = 1. + p.stretch_x, E11 = 0.5 * (l1 * l1 - 1.);
          double       l2 = 1. + p.stretch_y, E22 = 0.5 * (l2 * l2 - 1.);
          if (p.uniaxial_stress)
            {
              E22 = -nu * E11;
              l2  = std::sqrt(1. + 2. * E22);
            }
          const double S11     = p.uniaxial_stress ? E1 * E11 :
                                                     (E1 * E11 + nu * E2 * E22) / D,
                       S22     = p.uniaxial_stress ? 0. :
                                                     (nu * E2 * E11 + E2 * E22) / D;
          const double sigma11 = l1 * S11 / l2, sigma22 = l2 * S22 / l1;
          double       Fx = 0., Fy = 0., smax = -1e300, smin = 1e300;
          for (const unsigned int n : x_edge)
            Fx += s.reaction(n)[0];
          for (const unsigned int n : y_edge)
            Fy += s.reaction(n)[1];
          for (const auto &o : s.membrane_meshes[0]->cell_output)
            {
              smax = std::max(smax, o.max_principal);
              smin = std::min(smin, o.min_principal);
            }
          // Principal values of the homogeneous state (no shear).
          const double big      = std::max(sigma11, sigma22),
                       small    = std::min(sigma11, sigma22);
          std::vector<Result> r = {
            {"edge force F_x on x = a/2 [N]", Fx, t * p.side * l1 * S11},
            {"largest principal Cauchy stress [Pa]", smax, big}};
          if (p.uniaxial_stress)
            r.push_back({"|smallest principal stress| / largest (0)",
                         std::abs(smin) / smax,
                         0.,
                         true,
                         true});
          else
            {
              r.push_back(
                {"edge force F_y on y = a/2 [N]", Fy, t * p.side * l2 * S22});
              r.push_back(
                {"smallest principal Cauchy stress [Pa]", smin, small});
            }
          return r;
        }

      private:
        std::vector<unsigned int> x_edge, y_edge;
      };


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



      // ------------------------------------------------------------------
      /**
       * Mean of displacement component @p c of solid mesh @p mesh over its
       * faces with boundary id @p id, int u_c dA0 / A0 (the work-conjugate
       * of a uniform traction along c) [m].
       */
      template <int dim>
      double
      face_mean(const Talus::Structure::SolidMeshT<dim> &mesh,
                const Vector<double>                    &u,
                const unsigned int                       id,
                const unsigned int                       c)
      {
        const QGauss<dim - 1>            quadrature(mesh.fe->degree + 1);
        FEFaceValues<dim, 3>             fe_face_values(*mesh.fe,
                                            quadrature,
                                            update_values | update_JxW_values);
        const FEValuesExtractors::Scalar uc(c);
        Vector<double>                   local(mesh.dof_handler.n_dofs());
        for (unsigned int i = 0; i < local.size(); ++i)
          local[i] = u[mesh.offset + i];
        std::vector<double> values(quadrature.size());
        double              integral = 0., area = 0.;
        for (const auto &cell : mesh.dof_handler.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) && cell->face(f)->boundary_id() == id)
              {
                fe_face_values.reinit(cell, f);
                fe_face_values[uc].get_function_values(local, values);
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  {
                    integral += values[q] * fe_face_values.JxW(q);
                    area += fe_face_values.JxW(q);
                  }
              }
        return integral / area;
      }


      // ------------------------------------------------------------------
      /**
       * A continuum solid alone (subsection Solid): generated box or Gmsh
       * file of hexahedra, the supports and the traction of that
       * subsection, gravity. Reports the largest displacement, compared
       * with 'reference largest displacement' if that is set.
       */
      class SolidModel : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return std::string(p.plane_solid ? "plane-strain " : "") +
                 "continuum solid (St. Venant-Kirchhoff, FE_Q(" +
                 std::to_string(p.solid.degree) +
                 ")) with the supports and loads of subsection Solid";
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          const auto &g = p.solid_geometry;
          if (g.fixed_boundary_ids.empty() && !g.support_boxes.empty())
            return {{S + "/Solid",
                     "support boxes",
                     std::to_string(g.support_boxes.size()) + " box(es)"}};
          std::string ids;
          for (const unsigned int id : g.fixed_boundary_ids)
            ids += (ids.empty() ? "" : ", ") + std::to_string(id);
          return {{S + "/Solid", "fixed boundary ids", ids}};
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const std::string ss = S + "/Solid";
          if (p.solid_geometry.traction_boundary_id >= 0)
            add_solid_mesh(s, "solid", level)
              .emplace_back(p.solid_geometry.traction_boundary_id,
                            p.solid_geometry.traction);
          else
            add_solid_mesh(s, "solid", level);
          s.setup_dofs();
          on_solid(s, [&](const auto &mesh) {
            for (const unsigned int id : p.solid_geometry.fixed_boundary_ids)
              if (s.prescribe_solid_boundary(mesh, id) == 0)
                InputFile::reject(ss,
                                  "fixed boundary ids",
                                  std::to_string(id),
                                  "every fixed boundary id must be the id of "
                                  "faces on the boundary of the solid (a "
                                  "generated box has ids 0 to 5, a plane "
                                  "rectangle 0 to 3), and boundary id " +
                                    std::to_string(id) + " has none");
            unsigned int k = 0;
            for (const auto &box : p.solid_geometry.support_boxes)
              {
                ++k;
                if (s.prescribe_solid_box(
                      mesh, box.lower, box.upper, box.components) == 0)
                  InputFile::reject(
                    ss,
                    "support boxes",
                    "box " + std::to_string(k),
                    std::string("every support box must contain a node of "
                                "the solid") +
                      (p.plane_solid ? " (a plane solid lies at "
                                       "z = 0)" :
                                       "") +
                      ", and box " + std::to_string(k) + " contains none");
              }
          });
          s.gravity = p.gravity;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          double umax = 0.;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            umax = std::max(umax, s.node_displacement(u, k).norm());
          if (p.reference_displacement > 0.)
            return {
              {"largest displacement [m]", umax, p.reference_displacement}};
          return {{"largest displacement [m]", umax, 0., false}};
        }

      protected:
        std::shared_ptr<Talus::Structure::ContinuumSolid<3>>
        solid_component() const
        {
          return std::make_shared<Talus::Structure::ContinuumSolid<3>>(p.solid);
        }

        /**
         * Add the model's solid named @p name: the box of subsection Solid
         * (Triangulation<3,3>), or for the plane models its rectangle in
         * the x-y plane as a plane-strain solid of 'thickness' t. Returns
         * its tractions (to fill before setup_dofs()).
         */
        std::vector<std::pair<unsigned int, Tensor<1, 3>>> &
        add_solid_mesh(Structure         &s,
                       const std::string &name,
                       const unsigned int level) const
        {
          const auto &g = p.solid_geometry;
          if (p.plane_solid)
            {
              Triangulation<2> plane;
              g.create_triangulation(plane, level, S + "/Solid");
              auto solid =
                std::make_shared<Talus::Structure::ContinuumSolid<2>>();
              solid->youngs_modulus = p.solid.youngs_modulus;
              solid->poissons_ratio = p.solid.poissons_ratio;
              solid->density        = p.solid.density;
              solid->degree         = p.solid.degree;
              return s.add_plane_solid(name, solid, g.thickness, plane)
                .tractions;
            }
          auto &mesh = s.add_solid(name, solid_component());
          g.create_triangulation(mesh.triangulation, level, S + "/Solid");
          return mesh.tractions;
        }

        /** Call @p f with the model's (last) solid mesh, 3D or plane. */
        template <typename Function>
        static void
        on_solid(const Structure &s, const Function &f)
        {
          if (!s.plane_solid_meshes.empty())
            f(*s.plane_solid_meshes.back());
          else
            f(*s.solid_meshes.back());
        }

        /** Mean of displacement component @p c over the faces of boundary
         * id @p id of the model's solid (the work-conjugate of a uniform
         * traction there) [m]. */
        static double
        solid_face_mean(const Structure      &s,
                        const Vector<double> &u,
                        const unsigned int    id,
                        const unsigned int    c)
        {
          double mean = 0.;
          on_solid(s,
                   [&](const auto &mesh) { mean = face_mean(mesh, u, id, c); });
          return mean;
        }

        /** Direction of the "vertical" (height, load, gravity): z, or y
         * for a plane solid. */
        unsigned int
        vertical() const
        {
          return p.plane_solid ? 1 : 2;
        }

        /** Cross-section of the generated solid normal to x: width b
         * (y extent, or the thickness t of a plane solid) and height h
         * (z extent, or the y extent of a plane solid) [m]. */
        double
        width() const
        {
          const auto &g = p.solid_geometry;
          return p.plane_solid ? g.thickness :
                                 g.upper_corner[1] - g.lower_corner[1];
        }

        double
        height() const
        {
          const auto &g = p.solid_geometry;
          return g.upper_corner[vertical()] - g.lower_corner[vertical()];
        }

        /** Young's modulus and Poisson's ratio of the beam and bar
         * formulas: E, nu, or for plane strain E/(1 - nu^2), nu/(1 - nu). */
        double
        effective_modulus() const
        {
          const double nu = p.solid.poissons_ratio;
          return p.plane_solid ? p.solid.youngs_modulus / (1. - nu * nu) :
                                 p.solid.youngs_modulus;
        }

        double
        effective_poisson() const
        {
          const double nu = p.solid.poissons_ratio;
          return p.plane_solid ? nu / (1. - nu) : nu;
        }
      };


      /**
       * Cantilever: the generated box of subsection Solid (length L along
       * x, width b along y, height h along z) clamped at x = x_min
       * (boundary id 0: every DoF of the face fixed) and loaded on x = x_max
       * (id 1) by the uniform dead shear traction P/(b h) along z, P the
       * z component of 'point load'. The tip deflection is the load's
       * work-conjugate, the mean of u_z over the end face,
       * delta = int u_z dA / (b h). Reference: Timoshenko's beam,
       *   delta = P L^3/(3 E I) + P L/(kappa G b h),  I = b h^3/12,
       *   kappa = 10 (1 + nu)/(12 + 11 nu) (rectangle, Cowper 1966);
       * Euler-Bernoulli P L^3/(3 E I) is printed. The load must be small
       * (delta << h) for the linear beam theories to apply. 'plane
       * cantilever': the rectangle in the x-y plane (height h along y,
       * width b = the thickness t), load 'point load' (0, P, 0), and the
       * plane-strain beam: E' = E/(1 - nu^2) and nu' = nu/(1 - nu) in the
       * formulas above.
       */
      class Cantilever : public SolidModel
      {
      public:
        using SolidModel::SolidModel;

        std::string
        description() const override
        {
          return std::string(p.plane_solid ? "plane-strain " : "") +
                 "cantilever: continuum solid (St. Venant-Kirchhoff, FE_Q(" +
                 std::to_string(p.solid.degree) +
                 ")) clamped at x_min, end shear load; Timoshenko beam";
        }

        bool
        supports_dynamics() const override
        {
          return false;
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
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const auto  &g               = p.solid_geometry;
          const double L               = g.upper_corner[0] - g.lower_corner[0];
          const double b               = width();
          const double h               = height();
          const double E               = effective_modulus();
          const double nu              = effective_poisson();
          const double P               = p.point_load[vertical()];
          const double I               = b * h * h * h / 12.;
          const double G               = E / (2. * (1. + nu));
          const double kap             = 10. * (1. + nu) / (12. + 11. * nu);
          const double euler_bernoulli = P * L * L * L / (3. * E * I);
          const double timoshenko = euler_bernoulli + P * L / (kap * G * b * h);
          return {
            {"tip deflection [m]",
             solid_face_mean(s, u, 1, vertical()),
             timoshenko},
            {"Euler-Bernoulli deflection [m]", euler_bernoulli, 0., false}};
        }
      };


      /**
       * Axial bar: the generated box of subsection Solid (length L along x,
       * section A0 = b h), held by its three symmetry planes (u_x = 0 on
       * x = x_min, u_y = 0 on y = y_min, u_z = 0 on z = z_min: a
       * homogeneous uniaxial stress state is admissible) and pulled on
       * x = x_max (id 1) by the dead traction t = F/A0, F the x component
       * of 'point load'. Static, exact for any mesh (the field is linear):
       * S11 = E E11 with P11 = lambda S11 = t, i.e. E lambda (lambda^2 -
       * 1)/2 = t, end displacement (lambda - 1) L. Dynamic (the load
       * applied suddenly at t = 0 to the bar at rest): for nu = 0 the bar
       * is a one-dimensional rod whose end oscillates about the static
       * value with the period of the first axial mode, T1 = 4 L/c, c =
       * sqrt(E/rho) (all modes of the rod, omega_k = (2k - 1) omega_1,
       * cross the static value at T1/4 + n T1/2; the dispersion of the
       * higher modes of the finite elements moves the crossings slightly).
       * The period is measured from the crossings of the mean end
       * displacement (linear interpolation); the largest end displacement,
       * 2 (lambda - 1) L for the exact rod, is printed. 'plane axial bar':
       * the rectangle in the x-y plane (A0 = h t), u_x = 0 on x_min, u_y =
       * 0 on y_min, and E' = E/(1 - nu^2) in both references (uniaxial
       * force in plane strain: S11 = E' E11).
       */
      class AxialBar : public SolidModel
      {
      public:
        using SolidModel::SolidModel;

        std::string
        description() const override
        {
          return std::string(p.plane_solid ? "plane-strain " : "") +
                 "axial bar (continuum solid, FE_Q(" +
                 std::to_string(p.solid.degree) +
                 ")) on its symmetry planes, end traction" +
                 (p.dynamic ? " applied suddenly: first axial period" :
                              ": uniaxial stress");
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          return {{S, "model", p.model_text}};
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const double A0 = width() * height();
          add_solid_mesh(s, "bar", level)
            .emplace_back(1, Tensor<1, 3>({p.point_load[0] / A0, 0., 0.}));
          s.setup_dofs();
          on_solid(s, [&](const auto &mesh) {
            s.prescribe_solid_boundary(mesh, 0, {true, false, false});
            s.prescribe_solid_boundary(mesh, 2, {false, true, false});
            if (!p.plane_solid)
              s.prescribe_solid_boundary(mesh, 4, {false, false, true});
          });
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure      &s,
                const Vector<double> &u,
                const double          t) override
        {
          const double tip = solid_face_mean(s, u, 1, 0);
          if (p.dynamic)
            {
              const double u_static = static_end_displacement();
              if (!times.empty() &&
                  (samples.back() - u_static) * (tip - u_static) < 0.)
                crossings.push_back(times.back() +
                                    (t - times.back()) *
                                      (u_static - samples.back()) /
                                      (tip - samples.back()));
              times.push_back(t);
              samples.push_back(tip);
              largest = std::max(largest, std::abs(tip));
            }
          return {{"end_displacement", tip}};
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const double u_static = static_end_displacement();
          if (!p.dynamic)
            return {
              {"end displacement [m]", solid_face_mean(s, u, 1, 0), u_static}};
          const auto  &g = p.solid_geometry;
          const double L = g.upper_corner[0] - g.lower_corner[0];
          const double T1 =
            4. * L / std::sqrt(effective_modulus() / p.solid.density);
          std::vector<Result> r = {{"largest |end displacement| / static",
                                    largest / std::abs(u_static),
                                    2.,
                                    false},
                                   {"crossings of the static value",
                                    double(crossings.size()),
                                    0.,
                                    false}};
          r.push_back(
            {"first axial period [s]",
             crossings.size() >= 2 ?
               2. * (crossings.back() - crossings[0]) / (crossings.size() - 1) :
               0.,
             T1});
          return r;
        }

      private:
        std::vector<double> times, samples, crossings;
        double              largest = 0.;

        /** (lambda - 1) L with E lambda (lambda^2 - 1)/2 = t. */
        double
        static_end_displacement() const
        {
          const auto  &g  = p.solid_geometry;
          const double L  = g.upper_corner[0] - g.lower_corner[0];
          const double A0 = width() * height();
          const double t  = p.point_load[0] / A0;
          const double E  = effective_modulus();
          const double lambda =
            bisect([&](
                     const double x) { return E * x * (x * x - 1.) / 2. - t; },
                   1. / std::sqrt(3.),
                   2. + std::abs(t) / E);
          return (lambda - 1.) * L;
        }
      };


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
          return {{S + "/Solid",
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


      /**
       * Whether the free rotation of @p part (Structure::parts(),
       * can_rotate) is a mechanism to reject at set-up: in static runs
       * always when the part has a membrane or a solid; a part of cables
       * and trusses only when it is held at a single point (a cable held
       * at its two ends may swing about their line, stabilised by its
       * tension and load, e.g. the catenary). In dynamic runs a part with
       * mass may move freely (as for the translations).
       */
      bool
      rotation_is_mechanism(const Parameters    &p,
                            const Model         &model,
                            const StructurePart &part)
      {
        if (p.dynamic && !model.form_finding_before_dynamics() &&
            part.mass > 0.)
          return false;
        return part.has_continuum || part.held_at_one_point;
      }


      std::unique_ptr<Model>
      create_model(const Parameters &p)
      {
        if (p.model == "vibrating string")
          return std::make_unique<VibratingString>(p);
        if (p.model == "sheared membrane")
          return std::make_unique<ShearedMembrane>(p);
        if (p.model == "stretched membrane")
          return std::make_unique<StretchedMembrane>(p);
        if (p.model == "plastic bar")
          return std::make_unique<PlasticBar>(p);
        if (p.model == "capstan")
          return std::make_unique<Capstan>(p);
        if (p.model == "barrier")
          return std::make_unique<Barrier>(p);
        if (p.model == "solid")
          return std::make_unique<SolidModel>(p);
        if (p.model == "cantilever")
          return std::make_unique<Cantilever>(p);
        if (p.model == "hanging block")
          return std::make_unique<HangingBlock>(p);
        if (p.model == "axial bar")
          return std::make_unique<AxialBar>(p);
        if (p.model == "von Mises truss")
          return std::make_unique<VonMisesTruss>(p);
        if (p.model == "catenary" || p.model == "plane catenary")
          return std::make_unique<Catenary>(p);
        if (p.model == "circular membrane")
          return std::make_unique<CircularMembrane>(p);
        if (p.model == "square membrane")
          return std::make_unique<SquareMembrane>(p);
        if (p.model == "sliding ring")
          return std::make_unique<SlidingRing>(p);
        if (p.model == "brake")
          return std::make_unique<BrakeTest>(p);
        return std::make_unique<LineFromFile>(p);
      }


      Parameters
      parse_parameters(ParameterHandler &prm)
      {
        Parameters p;
        prm.enter_subsection(S);
        p.model      = prm.get("model");
        p.model_text = p.model;
        for (const std::string base :
             {"solid", "cantilever", "axial bar", "hanging block"})
          if (p.model == "plane " + base)
            {
              p.plane_solid = true;
              p.model       = base;
            }

        const std::string lm = S + "/Line members";
        prm.enter_subsection("Line members");
        p.line_element = prm.get("element");
        p.E            = get_positive(prm, lm, "Young's modulus");
        p.A            = get_positive(prm, lm, "cross-section area");
        p.prestress    = prm.get_double("prestress");
        p.density      = get_non_negative(prm, lm, "density");
        p.yield_stress = get_non_negative(prm, lm, "yield stress");
        p.hardening    = get_non_negative(prm, lm, "hardening modulus");
        p.elements     = prm.get_integer("elements per member");
        if (p.elements < 1)
          InputFile::reject(lm,
                            "elements per member",
                            prm.get("elements per member"),
                            "a member needs at least one element (two nodes)");
        p.slack_ratio = get_positive(prm, lm, "slack stiffness ratio");
        p.friction    = get_non_negative(prm, lm, "friction coefficient");
        p.stick_slip  = prm.get("friction law") == "stick-slip";
        if (p.stick_slip && !(p.friction > 0.))
          InputFile::reject(lm,
                            "friction law",
                            "stick-slip",
                            "the stick-slip law needs a 'friction coefficient' "
                            "> 0 (without friction a sliding cable has no "
                            "stick)");
        prm.leave_subsection();

        const std::string ms = S + "/Membrane";
        prm.enter_subsection("Membrane");
        p.membrane_E = get_positive(prm, ms, "Young's modulus");
        p.membrane_nu =
          get_in_open_interval(prm, ms, "Poisson's ratio", -1., 0.5 + 1e-12);
        p.orthotropic = prm.get_bool("orthotropic");
        if (p.orthotropic)
          {
            p.membrane_E2 = get_positive(prm, ms, "Young's modulus 2");
            p.membrane_G  = get_positive(prm, ms, "shear modulus");
          }
        p.thickness          = get_positive(prm, ms, "thickness");
        p.mode_amplitude     = prm.get_double("initial mode amplitude");
        p.membrane_density   = get_non_negative(prm, ms, "density");
        p.membrane_prestress = get_vector(prm, ms, "prestress");
        p.wrinkling          = prm.get_bool("wrinkling");
        p.initial_deflection = prm.get_double("initial deflection");
        p.shear_strain       = prm.get_double("shear strain");
        {
          const auto e = Utilities::string_to_double(
            Utilities::split_string_list(prm.get("stretch")));
          p.stretch_x = e[0];
          p.stretch_y = e[1];
        }
        p.uniaxial_stress = prm.get_bool("uniaxial stress");
        prm.leave_subsection();

        const std::string bs = S + "/Brake";
        prm.enter_subsection("Brake");
        p.brake_k      = get_positive(prm, bs, "stiffness");
        p.brake_Fa     = get_positive(prm, bs, "activation force");
        p.brake_H      = get_non_negative(prm, bs, "hardening");
        p.brake_smax   = get_non_negative(prm, bs, "stroke limit");
        p.brake_length = get_positive(prm, bs, "length");
        prm.leave_subsection();

        const std::string solid_s = S + "/Solid";
        prm.enter_subsection("Solid");
        p.solid.parse_parameters(prm, solid_s);
        p.solid_geometry.parse_parameters(prm, solid_s);
        p.solid_traction_text = prm.get("traction");
        prm.leave_subsection();
        if ((p.model == "cantilever" || p.model == "hanging block" ||
             p.model == "axial bar") &&
            !p.solid_geometry.mesh_file.empty())
          InputFile::reject(solid_s,
                            "mesh file",
                            p.solid_geometry.mesh_file,
                            "models 'cantilever', 'hanging block' and "
                            "'axial bar' generate their box (leave 'mesh "
                            "file' empty)");

        const std::string gs = S + "/Geometry";
        prm.enter_subsection("Geometry");
        p.half_span          = get_positive(prm, gs, "half span");
        p.rise               = get_positive(prm, gs, "rise");
        p.span               = get_positive(prm, gs, "span");
        p.unstretched_length = get_positive(prm, gs, "unstretched length");
        p.radius             = get_positive(prm, gs, "radius");
        p.side               = get_positive(prm, gs, "side");
        p.cable_length       = get_positive(prm, gs, "cable length");
        p.spring_EA          = get_non_negative(prm, gs, "spring EA");
        p.string_amplitude   = prm.get_double("string amplitude");
        p.wrap_angle         = prm.get_double("wrap angle");
        p.drum_radius        = get_positive(prm, gs, "drum radius");
        p.spring_length      = get_positive(prm, gs, "spring length");
        p.refinements        = prm.get_integer("refinements");
        p.mesh_file          = prm.get("mesh file");
        p.mesh_is_membrane   = prm.get("mesh file type") == "membrane";
        prm.leave_subsection();
        const bool catenary =
          p.model == "catenary" || p.model == "plane catenary";
        if (catenary && !(p.unstretched_length > p.span))
          InputFile::reject(gs,
                            "unstretched length",
                            std::to_string(p.unstretched_length),
                            "the catenary needs a cable longer than the span");
        if (p.model == "mesh file" && p.mesh_file.empty())
          InputFile::reject(gs,
                            "mesh file",
                            "",
                            "model 'mesh file' needs the name of a Gmsh file");

        const std::string ls = S + "/Loads";
        prm.enter_subsection("Loads");
        p.gravity                         = get_vector(prm, ls, "gravity");
        const std::string gravity_text    = prm.get("gravity");
        p.point_load                      = get_vector(prm, ls, "point load");
        const std::string point_load_text = prm.get("point load");
        p.pressure                        = prm.get_double("pressure");
        p.prescribed_displacement = prm.get_double("prescribed displacement");
        p.load_path               = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("load path")));
        prm.leave_subsection();
        if (p.model == "plane catenary" &&
            !(p.gravity[0] == 0. && p.gravity[2] == 0. && p.gravity[1] < 0.))
          InputFile::reject(ls,
                            "gravity",
                            gravity_text,
                            "the plane catenary lies in the x-y plane of a "
                            "2D problem and sags along -y: gravity must be "
                            "0, -g, 0 with g > 0");
        if (catenary && !(p.density > 0. && p.gravity.norm() > 0.))
          InputFile::reject(lm,
                            "density",
                            std::to_string(p.density),
                            "the catenary needs a weight: density > 0 and a "
                            "non-zero 'gravity' in subsection Loads");
        if ((p.model == "sliding ring" || p.model == "capstan") &&
            !(p.point_load.norm() > 0.))
          InputFile::reject(ls,
                            "point load",
                            point_load_text,
                            "the sliding ring needs a non-zero load in the "
                            "x-z plane");

        // Models loaded by 'point load' along one axis c only.
        const auto require_load_along = [&](const bool         applies,
                                            const unsigned int c,
                                            const std::string &what) {
          if (applies &&
              !(p.point_load[c] != 0. && p.point_load[(c + 1) % 3] == 0. &&
                p.point_load[(c + 2) % 3] == 0.))
            InputFile::reject(ls, "point load", point_load_text, what);
        };
        require_load_along(p.model == "cantilever" && !p.plane_solid,
                           2,
                           "the cantilever needs an end load 0, 0, P with "
                           "P != 0");
        require_load_along(p.model == "cantilever" && p.plane_solid,
                           1,
                           "the plane cantilever lies in the x-y plane and "
                           "needs an end load 0, P, 0 with P != 0");
        require_load_along(p.model == "plastic bar",
                           0,
                           "the plastic bar needs an end load F, 0, 0 with "
                           "F != 0");
        require_load_along(p.model == "axial bar",
                           0,
                           "the axial bar needs an end load F, 0, 0 with "
                           "F != 0");
        if (p.plane_solid && p.gravity[2] != 0.)
          InputFile::reject(ls,
                            "gravity",
                            gravity_text,
                            "a plane-strain solid lies in the x-y plane of "
                            "a 2D problem: gravity must be g_x, g_y, 0");
        if (p.plane_solid && p.solid_geometry.traction[2] != 0.)
          InputFile::reject(S + "/Solid",
                            "traction",
                            p.solid_traction_text,
                            "a plane-strain solid lies in the x-y plane of "
                            "a 2D problem: its traction must be t_x, t_y, 0");
        if (p.model == "plastic bar" && p.line_element != "truss")
          InputFile::reject(lm,
                            "element",
                            p.line_element,
                            "the plastic bar is made of 'truss' elements "
                            "(a cable has no plasticity)");
        if (p.model == "hanging block")
          {
            if (!p.plane_solid && !(p.gravity[0] == 0. && p.gravity[1] == 0. &&
                                    p.gravity[2] < 0.))
              InputFile::reject(ls,
                                "gravity",
                                gravity_text,
                                "the hanging block needs gravity 0, 0, -g "
                                "with g > 0");
            if (p.plane_solid && !(p.gravity[0] == 0. && p.gravity[1] < 0. &&
                                   p.gravity[2] == 0.))
              InputFile::reject(ls,
                                "gravity",
                                gravity_text,
                                "the plane hanging block needs gravity 0, "
                                "-g, 0 with g > 0 (it hangs along -y in the "
                                "x-y plane)");
            if (p.prestress != 0.)
              InputFile::reject(lm,
                                "prestress",
                                std::to_string(p.prestress),
                                "the hanging block's cable has no "
                                "pre-stress (its reference is for 0)");
          }
        p.barrier.parse_parameters(prm, S + "/Barrier");
        prm.enter_subsection("Solver");
        p.arc_length_control = prm.get("control") == "arc length";
        prm.leave_subsection();

        prm.enter_subsection("Dynamics");
        p.dynamic           = prm.get_bool("dynamic");
        p.mass_damping      = prm.get_double("mass damping");
        p.stiffness_damping = prm.get_double("stiffness damping");
        p.bossak_alpha      = prm.get_double("Bossak alpha");
        p.dynamic_time_step = prm.get_double("time step");
        prm.leave_subsection();
        if (p.dynamic && p.model != "square membrane" && p.model != "barrier" &&
            p.model != "vibrating string" && p.model != "solid" &&
            p.model != "axial bar")
          InputFile::reject(S + "/Dynamics",
                            "dynamic",
                            "true",
                            "only models 'square membrane', 'vibrating "
                            "string', 'solid', 'axial bar' and 'barrier' run "
                            "in time so far");
        if (!p.dynamic && p.model == "vibrating string")
          InputFile::reject(S + "/Dynamics",
                            "dynamic",
                            "false",
                            "model 'vibrating string' needs 'dynamic = true'");

        prm.enter_subsection("Output");
        p.directory = prm.get("output directory");
        p.write_vtu = prm.get_bool("write vtu");
        p.test_mode = prm.get_bool("test mode");
        prm.leave_subsection();

        prm.enter_subsection("Verification");
        p.tolerance = prm.get_double("tolerance");
        p.reference_displacement =
          prm.get_double("reference largest displacement");
        p.n_levels     = prm.get_integer("number of levels");
        p.first_level  = prm.get_integer("first level");
        p.minimum_rate = prm.get_double("minimum rate");
        prm.leave_subsection();
        prm.leave_subsection();
        return p;
      }
    } // namespace


    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection(S);
      prm.declare_entry(
        "model",
        "von Mises truss",
        Patterns::Selection("von Mises truss|catenary|plane catenary|"
                            "circular membrane|"
                            "square membrane|sheared membrane|vibrating string|"
                            "sliding ring|capstan|brake|mesh file|barrier|"
                            "solid|cantilever|hanging block|axial bar|"
                            "plane solid|plane cantilever|plane axial bar|"
                            "plane hanging block|"
                            "stretched membrane|plastic bar"),
        "Structural model built from the subsections below (used with "
        "'set problem = structure'): 'von Mises truss' (two bars, apex "
        "pushed down by 'prescribed displacement'), 'catenary' (cable "
        "under self weight between two supports), 'plane catenary' (the "
        "same as a 2D string: a Triangulation<1,2> in the x-y plane, "
        "gravity 0, -g, 0), 'circular membrane' "
        "(Hencky: clamped disk under pressure), 'square membrane' "
        "(pre-stressed, clamped, small pressure), 'sheared membrane' "
        "(square in simple shear: tension field with wrinkling), "
        "'vibrating string' (pre-stressed cable of two elements, middle node "
        "released: one degree of freedom against the Bossak recurrence), "
        "'sliding ring' (ring "
        "on a frictionless cable under 'point load'), 'capstan' (a sliding "
        "cable with friction around a drum, its free end pulled by "
        "|point load|), 'brake' (brake in "
        "series with a cable, end pulled by 'prescribed displacement'), "
        "'mesh file' (a line or membrane mesh read from 'mesh file', "
        "ends or boundary fixed, gravity and pressure), 'barrier' (the standard barrier of subsection Barrier "
        "with net, posts, support cables, retaining and lateral ropes and "
        "brakes: staged form finding of the pre-stressed state, then "
        "gravity and the field load; checks the global force balance), "
        "'solid' (a continuum solid of subsection Solid with its supports, "
        "traction and gravity), 'cantilever' (the box of subsection Solid "
        "clamped at x_min, end load 'point load' (0, 0, P) as a shear "
        "traction on x_max: Timoshenko's tip deflection), 'hanging block' "
        "(the box hanging under gravity on a vertical cable of 'cable "
        "length' tied to the centre of its top face: cable force and "
        "stretch by hand), 'axial bar' (the box on its symmetry planes "
        "pulled on x_max by 'point load' (F, 0, 0) as a traction: exact "
        "uniaxial stress, or with 'dynamic' the first axial period 4 L/c), "
        "'plane solid', 'plane cantilever', 'plane axial bar', 'plane "
        "hanging block' (the same four as plane-strain solids of a 2D "
        "problem: the rectangle of the x, y coordinates of subsection Solid "
        "as a Triangulation<2,2> in the x-y plane, 'thickness' t out of "
        "plane, u_z = 0; the cantilever is loaded along y by 'point load' "
        "(0, P, 0) against the plane-strain Timoshenko beam, the block "
        "hangs on a 2D string (Triangulation<1,2>) under gravity 0, -g, 0), "
        "'stretched membrane' (square membrane, orthotropic or not, under "
        "the homogeneous biaxial stretch or uniaxial stress of 'stretch'), "
        "'plastic bar' (a straight truss of 'span' along x, fixed at x = 0, "
        "its end loaded by the x component of 'point load' along 'load "
        "path': elasto-plastic with linear hardening, loading, unloading "
        "and residual elongation in closed form). "
        "Each model with a closed "
        "form reports and checks it.");

      prm.enter_subsection("Line members");
      prm.declare_entry("element",
                        "truss",
                        Patterns::Selection("truss|cable"),
                        "Element of the bars/cables: 'truss' (tension and "
                        "compression, optional plasticity) or 'cable' "
                        "(tension only, slack in compression).");
      prm.declare_entry("Young's modulus",
                        "2e11",
                        Patterns::Double(),
                        "E of the line members [Pa], > 0.");
      prm.declare_entry("cross-section area",
                        "1e-4",
                        Patterns::Double(),
                        "A of the line members [m^2], > 0.");
      prm.declare_entry("prestress",
                        "0",
                        Patterns::Double(),
                        "PK2 pre-stress sigma_0 added to E eps [Pa].");
      prm.declare_entry("density",
                        "0",
                        Patterns::Double(),
                        "Density [kg/m^3] (weight rho A g per unstretched "
                        "length), >= 0.");
      prm.declare_entry("yield stress",
                        "0",
                        Patterns::Double(),
                        "Truss yield stress (PK2) [Pa]; 0: elastic.");
      prm.declare_entry("hardening modulus",
                        "0",
                        Patterns::Double(),
                        "Linear isotropic hardening H of the truss [Pa].");
      prm.declare_entry("elements per member",
                        "1",
                        Patterns::Integer(),
                        "Elements along each bar or cable [-], >= 1 (the "
                        "catenary: on the coarsest level, even).");
      prm.declare_entry("friction coefficient",
                        "0",
                        Patterns::Double(),
                        "Capstan friction coefficient mu of sliding cables "
                        "at their interior nodes (model 'capstan') [-], >= "
                        "0.");
      prm.declare_entry("friction law",
                        "slide",
                        Patterns::Selection("slide|stick-slip"),
                        "Capstan friction of sliding cables: 'slide' (the "
                        "cable slides towards its last node at every node, "
                        "no history) or 'stick-slip' (a node sticks while "
                        "exp(-mu theta) <= N_k/N_{k-1} <= exp(mu theta) and "
                        "slips at the limit otherwise; history: the material "
                        "length of every segment).");
      prm.declare_entry("slack stiffness ratio",
                        "1e-8",
                        Patterns::Double(),
                        "Stiffness of a slack cable or brake in the Newton "
                        "matrix only (never in the forces), as a fraction "
                        "of EA/L (brake: of k_e) [-], > 0.");
      prm.leave_subsection();

      prm.enter_subsection("Membrane");
      prm.declare_entry("Young's modulus",
                        "1e9",
                        Patterns::Double(),
                        "E (isotropic) or E1 along material axis 1 [Pa], > "
                        "0.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(),
                        "nu (isotropic) or nu12 [-], in (-1, 0.5].");
      prm.declare_entry("orthotropic",
                        "false",
                        Patterns::Bool(),
                        "Orthotropic plane-stress SVK with E2 and G12 below "
                        "(axis 1: global x projected on the surface).");
      prm.declare_entry("Young's modulus 2",
                        "1e9",
                        Patterns::Double(),
                        "E2 along material axis 2 (orthotropic) [Pa].");
      prm.declare_entry("shear modulus",
                        "4e8",
                        Patterns::Double(),
                        "G12 (orthotropic) [Pa].");
      prm.declare_entry("thickness",
                        "1e-3",
                        Patterns::Double(),
                        "Membrane thickness t [m], > 0.");
      prm.declare_entry("density",
                        "0",
                        Patterns::Double(),
                        "Density [kg/m^3], >= 0.");
      prm.declare_entry("prestress",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "In-plane PK2 pre-stress S11, S22, S12 in the "
                        "material axes [Pa].");
      prm.declare_entry("wrinkling",
                        "false",
                        Patterns::Bool(),
                        "Tension-field law: no compressive principal stress "
                        "(taut / wrinkled / slack).");
      prm.declare_entry("initial mode amplitude",
                        "0",
                        Patterns::Double(),
                        "Dynamic square membrane: initial deflection A "
                        "cos(pi x/a) cos(pi y/a) (the first mode) [m], "
                        "released from rest.");
      prm.declare_entry("shear strain",
                        "1e-4",
                        Patterns::Double(),
                        "Model 'sheared membrane': engineering shear strain "
                        "gamma imposed on the boundary (u_x = gamma (y + "
                        "a/2)) at load factor 1 [-].");
      prm.declare_entry("stretch",
                        "0.01, 0.005",
                        Patterns::List(Patterns::Double(), 2, 2),
                        "Model 'stretched membrane': engineering strains "
                        "lambda_1 - 1, lambda_2 - 1 along x and y imposed on "
                        "the boundary (u_x = e_x x, u_y = e_y y) at load "
                        "factor 1 [-]; with 'uniaxial stress' only e_x is "
                        "used.");
      prm.declare_entry("uniaxial stress",
                        "false",
                        Patterns::Bool(),
                        "Model 'stretched membrane': prescribe u_x = e_x x "
                        "on the edges x = +-a/2 only and hold u_y on the "
                        "line y = 0 (lateral edges free: uniaxial stress) "
                        "instead of the biaxial stretch of the whole "
                        "boundary.");
      prm.declare_entry("initial deflection",
                        "0",
                        Patterns::Double(),
                        "Start of Newton for the circular membrane: a "
                        "paraboloid bulge of this height [m] (a flat "
                        "unstressed membrane has no stiffness normal to "
                        "itself). It does not change the solution.");
      prm.leave_subsection();

      prm.enter_subsection("Brake");
      prm.declare_entry("stiffness",
                        "1e6",
                        Patterns::Double(),
                        "Elastic stiffness k_e [N/m], > 0.");
      prm.declare_entry("activation force",
                        "5e4",
                        Patterns::Double(),
                        "Force F_a at which the brake starts to slip [N], > "
                        "0.");
      prm.declare_entry("hardening",
                        "0",
                        Patterns::Double(),
                        "Hardening H: force rise per metre of stroke [N/m], "
                        ">= 0.");
      prm.declare_entry("stroke limit",
                        "0",
                        Patterns::Double(),
                        "Stroke s_max after which the brake blocks [m]; 0: "
                        "unlimited.");
      prm.declare_entry("length",
                        "1",
                        Patterns::Double(),
                        "Reference length of the brake element [m], > 0.");
      prm.leave_subsection();

      prm.enter_subsection("Geometry");
      prm.declare_entry("half span",
                        "1",
                        Patterns::Double(),
                        "Half the distance between the supports b (von "
                        "Mises truss, sliding ring) [m], > 0.");
      prm.declare_entry("rise",
                        "0.1",
                        Patterns::Double(),
                        "Height h of the truss apex above the supports [m], "
                        "> 0.");
      prm.declare_entry("wrap angle",
                        "180",
                        Patterns::Double(1, 720),
                        "Capstan: angle the cable is wrapped around the drum "
                        "[degrees], 1 to 720 (more than 360: helix in the "
                        "plane is not modelled, keep <= 360).");
      prm.declare_entry("drum radius",
                        "0.5",
                        Patterns::Double(),
                        "Capstan: radius of the drum (fixed nodes on a "
                        "circle in the x-z plane) [m], > 0.");
      prm.declare_entry("string amplitude",
                        "1e-3",
                        Patterns::Double(),
                        "Model 'vibrating string': initial deflection of "
                        "the middle node, released from rest [m].");
      prm.declare_entry("spring EA",
                        "0",
                        Patterns::Double(),
                        "von Mises truss: if > 0, a vertical Truss spring of "
                        "this axial stiffness E A [N] stands on the apex and "
                        "carries the load at its top (snap-back under load "
                        "control when EA/L_s < EA h^2/L0^3).");
      prm.declare_entry("spring length",
                        "1",
                        Patterns::Double(),
                        "Length L_s of that spring [m], > 0.");
      prm.declare_entry("span",
                        "10",
                        Patterns::Double(),
                        "Distance between the catenary supports l [m], > 0.");
      prm.declare_entry("unstretched length",
                        "12",
                        Patterns::Double(),
                        "Stress-free length of the catenary or ring cable "
                        "[m], > 0.");
      prm.declare_entry("radius",
                        "1",
                        Patterns::Double(),
                        "Radius a of the circular membrane [m], > 0.");
      prm.declare_entry("side",
                        "1",
                        Patterns::Double(),
                        "Side a of the square membrane [m], > 0.");
      prm.declare_entry("cable length",
                        "5",
                        Patterns::Double(),
                        "Length of the cable behind the brake [m], > 0.");
      prm.declare_entry("refinements",
                        "3",
                        Patterns::Integer(0, 10),
                        "Global refinements of the membrane meshes (level 0 "
                        "of a convergence study) [-].");
      prm.declare_entry("mesh file type",
                        "lines",
                        Patterns::Selection("lines|membrane"),
                        "What the file of model 'mesh file' holds: 'lines' "
                        "(a cable or truss, element of subsection Line "
                        "members) or 'membrane' (quadrilaterals, material of "
                        "subsection Membrane).");
      prm.declare_entry("mesh file",
                        "",
                        Patterns::Anything(),
                        "Gmsh (.msh) file of a line mesh for model 'mesh "
                        "file'.");
      prm.leave_subsection();

      prm.enter_subsection("Loads");
      prm.declare_entry("gravity",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Gravity acceleration [m/s^2], scaled by the load "
                        "factor.");
      prm.declare_entry("point load",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Load at the model's load point (the ring) [N].");
      prm.declare_entry("pressure",
                        "0",
                        Patterns::Double(),
                        "Follower pressure on the membranes, along the "
                        "normal t1 x t2 of the current surface [Pa].");
      prm.declare_entry("prescribed displacement",
                        "0",
                        Patterns::Double(),
                        "Displacement of the controlled node at load factor "
                        "1 (truss apex down, brake cable end along x) [m].");
      prm.declare_entry("load path",
                        "",
                        Patterns::List(Patterns::Double()),
                        "Load factors to visit in order (e.g. '1, 0.5, 1.5' "
                        "to load, unload, reload), each leg in 'load steps' "
                        "increments; empty: 0 to 1 [-].");
      prm.leave_subsection();

      prm.enter_subsection("Solid");
      Talus::Structure::ContinuumSolid<3>::declare_parameters(prm);
      Talus::Structure::SolidGeometry::declare_parameters(prm);
      prm.leave_subsection();

      Talus::Structure::BarrierBuilder::declare_parameters(prm);
      Talus::Structure::StaticSolver::declare_parameters(prm);
      Talus::Structure::DynamicSolver::declare_parameters(prm);

      prm.enter_subsection("Output");
      prm.declare_entry("output directory",
                        "output-structure",
                        Patterns::Anything(),
                        "Directory of the VTU files and of "
                        "load_steps.csv.");
      prm.declare_entry("write vtu",
                        "false",
                        Patterns::Bool(),
                        "Write one VTU file per mesh and load step (and a "
                        ".pvd per mesh).");
      prm.declare_entry("test mode",
                        "false",
                        Patterns::Bool(),
                        "Deterministic terminal output: no step lines.");
      prm.leave_subsection();

      prm.enter_subsection("Verification");
      prm.declare_entry("tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails (exit code 3) when a checked "
                        "quantity misses its closed form by more than this "
                        "relative error on the finest level [-].");
      prm.declare_entry("reference largest displacement",
                        "0",
                        Patterns::Double(0),
                        "Model 'mesh file': if > 0, the largest nodal "
                        "displacement is compared with this value [m].");
      prm.declare_entry("number of levels",
                        "1",
                        Patterns::Integer(1, 8),
                        "Number of meshes, each refined once more (membranes: "
                        "one global refinement, catenary: twice the "
                        "elements) [-].");
      prm.declare_entry("first level",
                        "0",
                        Patterns::Integer(0, 8),
                        "Refinement level of the first run [-].");
      prm.declare_entry("minimum rate",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the study fails when the rate of a checked "
                        "error between the last two levels is below this "
                        "[-].");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    int
    run_parameter_file(const std::string &filename)
    {
      ParameterHandler prm;
      prm.declare_entry("problem", "structure", Patterns::Anything());
      prm.declare_entry("dimension", "3", Patterns::Integer(2, 3));
      declare_parameters(prm);
      prm.parse_input(filename);
      if (prm.get_integer("dimension") != 3)
        InputFile::reject("",
                          "dimension",
                          prm.get("dimension"),
                          "the structure models are three-dimensional "
                          "(remove the entry or set it to 3)");
      const Parameters p = parse_parameters(prm);
      try
        {
          std::filesystem::create_directories(p.directory);
        }
      catch (const std::exception &)
        {
          InputFile::reject(S + "/Output",
                            "output directory",
                            p.directory,
                            "the directory cannot be created");
        }

      std::cout << "Talus: barrier structure, model '" << p.model_text
                << "': " << create_model(p)->description() << '\n';
      ConvergenceTable                 table;
      std::vector<std::vector<Result>> level_results;
      for (unsigned int level = p.first_level;
           level < p.first_level + p.n_levels;
           ++level)
        {
          auto      model = create_model(p);
          Structure structure;
          model->build(structure, level);
          structure.setup_system();
          // A part held by no support (an unconnected component) makes the
          // static stiffness singular; in a dynamic run a part with mass
          // may move freely.
          for (const auto &part : structure.parts())
            if (!(part.held[0] && part.held[1] && part.held[2]) &&
                (!p.dynamic || model->form_finding_before_dynamics() ||
                 !(part.mass > 0.)))
              {
                std::string free;
                for (unsigned int d = 0; d < 3; ++d)
                  if (!part.held[d])
                    free +=
                      std::string(free.empty() ? "" : ", ") + char('x' + d);
                const bool nothing =
                  !(part.held[0] || part.held[1] || part.held[2]);
                std::ostringstream names, msg;
                for (unsigned int k = 0; k < part.meshes.size(); ++k)
                  names << (k > 0 ? ", " : "") << part.meshes[k];
                msg << "every part of the structure must be held by "
                       "supports in x, y and z, directly or through nodes it "
                       "shares with a held part (vertices of different "
                       "meshes closer than 1e-8 of the structure size are "
                       "tied), and the part made of mesh <"
                    << names.str() << "> (" << part.n_nodes
                    << " nodes, one at (" << part.a_node[0] << ", "
                    << part.a_node[1] << ", " << part.a_node[2] << ")) is "
                    << (nothing ? "connected to nothing" :
                                  "held by no support along " + free)
                    << ": its static stiffness would be singular (it can "
                       "translate freely along "
                    << free << ")";
                const auto what = model->support_parameter();
                InputFile::reject(what[0], what[1], what[2], msg.str());
              }
          // A part held in x, y and z whose supports lie at one point or on
          // one line can still rotate about that line (a rigid-body
          // mechanism: Newton would fail on a singular matrix later).
          for (const auto &part : structure.parts())
            if (part.can_rotate && rotation_is_mechanism(p, *model, part))
              {
                std::ostringstream names, msg;
                for (unsigned int k = 0; k < part.meshes.size(); ++k)
                  names << (k > 0 ? ", " : "") << part.meshes[k];
                // Round-off of the eigenvectors: print 0 for |v| < 1e-9.
                const auto clean = [](const double v) {
                  return std::abs(v) < 1e-9 ? 0. : v;
                };
                const auto point = [&](const Tensor<1, 3> &v) {
                  std::ostringstream o;
                  o << '(' << clean(v[0]) << ", " << clean(v[1]) << ", "
                    << clean(v[2]) << ')';
                  return o.str();
                };
                msg << "the part made of mesh <" << names.str() << "> ("
                    << part.n_nodes << " nodes, one at " << point(part.a_node)
                    << ") is held in x, y and z, but ";
                if (part.held_at_one_point)
                  msg << "all its supports are at one point, "
                      << point(part.axis_point)
                      << ", so it can rotate freely about that point";
                else
                  msg << "all its supports lie on the line through "
                      << point(part.axis_point) << " along "
                      << point(part.rotation_axis)
                      << ", so it can rotate freely about that line";
                msg << " (a rigid-body mechanism: its static stiffness "
                       "would be singular). "
                    << (part.held_at_one_point ?
                          "Hold it at three or more points that are not on "
                          "one line (e.g. a face)" :
                          "Hold it also at a point off that line (e.g. a "
                          "face)");
                const auto what = model->support_parameter();
                InputFile::reject(what[0], what[1], what[2], msg.str());
              }
          Talus::Structure::StaticSolver solver(structure);
          prm.enter_subsection(S);
          solver.parse_parameters(prm);
          prm.leave_subsection();
          solver.setup();
          model->initial_guess(structure, solver.displacement);

          unsigned int n_cells = 0;
          for (const auto &m : structure.line_meshes)
            n_cells += m->triangulation.n_active_cells();
          for (const auto &m : structure.membrane_meshes)
            n_cells += m->triangulation.n_active_cells();
          structure.for_each_solid_mesh([&](const auto &m) {
            n_cells += m.triangulation.n_active_cells();
          });
          std::cout << "Level " << level << ": " << structure.line_meshes.size()
                    << " line mesh(es), " << structure.membrane_meshes.size()
                    << " membrane mesh(es), "
                    << (structure.solid_meshes.empty() ?
                          std::string() :
                          std::to_string(structure.solid_meshes.size()) +
                            " solid mesh(es), ")
                    << (structure.plane_solid_meshes.empty() ?
                          std::string() :
                          std::to_string(structure.plane_solid_meshes.size()) +
                            " plane-strain solid mesh(es), ")
                    << n_cells << " cells, " << structure.n_nodes()
                    << " nodes, " << structure.n_dofs() << " DoFs\n";

          // Load factors to visit.
          std::vector<double> path;
          {
            const std::vector<double> legs =
              p.load_path.empty() ? std::vector<double>{1.} : p.load_path;
            double from = 0.;
            for (const double target : legs)
              {
                for (unsigned int k = 1; k <= solver.load_steps; ++k)
                  path.push_back(from +
                                 (target - from) * k / solver.load_steps);
                from = target;
              }
            if (p.load_path.empty())
              {
                for (const double x : model->extra_load_factors())
                  path.push_back(x);
                std::sort(path.begin(), path.end());
              }
          }

          const std::string csv_name =
            p.directory + "/load_steps" +
            (p.n_levels > 1 ? "_level" + std::to_string(level) : "") + ".csv";
          std::ofstream csv(csv_name);
          if (!csv)
            InputFile::reject(S + "/Output",
                              "output directory",
                              p.directory,
                              "the file <" + csv_name +
                                "> cannot be written there");
          csv << std::setprecision(10);
          bool header = false;

          double     last_lambda = 0.;
          const auto run_step    = [&](const unsigned int step,
                                    const double       lambda) {
            const auto status = step == 0 ?
                                     solver.solve(lambda) :
                                     solver.solve_with_cuts(last_lambda, lambda);
            last_lambda       = lambda;
            if (!status.converged)
              {
                std::ostringstream msg;
                msg << "the load step to load factor " << lambda
                    << " did not converge: " << status.failure
                    << ". Use more 'load steps', more 'maximum Newton "
                          "iterations' or 'maximum step cuts' in subsection "
                          "Structure/Solver.";
                throw ExcSimulationFailed(msg.str());
              }
            auto values =
              model->monitor(structure, solver.displacement, lambda);
            for (const auto &c : structure_columns(structure))
              values.push_back(c);
            if (!header)
              {
                csv << "step,load_factor,newton_iterations,residual";
                for (const auto &v : values)
                  csv << ',' << v.first;
                csv << '\n';
                header = true;
              }
            csv << step << ',' << lambda << ',' << status.iterations << ','
                << status.residual;
            for (const auto &v : values)
              csv << ',' << v.second;
            csv << '\n';
            if (p.write_vtu)
              structure.write_vtu(solver.displacement,
                                  p.directory,
                                  step,
                                  lambda);
            if (!p.test_mode)
              std::cout << "  step " << std::setw(4) << step << "  load factor "
                        << std::setw(10) << lambda << "  Newton "
                        << std::setw(2) << status.iterations << "  |r| "
                        << std::scientific << std::setprecision(2)
                        << status.residual << std::defaultfloat
                        << std::setprecision(6) << '\n';
            return status;
          };

          Talus::Structure::DynamicSolver dynamics(structure, solver);
          prm.enter_subsection(S);
          dynamics.parse_parameters(prm);
          prm.leave_subsection();
          if (dynamics.enabled)
            {
              if (model->form_finding_before_dynamics())
                {
                  // Stage 1 (the pre-stress step) and the model's further
                  // stages, then the motion under the full loads.
                  const auto status = solver.solve(0.);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the pre-stress equilibrium did not converge: " +
                      status.failure);
                  std::cout << "  pre-stress equilibrium (load factor 0): "
                            << status.iterations << " Newton iterations\n";
                  model->before_load_steps(structure, solver);
                }
              dynamics.initialize();
              const auto energy = [&]() {
                return dynamics.kinetic_energy() + structure.strain_energy() +
                       structure.load_potential(solver.displacement, 1.);
              };
              model->time           = 0.;
              model->total_energy   = energy();
              model->kinetic_energy = dynamics.kinetic_energy();
              model->monitor(structure, solver.displacement, 0.);
              unsigned int       step = 0, newton = 0;
              double             t       = 0.;
              const unsigned int n_steps = static_cast<unsigned int>(
                std::max(1.,
                         std::round(dynamics.end_time / dynamics.time_step)));
              // Equal steps that end exactly at the end time.
              const double dt = dynamics.end_time / n_steps;
              while (step < n_steps)
                {
                  const auto status = dynamics.solve_step(dt);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the time step from t = " + std::to_string(t) +
                      " s did not converge: " + status.failure +
                      ". Reduce 'time step' in subsection Structure/Dynamics.");
                  dynamics.commit_step();
                  t = (step + 1) * dt;
                  ++step;
                  newton += status.iterations;
                  // Energies at the committed state.
                  dealii::Vector<double> r;
                  structure.assemble(solver.displacement, 1., r, nullptr);
                  model->time           = t;
                  model->total_energy   = energy();
                  model->kinetic_energy = dynamics.kinetic_energy();
                  auto values =
                    model->monitor(structure, solver.displacement, t);
                  for (const auto &c : structure_columns(structure))
                    values.push_back(c);
                  if (step == 1)
                    {
                      csv << "step,newton_iterations,residual";
                      for (const auto &v : values)
                        csv << ',' << v.first;
                      csv << '\n';
                    }
                  csv << step << ',' << status.iterations << ','
                      << status.residual;
                  for (const auto &v : values)
                    csv << ',' << v.second;
                  csv << '\n';
                  if (p.write_vtu)
                    structure.write_vtu(solver.displacement,
                                        p.directory,
                                        step,
                                        t);
                }
              std::cout << "  " << step << " time steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / step
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
              path.clear();
              if (model->relax_to_equilibrium())
                {
                  const double T      = dynamics.kinetic_energy();
                  const auto   status = solver.solve(1.);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the static equilibrium after the dynamic relaxation "
                      "did not converge: " +
                      status.failure + ". Run the relaxation longer.");
                  std::cout << "  static equilibrium from the relaxed state "
                               "(kinetic energy "
                            << std::setprecision(3) << std::scientific << T
                            << " J): " << status.iterations
                            << " Newton iterations\n"
                            << std::defaultfloat << std::setprecision(6);
                }
            }
          else if (model->prestress_step())
            {
              const auto status = run_step(0, 0.);
              std::cout << "  pre-stress equilibrium (load factor 0): "
                        << (status.iterations == 0 ? "already in equilibrium" :
                                                     "reached")
                        << '\n';
            }
          if (!dynamics.enabled)
            model->before_load_steps(structure, solver);
          if (!dynamics.enabled && solver.control == "arc length")
            {
              // Arc-length steps: the load factor is an unknown.
              double                 lambda = 0.;
              dealii::Vector<double> direction;
              unsigned int           newton = 0;
              for (unsigned int k = 1; k <= solver.load_steps; ++k)
                {
                  const auto status = solver.solve_arc_length(lambda,
                                                              solver.arc_length,
                                                              direction);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "arc-length step " + std::to_string(k) +
                      " did not converge: " + status.failure + ".");
                  newton += status.iterations;
                  auto values =
                    model->monitor(structure, solver.displacement, lambda);
                  for (const auto &c : structure_columns(structure))
                    values.push_back(c);
                  if (k == 1)
                    {
                      csv << "step,load_factor,newton_iterations,residual";
                      for (const auto &v : values)
                        csv << ',' << v.first;
                      csv << '\n';
                    }
                  csv << k << ',' << lambda << ',' << status.iterations << ','
                      << status.residual;
                  for (const auto &v : values)
                    csv << ',' << v.second;
                  csv << '\n';
                  if (p.write_vtu)
                    structure.write_vtu(solver.displacement,
                                        p.directory,
                                        k,
                                        lambda);
                }
              std::cout << "  " << solver.load_steps << " arc-length steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / solver.load_steps
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
            }
          else if (!dynamics.enabled)
            {
              unsigned int newton = 0;
              for (unsigned int k = 0; k < path.size(); ++k)
                newton += run_step(k + 1, path[k]).iterations;
              std::cout << "  " << path.size() << " load steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / path.size()
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
            }

          const auto results = model->results(structure, solver.displacement);
          std::cout << "  " << std::left << std::setw(44) << "quantity"
                    << std::right << std::setw(15) << "computed"
                    << std::setw(15) << "reference" << std::setw(12)
                    << "rel. error" << '\n';
          for (const auto &r : results)
            {
              std::cout << "  " << std::left << std::setw(44) << r.name
                        << std::right << std::setprecision(7) << std::setw(15)
                        << r.computed;
              if (r.checked)
                std::cout << std::setw(15) << r.reference << std::setw(12)
                          << std::setprecision(3) << std::scientific
                          << r.error() << std::defaultfloat;
              std::cout << '\n' << std::setprecision(6);
            }
          level_results.push_back(results);

          table.add_value("level", level);
          table.add_value("DoFs", structure.n_dofs());
          for (const auto &r : results)
            if (r.checked)
              {
                table.add_value(r.name, r.error());
                table.set_scientific(r.name, true);
                table.set_precision(r.name, 3);
              }
        }

      if (p.n_levels > 1)
        {
          for (const auto &r : level_results.back())
            if (r.checked)
              table.evaluate_convergence_rates(
                r.name, ConvergenceTable::reduction_rate_log2);
          std::cout << "Convergence table (relative errors; rate: log2 of "
                       "the error reduction per level):\n";
          table.write_text(
            std::cout, TableHandler::table_with_separate_column_description);
        }

      bool passed = true;
      if (p.tolerance > 0.)
        for (const auto &r : level_results.back())
          if (r.checked)
            {
              const double tolerance =
                r.tolerance > 0. ? r.tolerance : p.tolerance;
              const bool ok = r.error() <= tolerance;
              std::cout << "  check " << r.name << ": "
                        << (ok ? "ok" : "FAILED") << " (tolerance " << tolerance
                        << ")\n";
              passed = passed && ok;
            }
      if (p.n_levels > 1 && p.minimum_rate > 0.)
        {
          const auto &fine   = level_results[p.n_levels - 1];
          const auto &coarse = level_results[p.n_levels - 2];
          for (unsigned int i = 0; i < fine.size(); ++i)
            if (fine[i].checked && !fine[i].is_error)
              {
                const double rate =
                  std::log2(coarse[i].error() / fine[i].error());
                const bool ok = rate >= p.minimum_rate;
                std::cout << "  check rate of " << fine[i].name << ": "
                          << std::setprecision(3) << std::fixed << rate
                          << std::defaultfloat << std::setprecision(6)
                          << (ok ? "  ok" : "  FAILED") << " (minimum "
                          << p.minimum_rate << ")\n";
                passed = passed && ok;
              }
        }
      if (!passed)
        throw ExcVerificationFailed(
          "the structure misses its closed-form reference (see the checks "
          "above).");
      return 0;
    }
  } // namespace StructureSimulation
} // namespace Talus
