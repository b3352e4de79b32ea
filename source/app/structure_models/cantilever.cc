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
    } // namespace


    std::unique_ptr<Model>
    create_cantilever(const Parameters &p)
    {
      return std::make_unique<Cantilever>(p);
    }


  } // namespace StructureModels
} // namespace Talus
