// A check of a computed value against one worked out by hand, shared by the
// unit tests of this directory: prints "<what>: <value> ok" or "WRONG" and
// counts the failures. Equal within 1e-14 relative (absolute below 1);
// an infinite expectation needs +infinity.
#ifndef talus_tests_solver_check_close_h
#define talus_tests_solver_check_close_h

#include <algorithm>
#include <cmath>
#include <iostream>

namespace
{
  int failures = 0;

  void
  check(const char *what, const double value, const double expected)
  {
    const bool ok =
      std::isinf(expected) ?
        std::isinf(value) && value > 0. :
        std::abs(value - expected) <= 1e-14 * std::max(1., std::abs(expected));
    std::cout << what << ": " << value << (ok ? " ok" : " WRONG") << '\n';
    failures += ok ? 0 : 1;
  }
} // namespace

#endif
