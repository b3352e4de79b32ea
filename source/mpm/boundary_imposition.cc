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
#include <set>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace MPM
  {
    using internal::read_tensor;

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
      // (contact forces that act with their end value are not in the
      // start acceleration: ContactTimeIntegration)
      for (const auto &b : boundary_points)
        if (!b.end_of_step)
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
        if (boundary_points[idx].end_of_step)
          return BoundaryForce();
        BoundaryPoint bp = boundary_points[idx];
        bp.du_bar        = tau2 * bp.a_bar;
        bp.gap_old       = 0.;
        bp.frozen        = frozen[idx];
        bp.lambda        = lambda_a[idx];
        dealii::Tensor<1, dim> a_b;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            const auto ci = fe.system_to_component_index(i);
            a_b[ci.first] +=
              bp.N[ci.second] * conforming_value(a_ghosted, c.dofs[i]);
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
      // boundaries whose particles act on the grid (not material-point
      // contact, the only kind with several velocity fields)
      bool particle_side = false;
      for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
        particle_side = particle_side ||
                        !boundary_particles->boundary(b).material_point_contact;
      Assert(!particle_side || grid.n_velocity_fields() == 1,
             dealii::ExcInternalError());
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        {
          if (!particle_side)
            break;
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
          // (a hanging node carries its masters' mass)
          for (const auto i : c.dofs)
            has_mass = has_mass || conforming_value(nodal_mass, i) > 0.;
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
              bp.weight      = props[BP::weight];
              bp.beta        = desc.beta;
              bp.mu          = desc.friction_coefficient;
              bp.condition   = desc.condition;
              bp.augmented   = desc.augmented || desc.lagrange_multiplier;
              bp.monolithic  = desc.lagrange_multiplier;
              bp.nitsche     = desc.nitsche;
              bp.theta       = desc.nitsche_theta;
              c.nitsche      = c.nitsche || desc.nitsche;
              bp.end_of_step = end_of_step_contact(desc);
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
          {
            // (the gradients for Nitsche's flux only)
            std::vector<double>                 values;
            std::vector<dealii::Tensor<1, dim>> gradients;
            append_q1_shapes(tria_cell, reference_points, values, gradients);
            for (unsigned int q = 0; q < n_kept; ++q)
              {
                auto &bp = boundary_points[c.first_boundary + q];
                bp.N.assign(values.begin() + q * n_nodes,
                            values.begin() + (q + 1) * n_nodes);
                if (bp.nitsche)
                  bp.dN.assign(gradients.begin() + q * n_nodes,
                               gradients.begin() + (q + 1) * n_nodes);
              }
          }
          // Nodes without mass are constrained to zero increments: in the
          // gap they stand for the boundary itself, so a point's prescribed
          // increment enters only with the share S of the nodes with mass,
          // g = g_old + sum_k N_k du_k - S du_bar. A rigid motion of the
          // massive nodes with the boundary then leaves the gap unchanged;
          // for a boundary at rest nothing changes.
          {
            // (a hanging node h moves with its masters j: its share is
            // that of its masters with mass, sum_j c_hj [m_j > 0])
            std::vector<bool>   massive(n_nodes);
            std::vector<double> share(n_nodes);
            for (unsigned int k = 0; k < n_nodes; ++k)
              {
                const auto dof =
                  c.dofs[grid.fe.component_to_system_index(0, k)];
                massive[k] = conforming_value(nodal_mass, dof) > 0.;
                share[k]   = mass_share(dof);
              }
            for (unsigned int q = 0; q < n_kept; ++q)
              {
                auto  &bp = boundary_points[c.first_boundary + q];
                double S  = 0.;
                for (unsigned int k = 0; k < n_nodes; ++k)
                  S += bp.N[k] * share[k];
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
      if (boundary_particles == nullptr)
        return;
      boundary_particles->clear_point_contact();
      const auto        &base    = grid.fe.base_element(0);
      const unsigned int n_nodes = base.dofs_per_cell;
      const double       h       = grid.is_cartesian ?
                                     *std::min_element(grid.cell_extent.begin_raw(),
                                           grid.cell_extent.end_raw()) :
                                     grid.minimal_cell_diameter;
      for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
        {
          const auto &desc = boundary_particles->boundary(b);
          if (!desc.material_point_contact)
            continue;
          AssertThrow(b < points.n_contact_slots(),
                      dealii::ExcMessage(
                        "MaterialPoints::set_contact_slots() must reserve "
                        "contact data for every boundary before generate()"));
          // every rank gets the whole surface of the boundary: positions,
          // normals and reference positions of its particles (gathered
          // once per step: the particles move only in commit_step())
          if (contact_surfaces.size() != boundary_particles->n_boundaries())
            contact_surfaces.assign(boundary_particles->n_boundaries(), {});
          ContactSurface &surface = contact_surfaces[b];
          if (!updating_boundaries)
            surface = boundary_particles->gather_surface(b);
          const auto &x_b  = surface.x;
          const auto &n_b  = surface.n;
          const auto &X_b  = surface.X;
          const auto &id_b = surface.id;
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
                  auto       particle = particles[mc.first + q];
                  auto       props    = particle->get_properties();
                  const auto x_p      = particle->get_location();
                  const dealii::Tensor<2, dim> F =
                    read_tensor<dim>(props, MP::deformation);
                  const double l0 =
                    std::pow(props[MP::initial_volume], 1. / dim);
                  // the circle (sphere) of the point's current volume: a
                  // rotation leaves it unchanged, and so does plastic flow
                  // at constant volume, whose F may be far from a rotation;
                  // with the point: of its initial volume (a rigid offset,
                  // so that the gap is not measured anew)
                  const double r =
                    desc.contact_point_with_point ?
                      0.5 * l0 :
                      0.5 * l0 * std::pow(dealii::determinant(F), 1. / dim);
                  // The surface is the tangent line (plane) of the nearest
                  // boundary particle j0, or, on a boundary at rest at a
                  // concave corner, of a
                  // neighbour k whose particle lies on the material side of
                  // j0's tangent (the surface turns towards the material)
                  // if the point is deeper below k's tangent: the gap is
                  // then the smallest over the faces that bound the point,
                  // continuous across the corner (the nearest particle alone
                  // switches between faces with a jump of the gap).
                  std::vector<unsigned int> nearest;
                  tree.query(boost::geometry::index::nearest(x_p, 1),
                             std::back_inserter(nearest));
                  unsigned int j = nearest[0];
                  // The further faces are looked for only where one can be
                  // within reach: a face within reach has a particle at
                  // most reach + r + s/2 away (s the particles' spacing,
                  // below h), so the nearest face's gap is at most reach +
                  // h. (A moving surface, a net or string, keeps the
                  // nearest particle's tangent: its kinks follow the
                  // load.)
                  dealii::Tensor<1, dim> v;
                  for (unsigned int d = 0; d < dim; ++d)
                    v[d] = props[MP::velocity + d];
                  const double reach_at_rest =
                    initializing ? 1e-6 * h :
                                   0.5 * h + 2. * dt * v.norm() +
                                     dt * dt * gravity_vector.norm();
                  if (!desc.moving &&
                      (x_p - r * n_b[j] - x_b[j]) * n_b[j] <= reach_at_rest + h)
                    {
                      nearest.clear();
                      tree.query(boost::geometry::index::nearest(
                                   x_p, dim == 2 ? 8u : 16u),
                                 std::back_inserter(nearest));
                      for (const unsigned int k : nearest)
                        if ((x_b[k] - x_p).norm_square() <
                            (x_b[j] - x_p).norm_square())
                          j = k;
                    }
                  {
                    const unsigned int j0 = j;
                    double g_min = (x_p - r * n_b[j0] - x_b[j0]) * n_b[j0];
                    for (const unsigned int k : nearest)
                      if (k != j0 && (x_b[k] - x_b[j0]) * n_b[j0] >
                                       1e-9 * (x_b[k] - x_b[j0]).norm())
                        {
                          const double g_k =
                            (x_p - r * n_b[k] - x_b[k]) * n_b[k];
                          if (g_k < g_min)
                            {
                              g_min = g_k;
                              j     = k;
                            }
                        }
                  }
                  const dealii::Tensor<1, dim> &n   = n_b[j];
                  const dealii::Point<dim>      x_c = x_p - r * n;
                  // an extent that overlaps the boundary at the start is
                  // measured from its initial depth on (contact offset)
                  if (initializing && (x_c - x_b[j]) * n < 0.)
                    props[points.contact_offset_index(b)] =
                      -((x_c - x_b[j]) * n);
                  const double offset = props[points.contact_offset_index(b)];
                  const double g0     = (x_c - x_b[j]) * n + offset;
                  // the surface's own increment in the step (a moving or
                  // coupled boundary) at the particle jf
                  const auto surface_increment = [&](const unsigned int jf) {
                    dealii::Tensor<1, dim> du_bar;
                    if (!initializing && desc.moving)
                      du_bar =
                        boundary_particles->prescribed_displacement(b,
                                                                    X_b[jf],
                                                                    time) -
                        boundary_particles->prescribed_displacement(b,
                                                                    X_b[jf],
                                                                    time - dt);
                    return du_bar;
                  };
                  // out of reach in this step: forget the stick spring
                  const double reach =
                    initializing ?
                      reach_at_rest :
                      reach_at_rest + std::max(0., surface_increment(j) * n);
                  if (g0 > reach)
                    {
                      for (unsigned int d = 0; d < dim; ++d)
                        props[points.contact_gap_index(b) + d] = 0.;
                      continue;
                    }
                  // One contact per face: the nearest face (above), and at
                  // a concave corner every other face within reach whose
                  // normal turns by more than 10 degrees (one particle per
                  // such face, the one with the smallest gap), so that the
                  // point meets the next face within the step it crosses
                  // the corner instead of passing below it along the
                  // tangent of the first (and being pushed out with the
                  // energy of a deep penetration in the next step). Only
                  // the nearest face keeps the tangential stick spring.
                  std::vector<std::pair<unsigned int, double>> faces = {
                    {j, g0}};
                  for (const unsigned int k : nearest)
                    if (k != j && n_b[k] * n < std::cos(10. * M_PI / 180.) &&
                        (x_b[k] - x_b[j]) * n > 0.)
                      {
                        const double g_k =
                          (x_p - r * n_b[k] - x_b[k]) * n_b[k] + offset;
                        if (g_k > reach)
                          continue;
                        bool same_face = false;
                        for (auto &f : faces)
                          if (n_b[f.first] * n_b[k] >=
                              std::cos(10. * M_PI / 180.))
                            {
                              same_face = true;
                              if (f.first != j && g_k < f.second)
                                f = {k, g_k};
                            }
                        if (!same_face)
                          faces.emplace_back(k, g_k);
                      }
                  for (const auto &face : faces)
                    {
                      const unsigned int            jf      = face.first;
                      const bool                    primary = jf == j;
                      const dealii::Tensor<1, dim> &n_f     = n_b[jf];
                      const dealii::Point<dim>      x_cf    = x_p - r * n_f;
                      dealii::Tensor<1, dim>        g_t;
                      if (primary)
                        {
                          for (unsigned int d = 0; d < dim; ++d)
                            g_t[d] = props[points.contact_gap_index(b) + d];
                          g_t -= (g_t * n_f) * n_f;
                        }
                      BoundaryPoint bp;
                      bp.particle          = particle;
                      bp.on_material_point = true;
                      bp.primary           = primary;
                      bp.surface_particle  = id_b[jf];
                      bp.boundary          = b;
                      bp.weight =
                        std::pow(props[MP::initial_volume], (dim - 1.) / dim);
                      bp.beta          = desc.beta;
                      bp.mu            = desc.friction_coefficient;
                      bp.condition     = desc.condition;
                      bp.damping       = desc.contact_damping;
                      bp.damping_onset = 1e-2 * h;
                      bp.end_of_step   = end_of_step_contact(desc);
                      bp.normal        = n_f;
                      bp.gap_old       = face.second * n_f + g_t;
                      bp.du_bar        = surface_increment(jf);
                      bp.a_bar         = 0.;
                      if (initializing && desc.moving)
                        {
                          const double eps = 1e-4; // [s], as for the particles
                          bp.a_bar =
                            (boundary_particles->prescribed_displacement(
                               b, X_b[jf], time) -
                             2. * boundary_particles->prescribed_displacement(
                                    b, X_b[jf], time + eps) +
                             boundary_particles->prescribed_displacement(
                               b, X_b[jf], time + 2. * eps)) /
                            (eps * eps);
                        }
                      // shape values of the point's cell at x_c (with the
                      // point: at the point's own location)
                      dealii::Point<dim> xi =
                        particle->get_reference_location();
                      // (the extent of the point's cell: that of the finest
                      // level, doubled per level above it)
                      if (desc.contact_point_with_point)
                        ;
                      else if (grid.is_cartesian)
                        for (unsigned int d = 0; d < dim; ++d)
                          xi[d] += (x_cf[d] - x_p[d]) /
                                   std::ldexp(grid.cell_extent[d],
                                              grid.cell_extent_level -
                                                mc.cell->level());
                      else
                        {
                          try
                            {
                              xi = grid.mapping.transform_real_to_unit_cell(
                                typename dealii::Triangulation<
                                  dim>::active_cell_iterator(mc.cell),
                                x_cf);
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
                }
              c.n_boundary = boundary_points.size() - c.first_boundary;
              if (c.n_boundary > 0)
                {
                  // only for cells with candidates; the Q1 dofs of the
                  // point's cell also with uGIMP (whose material cells
                  // carry the patch's)
                  c.dofs.resize(grid.fe.dofs_per_cell);
                  c.field = mc.field;
                  if (grid.n_velocity_fields() == 1)
                    mc.cell->get_dof_indices(c.dofs);
                  else
                    {
                      // the point's own body's field
                      const auto &system = grid.system_fe();
                      std::vector<dealii::types::global_dof_index> all(
                        system.dofs_per_cell);
                      mc.cell->get_dof_indices(all);
                      for (unsigned int i = 0; i < c.dofs.size(); ++i)
                        {
                          const auto ci = internal::component_and_node<dim>(i);
                          c.dofs[i]     = all[system.component_to_system_index(
                            mc.field * dim + ci.first, ci.second)];
                        }
                    }
                  boundary_cells.push_back(std::move(c));
                }
            }
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
                du_b[ci.first] +=
                  bp.N[ci.second] * conforming_value(displacement, c.dofs[i]);
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
    void
    MPMSolver<dim>::evaluate_boundary_trial()
    {
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      boundary_trial.clear();
      point_contact_trial.clear();
      boundary_trial_work.assign(accounts.boundary_friction_dissipation.size(),
                                 0.);
      {
        std::vector<double> work(boundary_trial_work.size(), 0.);
        // per-particle traction, force and gap at commit (debugging)
        const bool debug_boundary = std::getenv("TALUS_DEBUG_NITSCHE");
        const bool debug_point_contact =
          std::getenv("TALUS_DEBUG_POINT_CONTACT");
        std::vector<dealii::Tensor<1, dim>> dT(dofs_per_cell);
        std::vector<double>                 du_local(dofs_per_cell);
        for (const auto &c : boundary_cells)
          {
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              du_local[i] = conforming_value(displacement, c.dofs[i]);
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
                            << " lambda.n " << bp.lambda * bp.normal << " f.n "
                            << bf.force * bp.normal << " g.n "
                            << bf.gap * bp.normal << std::endl;
                // The part of the force on nodes without mass (constrained)
                // does not act on the material: report the rest.
                double active_share = 0.;
                for (unsigned int k = 0; k < n_nodes; ++k)
                  active_share +=
                    bp.N[k] *
                    mass_share(c.dofs[fe.component_to_system_index(0, k)]);
                // dissipated: -f . (relative increment - elastic gap change)
                const dealii::Tensor<1, dim> relative = du_b - bp.du_bar;
                if (bp.end_of_step)
                  {
                    // the force acts with its end value over the step
                    // (ContactTimeIntegration): its work -f . du less the
                    // change of the springs' energy k |g|^2 / 2 that the
                    // spring_energy column holds (active points only)
                    const double k = bp.beta * bp.weight;
                    const bool   was_active =
                      bp.on_material_point ?
                          bp.gap_old * bp.normal < 0. :
                          bp.particle->get_properties()
                            [Boundaries::BoundaryParticleProperties<
                              dim>::state] != 0.;
                    const double spring_new =
                      bf.state != 0 ? 0.5 * k * (bf.gap * bf.gap) : 0.;
                    const double spring_old =
                      was_active ? 0.5 * k * (bp.gap_old * bp.gap_old) : 0.;
                    work[bp.boundary] -=
                      bf.force * relative + (spring_new - spring_old);
                  }
                else if (start_force_recorded && !bp.on_material_point &&
                         !bp.augmented && !bp.nitsche && bp.damping == 0. &&
                         !boundary_particles->boundary(bp.boundary).moving)
                  {
                    // a penalty boundary at rest, with the integrator's
                    // account started from the forces at du = 0 (no
                    // boundary moves, record_start_force()): what
                    // Newmark's energy identity sees, the trapezoidal
                    // work of the force on the material -(f(0) + f(du)) .
                    // du / 2 (f(0) is in that residual), less the change
                    // of the springs' energy k |g|^2
                    // / 2 that the spring_energy column holds (active
                    // points only). In stick this is -f . (du - dg); in
                    // slip it also books the change of the force within
                    // the step, which the end force alone misses.
                    const double        k = bp.beta * bp.weight;
                    const BoundaryForce start =
                      boundary_force(bp, dealii::Tensor<1, dim>());
                    const double state_old =
                      bp.particle->get_properties()
                        [Boundaries::BoundaryParticleProperties<dim>::state];
                    const double spring_new =
                      bf.state != 0 ? 0.5 * k * (bf.gap * bf.gap) : 0.;
                    const double spring_old =
                      state_old != 0. ? 0.5 * k * (bp.gap_old * bp.gap_old) :
                                        0.;
                    work[bp.boundary] -=
                      0.5 * (start.force + bf.force) * relative +
                      (spring_new - spring_old);
                  }
                else
                  work[bp.boundary] -=
                    bf.force * (relative - (bf.gap - bp.gap_old));
                // a merged (cell-wise) point shares its gap, state and,
                // by weight, its reaction among its particles
                // the multiplier the next step starts from reproduces this
                // force at zero increment: lambda - k g = f
                const dealii::Tensor<1, dim> lambda =
                  bp.augmented ? bf.force + bp.beta * bp.weight * bf.gap :
                                 dealii::Tensor<1, dim>();
                const auto write = [&](auto particle, const double share) {
                  boundary_trial.push_back({particle,
                                            bf.gap,
                                            share * lambda,
                                            -share * active_share * bf.force,
                                            bf.state});
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
                    PointContactTrial pc;
                    pc.point    = bp.particle;
                    pc.boundary = bp.boundary;
                    pc.tangential_gap =
                      bf.state == 0 ? dealii::Tensor<1, dim>() :
                                      bf.gap - (bf.gap * bp.normal) * bp.normal;
                    pc.active  = bf.state != 0;
                    pc.primary = bp.primary;
                    if (bf.state != 0)
                      {
                        // the dashpot's work on the normal increment (in
                        // -f . du already with the end-of-step force)
                        const double dgn = (du_b - bp.du_bar) * bp.normal;
                        if (!bp.end_of_step)
                          work[bp.boundary] +=
                            bp.damping * bp.beta * bp.weight * dgn * dgn;
                        pc.reaction    = -bf.force;
                        pc.normal      = bp.normal;
                        pc.penetration = std::max(0., -(bf.gap * bp.normal));
                        pc.surface_particle = bp.surface_particle;
                        pc.spring_energy =
                          0.5 * bp.beta * bp.weight * (bf.gap * bf.gap);
                      }
                    point_contact_trial.push_back(pc);
                  }
                else if (bp.members.empty())
                  write(bp.particle, 1.);
                else
                  for (unsigned int m = 0; m < bp.members.size(); ++m)
                    write(bp.members[m], bp.member_weights[m] / bp.weight);
              }
          }
        if (!work.empty())
          dealii::Utilities::MPI::sum(work,
                                      grid.mpi_communicator,
                                      boundary_trial_work);
      }
    }


    template <int dim>
    void
    MPMSolver<dim>::commit_boundary_trial()
    {
      using BP = Boundaries::BoundaryParticleProperties<dim>;
      using MP = MaterialPointProperties<dim>;
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
      for (const auto &t : boundary_trial)
        {
          auto particle = t.particle;
          auto props    = particle->get_properties();
          for (unsigned int d = 0; d < dim; ++d)
            {
              props[BP::gap + d]        = t.gap[d];
              props[BP::multiplier + d] = t.multiplier[d];
              props[BP::reaction + d]   = t.reaction[d];
            }
          props[BP::state] = t.state;
        }
      for (const auto &pc : point_contact_trial)
        {
          auto point = pc.point;
          auto props = point->get_properties();
          if (pc.primary)
            for (unsigned int d = 0; d < dim; ++d)
              props[points.contact_gap_index(pc.boundary) + d] =
                pc.tangential_gap[d];
          if (pc.active)
            boundary_particles->record_point_contact(pc.boundary,
                                                     pc.reaction,
                                                     pc.normal,
                                                     pc.penetration,
                                                     pc.spring_energy);
        }
      // material-point contact: the reactions booked on the boundary
      // particles the points touch (boundary_reactions()), written into
      // their `reaction` property wherever they live (their `state` stays
      // 0: the boundary's resultant counts the points' records)
      if (dealii::Utilities::MPI::logical_or(!point_contact_trial.empty(),
                                             grid.mpi_communicator))
        {
          std::map<dealii::types::particle_index, dealii::Tensor<1, dim>>
            booked;
          for (const auto &part :
               dealii::Utilities::MPI::all_gather(grid.mpi_communicator,
                                                  point_contact_reactions()))
            for (const auto &[id, f] : part)
              booked[id] += f;
          for (auto &p : boundary_particles->particle_handler())
            {
              const auto it = booked.find(p.get_id());
              if (it == booked.end())
                continue;
              auto props = p.get_properties();
              for (unsigned int d = 0; d < dim; ++d)
                props[BP::reaction + d] = it->second[d];
            }
        }
      for (unsigned int b = 0; b < boundary_trial_work.size(); ++b)
        {
          accounts.friction_dissipation += boundary_trial_work[b];
          accounts.boundary_friction_dissipation[b] += boundary_trial_work[b];
        }
      boundary_trial.clear();
      point_contact_trial.clear();
      boundary_trial_work.assign(boundary_trial_work.size(), 0.);
      boundary_points.clear();
    }


    template <int dim>
    std::vector<
      std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>
    MPMSolver<dim>::boundary_reactions() const
    {
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      std::vector<
        std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>
        r;
      r.reserve(boundary_trial.size());
      for (const auto &t : boundary_trial)
        r.emplace_back(t.particle->get_id(), t.reaction);
      const auto booked = point_contact_reactions();
      r.insert(r.end(), booked.begin(), booked.end());
      return r;
    }


    template <int dim>
    std::vector<
      std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>
    MPMSolver<dim>::point_contact_reactions() const
    {
      // each pressed point's reaction on the boundary particle it touches,
      // summed per particle over this rank's points
      std::map<dealii::types::particle_index, dealii::Tensor<1, dim>> sum;
      for (const auto &pc : point_contact_trial)
        if (pc.active)
          sum[pc.surface_particle] += pc.reaction;
      return {sum.begin(), sum.end()};
    }


    template <int dim>
    std::pair<dealii::Tensor<1, dim>, dealii::Tensor<1, dim>>
    MPMSolver<dim>::boundary_force_balance() const
    {
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      const auto        &fe            = grid.fe;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const MPI_Comm     comm          = grid.mpi_communicator;
      // the particles' forces on the grid nodes, condensed by deal.II
      dealii::TrilinosWrappers::MPI::Vector on_grid(grid.locally_owned_dofs,
                                                    comm);
      dealii::Vector<double>                local(dofs_per_cell);
      std::vector<double>                   du_local(dofs_per_cell);
      for (const auto &c : boundary_cells)
        {
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            du_local[i] = conforming_value(displacement, c.dofs[i]);
          local = 0.;
          for (unsigned int b = 0; b < c.n_boundary; ++b)
            {
              const BoundaryPoint &bp = boundary_points[c.first_boundary + b];
              AssertThrow(!(bp.nitsche && bp.with_stress),
                          dealii::ExcMessage(
                            "the boundary force balance is not available for "
                            "Nitsche boundaries"));
              dealii::Tensor<1, dim> du_b;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  du_b[ci.first] += bp.N[ci.second] * du_local[i];
                }
              const BoundaryForce bf = boundary_force(bp, du_b);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  local[i] += bp.N[ci.second] * bf.force[ci.first];
                }
            }
          hanging_constraints.distribute_local_to_global(local,
                                                         c.dofs,
                                                         on_grid);
        }
      on_grid.compress(dealii::VectorOperation::add);
      // summed by component over the owned nodes that carry mass
      const auto                               &forces = on_grid;
      std::set<dealii::types::global_dof_index> counted;
      dealii::Tensor<1, dim>                    grid_sum, reaction_sum;
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < dim; ++d)
              {
                const auto i = cell->vertex_dof_index(v, d);
                if (grid.locally_owned_dofs.is_element(i) &&
                    nodal_mass(i) > 0. && counted.insert(i).second)
                  grid_sum[d] += forces(i);
              }
      for (const auto &t : boundary_trial)
        reaction_sum += t.reaction;
      for (const auto &pc : point_contact_trial)
        if (pc.active)
          reaction_sum += pc.reaction;
      return {dealii::Utilities::MPI::sum(grid_sum, comm),
              dealii::Utilities::MPI::sum(reaction_sum, comm)};
    }


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                                 \
  template void MPMSolver<dim>::evaluate_boundary_trial();                     \
  template void MPMSolver<dim>::commit_boundary_trial();                       \
  template std::pair<dealii::Tensor<1, dim>, dealii::Tensor<1, dim>>           \
  MPMSolver<dim>::boundary_force_balance() const;                              \
  template std::vector<                                                        \
    std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>          \
  MPMSolver<dim>::boundary_reactions() const;                                  \
  template std::vector<                                                        \
    std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>          \
                MPMSolver<dim>::point_contact_reactions() const;               \
  template void MPMSolver<dim>::initial_acceleration_with_boundaries(          \
    dealii::TrilinosWrappers::MPI::Vector &a);                                 \
  template void MPMSolver<dim>::cache_boundary_particles();                    \
  template void MPMSolver<dim>::cache_point_contacts();                        \
  template void MPMSolver<dim>::boundary_traction(                             \
    const BoundaryPoint                 &b,                                    \
    const std::vector<double>           &du_local,                             \
    dealii::Tensor<1, dim>              &T,                                    \
    std::vector<dealii::Tensor<1, dim>> &dT) const;                            \
  template double                        MPMSolver<dim>::update_multipliers(); \
  template MPMSolver<dim>::BoundaryForce MPMSolver<dim>::boundary_force(       \
    const BoundaryPoint &b, const dealii::Tensor<1, dim> &du) const;

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
