#ifndef talus_mpm_contact_time_integration_h
#define talus_mpm_contact_time_integration_h

#include <deal.II/base/parameter_handler.h>

namespace Talus
{
  namespace MPM
  {
    /**
     * How the penalty forces of unilateral boundary contact (conditions
     * `contact` and `friction` of boundaries at rest, on the boundary
     * particles' or the material points' side) enter Newmark's step
     * (`contact force in time`, subsection `Solver`).
     *
     * `trapezoidal` (default): like every other force, f_c enters the step
     * through the accelerations a_n and a_{n+1}, i.e. as the trapezoidal
     * average (f_c,n + f_c,n+1)/2 for beta = 1/4, gamma = 1/2. A contact that
     * closes within the step needs the impulse to stop the point, ~m v, at
     * the end of the step alone, so a_{n+1} ~ 4 v/dt; the points carry
     * that acceleration into the next step as a_n, where it acts again:
     * the point leaves with up to three times its impact speed. This is
     * the energy blow-up of Newmark's scheme with unilateral contact
     * (Acary 2016, INRIA RR-8602; Doyen, Ern and Piperno 2011, SIAM J.
     * Sci. Comput. 33:223).
     *
     * `end of step`: the contact force acts over the whole step
     * with its end value, as the fully implicit contact force of Doyen,
     * Ern and Piperno (2011), Sec. 3, while the other forces keep
     * Newmark's rule:
     * @f[
     *   \Delta u = \Delta t\,v_n + \Delta t^2[(\tfrac12-\beta) a_n
     *     + \beta a_{n+1}] + \tfrac12 \Delta t^2 a^c_{n+1},\quad
     *   v_{n+1} = v_n + \Delta t[(1-\gamma) a_n + \gamma a_{n+1}]
     *     + \Delta t\, a^c_{n+1},
     * @f]
     * with M a^c = f_c and M a = f_ext - f_int: in the residual of the
     * standard Newmark acceleration the contact force counts 1/(2 beta)
     * times, and the points carry only a (not a^c) into the next step.
     * A point at rest on the boundary stays at rest; a closing contact
     * stops or reflects the point within the step but never speeds it
     * up. For beta = 1/4, gamma = 1/2 the contact's work in the step is
     * f_c,n+1 . du, which exceeds the change of the spring energy by
     * k |dg|^2 / 2 >= 0 (booked as the boundary's dissipation).
     *
     * The step starts from the acceleration of the other forces,
     * a_n = M^-1 (f_ext - f_int)(u_n) ('start acceleration = from
     * forces', required): the points' projected acceleration would miss
     * the contact force that balances the others at a point in contact.
     * Coupling interfaces take it with 'interface force in time = end of
     * step' (subsection Coupling; Boundaries::BoundaryDescription::
     * end_of_step_force), and the structure then takes the interface
     * force with its end value as well (Structure::DynamicSolver). Other
     * boundaries that move (prescribed motion), Nitsche's method, the augmented
     * Lagrangian and Lagrange multipliers, and the bonded (`fixed`) and `slip`
     * conditions keep the trapezoidal rule, and the nodes of the cells of their
     * points the projected start acceleration (the residual at du = 0 does not
     * hold their start force). Not with grid friction boundaries. Lumped
     * mass only; an input in which no boundary would use it is rejected.
     */
    class ContactTimeIntegration
    {
    public:
      /** Declare `contact force in time` in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse it from the current subsection. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * With the end-of-step force, the start acceleration is taken from
       * the forces only at nodes of at least this fraction of the largest
       * nodal mass; lighter nodes keep the projected acceleration.
       */
      static constexpr double light_node_fraction = 1e-2;

      /** Whether unilateral penalty contact uses its end-of-step force. */
      bool end_of_step = false;
    };
  } // namespace MPM
} // namespace Talus

#endif
