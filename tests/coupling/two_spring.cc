// The two-spring Dirichlet-Neumann model of ../shared/VERIFICATION.md §4
// (two_spring_model.h): the interface iteration of one time step with plain
// Gauss-Seidel (omega = 1), the optimal constant relaxation, Aitken and
// IQN-ILS, against the closed forms:
//  - plain Gauss-Seidel multiplies the residual by -k_D/k_N per iteration:
//    k_D/k_N = 0.1 converges (in the number of iterations the geometric
//    series predicts), 10 and 100 diverge (residual growth = k_D/k_N);
//  - omega* = k_N/(k_N + k_D) = 0.909, 0.0909, 0.0099 converges after one
//    update (2 evaluations: the second one confirms);
//  - Aitken and IQN-ILS need at most 3 evaluations on the scalar linear
//    problem (one relaxation step, one exact secant step, the check);
//  - a 4-DoF vector version: Gauss-Seidel and constant relaxation against
//    the eigenvalues of K_N^-1 K_D, IQN-ILS within n + 2 evaluations
//    (Anderson acceleration = GMRES on a linear problem).
// "iterations" counts evaluations of the fixed-point operator (solves of
// both sides), including the one that shows convergence.

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/coupling_parameters.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "two_spring_model.h"

using namespace dealii;
using namespace Talus::Coupling;

namespace
{
  std::ofstream out("output");

  const double relative_tolerance = 1e-10;
  const double absolute_tolerance = 1e-15;

  using Operator =
    std::function<void(const Vector<double> &, Vector<double> &)>;


  WindowResult
  run(const Operator       &H,
      const unsigned int    n,
      InterfaceAccelerator &accelerator,
      const unsigned int    maximum_iterations)
  {
    ConvergenceCriterion criterion(relative_tolerance,
                                   absolute_tolerance,
                                   0.,
                                   maximum_iterations);
    return iterate_window([&](const Vector<double> &x,
                              Vector<double>       &x_tilde,
                              Vector<double> &) { H(x, x_tilde); },
                          Vector<double>(n),
                          accelerator,
                          criterion);
  }


  /** Evaluations plain Gauss-Seidel needs by the closed form: residual
   * |r_k| = (1 + rho) rho^k |d*|, output |x~_k| = |d*| |1 + rho (-rho)^k|. */
  unsigned int
  gauss_seidel_iterations_by_theory(const double rho)
  {
    for (unsigned int k = 0; k < 1000; ++k)
      {
        const double r       = (1. + rho) * std::pow(rho, k);
        const double x_tilde = std::abs(1. + rho * std::pow(-rho, k));
        if (r <= relative_tolerance * x_tilde)
          return k + 1;
      }
    return 0;
  }


  void
  check(const bool condition, const std::string &what)
  {
    CouplingTests::check(out, condition, what);
  }


