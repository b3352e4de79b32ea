#ifndef talus_mpm_boundary_contact_state_h
#define talus_mpm_boundary_contact_state_h

#include <talus/boundaries/boundary_particles.h>

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/particles/particle_iterator.h>

#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * A boundary particle in a cell with material, as MPMSolver imposes it
     * for one step (or, with contact side = material points, a material
     * point that may touch a boundary surface).
     *
     * It carries what the force of the particle on the material needs
     * (doc/theory.md, "Boundary particles"): the weight w (surface measure
     * JxW), the penalty beta, the friction coefficient mu, the condition
     * and the inward unit normal n, the prescribed increment du_bar of the
     * step and the gap g_old at its start. The penalty force is
     * f = -beta w g* on the trial gap g* = g_old + du - du_bar (all
     * components for fixed, the normal part for slip and for contact in
     * compression, a Coulomb return of the tangential part for friction);
     * the augmented Lagrangian adds the multiplier lambda, f = lambda -
     * beta w g* (Simo and Laursen 1992, Comput. Struct. 42), Nitsche's
     * method replaces lambda by the material's traction at the particle.
     * The fields below also hold the active-set safeguards of the Newton
     * iteration (frozen, last_state, last_slip, switches).
     */
    template <int dim>
    struct BoundaryPoint
    {
      typename dealii::Particles::ParticleIterator<dim> particle;
      unsigned int                                      boundary;
      double                                            weight;
      double                                            beta;
      double                                            mu;
      Boundaries::Condition                             condition;
      dealii::Tensor<1, dim>                            normal;
      /** Prescribed displacement increment of the step [m]. */
      dealii::Tensor<1, dim> du_bar;
      /**
       * Prescribed acceleration [m/s^2] at the initial time, set only
       * while initialize_acceleration() prepares its step (zero
       * otherwise and for a boundary at rest).
       */
      dealii::Tensor<1, dim> a_bar;
      /** Gap at the start of the step [m]. */
      dealii::Tensor<1, dim> gap_old;
      /**
       * Augmented Lagrangian: the multiplier, a force on the material
       * [N] (the converged force of the last step, then of the last
       * Uzawa update); zero for penalty.
       */
      dealii::Tensor<1, dim> lambda;
      bool                   augmented = false;
      /**
       * Lagrange multiplier method: lambda is a Newton unknown. The
       * assembly keeps the force f(lambda, u) of the iterate and its
       * derivative D = df/dF with respect to the trial force
       * F = lambda - k g (k = beta w), which the saddle-point solve
       * needs; dlambda is the last Newton correction of lambda.
       */
      bool                   monolithic = false;
      dealii::Tensor<1, dim> lm_force;
      dealii::Tensor<2, dim> lm_D;
      dealii::Tensor<1, dim> dlambda;
      /**
       * Changes of state in the current Newton solve; a Lagrange
       * multiplier point that changed 6 times (semi-smooth Newton cycling
       * between two active sets) is held in the more constrained of its
       * states (frozen) for the rest of the solve. A held point that the
       * converged solution does not satisfy is moved to the state the
       * solution asks for, at most three times per step (counted from
       * 100 on).
       */
      unsigned int switches = 0;
      /**
       * Nitsche's method: lambda is w times the traction of the material
       * at the particle, lambda = -w S(u) n, recomputed at each iterate;
       * theta is the symmetry parameter (1 symmetric, 0 incomplete, -1
       * skew).
       */
      bool   nitsche = false;
      double theta   = 1.;
      /**
       * Nitsche: Cauchy stress at the particle at the start of the step
       * (from the nodal projection of the points' stresses) and the
       * gradients of the cell's shape functions at the particle.
       */
      dealii::Tensor<2, dim>              sigma_n;
      std::vector<dealii::Tensor<1, dim>> dN;
      /** Whether sigma_n is known (a node of the cell has mass). */
      bool with_stress = false;
      /**
       * Whether every node of the cell has mass: only then does the
       * stress follow the increment within the step (the massless nodes
       * are held at zero and would read as a strain).
       */
      bool full_cell = false;
      /** Shape values of the cell's nodes at the particle. */
      std::vector<double> N;
      /**
       * For a cell-wise constraint: the particles merged into this
       * point (weight-averaged N, normal, gaps; summed weight) and
       * their weights; empty for a single particle.
       */
      std::vector<typename dealii::Particles::ParticleIterator<dim>> members;
      std::vector<double> member_weights;
      /**
       * Contact state the point is held in (-1: free to change; 0 open,
       * 1 closed/stick, 2 slip while pressed, 3 closed and sliding
       * whatever the normal force); used by the initial acceleration
       * iteration after 3 changes of state and by the Lagrange
       * multiplier Newton iteration against cycling.
       */
      int frozen = -1;
      /** State at the last Newton iterate (-1: none yet). */
      int last_state = -1;
      /** Slip direction (against the tangential force) at the last iterate.
       */
      dealii::Tensor<1, dim> last_slip;
      /**
       * Material-point contact (contact side = material points): particle
       * is the material point, N the shape values of its cell at its
       * contact point x_c, gap_old the geometric normal gap at the start
       * of the step plus the point's tangential stick spring.
       */
      bool on_material_point = false;
      /**
       * Material-point contact: the id of the boundary particle whose
       * tangent line (plane) the point touches; the point's reaction is
       * booked on it (boundary_reactions(), for a coupling interface).
       */
      dealii::types::particle_index surface_particle =
        dealii::numbers::invalid_unsigned_int;
      /**
       * Material-point contact: whether this is the contact with the
       * point's nearest face (which keeps the tangential stick spring)
       * rather than with a further face of a concave corner.
       */
      bool primary = true;
      /**
       * Material-point contact: the normal dashpot of the contact,
       * eta = 'contact damping', a force eta k (g - g_old) . n n added to
       * the spring's -k g while the point is pressed (0: none).
       */
      double damping = 0.;
      /**
       * Penetration over which the dashpot grows from zero to its full
       * value (so that the force is continuous at first contact) [m].
       */
      double damping_onset = 1.;
      /**
       * Whether the force acts with its end-of-step value over the step
       * (unilateral penalty contact of a boundary at rest, with
       * 'contact force in time = end of step'; ContactTimeIntegration).
       */
      bool end_of_step = false;
    };

    /**
     * Force of a boundary particle on the material for a displacement
     * increment du at the particle, f(du) (see BoundaryPoint), its exact
     * derivative df/d(du) (which enters the tangent), the new elastic gap
     * and the contact state (0 open, 1 closed/stick, 2 slip).
     */
    template <int dim>
    struct BoundaryForce
    {
      dealii::Tensor<1, dim> force; ///< on the material [N]
      dealii::Tensor<2, dim> dforce_du;
      dealii::Tensor<1, dim> gap; ///< new elastic gap [m]
      int                    state = 0;
    };

    /**
     * The trial state of the boundary particles at a converged iterate
     * (solve_step()): new gap, multiplier, reaction and state per
     * particle; for material-point contact the point's tangential stick
     * gap and its contribution to the boundary's resultant; the
     * dissipated work. commit_step() writes it (commit_boundary_trial()).
     */
    template <int dim>
    struct BoundaryParticleTrial
    {
      typename dealii::Particles::ParticleIterator<dim> particle;
      dealii::Tensor<1, dim>                            gap;
      dealii::Tensor<1, dim>                            multiplier;
      dealii::Tensor<1, dim>                            reaction;
      int                                               state = 0;
    };

    /**
     * The trial state of a material point in contact with a boundary
     * surface (contact side = material points) at a converged iterate: the
     * point's tangential stick gap, whether it is pressed, its reaction
     * on the boundary, the contact normal and penetration, the energy of
     * its penalty spring and the boundary particle whose tangent line
     * (plane) it touches (the reaction is booked on it).
     * commit_step() writes it (commit_boundary_trial()).
     */
    template <int dim>
    struct PointContactTrial
    {
      typename dealii::Particles::ParticleIterator<dim> point;
      unsigned int                                      boundary = 0;
      dealii::Tensor<1, dim>                            tangential_gap;
      bool                                              active = false;
      dealii::Tensor<1, dim>                            reaction;
      dealii::Tensor<1, dim>                            normal;
      double                                            penetration = 0.;
      /** beta w |g|^2 / 2 of the point's penalty spring [J]. */
      double                        spring_energy = 0.;
      dealii::types::particle_index surface_particle =
        dealii::numbers::invalid_unsigned_int;
      /** Whether the contact is with the point's nearest face. */
      bool primary = true;
    };
  } // namespace MPM
} // namespace Talus

#endif
