// Patch checks of the barrier structure elements (doc/verification.md,
// "Barrier structures"; VERIFICATION.md 3):
//  - Truss, Cable: rigid rotation by 90 degrees gives no force; uniaxial
//    stretch lambda gives N = EA lambda (lambda^2 - 1)/2; tangent equals
//    central differences of the forces (also elasto-plastic, prestressed,
//    and the lateral stiffness A S/L of a straight prestressed cable); a
//    compressed cable carries nothing
//  - Brake: plateau at F_a + H s, unloading along k_e, slack, stroke limit,
//    dissipated energy F_a s + H s^2/2, tangent
//  - SlidingCable: uniform tension at every node, tangent; stick-slip law
//    (capstan friction with history): a node sticks below the capstan
//    ratio and slips at it, material conserved; the analytic tangent of
//    the capstan laws (sliding, and stick-slip with nodes sticking,
//    slipping forward and backward) equals central differences
//  - Membrane: rigid rotation, uniaxial strain with lateral constraint
//    (edge force t W lambda S11), tangent with pre-stress and follower
//    pressure, wrinkled state (no compressive principal stress; tangent);
//    the orthotropic, pre-stressed wrinkling law: uniaxial relaxed stress,
//    consistent tangent, continuity across taut / wrinkled / slack
//  - ContinuumSolid (St. Venant-Kirchhoff, one cell, Q1 and Q2, 3D and
//    2D plane strain): rigid rotation, uniaxial stress (face force
//    E A lambda (lambda^2 - 1)/2 with free lateral faces), tangent
// Relative differences are printed rounded (or as "ok" below a bound).

#include <talus/structure/continuum_solid.h>
#include <talus/structure/line_elements.h>
#include <talus/structure/membrane.h>
#include <talus/structure/sliding_cable.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "line_element_checks.h"

using namespace dealii;
using namespace Talus::Structure;
using namespace LineElementChecks;

namespace
{
  void
  check_two_node(const LineElement &element, const double EA)
  {
    const Tensor<1, 3> X0({0.2, -0.1, 0.3}), X1({1.4, 0.5, -0.2});
    const double       L = (X1 - X0).norm();
    LineState          state;
    LineResponse       r;

    // Rigid rotation by 90 degrees about z, plus a translation.
    const auto rotate = [](const Tensor<1, 3> &a) {
      return Tensor<1, 3>({-a[1] + 3., a[0] - 1., a[2] + 2.});
    };
    element.compute(X0, X1, rotate(X0), rotate(X1), state, r);
    report("rigid rotation: |f| / (EA)", r.f.linfty_norm() / EA, 1e-14);

    // Uniaxial stretch lambda = 1.2 along the element.
    const double lambda = 1.2;
    element.compute(X0, X1, X0, X0 + lambda * (X1 - X0), state, r);
    const double N_exact = EA * lambda * (lambda * lambda - 1.) / 2.;
    out << "  stretch 1.2: N / (EA) = " << std::setprecision(8) << r.force / EA
        << " (exact " << N_exact / EA << ")\n";
    report("stretch 1.2: |N - N_exact| / N_exact",
           std::abs(r.force - N_exact) / N_exact,
           1e-13);
    // Tangent in a general configuration.
    const Tensor<1, 3> x0({0.25, -0.05, 0.31}), x1({1.5, 0.7, -0.1});
    report("tangent vs central differences (stretched, rotated)",
           line_tangent_error(element, X0, X1, x0, x1, state),
           1e-6);
    (void)L;
  }
} // namespace


