// Impact onset (../shared/VERIFICATION.md §4 "Impact onset", preCICE
// issues #1558 and #2374): before contact the interface carries no force,
// x = x~ = 0 for several iterations and windows; then the soil arrives and
// the residual jumps; later it leaves again.
//  1. Direct calls: every accelerator fed zero data for 3 windows of 3
//     iterations returns zeros (no NaN: no division by a zero residual or
//     residual difference); the first nonzero residual after them gives a
//     relaxation step with the initial factor (Aitken, IQN-ILS: fall-back,
//     no secant or column information).
//  2. A scalar contact model over 16 windows: soil front s(t) pressing on
//     the barrier only while s > x, f = k_D max(s - x, 0), d~ = f/k_N with
//     k_D/k_N = 10; exact solution x* = max(k_D s/(k_N + k_D), 0). Zero
//     windows, the jump at first contact, contact switches inside an
//     iteration (the first relaxation step can overshoot beyond s) and the
//     release: every window converges within 30 iterations (no stall) to x*.
//  3. The same on a 5-DoF string whose nodes are hit one after the other
//     (partial contact), checked against a primal-dual active-set solution.

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/coupling_parameters.h>
#include <talus/coupling/predictor.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "check.h"
#include "two_spring_model.h"

using namespace dealii;
using namespace Talus::Coupling;

namespace
{
  std::ofstream out("output");

  void
  check(const bool condition, const std::string &what)
  {
    CouplingTests::check(out, condition, what);
  }


  bool
  finite(const Vector<double> &v)
  {
    for (const double x : v)
      if (!std::isfinite(x))
        return false;
    return true;
  }


  std::vector<std::unique_ptr<InterfaceAccelerator>>
  all_accelerators(const double omega_constant)
  {
    std::vector<std::unique_ptr<InterfaceAccelerator>> a;
    a.push_back(std::make_unique<ConstantRelaxation>(omega_constant));
    a.push_back(std::make_unique<AitkenRelaxation>(0.5));
    a.push_back(
      std::make_unique<IQNILS>(0.1, 2, 100, IQNILS::Filter::QR2, 1e-2));
    a.push_back(
      std::make_unique<IQNILS>(0.1, 2, 100, IQNILS::Filter::QR1, 1e-6));
    a.push_back(
      std::make_unique<IQNILS>(0.1, 2, 100, IQNILS::Filter::none, 1e-2));
    return a;
  }


  std::string
  label(const InterfaceAccelerator &a, const unsigned int index)
  {
    const char *filters[] = {"", "", " QR2", " QR1", " none"};
    return a.name() + filters[index];
  }


  void
  direct_calls()
  {
    out << "1. Zero interface data, then a jump (direct calls, n = 3)\n";
    const Vector<double> zero(3);
    Vector<double>       jump(3);
    jump[0]           = 1e-3;
    jump[1]           = 2e-3;
    auto accelerators = all_accelerators(0.5);
    for (unsigned int i = 0; i < accelerators.size(); ++i)
      {
        InterfaceAccelerator &a        = *accelerators[i];
        bool                  all_zero = true;
        for (unsigned int w = 0; w < 3; ++w)
          {
            a.start_window();
            for (unsigned int k = 0; k < 3; ++k)
              {
                const Vector<double> next = a.compute_next(zero, zero);
                all_zero = all_zero && finite(next) && next.l2_norm() == 0.;
              }
            a.end_window(zero, zero);
          }
        a.start_window();
        const Vector<double> next = a.compute_next(zero, jump);
        Vector<double>       expected(jump);
        expected *= a.info().relaxation;
        expected -= next;
        out << "  " << std::left << std::setw(14) << label(a, i) << std::right
            << "after the jump: omega = " << a.info().relaxation
            << (a.info().fallback ? " (fall-back)" : "") << '\n';
        check(all_zero, label(a, i) + ": zero data gives zero iterates");
        check(finite(next) && a.info().relaxation > 0. &&
                expected.l2_norm() <= 1e-15,
              label(a, i) + ": the jump gives a relaxation step x + omega r");
        // a second iteration on the same residual after the jump
        const Vector<double> again = a.compute_next(next, jump);
        check(finite(again), label(a, i) + ": next iterate finite");
      }
    out << '\n';
  }


  /** Soil front position at window w (m): approaching, pressing, leaving. */
  double
  soil_front(const unsigned int w)
  {
    if (w <= 3)
      return -1e-3 * (4. - w); // not yet there
    if (w <= 10)
      return 1e-3 * (w - 3.);       // pressing up to 7 mm
    return 7e-3 - 3e-3 * (w - 10.); // leaving: below the barrier from w = 13
  }


