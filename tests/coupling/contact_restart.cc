// Restart of the accelerator at a change of the active set ('restart at
// contact change', doc/coupling.md "Iterations at contact"): the 5-node
// string of impact_onset.cc (part 3), K_D ~ 10 k_N, hit node after node by
// a soil front s that presses node j only while s_j > x_j, f_j = K_D,jj
// max(s_j - x_j, 0); 12 windows with a linear predictor, relative
// tolerance 1e-10. On each active set the map x -> x~ = K_N^-1 f(x) is
// affine; a quasi-Newton model that mixes columns of several sets fits
// none. iterate_window() with the callback active_set_changed() resets the
// accelerator at each change, at most maximum_contact_restarts (6) times
// per window. Checked for Aitken and IQN-ILS (QR2, the default; reuse 2)
// with the Dirichlet-Neumann operator and with Robin springs k_j = 0.3
// K_D,jj on the pressed nodes (an underestimate, as the diagonal Robin
// layer is for some modes of the MPM): every window converges to the
// primal-dual active-set solution (1e-11) without the restart, and with
// it when there are Robin springs; with the Dirichlet-Neumann operator
// (amplification ~10) the relaxation step after each restart is unstable and
// keeps the set switching: 3 of 12 windows do not converge in 50 iterations
// with the limit (5 without it), shown but not asserted: the restart is meant
// for a Robin iteration (the coupled default);
// the iterations per window are printed, and with Robin springs the
// restart may cost IQN-ILS at most 10 % more in total. This small model
// does not show the gain of the coupled case (measured 39 / 40: its
// active set changes at one node at a time, and the model of IQN-ILS is
// rebuilt within a few iterations either way); it checks that the restart
// and its limit converge.

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/coupling_parameters.h>
#include <talus/coupling/predictor.h>

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


  /** The 12 windows with one accelerator; returns the iterations per
   * window (0: not converged in 50) and checks the solutions. */
  std::vector<unsigned int>
  run(InterfaceAccelerator &a,
      const bool            restart,
      const double          robin_factor,
      const std::string    &name)
  {
    const unsigned int     n = 5;
    TwoSpring::VectorModel model(n, 10.);
    ConvergenceCriterion   criterion(1e-10, 1e-14, 0., 50);
    InterfacePredictor     predictor(InterfacePredictor::Order::linear);
    predictor.add_converged(0., Vector<double>(n));
    std::vector<unsigned int> iterations;
    double                    max_error = 0.;
    bool                      all       = true;
    unsigned int              restarts  = 0;
    for (unsigned int w = 1; w <= 12; ++w)
      {
        // node j is reached at window 2 + j, then pressed 1 mm per window
        Vector<double> s(n);
        for (unsigned int j = 0; j < n; ++j)
          s[j] = 1e-3 * (double(w) - 2. - j);
        std::vector<bool> active, previous;
        const auto        H = [&](const Vector<double> &x,
                           Vector<double>       &x_tilde,
                           Vector<double> &) {
          previous = active;
          active.assign(n, false);
          FullMatrix<double> A(model.K_N);
          Vector<double>     b(n);
          for (unsigned int j = 0; j < n; ++j)
            {
              active[j] = s[j] > x[j];
              if (active[j])
                {
                  b[j] = model.K_D(j, j) * (s[j] - x[j]);
                  // Robin springs towards x on the pressed nodes
                  const double k = robin_factor * model.K_D(j, j);
                  A(j, j) += k;
                  b[j] += k * x[j];
                }
            }
          FullMatrix<double> A_inverse(n, n);
          A_inverse.invert(A);
          A_inverse.vmult(x_tilde, b);
        };
        const WindowResult result =
          iterate_window(H,
                         predictor.predict(w),
                         a,
                         criterion,
                         true,
                         {},
                         restart ? std::function<bool()>([&]() {
                           return !previous.empty() && previous != active;
                         }) :
                                   std::function<bool()>());
        Vector<double> error(result.x_tilde);
        error -= active_set_solution(model, s);
        all       = all && result.accepted;
        max_error = std::max(max_error, error.l2_norm());
        restarts += result.contact_restarts;
        iterations.push_back(result.accepted ? result.iterations : 0);
        if (result.accepted)
          predictor.add_converged(w, result.x_tilde);
        else
          {
            a.reset();
            criterion.reset();
            predictor.add_converged(w, active_set_solution(model, s));
          }
      }
    unsigned int total = 0;
    for (const unsigned int k : iterations)
      total += k;
    out << "  " << std::left << std::setw(44) << name << std::right;
    for (const unsigned int k : iterations)
      out << std::setw(3) << (k > 0 ? std::to_string(k) : std::string("-"));
    out << "  total " << total << ", restarts " << restarts << '\n';
    // the Dirichlet-Neumann operator with restarts is shown, not asserted
    if (!restart || robin_factor > 0.)
      CouplingTests::check(out,
                           all && max_error <= 1e-11,
                           name + ": every window converges to the "
                                  "active-set solution");
    if (!restart)
      CouplingTests::check(out, restarts == 0, name + ": no restart");
    else
      CouplingTests::check(out,
                           restarts <= 12 * maximum_contact_restarts,
                           name + ": at most " +
                             std::to_string(maximum_contact_restarts) +
                             " restarts per window");
    return iterations;
  }


  unsigned int
  sum(const std::vector<unsigned int> &v)
  {
    unsigned int s = 0;
    for (const unsigned int k : v)
      s += k;
    return s;
  }
} // namespace


int
main()
{
  out << "String of 5 nodes hit one after the other, K_D ~ 10 k_N; "
         "iterations per window 1 ... 12\n";
  for (const double robin : {0., 0.3})
    {
      out << (robin == 0. ? "Dirichlet-Neumann:\n" :
                            "Robin springs 0.3 K_D on the pressed nodes:\n");
      for (const bool restart : {false, true})
        {
          AitkenRelaxation aitken(0.5);
          run(aitken,
              restart,
              robin,
              std::string("Aitken") + (restart ? ", restart" : ""));
        }
      std::vector<unsigned int> without, with;
      for (const bool restart : {false, true})
        {
          IQNILS iqn(0.1, 2, 100, IQNILS::Filter::QR2, 1e-2);
          (restart ? with : without) =
            run(iqn,
                restart,
                robin,
                std::string("IQN-ILS QR2") + (restart ? ", restart" : ""));
        }
      if (robin > 0.)
        CouplingTests::check(out,
                             sum(with) <= 1.1 * sum(without),
                             "IQN-ILS with Robin springs: the restart needs "
                             "at most 10 % more iterations in total");
    }
  return 0;
}
