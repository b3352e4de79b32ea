// Checks shared by the element tests of tests/structure/ (elements.cc,
// cable_engineering_law.cc): the output file, reports against bounds and
// central-difference tangents of line elements and sliding cables.

#ifndef talus_tests_structure_line_element_checks_h
#define talus_tests_structure_line_element_checks_h

#include <talus/structure/line_elements.h>
#include <talus/structure/sliding_cable.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace LineElementChecks
{
  using namespace dealii;
  using namespace Talus::Structure;

  /** The file the test framework compares with NAME.output. */
  inline std::ofstream out("output");

  /** "ok" or "FAILED" for a value against its bound (and the value on
   * stdout if it fails). */
  inline void
  report(const std::string &what, const double value, const double bound)
  {
    out << "  " << what << ": " << (value <= bound ? "ok" : "FAILED") << " (< "
        << bound << ")\n";
    if (value > bound)
      std::cout << what << " = " << value << std::endl;
  }

  /** max |A - B| / max |A| */
  inline double
  relative_difference(const FullMatrix<double> &A, const FullMatrix<double> &B)
  {
    double d = 0., a = 0.;
    for (unsigned int i = 0; i < A.m(); ++i)
      for (unsigned int j = 0; j < A.n(); ++j)
        {
          d = std::max(d, std::abs(A(i, j) - B(i, j)));
          a = std::max(a, std::abs(A(i, j)));
        }
    return d / a;
  }

  /**
   * Central differences (step h [m]) of the nodal forces of a sliding
   * cable at positions x; with old_lengths the stick-slip law from that
   * committed history.
   */
  inline FullMatrix<double>
  sliding_cable_fd_tangent(const SlidingCable              &cable,
                           const std::vector<Tensor<1, 3>> &X,
                           const std::vector<Tensor<1, 3>> &x,
                           const double                     h,
                           const std::vector<double> *old_lengths = nullptr)
  {
    const unsigned int n = 3 * x.size();
    FullMatrix<double> K_fd(n, n);
    for (unsigned int j = 0; j < n; ++j)
      {
        auto xp = x, xm = x;
        xp[j / 3][j % 3] += h;
        xm[j / 3][j % 3] -= h;
        Vector<double>      fp, fm;
        FullMatrix<double>  dummy;
        std::vector<double> L;
        if (old_lengths != nullptr)
          {
            cable.compute(X, xp, *old_lengths, fp, dummy, L);
            cable.compute(X, xm, *old_lengths, fm, dummy, L);
          }
        else
          {
            cable.compute(X, xp, fp, dummy);
            cable.compute(X, xm, fm, dummy);
          }
        for (unsigned int i = 0; i < n; ++i)
          K_fd(i, j) = (fp[i] - fm[i]) / (2. * h);
      }
    return K_fd;
  }

  /** Forces and central-difference tangent of a two-node element. */
  inline double
  line_tangent_error(const LineElement  &element,
                     const Tensor<1, 3> &X0,
                     const Tensor<1, 3> &X1,
                     const Tensor<1, 3> &x0,
                     const Tensor<1, 3> &x1,
                     const LineState    &state)
  {
    LineResponse r;
    element.compute(X0, X1, x0, x1, state, r);
    FullMatrix<double> K_fd(6, 6);
    const double       h = 1e-6 * (X1 - X0).norm();
    for (unsigned int j = 0; j < 6; ++j)
      {
        Tensor<1, 3> p0 = x0, p1 = x1, m0 = x0, m1 = x1;
        (j < 3 ? p0 : p1)[j % 3] += h;
        (j < 3 ? m0 : m1)[j % 3] -= h;
        LineResponse rp, rm;
        element.compute(X0, X1, p0, p1, state, rp);
        element.compute(X0, X1, m0, m1, state, rm);
        for (unsigned int i = 0; i < 6; ++i)
          K_fd(i, j) = (rp.f[i] - rm.f[i]) / (2. * h);
      }
    return relative_difference(r.K, K_fd);
  }

} // namespace LineElementChecks

#endif
