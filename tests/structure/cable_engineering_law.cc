// The engineering axial law of cables, sliding cables and trusses
// (strain measure = engineering, AxialLaw; doc/verification.md, "Cables
// with the engineering law"): N = EA (l - l0)/l0 with the unstretched length
// l0 = L/(1 + sigma_0/E), zero when slack (l < l0), strain energy
// EA (l - l0)^2/(2 l0); the tangent dN/dl = EA/l0 in the element tangent
// against central differences of the forces; dW/dl = N by central
// differences; a cable at l = l0 exactly: N = 0, taut, axial tangent EA/l0,
// the regularising stiffness across; the Green-Lagrange force at the same
// length for comparison, N_GL/N_eng = (1 + e)(1 + e/2) at sigma_0 = 0.
// Relative differences are printed as "ok" below a bound.

#include <talus/structure/axial_law.h>
#include <talus/structure/line_elements.h>
#include <talus/structure/sliding_cable.h>

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
  /** K of a sliding cable against central differences of f. */
  double
  sliding_tangent_error(const SlidingCable              &cable,
                        const std::vector<Tensor<1, 3>> &X,
                        const std::vector<Tensor<1, 3>> &x,
                        const std::vector<double>       *old_lengths = nullptr)
  {
    Vector<double>      f;
    FullMatrix<double>  K;
    std::vector<double> L;
    if (old_lengths != nullptr)
      cable.compute(X, x, *old_lengths, f, K, L);
    else
      cable.compute(X, x, f, K);
    return relative_difference(
      K, sliding_cable_fd_tangent(cable, X, x, 1e-7, old_lengths));
  }

  /** e^T K_00 e and |(I - e e^T) K_00 (I - e e^T)| of a response. */
  void
  axial_and_transverse(const LineResponse &r,
                       const Tensor<1, 3> &e,
                       double             &axial,
                       double             &transverse)
  {
    axial = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        axial += e[i] * r.K(i, j) * e[j];
    // A unit vector normal to e.
    Tensor<1, 3> t({-e[1], e[0], 0.});
    t /= t.norm();
    transverse = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        transverse += t[i] * r.K(i, j) * t[j];
  }
} // namespace


