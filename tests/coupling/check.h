// The assertion of the coupling tests: print the check with ok/FAILED into
// the test output, then stop the test if it failed.

#ifndef talus_tests_coupling_check_h
#define talus_tests_coupling_check_h

#include <deal.II/base/exceptions.h>

#include <ostream>
#include <string>

namespace CouplingTests
{
  inline void
  check(std::ostream &out, const bool condition, const std::string &what)
  {
    out << "  check: " << what << (condition ? ": ok" : ": FAILED")
        << std::endl;
    AssertThrow(condition, dealii::ExcMessage("Failed: " + what));
  }
} // namespace CouplingTests

#endif