  void
  scalar_contact()
  {
    const double k_N = 1e6, k_D = 1e7;
    out << "2. Scalar contact, k_D/k_N = 10, x* = max(k_D s/(k_N + k_D), 0)\n";
    auto accelerators = all_accelerators(k_N / (k_N + k_D));
    std::vector<std::vector<unsigned int>> iterations(accelerators.size());
    for (unsigned int i = 0; i < accelerators.size(); ++i)
      {
        InterfaceAccelerator &a = *accelerators[i];
        ConvergenceCriterion  criterion(1e-10, 1e-14, 0., 30);
        InterfacePredictor    predictor(InterfacePredictor::Order::linear);
        predictor.add_converged(0., Vector<double>(1));
        double max_error = 0.;
        bool   all       = true;
        for (unsigned int w = 1; w <= 16; ++w)
          {
            const double       s      = soil_front(w);
            const WindowResult result = iterate_window(
              [&](const Vector<double> &x,
                  Vector<double>       &x_tilde,
                  Vector<double>       &force) {
                force.reinit(1);
                force[0]   = k_D * std::max(s - x[0], 0.);
                x_tilde[0] = force[0] / k_N;
              },
              predictor.predict(w),
              a,
              criterion);
            const double exact = std::max(k_D * s / (k_N + k_D), 0.);
            all = all && result.accepted && finite(result.x_tilde);
            max_error =
              std::max(max_error, std::abs(result.x_tilde[0] - exact));
            iterations[i].push_back(result.accepted ? result.iterations : 0);
            if (result.accepted)
              predictor.add_converged(w, result.x_tilde);
            else
              {
                // the step would be rejected: forget and go on with x*
                a.reset();
                criterion.reset();
                Vector<double> x_exact(1);
                x_exact[0] = exact;
                predictor.add_converged(w, x_exact);
              }
          }
        // Constant relaxation with omega* of the contact branch cannot
        // leave contact quickly: out of contact x~ = 0, and x shrinks by
        // 1 - omega* = 0.91 per iteration (no assertion, shown in the table).
        if (i > 0)
          check(all && max_error <= 1e-10 * 7e-3 * 10. / 11. + 1e-14,
                label(a, i) + ": every window converges to x*");
      }
    out << "  soil front s [mm]:        ";
    for (unsigned int w = 1; w <= 16; ++w)
      out << std::setw(3) << soil_front(w) * 1e3;
    out << "\n  iterations per window (- : not converged in 30):\n";
    for (unsigned int i = 0; i < accelerators.size(); ++i)
      {
        out << "  " << std::left << std::setw(14)
            << (i == 0 ? std::string("constant w*") :
                         label(*accelerators[i], i))
            << std::right;
        for (const unsigned int n : iterations[i])
          out << std::setw(3) << (n > 0 ? std::to_string(n) : std::string("-"));
        out << '\n';
      }
    out << '\n';
  }


  void
  vector_contact()
  {
    const unsigned int     n = 5;
    TwoSpring::VectorModel model(n, 10.);
    out << "3. String of " << n
        << " nodes hit one after the other, K_D ~ 10 k_N\n";
    auto accelerators = all_accelerators(0.05);
    std::vector<std::vector<unsigned int>> iterations(accelerators.size());
    for (unsigned int i = 1; i < accelerators.size(); ++i)
      {
        InterfaceAccelerator &a = *accelerators[i];
        ConvergenceCriterion  criterion(1e-10, 1e-14, 0., 50);
        InterfacePredictor    predictor(InterfacePredictor::Order::linear);
        predictor.add_converged(0., Vector<double>(n));
        double max_error = 0.;
        bool   all       = true;
        for (unsigned int w = 1; w <= 12; ++w)
          {
            // node j is reached at window 2 + j, then pressed 1 mm per window
            Vector<double> s(n);
            for (unsigned int j = 0; j < n; ++j)
              s[j] = 1e-3 * (double(w) - 2. - j);
            const WindowResult result = iterate_window(
              [&](const Vector<double> &x,
                  Vector<double>       &x_tilde,
                  Vector<double> &) {
                Vector<double> f(n);
                for (unsigned int j = 0; j < n; ++j)
                  f[j] = model.K_D(j, j) * std::max(s[j] - x[j], 0.);
                model.K_N_inverse.vmult(x_tilde, f);
              },
              predictor.predict(w),
              a,
              criterion);
            if (!result.accepted && i <= 2)
              for (const IterationRecord &record : result.history)
                out << "    window " << w << ": " << record.status.to_string()
                    << "  columns " << record.acceleration.columns
                    << " filtered " << record.acceleration.filtered_columns
                    << '\n';
            Vector<double> error(result.x_tilde);
            error -= active_set_solution(model, s);
            all       = all && result.accepted && finite(result.x_tilde);
            max_error = std::max(max_error, error.l2_norm());
            iterations[i].push_back(result.accepted ? result.iterations : 0);
            if (result.accepted)
              predictor.add_converged(w, result.x_tilde);
            else
              {
                a.reset();
                criterion.reset();
                predictor.add_converged(w, active_set_solution(model, s));
              }
          }
        // Only Aitken and IQN-ILS with QR2 (the default) are asserted: QR1
        // (R_ii against |R|_F) removes the new, small columns near a contact
        // switch again and cycles, and without a filter the nearly
        // dependent columns of the kinked operator give wild steps; both
        // are shown in the table (doc/coupling.md).
        if (i <= 2)
          check(all && max_error <= 1e-11,
                label(a, i) +
                  ": every window converges to the active-set solution");
      }
    out << "  iterations per window (- : not converged in 50):\n";
    for (unsigned int i = 1; i < accelerators.size(); ++i)
      {
        out << "  " << std::left << std::setw(14) << label(*accelerators[i], i)
            << std::right;
        for (const unsigned int k : iterations[i])
          out << std::setw(3) << (k > 0 ? std::to_string(k) : std::string("-"));
        out << '\n';
      }
  }
} // namespace


int
main()
{
  out << std::setprecision(6);
  direct_calls();
  scalar_contact();
  vector_contact();
  return 0;
}
