#ifndef talus_structure_dynamic_solver_h
#define talus_structure_dynamic_solver_h

#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

namespace Talus
{
  namespace Structure
  {
    /**
     * Implicit dynamics of a Structure with the Bossak-Newmark scheme
     * (Wood, Bossak & Zienkiewicz 1980), lumped or consistent mass M and
     * Rayleigh damping
     * C = a_M M + a_K K_n (K_n: tangent at the start of the step):
     *   M [(1 - alpha) a_{n+1} + alpha a_n] + C v_{n+1} + f_int(u_{n+1})
     *     = f_ext,
     *   u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}],
     *   v_{n+1} = v_n + dt [(1 - gamma) a_n + gamma a_{n+1}],
     * beta = (1 - alpha)^2/4, gamma = 1/2 - alpha, -1/3 <= alpha <= 0
     * (alpha = 0: average acceleration, energy conserving for linear
     * problems). Each step is solved by the Newton iteration of
     * StaticSolver with the inertia and damping terms added (tangent
     * K + (1 - alpha)/(beta dt^2) M + gamma/(beta dt) C). Loads are those of
     * load factor 1 plus Structure::external_forces, which a coupling sets
     * before each step. Sub-solver contract: solve_step() can be repeated
     * (it starts from the last committed state), commit_step() accepts it.
     *
     * With interface_force_at_end, the external forces F (the coupling's
     * interface force) act with their end value over the whole step, as
     * the MPM's unilateral contact force with 'contact force in time =
     * end of step' (MPM::ContactTimeIntegration; Doyen, Ern & Piperno
     * 2011): a^c = M^-1 F adds dt^2/2 a^c to the increment and dt a^c to
     * the velocity, and a_{n+1} above is the acceleration of the other
     * forces. In the residual F then counts (1 - alpha)/(2 beta) times
     * (interface_force_factor()), the step carries only a_{n+1} into the
     * next one, and for alpha = 0 the work of F in the step is
     * F_{n+1} . du, the work the MPM's end-of-step contact force does on
     * the material with the opposite sign: the interface exchanges no
     * energy besides the penalty's booked dissipation. Lumped mass only.
     */
    class DynamicSolver
    {
    public:
      DynamicSolver(Structure &structure, StaticSolver &newton);

      /** Subsection "Dynamics". */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** After StaticSolver::setup() and the initial displacement: the
       * initial acceleration M^-1 (f_ext - f_int) (zero where M = 0). */
      void
      initialize();

      /** Solve the step of size @p dt from the committed state. */
      NewtonStatus
      solve_step(const double dt);

      /** Accept the last solve_step(): velocities, accelerations, history. */
      void
      commit_step();

      /**
       * Make the current displacement of the Newton solver the start of the
       * next step: u_n, and for stiffness damping the tangent K_n at u_n
       * (with the committed history). commit_step() and initialize() call
       * it; call it after restoring a saved state (displacement,
       * velocity, acceleration, history).
       */
      void
      update_step_start();

      /** Velocity of the last solve_step() (before commit_step()). */
      const dealii::Vector<double> &
      trial_velocity() const;

      /**
       * How many times the external forces count in the step's residual:
       * (1 - alpha)/(2 beta) with interface_force_at_end in a dynamic
       * analysis, else 1. A linearisation of the interface force (the
       * coupling's initial Jacobian) scales with it.
       */
      double
      interface_force_factor() const;

      /** Kinetic energy v.M v/2 of the committed state [J]. */
      double
      kinetic_energy() const;

      dealii::Vector<double> velocity;
      dealii::Vector<double> acceleration;
      /** Rayleigh damping force C v of the committed state [N]. */
      dealii::Vector<double> damping_force;
      /**
       * Work of the Rayleigh damping forces up to the committed state [J]:
       * per step du . (C v_n + C v_n+1) / 2, which closes the discrete
       * energy balance of the average-acceleration rule (alpha = 0):
       * kinetic + strain energy change = external work - damping work.
       */
      double damping_work = 0.;

      bool   enabled           = false;
      double end_time          = 1.;
      double time_step         = 1e-2;
      double alpha             = 0.;
      double mass_damping      = 0.; ///< a_M [1/s]
      double stiffness_damping = 0.; ///< a_K [s]
      /** Consistent instead of lumped mass matrix. */
      bool consistent_mass = false;
      /** The external forces act with their end value (see above; set by
       * the coupling, 'interface force in time'). */
      bool interface_force_at_end = false;

    private:
      Structure                   &structure;
      StaticSolver                &newton;
      dealii::Vector<double>       u_n, v_trial, a_trial, damping_trial;
      dealii::SparseMatrix<double> K_n;
      dealii::SparseMatrix<double> M_c; ///< consistent mass

      /** M x: the lumped or the consistent mass. */
      void
             mass_vmult(dealii::Vector<double>       &y,
                        const dealii::Vector<double> &x) const;
      double dt_last = 0.;
    };
  } // namespace Structure
} // namespace Talus

#endif