int
main()
{
  out << std::setprecision(12);
  const double       E = 1.2e11, A = 2e-4, EA = E * A;
  const Tensor<1, 3> X0({0.2, -0.1, 0.3}), X1({1.4, 0.5, -0.2});
  const double       L = (X1 - X0).norm();
  const Tensor<1, 3> e = (X1 - X0) / L;

  // ------------------------------------------------------------- Cable
  for (const double prestress : {0., 1e8})
    {
      out << "Cable, engineering law, E = 1.2e11 Pa, A = 2e-4 m^2, sigma_0 = "
          << prestress << " Pa\n";
      Cable cable;
      cable.youngs_modulus = E;
      cable.area           = A;
      cable.prestress      = prestress;
      cable.strain_measure = StrainMeasure::engineering;
      const double l0      = L / (1. + prestress / E);
      LineResponse r;
      for (const double stretch : {1.02, 1.2})
        {
          const Tensor<1, 3> x1 = X0 + stretch * l0 * e;
          cable.compute(X0, X1, X0, x1, LineState(), r);
          const double l = (x1 - X0).norm();
          const double N = EA * (l - l0) / l0,
                       W = 0.5 * EA * (l - l0) * (l - l0) / l0;
          out << "  l/l0 = " << stretch << ": N = " << r.force
              << " N (EA (l - l0)/l0 = " << N << "), W = " << r.energy
              << " J (EA (l - l0)^2/(2 l0) = " << W << ")\n";
          report("    |N - EA (l - l0)/l0| / N",
                 std::abs(r.force - N) / N,
                 1e-13);
          report("    |W - EA (l - l0)^2/(2 l0)| / W",
                 std::abs(r.energy - W) / W,
                 1e-12);
          double axial, transverse;
          axial_and_transverse(r, e, axial, transverse);
          report("    axial tangent e.K.e = EA/l0",
                 std::abs(axial - EA / l0) / (EA / l0),
                 1e-13);
          report("    transverse tangent = N/l",
                 std::abs(transverse - r.force / l) / (r.force / l),
                 1e-12);
          // dW/dl = N by central differences along e.
          const double h = 1e-6 * L;
          LineResponse rp, rm;
          cable.compute(X0, X1, X0, x1 + h * e, LineState(), rp);
          cable.compute(X0, X1, X0, x1 - h * e, LineState(), rm);
          report("    dW/dl (central differences) = N",
                 std::abs((rp.energy - rm.energy) / (2. * h) - r.force) /
                   r.force,
                 1e-7);
        }
      const Tensor<1, 3> x0({0.25, -0.05, 0.31}), x1({1.5, 0.7, -0.1});
      report("tangent vs central differences (stretched, rotated)",
             line_tangent_error(cable, X0, X1, x0, x1, LineState()),
             1e-6);
      cable.compute(X0, X1, X0, X1, LineState(), r);
      out << "  at the reference length l = L: N = " << r.force
          << " N (A sigma_0 = " << A * prestress << ")\n";
      // Exactly at the unstretched length.
      if (prestress == 0.)
        {
          cable.compute(X0, X1, X0, X1, LineState(), r);
          double axial, transverse;
          axial_and_transverse(r, e, axial, transverse);
          out << "  l = l0 exactly: N = " << r.force << ", slack = " << r.slack
              << ", e.K.e / (EA/l0) = " << axial / (EA / l0)
              << ", transverse / (EA/l0) = " << std::setprecision(6)
              << transverse / (EA / l0) << std::setprecision(12)
              << " (slack stiffness ratio)\n";
          report("  l = l0: tangent vs central differences along e",
                 std::abs(axial - EA / l0) / (EA / l0),
                 1e-13);
        }
      cable.compute(X0, X1, X0, X0 + 0.99 * l0 * e, LineState(), r);
      out << "  l = 0.99 l0: N = " << r.force << ", slack = " << r.slack
          << ", W = " << r.energy << " J\n";
    }

  // ------------------------------------------ comparison with Green-Lagrange
  {
    out << "Cable at l = 1.02 L (sigma_0 = 0): engineering vs Green-Lagrange\n";
    Cable eng, gl;
    eng.youngs_modulus = gl.youngs_modulus = E;
    eng.area = gl.area = A;
    eng.strain_measure = StrainMeasure::engineering;
    LineResponse       re, rg;
    const Tensor<1, 3> x1 = X0 + 1.02 * L * e;
    eng.compute(X0, X1, X0, x1, LineState(), re);
    gl.compute(X0, X1, X0, x1, LineState(), rg);
    out << "  N_eng = " << re.force << " N, N_GL = " << rg.force
        << " N, N_GL/N_eng = " << rg.force / re.force
        << " ((1 + e)(1 + e/2) = " << 1.02 * 1.01 << ")\n"
        << "  strain: engineering " << re.strain << ", Green-Lagrange "
        << rg.strain << "\n";
  }

  // ------------------------------------------------------------- Truss
  {
    out << "Truss, engineering law, sigma_0 = 1e8 Pa\n";
    Truss truss;
    truss.youngs_modulus = E;
    truss.area           = A;
    truss.prestress      = 1e8;
    truss.strain_measure = StrainMeasure::engineering;
    const double l0      = L / (1. + 1e8 / E);
    LineResponse r;
    for (const double stretch : {1.02, 0.97})
      {
        const Tensor<1, 3> x1 = X0 + stretch * l0 * e;
        truss.compute(X0, X1, X0, x1, LineState(), r);
        const double l = (x1 - X0).norm(), N = EA * (l - l0) / l0;
        out << "  l/l0 = " << stretch << ": N = " << r.force
            << " N (EA (l - l0)/l0 = " << N << ")\n";
        report("    |N - EA (l - l0)/l0| / |N|",
               std::abs(r.force - N) / std::abs(N),
               1e-13);
      }
    const Tensor<1, 3> x0({0.25, -0.05, 0.31}), x1({1.5, 0.7, -0.1});
    report("elastic: tangent vs central differences",
           line_tangent_error(truss, X0, X1, x0, x1, LineState()),
           1e-6);
    truss.yield_stress    = 2.5e8;
    truss.hardening       = 2e9;
    const Tensor<1, 3> xp = X0 + 1.01 * l0 * e;
    truss.compute(X0, X1, X0, xp, LineState(), r);
    // eps = 0.01 (to round-off), S = sigma_y + H alpha, alpha = (E eps -
    // sigma_y)/(E + H).
    const double eps   = ((xp - X0).norm() - l0) / l0,
                 alpha = (E * eps - 2.5e8) / (E + 2e9);
    out << "  plastic, eps = 0.01: S = N/A = " << r.force / A
        << " Pa (sigma_y + H alpha = " << 2.5e8 + 2e9 * alpha
        << "), plastic strain " << r.state.plastic << " (" << alpha << ")\n";
    report("    |S - (sigma_y + H alpha)| / S",
           std::abs(r.force / A - 2.5e8 - 2e9 * alpha) / (r.force / A),
           1e-12);
    report("plastic: tangent vs central differences",
           line_tangent_error(truss, X0, X1, X0, xp, LineState()),
           1e-6);
  }

  // ------------------------------------------------------ Sliding cable
  {
    out << "Sliding cable through 3 nodes, engineering law, sigma_0 = 1e8 "
           "Pa\n";
    SlidingCable cable;
    cable.youngs_modulus               = E;
    cable.area                         = A;
    cable.prestress                    = 1e8;
    cable.strain_measure               = StrainMeasure::engineering;
    const std::vector<Tensor<1, 3>> X  = {Tensor<1, 3>({0, 0, 0}),
                                          Tensor<1, 3>({1, 0, 0}),
                                          Tensor<1, 3>({2, 0, 0})};
    const std::vector<Tensor<1, 3>> x  = {Tensor<1, 3>({0, 0, 0}),
                                          Tensor<1, 3>({1.1, 0.02, -0.2}),
                                          Tensor<1, 3>({2, 0, 0})};
    const double                    l0 = 2. / (1. + 1e8 / E);
    const double       l = (x[1] - x[0]).norm() + (x[2] - x[1]).norm();
    Vector<double>     f;
    FullMatrix<double> K;
    double             W     = 0.;
    const double       N     = cable.compute(X, x, f, K, &W);
    const double       N_ref = EA * (l - l0) / l0,
                 W_ref       = 0.5 * EA * (l - l0) * (l - l0) / l0;
    out << "  l = " << l << " m: N = " << N << " N (EA (l - l0)/l0 = " << N_ref
        << "), W = " << W << " J (" << W_ref << ")\n";
    report("  |N - EA (l - l0)/l0| / N", std::abs(N - N_ref) / N_ref, 1e-13);
    report("  |W - EA (l - l0)^2/(2 l0)| / W",
           std::abs(W - W_ref) / W_ref,
           1e-12);
    report("frictionless: tangent vs central differences",
           sliding_tangent_error(cable, X, x),
           1e-6);
    cable.friction_coefficient = 0.2;
    cable.compute(X, x, f, K);
    out << "  with friction mu = 0.2: segment tensions "
        << cable.segment_forces[0] << ", " << cable.segment_forces[1]
        << " N, ratio " << cable.segment_forces[1] / cable.segment_forces[0]
        << "\n";
    report("friction (slide): tangent vs central differences",
           sliding_tangent_error(cable, X, x),
           1e-6);
    // Material of each segment: N_i = EA (l_i/(L_i lambda_0) - 1) with
    // sum L_i = 2 m (segment_forces of x, not of the last difference).
    cable.compute(X, x, f, K);
    double M = 0.;
    for (unsigned int i = 0; i < 2; ++i)
      M += (x[i + 1] - x[i]).norm() /
           ((1. + cable.segment_forces[i] / EA) / (1. + 1e8 / E));
    report("friction: material length sum L_i = L",
           std::abs(M - 2.) / 2.,
           1e-12);
    cable.stick_slip                = true;
    const std::vector<double> old_L = {1., 1.};
    report("stick-slip: tangent vs central differences",
           sliding_tangent_error(cable, X, x, &old_L),
           1e-6);
  }
  return 0;
}
