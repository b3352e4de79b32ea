// Structure verification model: midspan cable (set problem = structure).

#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/structure/axial_law.h>

#include <cmath>
#include <memory>

namespace Talus
{
  namespace StructureModels
  {
    namespace
    {
      using namespace dealii;

      // ------------------------------------------------------------------
      /**
       * A straight cable (or truss) of 'span' S between two anchors
       * (-S/2, 0, 0) and (S/2, 0, 0), its middle node loaded by 'point
       * load' (0, 0, -P), 'elements per member' elements per half, started
       * straight (u = 0; with zero pre-stress the cable is taut at zero
       * force there). Each half has the reference length b = S/2 and the
       * pre-stress sigma_0 (unstretched length b/(1 + sigma_0/E) with the
       * engineering law: l0 = S/2 for sigma_0 = 0). The two halves form a
       * two-bar truss: sag w, half length l = sqrt(b^2 + w^2),
       *   2 N(l/b) w/l = P,
       * N the axial law of 'strain measure' (AxialLaw: engineering N = EA
       * (l - l0)/l0, or Green-Lagrange), solved for w by bisection. Checks
       * the sag, the tension of every element and the strain energy 2 b
       * W(l/b) (W per reference length, AxialLaw::energy()), and the sag
       * against 'reference largest displacement' if > 0 (a value computed
       * independently); reports the sag of the other law (not checked).
       */
      class MidspanCable : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "cable between two anchors, point load at midspan (" +
                 Talus::Structure::to_string(p.strain_measure) + " law)";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          const double b = 0.5 * p.span;
          make_line(s.add_line_mesh("cable", line_element()).triangulation,
                    Point<3>(-b, 0, 0),
                    Point<3>(b, 0, 0),
                    2 * p.elements);
          s.setup_dofs();
          middle = node_at(s, Point<3>(0, 0, 0));
          for (const double x : {-b, b})
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(node_at(s, Point<3>(x, 0, 0)), c);
          // The cable stays in the x-z plane.
          for (unsigned int n = 0; n < s.n_nodes(); ++n)
            s.prescribe(n, 1);
          s.add_point_load(middle, p.point_load);
        }

        /** Sag of the two-bar truss with the law @p law [m]. */
        double
        sag(const Talus::Structure::AxialLaw &law) const
        {
          const double b = 0.5 * p.span, P = -p.point_load[2];
          const auto   balance = [&](const double w) {
            const double l = std::sqrt(b * b + w * w);
            return 2. * std::max(0., law.force(l / b)) * w / l - P;
          };
          double hi = b;
          while (balance(hi) < 0.)
            hi *= 2.;
          return bisect(balance, 0., hi);
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          using Talus::Structure::StrainMeasure;
          const double               b = 0.5 * p.span;
          Talus::Structure::AxialLaw law{p.strain_measure,
                                         p.E,
                                         p.A,
                                         p.prestress};
          const double               w     = sag(law);
          const double               l     = std::sqrt(b * b + w * w);
          const double               N_ref = law.force(l / b);
          const double               W_ref = 2. * b * law.energy(l / b);
          Talus::Structure::AxialLaw other = law;
          other.measure = p.strain_measure == StrainMeasure::engineering ?
                            StrainMeasure::green_lagrange :
                            StrainMeasure::engineering;
          const double w_other = sag(other);
          const double w_h     = -s.node_displacement(u, middle)[2];
          double       N_max = 0., N_min = 1e300;
          for (const double N : s.line_meshes[0]->force)
            {
              N_max = std::max(N_max, N);
              N_min = std::min(N_min, N);
            }
          std::vector<Result> r = {
            {"sag w [m]", w_h, w},
            {"cable tension N (largest) [N]", N_max, N_ref},
            {"cable tension N (smallest) [N]", N_min, N_ref},
            {"strain (l - b)/b of a half [-]", l / b - 1., 0., false},
            {"strain energy [J]", s.strain_energy(), W_ref},
            {"sag with the " + Talus::Structure::to_string(other.measure) +
               " law [m]",
             w_other,
             0.,
             false},
            {"sag difference of the laws / sag [-]",
             (w_other - w) / w,
             0.,
             false}};
          // The sag of an independent computation (the file's comment).
          if (p.reference_displacement > 0.)
            r.push_back({"sag w vs 'reference largest displacement' [m]",
                         w_h,
                         p.reference_displacement});
          return r;
        }

      private:
        unsigned int middle = 0;
      };
    } // namespace


    std::unique_ptr<Model>
    create_midspan_cable(const Parameters &p)
    {
      return std::make_unique<MidspanCable>(p);
    }
  } // namespace StructureModels
} // namespace Talus
