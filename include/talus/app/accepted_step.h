#ifndef talus_app_accepted_step_h
#define talus_app_accepted_step_h

#include <talus/base/energy_jump_monitor.h>
#include <talus/base/time_control.h>
#include <talus/io/checkpointing.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <functional>
#include <ostream>
#include <string>

namespace Talus
{
  /**
   * The end of an accepted step, the same in the MPM and the coupled time
   * loop (doc/checkpoint.md):
   * - material points were lost and `abort on lost material points` is set
   *   (@p lost_points_stop holds the message): write a checkpoint of the
   *   step, name it in the message and throw ExcSimulationFailed;
   * - `stop after minutes` is reached before the end: the same with the
   *   wall-time limit;
   * - otherwise call @p before_checkpoint (load balancing of the MPM loop;
   *   not after the last step) and write the scheduled checkpoint when one
   *   is due.
   * @p write_checkpoint writes one and returns its path. The checkpoint
   * tests' TALUS_DEBUG_KILL_AFTER_STEP = n kills the process here, after
   * step n, as SIGKILL would.
   */
  void
  end_accepted_step(const IO::Checkpointing &checkpointing,
                    const unsigned int       step,
                    const double             time,
                    const bool               finished,
                    std::string              lost_points_stop,
                    const std::function<std::string(const std::string &reason)>
                                                &write_checkpoint,
                    const std::function<void()> &before_checkpoint,
                    const MPI_Comm               communicator);

  /**
   * Call @p solve (the attempts at the step after step @p step, with their
   * retries). An exception that leaves it, other than the ones with their
   * own message (ExcSimulationFailed, ExcInvalidInput,
   * ExcVerificationFailed), e.g. from deal.II, Trilinos, a material model
   * or the memory, becomes ExcSimulationFailed naming the step, the
   * exception's text and a checkpoint of the last accepted step written by
   * @p write_checkpoint (when checkpoints are enabled): the attempts change
   * only trial state (MPMProblem::solve_step(),
   * GaussSeidelCoupling::solve_step() and the coupled step's rejection), so
   * the committed state is still whole. On more than one rank no
   * checkpoint is written, because the exception may be one rank's alone
   * while the others wait in a collective call; the message then names the
   * directory of the scheduled checkpoints instead.
   */
  void
  solve_or_checkpoint(
    const std::function<void()> &solve,
    const IO::Checkpointing     &checkpointing,
    const unsigned int           step,
    const double                 time,
    const std::function<std::string(const std::string &reason)>
                  &write_checkpoint,
    const MPI_Comm communicator);

  /**
   * The sentence a failure message of a time loop ends with when
   * checkpoints are enabled: the last accepted step @p step at @p time is
   * in the checkpoint @p path, to be resumed with changed parameters.
   */
  std::string
  failure_checkpoint_note(const unsigned int step,
                          const double       time,
                          const std::string &path);

  /**
   * The log line of a rejected attempt at the step after step @p step from
   * @p time with step size @p dt: "  step n at t = ... s rejected (dt =
   * ... s): <reason>", followed by "; retrying with dt = ... s" when
   * @p retry_dt is positive, and a newline, with the number format of
   * @p format (the log's stream). The same in both time loops.
   */
  std::string
  rejected_step_line(const std::ostream &format,
                     const unsigned int  step,
                     const double        time,
                     const double        dt,
                     const std::string  &reason,
                     const double        retry_dt = 0.);

  /**
   * The log line of a step of size @p dt rejected by the error control
   * of @p time_control because its estimated error @p error exceeds the
   * tolerance (rejected_step_line() with the retry step
   * TimeControl::next_step()). The same in both time loops.
   */
  std::string
  error_rejected_step_line(const std::ostream &format,
                           const TimeControl  &time_control,
                           const double        dt,
                           const double        error);

  /**
   * A step of size @p dt whose energy balance jumps (@p jump, from
   * EnergyJumpMonitor::describe_jump()) with 'energy jump action' =
   * reject: halve the step tried (TimeControl::reject() from @p dt, the
   * failure path of both time loops) and return the log line of the
   * rejection with the retry step. If no halving is left ('maximum step
   * halvings', 'minimum time step'), @p time_control is left as it was
   * and the string is empty: the caller commits the step and prints
   * energy_jump_kept_line().
   */
  std::string
  reject_energy_jump(const std::ostream &format,
                     TimeControl        &time_control,
                     const double        dt,
                     const std::string  &jump);

  /**
   * The warning that the step of size @p dt from the time of
   * @p time_control is committed with its energy jump @p jump because the
   * step cannot be halved again.
   */
  std::string
  energy_jump_kept_line(const std::ostream &format,
                        const TimeControl  &time_control,
                        const double        dt,
                        const std::string  &jump);

  /**
   * The check of a trial step committed on a copy of the committed state
   * ('energy jump action' = reject), the same in both time loops: if the
   * step of size @p dt with the energy balance @p balance and the scale
   * @p scale (EnergyJumpMonitor::is_jump(), @p points_lost) jumps and can
   * be halved, @p time_control is set for the retry and the rejection line
   * is returned: the caller restores its copy and prints it. Otherwise the
   * step is kept and the string is empty; a jump kept because no halving is
   * left prints energy_jump_kept_line() on @p out and counts @p kept.
   */
  std::string
  energy_jump_rejection(const EnergyJumpMonitor    &monitor,
                        const double                balance,
                        const double                scale,
                        const bool                  points_lost,
                        dealii::ConditionalOStream &out,
                        TimeControl                &time_control,
                        const double                dt,
                        unsigned int               &kept);
} // namespace Talus

#endif
