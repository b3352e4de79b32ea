#ifndef talus_app_run_console_h
#define talus_app_run_console_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

namespace Talus
{
  /**
   * What a run prints to and times with, the same for every problem (mpm,
   * coupled): rank 0's standard output (pcout) and its wall-time
   * TimerOutput, silent in `Output/test mode` (the test outputs compare
   * stdout, and timings differ from run to run). TimerOutput summarises
   * rank 0's own wall times, without MPI in its destructor, so a run that
   * stops on an error does not print a warning about skipped
   * communication.
   */
  struct RunConsole
  {
    /** Reads `Output/test mode` from @p prm. */
    RunConsole(dealii::ParameterHandler &prm, const MPI_Comm communicator);

    /** Whether this is rank 0. */
    const bool root;
    /** `Output/test mode`: no timings, no progress lines. */
    const bool                 test_mode;
    dealii::ConditionalOStream pcout;
    dealii::TimerOutput        timer;
  };
} // namespace Talus

#endif
