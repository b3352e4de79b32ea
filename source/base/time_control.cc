#include <talus/base/contact_onset.h>
#include <talus/base/energy_jump_monitor.h>
#include <talus/base/input.h>
#include <talus/base/time_control.h>

#include <algorithm>
#include <cmath>

namespace Talus
{
  NewmarkBeta::NewmarkBeta(const double beta, const double gamma)
    : beta(beta)
    , gamma(gamma)
  {}


  void
  NewmarkBeta::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Newmark beta",
                      "0.25",
                      dealii::Patterns::Double(),
                      "Newmark parameter beta [-]; 0 < beta <= 0.5 and "
                      "beta >= gamma/2 (unconditional stability). 0.25: "
                      "average acceleration.");
    prm.declare_entry("Newmark gamma",
                      "0.5",
                      dealii::Patterns::Double(),
                      "Newmark parameter gamma [-]; 0.5 <= gamma <= 1. "
                      "0.5: no numerical damping; larger values damp.");
  }


  void
  NewmarkBeta::parse_parameters(dealii::ParameterHandler &prm)
  {
    beta = prm.get_double("Newmark beta");
    if (!(beta > 0. && beta <= 0.5))
      InputFile::reject("Time",
                        "Newmark beta",
                        prm.get("Newmark beta"),
                        "it must be larger than 0 and at most 0.5");
    gamma = prm.get_double("Newmark gamma");
    if (gamma < 0.5 || gamma > 1.)
      InputFile::reject("Time",
                        "Newmark gamma",
                        prm.get("Newmark gamma"),
                        "it must lie in [0.5, 1]");
    if (2. * beta < gamma - 1e-14)
      InputFile::reject("Time",
                        "Newmark beta",
                        prm.get("Newmark beta"),
                        "beta >= gamma/2 is needed for unconditional "
                        "stability (gamma = " +
                          prm.get("Newmark gamma") + ")");
  }


  void
  TimeControl::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    prm.enter_subsection("Time");
    {
      prm.declare_entry("end time",
                        "1",
                        Double(),
                        "Simulated time at which the run ends [s]; > 0.");
      prm.declare_entry("time step",
                        "0.01",
                        Double(),
                        "Time step [s]; > 0. With an adaptive step this is "
                        "the initial and largest step.");
      prm.declare_entry("adaptive time step",
                        "false",
                        Bool(),
                        "Let the step grow back (x2, up to 'time step') "
                        "after 'steps before growth' accepted steps following "
                        "a rejection.");
      prm.declare_entry("maximum step halvings",
                        "5",
                        Integer(0, 30),
                        "How often a step whose Newton iteration failed is "
                        "retried with half the step before the run stops "
                        "with an error [-], 0 to 30.");
      prm.declare_entry(
        "minimum time step",
        "0",
        Double(0.),
        "Smallest step a halved (or adaptive) step may take [s], >= 0 and "
        "at most 'time step'; 0: 'time step' x min(1e-3, "
        "2^-'maximum step halvings'). A step that fails at this size stops "
        "the run with an error. Without the bound, an adaptive step that "
        "is rejected more often than it grows back (every 'steps before "
        "growth' steps) can ratchet down without limit and the run "
        "stalls.");
      prm.declare_entry("steps before growth",
                        "10",
                        Integer(1),
                        "Accepted steps after a rejection before an adaptive "
                        "step grows again [-], >= 1.");
      NewmarkBeta::declare_parameters(prm);
      TruncationErrorControl::declare_parameters(prm);
      ContactOnsetEvent::declare_parameters(prm);
      EnergyJumpMonitor::declare_parameters(prm);
    }
    prm.leave_subsection();
  }


  void
  TimeControl::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    end_time             = get_positive(prm, "Time", "end time");
    initial_dt           = get_positive(prm, "Time", "time step");
    dt                   = initial_dt;
    adaptive             = prm.get_bool("adaptive time step");
    max_halvings         = prm.get_integer("maximum step halvings");
    steps_before_growth  = prm.get_integer("steps before growth");
    const double minimum = prm.get_double("minimum time step");
    if (minimum > initial_dt)
      InputFile::reject("Time",
                        "minimum time step",
                        prm.get("minimum time step"),
                        "it must not exceed 'time step' (" +
                          prm.get("time step") + " s)");
    min_dt = minimum > 0. ?
               minimum :
               initial_dt * std::min(1e-3, std::ldexp(1., -max_halvings));
    newmark.parse_parameters(prm);
    error_control.parse_parameters(prm, initial_dt);
    if (error_control.enabled() && adaptive)
      InputFile::reject("Time",
                        "adaptive time step",
                        prm.get("adaptive time step"),
                        "it must be false when 'error tolerance' (" +
                          prm.get("error tolerance") +
                          ") chooses the step by the error");
    prm.leave_subsection();
  }


  double
  TimeControl::next_step() const
  {
    if (error_control.enabled())
      {
        const double remaining = next_event() - time;
        if (remaining <= dt * (1. + 1e-8))
          return remaining;
        if (remaining < 2. * dt)
          return remaining / 2.;
        return dt;
      }
    const double remaining = end_time - time;
    // Avoid a sliver of a last step: take it together with this one.
    if (remaining <= dt * (1. + 1e-8))
      return remaining;
    if (remaining < 1.5 * dt)
      return remaining / 2.;
    return dt;
  }


  bool
  TimeControl::reject()
  {
    // (a step shortened for an event: halve what was tried)
    if (error_control.enabled())
      dt = std::min(dt, next_step());
    if (halvings >= max_halvings || dt / 2. < min_dt * (1. - 1e-12))
      return false;
    ++halvings;
    dt /= 2.;
    successes_since_cut = 0;
    return true;
  }


  bool
  TimeControl::assess_error(const double step_taken, const double error)
  {
    const auto  &c = error_control;
    const double raw =
      error > 0. ? c.safety * std::sqrt(c.tolerance / error) : c.growth_limit;
    last_error = error;
    if (c.rejects(error) && step_taken > min_dt * (1. + 1e-12))
      {
        dt = std::max(step_taken * std::max(raw, c.shrink_limit), min_dt);
        ++error_rejections;
        successes_since_cut = 0;
        return false;
      }
    // The growth limit applies to the step proposed before an event
    // shortened step_taken (dt), the shrink limit to the step taken.
    dt = std::clamp(step_taken * raw,
                    step_taken * c.shrink_limit,
                    std::max(dt, step_taken) * c.growth_limit);
    dt = std::max(std::min(dt, c.max_dt), min_dt);
    return true;
  }


  void
  TimeControl::accept(const double step_taken)
  {
    if (error_control.enabled())
      {
        const double event = next_event();
        time += step_taken;
        if (std::abs(event - time) <= 1e-12 * std::max(1., std::abs(event)))
          time = event;
        ++step;
        halvings = 0;
        return;
      }
    time += step_taken;
    if (std::abs(end_time - time) < 1e-12 * end_time)
      time = end_time;
    ++step;
    halvings = 0;
    if (!adaptive)
      dt = initial_dt;
    else if (dt < initial_dt)
      {
        ++successes_since_cut;
        if (adaptive && successes_since_cut >= steps_before_growth)
          {
            dt                  = std::min(2. * dt, initial_dt);
            successes_since_cut = 0;
          }
      }
  }


  void
  TimeControl::add_event_times(const std::vector<double> &times)
  {
    event_times.insert(event_times.end(), times.begin(), times.end());
    std::sort(event_times.begin(), event_times.end());
  }


  void
  TimeControl::set_event_interval(const double interval)
  {
    event_interval = interval;
  }


  double
  TimeControl::next_event() const
  {
    // an event closer than this to the current time is the one just met
    const double tiny  = 1e-12 * std::max(1., end_time);
    double       event = end_time;
    for (const double t : event_times)
      if (t > time + tiny)
        {
          event = std::min(event, t);
          break;
        }
    if (event_interval > 0.)
      {
        const double k = std::floor(time / event_interval + 1e-9) + 1.;
        event          = std::min(event, k * event_interval);
      }
    return event;
  }


  bool
  TimeControl::finished() const
  {
    return time >= end_time - 1e-12 * end_time;
  }
} // namespace Talus