  void
  scalar_model()
  {
    out << "Scalar two-spring model, k_N = 1e6 N/m, dt = 1e-3 s, v_n = 5 m/s,"
        << " relative tolerance " << relative_tolerance << "\n\n";
    const std::vector<double>             ratios = {0.1, 10., 100.};
    std::vector<std::vector<std::string>> table(4);
    const std::vector<std::string>        names = {"Gauss-Seidel (omega = 1)",
                                                   "constant omega*",
                                                   "Aitken (omega_init = 0.5)",
                                                   "IQN-ILS (omega_0 = 0.1)"};
    for (const double ratio : ratios)
      {
        const TwoSpring::Scalar model(ratio);
        const Operator          H = std::cref(model);
        out << "k_D/k_N = " << ratio << ": k_s = " << model.k_s
            << " N/m, m = " << model.m << " kg, k_D = " << model.k_D
            << " N/m, d* = " << model.solution()
            << " m, omega* = " << model.optimal_relaxation() << '\n';

        // Plain Gauss-Seidel: residual factor -k_D/k_N.
        {
          ConstantRelaxation gs(1.);
          const WindowResult result = run(H, 1, gs, 8);
          out << "  Gauss-Seidel |r_k|/|r_0|:";
          const double r0 = result.history[0].status.residual;
          for (unsigned int k = 1;
               k < std::min<std::size_t>(4, result.history.size());
               ++k)
            out << ' ' << std::setprecision(6)
                << result.history[k].status.residual / r0;
          out << '\n';
          for (unsigned int k = 1;
               k < std::min<std::size_t>(4, result.history.size());
               ++k)
            {
              const double factor = result.history[k].status.residual /
                                    result.history[k - 1].status.residual;
              check(std::abs(factor - ratio) <= 1e-9 * ratio,
                    "Gauss-Seidel residual factor " + std::to_string(k) +
                      " equals k_D/k_N");
            }
          if (ratio < 1.)
            {
              ConstantRelaxation gs_long(1.);
              const WindowResult converged = run(H, 1, gs_long, 100);
              check(converged.accepted &&
                      converged.iterations ==
                        gauss_seidel_iterations_by_theory(ratio),
                    "Gauss-Seidel converges in " +
                      std::to_string(gauss_seidel_iterations_by_theory(ratio)) +
                      " iterations (geometric series)");
              table[0].push_back(std::to_string(converged.iterations));
            }
          else
            {
              check(!result.accepted &&
                      result.history.back().status.residual >
                        1e6 * result.history[0].status.residual,
                    "Gauss-Seidel diverges (residual grows > 1e6 in 8)");
              table[0].push_back("diverges");
            }
        }

        // Optimal constant relaxation: exact after one update.
        {
          ConstantRelaxation relaxation(model.optimal_relaxation());
          const WindowResult result = run(H, 1, relaxation, 30);
          check(result.accepted && result.iterations == 2,
                "omega* converges after one update");
          check(std::abs(result.x_tilde[0] - model.solution()) <=
                  1e-10 * model.solution(),
                "omega*: d = d*");
          table[1].push_back(std::to_string(result.iterations));
        }

        // Aitken and IQN-ILS: at most 3 evaluations.
        {
          AitkenRelaxation   aitken(0.5);
          const WindowResult result = run(H, 1, aitken, 30);
          check(result.accepted && result.iterations <= 3,
                "Aitken converges in <= 3 iterations");
          check(std::abs(aitken.relaxation() - model.optimal_relaxation()) <=
                  1e-10 * model.optimal_relaxation(),
                "Aitken's secant factor equals omega*");
          check(std::abs(result.x_tilde[0] - model.solution()) <=
                  1e-10 * model.solution(),
                "Aitken: d = d*");
          table[2].push_back(std::to_string(result.iterations));
        }
        {
          IQNILS             iqn(0.1, 0, 100, IQNILS::Filter::QR2, 1e-2);
          const WindowResult result = run(H, 1, iqn, 30);
          check(result.accepted && result.iterations <= 3,
                "IQN-ILS converges in <= 3 iterations");
          check(std::abs(result.x_tilde[0] - model.solution()) <=
                  1e-10 * model.solution(),
                "IQN-ILS: d = d*");
          table[3].push_back(std::to_string(result.iterations));
        }
        out << '\n';
      }

    out << "Iterations (evaluations of both sides) per method, scalar:\n"
        << std::left << std::setw(28) << "method";
    for (const double ratio : ratios)
      {
        std::ostringstream label;
        label << "k_D/k_N=" << ratio;
        out << std::setw(14) << label.str();
      }
    out << '\n';
    for (unsigned int m = 0; m < names.size(); ++m)
      {
        out << std::setw(28) << names[m];
        for (const auto &entry : table[m])
          out << std::setw(14) << entry;
        out << '\n';
      }
    out << std::right << '\n';
  }


  void
  vector_model()
  {
    const unsigned int     n     = 4;
    const double           ratio = 10.;
    TwoSpring::VectorModel model(n, ratio);
    const Operator         H = std::cref(model);

    // Eigenvalues of A = K_N^-1 K_D (real, positive: similar to an SPD
    // matrix); Gauss-Seidel's factor is max lambda, the best constant
    // relaxation 2/(2 + lambda_min + lambda_max) with the factor
    // (lambda_max - lambda_min)/(2 + lambda_max + lambda_min).
    FullMatrix<double> A(n, n);
    model.K_N_inverse.mmult(A, model.K_D);
    LAPACKFullMatrix<double> lapack(n, n);
    lapack = A;
    lapack.compute_eigenvalues();
    double lambda_min = 1e300, lambda_max = 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        lambda_min = std::min(lambda_min, lapack.eigenvalue(i).real());
        lambda_max = std::max(lambda_max, lapack.eigenvalue(i).real());
      }
    const double omega_best = 2. / (2. + lambda_min + lambda_max);
    const double factor_best =
      (lambda_max - lambda_min) / (2. + lambda_max + lambda_min);
    out << "Vector model, n = " << n << ", K_D = " << ratio
        << " k_N diag(0.5 + sin(pi (i + 1/2)/n)), K_N = k_N tridiag(-1, 2.1, "
           "-1):\n"
        << "  eigenvalues of K_N^-1 K_D in [" << std::setprecision(5)
        << lambda_min << ", " << lambda_max << "], best constant omega "
        << omega_best << " (factor " << factor_best << ")\n";

    const Vector<double> exact = model.linear_solution();
    auto                 error = [&](const WindowResult &result) {
      Vector<double> e(result.x_tilde);
      e -= exact;
      return e.l2_norm() / exact.l2_norm();
    };

