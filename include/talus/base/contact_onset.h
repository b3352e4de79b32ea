#ifndef talus_base_contact_onset_h
#define talus_base_contact_onset_h

#include <talus/base/time_control.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

namespace Talus
{
  /**
   * Contact onset as an event of the time stepping (subsection "Time",
   * 'contact onset time step' > 0; doc/theory.md, "Step chosen by the
   * truncation error", and doc/verification.md): a step in which the
   * active set of boundary contacts changes sharply is shortened, so that
   * the instant of an impact (on a floor, a wall, the barrier) is resolved
   * by short steps whatever the step before it.
   *
   * The time loop passes the number N of active boundary contacts of every
   * solved step (the boundary particles that carry a reaction,
   * count_active_contacts()) to assess(). With N_n that of the committed
   * step, the change
   * @f[ c = \frac{|N_{n+1} - N_n|}{\max(N_{n+1}, N_n, 1)} @f]
   * is 1 at an impact on a free surface (N_n = 0 < N_{n+1}) and at a
   * lift-off. A step with c > theta ('contact onset threshold') that is
   * longer than the onset step Delta t_c ('contact onset time step') is
   * rejected and repeated with max(Delta t / 4, Delta t_c): the steps close
   * in on the onset from before (a shortened step that ends before the
   * onset is accepted, the next one grows by at most x2 and is rejected
   * again if it reaches the onset), until the step that contains the onset
   * is at most Delta t_c. After it the step grows back by at most a factor
   * 2 per step: with the error control (TruncationErrorControl) by its
   * growth limit relative to the shortened step, with a fixed step by
   * after_accept() up to 'time step'. ('adaptive time step' keeps its own
   * growth after 'steps before growth' steps.)
   *
   * Forecast ('contact onset forecast', on by default): before each step
   * the time loop asks MPM::ContactForecast when the material will first
   * touch each boundary that no point touches yet, and passes the
   * earliest arrival t_a to forecast(): a planned step longer than t_a is
   * shortened to max(t_a, Delta t_c). The step then ends at the predicted
   * onset (or is at most Delta t_c if the onset is nearer), and the next
   * one, whose forecast is close to zero (material-point contact) or
   * which the forecast marks as the onset step (a boundary checked on the
   * boundary particles' side), is Delta t_c: the onset is
   * resolved without the rejected solves of the check after the step,
   * which stays as the safety net for what the forecast does not see
   * (forces other than gravity, a moving surface, contact between
   * bodies).
   *
   * Off (the default, Delta t_c = 0) nothing changes: the runs with a fixed
   * step give the same output as without the event.
   */
  class ContactOnsetEvent
  {
  public:
    /** Declare the entries in the current subsection ("Time"). */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse subsection "Time"; @p time_step is 'time step' [s], the
     * largest onset step. */
    void
    parse_parameters(dealii::ParameterHandler &prm, const double time_step);

    /** Whether the event is on ('contact onset time step' > 0). */
    bool
    enabled() const
    {
      return onset_dt > 0.;
    }

    /**
     * The step of size @p step_taken was solved with @p contacts active
     * boundary contacts. Returns true if it must be repeated: then the
     * next step of @p time_control is set (TimeControl::dt) and
     * TimeControl::accept() must not be called. Otherwise (also always
     * when off, and at the first step, whose active set at the start is
     * not known) the count is kept for accepted().
     */
    bool
    assess(TimeControl       &time_control,
           const double       step_taken,
           const unsigned int contacts);

    /** Whether the step is shortened ahead of a forecast onset. */
    bool
    forecasting() const
    {
      return enabled() && forecast_on;
    }

    /**
     * Before a step: the material is forecast to touch a boundary without
     * contacts after @p arrival [s] (MPM::ContactForecast). A planned step
     * of @p time_control longer than that is shortened to max(arrival,
     * Delta t_c) (TimeControl::dt); it grows back after the onset as
     * after a rejection. @p onset_in_next_step: the contact begins in the
     * step after the one that contains the arrival (a boundary checked on
     * the boundary particles' side, whose reaction begins in the step that
     * starts with material in the cells around its particles); the next
     * step is then Delta t_c whatever its forecast. Returns whether the
     * step was shortened.
     */
    bool
    forecast(TimeControl &time_control,
             const double arrival,
             const bool   onset_in_next_step = false);

    /**
     * After TimeControl::accept(): the step's active set is the committed
     * one; a fixed step grows back after an onset (x2 per step up to
     * 'time step').
     */
    void
    accepted(TimeControl &time_control);

    /**
     * Read or write the state (checkpoints): the active contacts of the
     * committed and the last solved step, the growth after an onset, the
     * rejections.
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      ar &committed_contacts &trial_contacts &growing &rejections &shortened
        &onset_follows;
    }

    /** Delta t_c [s]; 0: off. */
    double onset_dt = 0.;
    /** theta [-]. */
    double threshold = 0.5;
    /** Steps rejected at a contact onset so far. */
    unsigned int rejections = 0;
    /** Whether a step is shortened ahead of a forecast onset. */
    bool forecast_on = true;
    /** Steps shortened ahead of a forecast onset so far. */
    unsigned int shortened = 0;

  private:
    /** Active contacts of the committed step (-1: not known yet) and of
     * the last solved one. */
    int committed_contacts = -1;
    int trial_contacts     = -1;
    /** A fixed step grows back after an onset. */
    bool growing = false;
    /** The next step contains a forecast onset (forecast() with
     * onset_in_next_step): it is Delta t_c. */
    bool onset_follows = false;
    /** The last solved step [s]. */
    double trial_step = 0.;
  };

  /**
   * The number of active boundary contacts (ContactOnsetEvent): the
   * entries of @p reactions (MPM::MPMSolver::boundary_reactions() of the
   * solved step) with a nonzero reaction, summed over the ranks of
   * @p communicator (a boundary particle touched by material points on
   * two ranks counts twice). Collective.
   */
  template <class Reactions>
  unsigned int
  count_active_contacts(const Reactions &reactions, const MPI_Comm communicator)
  {
    unsigned int n = 0;
    for (const auto &r : reactions)
      if (r.second.norm_square() > 0.)
        ++n;
    return dealii::Utilities::MPI::sum(n, communicator);
  }
} // namespace Talus

#endif
