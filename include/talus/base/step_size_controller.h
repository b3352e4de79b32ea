#ifndef talus_base_step_size_controller_h
#define talus_base_step_size_controller_h

#include <deal.II/base/parameter_handler.h>

#include <utility>
#include <vector>

namespace Talus
{
  /**
   * Grid norms of one solved (not yet committed) time step from which
   * TruncationErrorControl estimates the local truncation error: mass
   * weighted root mean squares over the grid dofs that carry mass,
   * @f[ \|x\|_M = \Big(\sum_i m_i x_i^2 \Big/ \sum_i m_i\Big)^{1/2}. @f]
   * The MPM solver fills it (MPM::MPMSolver::truncation_error_norms()).
   */
  struct TruncationErrorNorms
  {
    /** ||a_{n+1} - a_n||_M, change of the grid acceleration [m/s^2]. */
    double acceleration_change = 0.;
    /** ||du||_M, the grid displacement increment of the step [m]. */
    double increment = 0.;
    /** The sum of the weights m_i over the dofs of the norms [kg] (kg/m
     * in 2D): the field's share in a mass weighted error of several
     * fields (TruncationErrorControl::mass_weighted_error()). */
    double mass = 0.;
  };


  /**
   * Time step chosen by the local truncation error of the Newmark scheme
   * (Zienkiewicz and Xie 1991, "A simple error estimator and adaptive time
   * stepping procedure for dynamic analysis", Earthquake Engng. Struct.
   * Dyn. 20: 871-887). The displacement error of a Newmark step is
   * estimated from the change of the acceleration over the step,
   * @f[ e_{n+1} \approx \Delta t^2 \left(\beta - \tfrac16\right)
   *     (a_{n+1} - a_n), @f]
   * (for beta = 1/6, where this vanishes, the bound
   * @f$ \tfrac16 \Delta t^2 |a_{n+1} - a_n| @f$ of a scheme without the
   * third-order cancellation; the stability check of NewmarkBeta, beta
   * >= gamma/2 >= 1/4, keeps beta away from 1/6 today). The error of the
   * step is measured relative to the step's own displacement increment,
   * with the mass weighted RMS over the grid dofs with mass
   * (TruncationErrorNorms) and an absolute floor u_0 ('error displacement
   * floor'):
   * @f[ \eta = \frac{\Delta t^2 |\beta - \tfrac16|\, \|a_{n+1} - a_n\|_M}
   *                 {\|\Delta u\|_M + u_0}. @f]
   * For a harmonic motion of circular frequency omega, eta = |beta - 1/6|
   * (omega dt)^2: the relative period error of the Newmark scheme per step,
   * so that the global (phase) error after a time T is about omega T eta
   * and follows the tolerance linearly. The RMS (not the largest nodal
   * value) keeps nodes with a tiny mass at the edge of the body, whose
   * accelerations are noisy in MPM, from controlling the step.
   *
   * With eta = O(dt^2), the next step is
   * @f[ \Delta t_{new} = \Delta t\, \min\big(f_{max}, \max\big(f_{min},
   *     s\, (\eta_{tol}/\eta)^{1/2}\big)\big), @f]
   * safety factor s, growth and shrink limits f_max, f_min, and within
   * ['minimum time step', 'maximum time step']. A step with
   * eta > r eta_tol (r: 'error rejection factor', default 2) is rejected
   * and repeated with the smaller step; a step at the minimum step is
   * accepted whatever its error.
   *
   * Only the displacement error is measured: with gamma > 1/2 the scheme
   * is first order in the velocity, which this estimate does not see.
   */
  class TruncationErrorControl
  {
  public:
    /** Declare the entries in the current subsection ("Time"). */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Parse from the current subsection ("Time"); rejects bad values.
     * @p time_step is the initial step ('time step') [s], the default of
     * the largest step.
     */
    void
    parse_parameters(dealii::ParameterHandler &prm, const double time_step);

    /** Whether the step is chosen by the error ('error tolerance' > 0). */
    bool
    enabled() const
    {
      return tolerance > 0.;
    }

    /**
     * The normalised error eta of a step of size @p dt with Newmark
     * parameter @p beta from the grid norms @p norms (see the class
     * documentation).
     */
    double
    error(const TruncationErrorNorms &norms,
          const double                dt,
          const double                beta) const;

    /**
     * The normalised error of one step of size @p dt shared by several
     * fields (the coupled step: the MPM grid and a dynamic structure),
     * each given by its norms and Newmark beta, as one mass weighted RMS
     * over the dofs of all fields:
     * @f[ \eta = \frac{\big(\sum_f m_f e_f^2 / \sum_f m_f\big)^{1/2}}
     *                  {\big(\sum_f m_f \|\Delta u\|_f^2 / \sum_f
     *                   m_f\big)^{1/2} + u_0}, \qquad
     *     e_f = \Delta t^2 |\beta_f - \tfrac16|\, \|a_{n+1} -
     *     a_n\|_f, @f]
     * m_f = TruncationErrorNorms::mass. The error of the whole system
     * rather than the larger of the fields' relative errors
     * ('coupled error norm = mass weighted'): the modes of a light
     * structure count by their share of the mass, so that a light string
     * excited by the interface does not alone set the step.
     */
    double
    mass_weighted_error(
      const std::vector<std::pair<TruncationErrorNorms, double>> &fields,
      const double                                                dt) const;

    /** Whether a step of error @p eta must be repeated with a smaller one. */
    bool
    rejects(const double eta) const
    {
      return eta > rejection_factor * tolerance;
    }

    /**
     * The factor s (eta_tol/eta)^(1/2), clamped to [f_min, f_max] (f_max
     * for eta = 0).
     */
    double
    step_factor(const double eta) const;

    double tolerance        = 0.;   ///< eta_tol [-]; 0: off
    double safety           = 0.9;  ///< s [-]
    double growth_limit     = 2.;   ///< f_max [-]
    double shrink_limit     = 0.2;  ///< f_min [-]
    double rejection_factor = 2.;   ///< r [-]
    double floor            = 1e-9; ///< u_0 [m]
    double max_dt           = 0.;   ///< largest step [s]
    /** 'coupled error norm = mass weighted': a coupled step's error by
     * mass_weighted_error(), else the larger of the fields' errors. */
    bool mass_weighted_coupled = false;
  };
} // namespace Talus

#endif
