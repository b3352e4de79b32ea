#include <talus/base/input.h>
#include <talus/coupling/convergence_criterion.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "range_checks.h"

namespace Talus
{
  namespace Coupling
  {
    std::string
    ConvergenceStatus::to_string() const
    {
      char line[200];
      std::snprintf(line,
                    sizeof(line),
                    "k = %u  |r| = %.3e %s %.3e",
                    iterations,
                    residual,
                    residual <= tolerance ? "<=" : "> ",
                    tolerance);
      std::string s(line);
      if (force_checked)
        {
          std::snprintf(line, sizeof(line), "  df/f = %.3e", force_change);
          s += line;
        }
      if (defect_checked)
        {
          std::snprintf(line, sizeof(line), "  |k dx|/|f| = %.3e", defect);
          s += line;
        }
      if (converged)
        s += "  converged";
      else if (maximum_reached)
        s += "  maximum iterations reached";
      return s;
    }


    ConvergenceCriterion::ConvergenceCriterion(
      const double       relative_tolerance,
      const double       absolute_tolerance,
      const double       force_tolerance,
      const unsigned int maximum_iterations)
      : relative(relative_tolerance)
      , absolute(absolute_tolerance)
      , force_relative(force_tolerance)
      , max_iterations(maximum_iterations)
    {}


    void
    ConvergenceCriterion::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      prm.declare_entry("maximum coupling iterations",
                        "50",
                        Integer(),
                        "Largest number of interface iterations (solves of "
                        "both sides) per time step [-], >= 1; a step that "
                        "has not converged then is rejected.");
      prm.declare_entry("relative tolerance",
                        "1e-6",
                        Double(),
                        "Converged when |x~ - x| <= max(absolute tolerance, "
                        "relative tolerance |x~|), x the interface "
                        "displacement given to the MPM, x~ the one the "
                        "structure returns [-], > 0.");
      prm.declare_entry("absolute tolerance",
                        "1e-10",
                        Double(),
                        "Absolute tolerance of the interface displacement "
                        "residual [m], > 0; it makes an interface without "
                        "load (before contact) converge at once.");
      prm.declare_entry("force tolerance",
                        "0",
                        Double(),
                        "Relative change of the interface force between two "
                        "iterations, |f_k - f_k-1| <= tol |f_k|, required "
                        "in addition [-], >= 0; 0: not checked.");
    }


    void
    ConvergenceCriterion::parse_parameters(dealii::ParameterHandler &prm,
                                           const std::string        &subsection)
    {
      max_iterations = internal::get_integer_at_least(
        prm, subsection, "maximum coupling iterations", 1);
      relative       = get_positive(prm, subsection, "relative tolerance");
      absolute       = get_positive(prm, subsection, "absolute tolerance");
      force_relative = get_non_negative(prm, subsection, "force tolerance");
    }


    void
    ConvergenceCriterion::start_window()
    {
      iterations = 0;
    }


    void
    ConvergenceCriterion::reset()
    {
      iterations = 0;
      have_force = false;
    }


    ConvergenceStatus
    ConvergenceCriterion::check(const dealii::Vector<double> &x,
                                const dealii::Vector<double> &x_tilde,
                                const dealii::Vector<double> *force)
    {
      ConvergenceStatus status;
      status.iterations = ++iterations;
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      status.residual  = residual.l2_norm();
      status.reference = x_tilde.l2_norm();
      status.tolerance = std::max(absolute, relative * status.reference);
      bool force_ok    = true;
      if (force_relative > 0. && force != nullptr)
        {
          if (have_force)
            {
              dealii::Vector<double> change(*force);
              change -= previous_force;
              const double change_norm = change.l2_norm();
              const double force_norm  = force->l2_norm();
              status.force_checked     = true;
              status.force_change =
                (change_norm == 0. ? 0. :
                 force_norm > 0.   ? change_norm / force_norm :
                                     std::numeric_limits<double>::infinity());
              force_ok = (change_norm <= force_relative * force_norm);
            }
          else
            force_ok = false; // nothing to compare with yet
          previous_force = *force;
          have_force     = true;
        }
      status.converged = status.residual <= status.tolerance && force_ok;
      status.maximum_reached =
        !status.converged && iterations >= max_iterations;
      return status;
    }


    unsigned int
    ConvergenceCriterion::maximum_iterations() const
    {
      return max_iterations;
    }


    double
    ConvergenceCriterion::relative_tolerance() const
    {
      return relative;
    }


    double
    ConvergenceCriterion::absolute_tolerance() const
    {
      return absolute;
    }
  } // namespace Coupling
} // namespace Talus
