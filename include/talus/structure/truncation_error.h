#ifndef talus_structure_truncation_error_h
#define talus_structure_truncation_error_h

#include <talus/base/step_size_controller.h>
#include <talus/structure/structure_problem.h>

#include <deal.II/lac/vector.h>

namespace Talus
{
  namespace Structure
  {
    /**
     * The norms of the Zienkiewicz-Xie estimate (TruncationErrorControl)
     * of the solved, not yet committed Bossak-Newmark step of size @p dt
     * of a dynamic structure: the change of the acceleration
     * a_{n+1} - a_n and the displacement increment u_{n+1} - u_n, mass
     * weighted RMS over the unconstrained DoFs with lumped mass,
     * @f[ \|x\|_M = \Big(\sum_i M_i x_i^2 \Big/ \sum_i M_i\Big)^{1/2}, @f]
     * with a_{n+1} from the Newmark formula of DynamicSolver,
     * @f[ a_{n+1} = \frac{u_{n+1} - u_n - \Delta t\, v_n}{\beta \Delta t^2}
     *     - \frac{1/2 - \beta}{\beta} a_n, \qquad
     *     \beta = (1 - \alpha)^2 / 4 @f]
     * (newmark_beta()), u_{n+1} = StructureProblem::displacement() after
     * solve_step(), v_n and a_n the committed velocity and acceleration
     * of the DynamicSolver and @p u_n the committed displacement. Zero
     * for a static structure.
     */
    TruncationErrorNorms
    truncation_error_norms(const StructureProblem       &structure,
                           const dealii::Vector<double> &u_n,
                           const double                  dt);

    /** The Newmark beta = (1 - alpha)^2/4 of the Bossak scheme of the
     * structure's DynamicSolver. */
    double
    newmark_beta(const StructureProblem &structure);
  } // namespace Structure
} // namespace Talus

#endif
