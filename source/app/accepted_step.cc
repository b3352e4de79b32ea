#include <talus/app/accepted_step.h>
#include <talus/app/simulation.h>

#include <csignal>
#include <cstdlib>

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
} // namespace Talus
