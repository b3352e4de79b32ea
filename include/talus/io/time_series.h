#ifndef talus_io_time_series_h
#define talus_io_time_series_h

#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/mpi.h>

#include <fstream>
#include <string>
#include <vector>

namespace Talus
{
  namespace IO
  {
    /**
     * CSV time series written every step by rank 0:
     * step, time, dt, Newton and linear iterations, total mass, momentum
     * (x, y, z; z = 0 in 2D), kinetic, strain and gravitational energy,
     * their sum, and the mass lost through the grid boundary in the step.
     * contrib/plot_time_series.py plots it.
     */
    template <int dim>
    class TimeSeries
    {
    public:
      /**
       * Open the file and write the header; every boundary in
       * @p boundary_names adds the columns <name>_force_x, _y, (_z),
       * <name>_normal_force, <name>_tangential_force, <name>_penetration
       * (reaction of the material on the boundary [N], its normal
       * (compression positive) and tangential resultants [N], largest
       * penetration [m]). With @p error_column (the step chosen by the
       * error, TruncationErrorControl) a last column `error_estimate`
       * holds the estimated relative truncation error of each step [-].
       * With @p n_bodies > 1 each body b adds (before it)
       * body<b>_mass, body<b>_momentum_x, _y, (_z), body<b>_kinetic_energy,
       * body<b>_strain_energy. With @p body_contact_columns
       * (multi-velocity-field contact between bodies) two columns follow
       * the bodies': body_contact_dissipation (minus the work of the contact
       * forces on the bodies since the start [J]) and body_contact_nodes
       * (the nodes in contact at the end of the step).
       */
      void
      open(const std::string              &filename,
           const MPI_Comm                  communicator,
           const std::vector<std::string> &boundary_names       = {},
           const bool                      error_column         = false,
           const unsigned int              n_bodies             = 1,
           const bool                      body_contact_columns = false);

      /** One row; @p error is written only with the error column. */
      void
      write(const unsigned int           step,
            const double                 time,
            const double                 dt,
            const MPM::NewtonResult     &newton,
            const MPM::Diagnostics<dim> &diagnostics,
            const double                 lost_mass,
            const double                 error = 0.);

      /**
       * Copy everything written so far to the file @p target (rank 0,
       * after a flush; nothing on the other ranks): what a checkpoint
       * keeps of the time series. A file copy, so that the memory of a
       * long run does not grow with its series (doc/performance.md,
       * "Memory over long runs").
       */
      void
      copy_to(const std::string &target);

      /**
       * Continue the time series of a resumed run: replace the file
       * @p filename by a copy of the file @p saved (what copy_to() wrote
       * into the checkpoint; rows written after the checkpoint by the run
       * that stopped are dropped) and append to it; @p error_column as in
       * open().
       */
      void
      resume(const std::string &filename,
             const MPI_Comm     communicator,
             const std::string &saved,
             const bool         error_column         = false,
             const bool         body_contact_columns = false);

    private:
      std::ofstream file;
      std::string   file_name;
      bool          is_root           = false;
      bool          with_error        = false;
      bool          with_body_contact = false;
    };
  } // namespace IO
} // namespace Talus

#endif
