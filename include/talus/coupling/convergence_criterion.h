#ifndef talus_coupling_convergence_criterion_h
#define talus_coupling_convergence_criterion_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <string>

namespace Talus
{
  namespace Coupling
  {
    /**
     * The state of the interface iteration after one evaluation of the
     * fixed-point operator, for the coupled step's log.
     */
    struct ConvergenceStatus
    {
      /** Evaluations of the operator in this window (1 after the first). */
      unsigned int iterations = 0;

      /** ‖r‖ = ‖x̃ − x‖ [m]. */
      double residual = 0.;

      /** ‖x̃‖ [m]. */
      double reference = 0.;

      /** The displacement tolerance max(abs_tol, rel_tol ‖x̃‖) [m]. */
      double tolerance = 0.;

      /** ‖f_k − f_{k−1}‖ / ‖f_k‖ [-] (0 if both are zero); only with a force
       * tolerance and a force passed to check(). */
      double force_change = 0.;

      /** The force test was made. */
      bool force_checked = false;

      /** Equilibrium defect of a Robin iteration, |k (x̃ − x)| / |f| [-]
       * (iterate_window() with an equilibrium defect; then it must also be
       * below the relative tolerance). */
      double defect = 0.;

      /** The defect test was made. */
      bool defect_checked = false;

      /** Both tests hold. */
      bool converged = false;

      /** Not converged and the iterations reached the maximum: the step
       * must be rejected (or, for a weak scheme, accepted as is). */
      bool maximum_reached = false;

      /** One line: "k = 3  |r| = 1.2e-08 <= 1.0e-07  df/f = ..." */
      std::string
      to_string() const;
    };


    /**
     * Convergence test of the Dirichlet-Neumann interface iteration, the
     * absolute-or-relative measure of preCICE (v3.4,
     * AbsoluteOrRelativeConvergenceMeasure) on the interface displacement:
     * @f[ \|\tilde x_k - x_k\| \le \max(\epsilon_a,\ \epsilon_r \|\tilde
     * x_k\|),
     * @f]
     * optionally together with a relative test on the interface force handed
     * from the MPM to the structure,
     * ‖f_k − f_{k−1}‖ ≤ ε_f ‖f_k‖, where f_{k−1} is the previous iteration's
     * force (in the first iteration of a window, the force of the last
     * converged window). The absolute tolerance ε_a > 0 makes a zero
     * interface (before contact: x = x̃ = 0) converge at once.
     *
     * Parameters (subsection `Coupling`): `relative tolerance`, `absolute
     * tolerance` [m], `force tolerance` (0: no force test), `maximum coupling
     * iterations`.
     */
    class ConvergenceCriterion
    {
    public:
      ConvergenceCriterion(const double       relative_tolerance = 1e-6,
                           const double       absolute_tolerance = 1e-10,
                           const double       force_tolerance    = 0.,
                           const unsigned int maximum_iterations = 50);

      /** Declare the entries in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse from the current subsection (@p subsection names it in error
       * messages): tolerances > 0 (force tolerance >= 0), maximum
       * iterations >= 1, else ExcInvalidInput. */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection = "Coupling");

      /** Begin a window: the iteration count restarts; the last force seen
       * is kept as the reference of the first force test. */
      void
      start_window();

      /** Forget the stored force (step rejected or first window). */
      void
      reset();

      /**
       * Test the iterate @p x against the operator's output @p x_tilde, and
       * @p force (may be null) against the previous one. Counts an
       * iteration.
       */
      ConvergenceStatus
      check(const dealii::Vector<double> &x,
            const dealii::Vector<double> &x_tilde,
            const dealii::Vector<double> *force = nullptr);

      unsigned int
      maximum_iterations() const;

      double
      relative_tolerance() const;

      double
      absolute_tolerance() const;

      /** Read or write (boost archive @p archive) the state carried from
       * window to window: the last force (a checkpoint). */
      template <class Archive>
      void
      serialize_state(Archive &archive)
      {
        archive &iterations &previous_force &have_force;
      }

    private:
      double                 relative;
      double                 absolute;
      double                 force_relative;
      unsigned int           max_iterations;
      unsigned int           iterations = 0;
      dealii::Vector<double> previous_force;
      bool                   have_force = false;
    };
  } // namespace Coupling
} // namespace Talus

#endif