namespace
{
  /**
   * One cell [0,2] x [0,1] (x [0,1]) of ContinuumSolid<dim> with FE_Q(degree):
   * rigid rotation, uniaxial stress along x, tangent vs central differences.
   */
  template <int dim>
  void
  check_solid(const unsigned int degree)
  {
    out << "ContinuumSolid<" << dim << ">, FE_Q(" << degree
        << "), one cell 2 m x 1 m" << (dim == 3 ? " x 1 m" : "")
        << " (E = 2e11 Pa, nu = 0.3" << (dim == 2 ? ", plane strain" : "")
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
    solid.youngs_modulus = 2e11;
    solid.poissons_ratio = 0.3;
    solid.degree         = degree;
    const double       E = solid.youngs_modulus, nu = solid.poissons_ratio;
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

    // Rigid rotation by 90 degrees (3D: about (1,1,1)/sqrt(3)).
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
    report("rigid rotation: |f| / (E A)", r.linfty_norm() / E, 1e-14);

    // Uniaxial stress: stretch lambda along x, lateral stretch with
    // S22 (= S33) = 0: E22 = -nu' E11 (3D nu' = nu, plane strain
    // nu' = nu/(1-nu)), S11 = E' E11 (E' = E, plane strain E/(1-nu^2)).
    const double lambda         = 1.2;
    const double E11            = (lambda * lambda - 1.) / 2.;
    const double nu_            = dim == 3 ? nu : nu / (1. - nu);
    const double E_             = dim == 3 ? E : E / (1. - nu * nu);
    const double lambda_lateral = std::sqrt(1. - 2. * nu_ * E11);
    const auto   stretch        = [&](const Point<dim> &p) {
      Tensor<1, dim> y = lambda_lateral * p;
      y[0]             = lambda * p[0];
      return y;
    };
    solid.compute(fe_values, displacement(stretch), r, K);
    double F_end = 0., F_lateral = 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int c = fe.system_to_component_index(i).first;
        if (c == 0 && X[indices[i]][0] > 1.5)
          F_end += r[i];
        if (c == 1 && X[indices[i]][1] > 0.5)
          F_lateral += r[i];
      }
    const double F_exact = E_ * lambda * E11; // A0 = 1 m^2 (2D: per m)
    out << "  uniaxial stress, lambda = 1.2: end force = " << F_end
        << " N (E' A lambda (lambda^2 - 1)/2 = " << F_exact << ")\n";
    report("uniaxial stress: end force error",
           std::abs(F_end - F_exact) / F_exact,
           1e-12);
    report("uniaxial stress: lateral face force / end force",
           std::abs(F_lateral) / F_exact,
           1e-12);

    // Rotated stretch: the end force rotates with the body (objectivity).
    const auto rotated_stretch = [&](const Point<dim> &p) {
      const Tensor<1, dim> y = stretch(p);
      return rotation(Point<dim>(y));
    };
    solid.compute(fe_values, displacement(rotated_stretch), r, K);
    Tensor<1, dim> F_rot;
    for (unsigned int i = 0; i < n; ++i)
      if (X[indices[i]][0] > 1.5)
        F_rot[fe.system_to_component_index(i).first] += r[i];
    Tensor<1, dim> e1;
    e1[0] = 1.;
    report("rotated stretch: |end force - R (F e1)| / F",
           (F_rot - F_exact * rotation(Point<dim>(e1))).norm() / F_exact,
           1e-12);

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
    // Energy: int W dV0 for the uniaxial stress state = E' E11^2/2 V.
    SolidCellOutput output;
    solid.compute(fe_values, displacement(stretch), r, K, &output);
    report("uniaxial stress: strain energy error",
           std::abs(output.strain_energy - 0.5 * E_ * E11 * E11 * 2.) /
             (0.5 * E_ * E11 * E11 * 2.),
           1e-12);
  }
} // namespace


