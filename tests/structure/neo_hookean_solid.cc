// Element checks of ContinuumSolid with 'material law = neo-Hookean'
// (doc/verification.md, "Cantilever swinging under its own weight"), one
// cell [0,2] x [0,1] (x [0,1]), Q1 and Q2, 2D plane strain and 3D,
// E = 1e6 Pa, nu = 0.3 (the cantilever's material):
//  - rigid rotation by 90 degrees: no force;
//  - uniaxial stress, stretch lambda = 1.5 and 0.6 along x with the free
//    lateral stretch l of the closed form P_22 = mu (l - 1/l) + lambda_L
//    ln J / l = 0 (J = lambda l, 3D: lambda l^2): the end force equals
//    P_11 A0 = (mu (lambda - 1/lambda) + lambda_L ln J / lambda) A0, the
//    lateral faces carry nothing, the strain energy equals W V0 with
//    W = mu/2 (tr C - 3) - mu ln J + lambda_L/2 (ln J)^2;
//  - the tangent equals central differences of the forces;
//  - small strains: the same forces as St. Venant-Kirchhoff to first order.
// Relative differences are printed as "ok" below a bound.

#include <talus/structure/continuum_solid.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>

#include "line_element_checks.h"

using namespace dealii;
using namespace Talus::Structure;
using namespace LineElementChecks;

namespace
{
  template <int dim>
  void
  check_neo_hookean(const unsigned int degree)
  {
    out << "ContinuumSolid<" << dim << ">, neo-Hookean, FE_Q(" << degree
        << "), one cell 2 m x 1 m" << (dim == 3 ? " x 1 m" : "")
        << " (E = 1e6 Pa, nu = 0.3" << (dim == 2 ? ", plane strain" : "")
        << ")\n";
    Triangulation<dim> tria;
    Point<dim>         upper;
    for (unsigned int d = 0; d < dim; ++d)
      upper[d] = d == 0 ? 2. : 1.;
    GridGenerator::hyper_rectangle(tria, Point<dim>(), upper);
    FESystem<dim>   fe(FE_Q<dim>(degree), dim);
    DoFHandler<dim> dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    std::vector<Point<dim>> X(dof_handler.n_dofs());
    DoFTools::map_dofs_to_support_points(MappingQ1<dim>(), dof_handler, X);
    const QGauss<dim> quadrature(degree + 1);
    FEValues<dim>     fe_values(
      fe, quadrature, update_values | update_gradients | update_JxW_values);
    fe_values.reinit(dof_handler.begin_active());
    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> indices(n);
    dof_handler.begin_active()->get_dof_indices(indices);

    ContinuumSolid<dim> solid;
    solid.youngs_modulus  = 1e6;
    solid.poissons_ratio  = 0.3;
    solid.degree          = degree;
    solid.law             = ContinuumSolid<dim>::Law::neo_hookean;
    const double       mu = solid.shear_modulus(), lam = solid.lame_lambda();
    Vector<double>     r;
    FullMatrix<double> K;
    const auto         displacement =
      [&](const std::function<Tensor<1, dim>(const Point<dim> &)> &map) {
        std::vector<double> u(n);
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int c = fe.system_to_component_index(i).first;
            u[i]                 = map(X[indices[i]])[c] - X[indices[i]][c];
          }
        return u;
      };

    const auto rotation = [](const Point<dim> &p) {
      Tensor<1, dim> y;
      if constexpr (dim == 3)
        {
          const Tensor<1, 3> k(
            {1. / std::sqrt(3.), 1. / std::sqrt(3.), 1. / std::sqrt(3.)});
          y = cross_product_3d(k, p) + (k * p) * k;
        }
      else
        {
          y[0] = -p[1];
          y[1] = p[0];
        }
      return y;
    };
    solid.compute(fe_values, displacement(rotation), r, K);
    report("rigid rotation: |f| / E", r.linfty_norm() / 1e6, 1e-14);

