#ifndef talus_base_energy_jump_monitor_h
#define talus_base_energy_jump_monitor_h

#include <deal.II/base/parameter_handler.h>

#include <optional>
#include <string>

namespace Talus
{
  /**
   * A warning for a committed step whose energy balance jumps (subsection
   * "Time", 'energy jump warning'; doc/theory.md, "Energy accounts").
   *
   * The balance B (kinetic + strain + gravitational energy plus every
   * booked dissipation, and for the coupled problem the structure's
   * energies and work) is constant for a scheme that books everything it
   * takes out; from step to step it drifts by round-off and by the
   * trapezoidal quadrature of the booked terms. A step whose Newton
   * iteration wandered far from its start can converge to a spurious
   * solution of the discrete equations that creates or destroys energy:
   * in the 2D flagship study (doc/verification.md, "Flexible barrier
   * (2D): convergence and sensitivity") one 10 ms step created 6.6 kJ/m,
   * kicked a group of points from 4.7 to 10-14 m/s, and they hit the net
   * 0.25 s later. After each committed step assess() compares the change
   * of B in the step with the energy moved so far,
   * @f[ |B_{n+1} - B_n| > f E_\text{scale} \quad\text{and}\quad
   *     |B_{n+1} - B_n| > c \frac{1}{n} \sum_{k < n} |B_{k+1} - B_k|, @f]
   * where E_scale is the largest released gravitational energy plus the
   * kinetic energy and c the outlier factor (the steady drift of the
   * booking, e.g. friction on a soft penalty, is not a jump), and returns a
   * warning line naming the step.
   *
   * With 'energy jump action' = reject the time loop also rejects such a
   * step: it commits the trial step on a copy of the committed state
   * (MPMProblem::save_state(), for the coupled problem both fields and the
   * coupling), asks is_jump() (which changes none of the statistics), and
   * if the step jumps restores the copy and retries the step with half the
   * time step, as a step whose Newton iteration failed ('maximum step
   * halvings'); when no halving is left the step is committed with a
   * warning. Only committed steps enter the statistics (assess()).
   *
   * Off with f = 0. The first four steps after the start or a resume are
   * not assessed (B_n and the mean change are not known to the monitor).
   */
  class EnergyJumpMonitor
  {
  public:
    /** What the time loop does with a step that jumps. */
    enum class Action
    {
      /** commit it and print the warning of assess() */
      warn,
      /** reject it and retry with half the time step */
      reject
    };

    /** Declare the entries in the current subsection ("Time"). */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse subsection "Time". */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    /**
     * After the committed step @p step ending at @p time: @p balance is
     * the energy balance B [J], @p scale the energy moved so far [J]. An
     * empty string, or the warning line (with its newline). A step in which
     * material points left the grid (@p points_lost; their energy leaves
     * B, and the loss is reported on its own) is not assessed and does not
     * count in the mean change.
     */
    std::string
    assess(const unsigned int step,
           const double       time,
           const double       balance,
           const double       scale,
           const bool         points_lost = false);

    /**
     * Whether the trial step with the energy balance @p balance [J] and the
     * energy moved @p scale [J] (arguments as for assess()) is a jump
     * against the committed steps assessed so far. Changes nothing: the
     * statistics include committed steps only (assess()).
     */
    bool
    is_jump(const double balance,
            const double scale,
            const bool   points_lost = false) const;

    /**
     * The jump of a step with @p balance and @p scale for a log line: "an
     * energy jump of ... J (... % of the energy moved so far, ... times the
     * mean change per step before)".
     */
    std::string
    describe_jump(const double balance, const double scale) const;

    /** Whether a step that jumps is rejected ('energy jump action' =
     * reject and the monitor on). */
    bool
    rejects() const
    {
      return action == Action::reject && fraction > 0.;
    }

    /** The number of steps warned about so far. */
    unsigned int
    n_warnings() const
    {
      return warnings;
    }

    /**
     * Read or write the state (checkpoints): the changes seen so far, the
     * last balance and the warnings, so that a resumed run judges its
     * steps as the uninterrupted one would.
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      bool   has_last = last_balance.has_value();
      double last     = has_last ? *last_balance : 0.;
      ar &sum_of_changes &n_changes &has_last &last &warnings;
      last_balance = has_last ? std::optional<double>(last) : std::nullopt;
    }

  private:
    /** f, the fraction of the energy moved ('energy jump warning'). */
    double fraction = 0.03;

    /** c ('energy jump outlier factor'). */
    double outlier_factor = 100.;

    /** 'energy jump action'. */
    Action action = Action::warn;

    /** Sum and number of the changes |B_{k+1} - B_k| so far. */
    double       sum_of_changes = 0.;
    unsigned int n_changes      = 0;

    /** B of the last assessed step. */
    std::optional<double> last_balance;

    unsigned int warnings = 0;
  };
} // namespace Talus

#endif
