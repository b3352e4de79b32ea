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
      const unsigned int n_fields = grid.n_velocity_fields();
      // uGIMP, cpGIMP, CPDI: the node patch of an owned cell reaches the
      // vertices of its ghost neighbours, whose friction nodes its rows
      // combine too
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() || (gimp && cell->is_ghost()))
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
              // (multi-velocity field: one friction node per body's field
              // at each vertex, each with its own contact state)
              for (const unsigned int v : face->vertex_indices())
                for (unsigned int field = 0; field < n_fields; ++field)
                  {
                    Candidate &cand =
                      candidates[face->vertex_dof_index(v, field * dim)];
                    for (unsigned int d = 0; d < dim; ++d)
                      cand.dofs[d] = face->vertex_dof_index(v, field * dim + d);
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
          // a hanging vertex on the boundary (3D: the middle of a coarse
          // cell's boundary edge) moves with its masters, whose friction
          // nodes hold it
          if (has_hanging_nodes &&
              hanging_constraints.is_constrained(cand.dofs[axis]))
            continue;
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
      // Cells with a hanging node whose masters include a friction node
      // (a node next to a coarser cell): their rows reach the friction
      // node through the hanging constraint.
      if (has_hanging_nodes && !friction_nodes.empty())
        {
          std::vector<dealii::types::global_dof_index> dofs(
            grid.system_fe().dofs_per_cell);
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                cell->get_dof_indices(dofs);
                for (const auto i : dofs)
                  if (hanging_constraints.is_constrained(i))
                    for (const auto &e :
                         *hanging_constraints.get_constraint_entries(i))
                      if (friction_node_of.count(e.first))
                        cell_touches_friction[cell->active_cell_index()] = true;
              }
        }
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
      if (committed_stuck.size() != friction_nodes.size())
        committed_stuck.assign(friction_nodes.size(), false);
      for (unsigned int n = 0; n < friction_nodes.size(); ++n)
        if (auto &fn = friction_nodes[n]; fn.owned)
          {
            // the state the last committed step ended in (free before the
            // first), not that of a rejected attempt
            const bool was_stuck = committed_stuck[n];
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
    void
    MPMSolver<dim>::commit_friction_states()
    {
      committed_stuck.resize(friction_nodes.size());
      for (unsigned int n = 0; n < friction_nodes.size(); ++n)
        committed_stuck[n] = friction_nodes[n].state == ContactState::stick;
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


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                         \
  template void   MPMSolver<dim>::setup_friction_nodes();              \
  template double MPMSolver<dim>::new_velocity(                        \
    const dealii::types::global_dof_index i, const double du_i) const; \
  template double MPMSolver<dim>::resting_increment(                   \
    const dealii::types::global_dof_index i) const;                    \
  template void         MPMSolver<dim>::exchange_friction_states();    \
  template void         MPMSolver<dim>::apply_impact_friction();       \
  template void         MPMSolver<dim>::initialize_friction_states();  \
  template void         MPMSolver<dim>::commit_friction_states();      \
  template unsigned int MPMSolver<dim>::update_friction_states(        \
    dealii::TrilinosWrappers::MPI::Vector &du);

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
