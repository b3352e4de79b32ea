#ifndef talus_mpm_body_contact_h
#define talus_mpm_body_contact_h

#include <deal.II/base/parameter_handler.h>

namespace Talus
{
  namespace MPM
  {
    /**
     * Contact between the bodies of material points (subsection "Body
     * contact").
     *
     * 'single velocity field' (default): all bodies share the grid's one
     * velocity field (standard MPM); bodies stick where their points share
     * a node, about a cell before they touch.
     *
     * 'multi-velocity field': each body has its own velocity field on the
     * grid (Bardenhagen, Brackbill and Sulsky 2000, CMAME 187, 529-541),
     * the grid element becomes FE_Q(1)^(dim n_bodies) and the points of
     * body b assemble only into field b. At a node where bodies a and b
     * both carry mass the contact normal (from a to b) is the outward
     * normal of the body with the larger nodal volume gradient g_b =
     * sum_{p in b} V_p grad N_I(x_p) (Nairn 2013), g_a / |g_a| or
     * -g_b / |g_b|, unless the other or their normalised sum separates
     * the bodies' point domains by more than a margin ('normal margin',
     * 5 % of the cell diameter; a gradient tilted by points crossing a
     * cell). The choice is continuous: the candidates' biased gaps are
     * s_i = g_i + b_i, g_i the gap along candidate i, b the margin times
     * the preference of a's (w) and b's (1 - w) normal, w rising linearly
     * from 0 to 1 as (|g_a| - |g_b|) / (|g_a| + |g_b|) goes from -1 % to
     * +1 %, and b_2 = 0; the normal is the normalised sum_i w_i n_i with
     * w_i = max(0, 1 - (max_j s_j - s_i) / tau), tau = margin / 4, and
     * the gap sum_i w_i g_i / sum_i w_i, so that mirrored nodes get
     * mirrored normals whatever the rounding (a hard switch broke the
     * mirror symmetry of two colliding disks). The
     * gap is measured from the points' domains (Nairn 2013,
     * CMES 92, 271-299, separation from the particles rather than from the
     * nodal velocities): g_0 = min_{p in b} (x_p . n - l_p) - max_{p in a}
     * (x_p . n + l_p) over the points whose cells hold the node, with l_p
     * half the edge of the point's current domain, (V_0 det F)^(1/dim) / 2.
     * In the implicit step the gap follows the nodal displacement
     * increments, g = g_0 + (du_b - du_a) . n, and a penalty pressure
     * p = k max(0, -g) pushes the two fields apart (no tension: they
     * separate freely), with k = 'penalty factor' min(m_a, m_b) / (beta
     * dt^2), the inertia stiffness of the lighter field at the node. The
     * force is part of the Newton residual with its exact tangent (the
     * active set follows the iterate). Coulomb friction between bodies
     * ('friction coefficient') acts on the tangential increment
     * (du_b - du_a)_t with a stick penalty k and slip at mu p.
     *
     * With 'carry contact forces' the force of a node that ended the last
     * step in contact is carried into the next (an incremental penalty):
     * p = p_n - k (du_b - du_a) . n and the stick trial f_t = P f_t,n -
     * k (du_b - du_a)_t, with f_n the committed force on b (P the
     * projector onto the current tangent plane); else the penalty starts
     * unloaded in every step, and a body held by another (resting or
     * sticking) moves by F / k in each step to rebuild the force, a creep
     * of about F beta dt / (factor m) per second.
     */
    class BodyContact
    {
    public:
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Parse subsection "Body contact"; @p n_bodies is 'number of bodies'
       * (the multi-velocity field needs two or more).
       */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const unsigned int        n_bodies);

      /** Whether each body has its own velocity field. */
      bool multi_velocity_field = false;
      /** Coulomb friction coefficient between bodies [-]. */
      double friction_coefficient = 0.;
      /** Penalty factor of the normal (and stick) contact stiffness [-]. */
      double penalty_factor = 100.;
      /** Whether contact forces are carried from step to step. */
      bool carry_contact_forces = false;
      /**
       * Preference of the normal of the larger volume gradient, as a
       * fraction of the smallest cell diameter [-].
       */
      double normal_margin = 0.05;
    };
  } // namespace MPM
} // namespace Talus

#endif