int
main()
{
  out << std::setprecision(8);

  // ---------------------------------------------------------------- Truss
  {
    out << "Truss (E = 2e11 Pa, A = 1e-4 m^2)\n";
    Truss truss;
    truss.youngs_modulus = 2e11;
    truss.area           = 1e-4;
    check_two_node(truss, 2e7);

    out << "Truss with prestress 1e8 Pa\n";
    truss.prestress = 1e8;
    const Tensor<1, 3> X0({0, 0, 0}), X1({2, 0, 0});
    LineResponse       r;
    truss.compute(X0, X1, X0, X1, LineState(), r);
    out << "  unstretched: N = " << r.force << " N (A sigma_0 = 10000)\n";
    report("straight prestressed truss: tangent vs central differences",
           line_tangent_error(truss, X0, X1, X0, X1, LineState()),
           1e-6);
    out << "  lateral stiffness K(yy) = " << r.K(1, 1)
        << " N/m (A sigma_0 / L = 5000)\n";

    out << "Elasto-plastic truss (sigma_y = 2.5e8 Pa, H = 2e9 Pa)\n";
    truss.prestress    = 0.;
    truss.yield_stress = 2.5e8;
    truss.hardening    = 2e9;
    // Green-Lagrange strain 0.01: S_trial = 2e9 > sigma_y.
    const double lambda = std::sqrt(1.02);
    truss.compute(X0, X1, X0, lambda * X1, LineState(), r);
    const double dgamma = (2e9 - 2.5e8) / (2e11 + 2e9);
    const double S      = 2e9 - 2e11 * dgamma;
    out << "  eps = 0.01: S = " << r.force / (1e-4 * lambda) << " Pa (exact "
        << S << "), plastic strain " << r.state.plastic << " (exact " << dgamma
        << ")\n";
    report("plastic: tangent vs central differences",
           line_tangent_error(truss, X0, X1, X0, lambda * X1, LineState()),
           1e-6);
    // Unloading to eps = 0.009 is elastic: S = E (0.009 - eps_p).
    LineResponse r2;
    truss.compute(X0, X1, X0, std::sqrt(1.018) * X1, r.state, r2);
    out << "  unloaded to eps = 0.009: S = "
        << r2.force / (1e-4 * std::sqrt(1.018)) << " Pa (exact "
        << 2e11 * (0.009 - dgamma) << ")\n";
    // Back to l = L: reverse yielding in compression,
    // S = S_trial + E dgamma2, dgamma2 = (|S_trial| - sigma_y - H alpha)/(E+H).
    truss.compute(X0, X1, X0, X1, r.state, r2);
    const double S_trial = -2e11 * dgamma;
    const double dgamma2 = (-S_trial - 2.5e8 - 2e9 * dgamma) / (2e11 + 2e9);
    out << "  back to l = L: S = " << r2.force / 1e-4
        << " Pa (exact, reverse yielding: " << S_trial + 2e11 * dgamma2
        << ")\n";
    report("reverse yielding: tangent vs central differences",
           line_tangent_error(truss, X0, X1, X0, X1, r.state),
           1e-6);
  }

  // ---------------------------------------------------------------- Cable
  {
    out << "Cable (E = 1e11 Pa, A = 2e-4 m^2)\n";
    Cable cable;
    cable.youngs_modulus = 1e11;
    cable.area           = 2e-4;
    check_two_node(cable, 2e7);
    const Tensor<1, 3> X0({0, 0, 0}), X1({2, 0, 0});
    LineResponse       r;
    cable.compute(X0, X1, X0, 0.9 * X1, LineState(), r);
    out << "  compressed (l = 0.9 L): N = " << r.force
        << ", |f| = " << r.f.linfty_norm() << ", slack = " << r.slack
        << ", K(0,0) / (EA/L) = " << r.K(0, 0) / (1e11 * 2e-4 / 2.)
        << " (regularisation only)\n";
    cable.prestress = 5e7;
    cable.compute(X0, X1, X0, X1, LineState(), r);
    out << "  prestressed 5e7 Pa, straight: N = " << r.force
        << " N, lateral stiffness K(yy) = " << r.K(1, 1)
        << " N/m (A S / L = 5000)\n";
    report("straight prestressed cable: tangent vs central differences",
           line_tangent_error(cable, X0, X1, X0, X1, LineState()),
           1e-6);
    cable.compute(X0, X1, X0, 0.9999 * X1, LineState(), r);
    out << "  prestressed, shortened by 1e-4 L: N = " << r.force
        << " N (A (E eps + sigma_0) l/L = "
        << 2e-4 * (1e11 * (0.9999 * 0.9999 - 1.) / 2. + 5e7) * 0.9999 << ")\n";
  }

  // ---------------------------------------------------------------- Brake
  {
    out << "Brake (k_e = 1e6 N/m, F_a = 5e4 N, H = 1e4 N/m, s_max = 1 m)\n";
    Brake brake;
    brake.stiffness        = 1e6;
    brake.activation_force = 5e4;
    brake.hardening        = 1e4;
    brake.stroke_limit     = 1.;
    const Tensor<1, 3> X0({0, 0, 0}), X1({1, 0, 0});
    LineState          state;
    LineResponse       r;
    double             max_D_error = 0.;
    out << "  elongation [m]  N [N]  stroke [m]  dissipated [J]\n";
    const std::vector<double> path = {
      0.02, 0.05, 0.1, 0.3, 0.6, 0.59, 0.55, 0.2, 0.8, 1.3, 0.5};
    for (const double d : path)
      {
        brake.compute(X0, X1, X0, (1. + d) * X1, state, r);
        state             = r.state;
        const double s    = state.plastic;
        const double D_ex = 5e4 * s + 0.5 * 1e4 * s * s;
        max_D_error =
          std::max(max_D_error,
                   std::abs(state.accumulated - D_ex) / std::max(D_ex, 1.));
        out << "  " << d << "  " << r.force << "  " << s << "  "
            << state.accumulated << (r.slack ? "  slack" : "") << '\n';
      }
    report("dissipated energy = F_a s + H s^2/2", max_D_error, 1e-12);
    LineState plastic;
    plastic.plastic = 0.2;
    report("tangent on the plateau",
           line_tangent_error(
             brake, X0, X1, X0 + Tensor<1, 3>({0, 0.01, 0}), 1.3 * X1, plastic),
           1e-6);
  }

  // -------------------------------------------------------- Sliding cable
  {
    out << "Sliding cable through 5 nodes (E = 1e11 Pa, A = 1e-4 m^2)\n";
    SlidingCable cable;
    cable.youngs_modulus              = 1e11;
    cable.area                        = 1e-4;
    cable.prestress                   = 1e7;
    const std::vector<Tensor<1, 3>> X = {Tensor<1, 3>({0, 0, 0}),
                                         Tensor<1, 3>({1, 0, 0}),
                                         Tensor<1, 3>({2, 0, 0}),
                                         Tensor<1, 3>({3, 0, 0}),
                                         Tensor<1, 3>({4, 0, 0})};
    std::vector<Tensor<1, 3>>       x = {Tensor<1, 3>({0, 0, 0}),
                                         Tensor<1, 3>({0.7, -0.4, 0.1}),
                                         Tensor<1, 3>({2.1, -0.6, 0}),
                                         Tensor<1, 3>({3.2, -0.2, -0.1}),
                                         Tensor<1, 3>({4.01, 0, 0})};
    Vector<double>                  f;
    FullMatrix<double>              K;
    const double                    N = cable.compute(X, x, f, K);
    double                          l = 0.;
    for (unsigned int i = 0; i + 1 < 5; ++i)
      l += (x[i + 1] - x[i]).norm();
    const double N_exact = 1e-4 * (1e11 * (l * l - 16.) / 32. + 1e7) * l / 4.;
    report("uniform tension N = A (E eps + sigma_0) l/L",
           std::abs(N - N_exact) / N_exact,
           1e-13);
    // Each interior node: N (e_{k-1} - e_k); |f| at the ends = N.
    const double end_force = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    report("end node force |f_0| = N", std::abs(end_force - N) / N, 1e-13);
    // Sum of all forces = N (e_last - e_first): a free body check.
    report("tangent vs central differences",
           relative_difference(K, sliding_cable_fd_tangent(cable, X, x, 1e-6)),
           1e-6);
  }

  // ---------------------------------------- Sliding cable, stick-slip law
  {
    out << "Sliding cable with stick-slip friction (mu = 0.2; 3 segments of "
           "1 m, 90 degree bend at node 1, straight at node 2, N_0 = A "
           "sigma_0 = 1000 N)\n";
    SlidingCable cable;
    cable.youngs_modulus                        = 1e11;
    cable.area                                  = 1e-4;
    cable.prestress                             = 1e7;
    cable.friction_coefficient                  = 0.2;
    cable.stick_slip                            = true;
    const std::vector<Tensor<1, 3>> X           = {Tensor<1, 3>({0, 0, 0}),
                                                   Tensor<1, 3>({1, 0, 0}),
                                                   Tensor<1, 3>({1, 1, 0}),
                                                   Tensor<1, 3>({1, 2, 0})};
    const std::vector<double>       old_lengths = {1., 1., 1.};
    const double                    ratio = std::exp(0.2 * numbers::PI / 2.);
    for (const double delta : {1e-5, 1e-3})
      {
        auto x = X;
        x[3][1] += delta; // pull the end along the cable
        Vector<double>      f;
        FullMatrix<double>  K;
        std::vector<double> L;
        cable.compute(X, x, old_lengths, f, K, L);
        const auto  &N     = cable.segment_forces;
        const double total = L[0] + L[1] + L[2];
        out << "  end pulled by " << delta << " m: N = " << std::setprecision(8)
            << N[0] << ", " << N[1] << ", " << N[2]
            << " N; N_1/N_0 = " << N[1] / N[0] << " (limit " << ratio << ")\n";
        report("  material conserved: |sum L_i - 3| / 3",
               std::abs(total - 3.) / 3.,
               1e-14);
        report("  node 2 (no bend) slips: |N_2 - N_1| / N_1",
               std::abs(N[2] - N[1]) / N[1],
               1e-12);
        if (delta < 1e-4) // N_1/N_0 = 1.05 < exp(mu theta)
          {
            // Stick at node 1: segment 0 keeps its material and tension.
            report("  node 1 sticks: |L_0 - 1|", std::abs(L[0] - 1.), 1e-15);
            report("  node 1 sticks: |N_0 - A sigma_0| / (A sigma_0)",
                   std::abs(N[0] - 1000.) / 1000.,
                   1e-12);
          }
        else
          report("  node 1 slips at the capstan limit: |N_1/N_0 - "
                 "exp(mu theta)|",
                 std::abs(N[1] / N[0] - ratio),
                 1e-11); // round-off of L_i times EA/N ~ 3e3
      }
  }

  // ------------------------ Sliding cable with friction: analytic tangent
  {
    out << "Capstan friction, tangent vs central differences (mu = 0.3; 3 "
           "segments of 1 m, bends of 60 and 30 degrees, E A = 1e5 N)\n";
    SlidingCable cable;
    cable.youngs_modulus       = 1e9;
    cable.area                 = 1e-4;
    cable.friction_coefficient = 0.3;
    const double c = std::cos(numbers::PI / 3.), s = std::sin(numbers::PI / 3.);
    const std::vector<Tensor<1, 3>> X = {Tensor<1, 3>({0, 0, 0}),
                                         Tensor<1, 3>({1, 0, 0}),
                                         Tensor<1, 3>({1 + c, s, 0}),
                                         Tensor<1, 3>({1 + c, s + 1, 0})};
    // Material 1e-4 shorter than each segment: N about 10 N.
    const std::vector<double> old_lengths = {1. - 1e-4, 1. - 1e-4, 1. - 1e-4};
    const auto fd_tangent = [&](const std::vector<Tensor<1, 3>> &x,
                                const bool                       with_history) {
      return sliding_cable_fd_tangent(
        cable, X, x, 1e-6, with_history ? &old_lengths : nullptr);
    };
    // h = 1e-6 m: the bisection of the return map leaves ~1e-15 relative
    // noise in the tensions, which smaller steps amplify (h = 1e-8 gives
    // differences of 1e-8 .. 7e-8); measured with h = 1e-6: 7e-11 .. 6e-10.
    // State of interior node k from the tension ratio.
    const auto state = [&](const std::vector<double>       &N,
                           const std::vector<Tensor<1, 3>> &x,
                           const unsigned int               k) {
      const Tensor<1, 3> a = x[k] - x[k - 1], b = x[k + 1] - x[k];
      const double       limit =
        std::exp(0.3 * std::acos(a * b / (a.norm() * b.norm())));
      if (std::abs(N[k] / N[k - 1] - limit) < 1e-9 * limit)
        return "slips forward";
      if (std::abs(N[k - 1] / N[k] - limit) < 1e-9 * limit)
        return "slips backward";
      return "sticks";
    };
    struct Case
    {
      const char  *name;
      unsigned int node;
      Tensor<1, 3> move;
    };
    const std::vector<Case> cases = {
      {"end pulled by 1e-6 m", 3, Tensor<1, 3>({0.2e-6, 1e-6, 0.1e-6})},
      {"end pulled by 3e-5 m", 3, Tensor<1, 3>({0.2e-5, 3e-5, 1e-6})},
      {"end pulled by 1e-3 m", 3, Tensor<1, 3>({1e-4, 1e-3, 1e-4})},
      {"start pulled back by 5e-5 m", 0, Tensor<1, 3>({-5e-5, 1e-6, 1e-6})},
      {"start pulled back by 1e-3 m", 0, Tensor<1, 3>({-1e-3, 1e-4, -1e-4})}};
    for (const Case &test : cases)
      {
        auto x = X;
        x[test.node] += test.move;
        Vector<double>      f;
        FullMatrix<double>  K;
        std::vector<double> L;
        cable.stick_slip = true;
        cable.compute(X, x, old_lengths, f, K, L);
        const std::vector<double> N = cable.segment_forces;
        out << "  stick-slip, " << test.name << ": node 1 " << state(N, x, 1)
            << ", node 2 " << state(N, x, 2) << "\n";
        report("    tangent vs central differences",
               relative_difference(K, fd_tangent(x, true)),
               1e-8);
        cable.stick_slip = false;
        cable.compute(X, x, f, K);
        report("    sliding law: tangent vs central differences",
               relative_difference(K, fd_tangent(x, false)),
               1e-8);
      }
  }

  // -------------------------------------------------------------- Membrane
  {
    out << "Membrane: one Q1 cell, 2 m x 1 m, in an inclined plane\n";
    // Reference cell: corners of a 2 x 1 rectangle rotated about x by 30 deg.
    const double             c = std::cos(M_PI / 6.), s = std::sin(M_PI / 6.);
    const Tensor<1, 3>       a({1., 0., 0.}), b({0., c, s});
    std::vector<Point<3>>    vertices = {Point<3>(),
                                         Point<3>(2. * a),
                                         Point<3>(b),
                                         Point<3>(2. * a + b)};
    std::vector<CellData<2>> cells(1);
    cells[0].vertices = {0, 1, 2, 3};
    Triangulation<2, 3> tria;
    tria.create_triangulation(vertices, cells, SubCellData());
    FESystem<2, 3>   fe(FE_Q<2, 3>(1), 3);
    DoFHandler<2, 3> dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    QGauss<2>      quadrature(2);
    FEValues<2, 3> fe_values(fe,
                             quadrature,
                             update_values | update_gradients |
                               update_jacobians | update_JxW_values);
    fe_values.reinit(dof_handler.begin_active());
    const unsigned int n = fe.n_dofs_per_cell();
    // Reference position of each dof's node.
    std::vector<Point<3>> X(n);
    for (unsigned int i = 0; i < n; ++i)
      X[i] = dof_handler.begin_active()->vertex(
        i / 3); // FESystem(FE_Q(1),3): vertex by vertex
    for (unsigned int i = 0; i < n; ++i)
      if (fe.system_to_component_index(i).first != i % 3)
        out << "unexpected dof order\n";

    Membrane membrane;
    membrane.material.thickness = 1e-3;
    membrane.material.set_isotropic(1e9, 0.3);
    membrane.fibre_direction = a;
    Vector<double>     r;
    FullMatrix<double> K;
    const auto         displacement =
      [&](const std::function<Tensor<1, 3>(const Point<3> &)> &map) {
        std::vector<double> u(n);
        for (unsigned int i = 0; i < n; ++i)
          u[i] = map(X[i])[i % 3] - X[i][i % 3];
        return u;
      };

    // Rigid rotation by 90 degrees about the axis (1,1,1)/sqrt(3).
    const auto rotation = [](const Point<3> &p) {
      const Tensor<1, 3> k(
        {1. / std::sqrt(3.), 1. / std::sqrt(3.), 1. / std::sqrt(3.)});
      // Rodrigues, 90 degrees: p' = (k x p) + k (k.p)
      return Tensor<1, 3>(cross_product_3d(k, p) + (k * p) * k);
    };
    membrane.compute(fe_values, displacement(rotation), 0., r, K);
    report("rigid rotation: |f| / (E t)", r.linfty_norm() / 1e6, 1e-14);

    // Uniaxial stretch lambda along a, no lateral strain.
    const double lambda  = 1.1;
    const auto   stretch = [&](const Point<3> &p) {
      return Tensor<1, 3>(p + (lambda - 1.) * (p * a) * a);
    };
    membrane.compute(fe_values, displacement(stretch), 0., r, K);
    double F_edge = 0.;
    for (unsigned int i = 0; i < n; ++i)
      if (X[i] * a > 1.5)
        F_edge += r[i] * a[i % 3];
    const double S11 = 1e9 / (1. - 0.09) * (lambda * lambda - 1.) / 2.;
    out << "  uniaxial strain 1.1: edge force = " << F_edge
        << " N (t W lambda S11 = " << 1e-3 * 1. * lambda * S11 << ")\n";
    report("uniaxial strain: edge force error",
           std::abs(F_edge - 1e-3 * lambda * S11) / (1e-3 * lambda * S11),
           1e-12);

    // Tangent with pre-stress, orthotropy and follower pressure.
    membrane.material.youngs_modulus_2 = 4e8;
    membrane.material.shear_modulus    = 1e8;
    membrane.material.prestress        = Tensor<1, 3>({2e6, 1e6, 3e5});
    membrane.pressure                  = 5e4;
    const std::vector<double> u0       = {
            0.01, -0.02, 0.03, 0.05, 0.01, -0.02, -0.03, 0.02, 0.1, 0.02, 0.04, 0.07};
    const auto fd_error = [&](const std::vector<double> &u) {
      membrane.compute(fe_values, u, 1., r, K);
      FullMatrix<double> K_fd(n, n);
      const double       h = 1e-7;
      for (unsigned int j = 0; j < n; ++j)
        {
          auto up = u, um = u;
          up[j] += h;
          um[j] -= h;
          Vector<double>     rp, rm;
          FullMatrix<double> dummy;
          membrane.compute(fe_values, up, 1., rp, dummy);
          membrane.compute(fe_values, um, 1., rm, dummy);
          for (unsigned int i = 0; i < n; ++i)
            K_fd(i, j) = (rp[i] - rm[i]) / (2. * h);
        }
      return relative_difference(K, K_fd);
    };
    report("orthotropic, pre-stress, follower pressure: tangent vs central "
           "differences",
           fd_error(u0),
           1e-6);

    // Wrinkling: compress along a by 5 %, stretch across by 2 %.
    membrane.material.set_isotropic(1e9, 0.3);
    membrane.material.prestress = Tensor<1, 3>();
    membrane.material.wrinkling = true;
    membrane.pressure           = 0.;
    const auto wrinkle          = [&](const Point<3> &p) {
      return Tensor<1, 3>(p - 0.05 * (p * a) * a + 0.02 * (p * b) * b +
                          0.01 * (p * b) * a);
    };
    MembraneCellOutput output;
    membrane.compute(fe_values, displacement(wrinkle), 0., r, K, &output);
    out << "  wrinkled: " << output.n_wrinkled
        << " of 4 points wrinkled, min principal stress / max = "
        << (std::abs(output.min_principal) < 1e-6 * output.max_principal ?
              0. :
              output.min_principal / output.max_principal)
        << '\n';
    report("wrinkled: tangent vs central differences",
           fd_error(displacement(wrinkle)),
           1e-5);
    const auto slack = [&](const Point<3> &p) {
      return Tensor<1, 3>(p - 0.05 * (p * a) * a - 0.01 * (p * b) * b);
    };
    membrane.compute(fe_values, displacement(slack), 0., r, K, &output);
    out << "  biaxial compression: " << output.n_slack
        << " of 4 points slack, |f| = " << r.linfty_norm() << '\n';

    // Orthotropic, pre-stressed wrinkling law (the flagship's net: E1 = E2
    // = 1 GPa, G12 = 0.1 GPa, nu = 0, S_0 = 1 MPa biaxial). Over a grid of
    // strains in [-1e-2, 1e-2]^3: the relaxed stress of a wrinkled point
    // is uniaxial (no compressive principal stress); its tangent equals
    // central differences of the stress; along straight strain paths the
    // stress is continuous across taut / wrinkled / slack (largest jump
    // per step against |C| |dE|).
    {
      MembraneMaterial m;
      m.youngs_modulus_1             = 1e9;
      m.youngs_modulus_2             = 1e9;
      m.shear_modulus                = 1e8;
      m.poissons_ratio               = 0.;
      m.prestress                    = Tensor<1, 3>({1e6, 1e6, 0.});
      m.wrinkling                    = true;
      unsigned int counts[3]         = {0, 0, 0};
      double       worst_compression = 0., worst_tangent = 0., worst_jump = 0.;
      const auto   strain = [](const unsigned int i) {
        return -1e-2 + 2e-2 * i / 10. + 1.234e-4; // off the symmetric points
      };
      for (unsigned int i = 0; i <= 10; ++i)
        for (unsigned int j = 0; j <= 10; ++j)
          for (unsigned int k = 0; k <= 10; ++k)
            {
              const Tensor<1, 3> E({strain(i), strain(j), strain(k)});
              Tensor<1, 3>       S;
              Tensor<2, 3>       C;
              const auto         state = m.stress(E, S, C);
              ++counts[static_cast<int>(state)];
              if (state != MembraneMaterial::State::wrinkled)
                continue;
              const double mean = 0.5 * (S[0] + S[1]);
              const double R    = std::hypot(0.5 * (S[0] - S[1]), S[2]);
              worst_compression = std::max(worst_compression,
                                           std::max(0., R - mean) / (mean + R));
              Tensor<2, 3> C_fd;
              bool         same_state = true;
              const double h          = 1e-9;
              for (unsigned int c = 0; c < 3; ++c)
                {
                  Tensor<1, 3> Ep = E, Em = E, Sp, Sm;
                  Tensor<2, 3> dummy;
                  Ep[c] += h;
                  Em[c] -= h;
                  same_state = same_state && m.stress(Ep, Sp, dummy) == state &&
                               m.stress(Em, Sm, dummy) == state;
                  for (unsigned int d = 0; d < 3; ++d)
                    C_fd[d][c] = (Sp[d] - Sm[d]) / (2. * h);
                }
              if (same_state)
                worst_tangent =
                  std::max(worst_tangent, (C_fd - C).norm() / C.norm());
            }
      const double C_norm = m.elasticity().norm();
      for (unsigned int i = 0; i <= 10; ++i)
        for (unsigned int j = 0; j <= 10; ++j)
          {
            // From (i, j, 0) to the mirrored point through the origin.
            const Tensor<1, 3> E0({strain(i), strain(j), 0.5 * strain(i + j)});
            const Tensor<1, 3> dE = -2. * E0 / 1000.;
            Tensor<1, 3>       S_prev, S;
            Tensor<2, 3>       C;
            m.stress(E0, S_prev, C);
            for (unsigned int step = 1; step <= 1000; ++step)
              {
                m.stress(E0 + step * dE, S, C);
                worst_jump =
                  std::max(worst_jump,
                           (S - S_prev).norm() / (C_norm * dE.norm()));
                S_prev = S;
              }
          }
      out << "  orthotropic, pre-stressed wrinkling law, 1331 strains: "
          << counts[0] << " taut, " << counts[1] << " wrinkled, " << counts[2]
          << " slack\n";
      report("wrinkled: compressive / tensile principal stress",
             worst_compression,
             1e-10);
      report("wrinkled: tangent vs central differences", worst_tangent, 1e-6);
      report("paths through all states: largest |dS| / (|C| |dE|)",
             worst_jump,
             2.);
    }

    // The same law in the element: tangent vs central differences.
    membrane.material.youngs_modulus_1 = 1e9;
    membrane.material.youngs_modulus_2 = 1e9;
    membrane.material.shear_modulus    = 1e8;
    membrane.material.poissons_ratio   = 0.;
    membrane.material.prestress        = Tensor<1, 3>({1e6, 1e6, 0.});
    membrane.compute(fe_values, displacement(wrinkle), 0., r, K, &output);
    out << "  orthotropic, pre-stressed: " << output.n_wrinkled
        << " of 4 points wrinkled\n";
    report("orthotropic, pre-stressed, wrinkled: tangent vs central "
           "differences",
           fd_error(displacement(wrinkle)),
           1e-5);
  }
  check_solid<3>(1);
  check_solid<3>(2);
  check_solid<2>(1);
  check_solid<2>(2);
  return 0;
}
