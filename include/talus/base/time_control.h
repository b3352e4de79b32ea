#ifndef talus_base_time_control_h
#define talus_base_time_control_h

#include <talus/base/step_size_controller.h>

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace Talus
{
  /**
   * Newmark-beta time integration of the grid (founding paper eq. 9-10):
   * @f[ a_{n+1} = \frac{\Delta u - \Delta t\, v_n
   *     - \Delta t^2 (\tfrac12 - \beta) a_n}{\beta \Delta t^2},\qquad
   *     v_{n+1} = v_n + \Delta t\,[(1-\gamma) a_n + \gamma a_{n+1}]. @f]
   * The default beta = 1/4, gamma = 1/2 (average acceleration) is
   * unconditionally stable and conserves energy for linear problems.
   */
  class NewmarkBeta
  {
  public:
    NewmarkBeta(const double beta = 0.25, const double gamma = 0.5);

    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse from the current subsection ("Time"); rejects beta <= 0 and
     * gamma < 1/2 or combinations that are not unconditionally stable. */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    /** Acceleration at t_{n+1} from the increment. */
    double
    acceleration(const double du,
                 const double v_n,
                 const double a_n,
                 const double dt) const
    {
      return (du - dt * v_n - dt * dt * (0.5 - beta) * a_n) / (beta * dt * dt);
    }

    /** Velocity at t_{n+1}. */
    double
    velocity(const double v_n,
             const double a_n,
             const double a_new,
             const double dt) const
    {
      return v_n + dt * ((1. - gamma) * a_n + gamma * a_new);
    }

    /** d a_{n+1} / d(du) = 1/(beta dt^2): factor of the mass in the tangent. */
    double
    mass_factor(const double dt) const
    {
      return 1. / (beta * dt * dt);
    }

    double beta;
    double gamma;
  };


  /**
   * Time stepping: end time, initial (or fixed) step, and the rejection of
   * failed steps. A step whose Newton iteration fails is retried with half
   * the step, at most 'maximum step halvings' times, each retry reported;
   * after that, or when the halved step would fall below 'minimum time
   * step' (default: the initial step x min(1e-3, 2^-'maximum step
   * halvings')), the run stops with an error. A fixed step returns to its
   * value after the halved step succeeded; with 'adaptive time step' the step
   * grows back by a factor 2 (never above the initial step) after 'steps before
   * growth' successful steps, and the minimum keeps a step that is
   * rejected more often than it grows from ratcheting down until the run
   * stalls.
   *
   * With 'error tolerance' > 0 the step is chosen by the estimated local
   * truncation error instead (TruncationErrorControl, member
   * error_control): the caller passes the error of every solved step to
   * assess_error(), which rejects it or sets the next step; the halving
   * of steps whose Newton iteration fails stays as the safety net, and
   * the steps land exactly on the event times (add_event_times(),
   * set_event_interval()) and the end time. Without it the fixed (or
   * 'adaptive time step') stepping above is unchanged and ignores the
   * events.
   */
  class TimeControl
  {
  public:
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse subsection "Time" (including the Newmark parameters). */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    /**
     * Step to attempt next: never beyond the end time. With the error
     * control never beyond the next event either: the step before an
     * event is shortened to land on it (two equal steps when one would
     * leave less than the step for the next).
     */
    double
    next_step() const;

    /** The attempted step failed: halve it. Returns false if the number
     * of halvings is exhausted or the halved step would be smaller than
     * min_dt. */
    bool
    reject();

    /**
     * Error control only: the step of size @p step_taken converged with
     * the estimated error @p error (TruncationErrorControl::error()). Sets
     * the next step, dt step_factor(error) within [min_dt, max_dt] (the
     * growth limit relative to the proposed step, so that a step
     * shortened for an event does not hold the next one back, the shrink
     * limit relative to the step taken), and
     * returns false if the step must be repeated (the error exceeds the
     * rejection factor times the tolerance and the step is above min_dt);
     * then accept() must not be called.
     */
    bool
    assess_error(const double step_taken, const double error);

    /** The attempted step of size @p step_taken was accepted: advance
     * time. A fixed step returns to 'time step' after a halved step. */
    void
    accept(const double step_taken);

    /** Error control: times the steps must land on (report times). */
    void
    add_event_times(const std::vector<double> &times);

    /**
     * Error control: the steps land on every multiple of @p interval (the
     * output interval; 0: none).
     */
    void
    set_event_interval(const double interval);

    /** The next event after the current time (at most the end time). */
    double
    next_event() const;

    bool
    finished() const;

    /**
     * Read or write the state of the time stepping with a boost archive
     * (checkpoints): time, step size, step number, halvings and the
     * successes since the last cut. The parameters (end time, initial and
     * minimum step, ...) come from the parameter file.
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      ar &time &dt &step &halvings &successes_since_cut;
    }

    double       time                = 0.;
    double       end_time            = 1.;
    double       initial_dt          = 0.1;
    double       dt                  = 0.1;
    double       min_dt              = 0.1 * 1e-3;
    unsigned int step                = 0;
    unsigned int halvings            = 0;
    unsigned int max_halvings        = 5;
    bool         adaptive            = false;
    unsigned int steps_before_growth = 10;
    unsigned int successes_since_cut = 0;
    NewmarkBeta  newmark;
    /** The step chosen by the error ('error tolerance' > 0). */
    TruncationErrorControl error_control;
    /** Error control: the error of the last assessed step [-]. */
    double last_error = 0.;
    /** Error control: steps rejected for their error so far. */
    unsigned int error_rejections = 0;

  private:
    std::vector<double> event_times;
    double              event_interval = 0.;
  };
} // namespace Talus

#endif
