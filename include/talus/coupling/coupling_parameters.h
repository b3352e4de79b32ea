#ifndef talus_coupling_coupling_parameters_h
#define talus_coupling_coupling_parameters_h

#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/predictor.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
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
     */
    WindowResult
    iterate_window(
      const std::function<void(const dealii::Vector<double> &x,
                               dealii::Vector<double>       &x_tilde,
                               dealii::Vector<double> &force)> &fixed_point,
      const dealii::Vector<double>                             &x0,
      InterfaceAccelerator                                     &accelerator,
      ConvergenceCriterion                                     &criterion,
      const bool                                                strong = true);
  } // namespace Coupling
} // namespace Talus

#endif
