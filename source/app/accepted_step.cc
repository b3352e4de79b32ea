#include <talus/app/accepted_step.h>
#include <talus/app/simulation.h>
#include <talus/base/input.h>

#include <deal.II/base/exceptions.h>

#include <csignal>
#include <cstdlib>
#include <sstream>

namespace Talus
{
  void
  end_accepted_step(const IO::Checkpointing &checkpointing,
                    const unsigned int       step,
                    const double             time,
                    const bool               finished,
                    std::string              lost_points_stop,
                    const std::function<std::string(const std::string &reason)>
                                                &write_checkpoint,
                    const std::function<void()> &before_checkpoint,
                    const MPI_Comm               communicator)
  {
    if (!lost_points_stop.empty())
      {
        if (checkpointing.enabled())
          lost_points_stop += IO::Checkpointing::lost_points_note(
            step, write_checkpoint("failure: material points lost"));
        throw ExcSimulationFailed(lost_points_stop);
      }
    if (checkpointing.stop_due(communicator) && !finished)
      throw ExcSimulationFailed(checkpointing.wall_limit_message(
        step, time, write_checkpoint("wall-time limit")));
    if (!finished && before_checkpoint)
      before_checkpoint();
    if (checkpointing.enabled() && !finished &&
        checkpointing.due(step, communicator))
      write_checkpoint("scheduled");
    // (the kill-and-resume test: die as if killed after this step)
    if (const char *kill = std::getenv("TALUS_DEBUG_KILL_AFTER_STEP"))
      if (std::to_string(step) == kill)
        std::raise(SIGKILL);
  }


  void
  solve_or_checkpoint(
    const std::function<void()> &solve,
    const IO::Checkpointing     &checkpointing,
    const unsigned int           step,
    const double                 time,
    const std::function<std::string(const std::string &reason)>
                  &write_checkpoint,
    const MPI_Comm communicator)
  {
    std::string what;
    try
      {
        solve();
        return;
      }
    catch (const ExcSimulationFailed &)
      {
        throw;
      }
    catch (const ExcInvalidInput &)
      {
        throw;
      }
    catch (const ExcVerificationFailed &)
      {
        throw;
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        what = info.str();
        while (!what.empty() && (what.back() == '\n' || what.back() == ' '))
          what.pop_back();
      }
    catch (const std::exception &e)
      {
        what = e.what();
      }

    std::ostringstream msg;
    msg << "The step after step " << step << " (t = " << time
        << " s) stopped with an exception: " << what << '.';
    if (checkpointing.enabled())
      {
        if (dealii::Utilities::MPI::n_mpi_processes(communicator) == 1)
          {
            try
              {
                msg << " The last accepted step (" << step << ", t = " << time
                    << " s) is in the checkpoint <"
                    << write_checkpoint("failure: exception in the step")
                    << ">: resume from it once the cause is removed.";
              }
            catch (const std::exception &e)
              {
                msg << " Writing a checkpoint of the last accepted step "
                       "failed too: "
                    << e.what();
              }
          }
        else
          msg << " No checkpoint is written after an exception on more "
                 "than one rank (it may be one rank's alone while the others "
                 "wait); the scheduled checkpoints are in <"
              << checkpointing.directory() << ">.";
      }
    throw ExcSimulationFailed(msg.str());
  }


  std::string
  failure_checkpoint_note(const unsigned int step,
                          const double       time,
                          const std::string &path)
  {
    std::ostringstream note;
    note << " The last accepted step (" << step << ", t = " << time
         << " s) is in the checkpoint <" << path
         << ">: change the parameters and resume from it.";
    return note.str();
  }


  std::string
  rejected_step_line(const std::ostream &format,
                     const unsigned int  step,
                     const double        time,
                     const double        dt,
                     const std::string  &reason,
                     const double        retry_dt)
  {
    std::ostringstream line;
    line.copyfmt(format);
    line << "  step " << step + 1 << " at t = " << time
         << " s rejected (dt = " << dt << " s): " << reason;
    if (retry_dt > 0.)
      line << "; retrying with dt = " << retry_dt << " s";
    line << '\n';
    return line.str();
  }


  std::string
  error_rejected_step_line(const std::ostream &format,
                           const TimeControl  &time_control,
                           const double        dt,
                           const double        error)
  {
    std::ostringstream reason;
    reason.copyfmt(format);
    reason << "estimated error " << error << " above the tolerance";
    return rejected_step_line(format,
                              time_control.step,
                              time_control.time,
                              dt,
                              reason.str(),
                              time_control.next_step());
  }


  std::string
  reject_energy_jump(const std::ostream &format,
                     TimeControl        &time_control,
                     const double        dt,
                     const std::string  &jump)
  {
    // halve the step tried (with the error control dt is already the
    // proposal for the next step)
    const double proposed = time_control.dt;
    time_control.dt       = dt;
    if (!time_control.reject())
      {
        time_control.dt = proposed;
        return "";
      }
    return rejected_step_line(format,
                              time_control.step,
                              time_control.time,
                              dt,
                              jump + " ('energy jump action = reject')",
                              time_control.next_step());
  }


  std::string
  energy_jump_kept_line(const std::ostream &format,
                        const TimeControl  &time_control,
                        const double        dt,
                        const std::string  &jump)
  {
    std::ostringstream line;
    line.copyfmt(format);
    line << "  Warning: *** step " << time_control.step + 1
         << " at t = " << time_control.time << " s (dt = " << dt
         << " s) is COMMITTED WITH " << jump
         << ": 'energy jump action = reject' cannot halve the step "
         << "again (" << time_control.halvings << " of 'maximum step "
         << "halvings' = " << time_control.max_halvings
         << " used, 'minimum time step' = " << time_control.min_dt
         << " s in subsection Time) ***\n";
    return line.str();
  }


  std::string
  energy_jump_rejection(const EnergyJumpMonitor    &monitor,
                        const double                balance,
                        const double                scale,
                        const bool                  points_lost,
                        dealii::ConditionalOStream &out,
                        TimeControl                &time_control,
                        const double                dt,
                        unsigned int               &kept)
  {
    if (!monitor.is_jump(balance, scale, points_lost))
      return "";
    const std::string jump = monitor.describe_jump(balance, scale);
    const std::string line =
      reject_energy_jump(out.get_stream(), time_control, dt, jump);
    if (line.empty())
      {
        ++kept;
        out << energy_jump_kept_line(out.get_stream(), time_control, dt, jump);
      }
    return line;
  }
} // namespace Talus