    for (const double lambda : {1.5, 0.6})
      {
        // the lateral stretch l with P_22 = 0 (Newton)
        const unsigned int n_lateral = dim - 1;
        double             l         = 1.;
        for (unsigned int k = 0; k < 50; ++k)
          {
            const double lnJ = std::log(lambda * std::pow(l, n_lateral));
            const double f   = mu * (l - 1. / l) + lam * lnJ / l;
            const double df =
              mu * (1. + 1. / (l * l)) + lam * (n_lateral - lnJ) / (l * l);
            l -= f / df;
          }
        const double J = lambda * std::pow(l, n_lateral);
        const double P11 =
          mu * (lambda - 1. / lambda) + lam * std::log(J) / lambda;
        // tr C - 3 over all three directions (plane strain: F_33 = 1)
        const double trC =
          lambda * lambda + n_lateral * l * l + (dim == 2 ? 1. : 0.);
        const double W = 0.5 * mu * (trC - 3.) - mu * std::log(J) +
                         0.5 * lam * std::log(J) * std::log(J);
        const auto stretch = [&](const Point<dim> &p) {
          Tensor<1, dim> y = l * p;
          y[0]             = lambda * p[0];
          return y;
        };
        SolidCellOutput output;
        solid.compute(fe_values, displacement(stretch), r, K, &output);
        double F_end = 0., F_lateral = 0.;
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int c = fe.system_to_component_index(i).first;
            if (c == 0 && X[indices[i]][0] > 1.5)
              F_end += r[i];
            if (c == 1 && X[indices[i]][1] > 0.5)
              F_lateral += r[i];
          }
        out << "  uniaxial stress, lambda = " << lambda << ": lateral stretch "
            << l << ", end force " << F_end << " N (P_11 A0 = " << P11 << ")\n";
        report("  end force error",
               std::abs(F_end - P11) / std::abs(P11),
               1e-12);
        report("  lateral face force / end force",
               std::abs(F_lateral) / std::abs(P11),
               1e-12);
        report("  strain energy error",
               std::abs(output.strain_energy - 2. * W) / (2. * W),
               1e-12);
      }

    // Tangent at a general state.
    std::vector<double> u0(n);
    for (unsigned int i = 0; i < n; ++i)
      u0[i] = 0.05 * std::sin(1.7 * i + 0.3) + 0.02 * std::cos(0.4 * i);
    solid.compute(fe_values, u0, r, K);
    FullMatrix<double> K_fd(n, n);
    const double       h = 1e-7;
    for (unsigned int j = 0; j < n; ++j)
      {
        auto up = u0, um = u0;
        up[j] += h;
        um[j] -= h;
        Vector<double>     rp, rm;
        FullMatrix<double> dummy;
        solid.compute(fe_values, up, rp, dummy);
        solid.compute(fe_values, um, rm, dummy);
        for (unsigned int i = 0; i < n; ++i)
          K_fd(i, j) = (rp[i] - rm[i]) / (2. * h);
      }
    report("tangent vs central differences",
           relative_difference(K, K_fd),
           1e-6);

    // Small strains: St. Venant-Kirchhoff to first order.
    std::vector<double> u_small(n);
    for (unsigned int i = 0; i < n; ++i)
      u_small[i] = 1e-6 * std::sin(1.7 * i + 0.3);
    Vector<double>      r_svk;
    ContinuumSolid<dim> svk = solid;
    svk.law                 = ContinuumSolid<dim>::Law::saint_venant_kirchhoff;
    solid.compute(fe_values, u_small, r, K);
    svk.compute(fe_values, u_small, r_svk, K);
    Vector<double> diff = r;
    diff -= r_svk;
    report("strain 1e-6: |f - f_SVK| / |f_SVK|",
           diff.l2_norm() / r_svk.l2_norm(),
           1e-5);
  }
} // namespace


int
main()
{
  out << std::setprecision(8);
  check_neo_hookean<2>(1);
  check_neo_hookean<2>(2);
  check_neo_hookean<3>(1);
  check_neo_hookean<3>(2);
  return 0;
}
