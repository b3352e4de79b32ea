#ifndef talus_base_eisenstat_walker_h
#define talus_base_eisenstat_walker_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace Talus
{
  /**
   * Forcing terms of an inexact Newton method: the relative tolerance
   * eta_k to which the Krylov solver solves the k-th Newton system
   * J_k d_k = -R_k, |R_k + J_k d_k| <= eta_k |R_k|, chosen from the
   * residual's contraction so that early iterations, far from the
   * solution, are solved loosely and the last ones tightly enough to keep
   * Newton's convergence (Eisenstat and Walker 1996, "Choosing the forcing
   * terms in an inexact Newton method", SIAM J. Sci. Comput. 17: 16-32,
   * choice 2):
   * @f[ \eta_k = \gamma \left(\frac{|R_k|}{|R_{k-1}|}\right)^{\alpha},
   *     \qquad \eta_0 = \eta_{max}, @f]
   * with the safeguard @f$ \eta_k \leftarrow \max(\eta_k, \gamma
   * \eta_{k-1}^\alpha) @f$ when @f$ \gamma \eta_{k-1}^\alpha > 0.1 @f$ (a
   * sudden drop of the residual does not make one solve much tighter than
   * the last), the bound @f$ \eta_k \le \eta_{max} @f$, and against
   * oversolving in the last iteration (Kelley 1995, "Iterative methods
   * for linear and nonlinear equations", eq. 6.20)
   * @f$ \eta_k \ge \tfrac12 \tau / |R_k| @f$, tau the residual at which
   * Newton stops. The fixed 'linear solver tolerance' is the floor.
   *
   * With the solves inexact, Newton converges superlinearly
   * (order (1 + sqrt 5)/2 for alpha = 2 in the theory's setting) instead
   * of quadratically, at fewer Krylov iterations in all.
   */
  class EisenstatWalkerForcing
  {
  public:
    /** Declare the entries in the current subsection ("Solver"). */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse from the current subsection, named @p subsection in errors. */
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &subsection);

    /** 'linear solver forcing = Eisenstat-Walker'. */
    bool
    enabled() const
    {
      return active;
    }

    /** Forget the previous iteration: a new Newton solve begins. */
    void
    start();

    /**
     * The relative tolerance of the next Krylov solve, at the residual
     * norm @p residual, for a Newton iteration that stops at
     * @p converged_residual, never below @p floor. Updates the history.
     */
    double
    next(const double residual,
         const double converged_residual,
         const double floor);

  private:
    bool   active  = false;
    double eta_max = 0.1;
    double gamma   = 0.9;
    double alpha   = 2.;

    double previous_residual = 0.;
    double previous_eta      = 0.;
  };
} // namespace Talus

#endif
