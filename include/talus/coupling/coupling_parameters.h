#ifndef talus_coupling_coupling_parameters_h
#define talus_coupling_coupling_parameters_h

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/predictor.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace Talus
{
  namespace Coupling
  {
    /**
     * Subsection `Coupling` of the parameter file: the scheme and the order
     * of the two solvers, and the parameters of the accelerator
     * (AccelerationParameters), the convergence test (ConvergenceCriterion)
     * and the predictor (InterfacePredictor), each declared and parsed by
     * its own class inside this subsection.
     *
     * - `scheme = strong`: iterate every step until ConvergenceCriterion
     *   holds (implicit, Gauss-Seidel); `weak`: one pass per step (explicit,
     *   staggered; unstable for a strong added-mass effect, k_D > k_N).
     * - `order = MPM first`: the Dirichlet-Neumann order of the founding
     *   paper (the MPM gets the structure's displacement, the structure the
     *   MPM's reactions; the accelerated data are the displacements);
     *   `structure first`: the structure is solved first with the forces of
     *   the last iteration (Kratos' mpm_fem_beam order).
     */
    class CouplingParameters
    {
    public:
      enum class Scheme
      {
        strong,
        weak
      };

      enum class Order
      {
        MPM_first,
        structure_first
      };

      /** Declare subsection `Coupling`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse subsection `Coupling`; bad values throw ExcInvalidInput
       * naming the parameter and the allowed range. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Robin-Neumann stabilisation (Badia, Nobile & Vergara 2008, J.
       * Comput. Phys. 227:7027): the structure is solved with interface
       * springs k_i (x̃_i - x_i) towards the iterate x handed to the MPM,
       * k_i = k_R sum_p N_i(X_p) w_p over the interface particles that
       * carry a force (w_p: their surface measure). The springs
       * vanish at the converged state (x̃ = x): they change how the
       * iteration converges, not its result. With k_R close to the
       * material's interface stiffness the iteration operator's large
       * eigenvalues (a heavy material on a light barrier: the added-mass
       * effect of the Dirichlet-Neumann scheme) shrink below one.
       * 'Robin stiffness': 0 (plain Dirichlet-Neumann), a value k_R
       * [Pa/m], 'inertia': k_R = rho d / (beta dt^2), the inertia of a
       * layer of material of depth d = 'Robin depth' cells behind the
       * interface, or 'automatic': that inertia plus the stiffness M / d of
       * the layer (M: the material's p-wave modulus), the material's
       * impedance for smooth and for short-wave interface motions. Both
       * are put in series with the smallest penalty beta of the interface
       * boundaries that impose their condition by a penalty alone (not
       * Nitsche, augmented Lagrangian or Lagrange multipliers): k_R =
       * 1/(1/k_layer + 1/beta).
       */
      bool   robin_inertia   = false;
      bool   robin_elastic   = false; ///< add M / d ('automatic')
      double robin_stiffness = 0.;    ///< k_R [Pa/m] when not 'inertia'
      double robin_depth     = 4.;    ///< d [cells] for 'inertia'
      /**
       * Directions of the Robin springs ('Robin directions'): every
       * component of the interface DoFs, or only the normal one (k n n^T,
       * lumped to its diagonal k n_d^2 with n the direction of the
       * point's reaction), where the interface transmits no tangential
       * force (slip, frictionless contact): a tangential spring there has
       * no counterpart in the material and only slows the iteration.
       */
      enum class RobinDirections
      {
        all,
        normal,
        automatic ///< normal if every interface boundary is slip or contact
      };
      RobinDirections robin_directions = RobinDirections::all;
      /**
       * Restart the accelerator when the active set changes within a window
       * ('restart at contact change'): the set of interface points that
       * carry a force differs from that of the window's previous
       * iteration. The map x -> x~ is then another (piecewise) affine map
       * and the Robin springs change with it, so the quasi-Newton columns
       * of the iterates before the change (and of past windows, and
       * IQN-IMVJ's Jacobian) describe another operator; after the restart
       * the model is built from iterates of the present active set only.
       */
      bool restart_at_contact_change = false;
      /**
       * 'initial Jacobian = interface stiffness': IQN-ILS starts every
       * window from the inverse Jacobian of the linearised interface
       * problem, built from the MPM's interface stiffness K_D (the
       * Schur complement of its tangent on the interface, by one
       * back-substitution per interface DoF,
       * MPM::MPMSolver::linearised_boundary_reactions()) and the
       * structure's tangent (GaussSeidelCoupling, doc/coupling.md).
       */
      bool interface_stiffness_jacobian = false;
      /** The MPM's Newton of an iteration starts from the last increment. */
      bool warm_start = false;
      /**
       * 'interface force in time = end of step': the unilateral contact
       * force of the interface boundaries acts with its end value over the
       * step, on the material (MPM::ContactTimeIntegration) and on the
       * structure (Structure::DynamicSolver::interface_force_at_end), so
       * that the interface does no work besides the penalty's booked
       * dissipation. Default: the trapezoidal rule of both Newmark schemes.
       */
      bool interface_force_at_end = false;

      Scheme                 scheme = Scheme::strong;
      Order                  order  = Order::MPM_first;
      AccelerationParameters acceleration;
      ConvergenceCriterion   criterion;
      InterfacePredictor     predictor;
    };


    /** One iteration of a window: the convergence test and, if the
     * iteration went on, what the accelerator did. */
    struct IterationRecord
    {
      ConvergenceStatus status;
      AccelerationInfo  acceleration;
    };


    /**
     * Thrown by a fixed-point operator whose evaluation failed (a field's
     * Newton iteration did not converge for the interface displacement it
     * was given); iterate_window() may retry from the last good iterate.
     */
    struct EvaluationFailed : std::runtime_error
    {
      using std::runtime_error::runtime_error;
    };


    /** Largest number of restarts at a change of the active set in one
     * window (iterate_window()). */
    constexpr unsigned int maximum_contact_restarts = 6;


    /** Outcome of iterate_window(). */
    struct WindowResult
    {
      /** Evaluations of the fixed-point operator (solves of both sides). */
      unsigned int iterations = 0;

      /** Converged (strong) or accepted after its one pass (weak). */
      bool accepted = false;

      /** The last iterate x and the operator's output x̃ for it (the
       * structure's interface displacement of the accepted state). */
      dealii::Vector<double> x;
      dealii::Vector<double> x_tilde;

      std::vector<IterationRecord> history;

      /**
       * Safeguarded restarts: evaluations at an accelerated iterate that
       * failed and were replaced by a relaxed step from the last good one.
       */
      unsigned int restarts = 0;

      /** Restarts of the accelerator at a change of the active set
       * (@p active_set_changed of iterate_window()). */
      unsigned int contact_restarts = 0;
    };


    /**
     * The interface iteration of one time window (doc/coupling.md):
     * @code
     * x = x0; repeat: x̃ = H(x); status = criterion.check(x, x̃, f);
     *                  if converged: accelerator.end_window(x, x̃); stop
     *                  if maximum reached: stop (not accepted)
     *                  x = accelerator.compute_next(x, x̃)
     * @endcode
     * @p fixed_point evaluates x̃ = H(x) (MPM with the displacement x, then
     * the structure with the MPM's reactions), and may set the interface
     * force for the optional force test (left empty: no force test). With
     * @p strong false (weak scheme) the window is accepted after one
     * evaluation. A window that is not accepted leaves the accelerator as
     * it was after its last step: call reset() before repeating the step.
     *
     * Safeguard: when the evaluation at an accelerated iterate throws
     * EvaluationFailed (the MPM's Newton fails because the accelerator
     * extrapolated the interface into the material, typical when contact
     * switches), the accelerator forgets what it learned (reset()) and
     * the next iterate is its first, relaxed step from the last iterate
     * that could be evaluated; at most 2 such restarts per window, then
     * (or at the first iterate) the exception is passed on and the step
     * is rejected.
     *
     * With @p equilibrium_defect (a Robin iteration: the structure was
     * solved with springs k (x̃ − x), so x̃ − x is small although the
     * structure alone is out of equilibrium by the spring force), the
     * relative defect it returns after each evaluation must also be at
     * most the criterion's relative tolerance.
     *
     * With @p active_set_changed (asked after every successful evaluation
     * but the window's first: whether the set of interface points that
     * carry a force differs from that of the previous evaluation), the
     * accelerator is reset at each change, so that its model is built
     * from iterates of one active set ('restart at contact change'), at
     * most maximum_contact_restarts times per window.
     */
    WindowResult
    iterate_window(
      const std::function<void(const dealii::Vector<double> &x,
                               dealii::Vector<double>       &x_tilde,
                               dealii::Vector<double> &force)> &fixed_point,
      const dealii::Vector<double>                             &x0,
      InterfaceAccelerator                                     &accelerator,
      ConvergenceCriterion                                     &criterion,
      const bool                                                strong = true,
      const std::function<double()> &equilibrium_defect                = {},
      const std::function<bool()>   &active_set_changed                = {});
  } // namespace Coupling
} // namespace Talus

#endif
