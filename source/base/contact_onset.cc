#include <talus/base/contact_onset.h>
#include <talus/base/input.h>

#include <algorithm>
#include <cmath>

namespace Talus
{
  void
  ContactOnsetEvent::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry(
      "contact onset time step",
      "0",
      dealii::Patterns::Double(0.),
      "Longest step over which the active set of boundary contacts (the "
      "boundary particles that carry a reaction: an impact on a floor, a "
      "wall, the barrier) may change sharply [s], >= 0 and at most 'time "
      "step'; 0: off. A longer step in which it changes by more than "
      "'contact onset threshold' is rejected and repeated with a quarter "
      "of its length (at least this step), so that the steps close in on "
      "the onset; afterwards the step grows back by at most x2 per step. "
      "With a fixed step or the step chosen by the error, for 'problem = "
      "mpm' and 'coupled'. Contact with the grid's fixed or slip boundaries "
      "is not seen.");
    prm.declare_entry(
      "contact onset forecast",
      "true",
      dealii::Patterns::Bool(),
      "With 'contact onset time step' > 0: before each step, forecast when "
      "the material points first touch each boundary that no point "
      "touches yet (each point's path at its current speed and under "
      "gravity: to the surface with 'contact side = material points'; "
      "into the cells around the boundary particles' cells with 'contact "
      "side = boundary particles', whose reaction begins when material "
      "reaches them, with uGIMP, cpGIMP and CPDI when the point's domain "
      "does) and shorten a longer "
      "step to that time (at least 'contact onset time step'), so that an "
      "impact is resolved without rejected steps; the check after the "
      "step stays as the safety net. false: the check alone.");
    prm.declare_entry(
      "contact onset threshold",
      "0.5",
      dealii::Patterns::Double(),
      "Relative change |N_new - N_old| / max(N_new, N_old) of the number N "
      "of active boundary contacts within a step above which 'contact "
      "onset time step' applies [-], in [0, 1) (an impact on a free "
      "surface or a lift-off changes it by 1).");
  }


  void
  ContactOnsetEvent::parse_parameters(dealii::ParameterHandler &prm,
                                      const double              time_step)
  {
    prm.enter_subsection("Time");
    onset_dt = prm.get_double("contact onset time step");
    if (onset_dt > time_step)
      InputFile::reject("Time",
                        "contact onset time step",
                        prm.get("contact onset time step"),
                        "at most 'time step' (" + prm.get("time step") + " s)");
    forecast_on = prm.get_bool("contact onset forecast");
    threshold   = prm.get_double("contact onset threshold");
    if (!(threshold >= 0. && threshold < 1.))
      InputFile::reject("Time",
                        "contact onset threshold",
                        prm.get("contact onset threshold"),
                        "a value in [0, 1)");
    prm.leave_subsection();
  }


  bool
  ContactOnsetEvent::assess(TimeControl       &time_control,
                            const double       step_taken,
                            const unsigned int contacts)
  {
    if (!enabled())
      return false;
    trial_contacts = static_cast<int>(contacts);
    trial_step     = step_taken;
    if (committed_contacts < 0)
      return false;
    const double n_old = committed_contacts;
    const double n_new = contacts;
    const double change =
      std::abs(n_new - n_old) / std::max({n_new, n_old, 1.});
    if (change > threshold && step_taken > onset_dt * (1. + 1e-9))
      {
        time_control.dt = std::max(0.25 * step_taken, onset_dt);
        time_control.successes_since_cut = 0;
        growing                          = true;
        ++rejections;
        return true;
      }
    return false;
  }


  bool
  ContactOnsetEvent::forecast(TimeControl &time_control,
                              double       arrival,
                              const bool   onset_in_next_step)
  {
    if (!forecasting())
      return false;
    // the step after one that ended past a forecast entry contains the
    // onset
    if (onset_follows)
      arrival = 0.;
    onset_follows = false;
    if (!(arrival < time_control.next_step()))
      return false;
    const double step = std::max(arrival, onset_dt);
    if (!(step < time_control.next_step() * (1. - 1e-9)))
      return false;
    time_control.dt = step;
    growing         = true;
    onset_follows   = onset_in_next_step && arrival > 0.;
    ++shortened;
    return true;
  }


  void
  ContactOnsetEvent::accepted(TimeControl &time_control)
  {
    if (!enabled())
      return;
    committed_contacts = trial_contacts;
    if (growing && !time_control.error_control.enabled() &&
        !time_control.adaptive)
      {
        // TimeControl::accept() set 'time step' again: grow x2 per step
        time_control.dt = std::min(2. * trial_step, time_control.initial_dt);
        growing         = time_control.dt < time_control.initial_dt;
      }
  }
} // namespace Talus
