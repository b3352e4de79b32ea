#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>
#include <talus/mpm/mpm_solver.h>
#include <talus/mpm/point_tensors.h>

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
    using internal::embed;
    using internal::read_tensor;

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
        ContactTimeIntegration::declare_parameters(prm);
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
          "benchmarks (doc/performance.md, 'Granular collapse: time to "
          "solution').");
        prm.declare_entry("linear solver",
                          "CG",
                          Patterns::Selection("CG|GMRES|direct"),
                          "'CG' or 'GMRES' (with 'preconditioner': by "
                          "default Trilinos ML algebraic multigrid with the "
                          "rigid body modes as near null space; 'GMRES' for "
                          "the non-symmetric tangents of plasticity with "
                          "contact, with 'AMG smoother = ILU' or "
                          "'preconditioner = ILU', doc/performance.md), or "
                          "'direct' (Amesos KLU or MUMPS, 'direct solver').");
        prm.declare_entry(
          "direct solver",
          "KLU",
          Patterns::Selection("KLU|MUMPS"),
          "Amesos package of 'linear solver = direct' [-]: 'KLU' (serial: "
          "the matrix is gathered on rank 0; symbolic analysis reused while "
          "the sparsity pattern stays, pivot sequence reused within a step) "
          "or 'MUMPS' (distributed multifrontal LU over all ranks, symbolic "
          "analysis reused like KLU's; for large 3D tangents and several "
          "ranks, doc/performance.md).");
        prm.declare_entry(
          "preconditioner",
          "AMG",
          Patterns::Selection("AMG|ILU|Jacobi"),
          "Preconditioner of 'linear solver = CG' or 'GMRES' [-]: 'AMG' "
          "(Trilinos ML, see 'AMG smoother'), 'ILU' (Ifpack incomplete LU "
          "of fill level 'ILU fill level', processor-local, additive Schwarz "
          "across ranks) or 'Jacobi' (point Jacobi). Built once per step "
          "with 'reuse preconditioner'.");
        prm.declare_entry("GMRES restart length",
                          "28",
                          Patterns::Integer(1),
                          "Krylov vectors of 'linear solver = GMRES' before "
                          "it restarts [-] (deal.II's default 28).");
        prm.declare_entry("AMG smoother sweeps",
                          "2",
                          Patterns::Integer(1),
                          "Smoother sweeps per level of the ML algebraic "
                          "multigrid [-].");
        prm.declare_entry("AMG aggregation threshold",
                          "0.02",
                          Patterns::Double(0),
                          "Strength-of-connection threshold of ML's "
                          "aggregation [-]: couplings weaker than it "
                          "relative to the diagonals are dropped.");
        prm.declare_entry("ILU fill level",
                          "0",
                          Patterns::Integer(0),
                          "Fill level k of ILU(k) for 'preconditioner = "
                          "ILU' [-].");
        prm.declare_entry(
          "AMG smoother",
          "Chebyshev",
          Patterns::Selection(
            "Chebyshev|symmetric Gauss-Seidel|Gauss-Seidel|ILU"),
          "Smoother of the ML algebraic multigrid ('AMG smoother sweeps' "
          "per level) [-]: 'Chebyshev' (polynomial in the point "
          "Jacobi-scaled matrix), 'symmetric Gauss-Seidel' or "
          "'Gauss-Seidel' (forward sweeps only; both processor-local, "
          "Jacobi across ranks) or 'ILU' (Ifpack ILU(0) of each level's "
          "matrix, processor-local; not symmetric: for GMRES). On the "
          "non-symmetric plastic and frictional tangents of the granular "
          "benchmarks the ILU smoother needs the fewest Krylov iterations "
          "and failed no solve up to 0.05 m cells in 3D, where Chebyshev "
          "and Gauss-Seidel fail on rows of grid friction "
          "(doc/performance.md, 'Growth with the grid'). Gauss-Seidel "
          "handles the stiff rank-one couplings of contact on boundaries "
          "that are not aligned with the grid much better than Chebyshev: "
          "the Lagrange multiplier block solve on a fine 3D grid needs it "
          "(doc/verification.md, saddle-point solve with AMG); combine it "
          "with a 'ghost penalty factor' when cut cells are small.");
        prm.declare_entry(
          "AMG aggregation",
          "symmetric",
          Patterns::Selection("symmetric|non-symmetric"),
          "Multigrid hierarchy of ML [-]: 'symmetric' (smoothed aggregation, "
          "ML's 'SA' defaults: the prolongator smoothed with a damped "
          "Jacobi step, restriction its transpose; Vanek, Mandel and Brezina "
          "1996) or 'non-symmetric' (ML's 'NSSA': Petrov-Galerkin smoothed "
          "aggregation with restriction and prolongation smoothed separately "
          "by energy minimisation, for non-symmetric operators; Sala and "
          "Tuminaro 2008, SIAM J. Sci. Comput. 31).");
        prm.declare_entry("AMG cycle",
                          "V",
                          Patterns::Selection("V|W"),
                          "Multigrid cycle of the ML preconditioner [-]: "
                          "'V' or 'W' (the coarse levels visited twice per "
                          "visit of the level above).");
        prm.declare_entry("AMG coarse size",
                          "2000",
                          Patterns::Integer(1),
                          "Rows of the coarsest ML level [-]: ML coarsens "
                          "until a level has fewer rows and solves that level "
                          "with KLU. A tangent with fewer rows than this is "
                          "solved directly by the 'preconditioner' (one "
                          "Krylov iteration).");
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
                          "Build the preconditioner ('preconditioner') once "
                          "per time step (first Newton iteration) and reuse "
                          "it in the later iterations, and in a coupled "
                          "problem through the coupling iterations of the "
                          "step while the interface stays in the same cells; "
                          "it is rebuilt when a boundary particle's contact "
                          "state changes and when the Krylov solver fails "
                          "with it.");
        prm.declare_entry("linear solver tolerance",
                          "1e-10",
                          Patterns::Double(0),
                          "Relative residual reduction of the iterative "
                          "linear solver [-].");
        EisenstatWalkerForcing::declare_parameters(prm);
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
          "acceleration' without boundary particles and with 'start "
          "acceleration = projected', else 'zero'. "
          "Measured (doc/performance.md, 'Granular collapse: time to "
          "solution'): the Bui "
          "collapse at 5 mm needs 4.4 instead of 5.8 Newton iterations per "
          "step, the plane-strain granular block of "
          "contrib/granular/block_rest_study.sh at 25 mm 670 instead of 1329 "
          "steps; the 3D block on the plane of boundary particles "
          "(benchmarks/granular_3d/block_on_rotated_plane.prm) is slower "
          "with it (more rejected steps), hence 'zero' there. Quasi-static "
          "analyses always start from zero.");
        prm.declare_entry(
          "start acceleration",
          "projected",
          Patterns::Selection("projected|from forces"),
          "Grid acceleration a_n at the start of a dynamic step, which the "
          "Newmark update v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma "
          "a_{n+1}) weighs [no unit]. 'projected': the points' accelerations "
          "projected to the nodes like their velocities (standard implicit "
          "MPM). 'from forces': a_n = (f_ext - f_int) / m_I at the free nodes "
          "from the points' stresses at the start of the step (one extra "
          "residual assembly per step), the acceleration for which the "
          "trapezoidal rule conserves the grid's energy; with 'projected' the "
          "difference does work du (m a_n - f_n) / 2 per step that no "
          "energy account books (doc/theory.md, 'Newton's method: line search "
          "and energy balance', the start acceleration). Lumped "
          "mass only, not with friction boundaries or boundary particles. "
          "'predictor = automatic' starts its Newton iterations from zero: "
          "the force acceleration of nodes with little mass is large, and "
          "the Newmark predictor inverted points of the cantilever of "
          "tests/mpm/cantilever_neo_hookean_energy (10 rejected steps).");
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
          "dissipative), in between a blend, applied once per step (see "
          "'FLIP fraction reference step'). Used by 'velocity update = "
          "FLIP' only.");
        prm.declare_entry(
          "FLIP fraction reference step",
          "0",
          Patterns::Double(0),
          "Step to which 'FLIP fraction' f refers [s], >= 0. 0: f is "
          "applied once per step whatever its size, so that the PIC share "
          "per second, and with it the damping of the points' velocity "
          "towards the grid's, grows as the step shrinks. > 0: a step of "
          "size dt uses f^(dt / reference step): the points' departure from "
          "the grid velocity decays as f^(t / reference step) whatever the "
          "step (a relaxation time -reference step / ln f), so that "
          "results converge in the step. Used with 'FLIP fraction' < 1 and "
          "'velocity update = FLIP' only.");
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
        prm.declare_entry(
          "shape functions",
          "linear",
          Patterns::Selection("linear|uGIMP|cpGIMP|CPDI"),
          "Shape functions of the transfer between the material points and "
          "the grid and of the points' integration [-]. 'linear': the Q1 "
          "shape functions of the point's cell (standard MPM; a point that "
          "crosses a cell face sees a jump of the gradient, the "
          "cell-crossing error). 'uGIMP' (uniform generalized interpolation "
          "material point, Bardenhagen and Kober 2004; weights of Steffen, "
          "Kirby and Berzins 2008, IJNME 76): the Q1 functions averaged over "
          "the point's domain, a box of half-width l_p = h / (2 n) per "
          "direction (h the cell size, n the points per cell per direction "
          "of subsection Body), fixed at its undeformed size. 'cpGIMP' "
          "(contiguous-particle GIMP, Bardenhagen and Kober 2004, with the "
          "domain update of Wallstedt and Guilkey 2008, J Comput Phys 227): "
          "the same box stretched by the point's "
          "deformation gradient F committed at the end of the last step "
          "('cpGIMP domain stretch'), frozen over a step and capped at the "
          "cell size h. 'CPDI' (convected particle domain interpolation, "
          "CPDI1 of Sadeghirad, Brannon and Burghardt 2011, IJNME 86): the "
          "point's domain is the parallelogram (parallelepiped in 3D) "
          "spanned by r_i = F r_i^0, r_i^0 = l0 e_i the uGIMP half-widths, "
          "with F committed at the end of the last step and frozen over a "
          "step; the weight is the mean of the Q1 functions at its 2^dim "
          "corners, the gradient the corner formula of the paper; a domain "
          "whose corners would leave the 3^dim cells around the point's "
          "cell or the grid is scaled down about the point until they do "
          "not (counted in the run's final message). The weights "
          "and their gradients are continuous as a point crosses a face; a "
          "point influences the nodes of the 3^dim cells around its cell "
          "(truncated at the grid's boundary), and Newton uses these "
          "gradients in its consistent tangent. F-bar averages over the "
          "points of a cell, whose derivatives then reach the whole patch. "
          "Boundary particles (and material-point contact) act on the grid's "
          "Q1 field at their location, as with 'linear'. uGIMP, cpGIMP and "
          "CPDI: "
          "Cartesian background grids only ('grid type = box'); not with "
          "APIC or the ghost penalty.");
        prm.declare_entry(
          "cpGIMP domain stretch",
          "diagonal",
          Patterns::Selection("diagonal|bounding box"),
          "With 'shape functions = cpGIMP': how the half-widths l0 = h / "
          "(2 n) of a point's box follow its deformation gradient F [-]. "
          "'diagonal': l_i = |F_ii| l0_i (Wallstedt and Guilkey 2008; a "
          "rotated point's box shrinks, to zero width at 90 degrees). "
          "'bounding box': l_i = sum_j |F_ij| l0_j, the axis-aligned box "
          "around the deformed parallelogram F (box) (exact under stretch "
          "along the axes and under rotations by multiples of 90 degrees, "
          "larger than the deformed domain under shear or other "
          "rotations). Either is capped at l_i = h, the reach of the 4^dim "
          "node patch; the run's final message (not in test mode) counts "
          "the capped points.");
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
      contact_time_integration.parse_parameters(prm);
      const auto g = parse_point<dim>(prm, sub, "gravity");
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
      direct_package =
        prm.get("direct solver") == "MUMPS" ? "Amesos_Mumps" : "Amesos_Klu";
      preconditioner_type = prm.get("preconditioner");
      gmres_restart       = prm.get_integer("GMRES restart length");
      amg_sweeps          = prm.get_integer("AMG smoother sweeps");
      amg_threshold       = prm.get_double("AMG aggregation threshold");
      amg_elliptic        = prm.get("AMG aggregation") == "symmetric";
      amg_w_cycle         = prm.get("AMG cycle") == "W";
      amg_coarse_size     = prm.get_integer("AMG coarse size");
      ilu_fill            = prm.get_integer("ILU fill level");
      {
        const std::string s = prm.get("saddle-point solver");
        block_saddle_point =
          s == "block preconditioned" ||
          (s == "automatic" && linear_solver_type != "direct");
      }
      linear_tolerance = get_positive(prm, sub, "linear solver tolerance");
      linear_forcing.parse_parameters(prm, sub);
      if (linear_forcing.enabled() && linear_solver_type == "direct")
        InputFile::reject(sub,
                          "linear solver forcing",
                          "Eisenstat-Walker",
                          "'fixed' with 'linear solver = direct' (inexact "
                          "Newton needs an iterative linear solver)");
      max_linear_iterations = prm.get_integer("maximum linear iterations");
      abort_on_lost_points  = prm.get_bool("abort on lost material points");
      use_fbar    = prm.get("volumetric locking treatment") == "F-bar";
      line_search = prm.get_bool("line search");
      predictor   = prm.get("predictor");
      start_acceleration_from_forces =
        prm.get("start acceleration") == "from forces";
      if (start_acceleration_from_forces && consistent_mass)
        InputFile::reject(sub,
                          "start acceleration",
                          "from forces",
                          "'projected' with 'mass matrix = consistent' "
                          "('from forces' needs the lumped mass)");
      flip_fraction       = prm.get_double("FLIP fraction");
      flip_reference_step = prm.get_double("FLIP fraction reference step");
      if (flip_reference_step > 0. && flip_fraction == 1.)
        InputFile::reject(sub,
                          "FLIP fraction reference step",
                          prm.get("FLIP fraction reference step"),
                          "it applies to a 'FLIP fraction' below 1 only "
                          "(with 1, pure FLIP, leave it at 0)");
      apic       = prm.get("velocity update") == "APIC";
      xpic_order = prm.get("velocity update") == "XPIC" ?
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
      shape_name           = prm.get("shape functions");
      gimp                 = shape_name != "linear";
      convected_domain     = shape_name == "cpGIMP";
      cpdi                 = shape_name == "CPDI";
      domain_bounding_box  = prm.get("cpGIMP domain stretch") == "bounding box";
      shape_stride         = gimp ? (dim == 2 ? 16 : 64) : (1u << dim);
      if (!convected_domain && prm.get("cpGIMP domain stretch") != "diagonal")
        InputFile::reject(sub,
                          "cpGIMP domain stretch",
                          prm.get("cpGIMP domain stretch"),
                          "it applies to 'shape functions = cpGIMP' only; "
                          "with 'shape functions = " +
                            shape_name + "' leave it at 'diagonal'");
      if (gimp)
        {
          const auto reject_with = [&](const std::string &what) {
            InputFile::reject(sub,
                              "shape functions",
                              shape_name,
                              shape_name + " is not implemented with " + what +
                                "; use 'shape functions = linear'");
          };
          if (apic)
            reject_with("'velocity update = APIC'");
          if (ghost_penalty_factor > 0.)
            reject_with("the ghost penalty ('ghost penalty factor' > 0)");
        }
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
        const unsigned int  n_history = model.n_history_variables();
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

      if (gimp)
        setup_gimp_lattice();

      // hanging-node constraints of a locally refined grid
      hanging_constraints.clear();
      hanging_constraints.reinit(grid.locally_relevant_dofs);
      dealii::DoFTools::make_hanging_node_constraints(dof_handler,
                                                      hanging_constraints);
      hanging_constraints.close();
      has_hanging_nodes = dealii::Utilities::MPI::logical_or(
        hanging_constraints.n_constraints() > 0, grid.mpi_communicator);
      if (has_hanging_nodes)
        check_local_refinement_support();

      dealii::DynamicSparsityPattern dsp(grid.locally_relevant_dofs);
      if (ghost_penalty_factor > 0.)
        dealii::DoFTools::make_flux_sparsity_pattern(dof_handler, dsp);
      else
        dealii::DoFTools::make_sparsity_pattern(dof_handler,
                                                dsp,
                                                hanging_constraints,
                                                true);
      dealii::SparsityTools::distribute_sparsity_pattern(
        dsp,
        grid.locally_owned_dofs,
        grid.mpi_communicator,
        grid.locally_relevant_dofs);
      amg.reset();
      ifpack_preconditioner.reset();
      direct_solver.reset();
      direct_problem.reset();
      matrix.reinit(grid.locally_owned_dofs,
                    grid.locally_owned_dofs,
                    dsp,
                    grid.mpi_communicator);
      // the whole grid's pattern: the first step makes its own
      pattern_current = false;
      p2g_current     = false;

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
          dof_handler,
          grid.component_mask(std::vector<bool>(dim, true)),
          grid.fixed_boundaries);
      if (grid.fixed_region_given)
        {
          // every grid node inside the fixed region, on the boundary or not
          const double tolerance = 1e-10 * grid.minimal_cell_diameter;
          const auto   inside    = [&](const dealii::Point<dim> &x) {
            for (unsigned int d = 0; d < dim; ++d)
              if (x[d] < grid.fixed_region_lower[d] - tolerance ||
                  x[d] > grid.fixed_region_upper[d] + tolerance)
                return false;
            return true;
          };
          std::vector<dealii::types::global_dof_index> dofs;
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (!cell->is_artificial())
              for (const unsigned int v : cell->vertex_indices())
                if (inside(cell->vertex(v)))
                  for (unsigned int d = 0; d < dim * grid.n_velocity_fields();
                       ++d)
                    dofs.push_back(cell->vertex_dof_index(v, d));
          std::sort(dofs.begin(), dofs.end());
          dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
          const unsigned int n_found =
            dealii::Utilities::MPI::max(static_cast<unsigned int>(dofs.size()),
                                        comm);
          if (n_found == 0)
            InputFile::reject("Background grid",
                              "fixed region lower corner",
                              "(with 'fixed region upper corner')",
                              "the box of fixed nodes contains no node of the "
                              "grid; it must enclose at least one");
          fixed_dofs.add_indices(dofs.begin(), dofs.end());
        }
      if (start_acceleration_from_forces && !grid.friction_boundaries.empty())
        InputFile::reject("Solver",
                          "start acceleration",
                          "from forces",
                          "'projected' with grid friction boundaries "
                          "('from forces' is implemented for fixed and "
                          "slip boundaries)");
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
          std::vector<bool>                    directions(dim, false);
          directions[axis]                 = true;
          const dealii::ComponentMask mask = grid.component_mask(directions);
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
          grid.system_fe().dofs_per_cell);
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
                      grid.system_fe().system_to_component_index(i).first % dim;
                  }
            }
      }
      dealii::DoFTools::extract_constant_modes(
        dof_handler,
        dealii::ComponentMask(grid.system_fe().n_components(), true),
        constant_modes);
      setup_friction_nodes();
    }


    template <int dim>
    void
    MPMSolver<dim>::check_local_refinement_support() const
    {
      const std::string why =
        "is not implemented on a locally refined background grid "
        "(subsection Adaptive grid, 'enable = true')";
      if (gimp)
        InputFile::reject("Solver",
                          "shape functions",
                          shape_name,
                          shape_name + " " + why +
                            "; use 'shape functions = linear'");
      if (apic)
        InputFile::reject("Solver",
                          "velocity update",
                          "APIC",
                          "APIC " + why + "; use FLIP/PIC or XPIC");
      if (consistent_mass)
        InputFile::reject("Solver",
                          "mass matrix",
                          "consistent",
                          "the consistent mass matrix " + why +
                            "; use 'mass matrix = lumped'");
      if (ghost_penalty_factor > 0.)
        InputFile::reject("Solver",
                          "ghost penalty factor",
                          std::to_string(ghost_penalty_factor),
                          "the ghost penalty " + why + "; set it to 0");
    }


    template <int dim>
    void
    MPMSolver<dim>::setup_gimp_lattice()
    {
      if (!grid.is_cartesian)
        InputFile::reject("Solver",
                          "shape functions",
                          shape_name,
                          shape_name +
                            " needs a Cartesian background grid "
                            "(subsection Background grid, 'grid type = box'); "
                            "this grid is read from a mesh file");
      // the caches' node-major dof order is FESystem<FE_Q(1)^dim>'s
      for (unsigned int i = 0; i < grid.fe.dofs_per_cell; ++i)
        AssertThrow(grid.fe.system_to_component_index(i) ==
                      internal::component_and_node<dim>(i),
                    dealii::ExcInternalError());
      const unsigned int n = points.points_per_cell_direction();
      for (unsigned int d = 0; d < dim; ++d)
        {
          gimp_half_width[d] = grid.cell_extent[d] / (2. * n);
          lattice_size[d] =
            std::llround((grid.upper_corner[d] - grid.lower_corner[d]) /
                         grid.cell_extent[d]) +
            1;
        }
      lattice_dofs.clear();
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int v : cell->vertex_indices())
            {
              long long key = 0;
              for (int d = dim - 1; d >= 0; --d)
                key = key * lattice_size[d] +
                      std::llround((cell->vertex(v)[d] - grid.lower_corner[d]) /
                                   grid.cell_extent[d]);
              std::vector<dealii::types::global_dof_index> dofs(
                dim * grid.n_velocity_fields());
              for (unsigned int d = 0; d < dofs.size(); ++d)
                dofs[d] = cell->vertex_dof_index(v, d);
              lattice_dofs[key] = std::move(dofs);
            }
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
    MPMSolver<dim>::make_constraints()
    {
      constraints.clear();
      constraints.reinit(grid.locally_relevant_dofs);
      n_active = 0;
      for (const auto i : grid.locally_relevant_dofs)
        {
          // a hanging node follows its masters (whatever else holds it:
          // its masters lie on the same boundary or have no mass either)
          if (has_hanging_nodes && hanging_constraints.is_constrained(i))
            {
              constraints.add_line(i);
              constraints.add_entries(
                i, *hanging_constraints.get_constraint_entries(i));
              continue;
            }
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
      time = new_time;
      dt   = step;
      cache_particles();
      project_to_grid();
      prepare_body_contact();
      acceleration_p2g = acceleration_n;
      // the initial acceleration's projection (zero step) is not a step
      p2g_current = !initializing;
      prepare_boundaries();
    }


    template <int dim>
    void
    MPMSolver<dim>::update_boundary_displacement()
    {
      if (!p2g_current)
        {
          AssertThrow(dt > 0.,
                      dealii::ExcMessage("update_boundary_displacement() "
                                         "before the first prepare_step()"));
          prepare_step(time, dt);
          return;
        }
      dealii::TimerOutput::Scope scope(timer, "prepare (P2G)");
      // the grid state as project_to_grid() left it (the last preparation
      // reset the constrained nodes, Newton restored released ones)
      velocity_n          = velocity_p2g;
      acceleration_n      = acceleration_p2g;
      updating_boundaries = true;
      prepare_boundaries();
      updating_boundaries = false;
    }


    template <int dim>
    void
    MPMSolver<dim>::prepare_boundaries()
    {
      step_impact_dissipation = 0.;
      step_reset_dissipation  = 0.;
      start_force_recorded    = false;
      cache_boundary_particles();
      if (ghost_penalty_factor > 0.)
        setup_ghost_penalty();
      make_step_sparsity_pattern();
      apply_impact_friction();
      initialize_friction_states();
      make_constraints();
      if (!preconditioner_kept_for_window)
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
    void
    MPMSolver<dim>::make_step_sparsity_pattern()
    {
      std::vector<dealii::types::global_dof_index> blocks;
      const auto add = [&blocks](const auto &set) {
        for (const auto &c : set)
          {
            blocks.push_back(c.dofs.size());
            blocks.insert(blocks.end(), c.dofs.begin(), c.dofs.end());
          }
      };
      add(cells);
      add(boundary_cells);
      add(ghost_faces);
      add(contact_nodes);
      const bool changed = dealii::Utilities::MPI::logical_or(
        !pattern_current || blocks != pattern_blocks, grid.mpi_communicator);
      // The saddle-point factorisation and the preconditioner are built
      // anew in every step (they reference the matrix: released first,
      // ML's Gauss-Seidel smoothers access it on destruction); the direct
      // solver's first factorisation of the step pivots anew
      // (solve_with_tangent()). A coupling iteration that moves the
      // interface within the same cells keeps the AMG or Ifpack
      // preconditioner of the last Newton iteration (with 'reuse
      // preconditioner'): the tangent changed only by the boundary
      // particles' small displacement, and newton_solve() drops it if a
      // contact state changed; a Krylov solve that fails with it rebuilds
      // it.
      preconditioner_kept_for_window =
        updating_boundaries && !changed && reuse_preconditioner;
      factorisation.reset();
      if (!preconditioner_kept_for_window)
        {
          amg.reset();
          ifpack_preconditioner.reset();
          amg_current = false;
        }
      direct_pivoting = true;
      if (!changed)
        return;
      pattern_blocks  = std::move(blocks);
      pattern_current = true;
      direct_solver.reset();
      direct_problem.reset();
      dealii::DynamicSparsityPattern dsp(grid.locally_relevant_dofs);
      for (const auto i : grid.locally_owned_dofs)
        dsp.add(i, i);
      const auto add_block =
        [&dsp, this](const std::vector<dealii::types::global_dof_index> &dofs) {
          std::vector<dealii::types::global_dof_index> sorted(dofs);
          std::sort(sorted.begin(), sorted.end());
          for (const auto i : sorted)
            dsp.add_entries(i, sorted.begin(), sorted.end(), true);
          // the couplings of the hanging nodes' masters
          if (has_hanging_nodes)
            hanging_constraints.add_entries_local_to_global(dofs, dsp, true);
        };
      for (const auto &c : cells)
        add_block(c.dofs);
      for (const auto &c : boundary_cells)
        add_block(c.dofs);
      for (const auto &g : ghost_faces)
        add_block(g.dofs);
      for (const auto &n : contact_nodes)
        add_block(n.dofs);
      dealii::SparsityTools::distribute_sparsity_pattern(
        dsp,
        grid.locally_owned_dofs,
        grid.mpi_communicator,
        grid.locally_relevant_dofs);
      matrix.reinit(grid.locally_owned_dofs,
                    grid.locally_owned_dofs,
                    dsp,
                    grid.mpi_communicator);
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
      // the states of the initial acceleration start the first step
      commit_friction_states();

      using Properties           = MaterialPointProperties<dim>;
      const unsigned int n_nodes = shape_stride;
      for (const auto &c : cells)
        for (unsigned int q = 0; q < c.n; ++q)
          {
            const unsigned int     k = c.first + q;
            dealii::Tensor<1, dim> a_p;
            for (unsigned int i = 0; i < c.dofs.size(); ++i)
              {
                const auto ci = internal::component_and_node<dim>(i);
                a_p[ci.first] += shape_values[k * n_nodes + ci.second] *
                                 conforming_value(acceleration_new, c.dofs[i]);
              }
            auto props = particles[k]->get_properties();
            for (unsigned int d = 0; d < dim; ++d)
              props[Properties::acceleration + d] = a_p[d];
          }
      p2g_current = false;
      prepared    = false;
    }


    template <int dim>
    void
    MPMSolver<dim>::attach_boundary_particles(
      Boundaries::BoundaryParticles<dim> &boundaries)
    {
      p2g_current        = false;
      boundary_particles = boundaries.empty() ? nullptr : &boundaries;
      check_contact_time_integration(boundaries);
      // (resize: a checkpoint restored before keeps its values)
      accounts.boundary_friction_dissipation.resize(boundaries.n_boundaries(),
                                                    0.);
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
    std::string
    MPMSolver<dim>::friction_at_rest_warning() const
    {
      // Friction between bodies: without the line search Newton cycles
      // where contact nodes switch between stick and slip
      // (doc/verification.md, "Several bodies and materials": a block
      // sticking at mu = 0.7 fails at every step size)
      const std::string bodies =
        multi_field && body_friction > 0. && !line_search ?
          "Warning: friction between bodies (subsection Body contact, "
          "'friction coefficient' > 0) without Newton's line search: where "
          "the bodies stick, Newton may cycle between stick and slip and "
          "the steps fail; set 'line search = true' in subsection <Solver> "
          "(doc/verification.md, \"Several bodies and materials\").\n" :
          "";
      return bodies + boundary_friction_at_rest_warning();
    }


    template <int dim>
    std::string
    MPMSolver<dim>::boundary_friction_at_rest_warning() const
    {
      // Bodies meant to stay at rest on a frictional boundary slip and creep
      // in cut cells without numerical damping and the ghost penalty
      // (doc/verification.md, "A block at rest whatever the cut": 0 of 40
      // cuts at rest with Newmark gamma = 0.5 and no ghost penalty, 40 of
      // 40 with gamma = 0.6 and ghost penalty factor 1).
      if (boundary_particles == nullptr || quasi_static ||
          (newmark.gamma > 0.5 && ghost_penalty_factor > 0.))
        return "";
      for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
        if (boundary_particles->boundary(b).condition ==
              Boundaries::Condition::friction &&
            !boundary_particles->boundary(b).moving)
          {
            std::ostringstream msg;
            msg << "Warning: boundary " << boundary_particles->name(b)
                << " holds material by Coulomb friction in a dynamic run "
                << (newmark.gamma <= 0.5 ? "without numerical damping "
                                           "(Newmark gamma = 0.5)" :
                                           "")
                << (newmark.gamma <= 0.5 && ghost_penalty_factor == 0. ?
                      " and " :
                      "")
                << (ghost_penalty_factor == 0. ? "without the ghost penalty" :
                                                 "")
                << ": a body meant to stay at rest on it may slip and creep "
                   "in cut cells (a block on a 30 degree incline below its "
                   "friction angle, 40 cuts of its cells: at rest in none "
                   "of the 40 runs with neither or with the ghost penalty "
                   "alone, in 32 with the damping alone, in all 40 with "
                   "both: 'Newmark gamma = 0.6', 'Newmark beta = 0.3025' in "
                   "subsection Time and 'ghost penalty factor = 1' in "
                   "subsection Solver; doc/verification.md, \"A block at "
                   "rest whatever the cut\").\n";
            return msg.str();
          }
      return "";
    }


    template <int dim>
    void
    MPMSolver<dim>::save_state()
    {
      saved_state.accounts            = accounts;
      saved_state.grid_kinetic_energy = grid_kinetic_energy;
      saved_state.max_grid_speed      = max_grid_speed;
      saved_state.contact_force       = contact_force;
      saved_state.grid_velocity       = committed_grid_velocity;
      saved_state.stuck               = committed_stuck;
      saved_state.saved               = true;
    }


    template <int dim>
    void
    MPMSolver<dim>::restore_state()
    {
      AssertThrow(saved_state.saved,
                  dealii::ExcMessage("MPMSolver::restore_state() without a "
                                     "preceding save_state()"));
      accounts                = saved_state.accounts;
      grid_kinetic_energy     = saved_state.grid_kinetic_energy;
      max_grid_speed          = saved_state.max_grid_speed;
      contact_force           = saved_state.contact_force;
      committed_grid_velocity = saved_state.grid_velocity;
      committed_stuck         = saved_state.stuck;
      p2g_current             = false;
      prepared                = false;
      solved                  = false;
    }


    template <int dim>
    std::vector<dealii::TrilinosWrappers::MPI::Vector>
    MPMSolver<dim>::committed_grid_vectors() const
    {
      const auto &owned    = grid.locally_owned_dofs;
      const auto &relevant = grid.locally_relevant_dofs;
      const auto  comm     = grid.mpi_communicator;
      std::vector<dealii::TrilinosWrappers::MPI::Vector> vectors(2);
      for (auto &v : vectors)
        v.reinit(owned, relevant, comm);
      if (committed_grid_velocity.size() == grid.dof_handler.n_dofs())
        vectors[0] = committed_grid_velocity;
      // only owned friction nodes read their committed state
      dealii::TrilinosWrappers::MPI::Vector stuck(owned, comm);
      for (unsigned int n = 0;
           n < std::min(friction_nodes.size(), committed_stuck.size());
           ++n)
        if (friction_nodes[n].owned && committed_stuck[n])
          stuck(friction_nodes[n].normal_dof) = 1.;
      stuck.compress(dealii::VectorOperation::insert);
      vectors[1] = stuck;
      return vectors;
    }


    template <int dim>
    void
    MPMSolver<dim>::set_committed_grid_vectors(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &vectors)
    {
      AssertThrow(vectors.size() == 2,
                  dealii::ExcMessage("set_committed_grid_vectors() needs the "
                                     "grid velocity and the stuck nodes"));
      committed_grid_velocity.reinit(grid.locally_owned_dofs,
                                     grid.locally_relevant_dofs,
                                     grid.mpi_communicator);
      committed_grid_velocity = vectors[0];
      committed_stuck.assign(friction_nodes.size(), false);
      for (unsigned int n = 0; n < friction_nodes.size(); ++n)
        if (friction_nodes[n].owned)
          committed_stuck[n] = vectors[1](friction_nodes[n].normal_dof) > 0.5;
      p2g_current = false;
      prepared    = false;
      solved      = false;
    }


    template <int dim>
    TruncationErrorNorms
    MPMSolver<dim>::truncation_error_norms() const
    {
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      // sums of m (a_{n+1} - a_n)^2, m du^2 and m over the owned dofs
      double sums[3] = {0., 0., 0.};
      if (!quasi_static)
        for (const auto i : grid.locally_owned_dofs)
          {
            const double m = nodal_mass(i);
            if (!(m > 0.))
              continue;
            const double du = displacement(i);
            const double an = acceleration_n(i);
            const double a  = newmark.acceleration(du, velocity_n(i), an, dt);
            sums[0] += m * (a - an) * (a - an);
            sums[1] += m * du * du;
            sums[2] += m;
          }
      dealii::Utilities::MPI::sum(sums, grid.mpi_communicator, sums);
      TruncationErrorNorms norms;
      if (sums[2] > 0.)
        {
          norms.acceleration_change = std::sqrt(sums[0] / sums[2]);
          norms.increment           = std::sqrt(sums[1] / sums[2]);
          norms.mass                = sums[2];
        }
      return norms;
    }


    template class MPMSolver<2>;
    template class MPMSolver<3>;
  } // namespace MPM
} // namespace Talus
