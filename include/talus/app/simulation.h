#ifndef talus_app_simulation_h
#define talus_app_simulation_h

#include <talus/app/run_verification.h>
#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <string>
#include <vector>

namespace Talus
{
  /**
   * Errors of a running simulation that are not input errors: a step that
   * cannot be solved even with the smallest allowed step, material points
   * lost when that is forbidden.
   */
  class ExcSimulationFailed : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** A verification run missed its reference values (exit code 3). */
  class ExcVerificationFailed : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * The final deposit of a run against the references of subsection
   * "Deposit profile", one row of a refinement study. Errors without a
   * reference are NaN.
   */
  struct DepositErrors
  {
    double cell_size = 0.; ///< edge of a background cell along x [m]
    double runout    = 0.; ///< L [m]
    /// (L - L_ref)/L_ref with the 'reference runout' [-]
    double runout_error = std::numeric_limits<double>::quiet_NaN();
    /// largest |h - h_ref| at the reference profile's stations [m]
    double max_height_error = std::numeric_limits<double>::quiet_NaN();
    /// root mean square of h - h_ref at those stations [m]
    double rms_height_error = std::numeric_limits<double>::quiet_NaN();
    /// every comparison of the deposit table within its tolerance
    bool passed = true;
  };

  /**
   * The Talus application for one parameter file: builds the background
   * grid, the material points, the constitutive model and the MPM solver
   * the file asks for, and runs the time loop
   * (prepare / solve / commit, with step rejection), writing the
   * progress, the CSV time series and the visualization files.
   */
  template <int dim>
  class Simulation
  {
  public:
    explicit Simulation(const MPI_Comm communicator);

    /** Declare every parameter of a run in @p prm. */
    static void
    declare_parameters(
      dealii::ParameterHandler &prm,
      const unsigned int        n_boundaries =
        Boundaries::BoundaryParticles<dim>::default_boundary_slots);

    /**
     * Run with the parameters in @p prm, on the background grid refined
     * @p refinement times (and the time step halved as often if the
     * convergence study asks for it). Returns the errors at the report
     * times (empty without an exact solution).
     */
    std::vector<VerificationErrors>
    run(dealii::ParameterHandler &prm, const unsigned int refinement = 0);

    /**
     * With @p fatal = false, run() returns normally when the deposit
     * misses its references (the table says so, deposit_errors() records
     * it) instead of throwing ExcVerificationFailed: the levels of a
     * refinement study are judged together. Default: fatal.
     */
    void
    set_deposit_misses_fatal(const bool fatal)
    {
      deposit_misses_fatal = fatal;
    }

    /**
     * Continue the next run() from a checkpoint (IO::Checkpointing):
     * @p path is a checkpoint directory or a directory of checkpoints,
     * whose newest complete one is taken. Empty: start at t = 0 (unless
     * the file sets `resume = true` in subsection `Checkpoint`).
     */
    void
    set_resume(const std::string &path)
    {
      resume_from = path;
    }

    /** The deposit of the last run() (cell size 0 if not measured). */
    const DepositErrors &
    deposit_errors() const
    {
      return deposit_result;
    }

  private:
    MPI_Comm      communicator;
    bool          deposit_misses_fatal = true;
    DepositErrors deposit_result;
    std::string   resume_from;
  };

  /**
   * Read the file, select the dimension and run it (with a convergence
   * study if the file asks for one); with @p resume_from a checkpoint (or
   * a directory of checkpoints) to continue from (Simulation::set_resume()).
   * Returns the exit code.
   */
  int
  run_parameter_file(const std::string &filename,
                     const MPI_Comm     communicator,
                     const std::string &resume_from = "");

  /** Print every parameter with its documentation (both dimensions). */
  void
  print_parameters(std::ostream &out, const std::string &format);
} // namespace Talus

#endif
