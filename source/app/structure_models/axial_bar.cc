// Structure verification model: continuum bar under axial load (set problem =
// structure).

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
          return {{structure_section, "model", p.model_text}};
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
    } // namespace


    std::unique_ptr<Model>
    create_axial_bar(const Parameters &p)
    {
      return std::make_unique<AxialBar>(p);
    }


  } // namespace StructureModels
} // namespace Talus
