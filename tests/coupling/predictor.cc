// InterfacePredictor: extrapolation of the converged interface displacement
// to the next step, against closed forms:
//  - none returns the last value;
//  - linear is exact on a linear history, quadratic on a quadratic one,
//    also with unequal steps (a halved step after a rejection);
//  - linear extrapolation of x = t^2 with a constant step dt is off by
//    exactly 2 dt^2 (the second difference);
//  - with fewer stored windows the order drops (one value: constant).

#include <talus/coupling/predictor.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <string>
#include <vector>

#include "check.h"

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


  /** Two components: a history f(t) and 2 f(t) - 1e-3. */
  Vector<double>
  sample(const std::function<double(double)> &f, const double t)
  {
    Vector<double> x(2);
    x[0] = f(t);
    x[1] = 2. * f(t) - 1e-3;
    return x;
  }


  /** Largest error of the prediction at t_next after the history times. */
  double
  error(const InterfacePredictor::Order      order,
        const std::function<double(double)> &f,
        const std::vector<double>           &times,
        const double                         t_next)
  {
    InterfacePredictor predictor(order);
    for (const double t : times)
      predictor.add_converged(t, sample(f, t));
    Vector<double> e = predictor.predict(t_next);
    e -= sample(f, t_next);
    return e.linfty_norm();
  }
} // namespace


int
main()
{
  out << std::setprecision(6);
  const auto constant  = [](const double) { return 3e-3; };
  const auto linear    = [](const double t) { return 1e-3 + 0.5 * t; };
  const auto quadratic = [](const double t) {
    return 1e-3 + 0.5 * t - 20. * t * t;
  };
  const std::vector<double> uniform = {0.01, 0.02, 0.03, 0.04};
  const std::vector<double> halved  = {0.01, 0.02, 0.025, 0.0275};
  using Order                       = InterfacePredictor::Order;

  check(error(Order::none, constant, uniform, 0.05) <= 1e-18,
        "none: the last value (exact on a constant history)");
  const double none_error = error(Order::none, linear, uniform, 0.05);
  out << "  none on a linear history: error " << none_error
      << " (slope x dt = " << 0.5 * 0.01 << ")\n";
  check(std::abs(none_error - 0.5 * 0.01 * 2.) <= 1e-15,
        "none lags by slope x dt (component 2: twice)");

  for (const auto *times : {&uniform, &halved})
    {
      const double      t_next = times->back() + 0.01;
      const std::string steps  = (times == &uniform ? "uniform" : "unequal");
      check(error(Order::linear, linear, *times, t_next) <= 1e-15,
            "linear exact on a linear history, " + steps + " steps");
      check(error(Order::quadratic, linear, *times, t_next) <= 1e-15,
            "quadratic exact on a linear history, " + steps + " steps");
      check(error(Order::quadratic, quadratic, *times, t_next) <= 1e-15,
            "quadratic exact on a quadratic history, " + steps + " steps");
    }

  const double dt           = 0.01;
  const double linear_error = error(Order::linear, quadratic, uniform, 0.05);
  out << "  linear on x = ... - 20 t^2: error " << linear_error
      << ", closed form 2 x 20 dt^2 x 2 = " << 2. * 20. * dt * dt * 2. << '\n';
  check(std::abs(linear_error - 2. * 20. * dt * dt * 2.) <= 1e-14,
        "linear extrapolation of a quadratic is off by the second "
        "difference");

  // Fewer stored windows than the order needs: constant, then linear.
  {
    InterfacePredictor predictor(Order::quadratic);
    predictor.add_converged(0.01, sample(quadratic, 0.01));
    Vector<double> e = predictor.predict(0.02);
    e -= sample(quadratic, 0.01);
    check(predictor.n_stored() == 1 && e.linfty_norm() == 0.,
          "one stored window: the prediction is that value");
    predictor.add_converged(0.02, sample(linear, 0.02));
    predictor.clear();
    predictor.add_converged(0.01, sample(linear, 0.01));
    predictor.add_converged(0.02, sample(linear, 0.02));
    e = predictor.predict(0.03);
    e -= sample(linear, 0.03);
    check(predictor.n_stored() == 2 && e.linfty_norm() <= 1e-15,
          "two stored windows: linear extrapolation");
  }
  return 0;
}
