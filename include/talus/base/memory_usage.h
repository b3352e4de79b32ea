#ifndef talus_base_memory_usage_h
#define talus_base_memory_usage_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <iomanip>
#include <sstream>
#include <string>

namespace Talus
{
  /**
   * The memory line of the end-of-run summary: the peak resident set size
   * (VmHWM of /proc/self/status, read by deal.II's
   * Utilities::System::get_memory_stats()) and the present resident set
   * size (VmRSS) in MB, each the largest over the ranks of @p communicator,
   * and with several ranks their sum. Collective. Where /proc is not
   * available (not Linux), deal.II reports 0. doc/performance.md, "Memory
   * over long runs", uses it to check that the memory stays flat over
   * 10^4 steps.
   */
  inline std::string
  memory_summary(const MPI_Comm communicator)
  {
    dealii::Utilities::System::MemoryStats stats;
    dealii::Utilities::System::get_memory_stats(stats);
    // kB -> MB
    const double peak = stats.VmHWM / 1024., now = stats.VmRSS / 1024.;
    const double max_peak = dealii::Utilities::MPI::max(peak, communicator);
    const double max_now  = dealii::Utilities::MPI::max(now, communicator);
    const double sum_peak = dealii::Utilities::MPI::sum(peak, communicator);
    std::ostringstream text;
    text << std::fixed << std::setprecision(1) << "  memory: peak resident set "
         << max_peak << " MB, resident now " << max_now << " MB";
    if (dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
      text << " (largest rank; peak sum over the ranks " << sum_peak << " MB)";
    text << '\n';
    return text.str();
  }
} // namespace Talus

#endif
