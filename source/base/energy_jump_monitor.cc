#include <talus/base/energy_jump_monitor.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace Talus
{
  void
  EnergyJumpMonitor::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry(
      "energy jump warning",
      "0.03",
      dealii::Patterns::Double(0.),
      "Warn about a committed step whose energy balance (kinetic + strain + "
      "gravitational energy plus the booked dissipation; coupled: of both "
      "fields) changes by more than this fraction of the energy moved so "
      "far (the largest released gravitational energy plus the kinetic "
      "energy) [-]: a sign of a spurious solution of the step (a shorter "
      "'time step' avoids it). 0: off. What happens to such a step: "
      "'energy jump action'.");
    prm.declare_entry(
      "energy jump outlier factor",
      "100",
      dealii::Patterns::Double(1.),
      "A step is warned about only if its change of the energy balance is "
      "also this many times the mean change per step of the steps before "
      "(at least 3 of them) [-], >= 1: the steady drift of the booking "
      "(e.g. friction on a soft penalty) is not a jump.");
    prm.declare_entry(
      "energy jump action",
      "warn",
      dealii::Patterns::Selection("warn|reject"),
      "What the time loop does with a step whose energy balance jumps "
      "('energy jump warning'): warn: commit it and print a warning; "
      "reject: discard it like a step whose Newton iteration failed and "
      "retry it with half the time step (at most 'maximum step halvings' "
      "times, not below 'minimum time step'; then it is committed with a "
      "warning). reject keeps a copy of the committed state in every step "
      "(MPM points, boundary particles; coupled: the structure too).");
  }


  void
  EnergyJumpMonitor::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    fraction       = prm.get_double("energy jump warning");
    outlier_factor = prm.get_double("energy jump outlier factor");
    action =
      prm.get("energy jump action") == "reject" ? Action::reject : Action::warn;
    prm.leave_subsection();
  }


  bool
  EnergyJumpMonitor::is_jump(const double balance,
                             const double scale,
                             const bool   points_lost) const
  {
    if (!(fraction > 0.) || !last_balance || points_lost)
      return false;
    const double jump = std::abs(balance - *last_balance);
    // the mean change per step before this one
    const double mean = n_changes > 0 ? sum_of_changes / n_changes : 0.;
    return scale > 0. && n_changes >= 3 && jump > fraction * scale &&
           jump > outlier_factor * mean;
  }


  std::string
  EnergyJumpMonitor::describe_jump(const double balance,
                                   const double scale) const
  {
    const double       jump = last_balance ? balance - *last_balance : 0.;
    const double       mean = n_changes > 0 ? sum_of_changes / n_changes : 0.;
    std::ostringstream msg;
    msg << "an energy jump of " << jump << " J ("
        << (scale > 0. ? 100. * std::abs(jump) / scale : 0.)
        << " % of the energy moved so far, "
        << (mean > 0. ? std::abs(jump) / mean : 0.)
        << " times the mean change per step before)";
    return msg.str();
  }


  std::string
  EnergyJumpMonitor::assess(const unsigned int step,
                            const double       time,
                            const double       balance,
                            const double       scale,
                            const bool         points_lost)
  {
    const bool                  warn = is_jump(balance, scale, points_lost);
    const std::optional<double> last = last_balance;
    last_balance                     = balance;
    if (!(fraction > 0.) || !last || points_lost)
      return "";
    const double jump = balance - *last;
    // the mean change per step before this one
    const double mean = n_changes > 0 ? sum_of_changes / n_changes : 0.;
    sum_of_changes += std::abs(jump);
    ++n_changes;
    if (!warn)
      return "";
    ++warnings;
    std::ostringstream msg;
    msg << "  Warning: step " << step << " (to t = " << time
        << " s): the energy balance changed by " << jump << " J in this step, "
        << 100. * std::abs(jump) / scale
        << " % of the energy moved so far (released gravitational plus "
           "kinetic energy) and "
        << std::abs(jump) / mean
        << " times the mean change per step before ('energy jump warning' "
           "in subsection Time): the "
           "step's solution may be spurious; a shorter 'time step' avoids "
           "it, unless a contact closed within the step ('contact force in "
           "time = end of step' in subsection Solver).\n";
    return msg.str();
  }
} // namespace Talus
