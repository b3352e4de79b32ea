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

      std::vector<typename dealii::Particles::ParticleIterator<dim>> in_cell;
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const typename dealii::Triangulation<dim>::active_cell_iterator
                               tria_cell(cell);
            const unsigned int n = handler.n_particles_in_cell(tria_cell);
            if (n == 0)
              continue;
            if (multi_field)
              {
                cache_cell_per_body(cell);
                continue;
              }
            CellCache c;
            c.cell  = cell;
            c.first = particles.size();
            c.n     = n;
            if (!gimp)
              {
                c.dofs.resize(fe.dofs_per_cell);
                cell->get_dof_indices(c.dofs);
              }
            in_cell.clear();
            for (auto p = handler.particles_in_cell(tria_cell).begin();
                 p != handler.particles_in_cell(tria_cell).end();
                 ++p)
              in_cell.push_back(p);
            append_cell_cache(in_cell, c);
          }
      (void)Properties::mass;
    }


    template <int dim>
    void
    MPMSolver<dim>::cache_cell_per_body(
      const typename dealii::DoFHandler<dim>::active_cell_iterator &cell)
    {
      auto       &handler = points.particle_handler();
      const auto &system  = grid.system_fe();
      const typename dealii::Triangulation<dim>::active_cell_iterator tria_cell(
        cell);
      std::vector<dealii::types::global_dof_index> all(system.dofs_per_cell);
      cell->get_dof_indices(all);
      for (unsigned int b = 0; b < grid.n_velocity_fields(); ++b)
        {
          std::vector<typename dealii::Particles::ParticleIterator<dim>> mine;
          for (auto p = handler.particles_in_cell(tria_cell).begin();
               p != handler.particles_in_cell(tria_cell).end();
               ++p)
            if (points.body_of(p->get_properties()) == b)
              mine.push_back(p);
          if (mine.empty())
            continue;
          CellCache c;
          c.cell  = cell;
          c.first = particles.size();
          c.n     = mine.size();
          c.field = b;
          if (!gimp)
            {
              c.dofs.resize(grid.fe.dofs_per_cell);
              for (unsigned int i = 0; i < c.dofs.size(); ++i)
                {
                  const auto ci = internal::component_and_node<dim>(i);
                  c.dofs[i] =
                    all[system.component_to_system_index(b * dim + ci.first,
                                                         ci.second)];
                }
            }
          // (GIMP: the patch dofs of field b, cache_gimp_cell())
          append_cell_cache(mine, c);
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::append_cell_cache(
      const std::vector<typename dealii::Particles::ParticleIterator<dim>>
                &points_of_cache,
      CellCache &c)
    {
      std::vector<dealii::Point<dim>> reference_points;
      for (const auto &p : points_of_cache)
        {
          particles.push_back(p);
          reference_points.push_back(p->get_reference_location());
        }
      if (gimp)
        cache_gimp_cell(c.cell, reference_points, c);
      else
        append_q1_shapes(
          typename dealii::Triangulation<dim>::active_cell_iterator(c.cell),
          reference_points,
          shape_values,
          shape_gradients);
      cells.push_back(std::move(c));
    }


    template <int dim>
    void
    MPMSolver<dim>::append_q1_shapes(
      const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
      const std::vector<dealii::Point<dim>> &reference_points,
      std::vector<double>                   &values,
      std::vector<dealii::Tensor<1, dim>>   &gradients) const
    {
      const auto        &base    = grid.fe.base_element(0);
      const unsigned int n_nodes = base.dofs_per_cell;
      if (grid.is_cartesian)
        {
          // the extent of this cell: that of the finest level, doubled per
          // level above it (locally refined grids)
          dealii::Tensor<1, dim> h = grid.cell_extent;
          if (cell->level() != grid.cell_extent_level)
            for (unsigned int d = 0; d < dim; ++d)
              h[d] = std::ldexp(grid.cell_extent[d],
                                grid.cell_extent_level - cell->level());
          for (const auto &xi : reference_points)
            for (unsigned int k = 0; k < n_nodes; ++k)
              {
                values.push_back(base.shape_value(k, xi));
                dealii::Tensor<1, dim> g = base.shape_grad(k, xi);
                for (unsigned int d = 0; d < dim; ++d)
                  g[d] /= h[d];
                gradients.push_back(g);
              }
          return;
        }
      const dealii::Quadrature<dim> quadrature(reference_points);
      dealii::FEValues<dim>         fe_values(grid.mapping,
                                      base,
                                      quadrature,
                                      dealii::update_values |
                                        dealii::update_gradients);
      fe_values.reinit(cell);
      for (unsigned int q = 0; q < reference_points.size(); ++q)
        for (unsigned int k = 0; k < n_nodes; ++k)
          {
            values.push_back(fe_values.shape_value(k, q));
            gradients.push_back(fe_values.shape_grad(k, q));
          }
    }


    template <int dim>
    void
    MPMSolver<dim>::cache_gimp_cell(
      const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
      const std::vector<dealii::Point<dim>> &reference_points,
      CellCache                             &c)
    {
      // Lattice index of the cell's lowest vertex and the patch nodes
      // (-1..2 per direction around it) that exist (the grid's boundary
      // truncates the patch).
      std::array<long long, dim> base;
      dealii::Point<dim>         lowest = cell->vertex(0);
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int d = 0; d < dim; ++d)
          lowest[d] = std::min(lowest[d], cell->vertex(v)[d]);
      for (unsigned int d = 0; d < dim; ++d)
        base[d] = std::llround((lowest[d] - grid.lower_corner[d]) /
                               grid.cell_extent[d]);
      std::vector<unsigned int> slot; // patch node (0..4^dim) of cache node
      c.dofs.clear();
      c.lattice_nodes.clear();
      for (unsigned int a = 0; a < shape_stride; ++a)
        {
          long long                  key    = 0;
          bool                       inside = true;
          unsigned int               rest   = a;
          std::array<long long, dim> index;
          for (unsigned int d = 0; d < dim; ++d)
            {
              index[d] = base[d] + static_cast<long long>(rest % 4) - 1;
              rest /= 4;
              if (index[d] < 0 || index[d] >= lattice_size[d])
                inside = false;
            }
          if (!inside)
            continue;
          for (int d = dim - 1; d >= 0; --d)
            key = key * lattice_size[d] + index[d];
          const auto it = lattice_dofs.find(key);
          AssertThrow(it != lattice_dofs.end(),
                      dealii::ExcMessage(
                        "uGIMP: a patch node is not locally relevant"));
          for (unsigned int d = 0; d < dim; ++d)
            c.dofs.push_back(it->second[c.field * dim + d]);
          c.lattice_nodes.push_back(key);
          slot.push_back(a);
        }
      // GIMP weights: tensor products of the 1D functions, per cache node
      // (node j of the cache is patch node slot[j]); the entries beyond
      // the cache's nodes stay zero. uGIMP: the half-widths l0 = h/(2 n);
      // cpGIMP: l0 stretched by the committed F_n of the point (frozen
      // over the step, so the weights stay functions of the position and
      // the Newton tangent is that of uGIMP), capped at h: beyond it the
      // point would reach nodes outside the 4^dim patch.
      const dealii::Tensor<1, dim> &h = grid.cell_extent;
      if (cpdi)
        {
          // CPDI (internal::cpdi_weights()): the parallelogram
          // (parallelepiped) spanned by r_i = F_n r_i^0, r_i^0 = l0_i e_i,
          // with the committed F_n (frozen over the step, as cpGIMP: the
          // weights stay functions of the start-of-step position and the
          // tangent is unchanged); its corners are kept in the 3^dim cells
          // around the point's cell (the patch) and in the grid by scaling
          // the domain down.
          using Properties = MaterialPointProperties<dim>;
          std::vector<std::array<int, dim>> nodes(slot.size());
          for (unsigned int j = 0; j < slot.size(); ++j)
            for (unsigned int d = 0, rest = slot[j]; d < dim; ++d, rest /= 4)
              nodes[j][d] = static_cast<int>(rest % 4) - 1;
          dealii::Tensor<1, dim> lowest, highest; // in cell units
          for (unsigned int d = 0; d < dim; ++d)
            {
              lowest[d] = std::max(-1., -static_cast<double>(base[d]));
              highest[d] =
                std::min(2.,
                         static_cast<double>(lattice_size[d] - 1 - base[d]));
            }
          for (unsigned int q = 0; q < reference_points.size(); ++q)
            {
              const auto props = particles[c.first + q]->get_properties();
              const dealii::Tensor<2, dim> F =
                read_tensor<dim>(props, Properties::deformation);
              dealii::Tensor<2, dim> R;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  R[i][j] = F[i][j] * gimp_half_width[j];
              const std::size_t first = shape_values.size();
              shape_values.resize(first + shape_stride, 0.);
              shape_gradients.resize(first + shape_stride);
              const double scale =
                internal::cpdi_weights<dim>(reference_points[q],
                                            R,
                                            h,
                                            lowest,
                                            highest,
                                            nodes,
                                            &shape_values[first],
                                            &shape_gradients[first]);
              ++n_domain_evaluations;
              if (scale < 1. - 1e-12)
                ++n_capped_domains;
            }
          return;
        }
      for (unsigned int q = 0; q < reference_points.size(); ++q)
        {
          const auto            &xi = reference_points[q];
          dealii::Tensor<1, dim> l  = gimp_half_width;
          if (convected_domain)
            {
              using Properties = MaterialPointProperties<dim>;
              const auto props = particles[c.first + q]->get_properties();
              const dealii::Tensor<2, dim> F =
                read_tensor<dim>(props, Properties::deformation);
              bool capped = false;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  if (domain_bounding_box)
                    {
                      l[d] = 0.;
                      for (unsigned int e = 0; e < dim; ++e)
                        l[d] += std::abs(F[d][e]) * gimp_half_width[e];
                    }
                  else
                    l[d] = std::abs(F[d][d]) * gimp_half_width[d];
                  if (l[d] >= h[d])
                    {
                      l[d]   = h[d];
                      capped = true;
                    }
                }
              ++n_domain_evaluations;
              if (capped)
                ++n_capped_domains;
            }
          const std::size_t first = shape_values.size();
          shape_values.resize(first + shape_stride, 0.);
          shape_gradients.resize(first + shape_stride);
          for (unsigned int j = 0; j < slot.size(); ++j)
            {
              unsigned int rest = slot[j];
              double       S[dim], dS[dim];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double offset = static_cast<double>(rest % 4) - 1.;
                  rest /= 4;
                  // x_p - x_I in units of the cell's lowest vertex
                  const double r = (xi[d] - offset) * h[d];
                  S[d]           = internal::gimp_weight(r, h[d], l[d], dS[d]);
                }
              double                 value = 1.;
              dealii::Tensor<1, dim> gradient;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  value *= S[d];
                  double g = dS[d];
                  for (unsigned int e = 0; e < dim; ++e)
                    if (e != d)
                      g *= S[e];
                  gradient[d] = g;
                }
              shape_values[first + j]    = value;
              shape_gradients[first + j] = gradient;
            }
        }
    }


    template <int dim>
    dealii::Tensor<1, dim>
    MPMSolver<dim>::point_domain_half_extent(
      const dealii::Tensor<2, dim> &F) const
    {
      dealii::Tensor<1, dim> l;
      if (!gimp)
        return l;
      const dealii::Tensor<1, dim> &h = grid.cell_extent;
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (cpdi || (convected_domain && domain_bounding_box))
            for (unsigned int e = 0; e < dim; ++e)
              l[d] += std::abs(F[d][e]) * gimp_half_width[e];
          else if (convected_domain)
            l[d] = std::abs(F[d][d]) * gimp_half_width[d];
          else
            l[d] = gimp_half_width[d];
          l[d] = std::min(l[d], h[d]);
        }
      return l;
    }


    template <int dim>
    std::pair<unsigned long long, unsigned long long>
    MPMSolver<dim>::capped_point_domains() const
    {
      return {dealii::Utilities::MPI::sum(n_capped_domains,
                                          grid.mpi_communicator),
              dealii::Utilities::MPI::sum(n_domain_evaluations,
                                          grid.mpi_communicator)};
    }


    template <int dim>
    void
    MPMSolver<dim>::project_to_grid()
    {
      using Properties            = MaterialPointProperties<dim>;
      const unsigned int n_nodes  = shape_stride;
      const unsigned int max_dofs = dim * shape_stride;

      dealii::TrilinosWrappers::MPI::Vector mass(grid.locally_owned_dofs,
                                                 grid.mpi_communicator);
      dealii::TrilinosWrappers::MPI::Vector momentum(mass), mass_acc(mass);
      external_force = 0.;
      particle_forces.resize(particles.size());

      dealii::Vector<double> m_local(max_dofs), p_local(max_dofs),
        a_local(max_dofs), f_local(max_dofs);
      for (const auto &c : cells)
        {
          const unsigned int dofs_per_cell = c.dofs.size();
          m_local.reinit(dofs_per_cell);
          p_local.reinit(dofs_per_cell);
          a_local.reinit(dofs_per_cell);
          f_local.reinit(dofs_per_cell);
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
                  const auto         ci = internal::component_and_node<dim>(i);
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
          // (on a locally refined grid: condensed to the masters of the
          // hanging nodes, the conforming shape functions' sums)
          add_condensed(c.dofs, m_local, mass);
          add_condensed(c.dofs, p_local, momentum);
          add_condensed(c.dofs, a_local, mass_acc);
          add_condensed(c.dofs, f_local, external_force);
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
      using Properties            = MaterialPointProperties<dim>;
      const unsigned int n_nodes  = shape_stride;
      const unsigned int max_dofs = dim * shape_stride;
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
      dealii::Vector<double>                p_local(max_dofs);
      for (unsigned int r = 0; r < xpic_order; ++r)
        {
          // P w: mass-weighted projection to the nodes and back
          grid_velocity = 0.;
          for (const auto &c : cells)
            {
              const unsigned int dofs_per_cell = c.dofs.size();
              p_local.reinit(dofs_per_cell);
              for (unsigned int q = 0; q < c.n; ++q)
                {
                  const unsigned int k = c.first + q;
                  const double       m =
                    particles[k]->get_properties()[Properties::mass];
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const auto ci = internal::component_and_node<dim>(i);
                      p_local[i] += shape_values[k * n_nodes + ci.second] * m *
                                    w[k][ci.first];
                    }
                }
              add_condensed(c.dofs, p_local, grid_velocity);
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
                for (unsigned int i = 0; i < c.dofs.size(); ++i)
                  {
                    const auto ci = internal::component_and_node<dim>(i);
                    w[k][ci.first] -= shape_values[k * n_nodes + ci.second] *
                                      conforming_value(ghosted, c.dofs[i]);
                  }
              }
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::commit_step()
    {
      dealii::TimerOutput::Scope scope(timer, "commit (G2P, move, sort)");
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      warm_start = false;
      last_increment.clear();
      commit_friction_states();
      commit_body_contact();
      accounts.friction_dissipation += step_impact_dissipation;
      accounts.reset_dissipation += step_reset_dissipation;
      using Properties             = MaterialPointProperties<dim>;
      const unsigned int n_nodes   = shape_stride;
      const unsigned int max_dofs  = dim * shape_stride;
      const unsigned int n_history = points.n_history();

      // Nodal accelerations and velocity increments at t_{n+1}.
      dealii::TrilinosWrappers::MPI::Vector a_new(grid.locally_owned_dofs,
                                                  grid.mpi_communicator);
      dealii::TrilinosWrappers::MPI::Vector dv(a_new);
      if (!quasi_static)
        {
          // the integrator's dissipation: the forces' work by the
          // trapezoidal rule, du (f_n + M a_{n+1}) / 2, minus the grid's
          // kinetic energy change (lumped masses). Newmark's own part, with
          // the start acceleration a_n, du M (a_n + a_{n+1}) / 2 - dK, is
          // zero for gamma = 1/2, beta = 1/4 (by its algebra: not summed,
          // so that round-off does not fill the column); the start
          // acceleration's part du (f_n - M a_n) / 2 is not, where a_n is
          // the points' projected acceleration instead of M^-1 f_n
          // (record_start_force(); the free nodes).
          //
          // Contact forces that act with their end value f_c over the step
          // (ContactTimeIntegration): a^c = M^-1 f_c adds dt a^c to the
          // velocity and dt^2/2 a^c to the increment, so Newmark's
          // acceleration of the increment holds a^c/(2 beta) besides the
          // acceleration a of the other forces; the points carry a.
          dealii::TrilinosWrappers::MPI::Vector f_c;
          const bool end_contact = uses_end_contact_force();
          if (end_contact)
            end_contact_force(&displacement, f_c);
          const double s          = end_contact_factor();
          double       integrator = 0.;
          double       start_work = 0.;
          const bool   newmark_part =
            !(newmark.gamma == 0.5 && newmark.beta == 0.25);
          for (const auto i : grid.locally_owned_dofs)
            if (nodal_mass(i) > 0.)
              {
                const double du = displacement(i);
                const double an = acceleration_n(i);
                const double a_c =
                  end_contact && !constraints.is_constrained(i) ?
                    f_c(i) / nodal_mass(i) :
                    0.;
                const double a =
                  newmark.acceleration(du, velocity_n(i), an, dt) - s * a_c;
                a_new(i) = a;
                dv(i)    = newmark.velocity(0., an, a, dt) + dt * a_c;
                integrator +=
                  nodal_mass(i) * (0.5 * du * (an + a) + du * a_c -
                                   dv(i) * (velocity_n(i) + 0.5 * dv(i)));
                if (start_force_recorded && !constraints.is_constrained(i))
                  start_work +=
                    0.5 * du * (start_force(i) - nodal_mass(i) * an);
              }
          if (!consistent_mass)
            accounts.integrator_dissipation +=
              dealii::Utilities::MPI::sum((newmark_part ? integrator : 0.) +
                                            start_work,
                                          grid.mpi_communicator);
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
          dv.compress(dealii::VectorOperation::add);
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
        accounts.friction_dissipation -=
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
      std::vector<double> du_local(max_dofs), a_local(max_dofs),
        dv_local(max_dofs), v_local(max_dofs), dv_square_local(max_dofs);
      double grid_energy = 0., grid_speed = 0., transfer_energy = 0.;
      // the FLIP/PIC blend of this step ('FLIP fraction reference step')
      const double                        flip = flip_reference_step > 0. ?
                                                   std::pow(flip_fraction, dt / flip_reference_step) :
                                                   flip_fraction;
      std::vector<dealii::Tensor<2, dim>> F_cell;
      dealii::Tensor<2, 3>                P;
      for (const auto &c : cells)
        {
          const unsigned int dofs_per_cell = c.dofs.size();
          du_local.resize(dofs_per_cell);
          a_local.resize(dofs_per_cell);
          dv_local.resize(dofs_per_cell);
          v_local.resize(dofs_per_cell);
          dv_square_local.resize(dofs_per_cell);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              du_local[i] = conforming_value(displacement, c.dofs[i]);
              a_local[i]  = conforming_value(acceleration_new, c.dofs[i]);
              dv_local[i] = conforming_value(dv_flip, c.dofs[i]);
              // |dv|^2 at the node; at a hanging node the masters' mean
              // sum_j c_hj |dv_j|^2: its mass is theirs (condensed)
              dv_square_local[i] = dv_local[i] * dv_local[i];
              if (has_hanging_nodes &&
                  hanging_constraints.is_constrained(c.dofs[i]))
                {
                  dv_square_local[i] = 0.;
                  for (const auto &e :
                       *hanging_constraints.get_constraint_entries(c.dofs[i]))
                    dv_square_local[i] +=
                      e.second * dv_flip(e.first) * dv_flip(e.first);
                }
              v_local[i] = conforming_value(velocity_n, c.dofs[i]) +
                           conforming_value(dv_ghosted, c.dofs[i]);
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
              // sum_I N_I |dv_I|^2: with it, the kinetic energy the grid
              // gains and the points do not (lumped-mass gap, below)
              double dv_square_mean = 0.;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = internal::component_and_node<dim>(i);
                  dv_square_mean += N[ci.second] * dv_square_local[i];
                  v_pic[ci.first] += N[ci.second] * v_local[i];
                  grad_v[ci.first] += v_local[i] * dN[ci.second];
                  du_p[ci.first] += N[ci.second] * du_local[i];
                  a_p[ci.first] += N[ci.second] * a_local[i];
                  dv_p[ci.first] += N[ci.second] * dv_local[i];
                  H[ci.first] += du_local[i] * dN[ci.second];
                }
              const dealii::Tensor<2, dim> F_n =
                read_tensor<dim>(props, Properties::deformation);
              const dealii::Tensor<2, dim> &F_new       = F_cell[q];
              const dealii::Tensor<2, 3>    F3          = embed<dim>(F_new);
              const auto                   &point_model = model_of(props);
              const unsigned int            n_point_history =
                point_model.n_history_variables();
              point_model.compute_stress(
                embed<dim>(F_n),
                F3,
                dealii::ArrayView<const double>(props.data() +
                                                  Properties::history,
                                                n_point_history),
                dealii::ArrayView<double>(history_new.data(), n_point_history),
                dt,
                P,
                nullptr);
              // Cauchy stress sigma = P F^T / J.
              const dealii::Tensor<2, 3> sigma =
                P * dealii::transpose(F3) / dealii::determinant(F3);
              Properties::store_stress(props, sigma);
              for (unsigned int h = 0; h < n_point_history; ++h)
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
                                     flip * v_flip + (1. - flip) * v_pic[i];
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
                  // the FLIP increment's lumped-mass gap: the grid's kinetic
                  // energy (lumped masses m_I = sum_p m_p N_I) changes by
                  // sum_I m_I (v_I . dv_I + |dv_I|^2 / 2), the points' by
                  // sum_p m_p (v_p . dv_p + |dv_p|^2 / 2) with dv_p =
                  // sum_I N_I dv_I; the first terms agree (the projection
                  // of the momentum), the second differ by
                  // m_p (sum_I N_I |dv_I|^2 - |dv_p|^2) / 2 >= 0 per point
                  // (Jensen), kinetic energy the transfer takes. With the
                  // consistent mass the grid's quadratic term is
                  // dv^T M dv / 2 = sum_p m_p |dv_p|^2 / 2: no gap.
                  if (!consistent_mass)
                    transfer_energy += 0.5 * props[Properties::mass] *
                                       (dv_square_mean - dv_p.norm_square());
                  grid_energy +=
                    0.5 * props[Properties::mass] * v_pic.norm_square();
                  grid_speed = std::max(grid_speed, v_pic.norm());
                }
            }
        }
      grid_kinetic_energy =
        dealii::Utilities::MPI::sum(grid_energy, grid.mpi_communicator);
      accounts.transfer_dissipation +=
        dealii::Utilities::MPI::sum(transfer_energy, grid.mpi_communicator);
      max_grid_speed =
        dealii::Utilities::MPI::max(grid_speed, grid.mpi_communicator);
      // Boundary particles: the new gaps, reactions and states of the
      // converged iterate (computed by solve_step(), trial state) become
      // the committed ones; the friction work is booked.
      if (boundary_particles != nullptr)
        commit_boundary_trial();

      cells.clear();
      particles.clear();
      {
        dealii::TimerOutput::Scope s(timer, "sort particles");
        points.particle_handler().sort_particles_into_subdomains_and_cells();
        if (boundary_particles != nullptr)
          boundary_particles->move_to(time);
      }
      p2g_current = false;
      prepared    = false;
      solved      = false;
    }


    template <int dim>
    void
    MPMSolver<dim>::project_stress_to_grid()
    {
      using Properties            = MaterialPointProperties<dim>;
      const unsigned int n_nodes  = shape_stride;
      const unsigned int max_dofs = dim * shape_stride;
      std::vector<dealii::TrilinosWrappers::MPI::Vector> sum(
        dim,
        dealii::TrilinosWrappers::MPI::Vector(grid.locally_owned_dofs,
                                              grid.mpi_communicator));
      std::vector<dealii::Vector<double>> local(
        dim, dealii::Vector<double>(max_dofs));
      // Voigt order of the stored stress: xx yy zz xy yz xz
      const unsigned int voigt[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
      for (const auto &c : cells)
        {
          const unsigned int dofs_per_cell = c.dofs.size();
          for (auto &l : local)
            l.reinit(dofs_per_cell);
          for (unsigned int q = 0; q < c.n; ++q)
            {
              const unsigned int k     = c.first + q;
              const auto         props = particles[k]->get_properties();
              const double       m     = props[Properties::mass];
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto   ci = internal::component_and_node<dim>(i);
                  const double N  = shape_values[k * n_nodes + ci.second];
                  for (unsigned int j = 0; j < dim; ++j)
                    local[j][i] +=
                      N * m * props[Properties::stress + voigt[ci.first][j]];
                }
            }
          for (unsigned int j = 0; j < dim; ++j)
            add_condensed(c.dofs, local[j], sum[j]);
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


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                                  \
  template void MPMSolver<dim>::cache_particles();                              \
  template void MPMSolver<dim>::cache_cell_per_body(                            \
    const typename dealii::DoFHandler<dim>::active_cell_iterator &);            \
  template void MPMSolver<dim>::append_cell_cache(                              \
    const std::vector<typename dealii::Particles::ParticleIterator<dim>> &,     \
    CellCache &);                                                               \
  template std::pair<unsigned long long, unsigned long long>                    \
                                  MPMSolver<dim>::capped_point_domains() const; \
  template dealii::Tensor<1, dim> MPMSolver<dim>::point_domain_half_extent(     \
    const dealii::Tensor<2, dim> &) const;                                      \
  template void MPMSolver<dim>::project_to_grid();                              \
  template void MPMSolver<dim>::compute_xpic_correction(                        \
    std::vector<dealii::Tensor<1, dim>> &w) const;                              \
  template void MPMSolver<dim>::commit_step();                                  \
  template void MPMSolver<dim>::project_stress_to_grid();                       \
  template void MPMSolver<dim>::append_q1_shapes(                               \
    const typename dealii::Triangulation<dim>::active_cell_iterator &,          \
    const std::vector<dealii::Point<dim>> &,                                    \
    std::vector<double> &,                                                      \
    std::vector<dealii::Tensor<1, dim>> &) const;

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
