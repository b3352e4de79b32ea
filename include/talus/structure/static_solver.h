#ifndef talus_structure_static_solver_h
#define talus_structure_static_solver_h

#include <talus/structure/structure.h>

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <string>

namespace Talus
{
  namespace Structure
  {
    /** Outcome of one Newton solve. */
    struct NewtonStatus
    {
      bool         converged  = false;
      unsigned int iterations = 0;
      double       residual   = 0.; ///< final |r| [N]
      std::string  failure;
    };


    /**
     * Static equilibrium of a Structure: for a load factor lambda, find u
     * with f_int(u) = lambda f_ext (+ external nodal forces) and the
     * prescribed displacements lambda u_D, by Newton's method with the
     * consistent tangent, solved with UMFPACK (the tangent is
     * non-symmetric with follower pressure), and an optional backtracking
     * line search on |r|. Load stepping: lambda = k/n for k = 1..n.
     * Displacement control: prescribe the displacement of the loaded node
     * (Structure::prescribe) instead of a load and read the reaction; this
     * follows a path through limit points of the load as long as the
     * controlled displacement grows monotonically (the von Mises truss).
     * Lambda = 0 is the pre-stress equilibrium step.
     */
    class StaticSolver
    {
    public:
      explicit StaticSolver(Structure &structure);

      /** Subsection "Structure/Solver". */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Allocate the matrix and vectors (after Structure::setup_system). */
      void
      setup();

      /**
       * Terms added to the residual r (and the tangent K, if not null) at
       * displacement u after the structure's own (e.g. inertia and damping
       * of DynamicSolver); only on unconstrained DoFs.
       */
      using ExtraTerms = std::function<void(const dealii::Vector<double> &u,
                                            dealii::Vector<double>       &r,
                                            dealii::SparseMatrix<double> *K)>;

      /**
       * Solve for @p load_factor from the current displacement; on success
       * commits the history if @p commit.
       */
      NewtonStatus
      solve(const double      load_factor,
            const ExtraTerms &extra  = ExtraTerms(),
            const bool        commit = true);

      /**
       * Solve for @p to from the converged state at load factor @p from;
       * if Newton fails, restart from that state with half the increment,
       * up to max_step_cuts times in a row (adaptive load stepping; a
       * converged sub-step doubles the increment again, not beyond the
       * original). With the secant predictor each increment starts from
       * the extrapolation of the last two converged states (a retry after
       * a failure from the last converged state). Returns the status of
       * the last solve with the total number of Newton iterations.
       */
      NewtonStatus
      solve_with_cuts(const double from, const double to);

      /**
       * One step of the arc-length method (Crisfield's cylindrical
       * constraint |u - u_0|^2 = ds^2 over the unconstrained DoFs, bordering
       * with two solves per iteration) from the committed state
       * (displacement, @p load_factor). The load factor becomes an unknown:
       * on success @p load_factor is the new one and the history is
       * committed. The predictor follows the previous direction
       * @p direction (updated), so the path passes limit points of the
       * load. Needs homogeneous supports (prescribed displacements are
       * not scaled by the arc-length load factor).
       */
      NewtonStatus
      solve_arc_length(double                 &load_factor,
                       const double            ds,
                       dealii::Vector<double> &direction);

      /**
       * What the solver remembers between solves besides the displacement:
       * the force scale of the Newton tolerance (the largest nodal force of
       * converged states) and the last converged state of
       * solve_with_cuts() (secant predictor). StructureProblem saves and
       * restores it with the structure's state, so that a repeated solve
       * from a committed state is the same.
       */
      struct History
      {
        double                 force_scale = 0.; ///< [N]
        dealii::Vector<double> previous_displacement;
        double                 previous_load_factor = 0.;
        bool                   previous_valid       = false;
      };

      History
      get_history() const;

      /**
       * The tangent of the last Newton iteration (condensed with the
       * constraints; with the dynamic solver's inertia and damping terms
       * and the Robin interface springs of that solve): the linearised
       * response of a solved state to its loads (the coupling's interface
       * Jacobian).
       */
      const dealii::SparseMatrix<double> &
      tangent() const
      {
        return matrix;
      }

      void
      set_history(const History &history);

      dealii::Vector<double> displacement;

      unsigned int load_steps     = 10;
      unsigned int max_iterations = 30;
      /** Halvings of a failed load increment (solve_with_cuts) [-]. */
      unsigned int max_step_cuts = 0;
      /** Start of each increment of solve_with_cuts(): "constant" (the
       * last converged displacement) or "secant" (extrapolated linearly in
       * the load factor from the last two converged states). */
      std::string predictor = "constant";
      double      tolerance = 1e-10;
      /**
       * Newton also stops when |r| <= round_off_factor eps | |K| |u| |
       * (free rows; eps the machine epsilon): the residual cannot be
       * computed more accurately than the representation of u allows
       * (doc/theory.md, "Round-off floor of the Newton test") [-].
       */
      static constexpr double round_off_factor = 10.;
      bool                    line_search      = true;
      /** Largest displacement change of one Newton iteration [m]; 0: no
       * limit. Longer steps are scaled down (a trust region for structures
       * that start far from equilibrium). */
      double max_increment = 0.;
      /** "load" (load factor steps) or "arc length". */
      std::string control    = "load";
      double      arc_length = 0.01; ///< ds [m]

    private:
      Structure                   &structure;
      dealii::SparseMatrix<double> matrix;
      /** Largest nodal force norm seen, the scale of the tolerance [N]. */
      double force_scale = 0.;
      /** The converged state before the last one of solve_with_cuts()
       * (secant predictor); valid if previous_valid. */
      dealii::Vector<double> previous_displacement;
      double                 previous_load_factor = 0.;
      bool                   previous_valid       = false;
    };
  } // namespace Structure
} // namespace Talus

#endif
