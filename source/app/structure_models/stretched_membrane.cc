// Structure verification model: orthotropic membrane stretched (set problem =
// structure).

#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/in_plane_square_membrane.h>
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
    } // namespace


    std::unique_ptr<Model>
    create_stretched_membrane(const Parameters &p)
    {
      return std::make_unique<StretchedMembrane>(p);
    }


  } // namespace StructureModels
} // namespace Talus
