// Forcing terms of the inexact Newton method (Talus::EisenstatWalkerForcing)
// against the formulas of Eisenstat and Walker 1996 (choice 2, gamma = 0.9,
// alpha = 2, eta_max = 0.1) and Kelley's oversolving bound, evaluated by
// hand for a residual history 1, 0.1, 1e-3, 1e-4, 1e-7 with the Newton
// tolerance 1e-8 and the floor 1e-10:
//   eta_0 = eta_max                               = 0.1
//   eta_1 = 0.9 (0.1)^2                           = 9e-3
//   eta_2 = 0.9 (1e-2)^2                          = 9e-5
//   eta_3 = max(0.9 (0.1)^2, 0.5e-8/1e-4)         = 9e-3
//   eta_4 = max(0.9 (1e-3)^2, 0.5e-8/1e-7)        = 0.05
// and a safeguarded case: after eta = 0.1 with gamma = 0.9 ... the
// safeguard 0.9 eta^2 is below 0.1 for eta_max < 0.33; with eta_max = 0.5,
// residuals 1, 1e-3: eta_1 = max(0.9e-6, 0.9 * 0.25 = 0.225) = 0.225.
// A new Newton solve (start()) begins again at eta_max.
#include <talus/base/eisenstat_walker.h>

#include <cmath>
#include <iostream>

namespace
{
  int failures = 0;

  void
  check(const char *what, const double value, const double expected)
  {
    const bool ok = std::abs(value - expected) <= 1e-14 * expected;
    std::cout << what << ": " << value << (ok ? " ok" : " WRONG") << '\n';
    failures += ok ? 0 : 1;
  }

  Talus::EisenstatWalkerForcing
  forcing(const char *eta_max)
  {
    dealii::ParameterHandler prm;
    Talus::EisenstatWalkerForcing::declare_parameters(prm);
    prm.set("linear solver forcing", "Eisenstat-Walker");
    prm.set("maximum forcing term", eta_max);
    Talus::EisenstatWalkerForcing f;
    f.parse_parameters(prm, "Solver");
    return f;
  }
} // namespace

int
main()
{
  Talus::EisenstatWalkerForcing f = forcing("0.1");
  f.start();
  check("eta_0", f.next(1., 1e-8, 1e-10), 0.1);
  check("eta_1", f.next(0.1, 1e-8, 1e-10), 9e-3);
  check("eta_2", f.next(1e-3, 1e-8, 1e-10), 9e-5);
  check("eta_3 (residual stalls)", f.next(1e-4, 1e-8, 1e-10), 9e-3);
  check("eta_4 (oversolving bound)", f.next(1e-7, 1e-8, 1e-10), 0.05);
  f.start();
  check("eta_0 after start()", f.next(1e-7, 1e-8, 1e-10), 0.1);

  Talus::EisenstatWalkerForcing g = forcing("0.5");
  g.start();
  check("eta_0 (eta_max 0.5)", g.next(1., 1e-12, 1e-10), 0.5);
  check("eta_1 (safeguard)", g.next(1e-3, 1e-12, 1e-10), 0.225);
  check("floor", g.next(1e-3 * 1e-6, 1e-20, 1e-4), 1e-4);
  return failures;
}
