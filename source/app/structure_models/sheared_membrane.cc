// Structure verification model: membrane in simple shear (set problem =
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
    } // namespace


    std::unique_ptr<Model>
    create_sheared_membrane(const Parameters &p)
    {
      return std::make_unique<ShearedMembrane>(p);
    }


  } // namespace StructureModels
} // namespace Talus
