#ifndef talus_app_run_verification_h
#define talus_app_run_verification_h

#include <talus/boundaries/boundary_particles.h>
#include <talus/mpm/diagnostics.h>
#include <talus/mpm/material_points.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace Talus
{
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

    /** Read or write with a boost archive (checkpoints). */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      ar &time &displacement_error &exact_displacement &stress_error
        &stress_rms_error;
    }
  };

  /**
   * The checks of subsection "Verification" of an MPM run against the
   * references the parameter file gives: the displacement (and stress)
   * of the material points against an exact solution at the report
   * times, the drift of kinetic + strain + gravitational energy, the
   * change of the energy balance B (Diagnostics::energy_balance()), the
   * largest penetration into the boundaries, the summed reaction at the
   * end, the ratio J_t / J_n of the boundaries' impulse (Coulomb's law),
   * the speed at the end or over a final window, and the period of the
   * momentum's oscillation. It also declares subsection "Convergence
   * study" (run_parameter_file() reads it).
   *
   * The time loop (Simulation) calls record_step() and measure_due()
   * after every accepted step and report() after the last; what the
   * records hold over the run goes into the loop's checkpoints
   * (serialize_records(), serialize_errors()).
   */
  template <int dim>
  class RunVerification
  {
  public:
    explicit RunVerification(const MPI_Comm communicator);

    /** Declare subsections "Verification" and "Convergence study". */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Read subsection "Verification"; @p boundaries for the check that a
     * reaction has boundaries to come from, @p end_time the last report
     * time.
     */
    void
    parse_parameters(dealii::ParameterHandler                 &prm,
                     const Boundaries::BoundaryParticles<dim> &boundaries,
                     const double                              end_time);

    /** Whether the points are measured against an exact solution. */
    bool
    compares() const
    {
      return compare;
    }

    /** The report times (sorted, the end time included) [s]. */
    const std::vector<double> &
    report_times() const
    {
      return times;
    }

    /** Start the records of a new run from its @p initial state. */
    void
    start(const MPM::Diagnostics<dim> &initial);

    /**
     * Record the accepted step of size @p dt to @p time, with the
     * diagnostics @p d of the committed state (collective: the speed of
     * the points in the final window).
     */
    void
    record_step(const MPM::Diagnostics<dim>    &initial,
                const MPM::Diagnostics<dim>    &d,
                const MPM::MaterialPoints<dim> &points,
                const double                    time,
                const double                    dt,
                const double                    end_time);

    /**
     * Measure the errors against the exact solution at the report times
     * reached by the step of size @p dt to @p time (collective).
     */
    void
    measure_due(const double                    time,
                const double                    dt,
                const MPM::MaterialPoints<dim> &points);

    /**
     * The largest released gravitational energy max|G(t) - G(0)| of the
     * steps recorded so far [J].
     */
    double
    released() const
    {
      return max_released;
    }

    /** The errors measured so far. */
    const std::vector<VerificationErrors> &
    errors() const
    {
      return measured;
    }

    /**
     * Print the errors, the reactions of the boundaries at the end and
     * every check against the file's references; returns whether all of
     * them passed (collective). @p gravity and @p time for the impulse
     * of gravity over the run.
     */
    bool
    report(dealii::ConditionalOStream               &pcout,
           const MPM::Diagnostics<dim>              &initial,
           const MPM::Diagnostics<dim>              &final_state,
           const Boundaries::BoundaryParticles<dim> &boundaries,
           const MPM::MaterialPoints<dim>           &points,
           const dealii::Tensor<1, dim>             &gravity,
           const double                              time) const;

    /**
     * The records over the run a checkpoint carries, in the order of the
     * time loop's archive (checkpoint format: the loop writes its own
     * counters between these and serialize_errors()).
     */
    template <class Archive>
    void
    serialize_records(Archive &ar)
    {
      ar &window_speed &window_speed_time &max_drift &max_balance_change
        &max_released &max_penetration &last_momentum &crossings;
    }

    /** The errors measured so far and the next report time's index. */
    template <class Archive>
    void
    serialize_errors(Archive &ar)
    {
      ar &measured &next_report;
    }

  private:
    /** The errors at time @p t (collective). */
    VerificationErrors
    measure(const double t, const MPM::MaterialPoints<dim> &points);

    /** The largest speed of a material point (collective) [m/s]. */
    double
    max_point_speed(const MPM::MaterialPoints<dim> &points) const;

    MPI_Comm communicator;

    // what the file asks for
    bool                                   compare = false;
    std::vector<double>                    times;
    dealii::Functions::ParsedFunction<dim> exact_displacement;
    dealii::Functions::ParsedFunction<dim> exact_stress;
    bool                                   compare_stress       = false;
    bool                                   compare_center       = false;
    double                                 u_tolerance          = 0.;
    double                                 u_relative_tolerance = 0.;
    double                                 s_tolerance          = 0.;
    bool                                   stress_rms           = false;
    bool                                   axial_stress         = false;
    dealii::Tensor<1, dim>                 stress_axis;
    double                                 reference_period   = 0.;
    double                                 period_tolerance   = 0.;
    double                                 drift_tolerance    = 0.;
    double                                 speed_limit        = 0.;
    double                                 speed_window       = 0.;
    bool                                   speed_of_grid      = false;
    double                                 balance_tolerance  = 0.;
    double                                 penetration_limit  = 0.;
    double                                 expected_reaction  = 0.;
    double                                 reaction_tolerance = 0.;
    bool                                   impulse_check      = false;
    dealii::Tensor<1, dim>                 impulse_normal;
    double                                 impulse_ratio           = 0.;
    double                                 impulse_ratio_tolerance = 0.;

    // the records over the run
    double window_speed = 0., window_speed_time = 0.;
    double max_drift = 0., max_balance_change = 0., max_released = 0.;
    double max_penetration = 0.;
    double last_momentum   = 0.;
    /** Zero crossings of the momentum in x [s]. */
    std::vector<double>             crossings;
    std::vector<VerificationErrors> measured;
    std::size_t                     next_report = 0;
  };
} // namespace Talus

#endif
