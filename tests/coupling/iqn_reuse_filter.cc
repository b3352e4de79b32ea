// IQN-ILS over several time windows (two_spring_model.h, vector model,
// n = 10 interface DoFs, k_D/k_N ~ 10, with a cubic soil stiffening so
// that the interface problem is nonlinear): the load changes from window to
// window, the first iterate comes from the linear predictor.
//  - reusing the columns of q > 0 past windows needs fewer iterations in
//    total than q = 0 (Degroote et al. 2009, preCICE's time-windows-reused);
//  - with q = 8 the model holds more columns than the interface has DoFs,
//    so columns are linearly dependent: QR1 and QR2 remove them (counted),
//    without a filter the model keeps the newest n; all converge to the
//    reference (linear case);
//  - the reference is an independent Newton solve of the monolithic
//    equations (K_N + K_D) x + c x^3 = f_0 per window.

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/coupling_parameters.h>
#include <talus/coupling/predictor.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "check.h"
#include "two_spring_model.h"

using namespace dealii;
using namespace Talus::Coupling;

namespace
{
  std::ofstream out("output");

  const unsigned int n_dofs    = 10;
  const unsigned int n_windows = 12;
  const double       dt        = 1e-3;
  double             cubic     = 1e12; // N/m^3


  void
  check(const bool condition, const std::string &what)
  {
    CouplingTests::check(out, condition, what);
  }


  double
  load_amplitude(const unsigned int window)
  {
    return 1. + 0.5 * std::sin(0.5 * window);
  }


  struct Run
  {
    std::string               name;
    std::vector<unsigned int> iterations;
    unsigned int              total     = 0;
    unsigned int              filtered  = 0;
    double                    max_error = 0.;
  };


  Run
  run(const std::string   &name,
      const unsigned int   reuse,
      const IQNILS::Filter filter,
      const double         filter_tolerance)
  {
    Run result;
    result.name = name;
    TwoSpring::VectorModel model(n_dofs, 10., cubic);
    IQNILS                 iqn(0.1, reuse, 100, filter, filter_tolerance);
    ConvergenceCriterion   criterion(1e-8, 1e-14, 0., 100);
    InterfacePredictor     predictor(InterfacePredictor::Order::linear);
    predictor.add_converged(0., Vector<double>(n_dofs));
    bool finite = true;
    for (unsigned int w = 1; w <= n_windows; ++w)
      {
        model.set_load(load_amplitude(w));
        const WindowResult window =
          iterate_window([&](const Vector<double> &x,
                             Vector<double>       &x_tilde,
                             Vector<double> &) { model(x, x_tilde); },
                         predictor.predict(w * dt),
                         iqn,
                         criterion);
        finite = finite && std::isfinite(window.x_tilde.l2_norm()) &&
                 std::isfinite(window.history.back().status.residual);
        if (!window.accepted)
          {
            for (const IterationRecord &record : window.history)
              out << "    " << record.status.to_string() << "  columns "
                  << record.acceleration.columns << " filtered "
                  << record.acceleration.filtered_columns << '\n';
            check(false, name + ", window " + std::to_string(w) + " converges");
          }
        Vector<double>       error(window.x_tilde);
        const Vector<double> reference = model.monolithic_solution();
        error -= reference;
        result.max_error =
          std::max(result.max_error, error.l2_norm() / reference.l2_norm());
        result.iterations.push_back(window.iterations);
        result.total += window.iterations;
        predictor.add_converged(w * dt, window.x_tilde);
      }
    result.filtered = iqn.n_filtered_columns();
    check(finite, name + ": no NaN or inf in any window");
    check(result.max_error <= 1e-6,
          name + ": every window converges, within 1e-6 of the monolithic "
                 "solution");
    return result;
  }
} // namespace


void
print_table(const std::vector<Run> &runs)
{
  out << "\nIterations per window:\n" << std::left << std::setw(18) << "run";
  for (unsigned int w = 1; w <= n_windows; ++w)
    out << std::setw(4) << w;
  out << std::setw(7) << "total"
      << "filtered columns\n";
  for (const Run &r : runs)
    {
      out << std::setw(18) << r.name;
      for (const unsigned int i : r.iterations)
        out << std::setw(4) << i;
      out << std::setw(7) << r.total << r.filtered << '\n';
    }
  out << std::right << '\n';
}


int
main()
{
  out << "IQN-ILS over " << n_windows << " windows, n = " << n_dofs
      << " interface DoFs, K_D ~ 10 k_N (K_N^-1 K_D up to ~27), relative "
         "tolerance 1e-8, at most 100 iterations and 100 columns, linear "
         "predictor\n\n";

  // 1. Nonlinear (cubic soil stiffening): reuse pays off.
  cubic = 1e12;
  out << "1. Nonlinear, cubic soil term " << cubic << " N/m^3\n";
  std::vector<Run> nonlinear;
  nonlinear.push_back(run("q = 0, QR2 1e-2", 0, IQNILS::Filter::QR2, 1e-2));
  nonlinear.push_back(run("q = 1, QR2 1e-2", 1, IQNILS::Filter::QR2, 1e-2));
  nonlinear.push_back(run("q = 4, QR2 1e-2", 4, IQNILS::Filter::QR2, 1e-2));
  nonlinear.push_back(run("q = 8, QR2 1e-2", 8, IQNILS::Filter::QR2, 1e-2));
  print_table(nonlinear);
  for (unsigned int i = 1; i < nonlinear.size(); ++i)
    check(nonlinear[i].total < nonlinear[0].total,
          nonlinear[i].name + " needs fewer iterations in total than q = 0");
  check(nonlinear[3].filtered > 0,
        "q = 8 (more columns than DoFs): QR2 removes dependent columns");

  // 2. Linear: 8 reused windows give far more columns than the 10 DoFs,
  //    nearly dependent; the filters remove them, without a filter the
  //    model keeps the newest 10 (no more than the DoFs).
  cubic = 0.;
  out << "2. Linear (cubic term 0)\n";
  std::vector<Run> linear;
  linear.push_back(run("q = 0, QR2 1e-2", 0, IQNILS::Filter::QR2, 1e-2));
  linear.push_back(run("q = 8, QR2 1e-2", 8, IQNILS::Filter::QR2, 1e-2));
  linear.push_back(run("q = 8, QR1 1e-6", 8, IQNILS::Filter::QR1, 1e-6));
  linear.push_back(run("q = 8, no filter", 8, IQNILS::Filter::none, 1e-2));
  print_table(linear);
  check(linear[3].iterations[0] <= n_dofs + 2,
        "first window without a filter: at most n + 2 iterations (GMRES "
        "bound)");
  check(linear[1].total < linear[0].total &&
          linear[2].total < linear[0].total &&
          linear[3].total < linear[0].total,
        "q = 8 (QR1, QR2, no filter) needs fewer iterations than q = 0");
  check(linear[1].filtered > 0 && linear[2].filtered > 0,
        "QR1 and QR2 remove columns");
  return 0;
}
