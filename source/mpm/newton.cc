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
    template <int dim>
    void
    MPMSolver<dim>::newton_solve(dealii::TrilinosWrappers::MPI::Vector &du,
                                 const double  f_ext_norm,
                                 double       &reference,
                                 NewtonResult &result)
    {
      // The preconditioner of the last Newton solve fits this one's first
      // tangent only in a coupling iteration that kept it (the interface
      // moved a little, the sparsity pattern stayed,
      // make_step_sparsity_pattern()), and only while the boundary points'
      // contact states are those it was built with.
      if (!preconditioner_kept_for_window)
        assembled_states.clear();
      preconditioner_kept_for_window = false;
      for (auto &bp : boundary_points)
        {
          bp.last_state = -1;
          bp.switches   = 0;
          if (bp.monolithic)
            bp.frozen = -1;
        }
      contact_targets.clear();
      linear_forcing.start();
      contact_jump_active   = false;
      displacement          = du;
      double last_increment = 0.;
      // the residual norm at which the last correction was computed
      double residual_at_correction = 0.;
      // the residual's contraction over the last correction (negative
      // before the first)
      double contraction = -1.;
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
      // The trial was assembled without the matrix, because the full
      // correction was predicted to converge (line search below).
      bool residual_at_iterate = false;
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
          // the residual-only trial's iterate still needs the matrix
          // before its correction (below), unless it converges
          bool matrix_pending = false;
          if (assembled_at_iterate)
            {
              assembled_at_iterate = false;
              ok                   = true;
            }
          else if (residual_at_iterate &&
                   residual.l2_norm() <=
                     std::max(residual_tolerance * reference,
                              absolute_residual_tolerance))
            {
              residual_at_iterate = false;
              matrix_pending      = true;
              ok                  = true;
            }
          else
            {
              residual_at_iterate = false;
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
            {
              reference = std::max(r, f_ext_norm);
              record_start_force();
            }
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
                              bp.N[ci.second] *
                              conforming_value(displacement, c.dofs[i]);
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

          if (matrix_pending)
            {
              // the prediction missed: the matrix at the same iterate
              // (the return-branch changes it records are reset with the
              // correction below, so a miss does not extend the iteration
              // by 'maximum Newton iterations with state changes')
              dealii::TimerOutput::Scope s(timer, "assembly");
              if (!assemble(displacement, true, !quasi_static, failure))
                {
                  result.failure = failure;
                  return;
                }
            }
          unsigned int n_linear = 0;
          contraction =
            residual_at_correction > 0. ? r / residual_at_correction : -1.;
          residual_at_correction = r;
          // inexact Newton: solve loosely while far from the solution
          const double krylov_tolerance =
            linear_forcing.enabled() ?
              linear_forcing.next(r,
                                  std::max(residual_tolerance * reference,
                                           absolute_residual_tolerance),
                                  linear_tolerance) :
              linear_tolerance;
          try
            {
              n_linear = solve_linear(increment, krylov_tolerance);
            }
          catch (const dealii::SolverControl::NoConvergence &e)
            {
              // one line, not deal.II's page of advice
              std::ostringstream msg;
              msg << "the linear solver (" << linear_solver_type
                  << ") did not converge in " << e.last_step
                  << " iterations (residual " << e.last_residual
                  << "; 'maximum linear iterations', 'linear solver "
                     "tolerance' in subsection Solver, or 'linear solver = "
                     "direct')";
              result.failure = msg.str();
              return;
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
              // The full correction is predicted to meet the residual
              // tolerance if it contracts the residual as much as the last
              // one did (Newton converges faster than that): its matrix
              // would not be needed, so the trial assembles the residual
              // only. A wrong prediction costs that residual assembly
              // again with the matrix at the top of the loop.
              const bool convergence_predicted =
                contraction >= 0. && contraction < 1. &&
                r * contraction <= std::max(residual_tolerance * reference,
                                            absolute_residual_tolerance);
              if (convergence_predicted && std::getenv("TALUS_DEBUG_NEWTON"))
                std::cerr << "    convergence predicted: residual-only trial"
                          << std::endl;
              for (unsigned int k = 0; k < max_line_search; ++k)
                {
                  const bool with_matrix = k == 0 && full_step_accepted &&
                                           boundary_particles == nullptr &&
                                           !convergence_predicted;
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
                      residual_at_iterate =
                        !with_matrix && boundary_particles == nullptr;
                      any_accepted = true;
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
    NewtonResult
    MPMSolver<dim>::solve_step()
    {
      dealii::TimerOutput::Scope scope(timer, "solve (Newton)");
      Assert(prepared, dealii::ExcMessage("prepare_step() first"));
      const NewtonResult result = solve_increment();
      if (result.converged)
        last_increment = displacement;
      if (result.converged && boundary_particles != nullptr)
        evaluate_boundary_trial();
      return result;
    }


    template <int dim>
    void
    MPMSolver<dim>::record_start_force()
    {
      start_force_recorded = false;
      if (quasi_static || consistent_mass)
        return;
      // A moving boundary of particles (a prescribed motion, a coupling
      // interface) has moved to its end-of-step position in the residual
      // at du = 0: its penalty force there is not the force at the start
      // of the step, so the start acceleration's work is not booked.
      if (boundary_particles != nullptr)
        for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
          if (boundary_particles->boundary(b).moving)
            return;
      // (without the contact forces that act with their end value: the
      // start acceleration a_n does not hold them)
      dealii::TrilinosWrappers::MPI::Vector f_c;
      const bool end_contact = uses_end_contact_force();
      if (end_contact)
        end_contact_force(nullptr, f_c);
      const double s = end_contact_factor();
      start_force.reinit(grid.locally_owned_dofs, grid.mpi_communicator);
      for (const auto i : grid.locally_owned_dofs)
        if (!constraints.is_constrained(i) && nodal_mass(i) > 0.)
          start_force(i) =
            residual(i) - (end_contact ? s * f_c(i) : 0.) +
            nodal_mass(i) *
              newmark.acceleration(0., velocity_n(i), acceleration_n(i), dt);
      start_force.compress(dealii::VectorOperation::insert);
      start_force_recorded = true;
    }


    template <int dim>
    NewtonResult
    MPMSolver<dim>::solve_increment()
    {
      NewtonResult result;

      dealii::TrilinosWrappers::MPI::Vector du(grid.locally_owned_dofs,
                                               grid.mpi_communicator);
      displacement = du;
      if (start_acceleration_from_forces && !quasi_static)
        {
          // a_n = (f_ext - f_int(u_n)) / m_I at the free nodes with mass
          // (the residual without inertia at du = 0; zero at the
          // constrained nodes, as prepare_step() left them)
          std::string failure;
          {
            dealii::TimerOutput::Scope s(timer, "assembly");
            if (!assemble(displacement, false, false, failure))
              {
                result.failure = failure;
                return result;
              }
          }
          dealii::TrilinosWrappers::MPI::Vector a(grid.locally_owned_dofs,
                                                  grid.mpi_communicator);
          // (without the contact forces that act with their end value)
          dealii::TrilinosWrappers::MPI::Vector f_c;
          const bool end_contact = uses_end_contact_force();
          if (end_contact)
            end_contact_force(nullptr, f_c);
          const double s = end_contact_factor();
          // With the end-of-step contact force, nodes lighter than a
          // fraction of the heaviest keep the projected acceleration: the
          // internal force of a point at the edge of a node's support does
          // not vanish with its shape value, so f/m_I grows without bound
          // as m_I -> 0 (ContactTimeIntegration::light_node_fraction)
          double light = 0.;
          if (end_contact)
            {
              for (const auto i : grid.locally_owned_dofs)
                light = std::max(light, static_cast<double>(nodal_mass(i)));
              light = ContactTimeIntegration::light_node_fraction *
                      dealii::Utilities::MPI::max(light, grid.mpi_communicator);
            }
          // Nodes of cells with boundary points whose force keeps
          // Newmark's trapezoidal rule keep the projected acceleration as
          // well: there the residual at du = 0 holds neither the friction
          // force (it starts unloaded in every step) nor the force of the
          // other penalties that balances the points' projected
          // acceleration (doc/theory.md, "Contact force in time")
          dealii::TrilinosWrappers::MPI::Vector trapezoidal;
          if (boundary_particles != nullptr)
            {
              trapezoidal.reinit(grid.locally_owned_dofs,
                                 grid.mpi_communicator);
              for (const auto &c : boundary_cells)
                {
                  bool any = false;
                  for (unsigned int b = 0; b < c.n_boundary; ++b)
                    any =
                      any || !boundary_points[c.first_boundary + b].end_of_step;
                  if (!any)
                    continue;
                  dealii::Vector<double> ones(c.dofs.size());
                  ones = 1.;
                  constraints.distribute_local_to_global(ones,
                                                         c.dofs,
                                                         trapezoidal);
                }
              trapezoidal.compress(dealii::VectorOperation::add);
            }
          for (const auto i : grid.locally_owned_dofs)
            if (!constraints.is_constrained(i) && nodal_mass(i) > 0.)
              a(i) = nodal_mass(i) < light ||
                         (trapezoidal.size() > 0 && trapezoidal(i) > 0.) ?
                       acceleration_n(i) :
                       (residual(i) - (end_contact ? s * f_c(i) : 0.)) /
                         nodal_mass(i);
          a.compress(dealii::VectorOperation::insert);
          acceleration_n = a;
        }
      const double f_ext_norm = external_force.l2_norm();
      double       reference  = 0.;
      const bool   warm = warm_start && last_increment.size() == du.size();
      const bool   newmark_predictor =
        predictor == "constant acceleration" ||
        (predictor == "automatic" && boundary_particles == nullptr &&
         !start_acceleration_from_forces);
      if (warm || (newmark_predictor && !quasi_static))
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
          record_start_force();
          // du = dt v_n + dt^2/2 a_n at the free nodes with mass; v_n and
          // a_n are zero at the constrained ones (prepare_step()).
          for (const auto i : grid.locally_owned_dofs)
            if (!constraints.is_constrained(i) && nodal_mass(i) > 0.)
              du(i) = warm ?
                        last_increment(i) :
                        dt * velocity_n(i) + 0.5 * dt * dt * acceleration_n(i);
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


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                 \
  template NewtonResult MPMSolver<dim>::solve_step();          \
  template NewtonResult MPMSolver<dim>::solve_increment();     \
  template void         MPMSolver<dim>::newton_solve(          \
    dealii::TrilinosWrappers::MPI::Vector &du,         \
    const double                           f_ext_norm, \
    double                                &reference,  \
    NewtonResult                          &result);                             \
  template void MPMSolver<dim>::record_start_force();

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