    std::vector<std::pair<std::string, std::string>> rows;
    {
      ConstantRelaxation gs(1.);
      const WindowResult result = run(H, n, gs, 40);
      // the residual grows like lambda_max^k asymptotically
      const double last =
        result.history[39].status.residual / result.history[38].status.residual;
      out << "  Gauss-Seidel residual factor at k = 39: " << last << '\n';
      check(!result.accepted &&
              std::abs(last - lambda_max) <= 1e-6 * lambda_max,
            "Gauss-Seidel diverges with the factor lambda_max");
      rows.emplace_back("Gauss-Seidel (omega = 1)", "diverges");
    }
    {
      ConstantRelaxation relaxation(omega_best);
      const WindowResult result = run(H, n, relaxation, 400);
      const unsigned int k      = result.iterations - 1;
      const double       factor = std::pow(result.history[k].status.residual /
                                       result.history[0].status.residual,
                                     1. / k);
      out << "  best constant omega: mean residual factor " << factor << '\n';
      check(result.accepted && factor <= factor_best * (1. + 1e-6),
            "best constant relaxation converges at most at the factor "
            "(lambda_max - lambda_min)/(2 + lambda_max + lambda_min)");
      check(error(result) <= 1e-8, "best constant omega: x = x*");
      rows.emplace_back("constant omega_best",
                        std::to_string(result.iterations));
    }
    {
      AitkenRelaxation   aitken(0.5);
      const WindowResult result = run(H, n, aitken, 100);
      check(result.accepted && error(result) <= 1e-8, "Aitken converges to x*");
      rows.emplace_back("Aitken (omega_init = 0.5)",
                        std::to_string(result.iterations));
    }
    for (const auto filter :
         {IQNILS::Filter::none, IQNILS::Filter::QR1, IQNILS::Filter::QR2})
      {
        const double tolerance = (filter == IQNILS::Filter::QR1 ? 1e-6 : 1e-2);
        IQNILS       iqn(0.1, 0, 100, filter, tolerance);
        const WindowResult result = run(H, n, iqn, 100);
        const std::string  name   = std::string("IQN-ILS (") +
                                 (filter == IQNILS::Filter::none ? "no filter" :
                                  filter == IQNILS::Filter::QR1  ? "QR1 1e-6" :
                                                                   "QR2 1e-2") +
                                 ")";
        out << "  " << name << ": " << result.iterations << " iterations, "
            << iqn.n_filtered_columns() << " columns filtered, error "
            << error(result) << '\n';
        // Without filtering, Anderson acceleration on a linear problem is
        // GMRES: at most n quasi-Newton steps after the relaxation step.
        // QR2 at 1e-2 drops a nearly dependent column and may need more.
        if (filter == IQNILS::Filter::QR2)
          check(result.accepted && result.iterations <= 2 * (n + 1) &&
                  error(result) <= 1e-8,
                name + " converges to x* in <= 2 (n + 1) iterations");
        else
          check(result.accepted && result.iterations <= n + 2 &&
                  error(result) <= 1e-8,
                name + " converges to x* in <= n + 2 iterations");
        rows.emplace_back(name, std::to_string(result.iterations));
      }
    out << "Iterations per method, vector (n = 4, k_D/k_N ~ " << ratio
        << "):\n";
    for (const auto &row : rows)
      out << "  " << std::left << std::setw(28) << row.first << row.second
          << std::right << '\n';
  }


  /** The optional force test: starting at d* the displacement residual is
   * zero at once, but the force test needs a previous force, so the first
   * window takes a second evaluation (force change at round-off); from a
   * wrong start both tests must hold. */
  void
  force_test()
  {
    const TwoSpring::Scalar model(10.);
    out << "\nForce test (k_D/k_N = 10, force tolerance 1e-8):\n";
    auto operator_with_force =
      [&](const Vector<double> &x, Vector<double> &x_tilde, Vector<double> &f) {
        f.reinit(1);
        f[0] = model.force(x[0]);
        model(x, x_tilde);
      };
    Vector<double> exact(1);
    exact[0] = model.solution();
    for (const double force_tolerance : {0., 1e-8})
      {
        ConvergenceCriterion criterion(1e-10, 1e-15, force_tolerance, 30);
        AitkenRelaxation     aitken(0.5);
        const WindowResult   at_solution =
          iterate_window(operator_with_force, exact, aitken, criterion);
        const ConvergenceStatus &last = at_solution.history.back().status;
        out << "  force tolerance " << force_tolerance
            << ", start at d*: " << at_solution.iterations
            << " iterations, force checked " << last.force_checked
            << ", change "
            << (last.force_change <= 1e-12 ? "<= 1e-12" : "> 1e-12") << '\n';
        check(at_solution.accepted &&
                at_solution.iterations == (force_tolerance > 0. ? 2 : 1) &&
                last.force_checked == (force_tolerance > 0.) &&
                last.force_change <= 1e-12,
              "start at d*: 1 iteration, 2 with the force test (change at "
              "round-off)");
        // next window from 0: the force of the last window is the first
        // reference; it converges with both tests
        const WindowResult       from_zero = iterate_window(operator_with_force,
                                                      Vector<double>(1),
                                                      aitken,
                                                      criterion);
        const ConvergenceStatus &end       = from_zero.history.back().status;
        out << "  force tolerance " << force_tolerance
            << ", start at 0: " << from_zero.iterations << " iterations\n";
        check(from_zero.accepted && end.force_change <= force_tolerance &&
                std::abs(from_zero.x_tilde[0] - model.solution()) <=
                  1e-10 * model.solution(),
              "start at 0: converges with the force change within tolerance");
      }
  }
} // namespace


int
main()
{
  out << std::setprecision(6);
  scalar_model();
  vector_model();
  force_test();
  return 0;
}
