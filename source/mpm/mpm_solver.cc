#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/rtree.h>

#include <deal.II/differentiation/ad/sacado_product_types.h>

#include <Amesos.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <Sacado.hpp>
#include <Teuchos_ParameterList.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace MPM
  {
    namespace
    {
      /** Embed an in-plane (dim x dim) deformation gradient in 3D. */
      template <int dim>
      dealii::Tensor<2, 3>
      embed(const dealii::Tensor<2, dim> &F)
      {
        dealii::Tensor<2, 3> F3;
        for (unsigned int i = 0; i < 3; ++i)
          F3[i][i] = 1.;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            F3[i][j] = F[i][j];
        return F3;
      }

      template <int dim>
      dealii::Tensor<2, dim>
      read_tensor(const dealii::ArrayView<const double> &p,
                  const unsigned int                     first)
      {
        dealii::Tensor<2, dim> t;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            t[i][j] = p[first + i * dim + j];
        return t;
      }

      /** Value of a plain or forward-AD number. */
      inline double
      value_of(const double x)
      {
        return x;
      }

      template <typename Number>
      inline double
      value_of(const Number &x)
      {
        return x.val();
      }

      /**
       * Forward-mode AD number with one derivative per degree of freedom
       * of a Q1 cell (static size: no allocation).
       */
      template <int dim>
      using CellAD = Sacado::Fad::SFad<double, dim *(1 << dim)>;

      /**
       * F-bar internal forces of the points of one cell (see
       * MPMSolver::fbar_cell()), for Number = double (residual only) or
       * CellAD<dim> (residual and exact derivative). The points are given
       * by their shape gradients dN (with respect to the positions at the
       * start of the step), F_n, V0; P_and_A evaluates the constitutive
       * model at a deformation gradient (3x3) and returns false on
       * failure.
       *
       * Variational F-bar: with f_p = I + H_p, J_p = det f_p, the volume
       * weights w_p = v_p / sum v (v_p = V0 det F_n), J_bar = sum w_q J_q,
       * alpha_p = (J_bar/J_p)^(1/dim) and F_bar_p = alpha_p f_p F_n, the
       * internal virtual work sum_p V0 P(F_bar_p) : dF_bar_p equals
       * sum_p T_p : dH_p with
       *   T_p = alpha_p S_p + (s_bar beta_p - alpha_p s_p)/dim f_p^{-T},
       *   S_p = V0 P F_n^T, s_p = S_p : f_p, s_bar = sum_q alpha_q s_q,
       *   beta_p = w_p J_p / J_bar.
       */
      template <int dim, typename Number, typename ModelCall>
      bool
      fbar_internal_forces(const unsigned int                         n_points,
                           const unsigned int                         n_nodes,
                           const std::vector<unsigned int>           &comp,
                           const std::vector<unsigned int>           &node,
                           const std::vector<Number>                 &u,
                           const dealii::Tensor<1, dim>              *dN_first,
                           const std::vector<dealii::Tensor<2, dim>> &F_n,
                           const std::vector<double>                 &V0,
                           const ModelCall                           &P_and_A,
                           std::vector<Number>                       &f_int,
                           std::vector<dealii::Tensor<2, dim>>       *F_bar_out)
      {
        const unsigned int                          n_dofs = u.size();
        std::vector<dealii::Tensor<2, dim, Number>> f(n_points);
        std::vector<Number>                         J(n_points);
        std::vector<double>                         v(n_points);
        Number                                      J_bar = 0.;
        double                                      v_sum = 0.;
        for (unsigned int q = 0; q < n_points; ++q)
          {
            const dealii::Tensor<1, dim> *dN = dN_first + q * n_nodes;
            for (unsigned int d = 0; d < dim; ++d)
              f[q][d][d] = 1.;
            for (unsigned int i = 0; i < n_dofs; ++i)
              for (unsigned int d = 0; d < dim; ++d)
                f[q][comp[i]][d] += u[i] * dN[node[i]][d];
            J[q] = dealii::determinant(f[q]);
            if (!(value_of(J[q]) > 0.))
              return false;
            v[q] = V0[q] * dealii::determinant(F_n[q]);
            v_sum += v[q];
            J_bar += v[q] * J[q];
          }
        J_bar /= v_sum;

        std::vector<Number> alpha(n_points), s(n_points);
        std::vector<dealii::Tensor<2, dim, Number>> S(n_points);
        Number                                      s_bar = 0.;
        dealii::Tensor<2, 3>                        P;
        dealii::Tensor<4, 3>                        A;
        constexpr bool with_derivatives = !std::is_same<Number, double>::value;
        for (unsigned int q = 0; q < n_points; ++q)
          {
            {
              // (J_bar/J_p)^(1/dim) without pow (a tenth of the F-bar cost)
              using std::cbrt;
              using std::sqrt;
              if constexpr (dim == 2)
                alpha[q] = sqrt(J_bar / J[q]);
              else
                alpha[q] = cbrt(J_bar / J[q]);
            }
            // (explicit loops: deal.II's scalar-tensor operators do not
            // accept Sacado's expression types)
            dealii::Tensor<2, dim, Number> F_bar;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                {
                  Number sum = 0.;
                  for (unsigned int k = 0; k < dim; ++k)
                    sum += f[q][i][k] * F_n[q][k][j];
                  F_bar[i][j] = alpha[q] * sum;
                }
            dealii::Tensor<2, dim> F_value;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                F_value[i][j] = value_of(F_bar[i][j]);
            if (F_bar_out != nullptr)
              (*F_bar_out)[q] = F_value;
            if (!P_and_A(q, F_value, P, with_derivatives ? &A : nullptr))
              return false;
            // P(F_bar) linearized around the value: exact first derivative.
            dealii::Tensor<2, dim, Number> P_ad;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int J_ = 0; J_ < dim; ++J_)
                {
                  P_ad[i][J_] = P[i][J_];
                  if (with_derivatives)
                    for (unsigned int k = 0; k < dim; ++k)
                      for (unsigned int L = 0; L < dim; ++L)
                        P_ad[i][J_] +=
                          A[i][J_][k][L] * (F_bar[k][L] - F_value[k][L]);
                }
            s[q] = 0.;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                {
                  Number sum = 0.;
                  for (unsigned int k = 0; k < dim; ++k)
                    sum += P_ad[i][k] * F_n[q][j][k];
                  S[q][i][j] = V0[q] * sum;
                  s[q] += S[q][i][j] * f[q][i][j];
                }
            s_bar += alpha[q] * s[q];
          }

        for (unsigned int q = 0; q < n_points; ++q)
          {
            const Number beta = v[q] * J[q] / (v_sum * J_bar);
            const Number coefficient =
              (s_bar * beta - alpha[q] * s[q]) / double(dim);
            const dealii::Tensor<2, dim, Number> f_inv = dealii::invert(f[q]);
            dealii::Tensor<2, dim, Number>       T;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                T[i][j] = alpha[q] * S[q][i][j] + coefficient * f_inv[j][i];
            const dealii::Tensor<1, dim> *dN = dN_first + q * n_nodes;
            for (unsigned int i = 0; i < n_dofs; ++i)
              for (unsigned int d = 0; d < dim; ++d)
                f_int[i] += T[comp[i]][d] * dN[node[i]][d];
          }
        return true;
      }
    } // namespace


    template <int dim>
    MPMSolver<dim>::MPMSolver(BackgroundGrid<dim>                &grid,
                              MaterialPoints<dim>                &points,
                              const Materials::ConstitutiveModel &model,
                              const NewmarkBeta                  &newmark,
                              dealii::TimerOutput                &timer)
      : grid(grid)
      , points(points)
      , model(model)
      , newmark(newmark)
      , timer(timer)
      , quasi_static(false)
      , consistent_mass(false)
      , load_ramp_time(0.)
      , max_newton_iterations(20)
      , max_state_change_newton_iterations(50)
      , residual_tolerance(1e-8)
      , absolute_residual_tolerance(1e-12)
      , increment_tolerance(1e-8)
      , linear_solver_type("CG")
      , linear_tolerance(1e-10)
      , max_linear_iterations(1000)
      , time(0.)
      , dt(0.)
      , n_active(0)
      , prepared(false)
      , solved(false)
    {}


    template <int dim>
    void
    MPMSolver<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Solver");
      {
        prm.declare_entry("analysis",
                          "dynamic",
                          Patterns::Selection("dynamic|quasi-static"),
                          "'dynamic': momentum balance with inertia "
                          "(Newmark-beta). 'quasi-static': equilibrium "
                          "without inertia, loads applied incrementally "
                          "(see 'load ramp time'); velocities stay zero.");
        prm.declare_entry("mass matrix",
                          "lumped",
                          Patterns::Selection("lumped|consistent"),
                          "Grid mass matrix in the inertia term: 'lumped' "
                          "(row sums, m_I = sum_p N_I m_p) or 'consistent' "
                          "(M_IJ = sum_p m_p N_I N_J). The projection of "
                          "velocity and acceleration to the grid always uses "
                          "the lumped mass.");
        prm.declare_entry("gravity",
                          dim == 2 ? "0, -9.81" : "0, 0, -9.81",
                          Patterns::Anything(),
                          "Gravitational acceleration [m/s^2], one component "
                          "per direction separated by commas. Any direction "
                          "is allowed (tilt it to model an incline).");
        prm.declare_entry("load ramp time",
                          "0",
                          Patterns::Double(0),
                          "Gravity and body forces grow linearly from zero to "
                          "their full value over this time [s], >= 0; 0: "
                          "applied at once. A quasi-static run with end time "
                          "T, time step T/20 and ramp time T applies the load "
                          "in 20 steps.");
        prm.enter_subsection("Body force");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
        prm.declare_entry("maximum Newton iterations",
                          "20",
                          Patterns::Integer(1, 1000),
                          "Newton iterations per step before the step is "
                          "rejected [-], 1 to 1000; iterations that change "
                          "the return branch of a material point count "
                          "separately ('maximum Newton iterations with "
                          "state changes').");
        prm.declare_entry(
          "maximum Newton iterations with state changes",
          "50",
          Patterns::Integer(1, 1000),
          "Newton iterations per step in all, counting those whose "
          "correction changed the branch of the return mapping (elastic, "
          "plane, edge, apex) of at least one material point [-], 1 to "
          "1000. Such iterations do not count toward 'maximum Newton "
          "iterations' (like the severe discontinuity iterations of "
          "Abaqus); a value not above 'maximum Newton iterations' makes "
          "them count, and so do state changes once the residual has not "
          "reached a new minimum (below 0.9 of the best) for 10 "
          "iterations (a cycle). Plastic granular material near rest "
          "converges "
          "erratically but surely while its points settle between the "
          "plane and the apex of the yield surface (20 to 46 iterations at "
          "a 5 ms step in contrib/granular/thin_layer_stop.prm); counted "
          "like the others, those steps are rejected and the adaptive step "
          "shrinks (doc/performance.md, 'Newton near rest').");
        prm.declare_entry("residual tolerance",
                          "1e-8",
                          Patterns::Double(0),
                          "Newton converges when |R| <= tol * max(|R_0|, "
                          "|f_ext|) (or |R| <= 'absolute residual "
                          "tolerance') and the increment criterion holds [-].");
        prm.declare_entry("absolute residual tolerance",
                          "1e-12",
                          Patterns::Double(0),
                          "Residual norm below which Newton has converged "
                          "regardless of the relative criterion [N].");
        prm.declare_entry("increment tolerance",
                          "1e-8",
                          Patterns::Double(0),
                          "Newton also requires |d(du)| <= tol * max(|du|, h) "
                          "for the last correction [-] (h: smallest cell "
                          "diameter, for bodies at rest), unless the "
                          "residual is already below 1e-2 times its "
                          "tolerance. See 'increment test' for what is "
                          "compared.");
        prm.declare_entry(
          "increment test",
          "last correction",
          Patterns::Selection("last correction|estimated error"),
          "What 'increment tolerance' bounds [-]. 'last correction': the "
          "norm of the last Newton correction |d(du)_k|, which measures the "
          "error of the iterate before it (one iteration behind: with "
          "quadratic convergence the accepted iterate is far more accurate). "
          "'estimated error': the error of the current iterate estimated as "
          "|d(du)_k| min(1, |R_k| / |R_{k-1}|), the next correction "
          "predicted from the contraction of the residual over the last "
          "correction (Deuflhard 2004, Newton Methods for Nonlinear Problems, "
          "section 2.1); it saves the last iteration when the residual test "
          "already holds. Used with an increment tolerance matched to the "
          "residual tolerance (e.g. 1e-6 both) by the granular collapse "
          "benchmarks (doc/performance.md, 'Newton: the friction state "
          "guess and an estimated error').");
        prm.declare_entry("linear solver",
                          "CG",
                          Patterns::Selection("CG|GMRES|direct"),
                          "'CG' or 'GMRES' (Trilinos ML algebraic multigrid "
                          "preconditioner with the rigid body modes as near "
                          "null space), or 'direct' (Amesos KLU, for small "
                          "problems).");
        prm.declare_entry(
          "AMG smoother",
          "Chebyshev",
          Patterns::Selection("Chebyshev|symmetric Gauss-Seidel"),
          "Smoother of the ML algebraic multigrid (2 sweeps per level) [-]: "
          "'Chebyshev' (polynomial in the point Jacobi-scaled matrix) or "
          "'symmetric Gauss-Seidel' (processor-local, Jacobi across ranks). "
          "Gauss-Seidel handles the stiff rank-one couplings of contact on "
          "boundaries that are not aligned with the grid much better: the "
          "Lagrange multiplier block solve on a fine 3D grid needs it "
          "(doc/verification.md, saddle-point solve with AMG); combine it "
          "with a 'ghost penalty factor' when cut cells are small.");
        prm.declare_entry(
          "saddle-point solver",
          "automatic",
          Patterns::Selection(
            "automatic|Schur complement|block preconditioned"),
          "Linear solve of the Newton systems with Lagrange multiplier "
          "boundaries, [A C; B E] [x; y] = [r; s] (doc/theory.md) [-]. "
          "'Schur complement': GMRES on the multipliers' Schur complement "
          "E - B A^-1 C, each application solving with A (exact with the "
          "direct solver; a full AMG-preconditioned Krylov solve per "
          "iteration otherwise). 'block preconditioned': FGMRES on the whole "
          "system with the block upper-triangular preconditioner [A~ C; 0 "
          "S~], A~^-1 one AMG V-cycle (or the factorisation with 'direct') "
          "and S~ = E - B diag(A)^-1 C point by point: no nested solves. "
          "'automatic': Schur complement with 'direct', block "
          "preconditioned with CG or GMRES.");
        prm.declare_entry("reuse preconditioner",
                          "true",
                          Patterns::Bool(),
                          "Build the AMG preconditioner once per time step "
                          "(first Newton iteration) and reuse it in the later "
                          "iterations; it is rebuilt if the Krylov solver "
                          "then fails.");
        prm.declare_entry("linear solver tolerance",
                          "1e-10",
                          Patterns::Double(0),
                          "Relative residual reduction of the iterative "
                          "linear solver [-].");
        prm.declare_entry("maximum linear iterations",
                          "2000",
                          Patterns::Integer(1),
                          "Iterations of the linear solver before the Newton "
                          "step counts as failed [-].");
        prm.declare_entry(
          "volumetric locking treatment",
          "none",
          Patterns::Selection("none|F-bar"),
          "'none': every material point uses its own deformation gradient. "
          "'F-bar': the volume change of the step is averaged over the "
          "points of each cell, f_p -> (J_bar/J_p)^(1/dim) f_p with the "
          "volume-weighted mean J_bar of J_p = det f_p (f_p: deformation "
          "gradient of the step), which removes volumetric locking of "
          "isochoric plastic flow and nearly incompressible materials on "
          "Q1 cells with several points per cell (Coombs et al. 2018, "
          "CMAME 333; variational form and exact tangent: doc/theory.md). "
          "Use it for granular materials.");
        prm.declare_entry(
          "line search",
          "false",
          Patterns::Bool(),
          "Backtracking line search in the Newton iteration: the correction "
          "is halved (up to 'maximum line search halvings' times) while it "
          "increases the residual norm. Recommended for plasticity (Mohr-"
          "Coulomb, Drucker-Prager), whose pre-asymptotic Newton iterates "
          "can oscillate; each trial costs one residual assembly.");
        prm.declare_entry(
          "predictor",
          "automatic",
          Patterns::Selection("automatic|zero|constant acceleration"),
          "Initial guess of the grid displacement increment in the Newton "
          "iteration of a dynamic step [no unit]. 'zero': du = 0, the nodes "
          "stand still, so a body in motion starts from the inertial "
          "residual of stopping it (m v/(beta dt)). 'constant acceleration': "
          "du = dt v_n + dt^2/2 a_n at the free nodes with mass (the Newmark "
          "predictor, a_{n+1} = a_n); nodes held by essential conditions or "
          "stuck on friction boundaries start from their held value as with "
          "'zero'. Either way the convergence reference is the residual at "
          "du = 0 (one extra residual assembly per step with the predictor), "
          "so the tolerances mean the same. 'automatic': 'constant "
          "acceleration' without boundary particles, 'zero' with them. "
          "Measured (doc/performance.md, 'Newton predictor'): the Bui "
          "collapse at 5 mm needs 4.4 instead of 5.8 Newton iterations per "
          "step, the plane-strain granular block of "
          "contrib/granular/block_rest_study.sh at 25 mm 670 instead of 1329 "
          "steps; the 3D block on the plane of boundary particles "
          "(benchmarks/granular_3d/block_on_rotated_plane.prm) is slower "
          "with it (more rejected steps), hence 'zero' there. Quasi-static "
          "analyses always start from zero.");
        prm.declare_entry("maximum line search halvings",
                          "4",
                          Patterns::Integer(1, 20),
                          "Halvings of the Newton correction in the line "
                          "search [-], 1 to 20.");
        prm.declare_entry(
          "FLIP fraction",
          "1",
          Patterns::Double(0, 1),
          "Velocity update of the material points [-], 0 to 1: 1 = FLIP "
          "(v_p += interpolated grid velocity increment; no numerical "
          "dissipation), 0 = PIC (v_p = interpolated grid velocity; "
          "dissipative), in between a blend. Used by 'velocity update = "
          "FLIP' only.");
        prm.declare_entry(
          "velocity update",
          "FLIP",
          Patterns::Selection("FLIP|APIC|XPIC"),
          "Transfer of the velocity between the material points and the "
          "grid [-]. 'FLIP': the points keep their own velocity and add the "
          "interpolated grid increment (blended with PIC by 'FLIP "
          "fraction'); velocity fields the grid cannot represent (more "
          "points than nodes) are never corrected. 'APIC' (affine particle-"
          "in-cell, Jiang et al. 2015, J. Comput. Phys. 290): the points "
          "take the interpolated grid velocity v_p = sum_I N_I(x_p) v_I and "
          "its gradient C_p = sum_I v_I grad N_I(x_p), and project the "
          "momentum m_p (v_p + C_p (x_I - x_p)) to node I. Conserves linear "
          "momentum in the transfer (Q1 reproduces linear fields; angular "
          "momentum is not tested here), removes the sub-cell velocity "
          "fields FLIP keeps, and dissipates only the velocity beyond the "
          "affine field of each point (doc/theory.md). 'XPIC' (extended "
          "particle-in-cell of order m = 'XPIC order', Hammerquist and "
          "Nairn 2017, CMAME 318): the FLIP update minus (I - P)^m v_p^n, "
          "where P = projection to the grid and back; removes the sub-cell "
          "velocity fields FLIP keeps with less dissipation than PIC (m = 1 "
          "is PIC).");
        prm.declare_entry(
          "XPIC order",
          "2",
          Patterns::Integer(1, 10),
          "Order m of the XPIC velocity update [-], 1 to 10 (1 = PIC; each "
          "order costs one more projection to the grid and back per step). "
          "Used by 'velocity update = XPIC' only; a value other than 2 "
          "with FLIP or APIC is rejected.");
        prm.declare_entry(
          "ghost penalty factor",
          "0",
          Patterns::Double(0),
          "Small-cut stabilisation (ghost penalty, Burman 2010; for MPM "
          "Coombs et al. 2020, CMAME 358) [-], >= 0; 0: off. Adds "
          "gamma h int_F [grad du . n] . [grad v . n] dA over every face F "
          "between two cells with material points of which at least one "
          "is cut: it has a face neighbour without material points or "
          "contains boundary particles. gamma = factor * M with M the "
          "P-wave modulus of the undeformed material (lambda + 2 mu) and "
          "h the cell size along the face normal; du is the displacement "
          "increment of the step. It ties the gradient of cells that hold "
          "only a sliver of material to their neighbours, so that their "
          "outer nodes are not nearly free (small-cut instability). "
          "Weakly consistent: the penalised jump vanishes for linear "
          "fields, the added energy scales with the factor. "
          "doc/theory.md and doc/verification.md give the measured effect "
          "of the factor.");
        prm.declare_entry("abort on lost material points",
                          "false",
                          Patterns::Bool(),
                          "Material points that leave the background grid are "
                          "removed with a warning naming the lost mass; true "
                          "turns this into an error that stops the run.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    MPMSolver<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      const std::string sub = "Solver";
      prm.enter_subsection(sub);
      quasi_static    = prm.get("analysis") == "quasi-static";
      consistent_mass = prm.get("mass matrix") == "consistent";
      const auto g    = parse_point<dim>(prm, sub, "gravity");
      for (unsigned int d = 0; d < dim; ++d)
        gravity_vector[d] = g[d];
      load_ramp_time = prm.get_double("load ramp time");
      prm.enter_subsection("Body force");
      body_force =
        std::make_unique<dealii::Functions::ParsedFunction<dim>>(dim);
      parse_function(prm, *body_force, "Solver/Body force");
      prm.leave_subsection();
      max_newton_iterations = prm.get_integer("maximum Newton iterations");
      max_state_change_newton_iterations =
        prm.get_integer("maximum Newton iterations with state changes");
      residual_tolerance = get_positive(prm, sub, "residual tolerance");
      absolute_residual_tolerance =
        prm.get_double("absolute residual tolerance");
      increment_tolerance = get_positive(prm, sub, "increment tolerance");
      estimated_increment_error =
        prm.get("increment test") == "estimated error";
      linear_solver_type   = prm.get("linear solver");
      reuse_preconditioner = prm.get_bool("reuse preconditioner");
      amg_smoother         = prm.get("AMG smoother");
      {
        const std::string s = prm.get("saddle-point solver");
        block_saddle_point =
          s == "block preconditioned" ||
          (s == "automatic" && linear_solver_type != "direct");
      }
      linear_tolerance      = get_positive(prm, sub, "linear solver tolerance");
      max_linear_iterations = prm.get_integer("maximum linear iterations");
      abort_on_lost_points  = prm.get_bool("abort on lost material points");
      use_fbar      = prm.get("volumetric locking treatment") == "F-bar";
      line_search   = prm.get_bool("line search");
      predictor     = prm.get("predictor");
      flip_fraction = prm.get_double("FLIP fraction");
      apic          = prm.get("velocity update") == "APIC";
      xpic_order    = prm.get("velocity update") == "XPIC" ?
                        prm.get_integer("XPIC order") :
                        0;
      if (xpic_order == 0 && prm.get_integer("XPIC order") != 2)
        InputFile::reject(sub,
                          "XPIC order",
                          prm.get("XPIC order"),
                          "it applies to 'velocity update = XPIC' only; "
                          "with 'velocity update = " +
                            prm.get("velocity update") +
                            "' leave it at its default 2");
      if ((apic || xpic_order > 0) && flip_fraction != 1.)
        InputFile::reject(sub,
                          "FLIP fraction",
                          prm.get("FLIP fraction"),
                          "it applies to 'velocity update = FLIP' only; "
                          "with 'velocity update = " +
                            prm.get("velocity update") + "' leave it at 1");
      ghost_penalty_factor = prm.get_double("ghost penalty factor");
      max_line_search      = prm.get_integer("maximum line search halvings");
      prm.leave_subsection();
    }


    template <int dim>
    void
    MPMSolver<dim>::setup()
    {
      dealii::TimerOutput::Scope scope(timer, "setup");
      const auto                &dof_handler = grid.dof_handler;
      {
        // tangent of the undeformed, virgin material (Nitsche's method)
        const unsigned int  n_history = points.n_history();
        std::vector<double> h_old(n_history, 0.), h_new(n_history, 0.);
        model.initialize_history(
          dealii::ArrayView<double>(h_old.data(), n_history));
        dealii::Tensor<2, 3> P;
        dealii::Tensor<4, 3> A;
        const auto           I = dealii::unit_symmetric_tensor<3>();
        model.compute_stress(I,
                             I,
                             dealii::ArrayView<const double>(h_old.data(),
                                                             n_history),
                             dealii::ArrayView<double>(h_new.data(), n_history),
                             0., // no rate: the virgin tangent
                             P,
                             &A);
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                elastic_tangent[i][j][k][l] = A[i][j][k][l];
      }

      dealii::DynamicSparsityPattern dsp(grid.locally_relevant_dofs);
      if (ghost_penalty_factor > 0.)
        dealii::DoFTools::make_flux_sparsity_pattern(dof_handler, dsp);
      else
        dealii::DoFTools::make_sparsity_pattern(dof_handler, dsp);
      dealii::SparsityTools::distribute_sparsity_pattern(
        dsp,
        grid.locally_owned_dofs,
        grid.mpi_communicator,
        grid.locally_relevant_dofs);
      amg.reset();
      direct_solver.reset();
      direct_problem.reset();
      matrix.reinit(grid.locally_owned_dofs,
                    grid.locally_owned_dofs,
                    dsp,
                    grid.mpi_communicator);

      const auto owned    = grid.locally_owned_dofs;
      const auto relevant = grid.locally_relevant_dofs;
      const auto comm     = grid.mpi_communicator;
      for (auto *v : {&nodal_mass,
                      &velocity_n,
                      &velocity_p2g,
                      &acceleration_n,
                      &displacement,
                      &acceleration_new})
        v->reinit(owned, relevant, comm);
      for (auto *v : {&external_force, &residual, &increment})
        v->reinit(owned, comm);
      raw_residual.reinit(owned, comm);

      // Degrees of freedom on fixed and slip boundaries.
      // (an empty set of ids would mean "all boundaries" to deal.II)
      fixed_dofs = dealii::IndexSet(dof_handler.n_dofs());
      if (!grid.fixed_boundaries.empty())
        fixed_dofs = dealii::DoFTools::extract_boundary_dofs(
          dof_handler, dealii::ComponentMask(dim, true), grid.fixed_boundaries);
      slip_dofs.assign(dim, dealii::IndexSet(dof_handler.n_dofs()));
      for (const auto id : grid.slip_boundaries)
        {
          // Normal direction of the (axis aligned) boundary.
          int axis        = -1;
          int not_aligned = 0;
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    cell->face(f)->boundary_id() == id)
                  {
                    dealii::Tensor<1, dim> n =
                      cell->face(f)->center() - cell->center();
                    n /= n.norm();
                    for (unsigned int d = 0; d < dim; ++d)
                      if (std::abs(std::abs(n[d]) - 1.) < 1e-8)
                        axis = d;
                    if (axis < 0)
                      not_aligned = 1;
                  }
          axis = dealii::Utilities::MPI::max(axis, comm);
          if (dealii::Utilities::MPI::max(not_aligned, comm) > 0 || axis < 0)
            InputFile::reject("Background grid",
                              "slip boundaries",
                              std::to_string(id),
                              "slip is only possible on axis-aligned "
                              "boundaries; boundary " +
                                std::to_string(id) + " is not axis aligned");
          std::set<dealii::types::boundary_id> ids{id};
          dealii::ComponentMask                mask(dim, false);
          mask.set(axis, true);
          slip_dofs[axis].add_indices(
            dealii::DoFTools::extract_boundary_dofs(dof_handler, mask, ids));
        }

      // Support points of the owned dofs (relative to the grid centre, for
      // well-scaled rotation modes) and their components.
      {
        std::map<dealii::types::global_dof_index, dealii::Point<dim>> points;
        dealii::DoFTools::map_dofs_to_support_points(grid.mapping,
                                                     dof_handler,
                                                     points);
        const dealii::Point<dim> centre =
          0.5 * (grid.lower_corner + grid.upper_corner);
        owned_support_points.resize(grid.locally_owned_dofs.n_elements());
        owned_components.resize(grid.locally_owned_dofs.n_elements());
        std::vector<dealii::types::global_dof_index> dofs(
          grid.fe.dofs_per_cell);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (grid.locally_owned_dofs.is_element(dofs[i]))
                  {
                    const auto k =
                      grid.locally_owned_dofs.index_within_set(dofs[i]);
                    owned_support_points[k] =
                      dealii::Point<dim>(points[dofs[i]] - centre);
                    owned_components[k] =
                      grid.fe.system_to_component_index(i).first;
                  }
            }
      }
      dealii::DoFTools::extract_constant_modes(dof_handler,
                                               dealii::ComponentMask(dim, true),
                                               constant_modes);
      setup_friction_nodes();
    }


    template <int dim>
    dealii::Tensor<1, dim>
    MPMSolver<dim>::external_acceleration(const dealii::Point<dim> &X,
                                          const double              t) const
    {
      const double factor =
        load_ramp_time > 0. ? std::min(1., t / load_ramp_time) : 1.;
      dealii::Tensor<1, dim> b = gravity_vector;
      body_force->set_time(t);
      for (unsigned int d = 0; d < dim; ++d)
        b[d] += body_force->value(X, d);
      return factor * b;
    }


    template <int dim>
    void
    MPMSolver<dim>::cache_particles()
    {
      using Properties           = MaterialPointProperties<dim>;
      auto              &handler = points.particle_handler();
      const auto        &fe      = grid.fe;
      const auto        &base    = fe.base_element(0);
      const unsigned int n_nodes = base.dofs_per_cell;

      cells.clear();
      particles.clear();
      shape_values.clear();
      shape_gradients.clear();
      particles.reserve(handler.n_locally_owned_particles());
      shape_values.reserve(handler.n_locally_owned_particles() * n_nodes);
      shape_gradients.reserve(handler.n_locally_owned_particles() * n_nodes);

      std::vector<dealii::Point<dim>> reference_points;
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const typename dealii::Triangulation<dim>::active_cell_iterator
                               tria_cell(cell);
            const unsigned int n = handler.n_particles_in_cell(tria_cell);
            if (n == 0)
              continue;
            CellCache c;
            c.cell  = cell;
            c.first = particles.size();
            c.n     = n;
            c.dofs.resize(fe.dofs_per_cell);
            cell->get_dof_indices(c.dofs);
            reference_points.clear();
            for (auto p = handler.particles_in_cell(tria_cell).begin();
                 p != handler.particles_in_cell(tria_cell).end();
                 ++p)
              {
                particles.push_back(p);
                reference_points.push_back(p->get_reference_location());
              }
            if (grid.is_cartesian)
              {
                for (const auto &xi : reference_points)
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    {
                      shape_values.push_back(base.shape_value(k, xi));
                      dealii::Tensor<1, dim> g = base.shape_grad(k, xi);
                      for (unsigned int d = 0; d < dim; ++d)
                        g[d] /= grid.cell_extent[d];
                      shape_gradients.push_back(g);
                    }
              }
            else
              {
                const dealii::Quadrature<dim> quadrature(reference_points);
                dealii::FEValues<dim>         fe_values(grid.mapping,
                                                base,
                                                quadrature,
                                                dealii::update_values |
                                                  dealii::update_gradients);
                fe_values.reinit(tria_cell);
                for (unsigned int q = 0; q < n; ++q)
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    {
                      shape_values.push_back(fe_values.shape_value(k, q));
                      shape_gradients.push_back(fe_values.shape_grad(k, q));
                    }
              }
            cells.push_back(std::move(c));
          }
      (void)Properties::mass;
    }


    template <int dim>
    void
    MPMSolver<dim>::project_to_grid()
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;

      dealii::TrilinosWrappers::MPI::Vector mass(grid.locally_owned_dofs,
                                                 grid.mpi_communicator);
      dealii::TrilinosWrappers::MPI::Vector momentum(mass), mass_acc(mass);
      external_force = 0.;
      particle_forces.resize(particles.size());

      dealii::Vector<double> m_local(dofs_per_cell), p_local(dofs_per_cell),
        a_local(dofs_per_cell), f_local(dofs_per_cell);
      for (const auto &c : cells)
        {
          m_local = 0.;
          p_local = 0.;
          a_local = 0.;
          f_local = 0.;
          for (unsigned int q = 0; q < c.n; ++q)
            {
              const unsigned int k     = c.first + q;
              const auto         props = particles[k]->get_properties();
              const double       m     = props[Properties::mass];
              dealii::Point<dim> X;
              for (unsigned int d = 0; d < dim; ++d)
                X[d] = props[Properties::initial_position + d];
              const auto b                 = external_acceleration(X, time);
              particle_forces[k]           = m * b;
              const dealii::Point<dim> x_p = particles[k]->get_location();
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto         ci = fe.system_to_component_index(i);
                  const double       N  = shape_values[k * n_nodes + ci.second];
                  const unsigned int comp = ci.first;
                  // APIC: the point's affine velocity at the node,
                  // v_p + C_p (x_I - x_p) (FE_Q(1): node k = vertex k)
                  double v = props[Properties::velocity + comp];
                  if (apic)
                    {
                      const dealii::Tensor<1, dim> dx =
                        c.cell->vertex(ci.second) - x_p;
                      for (unsigned int j = 0; j < dim; ++j)
                        v +=
                          props[Properties::affine_velocity + comp * dim + j] *
                          dx[j];
                    }
                  m_local[i] += N * m;
                  p_local[i] += N * m * v;
                  a_local[i] += N * m * props[Properties::acceleration + comp];
                  f_local[i] += N * m * b[comp];
                }
            }
          mass.add(c.dofs, m_local);
          momentum.add(c.dofs, p_local);
          mass_acc.add(c.dofs, a_local);
          external_force.add(c.dofs, f_local);
        }
      mass.compress(dealii::VectorOperation::add);
      momentum.compress(dealii::VectorOperation::add);
      mass_acc.compress(dealii::VectorOperation::add);
      external_force.compress(dealii::VectorOperation::add);

      for (const auto i : grid.locally_owned_dofs)
        if (mass(i) > 0.)
          {
            momentum(i) /= mass(i);
            mass_acc(i) /= mass(i);
          }
      momentum.compress(dealii::VectorOperation::insert);
      mass_acc.compress(dealii::VectorOperation::insert);
      nodal_mass     = mass;
      velocity_n     = momentum;
      velocity_p2g   = momentum;
      acceleration_n = mass_acc;
    }


    template <int dim>
    void
    MPMSolver<dim>::compute_xpic_correction(
      std::vector<dealii::Tensor<1, dim>> &w) const
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      w.assign(particles.size(), dealii::Tensor<1, dim>());
      for (const auto &c : cells)
        for (unsigned int q = 0; q < c.n; ++q)
          {
            const auto props = particles[c.first + q]->get_properties();
            for (unsigned int d = 0; d < dim; ++d)
              w[c.first + q][d] = props[Properties::velocity + d];
          }
      dealii::TrilinosWrappers::MPI::Vector grid_velocity(
        grid.locally_owned_dofs, grid.mpi_communicator);
      dealii::TrilinosWrappers::MPI::Vector ghosted(grid.locally_owned_dofs,
                                                    grid.locally_relevant_dofs,
                                                    grid.mpi_communicator);
      dealii::Vector<double>                p_local(dofs_per_cell);
      for (unsigned int r = 0; r < xpic_order; ++r)
        {
          // P w: mass-weighted projection to the nodes and back
          grid_velocity = 0.;
          for (const auto &c : cells)
            {
              p_local = 0.;
              for (unsigned int q = 0; q < c.n; ++q)
                {
                  const unsigned int k = c.first + q;
                  const double       m =
                    particles[k]->get_properties()[Properties::mass];
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const auto ci = fe.system_to_component_index(i);
                      p_local[i] += shape_values[k * n_nodes + ci.second] * m *
                                    w[k][ci.first];
                    }
                }
              grid_velocity.add(c.dofs, p_local);
            }
          grid_velocity.compress(dealii::VectorOperation::add);
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              grid_velocity(i) /= nodal_mass(i);
          grid_velocity.compress(dealii::VectorOperation::insert);
          ghosted = grid_velocity;
          for (const auto &c : cells)
            for (unsigned int q = 0; q < c.n; ++q)
              {
                const unsigned int k = c.first + q;
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    const auto ci = fe.system_to_component_index(i);
                    w[k][ci.first] -= shape_values[k * n_nodes + ci.second] *
                                      ghosted(c.dofs[i]);
                  }
              }
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::make_constraints()
    {
      constraints.clear();
      constraints.reinit(grid.locally_relevant_dofs);
      n_active = 0;
      for (const auto i : grid.locally_relevant_dofs)
        {
          bool constrained = nodal_mass(i) <= 0. || fixed_dofs.is_element(i) ||
                             friction_corner_dofs.is_element(i);
          for (unsigned int d = 0; d < dim && !constrained; ++d)
            constrained = slip_dofs[d].is_element(i);
          if (constrained)
            constraints.add_line(i);
        }
      for (const auto &fn : friction_nodes)
        if (fn.state != ContactState::free)
          {
            if (!constraints.is_constrained(fn.normal_dof))
              constraints.add_line(fn.normal_dof);
            if (fn.state == ContactState::stick)
              for (const auto t : fn.tangential_dofs)
                if (!constraints.is_constrained(t))
                  constraints.add_line(t);
          }
      if (contact_jump_active)
        for (const auto &fn : friction_nodes)
          if (fn.state != ContactState::free)
            {
              const auto set = [&](const dealii::types::global_dof_index i) {
                const double g = contact_jump(i);
                if (g != 0. && constraints.is_constrained(i) &&
                    constraints.get_constraint_entries(i) != nullptr &&
                    constraints.get_constraint_entries(i)->empty())
                  constraints.set_inhomogeneity(i, g);
              };
              set(fn.normal_dof);
              if (fn.state == ContactState::stick)
                for (const auto t : fn.tangential_dofs)
                  set(t);
            }
      for (const auto i : grid.locally_owned_dofs)
        if (!constraints.is_constrained(i))
          ++n_active;
      constraints.close();
      n_active = dealii::Utilities::MPI::sum(n_active, grid.mpi_communicator);
    }


    template <int dim>
    void
    MPMSolver<dim>::prepare_step(const double new_time, const double step)
    {
      dealii::TimerOutput::Scope scope(timer, "prepare (P2G)");
      time                    = new_time;
      dt                      = step;
      step_impact_dissipation = 0.;
      step_reset_dissipation  = 0.;
      cache_particles();
      project_to_grid();
      cache_boundary_particles();
      if (ghost_penalty_factor > 0.)
        setup_ghost_penalty();
      make_step_sparsity_pattern();
      apply_impact_friction();
      initialize_friction_states();
      make_constraints();
      amg_current = false;
      // Grid velocity and acceleration obey the essential conditions: a
      // fixed node neither moves nor carries the particles' velocity. The
      // kinetic energy this removes is booked (reset_dissipation). Not so
      // the tangential dofs of friction nodes that start the step stuck
      // ('friction state guess = previous step'): their constraint, the
      // resting increment, brings the velocity to zero within the step
      // through the friction force, and a node that slips after all keeps
      // the velocity and acceleration the points gave it.
      std::vector<dealii::types::global_dof_index> stuck_tangential;
      for (const auto &fn : friction_nodes)
        if (fn.owned && fn.state == ContactState::stick)
          stuck_tangential.insert(stuck_tangential.end(),
                                  fn.tangential_dofs.begin(),
                                  fn.tangential_dofs.end());
      std::sort(stuck_tangential.begin(), stuck_tangential.end());
      double removed = 0.;
      for (auto *v : {&velocity_n, &acceleration_n})
        {
          dealii::TrilinosWrappers::MPI::Vector owned(grid.locally_owned_dofs,
                                                      grid.mpi_communicator);
          owned              = *v;
          Epetra_FEVector &e = owned.trilinos_vector();
          for (const auto i : grid.locally_owned_dofs)
            if (constraints.is_constrained(i) &&
                !std::binary_search(stuck_tangential.begin(),
                                    stuck_tangential.end(),
                                    i))
              {
                const int l = e.Map().LID(static_cast<int>(i));
                if (v == &velocity_n && !quasi_static)
                  removed += 0.5 * nodal_mass(i) * e[0][l] * e[0][l];
                e[0][l] = 0.;
              }
          *v = owned;
        }
      step_reset_dissipation =
        dealii::Utilities::MPI::sum(removed, grid.mpi_communicator);
      cell_contributions_current = false;
      prepared                   = true;
      solved                     = false;
    }


    template <int dim>
    bool
    MPMSolver<dim>::assemble(const dealii::TrilinosWrappers::MPI::Vector &du,
                             const bool   with_matrix,
                             const bool   with_inertia,
                             std::string &failure,
                             const bool   same_iterate)
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const unsigned int n_history     = points.n_history();
      const double       c_mass = with_inertia ? newmark.mass_factor(dt) : 0.;

      if (with_matrix)
        {
          matrix                   = 0.;
          reversed_boundary_points = 0;
          boundary_states_changed  = false;
        }
      residual            = 0.;
      multiplier_residual = 0.;
      if (!grid.friction_boundaries.empty())
        raw_residual = 0.;

      dealii::FullMatrix<double> k_local(dofs_per_cell, dofs_per_cell);
      dealii::Vector<double>     r_local(dofs_per_cell);
      std::vector<double>       du_local(dofs_per_cell), a_local(dofs_per_cell);
      std::vector<unsigned int> comp(dofs_per_cell), node(dofs_per_cell);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          comp[i] = fe.system_to_component_index(i).first;
          node[i] = fe.system_to_component_index(i).second;
        }
      std::vector<double>                 history_new(n_history);
      std::vector<dealii::Tensor<1, dim>> G(n_nodes);
      dealii::Tensor<2, 3>                P;
      dealii::Tensor<4, 3>                A;
      bool                                ok = true;

      // The cells' contributions before friction and constraints, kept for
      // a re-assembly at the same iterate after a contact state update.
      const unsigned int block = dofs_per_cell * dofs_per_cell + dofs_per_cell;
      const bool         keep_contributions =
        with_matrix && !grid.friction_boundaries.empty();
      const bool reuse_contributions =
        same_iterate && with_matrix && cell_contributions_current;
      if (keep_contributions && !reuse_contributions)
        cell_contributions.resize(cells.size() * block);
      cell_contributions_current = false;

      for (unsigned int cell_index = 0; cell_index < cells.size(); ++cell_index)
        {
          const CellCache &c = cells[cell_index];
          if (!ok)
            break;
          double *const stored     = keep_contributions ?
                                       &cell_contributions[cell_index * block] :
                                       nullptr;
          bool          from_store = reuse_contributions;
          if (from_store && !inertia_changed_dofs.empty())
            for (const auto i : c.dofs)
              if (std::binary_search(inertia_changed_dofs.begin(),
                                     inertia_changed_dofs.end(),
                                     i))
                from_store = false;
          if (from_store)
            {
              std::copy(stored,
                        stored + dofs_per_cell * dofs_per_cell,
                        &k_local(0, 0));
              std::copy(stored + dofs_per_cell * dofs_per_cell,
                        stored + block,
                        r_local.begin());
            }
          else
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  du_local[i] = du(c.dofs[i]);
                  a_local[i]  = with_inertia ?
                                  newmark.acceleration(du_local[i],
                                                      velocity_n(c.dofs[i]),
                                                      acceleration_n(c.dofs[i]),
                                                      dt) :
                                  0.;
                }
              k_local = 0.;
              r_local = 0.;
              for (unsigned int q = 0; q < c.n; ++q)
                {
                  const unsigned int k     = c.first + q;
                  const auto         props = particles[k]->get_properties();
                  const double      *N     = &shape_values[k * n_nodes];
                  const auto        *dN    = &shape_gradients[k * n_nodes];

                  const dealii::Tensor<2, dim> F_n =
                    read_tensor<dim>(props, Properties::deformation);
                  const double V0 = props[Properties::initial_volume];
                  const double m  = props[Properties::mass];

                  // Particle acceleration for the (consistent) inertia term.
                  dealii::Tensor<1, dim> a_p;
                  if (with_inertia && consistent_mass)
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      a_p[comp[i]] += N[node[i]] * a_local[i];

                  // External and inertia forces.
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const unsigned int ci = comp[i];
                      r_local[i] += N[node[i]] * particle_forces[k][ci];
                      if (!with_inertia)
                        continue;
                      if (consistent_mass)
                        {
                          r_local[i] -= m * N[node[i]] * a_p[ci];
                          if (with_matrix)
                            for (unsigned int j = 0; j < dofs_per_cell; ++j)
                              if (comp[j] == ci)
                                k_local(i, j) +=
                                  c_mass * m * N[node[i]] * N[node[j]];
                        }
                      else
                        {
                          r_local[i] -= m * N[node[i]] * a_local[i];
                          if (with_matrix)
                            k_local(i, i) += c_mass * m * N[node[i]];
                        }
                    }
                  if (use_fbar)
                    continue; // internal forces of the cell below

                  // Increment gradient, total deformation gradient.
                  dealii::Tensor<2, dim> H;
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    H[comp[i]] += du_local[i] * dN[node[i]];
                  dealii::Tensor<2, dim> F_new = F_n + H * F_n;

                  try
                    {
                      model.compute_stress(
                        embed<dim>(F_n),
                        embed<dim>(F_new),
                        dealii::ArrayView<const double>(props.data() +
                                                          Properties::history,
                                                        n_history),
                        dealii::ArrayView<double>(history_new.data(),
                                                  n_history),
                        dt,
                        P,
                        with_matrix ? &A : nullptr);
                    }
                  catch (const std::exception &e)
                    {
                      ok = false;
                      std::ostringstream msg;
                      msg << "constitutive update failed at the material point "
                             "near "
                          << particles[k]->get_location() << ": " << e.what();
                      failure = msg.str();
                      break;
                    }
                  if (with_matrix)
                    record_branch(k,
                                  dealii::ArrayView<const double>(
                                    history_new.data(), n_history));
                  for (unsigned int d = 0; d < 3; ++d)
                    for (unsigned int e = 0; e < 3; ++e)
                      if (!std::isfinite(P[d][e]))
                        {
                          ok      = false;
                          failure = "non-finite stress at a material point";
                        }
                  if (!ok)
                    break;

                  // Gradients with respect to the initial configuration.
                  for (unsigned int a = 0; a < n_nodes; ++a)
                    {
                      G[a] = 0.;
                      for (unsigned int J = 0; J < dim; ++J)
                        for (unsigned int i = 0; i < dim; ++i)
                          G[a][J] += F_n[i][J] * dN[a][i];
                    }

                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const unsigned int ci = comp[i];
                      const auto        &Gi = G[node[i]];
                      double             f  = 0.;
                      for (unsigned int J = 0; J < dim; ++J)
                        f += P[ci][J] * Gi[J];
                      r_local[i] -= V0 * f;
                      if (!with_matrix)
                        continue;
                      for (unsigned int j = 0; j < dofs_per_cell; ++j)
                        {
                          const unsigned int cj  = comp[j];
                          const auto        &Gj  = G[node[j]];
                          double             kij = 0.;
                          for (unsigned int J = 0; J < dim; ++J)
                            for (unsigned int L = 0; L < dim; ++L)
                              kij += Gi[J] * A[ci][J][cj][L] * Gj[L];
                          k_local(i, j) += V0 * kij;
                        }
                    }
                }
              if (ok && use_fbar)
                ok = fbar_cell(c,
                               du_local,
                               r_local,
                               with_matrix ? &k_local : nullptr,
                               failure);
              if (!ok)
                break;
              if (keep_contributions)
                {
                  std::copy(&k_local(0, 0),
                            &k_local(0, 0) + dofs_per_cell * dofs_per_cell,
                            stored);
                  std::copy(r_local.begin(),
                            r_local.end(),
                            stored + dofs_per_cell * dofs_per_cell);
                }
            }

          if (!grid.friction_boundaries.empty() &&
              cell_touches_friction[c.cell->active_cell_index()])
            {
              // Unconstrained residual for the contact reactions, then the
              // Coulomb force of slipping nodes as a combination of rows:
              // r_t += mu * inward * s_t * r_n (exactly linearized).
              raw_residual.add(c.dofs, r_local);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto it = friction_node_of.find(c.dofs[i]);
                  if (it == friction_node_of.end())
                    continue;
                  const FrictionNode &fn = friction_nodes[it->second];
                  if (fn.state != ContactState::slip || fn.mu == 0.)
                    continue;
                  for (const auto t : fn.tangential_dofs)
                    {
                      unsigned int j = 0;
                      while (j < dofs_per_cell && c.dofs[j] != t)
                        ++j;
                      Assert(j < dofs_per_cell, dealii::ExcInternalError());
                      const double factor =
                        fn.mu * fn.inward * fn.slip_direction[comp[j]];
                      r_local[j] += factor * r_local[i];
                      if (with_matrix)
                        for (unsigned int l = 0; l < dofs_per_cell; ++l)
                          k_local(j, l) += factor * k_local(i, l);
                    }
                }
            }

          if (with_matrix)
            constraints.distribute_local_to_global(
              k_local, r_local, c.dofs, matrix, residual);
          else
            constraints.distribute_local_to_global(r_local, c.dofs, residual);
        }

      cell_contributions_current = keep_contributions && ok;
      inertia_changed_dofs.clear();

      // Boundary particles in cells with at least one node that carries
      // mass: penalty forces on the material.
      std::vector<dealii::Tensor<1, dim>> dT(dofs_per_cell), df(dofs_per_cell);
      for (const auto &c : boundary_cells)
        {
          if (!ok)
            break;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            du_local[i] = du(c.dofs[i]);
          k_local = 0.;
          r_local = 0.;
          for (unsigned int b = 0; b < c.n_boundary; ++b)
            {
              BoundaryPoint         &bp = boundary_points[c.first_boundary + b];
              dealii::Tensor<1, dim> du_b;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                du_b[comp[i]] += bp.N[node[i]] * du_local[i];
              // traction -S n on the material and its derivatives (a
              // cell without material points falls back to penalty)
              const bool nitsche = bp.nitsche && bp.with_stress;
              if (nitsche)
                {
                  dealii::Tensor<1, dim> T;
                  boundary_traction(bp, du_local, T, dT);
                  bp.lambda = bp.weight * T;
                }
              BoundaryForce bf = boundary_force(bp, du_b);
              // A slip direction that reverses from one iterate to the
              // next means the solution lies in the (narrow, width
              // 2 mu f_n / k) stick zone between them: hold the point in
              // stick for this iterate instead of letting Newton jump
              // across it (with the slip tangent's zero tangential
              // stiffness it would cycle).
              if (with_matrix && bp.frozen < 0 && bf.state == 2)
                {
                  // (the direction opposite to the tangential force)
                  dealii::Tensor<1, dim> slip =
                    (bf.force * bp.normal) * bp.normal - bf.force;
                  if (slip.norm() > 0.)
                    slip /= slip.norm();
                  if (bp.last_state == 2 && slip * bp.last_slip < 0.)
                    {
                      BoundaryPoint held = bp;
                      held.frozen        = 1;
                      bf                 = boundary_force(held, du_b);
                      ++reversed_boundary_points;
                    }
                  else
                    bp.last_slip = slip;
                }
              if (with_matrix && bp.monolithic && bp.frozen < 0 &&
                  bp.last_state >= 0 && bf.state != bp.last_state &&
                  ++bp.switches >= 6)
                {
                  // cycling: hold the point closed (or sticking) if one of
                  // the two states was, closed and sliding otherwise
                  bp.frozen = (bf.state == 1 || bp.last_state == 1) ? 1 : 3;
                  bf        = boundary_force(bp, du_b);
                }
              if (with_matrix)
                {
                  // a changed contact state changes A (the trial-force
                  // stiffness k N^T D N): the AMG hierarchy of an earlier
                  // iterate no longer fits it
                  if (bf.state != bp.last_state)
                    boundary_states_changed = true;
                  bp.last_state = bf.state;
                }
              if (bp.monolithic)
                {
                  // the multiplier's equation (lambda - f) / k = 0 and
                  // D = df/dF for the saddle-point solve
                  const double k = bp.beta * bp.weight;
                  bp.lm_force    = bf.force;
                  bp.lm_D        = -bf.dforce_du / k;
                  multiplier_residual =
                    std::max(multiplier_residual,
                             (bp.lambda - bf.force).norm() / k);
                }
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const double Ni = bp.N[node[i]];
                  r_local[i] += Ni * bf.force[comp[i]];
                  if (with_matrix)
                    for (unsigned int j = 0; j < dofs_per_cell; ++j)
                      k_local(i, j) -=
                        Ni * bp.N[node[j]] * bf.dforce_du[comp[i]][comp[j]];
                }
              if (nitsche)
                {
                  // f = D(w T - k g): D = df/dF = -dforce_du / k; the
                  // force also changes with the stress, df_j += w D dT_j.
                  // Symmetry term (theta): r_i -= theta/beta (f - w T) .
                  // dT_i, its tangent without second derivatives of S.
                  const double                 k       = bp.beta * bp.weight;
                  const dealii::Tensor<2, dim> D       = -bf.dforce_du / k;
                  const dealii::Tensor<1, dim> q       = bf.force - bp.lambda;
                  const double                 c_theta = bp.theta / bp.beta;
                  for (unsigned int j = 0; j < dofs_per_cell; ++j)
                    {
                      df[j] = bp.weight * (D * dT[j]);
                      for (unsigned int d = 0; d < dim; ++d)
                        df[j][d] += bp.N[node[j]] * bf.dforce_du[d][comp[j]];
                    }
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const double Ni = bp.N[node[i]];
                      r_local[i] -= c_theta * (q * dT[i]);
                      if (!with_matrix)
                        continue;
                      for (unsigned int j = 0; j < dofs_per_cell; ++j)
                        {
                          k_local(i, j) -=
                            Ni * bp.weight * (D * dT[j])[comp[i]];
                          k_local(i, j) +=
                            c_theta * ((df[j] - bp.weight * dT[j]) * dT[i]);
                        }
                    }
                }
            }
          if (with_matrix)
            constraints.distribute_local_to_global(
              k_local, r_local, c.dofs, matrix, residual);
          else
            constraints.distribute_local_to_global(r_local, c.dofs, residual);
        }

      // Ghost penalty: linear in the increment, r = -K_g du.
      for (const auto &g : ghost_faces)
        {
          if (!ok)
            break;
          const unsigned int     n = g.dofs.size();
          dealii::Vector<double> du_g(n), r_g(n);
          for (unsigned int i = 0; i < n; ++i)
            du_g[i] = du(g.dofs[i]);
          g.matrix.vmult(r_g, du_g);
          r_g *= -1.;
          if (with_matrix)
            constraints.distribute_local_to_global(
              g.matrix, r_g, g.dofs, matrix, residual);
          else
            constraints.distribute_local_to_global(r_g, g.dofs, residual);
        }

      residual.compress(dealii::VectorOperation::add);
      if (!grid.friction_boundaries.empty())
        raw_residual.compress(dealii::VectorOperation::add);
      // Constrained rows keep the external force they were initialized
      // with: clear them (owned entries, written directly).
      {
        Epetra_FEVector &r = residual.trilinos_vector();
        for (const auto i : grid.locally_owned_dofs)
          if (constraints.is_constrained(i))
            r[0][r.Map().LID(static_cast<int>(i))] = 0.;
      }
      if (with_matrix)
        {
          matrix.compress(dealii::VectorOperation::add);
          // Rows of nodes without mass: identity scaled like the others.
          double max_diagonal = 0.;
          for (const auto i : grid.locally_owned_dofs)
            if (!constraints.is_constrained(i))
              max_diagonal =
                std::max(max_diagonal, std::abs(matrix.diag_element(i)));
          max_diagonal =
            dealii::Utilities::MPI::max(max_diagonal, grid.mpi_communicator);
          if (max_diagonal == 0.)
            max_diagonal = 1.;
          // 3D slip: derivative of the direction s = v_t/|v_t| of the
          // friction force -mu p s with respect to the tangential
          // increments, mu p (I - s s)/|v_t| dv/du (p lagged). It is
          // singular at v_t -> 0: in the Jacobian only, |v_t| is bounded
          // below by 1e-10 h/dt (a slip speed of 1e-18 m/s gave diagonals
          // of 1e23 and a singular factorisation in the 3D block run).
          if (dim == 3 && !grid.friction_boundaries.empty())
            {
              const double dv_du =
                quasi_static ? 1. / dt : newmark.gamma / (newmark.beta * dt);
              const double speed_floor =
                1e-10 * grid.minimal_cell_diameter / dt;
              for (const auto &fn : friction_nodes)
                if (fn.owned && fn.state == ContactState::slip && fn.mu > 0. &&
                    fn.tangential_dofs.size() == 2)
                  {
                    const double p = -fn.inward * raw_residual(fn.normal_dof);
                    dealii::Tensor<1, dim> v_t;
                    for (unsigned int k = 0; k < 2; ++k)
                      v_t[fn.tangential_components[k]] =
                        new_velocity(fn.tangential_dofs[k],
                                     du(fn.tangential_dofs[k]));
                    const double speed = std::max(v_t.norm(), speed_floor);
                    if (!(p > 0.))
                      continue;
                    for (unsigned int k = 0; k < 2; ++k)
                      for (unsigned int l = 0; l < 2; ++l)
                        {
                          const auto   ck = fn.tangential_components[k];
                          const auto   cl = fn.tangential_components[l];
                          const double value =
                            fn.mu * p *
                            ((k == l ? 1. : 0.) -
                             fn.slip_direction[ck] * fn.slip_direction[cl]) /
                            speed * dv_du;
                          matrix.add(fn.tangential_dofs[k],
                                     fn.tangential_dofs[l],
                                     value);
                        }
                  }
              matrix.compress(dealii::VectorOperation::add);
            }
          for (const auto i : grid.locally_owned_dofs)
            if (constraints.is_constrained(i) && matrix.diag_element(i) == 0.)
              matrix.set(i, i, max_diagonal);
          matrix.compress(dealii::VectorOperation::insert);
          if (dealii::Utilities::MPI::logical_or(boundary_states_changed,
                                                 grid.mpi_communicator))
            amg_current = false;
        }

      const bool all_ok =
        dealii::Utilities::MPI::min(ok ? 1 : 0, grid.mpi_communicator) == 1;
      if (!all_ok)
        {
          // Every rank reports the first failure of any rank.
          const auto all =
            dealii::Utilities::MPI::all_gather(grid.mpi_communicator, failure);
          for (const auto &f : all)
            if (!f.empty())
              {
                failure = f;
                break;
              }
        }
      return all_ok;
    }


    template <int dim>
    void
    MPMSolver<dim>::record_branch(
      const unsigned int                     k,
      const dealii::ArrayView<const double> &history) const
    {
      if (k >= point_branches.size())
        return;
      const int branch = static_cast<int>(model.return_branch(history));
      if (point_branches[k] >= 0 && point_branches[k] != branch)
        ++branch_changes;
      point_branches[k] = branch;
    }


    template <int dim>
    bool
    MPMSolver<dim>::fbar_cell(const CellCache            &c,
                              const std::vector<double>  &du_local,
                              dealii::Vector<double>     &r_local,
                              dealii::FullMatrix<double> *k_local,
                              std::string                &failure) const
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const unsigned int n_history     = points.n_history();

      std::vector<unsigned int> comp(dofs_per_cell), node(dofs_per_cell);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          comp[i] = fe.system_to_component_index(i).first;
          node[i] = fe.system_to_component_index(i).second;
        }
      std::vector<dealii::Tensor<2, dim>> F_n(c.n);
      std::vector<double>                 V0(c.n);
      for (unsigned int q = 0; q < c.n; ++q)
        {
          const auto props = particles[c.first + q]->get_properties();
          F_n[q]           = read_tensor<dim>(props, Properties::deformation);
          V0[q]            = props[Properties::initial_volume];
        }

      std::vector<double> history_new(n_history);
      const auto          model_call = [&](const unsigned int            q,
                                  const dealii::Tensor<2, dim> &F,
                                  dealii::Tensor<2, 3>         &P,
                                  dealii::Tensor<4, 3>         *A) -> bool {
        const auto props = particles[c.first + q]->get_properties();
        try
          {
            model.compute_stress(
              embed<dim>(F_n[q]),
              embed<dim>(F),
              dealii::ArrayView<const double>(props.data() +
                                                Properties::history,
                                              n_history),
              dealii::ArrayView<double>(history_new.data(), n_history),
              dt,
              P,
              A);
          }
        catch (const std::exception &e)
          {
            std::ostringstream msg;
            msg << "constitutive update failed at the material point near "
                << particles[c.first + q]->get_location() << ": " << e.what();
            failure = msg.str();
            return false;
          }
        if (k_local != nullptr)
          record_branch(c.first + q,
                        dealii::ArrayView<const double>(history_new.data(),
                                                        n_history));
        for (unsigned int d = 0; d < 3; ++d)
          for (unsigned int e = 0; e < 3; ++e)
            if (!std::isfinite(P[d][e]))
              {
                failure = "non-finite stress at a material point";
                return false;
              }
        return true;
      };

      const dealii::Tensor<1, dim> *dN = &shape_gradients[c.first * n_nodes];
      bool                          ok = true;
      if (k_local != nullptr)
        {
          using AD = CellAD<dim>;
          std::vector<AD> u(dofs_per_cell), f_int(dofs_per_cell);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              u[i]     = AD(dofs_per_cell, i, du_local[i]);
              f_int[i] = 0.;
            }
          ok = fbar_internal_forces<dim>(c.n,
                                         n_nodes,
                                         comp,
                                         node,
                                         u,
                                         dN,
                                         F_n,
                                         V0,
                                         model_call,
                                         f_int,
                                         nullptr);
          if (ok)
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              {
                r_local[i] -= f_int[i].val();
                for (unsigned int j = 0; j < dofs_per_cell; ++j)
                  (*k_local)(i, j) += f_int[i].dx(j);
              }
        }
      else
        {
          std::vector<double> f_int(dofs_per_cell, 0.);
          ok = fbar_internal_forces<dim>(c.n,
                                         n_nodes,
                                         comp,
                                         node,
                                         du_local,
                                         dN,
                                         F_n,
                                         V0,
                                         model_call,
                                         f_int,
                                         nullptr);
          if (ok)
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              r_local[i] -= f_int[i];
        }
      if (!ok && failure.empty())
        {
          std::ostringstream msg;
          msg << "a material point in the cell near " << c.cell->center()
              << " was inverted (det of the step's deformation gradient <= 0)";
          failure = msg.str();
        }
      return ok;
    }


    template <int dim>
    void
    MPMSolver<dim>::cell_deformation_gradients(
      const CellCache                     &c,
      const std::vector<double>           &du_local,
      std::vector<dealii::Tensor<2, dim>> &F_new) const
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      F_new.resize(c.n);
      std::vector<dealii::Tensor<2, dim>> f(c.n);
      std::vector<double>                 J(c.n), v(c.n);
      double                              J_bar = 0., v_sum = 0.;
      for (unsigned int q = 0; q < c.n; ++q)
        {
          const auto props = particles[c.first + q]->get_properties();
          const auto F_n   = read_tensor<dim>(props, Properties::deformation);
          const dealii::Tensor<1, dim> *dN =
            &shape_gradients[(c.first + q) * n_nodes];
          for (unsigned int d = 0; d < dim; ++d)
            f[q][d][d] = 1.;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              const auto ci = fe.system_to_component_index(i);
              f[q][ci.first] += du_local[i] * dN[ci.second];
            }
          F_new[q] = f[q] * F_n;
          J[q]     = dealii::determinant(f[q]);
          v[q] = props[Properties::initial_volume] * dealii::determinant(F_n);
          v_sum += v[q];
          J_bar += v[q] * J[q];
        }
      if (!use_fbar)
        return;
      J_bar /= v_sum;
      for (unsigned int q = 0; q < c.n; ++q)
        F_new[q] *= std::pow(J_bar / J[q], 1. / dim);
    }


    template <int dim>
    void
    MPMSolver<dim>::setup_friction_nodes()
    {
      friction_nodes.clear();
      friction_node_of.clear();
      const auto &dof_handler = grid.dof_handler;
      cell_touches_friction.assign(grid.triangulation.n_active_cells(), false);
      friction_corner_dofs = dealii::IndexSet(dof_handler.n_dofs());
      if (grid.friction_boundaries.empty())
        return;

      // Per grid vertex (keyed by its x dof): the friction boundaries it
      // lies on, as (axis, inward sign, mu), and its dofs.
      struct Candidate
      {
        std::vector<std::tuple<unsigned int, double, double>> faces;
        std::array<dealii::types::global_dof_index, dim>      dofs;
      };
      std::map<dealii::types::global_dof_index, Candidate> candidates;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            {
              const auto face = cell->face(f);
              if (!face->at_boundary())
                continue;
              const auto mu_it =
                grid.friction_boundaries.find(face->boundary_id());
              if (mu_it == grid.friction_boundaries.end())
                continue;
              dealii::Tensor<1, dim> n = face->center() - cell->center();
              n /= n.norm();
              int axis = -1;
              for (unsigned int d = 0; d < dim; ++d)
                if (std::abs(std::abs(n[d]) - 1.) < 1e-8)
                  axis = d;
              if (axis < 0)
                InputFile::reject("Background grid",
                                  "friction boundaries",
                                  std::to_string(face->boundary_id()) + ": " +
                                    std::to_string(mu_it->second),
                                  "friction is only possible on axis-aligned "
                                  "boundaries; boundary " +
                                    std::to_string(face->boundary_id()) +
                                    " is not axis aligned");
              const double inward = n[axis] > 0. ? -1. : 1.;
              cell_touches_friction[cell->active_cell_index()] = true;
              for (const unsigned int v : face->vertex_indices())
                {
                  Candidate &cand = candidates[face->vertex_dof_index(v, 0)];
                  for (unsigned int d = 0; d < dim; ++d)
                    cand.dofs[d] = face->vertex_dof_index(v, d);
                  bool known = false;
                  for (const auto &e : cand.faces)
                    known = known || (std::get<0>(e) == unsigned(axis) &&
                                      std::get<1>(e) == inward);
                  if (!known)
                    cand.faces.emplace_back(axis, inward, mu_it->second);
                }
            }
      // Cells that touch a friction node through a vertex only (not a face)
      // must combine rows too.
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            if (candidates.count(cell->vertex_dof_index(v, 0)))
              cell_touches_friction[cell->active_cell_index()] = true;

      for (const auto &[key, cand] : candidates)
        {
          (void)key;
          if (cand.faces.size() > 1)
            {
              for (const auto d : cand.dofs)
                friction_corner_dofs.add_index(d);
              continue;
            }
          const unsigned int axis = std::get<0>(cand.faces[0]);
          if (fixed_dofs.is_element(cand.dofs[axis]) ||
              slip_dofs[axis].is_element(cand.dofs[axis]))
            continue; // governed by the other condition
          FrictionNode fn;
          fn.normal_dof       = cand.dofs[axis];
          fn.normal_component = axis;
          fn.inward           = std::get<1>(cand.faces[0]);
          fn.mu               = std::get<2>(cand.faces[0]);
          fn.owned    = grid.locally_owned_dofs.is_element(fn.normal_dof);
          fn.state    = ContactState::free;
          fn.switches = 0;
          for (unsigned int d = 0; d < dim; ++d)
            if (d != axis && !fixed_dofs.is_element(cand.dofs[d]) &&
                !slip_dofs[d].is_element(cand.dofs[d]))
              {
                fn.tangential_dofs.push_back(cand.dofs[d]);
                fn.tangential_components.push_back(d);
              }
          friction_node_of[fn.normal_dof] = friction_nodes.size();
          friction_nodes.push_back(fn);
        }
      friction_corner_dofs.compress();
    }


    template <int dim>
    double
    MPMSolver<dim>::new_velocity(const dealii::types::global_dof_index i,
                                 const double du_i) const
    {
      if (quasi_static)
        return du_i / dt;
      const double a =
        newmark.acceleration(du_i, velocity_n(i), acceleration_n(i), dt);
      return newmark.velocity(velocity_n(i), acceleration_n(i), a, dt);
    }


    template <int dim>
    double
    MPMSolver<dim>::resting_increment(
      const dealii::types::global_dof_index i) const
    {
      if (quasi_static)
        return 0.;
      const double v = velocity_n(i);
      const double a = acceleration_n(i);
      // v_{n+1} = v + dt ((1 - gamma) a + gamma a_new) = 0
      const double a_new =
        -(v + dt * (1. - newmark.gamma) * a) / (newmark.gamma * dt);
      return dt * v +
             dt * dt * ((0.5 - newmark.beta) * a + newmark.beta * a_new);
    }


    template <int dim>
    void
    MPMSolver<dim>::exchange_friction_states()
    {
      // Owners write the state code at the normal dof (0 free, 1 stick,
      // 2 slip) and the slip direction at the tangential dofs; every rank
      // reads them for the nodes its cells touch.
      dealii::TrilinosWrappers::MPI::Vector owned(grid.locally_owned_dofs,
                                                  grid.mpi_communicator);
      Epetra_FEVector                      &e = owned.trilinos_vector();
      const auto set = [&](const dealii::types::global_dof_index i,
                           const double                          value) {
        e[0][e.Map().LID(static_cast<int>(i))] = value;
      };
      for (const auto &fn : friction_nodes)
        if (fn.owned)
          {
            set(fn.normal_dof,
                fn.state == ContactState::free  ? 0. :
                fn.state == ContactState::stick ? 1. :
                                                  2.);
            for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
              set(fn.tangential_dofs[k],
                  fn.slip_direction[fn.tangential_components[k]]);
          }
      dealii::TrilinosWrappers::MPI::Vector ghosted(grid.locally_owned_dofs,
                                                    grid.locally_relevant_dofs,
                                                    grid.mpi_communicator);
      ghosted = owned;
      for (auto &fn : friction_nodes)
        if (!fn.owned)
          {
            const double code = ghosted(fn.normal_dof);
            fn.state          = code < 0.5 ? ContactState::free :
                                code < 1.5 ? ContactState::stick :
                                             ContactState::slip;
            fn.slip_direction = 0.;
            for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
              fn.slip_direction[fn.tangential_components[k]] =
                ghosted(fn.tangential_dofs[k]);
          }
    }


    template <int dim>
    void
    MPMSolver<dim>::make_step_sparsity_pattern()
    {
      dealii::DynamicSparsityPattern dsp(grid.locally_relevant_dofs);
      for (const auto i : grid.locally_owned_dofs)
        dsp.add(i, i);
      const auto add_block =
        [&dsp](const std::vector<dealii::types::global_dof_index> &dofs) {
          std::vector<dealii::types::global_dof_index> sorted(dofs);
          std::sort(sorted.begin(), sorted.end());
          for (const auto i : sorted)
            dsp.add_entries(i, sorted.begin(), sorted.end(), true);
        };
      for (const auto &c : cells)
        add_block(c.dofs);
      for (const auto &c : boundary_cells)
        add_block(c.dofs);
      for (const auto &g : ghost_faces)
        add_block(g.dofs);
      dealii::SparsityTools::distribute_sparsity_pattern(
        dsp,
        grid.locally_owned_dofs,
        grid.mpi_communicator,
        grid.locally_relevant_dofs);
      // the preconditioners reference the matrix: release them first (ML's
      // Gauss-Seidel smoothers access it on destruction)
      factorisation.reset();
      direct_solver.reset();
      direct_problem.reset();
      amg.reset();
      amg_current = false;
      matrix.reinit(grid.locally_owned_dofs,
                    grid.locally_owned_dofs,
                    dsp,
                    grid.mpi_communicator);
    }


    template <int dim>
    void
    MPMSolver<dim>::apply_impact_friction()
    {
      if (grid.friction_boundaries.empty() || quasi_static)
        return;
      dealii::TrilinosWrappers::MPI::Vector owned(grid.locally_owned_dofs,
                                                  grid.mpi_communicator);
      owned                       = velocity_n;
      Epetra_FEVector &e          = owned.trilinos_vector();
      double           dissipated = 0.;
      for (const auto &fn : friction_nodes)
        {
          const double m = nodal_mass(fn.normal_dof);
          if (!fn.owned || m <= 0. || fn.mu == 0. || fn.tangential_dofs.empty())
            continue;
          const double v_n = fn.inward * velocity_n(fn.normal_dof);
          if (v_n >= 0.)
            continue;
          double v_t2 = 0.;
          for (const auto t : fn.tangential_dofs)
            v_t2 += velocity_n(t) * velocity_n(t);
          if (v_t2 <= 0.)
            continue;
          const double v_t   = std::sqrt(v_t2);
          const double scale = std::max(0., 1. - fn.mu * (-v_n) / v_t);
          for (const auto t : fn.tangential_dofs)
            e[0][e.Map().LID(static_cast<int>(t))] = scale * velocity_n(t);
          dissipated += 0.5 * m * v_t2 * (1. - scale * scale);
        }
      velocity_n = owned;
      step_impact_dissipation =
        dealii::Utilities::MPI::sum(dissipated, grid.mpi_communicator);
    }


    template <int dim>
    void
    MPMSolver<dim>::initialize_friction_states()
    {
      if (grid.friction_boundaries.empty())
        return;
      frozen_nodes = 0;
      for (auto &fn : friction_nodes)
        if (fn.owned)
          {
            // the state the previous step ended in (free before the first)
            const bool was_stuck = fn.state == ContactState::stick;
            fn.switches          = 0;
            fn.held              = false;
            fn.slip_direction    = 0.;
            if (nodal_mass(fn.normal_dof) <= 0.)
              {
                fn.state = ContactState::free;
                continue;
              }
            // 'friction separation = velocity': a node that moves away from
            // the boundary fast enough to lift off by a resolved height,
            // v_n^2 / (2 g_n) > f h, and faster than gravity brings it back
            // within the step, v_n > dt g_n / 2 (g_n: the part of gravity
            // pushing into the boundary), starts free: the reset does not
            // hold it back. If the step pushes it back into the boundary,
            // update_friction_states() closes the contact. ('pressure': all
            // nodes with mass start in contact.)
            if (grid.friction_separation_by_velocity && !quasi_static)
              {
                const double v_n = fn.inward * velocity_n(fn.normal_dof);
                const double g_n =
                  std::max(0.,
                           -fn.inward * gravity_vector[fn.normal_component]);
                // lift-off by more than the resolved height f h:
                // v_n^2 / (2 g_n) > f h
                const double h_cell =
                  grid.minimal_cell_diameter / std::sqrt(double(dim));
                const double v_lift =
                  std::sqrt(2. * grid.separation_lift_height * g_n * h_cell);
                if (v_n > std::max({v_lift,
                                    0.5 * dt * g_n,
                                    1e-9 * grid.minimal_cell_diameter / dt}))
                  {
                    fn.state = ContactState::free;
                    continue;
                  }
              }
            // Otherwise in contact at the start of the step (the grid is
            // reset onto the boundary); slipping if it carries a tangential
            // velocity (or accelerates: starting to slide from rest).
            dealii::Tensor<1, dim> v_t, a_t;
            for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
              {
                v_t[fn.tangential_components[k]] =
                  velocity_n(fn.tangential_dofs[k]);
                a_t[fn.tangential_components[k]] =
                  acceleration_n(fn.tangential_dofs[k]);
              }
            const dealii::Tensor<1, dim> direction =
              v_t.norm() > 0. ? v_t : a_t;
            if (fn.mu == 0. || fn.tangential_dofs.empty())
              fn.state = ContactState::slip;
            else if (was_stuck && grid.friction_guess_from_previous_step &&
                     v_t.norm() <=
                       fn.mu *
                         std::max(0.,
                                  -fn.inward *
                                    gravity_vector[fn.normal_component]) *
                         dt)
              // stuck before, and friction under the node's weight can stop
              // its projected tangential velocity within the step
              fn.state = ContactState::stick;
            else
              fn.state = direction.norm() > 0. ? ContactState::slip :
                                                 ContactState::stick;
            if (direction.norm() > 0.)
              fn.slip_direction = direction / direction.norm();
          }
      exchange_friction_states();
    }


    template <int dim>
    unsigned int
    MPMSolver<dim>::update_friction_states(
      dealii::TrilinosWrappers::MPI::Vector &du)
    {
      if (grid.friction_boundaries.empty())
        return 0;
      constexpr unsigned int max_switches = 4;
      // Tolerances against chattering on round-off: a stuck node slips
      // when the needed force exceeds mu p by 1e-6 relative, a slipping
      // node sticks when its velocity reverses by more than 1e-9 cell
      // sizes per step, contact opens below -1e-10 times the node weight.
      const double length_tol = 1e-10 * grid.minimal_cell_diameter;
      const double speed_tol  = 1e-9 * grid.minimal_cell_diameter / dt;
      unsigned int changed    = 0;
      std::vector<std::pair<dealii::types::global_dof_index, double>> values;
      std::vector<dealii::types::global_dof_index>                    released;
      // Project the increment onto the constraints of a node's new state.
      const auto project_increment = [&](const FrictionNode &fn) {
        if (fn.state != ContactState::free)
          values.emplace_back(fn.normal_dof, 0.);
        if (fn.state == ContactState::stick)
          for (const auto t : fn.tangential_dofs)
            values.emplace_back(t, resting_increment(t));
      };
      for (auto &fn : friction_nodes)
        {
          if (!fn.owned || nodal_mass(fn.normal_dof) <= 0.)
            continue;
          const ContactState           old_state     = fn.state;
          const dealii::Tensor<1, dim> old_direction = fn.slip_direction;
          // contact pressure (force) and tangential reaction
          const double p = -fn.inward * raw_residual(fn.normal_dof);
          const double pressure_tol =
            1e-10 * nodal_mass(fn.normal_dof) * gravity_vector.norm();
          dealii::Tensor<1, dim> R_t, v_t;
          for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
            {
              const auto t = fn.tangential_dofs[k];
              const auto d = fn.tangential_components[k];
              R_t[d]       = -raw_residual(t);
              v_t[d]       = new_velocity(t, du(t));
            }
          switch (fn.state)
            {
              case ContactState::free:
                // Closing contact: a node that arrives with a tangential
                // velocity slides (its friction is then bounded by mu p);
                // one that arrives at rest sticks.
                if (fn.inward * du(fn.normal_dof) < -length_tol)
                  {
                    if (fn.mu == 0. || fn.tangential_dofs.empty())
                      fn.state = ContactState::slip;
                    else if (v_t.norm() > speed_tol)
                      {
                        fn.state          = ContactState::slip;
                        fn.slip_direction = v_t / v_t.norm();
                      }
                    else
                      fn.state = ContactState::stick;
                  }
                break;
              case ContactState::stick:
                if (p < -pressure_tol)
                  fn.state = ContactState::free;
                else if (R_t.norm() > fn.mu * p * (1. + 1e-6))
                  {
                    fn.state          = ContactState::slip;
                    fn.slip_direction = -R_t / R_t.norm();
                  }
                break;
              case ContactState::slip:
                if (p < -pressure_tol)
                  fn.state = ContactState::free;
                else if (fn.mu > 0. && !fn.tangential_dofs.empty())
                  {
                    if (v_t * fn.slip_direction < -speed_tol)
                      fn.state = ContactState::stick;
                    else if (dim == 3 && v_t.norm() > 0.)
                      fn.slip_direction = v_t / v_t.norm();
                  }
                break;
            }
          const bool state_changed = fn.state != old_state;
          if (std::getenv("TALUS_DEBUG_FRICTION") && state_changed)
            std::cerr << "node " << fn.normal_dof << " " << int(old_state)
                      << " -> " << int(fn.state) << " p = " << p
                      << " R_t = " << R_t << " v_t = " << v_t
                      << " du_n = " << du(fn.normal_dof) << std::endl;
          const bool direction_changed =
            fn.state == ContactState::slip &&
            (fn.slip_direction - old_direction).norm() > 1e-8;
          if (!state_changed && !direction_changed)
            continue;
          if (state_changed && ++fn.switches > max_switches)
            {
              // Cycling between states: keep the previous one, except
              // between stick and slip: there the node is held stuck
              // (reported after convergence with the size of the
              // violation). The cycle means the solution sits at the kink
              // of Coulomb's law, a tangential force of mu p at nearly zero
              // speed. Held in slip, the node may move against its slip
              // direction, so that the friction force does positive work
              // (measured under the plane-strain block of
              // contrib/granular/block_rest_study.sh at 25 mm: up to 0.26
              // m/s backwards, in 362 of 1175 steps above 5 mm/s); held
              // stuck, it does not move and its reaction exceeds mu p.
              const bool stick_slip_cycle = (old_state == ContactState::stick &&
                                             fn.state == ContactState::slip) ||
                                            (old_state == ContactState::slip &&
                                             fn.state == ContactState::stick);
              fn.state = stick_slip_cycle ? ContactState::stick : old_state;
              fn.slip_direction = old_direction;
              if (fn.state != old_state)
                {
                  project_increment(fn);
                  ++changed;
                }
              if (!fn.held)
                ++frozen_nodes;
              fn.held = true;
              continue;
            }
          ++changed;
          // A node released from contact leaves with the normal velocity
          // the particles gave it: the reset had set it to zero, which
          // would pull it back without friction.
          if (old_state != ContactState::free &&
              fn.state == ContactState::free && !quasi_static)
            released.push_back(fn.normal_dof);
          project_increment(fn);
        }
      changed = dealii::Utilities::MPI::sum(changed, grid.mpi_communicator);
      if (changed == 0)
        return 0;
      {
        // The new states' values enter the next correction as
        // inhomogeneous constraints (make_constraints()).
        contact_targets = values;
        dealii::TrilinosWrappers::MPI::Vector jump(grid.locally_owned_dofs,
                                                   grid.mpi_communicator);
        Epetra_FEVector                      &e = jump.trilinos_vector();
        for (const auto &[i, value] : values)
          e[0][e.Map().LID(static_cast<int>(i))] = value - du(i);
        contact_jump.reinit(grid.locally_owned_dofs,
                            grid.locally_relevant_dofs,
                            grid.mpi_communicator);
        contact_jump        = jump;
        contact_jump_active = true;
      }
      if (dealii::Utilities::MPI::sum(released.size(), grid.mpi_communicator) >
          0)
        {
          // their cells' inertia changes: a re-assembly at this iterate
          // evaluates them again
          inertia_changed_dofs.clear();
          for (const auto &r :
               dealii::Utilities::MPI::all_gather(grid.mpi_communicator,
                                                  released))
            inertia_changed_dofs.insert(inertia_changed_dofs.end(),
                                        r.begin(),
                                        r.end());
          std::sort(inertia_changed_dofs.begin(), inertia_changed_dofs.end());
          dealii::TrilinosWrappers::MPI::Vector owned(grid.locally_owned_dofs,
                                                      grid.mpi_communicator);
          owned                     = velocity_n;
          Epetra_FEVector &e        = owned.trilinos_vector();
          double           restored = 0.;
          for (const auto i : released)
            {
              const int    l = e.Map().LID(static_cast<int>(i));
              const double v = velocity_p2g(i);
              restored += 0.5 * nodal_mass(i) * (v * v - e[0][l] * e[0][l]);
              e[0][l] = v;
            }
          velocity_n = owned;
          step_reset_dissipation -=
            dealii::Utilities::MPI::sum(restored, grid.mpi_communicator);
        }
      exchange_friction_states();
      make_constraints();
      amg_current = false;
      return changed;
    }


    template <int dim>
    unsigned int
    MPMSolver<dim>::solve_linear(dealii::TrilinosWrappers::MPI::Vector &x)
    {
      dealii::TimerOutput::Scope scope(timer, "linear solver");
      if (with_lagrange_multipliers)
        return solve_saddle_point(x);
      return solve_with_tangent(x, residual);
    }


    template <int dim>
    void
    MPMSolver<dim>::build_amg()
    {
      dealii::TimerOutput::Scope s(timer, "AMG setup");
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.constant_modes        = constant_modes;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.smoother_type         = amg_smoother.c_str();
      data.aggregation_threshold = 0.02;
      // ML parameters with the rigid body modes (translations and
      // rotations) as near null space; deal.II 9.4's AdditionalData only
      // takes the translations.
      Teuchos::ParameterList              parameters;
      std::unique_ptr<Epetra_MultiVector> translations;
      data.set_parameters(parameters, translations, matrix);
      const Epetra_Map  &map     = matrix.trilinos_matrix().DomainMap();
      const unsigned int n_modes = dim == 2 ? 3 : 6;
      rigid_body_modes = std::make_unique<Epetra_MultiVector>(map, n_modes);
      for (int l = 0; l < map.NumMyElements(); ++l)
        {
          const auto global =
            static_cast<dealii::types::global_dof_index>(map.GID(l));
          const auto local_index =
            grid.locally_owned_dofs.index_within_set(global);
          const auto        &x = owned_support_points[local_index];
          const unsigned int c = owned_components[local_index];
          double            *v = (*rigid_body_modes)[0];
          const int          n = map.NumMyElements();
          for (unsigned int m = 0; m < n_modes; ++m)
            v[m * n + l] = 0.;
          v[c * n + l] = 1.; // translation in direction c
          if (dim == 2)
            v[2 * n + l] = (c == 0 ? -x[1] : x[0]);
          else
            {
              // rotations about x, y, z
              const double rx[3] = {0., -x[2], x[1]};
              const double ry[3] = {x[2], 0., -x[0]};
              const double rz[3] = {-x[1], x[0], 0.};
              v[3 * n + l]       = rx[c];
              v[4 * n + l]       = ry[c];
              v[5 * n + l]       = rz[c];
            }
        }
      parameters.set("null space: type", "pre-computed");
      parameters.set("null space: dimension", static_cast<int>(n_modes));
      parameters.set("null space: vectors", rigid_body_modes->Values());
      amg = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
      amg->initialize(matrix, parameters);
    }


    template <int dim>
    unsigned int
    MPMSolver<dim>::solve_with_tangent(
      dealii::TrilinosWrappers::MPI::Vector       &x,
      const dealii::TrilinosWrappers::MPI::Vector &b)
    {
      x = 0.;
      if (linear_solver_type == "direct")
        {
          if (factorisation)
            factorisation->solve(x, b);
          else
            {
              if (!direct_solver)
                {
                  direct_problem = std::make_unique<Epetra_LinearProblem>();
                  direct_problem->SetOperator(
                    const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()));
                  Amesos factory;
                  direct_solver.reset(
                    factory.Create("Amesos_Klu", *direct_problem));
                  AssertThrow(direct_solver != nullptr,
                              dealii::ExcMessage(
                                "Amesos KLU is not available"));
                  // Later factorisations of the step reuse the pivot
                  // sequence of the first (klu_refactor); Amesos falls back
                  // to a factorisation with pivoting if that fails or if
                  // its estimate of the reciprocal condition number (the
                  // ratio of the smallest to the largest pivot) is below
                  // 1e-6 (Amesos' default: 1e-12).
                  Teuchos::ParameterList parameters;
                  parameters.set("Refactorize", true);
                  parameters.set("RcondThreshold", 1e-6);
                  direct_solver->SetParameters(parameters);
                  AssertThrow(direct_solver->SymbolicFactorization() == 0,
                              dealii::ExcMessage(
                                "the symbolic factorisation of the tangent "
                                "(Amesos KLU) failed"));
                }
              direct_problem->SetLHS(&x.trilinos_vector());
              direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
                static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
              const int factorised = direct_solver->NumericFactorization();
              AssertThrow(factorised == 0,
                          dealii::ExcMessage(
                            "the factorisation of the tangent (Amesos KLU) "
                            "failed with error code " +
                            std::to_string(factorised) +
                            " (a singular tangent?)"));
              const int solve_status = direct_solver->Solve();
              AssertThrow(solve_status == 0,
                          dealii::ExcMessage(
                            "the direct solve with the tangent (Amesos KLU) "
                            "failed with error code " +
                            std::to_string(solve_status)));
            }
          constraints.distribute(x);
          return 1;
        }

      // The AMG hierarchy is built at the first Newton iteration of a step
      // and reused by the later ones (the tangent changes little); if the
      // Krylov solver fails with a reused hierarchy, it is rebuilt once.
      bool fresh = false;
      if (!amg || !reuse_preconditioner || !amg_current)
        {
          build_amg();
          amg_current = true;
          fresh       = true;
        }

      const auto krylov = [&](dealii::SolverControl &control) {
        x = 0.;
        if (linear_solver_type == "CG")
          {
            dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> solver(
              control);
            solver.solve(matrix, x, b, *amg);
          }
        else
          {
            // right preconditioning: the convergence test then sees the
            // true residual |b - A x| that the tolerance refers to (with
            // left preconditioning deal.II tests |P^-1 (b - A x)|, a
            // displacement, against a force)
            dealii::SolverGMRES<
              dealii::TrilinosWrappers::MPI::Vector>::AdditionalData data;
            data.right_preconditioning = true;
            dealii::SolverGMRES<dealii::TrilinosWrappers::MPI::Vector> solver(
              control, data);
            solver.solve(matrix, x, b, *amg);
          }
      };
      dealii::SolverControl control(max_linear_iterations,
                                    linear_tolerance * b.l2_norm());
      try
        {
          krylov(control);
        }
      catch (const dealii::SolverControl::NoConvergence &)
        {
          if (fresh)
            throw;
          build_amg();
          krylov(control);
        }
      if (std::getenv("TALUS_DEBUG_LINEAR") &&
          dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) == 0)
        std::cerr << "    Krylov " << control.last_step() << std::endl;
      constraints.distribute(x);
      return control.last_step();
    }


    template <int dim>
    unsigned int
    MPMSolver<dim>::solve_saddle_point(dealii::TrilinosWrappers::MPI::Vector &x)
    {
      using Vector                     = dealii::TrilinosWrappers::MPI::Vector;
      const auto        &fe            = grid.fe;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const MPI_Comm     comm          = grid.mpi_communicator;

      // the multiplier points of this rank and their cells' dofs
      std::vector<BoundaryPoint *>                                      lm;
      std::vector<const std::vector<dealii::types::global_dof_index> *> dofs;
      for (const auto &c : boundary_cells)
        for (unsigned int b = 0; b < c.n_boundary; ++b)
          if (boundary_points[c.first_boundary + b].monolithic)
            {
              lm.push_back(&boundary_points[c.first_boundary + b]);
              dofs.push_back(&c.dofs);
            }
      const dealii::IndexSet owned =
        dealii::Utilities::MPI::create_ascending_partitioning(
          comm,
          lm.size() * dim)[dealii::Utilities::MPI::this_mpi_process(comm)];
      std::vector<unsigned int> comp(dofs_per_cell), node(dofs_per_cell);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          comp[i] = fe.system_to_component_index(i).first;
          node[i] = fe.system_to_component_index(i).second;
        }

      // N z at the multiplier points for an owned grid vector z
      Vector     z_ghosted(grid.locally_owned_dofs,
                       grid.locally_relevant_dofs,
                       comm);
      const auto interpolate = [&](const Vector &z) {
        z_ghosted = z;
        std::vector<dealii::Tensor<1, dim>> values(lm.size());
        for (unsigned int p = 0; p < lm.size(); ++p)
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            values[p][comp[i]] += lm[p]->N[node[i]] * z_ghosted((*dofs[p])[i]);
        return values;
      };
      // N^T D y on the grid for a multiplier vector y
      dealii::Vector<double> r_local(dofs_per_cell);
      const auto             spread = [&](const Vector &y, Vector &t) {
        t = 0.;
        for (unsigned int p = 0; p < lm.size(); ++p)
          {
            dealii::Tensor<1, dim> yp;
            for (unsigned int d = 0; d < dim; ++d)
              yp[d] = y.begin()[p * dim + d];
            const dealii::Tensor<1, dim> f = lm[p]->lm_D * yp;
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              r_local[i] = lm[p]->N[node[i]] * f[comp[i]];
            constraints.distribute_local_to_global(r_local, *dofs[p], t);
          }
        t.compress(dealii::VectorOperation::add);
      };

      unsigned int n_iterations = 0;
      Vector       t(grid.locally_owned_dofs, comm), z(t);
      // the Schur complement S y = E y + D N A^-1 N^T D y, plus a
      // compliance 1e-6 / k on the active directions: in 3D the cell-wise
      // multipliers of neighbouring cut cells can constrain the same few
      // massive nodes, which makes S singular (Newton did not converge on
      // the rotated plane). Only the Jacobian changes, not the residual,
      // so the converged constraint is still exact.
      const double regularisation = 1e-6;
      struct Operator
      {
        std::function<void(Vector &, const Vector &)> apply;
        void
        vmult(Vector &dst, const Vector &src) const
        {
          apply(dst, src);
        }
      };
      // the multipliers' rows E y + D (N x): dst_p = (y_p - D y_p) / k +
      // D Nx_p + regularisation D y_p / k, given Nx = N x at the points
      const auto multiplier_rows =
        [&](Vector                                    &dst,
            const Vector                              &y,
            const std::vector<dealii::Tensor<1, dim>> &Nx) {
          for (unsigned int p = 0; p < lm.size(); ++p)
            {
              const double           k = lm[p]->beta * lm[p]->weight;
              dealii::Tensor<1, dim> yp;
              for (unsigned int d = 0; d < dim; ++d)
                yp[d] = y.begin()[p * dim + d];
              const dealii::Tensor<1, dim> row =
                (yp - lm[p]->lm_D * yp) / k + lm[p]->lm_D * Nx[p] +
                regularisation * (lm[p]->lm_D * yp) / k;
              for (unsigned int d = 0; d < dim; ++d)
                dst.begin()[p * dim + d] = row[d];
            }
        };
      const Operator schur{[&](Vector &dst, const Vector &src) {
        spread(src, t);
        n_iterations += solve_with_tangent(z, t);
        multiplier_rows(dst, src, interpolate(z));
      }};
      // Preconditioner: S with A replaced by its diagonal and only the
      // point's own block, P = (I - D) / k + D C D with
      // C = diag_c(sum_i N_i^2 / A_ii,c), inverted point by point.
      std::vector<dealii::Tensor<2, dim>> P_inverse(lm.size());
      {
        Vector diagonal(grid.locally_owned_dofs, comm);
        for (const auto i : grid.locally_owned_dofs)
          diagonal(i) = matrix.diag_element(i);
        diagonal.compress(dealii::VectorOperation::insert);
        z_ghosted = diagonal;
        for (unsigned int p = 0; p < lm.size(); ++p)
          {
            const double           k = lm[p]->beta * lm[p]->weight;
            dealii::Tensor<2, dim> C;
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              {
                const double a_ii = z_ghosted((*dofs[p])[i]);
                if (a_ii > 0. && !constraints.is_constrained((*dofs[p])[i]))
                  C[comp[i]][comp[i]] +=
                    lm[p]->N[node[i]] * lm[p]->N[node[i]] / a_ii;
              }
            const dealii::Tensor<2, dim> &D = lm[p]->lm_D;
            const dealii::Tensor<2, dim>  P =
              (dealii::unit_symmetric_tensor<dim>() - D) / k + D * C * D +
              regularisation * D / k;
            const double det = dealii::determinant(P);
            P_inverse[p]     = std::abs(det) > 1e-12 * std::pow(1. / k, dim) ?
                                 dealii::invert(P) :
                                 dealii::Tensor<2, dim>(
                               k * dealii::unit_symmetric_tensor<dim>());
          }
      }
      const Operator preconditioner{[&](Vector &dst, const Vector &src) {
        for (unsigned int p = 0; p < lm.size(); ++p)
          {
            dealii::Tensor<1, dim> yp;
            for (unsigned int d = 0; d < dim; ++d)
              yp[d] = src.begin()[p * dim + d];
            const dealii::Tensor<1, dim> q = P_inverse[p] * yp;
            for (unsigned int d = 0; d < dim; ++d)
              dst.begin()[p * dim + d] = q[d];
          }
      }};

      dealii::SolverControl factorisation_control(1, 0.);
      if (linear_solver_type == "direct")
        {
          factorisation =
            std::make_unique<dealii::TrilinosWrappers::SolverDirect>(
              factorisation_control);
          dealii::TimerOutput::Scope s(timer, "factorisation");
          factorisation->initialize(matrix);
        }
      if (block_saddle_point)
        try
          {
            // FGMRES on [A C; B E] [x; y] = [r; s] (C = -N^T D, B = D N,
            // E as in the Schur operator) with the block upper-triangular
            // preconditioner [A~ C; 0 S~]: y = S~^-1 b_y (point-wise
            // P_inverse), x = A~^-1 (b_x - C y) with A~^-1 one AMG V-cycle
            // (the factorisation with 'direct'). Constrained dofs are kept
            // at zero in every vector that reaches the multipliers.
            using BlockVector = dealii::TrilinosWrappers::MPI::BlockVector;
            const std::vector<dealii::IndexSet> partitioning = {
              grid.locally_owned_dofs, owned};
            bool fresh_amg = false;
            if (linear_solver_type != "direct" &&
                (!amg || !reuse_preconditioner || !amg_current))
              {
                build_amg();
                amg_current = true;
                fresh_amg   = true;
              }
            BlockVector solution(partitioning, comm), rhs(partitioning, comm);
            rhs.block(0) = residual;
            for (unsigned int p = 0; p < lm.size(); ++p)
              {
                const double                 k = lm[p]->beta * lm[p]->weight;
                const dealii::Tensor<1, dim> s =
                  (lm[p]->lm_force - lm[p]->lambda) / k;
                for (unsigned int d = 0; d < dim; ++d)
                  rhs.block(1).begin()[p * dim + d] = k * s[d];
              }
            Vector     masked(grid.locally_owned_dofs, comm);
            const auto apply_A_inverse = [&](Vector &dst, const Vector &src) {
              if (linear_solver_type == "direct")
                factorisation->solve(dst, src);
              else
                amg->vmult(dst, src);
              constraints.set_zero(dst);
            };
            struct BlockOperator
            {
              std::function<void(BlockVector &, const BlockVector &)> apply;
              void
              vmult(BlockVector &dst, const BlockVector &src) const
              {
                apply(dst, src);
              }
            };
            // The multiplier rows are gaps [m]; scaled by each point's k
            // they become forces [N] like the momentum rows, so that the
            // FGMRES residual weighs both blocks alike (unscaled, the
            // gap rows of a first contact could be left unsolved below a
            // tolerance set by the force rows).
            Vector     scaled(owned, comm);
            const auto scale_rows = [&](Vector &v) {
              for (unsigned int p = 0; p < lm.size(); ++p)
                for (unsigned int d = 0; d < dim; ++d)
                  v.begin()[p * dim + d] *= lm[p]->beta * lm[p]->weight;
            };
            const auto unscale_rows = [&](Vector &v) {
              for (unsigned int p = 0; p < lm.size(); ++p)
                for (unsigned int d = 0; d < dim; ++d)
                  v.begin()[p * dim + d] /= lm[p]->beta * lm[p]->weight;
            };
            // initial guess: x = A~^-1 r, y = 0
            apply_A_inverse(solution.block(0), residual);
            const BlockOperator system{[&](BlockVector       &dst,
                                           const BlockVector &src) {
              masked = src.block(0);
              constraints.set_zero(masked);
              matrix.vmult(dst.block(0), masked);
              spread(src.block(1), t);
              dst.block(0) -= t;
              multiplier_rows(dst.block(1), src.block(1), interpolate(masked));
              scale_rows(dst.block(1));
            }};
            const BlockOperator block_preconditioner{
              [&](BlockVector &dst, const BlockVector &src) {
                scaled = src.block(1);
                unscale_rows(scaled);
                preconditioner.vmult(dst.block(1), scaled);
                spread(dst.block(1), t);
                t += src.block(0);
                apply_A_inverse(dst.block(0), t);
              }};
            dealii::SolverControl             control(max_linear_iterations,
                                          linear_tolerance * rhs.l2_norm());
            dealii::SolverFGMRES<BlockVector> fgmres(
              control, dealii::SolverFGMRES<BlockVector>::AdditionalData(100));
            try
              {
                fgmres.solve(system, solution, rhs, block_preconditioner);
              }
            catch (const dealii::SolverControl::NoConvergence &)
              {
                // a hierarchy reused from an earlier Newton iteration may
                // no longer fit A (the contact states changed): rebuild it
                // once and start again
                if (linear_solver_type == "direct" || fresh_amg)
                  throw;
                n_iterations += control.last_step();
                build_amg();
                apply_A_inverse(solution.block(0), residual);
                solution.block(1) = 0.;
                fgmres.solve(system, solution, rhs, block_preconditioner);
              }
            n_iterations += control.last_step();
            if (std::getenv("TALUS_DEBUG_NEWTON"))
              {
                BlockVector check(partitioning, comm);
                system.vmult(check, solution);
                check -= rhs;
                const double r0 = check.block(0).l2_norm(),
                             r1 = check.block(1).l2_norm();
                if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
                  std::cerr << "    block residual: force " << r0 << " / "
                            << rhs.block(0).l2_norm() << ", gap " << r1 << " / "
                            << rhs.block(1).l2_norm() << std::endl;
              }
            x = solution.block(0);
            constraints.set_zero(x);
            constraints.distribute(x);
            if (std::getenv("TALUS_DEBUG_NEWTON") &&
                dealii::Utilities::MPI::this_mpi_process(comm) == 0)
              std::cerr << "    saddle point (block): " << owned.size()
                        << " multipliers, FGMRES " << control.last_step()
                        << std::endl;
            for (unsigned int p = 0; p < lm.size(); ++p)
              for (unsigned int d = 0; d < dim; ++d)
                lm[p]->dlambda[d] = solution.block(1).begin()[p * dim + d];
            factorisation.reset();
            return n_iterations;
          }
        catch (...)
          {
            factorisation.reset();
            throw;
          }
      try
        {
          // x0 = A^-1 r and the right-hand side s - D N x0
          n_iterations += solve_with_tangent(x, residual);
          const auto Nx0 = interpolate(x);
          Vector     y(owned, comm), rhs(owned, comm);
          for (unsigned int p = 0; p < lm.size(); ++p)
            {
              const double                 k = lm[p]->beta * lm[p]->weight;
              const dealii::Tensor<1, dim> s =
                (lm[p]->lm_force - lm[p]->lambda) / k - lm[p]->lm_D * Nx0[p];
              for (unsigned int d = 0; d < dim; ++d)
                rhs.begin()[p * dim + d] = s[d];
            }
          dealii::SolverControl       control(max_linear_iterations,
                                        linear_tolerance * rhs.l2_norm());
          dealii::SolverGMRES<Vector> gmres(
            control, dealii::SolverGMRES<Vector>::AdditionalData(100));
          gmres.solve(schur, y, rhs, preconditioner);
          // x = x0 + A^-1 N^T D y
          spread(y, t);
          n_iterations += solve_with_tangent(z, t);
          x += z;
          if (std::getenv("TALUS_DEBUG_NEWTON"))
            {
              const double r_norm = rhs.l2_norm(), y_norm = y.l2_norm(),
                           x_norm = x.l2_norm();
              if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
                std::cerr << "    saddle point: " << y.size()
                          << " multipliers, |s - D N x0| " << r_norm
                          << ", GMRES " << control.last_step() << ", |dlambda| "
                          << y_norm << ", |du| " << x_norm << std::endl;
            }
          for (unsigned int p = 0; p < lm.size(); ++p)
            for (unsigned int d = 0; d < dim; ++d)
              lm[p]->dlambda[d] = y.begin()[p * dim + d];
        }
      catch (...)
        {
          factorisation.reset();
          throw;
        }
      factorisation.reset();
      return n_iterations;
    }


    template <int dim>
    NewtonResult
    MPMSolver<dim>::solve_step()
    {
      dealii::TimerOutput::Scope scope(timer, "solve (Newton)");
      Assert(prepared, dealii::ExcMessage("prepare_step() first"));
      NewtonResult result;

      dealii::TrilinosWrappers::MPI::Vector du(grid.locally_owned_dofs,
                                               grid.mpi_communicator);
      displacement            = du;
      const double f_ext_norm = external_force.l2_norm();
      double       reference  = 0.;
      const bool   newmark_predictor =
        predictor == "constant acceleration" ||
        (predictor == "automatic" && boundary_particles == nullptr);
      if (newmark_predictor && !quasi_static)
        {
          // The reference of the convergence test stays the residual at
          // du = 0, as without the predictor.
          std::string failure;
          {
            dealii::TimerOutput::Scope s(timer, "assembly");
            if (!assemble(displacement, false, true, failure))
              {
                result.failure = failure;
                return result;
              }
          }
          const double r0 = residual.l2_norm();
          if (!std::isfinite(r0))
            {
              result.failure = "the residual is not finite";
              return result;
            }
          reference = std::max(r0, f_ext_norm);
          // du = dt v_n + dt^2/2 a_n at the free nodes with mass; v_n and
          // a_n are zero at the constrained ones (prepare_step()).
          for (const auto i : grid.locally_owned_dofs)
            if (!constraints.is_constrained(i) && nodal_mass(i) > 0.)
              du(i) = dt * velocity_n(i) + 0.5 * dt * dt * acceleration_n(i);
          du.compress(dealii::VectorOperation::insert);
          displacement = du;
        }
      // Augmented Lagrangian boundaries: after each converged Newton solve
      // the multipliers take the boundary forces (Uzawa) and Newton runs
      // again from the solution, until the gaps are below the tolerance.
      const bool augmented =
        boundary_particles != nullptr && boundary_particles->any_augmented();
      const unsigned int max_updates =
        augmented ? boundary_particles->max_multiplier_updates() : 0;
      for (unsigned int update = 0;; ++update)
        {
          const unsigned int iterations_before = result.iterations;
          newton_solve(du, f_ext_norm, reference, result);
          result.iterations += iterations_before;
          if (!result.converged || !augmented)
            return result;
          result.constraint_gap = update_multipliers();
          if (result.constraint_gap <=
              boundary_particles->multiplier_tolerance())
            return result;
          if (update == max_updates)
            {
              std::ostringstream msg;
              msg << "the augmented Lagrangian boundary gaps did not converge "
                     "in "
                  << max_updates << " multiplier updates (largest gap "
                  << result.constraint_gap << " m, tolerance "
                  << boundary_particles->multiplier_tolerance()
                  << " m); raise the penalty factor or 'maximum "
                     "multiplier updates'";
              result.converged = false;
              result.failure   = msg.str();
              solved           = false;
              return result;
            }
          ++result.multiplier_updates;
          result.converged = false;
          solved           = false;
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::newton_solve(dealii::TrilinosWrappers::MPI::Vector &du,
                                 const double  f_ext_norm,
                                 double       &reference,
                                 NewtonResult &result)
    {
      for (auto &bp : boundary_points)
        {
          bp.last_state = -1;
          bp.switches   = 0;
          if (bp.monolithic)
            bp.frozen = -1;
        }
      contact_targets.clear();
      contact_jump_active   = false;
      displacement          = du;
      double last_increment = 0.;
      // the residual norm at which the last correction was computed
      double residual_at_correction = 0.;
      // contact states are updated only from a solution of the current
      // linear system
      bool         solved_since_update = false;
      unsigned int contact_rounds      = 0;
      // the reference residual is that of the first Newton solve of the
      // step (later solves after multiplier updates start near it)
      const bool first_solve = reference == 0.;

      // Iterations granted after a correction of held multiplier states
      // (below): the correction restarts the semi-smooth Newton iteration
      // from a changed active set, which needs a few iterations again.
      unsigned int granted_iterations = 0;
      // Iterations whose correction changed the return branch of a
      // material point (not counted toward max_newton_iterations, up to
      // max_state_change_newton_iterations in all).
      unsigned int state_change_iterations = 0;
      // iterations without a new minimum of the residual after which state
      // changes no longer extend the iteration
      constexpr unsigned int stall_iterations = 10;
      double                 best_residual = std::numeric_limits<double>::max();
      unsigned int           best_iteration = 0;
      point_branches.assign(particles.size(), -1);
      // changes since the last correction (re-assemblies after contact
      // state updates included)
      branch_changes = 0;
      // The line search's first trial (the full correction) is assembled
      // with the matrix when that matrix is the one the next iteration
      // needs: same iterate, same constraints, no boundary particles (whose
      // states a matrix assembly updates). Accepted, it saves the next
      // iteration's assembly; rejected, it costs the tangent once, so it is
      // tried only while full corrections are accepted (the thin granular
      // layer of contrib/granular/thin_layer_stop.prm rejects every second
      // one; the collapse almost none).
      bool assembled_at_iterate = false;
      bool full_step_accepted   = true;
      // the next assembly is at the iterate of the last one, after a
      // contact state update
      bool contact_reassembly = false;
      // The line search found no step along the last correction that
      // lowers the residual of an iterate which already meets the residual
      // tolerance: the iteration stays at that iterate and accepts it
      // (below).
      bool no_descent_at_converged_residual = false;
      for (unsigned int it = 0;
           it <=
           max_newton_iterations + granted_iterations + state_change_iterations;
           ++it)
        {
          std::string failure;
          bool        ok;
          if (assembled_at_iterate)
            {
              assembled_at_iterate = false;
              ok                   = true;
            }
          else
            {
              dealii::TimerOutput::Scope s(timer, "assembly");
              ok = assemble(
                displacement, true, !quasi_static, failure, contact_reassembly);
            }
          contact_reassembly = false;
          if (!ok)
            {
              result.failure = failure;
              return;
            }
          const double r = residual.l2_norm();
          if (!std::isfinite(r))
            {
              result.failure = "the residual is not finite";
              return;
            }
          // Contact states (after the first correction): a change
          // re-assembles with the new constraints.
          if (solved_since_update && !grid.friction_boundaries.empty() &&
              update_friction_states(du) > 0)
            {
              displacement        = du;
              solved_since_update = false;
              // the same iterate with new constraints: the material cells'
              // contributions are reused (assemble())
              contact_reassembly = true;
              // re-assembly rounds do not count as Newton iterations (at
              // most 2 * maximum Newton iterations of them)
              if (++contact_rounds <= 2 * max_newton_iterations)
                --it;
              continue;
            }
          if (it == 0 && first_solve)
            reference = std::max(r, f_ext_norm);
          const unsigned int changed_branches =
            dealii::Utilities::MPI::sum(branch_changes, grid.mpi_communicator);
          // ... but only while the iteration makes progress: a residual
          // without a new minimum (below 0.9 of the best so far) for 10
          // iterations is a cycle (e.g. alternating between two iterates),
          // which more iterations do not break.
          if (r < 0.9 * best_residual)
            {
              best_residual  = r;
              best_iteration = it;
            }
          if (it > 0 && changed_branches > 0 &&
              it < best_iteration + stall_iterations &&
              max_newton_iterations + state_change_iterations <
                max_state_change_newton_iterations)
            ++state_change_iterations;
          result.residual      = reference > 0. ? r / reference : r;
          const double du_norm = du.l2_norm();
          if (std::getenv("TALUS_DEBUG_NEWTON"))
            {
              std::cerr << "  Newton " << it << ": " << result.residual
                        << " last correction "
                        << last_increment /
                             std::max(du_norm, grid.minimal_cell_diameter)
                        << " contraction "
                        << (residual_at_correction > 0. ?
                              r / residual_at_correction :
                              0.)
                        << " (" << changed_branches
                        << " points changed return branch)";
              // points per branch on this rank: elastic, plane, edge, apex,
              // tension cut-off
              unsigned int n_branch[5] = {0, 0, 0, 0, 0};
              for (const int b : point_branches)
                if (b >= 0 && b < 5)
                  ++n_branch[b];
              std::cerr << " [elastic/plane/edge/apex/cut-off " << n_branch[0]
                        << '/' << n_branch[1] << '/' << n_branch[2] << '/'
                        << n_branch[3] << '/' << n_branch[4] << ']'
                        << std::endl;
            }
          result.iterations      = it;
          const bool residual_ok = r <= residual_tolerance * reference ||
                                   r <= absolute_residual_tolerance;
          // The increment criterion (relative to |du|, or to the cell size
          // for bodies at rest) may be waived when the residual is far
          // below its tolerance (quadratic convergence: the last correction
          // is then still large relative to the current error).
          // 'increment test = estimated error': the next correction
          // predicted from the residual's contraction over the last one.
          const double increment_measure =
            estimated_increment_error && residual_at_correction > 0. ?
              last_increment * std::min(1., r / residual_at_correction) :
              last_increment;
          const bool increment_ok =
            it > 0 && (increment_measure <=
                         increment_tolerance *
                           std::max(du_norm, grid.minimal_cell_diameter) ||
                       r <= 1e-2 * residual_tolerance * reference);
          const bool states_ok =
            boundary_particles == nullptr ||
            dealii::Utilities::MPI::sum(reversed_boundary_points,
                                        grid.mpi_communicator) == 0;
          // Lagrange multipliers: their equations (the gaps) converged too
          bool multipliers_ok = true;
          if (with_lagrange_multipliers)
            {
              result.constraint_gap =
                dealii::Utilities::MPI::max(multiplier_residual,
                                            grid.mpi_communicator);
              multipliers_ok = result.constraint_gap <=
                               boundary_particles->multiplier_tolerance();
              if (std::getenv("TALUS_DEBUG_NEWTON"))
                {
                  unsigned int n_frozen = 0, n_states[3] = {0, 0, 0};
                  for (const auto &bp : boundary_points)
                    if (bp.monolithic)
                      {
                        n_frozen += bp.frozen >= 0 ? 1 : 0;
                        if (bp.last_state >= 0)
                          ++n_states[bp.last_state];
                      }
                  std::cerr << "    multiplier residual "
                            << result.constraint_gap << " m, open/stick/slip "
                            << n_states[0] << '/' << n_states[1] << '/'
                            << n_states[2] << ", held " << n_frozen
                            << ", reversed " << reversed_boundary_points
                            << std::endl;
                }
            }
          if (residual_ok && states_ok && multipliers_ok &&
              (it == 0 ? r <= absolute_residual_tolerance || reference == 0. :
                         increment_ok || no_descent_at_converged_residual))
            {
              // a point held in a state (cycling) must satisfy it at the
              // solution, otherwise the step is not accepted
              if (with_lagrange_multipliers)
                {
                  unsigned int violated = 0, moved = 0;
                  for (const auto &c : boundary_cells)
                    for (unsigned int b = 0; b < c.n_boundary; ++b)
                      {
                        BoundaryPoint &bp =
                          boundary_points[c.first_boundary + b];
                        if (!bp.monolithic || bp.frozen < 0)
                          continue;
                        BoundaryPoint free = bp;
                        free.frozen        = -1;
                        dealii::Tensor<1, dim> du_b;
                        for (unsigned int i = 0; i < grid.fe.dofs_per_cell; ++i)
                          {
                            const auto ci =
                              grid.fe.system_to_component_index(i);
                            du_b[ci.first] +=
                              bp.N[ci.second] * displacement(c.dofs[i]);
                          }
                        // admissible if the free evaluation gives the
                        // state, or (at the kink between the two states)
                        // a force within k times the gap tolerance
                        const BoundaryForce held_force =
                          boundary_force(bp, du_b);
                        const BoundaryForce free_force =
                          boundary_force(free, du_b);
                        const int state = free_force.state;
                        if (state == held_force.state ||
                            (held_force.force - free_force.force).norm() <=
                              bp.beta * bp.weight *
                                boundary_particles->multiplier_tolerance())
                          continue;
                        // held in the wrong state: hold it in the state
                        // the solution asks for and iterate on, at most
                        // three times per point and step (switches counts
                        // the moves from 100 on)
                        if (bp.switches < 102)
                          {
                            bp.frozen   = state == 2 ? 3 : state;
                            bp.switches = std::max(bp.switches + 1, 100u);
                            ++moved;
                          }
                        else
                          ++violated;
                      }
                  violated = dealii::Utilities::MPI::sum(violated,
                                                         grid.mpi_communicator);
                  moved =
                    dealii::Utilities::MPI::sum(moved, grid.mpi_communicator);
                  if (violated == 0 && moved > 0 &&
                      it < max_newton_iterations + granted_iterations)
                    {
                      // at most max_newton_iterations more in all
                      granted_iterations = std::min(granted_iterations + 10,
                                                    max_newton_iterations);
                      if (std::getenv("TALUS_DEBUG_NEWTON"))
                        std::cerr << "    " << moved
                                  << " held multiplier point(s) moved to "
                                     "the state of the solution"
                                  << std::endl;
                      solved_since_update = false;
                      continue;
                    }
                  if (violated > 0 || moved > 0)
                    {
                      result.failure =
                        "Newton converged with " +
                        std::to_string(violated + moved) +
                        " Lagrange multiplier point(s) held in a contact "
                        "state they do not satisfy (they cycled between two "
                        "states)";
                      return;
                    }
                }
              result.converged = true;
              result.accepted_without_descent =
                no_descent_at_converged_residual;
              solved = true;
              return;
            }
          no_descent_at_converged_residual = false;
          if (it == max_newton_iterations + granted_iterations +
                      state_change_iterations)
            break;

          unsigned int n_linear  = 0;
          residual_at_correction = r;
          try
            {
              n_linear = solve_linear(increment);
            }
          catch (const std::exception &e)
            {
              result.failure =
                std::string("the linear solver failed: ") + e.what();
              return;
            }
          result.linear_iterations += n_linear;
          // Debugging aid (doc/performance.md, "The stall just above the
          // tolerance"): at a lingering iteration (the fifth on) near
          // convergence, compare the residual's change along the
          // correction d, (R(u + eps d) - R(u)) / eps, with the tangent's
          // prediction J d (J d = -R here), for eps = 1 ... 1e-6. The
          // residual, the iterate and the recorded branches are restored.
          if (std::getenv("TALUS_DEBUG_FD") && reference > 0. &&
              r < 1e-5 * reference && it >= 5)
            {
              const dealii::TrilinosWrappers::MPI::Vector R0 = residual;
              dealii::TrilinosWrappers::MPI::Vector Jd(R0), dR(R0), diff(R0);
              matrix.vmult(Jd, increment);
              const std::vector<int> branches_saved = point_branches;
              const unsigned int     changes_saved  = branch_changes;
              std::ostringstream     fd_log;
              fd_log << "    FD check |R| " << r / reference << " |Jd| "
                     << Jd.l2_norm() << " |R0| " << R0.l2_norm();
              for (const double eps : {1., 1e-1, 1e-2, 1e-3, 1e-4, 1e-6})
                {
                  // du is owned, displacement ghosted: add on the former
                  dealii::TrilinosWrappers::MPI::Vector u_eps(du);
                  u_eps.add(eps, increment);
                  displacement = u_eps;
                  std::string f;
                  assemble(displacement, false, !quasi_static, f);
                  dR = residual;
                  dR -= R0;
                  dR /= eps;
                  diff = dR;
                  diff -= Jd;
                  const double e_minus = diff.l2_norm();
                  diff                 = dR;
                  diff += Jd;
                  const double e_plus = diff.l2_norm();
                  fd_log << " | eps " << eps << ": |dR-Jd|/|Jd| "
                         << e_minus / Jd.l2_norm() << " |dR+Jd|/|Jd| "
                         << e_plus / Jd.l2_norm() << " |R(u+eps d)| "
                         << residual.l2_norm() / reference;
                }
              if (dealii::Utilities::MPI::this_mpi_process(
                    grid.mpi_communicator) == 0)
                std::cerr << fd_log.str() << std::endl;
              point_branches = branches_saved;
              branch_changes = changes_saved;
              displacement   = du;
              residual       = R0;
            }
          branch_changes = 0;
          du += increment;
          displacement = du;
          for (auto &bp : boundary_points)
            if (bp.monolithic)
              bp.lambda += bp.dlambda;
          // The contact dofs' targets are reached by the full correction:
          // the constraints are homogeneous again from here on (a residual
          // assembly ignores inhomogeneities anyway).
          const bool contact_jump_was_active = contact_jump_active;
          if (contact_jump_active)
            {
              contact_jump_active = false;
              make_constraints();
            }
          double step_length = 1.;
          if (line_search)
            {
              // Backtracking on the residual norm: halve the correction
              // while the residual grows (at most max_line_search times).
              dealii::TimerOutput::Scope s(timer, "line search");
              bool                       any_accepted = false;
              for (unsigned int k = 0; k < max_line_search; ++k)
                {
                  const bool with_matrix = k == 0 && full_step_accepted &&
                                           boundary_particles == nullptr;
                  // a rejected trial must not count its return branches
                  const std::vector<int> branches_before =
                    with_matrix ? point_branches : std::vector<int>();
                  const unsigned int changes_before = branch_changes;
                  std::string        trial_failure;
                  const bool         trial_ok = assemble(displacement,
                                                 with_matrix,
                                                 !quasi_static,
                                                 trial_failure);
                  const double       r_trial  = residual.l2_norm();
                  const bool         accepted =
                    trial_ok && std::isfinite(r_trial) && r_trial < r;
                  if (k == 0)
                    full_step_accepted = accepted;
                  if (accepted)
                    {
                      assembled_at_iterate = with_matrix;
                      any_accepted         = true;
                      break;
                    }
                  if (with_matrix)
                    {
                      point_branches = branches_before;
                      branch_changes = changes_before;
                    }
                  step_length *= 0.5;
                  du.add(-step_length, increment);
                  displacement = du;
                  for (auto &bp : boundary_points)
                    if (bp.monolithic)
                      bp.lambda -= step_length * bp.dlambda;
                }
              // Every trial raised the residual of an iterate that already
              // meets the residual tolerance (semi-smooth Newton at a kink
              // of the return map: a point toggling between two return
              // branches, whose tangents send the correction the wrong way,
              // so that the iteration cycles between that iterate and a
              // worse one). Go back to the iterate and accept it: no step
              // along the correction improves it, and the increment test
              // cannot be met by steps the residual rejects.
              if (!any_accepted && !contact_jump_was_active &&
                  !with_lagrange_multipliers && residual_ok)
                {
                  du.add(-step_length, increment);
                  displacement = du;
                  for (auto &bp : boundary_points)
                    if (bp.monolithic)
                      bp.lambda -= step_length * bp.dlambda;
                  no_descent_at_converged_residual = true;
                  solved_since_update              = false;
                  continue;
                }
            }
          if (contact_jump_was_active)
            {
              // after a shortened correction the constrained dofs are set
              // to their targets
              if (step_length < 1.)
                {
                  Epetra_FEVector &e = du.trilinos_vector();
                  for (const auto &[i, value] : contact_targets)
                    e[0][e.Map().LID(static_cast<int>(i))] = value;
                  displacement = du;
                }
              contact_targets.clear();
            }
          last_increment      = step_length * increment.l2_norm();
          solved_since_update = true;
        }
      std::ostringstream msg;
      msg << "no convergence in "
          << max_newton_iterations + granted_iterations +
               state_change_iterations
          << " Newton iterations";
      if (state_change_iterations > 0)
        msg << " (" << state_change_iterations
            << " of them changed the return branch of material points)";
      if (granted_iterations > 0)
        msg << " (" << granted_iterations
            << " of them granted after corrections of held Lagrange "
               "multiplier states)";
      msg << " (relative residual " << result.residual << ")";
      if (!grid.friction_boundaries.empty())
        msg << "; contact states on friction boundaries may still be "
               "changing";
      result.failure = msg.str();
      return;
    }


    template <int dim>
    void
    MPMSolver<dim>::initialize_acceleration(const double t)
    {
      if (quasi_static)
        return;
      // Project with a zero step: only mass and forces are used.
      initializing = true;
      prepare_step(t, 1.);
      initializing = false;
      std::string failure;
      displacement = 0.;
      if (!assemble(displacement, false, false, failure))
        throw std::runtime_error("initial state: " + failure);
      // a_I = r_I / m_I with the lumped mass (r = f_ext - f_int).
      dealii::TrilinosWrappers::MPI::Vector a(grid.locally_owned_dofs,
                                              grid.mpi_communicator);
      for (const auto i : grid.locally_owned_dofs)
        if (!constraints.is_constrained(i) && nodal_mass(i) > 0.)
          a(i) = residual(i) / nodal_mass(i);
      // Friction nodes (lumped mass: node by node): held normally while
      // pressed, tangentially while the needed force is within mu p,
      // otherwise accelerated by the net force minus the Coulomb force.
      for (const auto &fn : friction_nodes)
        if (fn.owned && nodal_mass(fn.normal_dof) > 0.)
          {
            const double           m = nodal_mass(fn.normal_dof);
            const double           p = -fn.inward * raw_residual(fn.normal_dof);
            dealii::Tensor<1, dim> r_t;
            for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
              r_t[fn.tangential_components[k]] =
                raw_residual(fn.tangential_dofs[k]);
            if (p < 0.)
              {
                a(fn.normal_dof) = raw_residual(fn.normal_dof) / m;
                for (const auto t : fn.tangential_dofs)
                  a(t) = raw_residual(t) / m;
                continue;
              }
            a(fn.normal_dof)    = 0.;
            const double excess = r_t.norm() - fn.mu * p;
            for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
              a(fn.tangential_dofs[k]) =
                excess > 0. ?
                  excess / r_t.norm() * r_t[fn.tangential_components[k]] / m :
                  0.;
          }
      a.compress(dealii::VectorOperation::insert);
      if (boundary_particles != nullptr)
        initial_acceleration_with_boundaries(a);
      acceleration_new = a;

      using Properties           = MaterialPointProperties<dim>;
      const auto        &fe      = grid.fe;
      const unsigned int n_nodes = fe.base_element(0).dofs_per_cell;
      for (const auto &c : cells)
        for (unsigned int q = 0; q < c.n; ++q)
          {
            const unsigned int     k = c.first + q;
            dealii::Tensor<1, dim> a_p;
            for (unsigned int i = 0; i < fe.dofs_per_cell; ++i)
              {
                const auto ci = fe.system_to_component_index(i);
                a_p[ci.first] += shape_values[k * n_nodes + ci.second] *
                                 acceleration_new(c.dofs[i]);
              }
            auto props = particles[k]->get_properties();
            for (unsigned int d = 0; d < dim; ++d)
              props[Properties::acceleration + d] = a_p[d];
          }
      prepared = false;
    }


    template <int dim>
    void
    MPMSolver<dim>::commit_step()
    {
      dealii::TimerOutput::Scope scope(timer, "commit (G2P, move, sort)");
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      friction_dissipation += step_impact_dissipation;
      reset_dissipation += step_reset_dissipation;
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const unsigned int n_history     = points.n_history();

      // Nodal accelerations and velocity increments at t_{n+1}.
      dealii::TrilinosWrappers::MPI::Vector a_new(grid.locally_owned_dofs,
                                                  grid.mpi_communicator);
      dealii::TrilinosWrappers::MPI::Vector dv(a_new);
      if (!quasi_static)
        {
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              {
                const double du = displacement(i);
                const double an = acceleration_n(i);
                const double a =
                  newmark.acceleration(du, velocity_n(i), an, dt);
                a_new(i) = a;
                dv(i)    = newmark.velocity(0., an, a, dt);
              }
          a_new.compress(dealii::VectorOperation::insert);
          dv.compress(dealii::VectorOperation::insert);
        }
      acceleration_new = a_new;
      dealii::TrilinosWrappers::MPI::Vector dv_ghosted(
        grid.locally_owned_dofs,
        grid.locally_relevant_dofs,
        grid.mpi_communicator);
      dv_ghosted = dv;
      // FLIP increment v_I^{n+1} - v_I^{P2G}: where the constraints set the
      // start velocity of a node with mass to zero (fixed, slip, stick),
      // the increment includes that change, so that the points lose the
      // velocity the boundary removes (with dv alone they kept it and
      // handed it back to the free nodes of their cell at every P2G).
      // Elsewhere v_P2G = v_n exactly and the increment is dv.
      {
        // end-of-step grid velocity v_n + dv (zero without mass)
        dealii::TrilinosWrappers::MPI::Vector v(grid.locally_owned_dofs,
                                                grid.mpi_communicator);
        if (!quasi_static)
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              v(i) = velocity_n(i) + dv(i);
        v.compress(dealii::VectorOperation::insert);
        committed_grid_velocity.reinit(grid.locally_owned_dofs,
                                       grid.locally_relevant_dofs,
                                       grid.mpi_communicator);
        committed_grid_velocity = v;
      }
      dealii::TrilinosWrappers::MPI::Vector dv_flip(dv_ghosted);
      if (!quasi_static)
        {
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              dv(i) -= velocity_p2g(i) - velocity_n(i);
          dv.compress(dealii::VectorOperation::insert);
          dv_flip = dv;
        }

      // Contact forces and friction work of the friction boundaries (from
      // the unconstrained residual of the converged iterate).
      {
        dealii::Tensor<1, dim> force;
        double                 work = 0.;
        for (const auto &fn : friction_nodes)
          if (fn.owned && fn.state != ContactState::free &&
              nodal_mass(fn.normal_dof) > 0.)
            {
              force[fn.normal_component] -= raw_residual(fn.normal_dof);
              for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
                {
                  const auto   t = fn.tangential_dofs[k];
                  const double R = -raw_residual(t);
                  force[fn.tangential_components[k]] += R;
                  work += R * displacement(t);
                }
            }
        contact_force =
          dealii::Utilities::MPI::sum(force, grid.mpi_communicator);
        friction_dissipation -=
          dealii::Utilities::MPI::sum(work, grid.mpi_communicator);
        // How far the nodes held in a state (cycling) violate Coulomb's
        // law at the converged iterate: a stuck node by its tangential
        // reaction beyond mu p, a slipping node by the speed against its
        // slip direction, a contact node by a pull (p < 0).
        double excess_force = 0., reversed_speed = 0., pull = 0.;
        for (const auto &fn : friction_nodes)
          if (fn.owned && fn.held && nodal_mass(fn.normal_dof) > 0.)
            {
              const double p = -fn.inward * raw_residual(fn.normal_dof);
              if (fn.state != ContactState::free)
                pull = std::max(pull, -p);
              dealii::Tensor<1, dim> R_t, v_t;
              for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
                {
                  const auto t                     = fn.tangential_dofs[k];
                  R_t[fn.tangential_components[k]] = -raw_residual(t);
                  v_t[fn.tangential_components[k]] =
                    new_velocity(t, displacement(t));
                }
              if (fn.state == ContactState::stick)
                excess_force =
                  std::max(excess_force, R_t.norm() - fn.mu * std::max(p, 0.));
              else if (fn.state == ContactState::slip)
                reversed_speed =
                  std::max(reversed_speed, -(v_t * fn.slip_direction));
            }
        const MPI_Comm     comm = grid.mpi_communicator;
        const unsigned int frozen =
          dealii::Utilities::MPI::sum(frozen_nodes, comm);
        excess_force   = dealii::Utilities::MPI::max(excess_force, comm);
        reversed_speed = dealii::Utilities::MPI::max(reversed_speed, comm);
        pull           = dealii::Utilities::MPI::max(pull, comm);
        if (frozen > 0 && dealii::Utilities::MPI::this_mpi_process(comm) == 0)
          std::cerr << "Warning: " << frozen
                    << " grid node(s) on friction boundaries kept their "
                       "contact state after 4 changes in one step; Coulomb's "
                       "law is violated there by at most "
                    << std::max(excess_force, 0.)
                    << " N of tangential force beyond mu p (stuck nodes), "
                    << std::max(reversed_speed, 0.)
                    << " m/s against the slip direction (slipping nodes) and "
                    << pull << " N of pull (nodes in contact)." << std::endl;
      }

      // XPIC(m): the part (I - P)^m v^n of the points' old velocities that
      // the FLIP update keeps and PIC would remove, with P the projection
      // to the grid and back (mass-weighted, at the old positions); m
      // applications of P.
      std::vector<dealii::Tensor<1, dim>> xpic_correction;
      if (xpic_order > 0 && !quasi_static)
        compute_xpic_correction(xpic_correction);

      std::vector<double> history_new(n_history);
      std::vector<double> du_local(dofs_per_cell), a_local(dofs_per_cell),
        dv_local(dofs_per_cell), v_local(dofs_per_cell);
      double grid_energy = 0., grid_speed = 0., transfer_energy = 0.;
      std::vector<dealii::Tensor<2, dim>> F_cell;
      dealii::Tensor<2, 3>                P;
      for (const auto &c : cells)
        {
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              du_local[i] = displacement(c.dofs[i]);
              a_local[i]  = acceleration_new(c.dofs[i]);
              dv_local[i] = dv_flip(c.dofs[i]);
              v_local[i]  = velocity_n(c.dofs[i]) + dv_ghosted(c.dofs[i]);
            }
          cell_deformation_gradients(c, du_local, F_cell);
          for (unsigned int q = 0; q < c.n; ++q)
            {
              const unsigned int k     = c.first + q;
              auto               props = particles[k]->get_properties();
              const double      *N     = &shape_values[k * n_nodes];
              const auto        *dN    = &shape_gradients[k * n_nodes];

              dealii::Tensor<1, dim> du_p, a_p, dv_p, v_pic;
              dealii::Tensor<2, dim> H, grad_v;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  v_pic[ci.first] += N[ci.second] * v_local[i];
                  grad_v[ci.first] += v_local[i] * dN[ci.second];
                  du_p[ci.first] += N[ci.second] * du_local[i];
                  a_p[ci.first] += N[ci.second] * a_local[i];
                  dv_p[ci.first] += N[ci.second] * dv_local[i];
                  H[ci.first] += du_local[i] * dN[ci.second];
                }
              const dealii::Tensor<2, dim> F_n =
                read_tensor<dim>(props, Properties::deformation);
              const dealii::Tensor<2, dim> &F_new = F_cell[q];
              const dealii::Tensor<2, 3>    F3    = embed<dim>(F_new);
              model.compute_stress(
                embed<dim>(F_n),
                F3,
                dealii::ArrayView<const double>(props.data() +
                                                  Properties::history,
                                                n_history),
                dealii::ArrayView<double>(history_new.data(), n_history),
                dt,
                P,
                nullptr);
              // Cauchy stress sigma = P F^T / J.
              const dealii::Tensor<2, 3> sigma =
                P * dealii::transpose(F3) / dealii::determinant(F3);
              Properties::store_stress(props, sigma);
              for (unsigned int h = 0; h < n_history; ++h)
                props[Properties::history + h] = history_new[h];
              for (unsigned int i = 0; i < dim; ++i)
                {
                  for (unsigned int j = 0; j < dim; ++j)
                    props[Properties::deformation + i * dim + j] = F_new[i][j];
                  // FLIP (increment) blended with PIC (grid velocity), or
                  // APIC (grid velocity and its gradient)
                  // or XPIC (FLIP minus (I - P)^m v^n)
                  const double v_flip =
                    props[Properties::velocity + i] + dv_p[i];
                  props[Properties::velocity + i] =
                    quasi_static   ? 0. :
                    apic           ? v_pic[i] :
                    xpic_order > 0 ? v_flip - xpic_correction[k][i] :
                                     flip_fraction * v_flip +
                                       (1. - flip_fraction) * v_pic[i];
                  for (unsigned int j = 0; j < dim; ++j)
                    props[Properties::affine_velocity + i * dim + j] =
                      (apic && !quasi_static) ? grad_v[i][j] : 0.;
                  props[Properties::acceleration + i] =
                    quasi_static ? 0. : a_p[i];
                  if (!quasi_static)
                    transfer_energy +=
                      0.5 * props[Properties::mass] *
                      (v_flip * v_flip - props[Properties::velocity + i] *
                                           props[Properties::velocity + i]);
                }
              particles[k]->set_location(particles[k]->get_location() + du_p);
              if (!quasi_static)
                {
                  grid_energy +=
                    0.5 * props[Properties::mass] * v_pic.norm_square();
                  grid_speed = std::max(grid_speed, v_pic.norm());
                }
            }
        }
      grid_kinetic_energy =
        dealii::Utilities::MPI::sum(grid_energy, grid.mpi_communicator);
      transfer_dissipation +=
        dealii::Utilities::MPI::sum(transfer_energy, grid.mpi_communicator);
      max_grid_speed =
        dealii::Utilities::MPI::max(grid_speed, grid.mpi_communicator);
      // Boundary particles: new gaps, reactions and states; friction work.
      if (boundary_particles != nullptr)
        {
          using BP = Boundaries::BoundaryParticleProperties<dim>;
          for (auto &p : boundary_particles->particle_handler())
            {
              auto props = p.get_properties();
              for (unsigned int d = 0; d < dim; ++d)
                {
                  props[BP::gap + d]        = 0.;
                  props[BP::reaction + d]   = 0.;
                  props[BP::multiplier + d] = 0.;
                }
              props[BP::state] = 0.;
            }
          double work = 0.;
          // per-particle traction, force and gap at commit (debugging)
          const bool debug_boundary = std::getenv("TALUS_DEBUG_NITSCHE");
          const bool debug_point_contact =
            std::getenv("TALUS_DEBUG_POINT_CONTACT");
          std::vector<dealii::Tensor<1, dim>> dT(dofs_per_cell);
          std::vector<double>                 du_local(dofs_per_cell);
          for (const auto &c : boundary_cells)
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                du_local[i] = displacement(c.dofs[i]);
              for (unsigned int b = 0; b < c.n_boundary; ++b)
                {
                  BoundaryPoint &bp = boundary_points[c.first_boundary + b];
                  dealii::Tensor<1, dim> du_b;
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const auto ci = fe.system_to_component_index(i);
                      du_b[ci.first] += bp.N[ci.second] * du_local[i];
                    }
                  if (bp.nitsche && bp.with_stress)
                    {
                      dealii::Tensor<1, dim> T;
                      boundary_traction(bp, du_local, T, dT);
                      bp.lambda = bp.weight * T;
                    }
                  const BoundaryForce bf = boundary_force(bp, du_b);
                  if (debug_boundary && bf.state != 0)
                    std::cerr << "  bp " << bp.particle->get_location()
                              << " lambda.n " << bp.lambda * bp.normal
                              << " f.n " << bf.force * bp.normal << " g.n "
                              << bf.gap * bp.normal << std::endl;
                  // The part of the force on nodes without mass (constrained)
                  // does not act on the material: report the rest.
                  double active_share = 0.;
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    if (nodal_mass(c.dofs[fe.component_to_system_index(0, k)]) >
                        0.)
                      active_share += bp.N[k];
                  // dissipated: -f . (relative increment - elastic gap change)
                  work -=
                    bf.force * ((du_b - bp.du_bar) - (bf.gap - bp.gap_old));
                  // a merged (cell-wise) point shares its gap, state and,
                  // by weight, its reaction among its particles
                  // the multiplier the next step starts from reproduces this
                  // force at zero increment: lambda - k g = f
                  const dealii::Tensor<1, dim> lambda =
                    bp.augmented ? bf.force + bp.beta * bp.weight * bf.gap :
                                   dealii::Tensor<1, dim>();
                  const auto write = [&](auto particle, const double share) {
                    auto props = particle->get_properties();
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        props[BP::gap + d]        = bf.gap[d];
                        props[BP::multiplier + d] = share * lambda[d];
                        props[BP::reaction + d] =
                          -share * active_share * bf.force[d];
                      }
                    props[BP::state] = bf.state;
                  };
                  if (bp.on_material_point)
                    {
                      if (debug_point_contact && bf.state != 0)
                        {
                          std::cerr << "  t " << time << " mp "
                                    << bp.particle->get_location() << " g0 "
                                    << bp.gap_old * bp.normal << " du.n "
                                    << (du_b - bp.du_bar) * bp.normal << " g.n "
                                    << bf.gap * bp.normal << " f " << bf.force
                                    << " state " << bf.state << " N";
                          for (const double v : bp.N)
                            std::cerr << ' ' << v;
                          std::cerr << std::endl;
                        }
                      // the stick spring stays on the material point; the
                      // reaction goes to the boundary's resultant
                      auto props = bp.particle->get_properties();
                      const dealii::Tensor<1, dim> g_t =
                        bf.state == 0 ?
                          dealii::Tensor<1, dim>() :
                          bf.gap - (bf.gap * bp.normal) * bp.normal;
                      for (unsigned int d = 0; d < dim; ++d)
                        props[Properties::contact_gap + dim * bp.boundary + d] =
                          g_t[d];
                      if (bf.state != 0)
                        {
                          // the dashpot's work on the normal increment
                          const double dgn = (du_b - bp.du_bar) * bp.normal;
                          work += bp.damping * bp.beta * bp.weight * dgn * dgn;
                          boundary_particles->record_point_contact(
                            bp.boundary,
                            -bf.force,
                            bp.normal,
                            std::max(0., -(bf.gap * bp.normal)));
                        }
                    }
                  else if (bp.members.empty())
                    write(bp.particle, 1.);
                  else
                    for (unsigned int m = 0; m < bp.members.size(); ++m)
                      write(bp.members[m], bp.member_weights[m] / bp.weight);
                }
            }
          friction_dissipation +=
            dealii::Utilities::MPI::sum(work, grid.mpi_communicator);
          boundary_points.clear();
        }

      cells.clear();
      particles.clear();
      {
        dealii::TimerOutput::Scope s(timer, "sort particles");
        points.particle_handler().sort_particles_into_subdomains_and_cells();
        if (boundary_particles != nullptr)
          boundary_particles->move_to(time);
      }
      prepared = false;
      solved   = false;
    }


    template <int dim>
    void
    MPMSolver<dim>::initial_acceleration_with_boundaries(
      dealii::TrilinosWrappers::MPI::Vector &a)
    {
      // The boundary conditions act on the accelerations as on the
      // displacements: solve M a = r0 + N^T f_b(tau^2 N a) with the lumped
      // mass M, r0 = f_ext - f_int at the initial state and the penalty
      // forces of the boundary particles for the "displacement" tau^2 a
      // relative to the boundary's tau^2 a_bar (no gap). tau^2 makes the
      // penalty 1e4 times stiffer than the heaviest node, so that the
      // constraints hold to about 1e-4 (bonded, slip, contact, Coulomb friction
      // on the acceleration). Newton on this piecewise linear system. The
      // boundaries with an exact method add Uzawa multiplier updates (below)
      // until the constraints hold to 1e-10 of the loads.
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      double             max_mass = 0., min_stiffness = 1e300;
      for (const auto i : grid.locally_owned_dofs)
        max_mass = std::max(max_mass, static_cast<double>(nodal_mass(i)));
      for (const auto &b : boundary_points)
        min_stiffness = std::min(min_stiffness, b.beta * b.weight);
      max_mass = dealii::Utilities::MPI::max(max_mass, grid.mpi_communicator);
      min_stiffness =
        dealii::Utilities::MPI::min(min_stiffness, grid.mpi_communicator);
      if (!(min_stiffness < 1e300) || !(max_mass > 0.))
        return; // no boundary particle touches the material
      const double tau2 = 1e4 * max_mass / min_stiffness;

      const dealii::TrilinosWrappers::MPI::Vector r0 = residual;
      const double r0_norm   = std::max(r0.l2_norm(), 1e-300);
      double       reference = r0_norm;
      dealii::TrilinosWrappers::MPI::Vector a_ghosted(
        grid.locally_owned_dofs,
        grid.locally_relevant_dofs,
        grid.mpi_communicator);
      dealii::FullMatrix<double> k_local(dofs_per_cell, dofs_per_cell);
      dealii::Vector<double>     r_local(dofs_per_cell);
      // states per point: a point that changes state 3 times keeps it
      std::vector<int>          last(boundary_points.size(), -1);
      std::vector<int>          frozen(boundary_points.size(), -1);
      std::vector<unsigned int> switches(boundary_points.size(), 0);
      bool                      converged = false;
      // Boundaries with an exact method (Lagrange multipliers, augmented
      // Lagrangian, Nitsche) get exact constraints: Uzawa updates of a
      // multiplier lambda_a (a force) on top of the stiff penalty, each of
      // which reduces the violation by about the factor 1e-4 of tau^2; at
      // most 6, until lambda_a changes by less than 1e-10 of the loads.
      // Penalty boundaries keep the penalty (lambda_a = 0).
      std::vector<dealii::Tensor<1, dim>> lambda_a(boundary_points.size());
      bool                                exact = false;
      for (const auto &b : boundary_points)
        exact = exact || b.monolithic || b.augmented || b.nitsche;
      exact = dealii::Utilities::MPI::logical_or(exact, grid.mpi_communicator);
      // the force of boundary particle idx of cell c for the acceleration
      // a_ghosted, as a penalty on tau^2 (a - a_bar) plus lambda_a
      const auto force_at = [&](const CellCache &c, const unsigned int idx) {
        BoundaryPoint bp = boundary_points[idx];
        bp.du_bar        = tau2 * bp.a_bar;
        bp.gap_old       = 0.;
        bp.frozen        = frozen[idx];
        bp.lambda        = lambda_a[idx];
        dealii::Tensor<1, dim> a_b;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            const auto ci = fe.system_to_component_index(i);
            a_b[ci.first] += bp.N[ci.second] * a_ghosted(c.dofs[i]);
          }
        return boundary_force(bp, tau2 * a_b);
      };
      const unsigned int max_updates       = exact ? 6 : 0;
      double             multiplier_change = 0.;
      for (unsigned int update = 0; update <= max_updates; ++update)
        {
          if (update > 0)
            {
              // Uzawa: lambda_a <- the force of the converged iterate; the
              // change is measured as nodal forces on the dofs with mass
              // (a particle whose nodes are all held changes nothing)
              a_ghosted = a;
              increment = 0.;
              for (const auto &c : boundary_cells)
                for (unsigned int b = 0; b < c.n_boundary; ++b)
                  {
                    const unsigned int   idx = c.first_boundary + b;
                    const BoundaryPoint &bp  = boundary_points[idx];
                    if (!(bp.monolithic || bp.augmented || bp.nitsche))
                      continue;
                    const BoundaryForce bf = force_at(c, idx);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      {
                        const auto ci = fe.system_to_component_index(i);
                        r_local[i]    = bp.N[ci.second] *
                                     (bf.force - lambda_a[idx])[ci.first];
                      }
                    constraints.distribute_local_to_global(r_local,
                                                           c.dofs,
                                                           increment);
                    lambda_a[idx] = bf.force;
                  }
              increment.compress(dealii::VectorOperation::add);
              multiplier_change = increment.l2_norm();
              if (std::getenv("TALUS_DEBUG_NEWTON") &&
                  dealii::Utilities::MPI::this_mpi_process(
                    grid.mpi_communicator) == 0)
                std::cerr << "  initial acceleration: multiplier update "
                          << update << ", change of the nodal forces "
                          << multiplier_change / r0_norm << " of the loads"
                          << std::endl;
              if (multiplier_change <= 1e-10 * r0_norm)
                break;
              converged = false;
            }
          for (unsigned int it = 0; it < 30; ++it)
            {
              a_ghosted = a;
              matrix    = 0.;
              residual  = 0.;
              for (const auto &c : boundary_cells)
                {
                  k_local = 0.;
                  r_local = 0.;
                  for (unsigned int b = 0; b < c.n_boundary; ++b)
                    {
                      const unsigned int   idx = c.first_boundary + b;
                      const BoundaryPoint &bp  = boundary_points[idx];
                      const BoundaryForce  bf  = force_at(c, idx);
                      if (frozen[idx] < 0)
                        {
                          if (last[idx] >= 0 && bf.state != last[idx])
                            ++switches[idx];
                          last[idx] = bf.state;
                          if (switches[idx] >= 3)
                            frozen[idx] = bf.state;
                        }
                      for (unsigned int i = 0; i < dofs_per_cell; ++i)
                        {
                          const auto   ci = fe.system_to_component_index(i);
                          const double Ni = bp.N[ci.second];
                          r_local[i] += Ni * bf.force[ci.first];
                          for (unsigned int j = 0; j < dofs_per_cell; ++j)
                            {
                              const auto cj = fe.system_to_component_index(j);
                              k_local(i, j) -= tau2 * Ni * bp.N[cj.second] *
                                               bf.dforce_du[ci.first][cj.first];
                            }
                        }
                    }
                  constraints.distribute_local_to_global(
                    k_local, r_local, c.dofs, matrix, residual);
                }
              residual.compress(dealii::VectorOperation::add);
              matrix.compress(dealii::VectorOperation::add);
              {
                // owned entries, written directly (no compress per entry)
                Epetra_FEVector          &r   = residual.trilinos_vector();
                const Epetra_MultiVector &r0v = r0.trilinos_vector();
                const Epetra_MultiVector &av  = a.trilinos_vector();
                for (const auto i : grid.locally_owned_dofs)
                  {
                    const int l = r.Map().LID(static_cast<int>(i));
                    if (constraints.is_constrained(i) || !(nodal_mass(i) > 0.))
                      {
                        r[0][l] = 0.;
                        matrix.add(i, i, max_mass);
                        continue;
                      }
                    r[0][l] += r0v[0][l] - nodal_mass(i) * av[0][l];
                    matrix.add(i, i, static_cast<double>(nodal_mass(i)));
                  }
              }
              matrix.compress(dealii::VectorOperation::add);
              const double r = residual.l2_norm();
              // relative to the loads, or to the first residual when there
              // are none (a moving boundary accelerating a body at rest)
              if (it == 0)
                reference = std::max(r0_norm, r);
              if (std::getenv("TALUS_DEBUG_NEWTON"))
                std::cerr << "  initial acceleration " << it << ": "
                          << r / reference << std::endl;
              if (r <= 1e-10 * reference)
                {
                  converged = true;
                  break;
                }
              dealii::SolverControl                  control(1, 0.);
              dealii::TrilinosWrappers::SolverDirect solver(control);
              increment = 0.;
              solver.solve(matrix, increment, residual);
              a += increment;
            }
          if (!converged)
            break;
        }
      if (converged && max_updates > 0 && multiplier_change > 1e-10 * r0_norm &&
          dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) == 0)
        std::cerr << "Warning: the initial accelerations meet the exact "
                     "boundary conditions (Lagrange multipliers, augmented "
                     "Lagrangian, Nitsche) only to "
                  << multiplier_change / r0_norm << " of the loads after "
                  << max_updates << " multiplier updates." << std::endl;
      if (!converged &&
          dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) == 0)
        std::cerr << "Warning: the initial accelerations with the boundary "
                     "particles did not converge in 30 iterations (contact "
                     "states keep changing); the first steps start from "
                     "the last iterate."
                  << std::endl;
      (void)n_nodes;
    }


    template <int dim>
    void
    MPMSolver<dim>::attach_boundary_particles(
      Boundaries::BoundaryParticles<dim> &boundaries)
    {
      boundary_particles = boundaries.empty() ? nullptr : &boundaries;
      // The symmetric Nitsche form is coercive only above a stabilisation
      // that grows without bound as a cut shrinks (doc/verification.md).
      if (ghost_penalty_factor == 0. &&
          dealii::Utilities::MPI::this_mpi_process(grid.mpi_communicator) == 0)
        for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
          if (boundaries.boundary(b).nitsche &&
              boundaries.boundary(b).nitsche_theta > 0.)
            std::cerr << "Warning: boundary " << boundaries.name(b)
                      << " uses Nitsche's method with 'Nitsche symmetry' > 0 "
                         "without the ghost penalty (subsection Solver, "
                         "'ghost penalty factor' = 0): the form is then "
                         "stable only for a stabilisation above a threshold "
                         "that grows as the cut cells shrink, and Newton may "
                         "fail; set the ghost penalty factor (e.g. 1) or "
                         "'Nitsche symmetry' = -1."
                      << std::endl;
    }


    template <int dim>
    void
    MPMSolver<dim>::cache_boundary_particles()
    {
      boundary_points.clear();
      with_lagrange_multipliers = false;
      if (boundary_particles == nullptr)
        return;
      using BP                   = Boundaries::BoundaryParticleProperties<dim>;
      auto              &handler = boundary_particles->particle_handler();
      const auto        &base    = grid.fe.base_element(0);
      const unsigned int n_nodes = base.dofs_per_cell;
      boundary_cells.clear();
      with_nitsche = false;
      for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
        with_nitsche = with_nitsche || boundary_particles->boundary(b).nitsche;
      if (with_nitsche)
        project_stress_to_grid();
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          const typename dealii::Triangulation<dim>::active_cell_iterator
                             tria_cell(cell);
          const unsigned int n = handler.n_particles_in_cell(tria_cell);
          if (n == 0)
            continue;
          CellCache c;
          c.cell  = cell;
          c.first = 0;
          c.n     = 0;
          c.dofs.resize(grid.fe.dofs_per_cell);
          cell->get_dof_indices(c.dofs);
          bool has_mass = false;
          for (const auto i : c.dofs)
            has_mass = has_mass || nodal_mass(i) > 0.;
          if (!has_mass)
            continue;
          c.first_boundary = boundary_points.size();
          std::vector<dealii::Point<dim>> reference_points;
          for (auto p = handler.particles_in_cell(tria_cell).begin();
               p != handler.particles_in_cell(tria_cell).end();
               ++p)
            {
              BoundaryPoint bp;
              bp.particle      = p;
              const auto props = p->get_properties();
              bp.boundary      = static_cast<unsigned int>(props[BP::boundary]);
              const auto &desc = boundary_particles->boundary(bp.boundary);
              // material-point contact: the particles only give the surface
              if (desc.material_point_contact)
                continue;
              bp.weight     = props[BP::weight];
              bp.beta       = desc.beta;
              bp.mu         = desc.friction_coefficient;
              bp.condition  = desc.condition;
              bp.augmented  = desc.augmented || desc.lagrange_multiplier;
              bp.monolithic = desc.lagrange_multiplier;
              bp.nitsche    = desc.nitsche;
              bp.theta      = desc.nitsche_theta;
              c.nitsche     = c.nitsche || desc.nitsche;
              dealii::Point<dim> X;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  bp.normal[d]  = props[BP::normal + d];
                  bp.gap_old[d] = props[BP::gap + d];
                  bp.lambda[d]  = props[BP::multiplier + d];
                  X[d]          = props[BP::reference_position + d];
                }
              // no increment at the initial state (the residual of
              // initialize_acceleration() is taken at rest)
              bp.du_bar = 0.;
              if (!initializing && desc.moving)
                bp.du_bar =
                  boundary_particles->prescribed_displacement(bp.boundary,
                                                              X,
                                                              time) -
                  boundary_particles->prescribed_displacement(bp.boundary,
                                                              X,
                                                              time - dt);
              bp.a_bar = 0.;
              if (initializing && desc.moving)
                {
                  // one-sided second difference at the initial time (a
                  // coupling need not define u before it)
                  const double eps = 1e-4; // [s]
                  bp.a_bar = (boundary_particles->prescribed_displacement(
                                bp.boundary, X, time) -
                              2. * boundary_particles->prescribed_displacement(
                                     bp.boundary, X, time + eps) +
                              boundary_particles->prescribed_displacement(
                                bp.boundary, X, time + 2. * eps)) /
                             (eps * eps);
                }
              reference_points.push_back(p->get_reference_location());
              boundary_points.push_back(std::move(bp));
            }
          const unsigned int n_kept = reference_points.size();
          if (n_kept == 0)
            continue;
          c.n_boundary = n_kept;
          if (grid.is_cartesian)
            for (unsigned int q = 0; q < n_kept; ++q)
              {
                auto &bp = boundary_points[c.first_boundary + q];
                bp.N.resize(n_nodes);
                for (unsigned int k = 0; k < n_nodes; ++k)
                  bp.N[k] = base.shape_value(k, reference_points[q]);
                if (bp.nitsche)
                  {
                    bp.dN.resize(n_nodes);
                    for (unsigned int k = 0; k < n_nodes; ++k)
                      {
                        bp.dN[k] = base.shape_grad(k, reference_points[q]);
                        for (unsigned int d = 0; d < dim; ++d)
                          bp.dN[k][d] /= grid.cell_extent[d];
                      }
                  }
              }
          else
            {
              const dealii::Quadrature<dim> quadrature(reference_points);
              dealii::FEValues<dim>         fe_values(grid.mapping,
                                              base,
                                              quadrature,
                                              dealii::update_values |
                                                dealii::update_gradients);
              fe_values.reinit(tria_cell);
              for (unsigned int q = 0; q < n_kept; ++q)
                {
                  auto &bp = boundary_points[c.first_boundary + q];
                  bp.N.resize(n_nodes);
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    bp.N[k] = fe_values.shape_value(k, q);
                  if (bp.nitsche)
                    {
                      bp.dN.resize(n_nodes);
                      for (unsigned int k = 0; k < n_nodes; ++k)
                        bp.dN[k] = fe_values.shape_grad(k, q);
                    }
                }
            }
          // Nodes without mass are constrained to zero increments: in the
          // gap they stand for the boundary itself, so a point's prescribed
          // increment enters only with the share S of the nodes with mass,
          // g = g_old + sum_k N_k du_k - S du_bar. A rigid motion of the
          // massive nodes with the boundary then leaves the gap unchanged;
          // for a boundary at rest nothing changes.
          {
            std::vector<bool> massive(n_nodes);
            for (unsigned int k = 0; k < n_nodes; ++k)
              massive[k] =
                nodal_mass(c.dofs[grid.fe.component_to_system_index(0, k)]) >
                0.;
            for (unsigned int q = 0; q < n_kept; ++q)
              {
                auto  &bp = boundary_points[c.first_boundary + q];
                double S  = 0.;
                for (unsigned int k = 0; k < n_nodes; ++k)
                  if (massive[k])
                    S += bp.N[k];
                bp.du_bar *= S;
                bp.a_bar *= S;
                // Nitsche: the stress at the start of the step, interpolated
                // from the nodes with mass
                if (bp.nitsche && S > 0.)
                  {
                    bp.sigma_n = 0.;
                    for (unsigned int k = 0; k < n_nodes; ++k)
                      if (massive[k])
                        for (unsigned int i = 0; i < dim; ++i)
                          for (unsigned int j = 0; j < dim; ++j)
                            bp.sigma_n[i][j] +=
                              bp.N[k] *
                              nodal_stress[j](
                                c.dofs[grid.fe.component_to_system_index(i,
                                                                         k)]);
                    bp.sigma_n /= S;
                    bp.with_stress = true;
                    bp.full_cell =
                      std::find(massive.begin(), massive.end(), false) ==
                      massive.end();
                  }
              }
          }
          // Cell-wise constraints: merge the particles of each such
          // boundary into one point with weight-averaged data.
          bool any_cellwise = false;
          for (unsigned int q = 0; q < n_kept; ++q)
            any_cellwise =
              any_cellwise ||
              boundary_particles
                ->boundary(boundary_points[c.first_boundary + q].boundary)
                .cellwise;
          if (any_cellwise)
            {
              std::map<unsigned int, BoundaryPoint> merged;
              std::vector<BoundaryPoint>            kept;
              for (unsigned int q = 0; q < n_kept; ++q)
                {
                  BoundaryPoint &bp = boundary_points[c.first_boundary + q];
                  if (!boundary_particles->boundary(bp.boundary).cellwise)
                    {
                      kept.push_back(std::move(bp));
                      continue;
                    }
                  auto it = merged.find(bp.boundary);
                  if (it == merged.end())
                    {
                      BoundaryPoint m  = bp;
                      m.members        = {bp.particle};
                      m.member_weights = {bp.weight};
                      m.normal *= bp.weight;
                      m.du_bar *= bp.weight;
                      m.a_bar *= bp.weight;
                      m.gap_old *= bp.weight;
                      m.sigma_n *= bp.weight;
                      m.full_cell = bp.full_cell;
                      for (auto &v : m.N)
                        v *= bp.weight;
                      for (auto &v : m.dN)
                        v *= bp.weight;
                      merged.emplace(bp.boundary, std::move(m));
                      continue;
                    }
                  BoundaryPoint &m = it->second;
                  m.members.push_back(bp.particle);
                  m.member_weights.push_back(bp.weight);
                  m.weight += bp.weight;
                  m.normal += bp.weight * bp.normal;
                  m.du_bar += bp.weight * bp.du_bar;
                  m.a_bar += bp.weight * bp.a_bar;
                  m.gap_old += bp.weight * bp.gap_old;
                  m.lambda += bp.lambda; // forces add up
                  m.sigma_n += bp.weight * bp.sigma_n;
                  m.with_stress = m.with_stress && bp.with_stress;
                  m.full_cell   = m.full_cell && bp.full_cell;
                  for (unsigned int k = 0; k < m.dN.size(); ++k)
                    m.dN[k] += bp.weight * bp.dN[k];
                  for (unsigned int k = 0; k < m.N.size(); ++k)
                    m.N[k] += bp.weight * bp.N[k];
                }
              if (!merged.empty())
                {
                  for (auto &entry : merged)
                    {
                      BoundaryPoint &m = entry.second;
                      m.normal /= m.normal.norm();
                      m.du_bar /= m.weight;
                      m.a_bar /= m.weight;
                      m.gap_old /= m.weight;
                      m.sigma_n /= m.weight;
                      for (auto &v : m.N)
                        v /= m.weight;
                      for (auto &v : m.dN)
                        v /= m.weight;
                      kept.push_back(std::move(m));
                    }
                  boundary_points.resize(c.first_boundary);
                  for (auto &bp : kept)
                    boundary_points.push_back(std::move(bp));
                  c.n_boundary = kept.size();
                }
            }
          boundary_cells.push_back(std::move(c));
        }
      cache_point_contacts();
      bool any_monolithic = false;
      for (const auto &bp : boundary_points)
        any_monolithic = any_monolithic || bp.monolithic;
      with_lagrange_multipliers =
        dealii::Utilities::MPI::logical_or(any_monolithic,
                                           grid.mpi_communicator);
    }



    template <int dim>
    void
    MPMSolver<dim>::cache_point_contacts()
    {
      // Node-to-surface contact with the material as the slave side: the
      // contact point of material point p against boundary b is the lowest
      // point of its extent, x_c = x_p - r_p n with r_p = (l0/2) J^(1/dim)
      // (the radius of the circle of the point's current volume,
      // l0 = V0^(1/dim)),
      // n and x_b the normal and position of the boundary particle nearest
      // to x_p. Its gap at the start of the step is the geometric distance
      // g0 = (x_c - x_b) . n; within the step it changes by the increment
      // at x_c interpolated with the shape functions of the point's own
      // cell (extrapolated where x_c lies outside it), all of whose nodes
      // carry mass. The tangential stick spring is the point's contact gap.
      using BP = Boundaries::BoundaryParticleProperties<dim>;
      using MP = MaterialPointProperties<dim>;
      static_assert(MP::n_contact_slots ==
                      Boundaries::BoundaryParticles<dim>::max_boundaries,
                    "one contact gap slot per boundary slot");
      if (boundary_particles == nullptr)
        return;
      boundary_particles->clear_point_contact();
      const auto        &base    = grid.fe.base_element(0);
      const unsigned int n_nodes = base.dofs_per_cell;
      const MPI_Comm     comm    = grid.mpi_communicator;
      const double       h       = grid.is_cartesian ?
                                     *std::min_element(grid.cell_extent.begin_raw(),
                                           grid.cell_extent.end_raw()) :
                                     grid.minimal_cell_diameter;
      for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
        {
          const auto &desc = boundary_particles->boundary(b);
          if (!desc.material_point_contact)
            continue;
          // every rank gets the whole surface of the boundary: positions,
          // normals and reference positions of its particles
          std::vector<double> local;
          for (const auto &p : boundary_particles->particle_handler())
            {
              const auto props = p.get_properties();
              if (static_cast<unsigned int>(props[BP::boundary]) != b)
                continue;
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(p.get_location()[d]);
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(props[BP::normal + d]);
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(props[BP::reference_position + d]);
            }
          std::vector<dealii::Point<dim>>     x_b, X_b;
          std::vector<dealii::Tensor<1, dim>> n_b;
          for (const auto &part :
               dealii::Utilities::MPI::all_gather(comm, local))
            for (unsigned int k = 0; k + 3 * dim <= part.size(); k += 3 * dim)
              {
                dealii::Point<dim>     x, X;
                dealii::Tensor<1, dim> n;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    x[d] = part[k + d];
                    n[d] = part[k + dim + d];
                    X[d] = part[k + 2 * dim + d];
                  }
                x_b.push_back(x);
                n_b.push_back(n);
                X_b.push_back(X);
              }
          if (x_b.empty())
            continue;
          const auto tree = dealii::pack_rtree_of_indices(x_b);
          for (const auto &mc : cells)
            {
              CellCache c;
              c.cell           = mc.cell;
              c.first          = 0;
              c.n              = 0;
              c.point_contact  = true;
              c.first_boundary = boundary_points.size();
              for (unsigned int q = 0; q < mc.n; ++q)
                {
                  auto                      particle = particles[mc.first + q];
                  auto                      props = particle->get_properties();
                  const auto                x_p   = particle->get_location();
                  std::vector<unsigned int> nearest;
                  tree.query(boost::geometry::index::nearest(x_p, 1),
                             std::back_inserter(nearest));
                  const unsigned int            j = nearest[0];
                  const dealii::Tensor<1, dim> &n = n_b[j];
                  const dealii::Tensor<2, dim>  F =
                    read_tensor<dim>(props, MP::deformation);
                  const double l0 =
                    std::pow(props[MP::initial_volume], 1. / dim);
                  // the circle (sphere) of the point's current volume: a
                  // rotation leaves it unchanged, and so does plastic flow
                  // at constant volume, whose F may be far from a rotation
                  const double r =
                    0.5 * l0 * std::pow(dealii::determinant(F), 1. / dim);
                  const dealii::Point<dim> x_c = x_p - r * n;
                  // an extent that overlaps the boundary at the start is
                  // measured from its initial depth on (contact offset)
                  if (initializing && (x_c - x_b[j]) * n < 0.)
                    props[MP::contact_offset + b] = -((x_c - x_b[j]) * n);
                  const double g0 =
                    (x_c - x_b[j]) * n + props[MP::contact_offset + b];
                  dealii::Tensor<1, dim> g_t;
                  for (unsigned int d = 0; d < dim; ++d)
                    g_t[d] = props[MP::contact_gap + dim * b + d];
                  g_t -= (g_t * n) * n;
                  // out of reach in this step: forget the stick spring
                  dealii::Tensor<1, dim> v;
                  for (unsigned int d = 0; d < dim; ++d)
                    v[d] = props[MP::velocity + d];
                  const double reach = initializing ?
                                         1e-6 * h :
                                         0.5 * h + 2. * dt * v.norm() +
                                           dt * dt * gravity_vector.norm();
                  if (g0 > reach)
                    {
                      for (unsigned int d = 0; d < dim; ++d)
                        props[MP::contact_gap + dim * b + d] = 0.;
                      continue;
                    }
                  BoundaryPoint bp;
                  bp.particle          = particle;
                  bp.on_material_point = true;
                  bp.boundary          = b;
                  bp.weight =
                    std::pow(props[MP::initial_volume], (dim - 1.) / dim);
                  bp.beta          = desc.beta;
                  bp.mu            = desc.friction_coefficient;
                  bp.condition     = desc.condition;
                  bp.damping       = desc.contact_damping;
                  bp.damping_onset = 1e-2 * h;
                  bp.normal        = n;
                  bp.gap_old       = g0 * n + g_t;
                  bp.du_bar        = 0.;
                  bp.a_bar         = 0.;
                  if (!initializing && desc.moving)
                    bp.du_bar =
                      boundary_particles->prescribed_displacement(b,
                                                                  X_b[j],
                                                                  time) -
                      boundary_particles->prescribed_displacement(b,
                                                                  X_b[j],
                                                                  time - dt);
                  if (initializing && desc.moving)
                    {
                      const double eps = 1e-4; // [s], as for the particles
                      bp.a_bar =
                        (boundary_particles->prescribed_displacement(b,
                                                                     X_b[j],
                                                                     time) -
                         2. * boundary_particles->prescribed_displacement(
                                b, X_b[j], time + eps) +
                         boundary_particles->prescribed_displacement(
                           b, X_b[j], time + 2. * eps)) /
                        (eps * eps);
                    }
                  // shape values of the point's cell at x_c
                  dealii::Point<dim> xi = particle->get_reference_location();
                  if (grid.is_cartesian)
                    for (unsigned int d = 0; d < dim; ++d)
                      xi[d] += (x_c[d] - x_p[d]) / grid.cell_extent[d];
                  else
                    {
                      try
                        {
                          xi = grid.mapping.transform_real_to_unit_cell(
                            typename dealii::Triangulation<
                              dim>::active_cell_iterator(mc.cell),
                            x_c);
                        }
                      catch (...)
                        {
                          // keep the point's own location
                        }
                    }
                  bp.N.resize(n_nodes);
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    bp.N[k] = base.shape_value(k, xi);
                  boundary_points.push_back(std::move(bp));
                }
              c.n_boundary = boundary_points.size() - c.first_boundary;
              if (c.n_boundary > 0)
                {
                  c.dofs = mc.dofs; // only for cells with candidates
                  boundary_cells.push_back(std::move(c));
                }
            }
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::setup_ghost_penalty()
    {
      ghost_faces.clear();
      const auto &dof_handler = grid.dof_handler;
      // Per cell: bit 0 material points, bit 1 boundary particles, bit 2
      // cut (computed on owned cells, then sent to the ghost cells).
      std::vector<unsigned char> flags(grid.triangulation.n_active_cells(), 0);
      for (const auto &c : cells)
        flags[c.cell->active_cell_index()] |= 1;
      for (const auto &c : boundary_cells)
        if (!c.point_contact)
          flags[c.cell->active_cell_index()] |= 2;
      using Iterator = typename dealii::DoFHandler<dim>::active_cell_iterator;
      const auto exchange = [&]() {
        dealii::GridTools::
          exchange_cell_data_to_ghosts<unsigned char, dealii::DoFHandler<dim>>(
            dof_handler,
            [&](const Iterator &cell) {
              return flags[cell->active_cell_index()];
            },
            [&](const Iterator &cell, const unsigned char &f) {
              flags[cell->active_cell_index()] = f;
            });
      };
      exchange();
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && (flags[cell->active_cell_index()] & 1))
          {
            bool cut = (flags[cell->active_cell_index()] & 2) != 0;
            for (const unsigned int f : cell->face_indices())
              if (!cell->at_boundary(f) &&
                  !(flags[cell->neighbor(f)->active_cell_index()] & 1))
                cut = true;
            if (cut)
              flags[cell->active_cell_index()] |= 4;
          }
      exchange();

      const double gamma = ghost_penalty_factor * elastic_tangent[0][0][0][0];
      const dealii::QGauss<dim - 1>  quadrature(2);
      dealii::FEInterfaceValues<dim> fiv(grid.mapping,
                                         grid.fe,
                                         quadrature,
                                         dealii::update_gradients |
                                           dealii::update_JxW_values |
                                           dealii::update_normal_vectors);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          if (!cell->is_locally_owned() ||
              !(flags[cell->active_cell_index()] & 1))
            continue;
          for (const unsigned int f : cell->face_indices())
            {
              if (cell->at_boundary(f))
                continue;
              const auto neighbor = cell->neighbor(f);
              const auto nf       = neighbor->active_cell_index();
              if (!(flags[nf] & 1) ||
                  !((flags[cell->active_cell_index()] | flags[nf]) & 4))
                continue;
              // each face once: the lower cell id (owned neighbour) or the
              // lower subdomain (ghost neighbour) assembles it
              if (neighbor->is_locally_owned() ?
                    !(cell->id() < neighbor->id()) :
                    !(cell->subdomain_id() < neighbor->subdomain_id()))
                continue;
              fiv.reinit(cell,
                         f,
                         dealii::numbers::invalid_unsigned_int,
                         neighbor,
                         cell->neighbor_of_neighbor(f),
                         dealii::numbers::invalid_unsigned_int);
              GhostFace g;
              g.dofs                     = fiv.get_interface_dof_indices();
              const unsigned int n       = g.dofs.size();
              const double       h       = cell->extent_in_direction(f / 2);
              const auto        &normals = fiv.get_normal_vectors();
              g.matrix.reinit(n, n);
              std::vector<double>       jump(n);
              std::vector<unsigned int> component(n);
              for (unsigned int i = 0; i < n; ++i)
                {
                  const auto pair = fiv.interface_dof_to_dof_indices(i);
                  component[i] =
                    grid.fe
                      .system_to_component_index(
                        pair[0] != dealii::numbers::invalid_unsigned_int ?
                          pair[0] :
                          pair[1])
                      .first;
                }
              for (unsigned int q = 0; q < fiv.n_quadrature_points; ++q)
                {
                  for (unsigned int i = 0; i < n; ++i)
                    jump[i] = fiv.jump_in_shape_gradients(i, q, component[i]) *
                              normals[q];
                  const double w = gamma * h * fiv.JxW(q);
                  for (unsigned int i = 0; i < n; ++i)
                    for (unsigned int j = 0; j < n; ++j)
                      if (component[i] == component[j])
                        g.matrix(i, j) += w * jump[i] * jump[j];
                }
              ghost_faces.push_back(std::move(g));
            }
        }
      n_ghost_faces = dealii::Utilities::MPI::sum(
        static_cast<unsigned int>(ghost_faces.size()), grid.mpi_communicator);
    }


    template <int dim>
    void
    MPMSolver<dim>::project_stress_to_grid()
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      std::vector<dealii::TrilinosWrappers::MPI::Vector> sum(
        dim,
        dealii::TrilinosWrappers::MPI::Vector(grid.locally_owned_dofs,
                                              grid.mpi_communicator));
      std::vector<dealii::Vector<double>> local(
        dim, dealii::Vector<double>(dofs_per_cell));
      // Voigt order of the stored stress: xx yy zz xy yz xz
      const unsigned int voigt[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
      for (const auto &c : cells)
        {
          for (auto &l : local)
            l = 0.;
          for (unsigned int q = 0; q < c.n; ++q)
            {
              const unsigned int k     = c.first + q;
              const auto         props = particles[k]->get_properties();
              const double       m     = props[Properties::mass];
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto   ci = fe.system_to_component_index(i);
                  const double N  = shape_values[k * n_nodes + ci.second];
                  for (unsigned int j = 0; j < dim; ++j)
                    local[j][i] +=
                      N * m * props[Properties::stress + voigt[ci.first][j]];
                }
            }
          for (unsigned int j = 0; j < dim; ++j)
            sum[j].add(c.dofs, local[j]);
        }
      nodal_stress.resize(dim);
      for (unsigned int j = 0; j < dim; ++j)
        {
          sum[j].compress(dealii::VectorOperation::add);
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              sum[j](i) /= nodal_mass(i);
          sum[j].compress(dealii::VectorOperation::insert);
          nodal_stress[j].reinit(grid.locally_owned_dofs,
                                 grid.locally_relevant_dofs,
                                 grid.mpi_communicator);
          nodal_stress[j] = sum[j];
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::boundary_traction(
      const BoundaryPoint                 &b,
      const std::vector<double>           &du_local,
      dealii::Tensor<1, dim>              &T,
      std::vector<dealii::Tensor<1, dim>> &dT) const
    {
      const auto        &fe            = grid.fe;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const auto        &n             = b.normal;
      if (!b.full_cell)
        {
          // the stress at the start of the step only
          T = -(b.sigma_n * n);
          for (auto &d : dT)
            d = 0.;
          return;
        }
      // grad du at the particle
      dealii::Tensor<2, dim> H;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const auto ci = fe.system_to_component_index(i);
          H[ci.first] += du_local[i] * b.dN[ci.second];
        }
      dealii::Tensor<2, dim> sigma = b.sigma_n;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int m = 0; m < dim; ++m)
              sigma[i][j] += elastic_tangent[i][j][c][m] * H[c][m];
      T = -(sigma * n);
      for (unsigned int l = 0; l < dofs_per_cell; ++l)
        {
          const auto ci = fe.system_to_component_index(l);
          dT[l]         = 0.;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              for (unsigned int m = 0; m < dim; ++m)
                dT[l][i] -= elastic_tangent[i][j][ci.first][m] *
                            b.dN[ci.second][m] * n[j];
        }
    }


    template <int dim>
    double
    MPMSolver<dim>::update_multipliers()
    {
      const auto        &fe            = grid.fe;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      double             largest_gap   = 0.;
      for (const auto &c : boundary_cells)
        for (unsigned int b = 0; b < c.n_boundary; ++b)
          {
            BoundaryPoint &bp = boundary_points[c.first_boundary + b];
            if (!bp.augmented || bp.monolithic)
              continue;
            dealii::Tensor<1, dim> du_b;
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              {
                const auto ci = fe.system_to_component_index(i);
                du_b[ci.first] += bp.N[ci.second] * displacement(c.dofs[i]);
              }
            const BoundaryForce bf = boundary_force(bp, du_b);
            if (bf.state == 0)
              {
                bp.lambda = 0.;
                continue;
              }
            // the constraint violated: the whole gap when bonded or
            // sticking, its normal part when sliding or frictionless
            const dealii::Tensor<1, dim> g = bp.gap_old + du_b - bp.du_bar;
            const bool                   whole =
              bp.condition == Boundaries::Condition::fixed ||
              (bp.condition == Boundaries::Condition::friction &&
               bf.state == 1);
            largest_gap =
              std::max(largest_gap, whole ? g.norm() : std::abs(g * bp.normal));
            bp.lambda = bf.force;
          }
      return dealii::Utilities::MPI::max(largest_gap, grid.mpi_communicator);
    }


    template <int dim>
    typename MPMSolver<dim>::BoundaryForce
    MPMSolver<dim>::boundary_force(const BoundaryPoint          &b,
                                   const dealii::Tensor<1, dim> &du) const
    {
      using Boundaries::Condition;
      // Trial force F = lambda - k g on the material (lambda = 0 for
      // penalty); its normal part F_n = F . n decides contact (F_n > 0:
      // pressed together; for penalty the same as g . n < 0).
      BoundaryForce                 r;
      const double                  k  = b.beta * b.weight;
      const dealii::Tensor<1, dim>  g  = b.gap_old + du - b.du_bar;
      const dealii::Tensor<1, dim> &n  = b.normal;
      const double                  gn = g * n;
      const dealii::Tensor<2, dim>  I  = dealii::unit_symmetric_tensor<dim>();
      const dealii::Tensor<2, dim>  nn = dealii::outer_product(n, n);
      // material-point contact: the normal dashpot eta k (g - g_old) . n,
      // scaled by s = min(1, p / p_s) with the penetration p = -g . n, so
      // that it neither pushes before contact nor jumps at first contact
      double       kd  = 0.;
      double       s   = 0.;
      const double dgn = (du - b.du_bar) * n;
      if (b.damping > 0. && gn < 0.)
        {
          s  = std::min(1., -gn / b.damping_onset);
          kd = b.damping * k * s;
          if (s < 1.) // d(s dgn)/du = s n + dgn ds/du, ds/du = -n / p_s
            kd -= b.damping * k * dgn / b.damping_onset;
        }
      const dealii::Tensor<1, dim> F =
        b.lambda - k * g - (b.damping * k * s * dgn) * n;
      const double Fn = F * n;
      // Lagrange multipliers: hysteresis at the kinks of the semi-smooth
      // Newton iteration. A point that was open in the last iterate closes
      // only when it penetrates by more than the gap tolerance, and a point
      // that slid sticks only when its trial force lies more than k times
      // the gap tolerance inside the Coulomb cone; a closed point opens, and
      // a sticking one slides, as soon as the force asks for it (no
      // adhesion, no force beyond the cone). Near convergence this keeps
      // points whose force is zero (or at the cone) to round-off from
      // flipping between the two states, at an error within the gap
      // tolerance.
      const bool   hysteresis = b.monolithic && b.frozen < 0;
      const double margin =
        hysteresis ? k * boundary_particles->multiplier_tolerance() : 0.;
      const bool pressed = Fn > (hysteresis && b.last_state == 0 ? margin : 0.);
      switch (b.condition)
        {
          case Condition::fixed:
            r.force     = F;
            r.dforce_du = -k * I;
            r.gap       = g;
            r.state     = 1;
            break;
          case Condition::slip:
            r.force     = Fn * n;
            r.dforce_du = -k * nn;
            r.gap       = gn * n;
            r.state     = 1;
            break;
          case Condition::contact:
            if (b.frozen < 0 ? pressed : b.frozen != 0)
              {
                r.force     = Fn * n;
                r.dforce_du = -(k + kd) * nn;
                r.gap       = gn * n;
                r.state     = 1;
              }
            break;
          case Condition::friction:
            if (b.frozen < 0 ? pressed :
                               (b.frozen == 1 || b.frozen == 3 ||
                                (b.frozen == 2 && pressed)))
              {
                const double                 fn      = Fn; // > 0
                const dealii::Tensor<1, dim> f_trial = F - Fn * n;
                const double                 norm    = f_trial.norm();
                const double                 limit   = b.mu * fn;
                const double                 stick_limit =
                  limit - (hysteresis && b.last_state == 2 ? margin : 0.);
                if (b.frozen < 0 ? norm <= stick_limit :
                                   (b.frozen == 1 || norm == 0.))
                  {
                    r.force     = fn * n + f_trial;
                    r.dforce_du = -k * I - kd * nn;
                    r.gap       = g;
                    r.state     = 1;
                  }
                else
                  {
                    const dealii::Tensor<1, dim> s = f_trial / norm;
                    r.force                        = fn * n + limit * s;
                    r.dforce_du =
                      -(k + kd) * nn -
                      (k + kd) * b.mu * dealii::outer_product(s, n) -
                      (limit * k / norm) *
                        ((I - dealii::outer_product(s, s)) * (I - nn));
                    // penalty: the elastic part of the tangential gap
                    // carries the force into the next step; augmented
                    // Lagrangian: the multiplier does, the gap keeps only
                    // its normal part
                    r.gap   = b.augmented || b.nitsche ? gn * n :
                                                         gn * n - (limit / k) * s;
                    r.state = 2;
                  }
              }
            break;
        }
      return r;
    }


    template <int dim>
    Diagnostics<dim>
    MPMSolver<dim>::compute_diagnostics() const
    {
      using Properties = MaterialPointProperties<dim>;
      Diagnostics<dim>   d;
      double             point_speed       = 0.;
      const unsigned int n_history         = points.n_history();
      int                dissipation_index = -1;
      {
        const auto names = model.history_names();
        for (unsigned int h = 0; h < names.size(); ++h)
          if (names[h] == "plastic_dissipation")
            dissipation_index = h;
      }
      for (const auto &p : points.particle_handler())
        {
          if (dissipation_index >= 0)
            d.plastic_dissipation +=
              p.get_properties()[Properties::initial_volume] *
              p.get_properties()[Properties::history + dissipation_index];
          const auto   props = p.get_properties();
          const double m     = props[Properties::mass];
          d.mass += m;
          double v2 = 0.;
          for (unsigned int i = 0; i < dim; ++i)
            {
              const double v = props[Properties::velocity + i];
              d.momentum[i] += m * v;
              v2 += v * v;
              d.gravitational_energy -=
                m * gravity_vector[i] * p.get_location()[i];
            }
          d.kinetic_energy += 0.5 * m * v2;
          point_speed = std::max(point_speed, std::sqrt(v2));
          d.volume += props[Properties::initial_volume] *
                      dealii::determinant(
                        read_tensor<dim>(props, Properties::deformation));
          d.strain_energy +=
            props[Properties::initial_volume] *
            model.energy_density(
              embed<dim>(read_tensor<dim>(props, Properties::deformation)),
              dealii::ArrayView<const double>(props.data() +
                                                Properties::history,
                                              n_history));
        }
      const MPI_Comm comm = grid.mpi_communicator;
      d.mass              = dealii::Utilities::MPI::sum(d.mass, comm);
      d.momentum          = dealii::Utilities::MPI::sum(d.momentum, comm);
      d.kinetic_energy    = dealii::Utilities::MPI::sum(d.kinetic_energy, comm);
      d.strain_energy     = dealii::Utilities::MPI::sum(d.strain_energy, comm);
      d.gravitational_energy =
        dealii::Utilities::MPI::sum(d.gravitational_energy, comm);
      d.plastic_dissipation =
        dealii::Utilities::MPI::sum(d.plastic_dissipation, comm);
      d.volume               = dealii::Utilities::MPI::sum(d.volume, comm);
      d.friction_dissipation = friction_dissipation;
      d.reset_dissipation    = reset_dissipation;
      d.transfer_dissipation = transfer_dissipation;
      d.contact_force        = contact_force;
      if (grid_kinetic_energy >= 0.)
        {
          d.grid_kinetic_energy = grid_kinetic_energy;
          d.max_grid_speed      = max_grid_speed;
        }
      else
        {
          // no step yet: the points' velocities are the initial field
          d.grid_kinetic_energy = d.kinetic_energy;
          d.max_grid_speed = dealii::Utilities::MPI::max(point_speed, comm);
        }
      if (boundary_particles != nullptr)
        d.boundaries = boundary_particles->resultants();
      return d;
    }


    template class MPMSolver<2>;
    template class MPMSolver<3>;
  } // namespace MPM
} // namespace Talus
