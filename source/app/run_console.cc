#include <talus/app/run_console.h>

#include <deal.II/base/utilities.h>

#include <iostream>

namespace Talus
{
  namespace
  {
    bool
    read_test_mode(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      const bool test_mode = prm.get_bool("test mode");
      prm.leave_subsection();
      return test_mode;
    }
  } // namespace


  RunConsole::RunConsole(dealii::ParameterHandler &prm,
                         const MPI_Comm            communicator)
    : root(dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
    , test_mode(read_test_mode(prm))
    , pcout(std::cout, root)
    , timer(pcout,
            test_mode ? dealii::TimerOutput::never :
                        dealii::TimerOutput::summary,
            dealii::TimerOutput::wall_times)
  {}
} // namespace Talus
