#ifndef talus_app_simulation_h
#define talus_app_simulation_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

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

  /** Errors measured against an exact solution at one report time. */
  struct VerificationErrors
  {
    double time               = 0.;
    double displacement_error = 0.; ///< [sum V0 |u - u_ex|^2 / sum V0]^1/2
    /** The same norm of u_ex (|u_ex(X_c)| for the center of mass) [m]. */
    double exact_displacement = 0.;
    double stress_error       = 0.; ///< max |sigma - sigma_ex| / max |sigma_ex|
    /** [sum V0 |sigma - sigma_ex|^2 / sum V0]^1/2 / max |sigma_ex| */
    double stress_rms_error = 0.;
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
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Run with the parameters in @p prm, on the background grid refined
     * @p refinement times (and the time step halved as often if the
     * convergence study asks for it). Returns the errors at the report
     * times (empty without an exact solution).
     */
    std::vector<VerificationErrors>
    run(dealii::ParameterHandler &prm, const unsigned int refinement = 0);

  private:
    MPI_Comm communicator;
  };

  /**
   * Read the file, select the dimension and run it (with a convergence
   * study if the file asks for one). Returns the exit code.
   */
  int
  run_parameter_file(const std::string &filename, const MPI_Comm communicator);

  /** Print every parameter with its documentation (both dimensions). */
  void
  print_parameters(std::ostream &out, const std::string &format);
} // namespace Talus

#endif
