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

    namespace
    {
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
       * The same for the up to 4^dim patch nodes of a uGIMP cell
       * ('shape functions = uGIMP'): at most 32 derivatives in 2D, 192 in
       * 3D, as many as the patch has dofs (the grid's boundary truncates
       * it).
       */
      template <int dim>
      using PatchAD = Sacado::Fad::SLFad<double, dim *(1 << (2 * dim))>;

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
    bool
    MPMSolver<dim>::assemble(const dealii::TrilinosWrappers::MPI::Vector &du,
                             const bool   with_matrix,
                             const bool   with_inertia,
                             std::string &failure,
                             const bool   same_iterate)
    {
      using Properties                 = MaterialPointProperties<dim>;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = shape_stride;
      const unsigned int dofs_per_cell = fe.dofs_per_cell; // boundary cells
      const unsigned int max_dofs      = dim * shape_stride;
      const unsigned int n_history     = points.n_history();
      const double       c_mass = with_inertia ? newmark.mass_factor(dt) : 0.;

      // the contact state of each boundary point at this assembly (-2: not
      // assembled), compared with the last matrix assembly's
      std::vector<int> states;
      if (with_matrix)
        {
          matrix                   = 0.;
          reversed_boundary_points = 0;
          states.assign(boundary_points.size(), -2);
        }
      residual            = 0.;
      multiplier_residual = 0.;
      if (!grid.friction_boundaries.empty())
        raw_residual = 0.;

      dealii::FullMatrix<double> k_local(max_dofs, max_dofs);
      dealii::Vector<double>     r_local(max_dofs);
      std::vector<double>        du_local(max_dofs), a_local(max_dofs);
      std::vector<unsigned int>  comp(max_dofs), node(max_dofs), active;
      active.reserve(max_dofs);
      // uGIMP: the nodes a point reaches and V0 G_a . A per node
      std::vector<unsigned int>           active_nodes;
      std::vector<dealii::Tensor<3, dim>> GA(shape_stride);
      for (unsigned int i = 0; i < max_dofs; ++i)
        {
          comp[i] = internal::component_and_node<dim>(i).first;
          node[i] = internal::component_and_node<dim>(i).second;
        }
      std::vector<double>                 history_new(n_history);
      std::vector<dealii::Tensor<1, dim>> G(n_nodes);
      dealii::Tensor<2, 3>                P;
      dealii::Tensor<4, 3>                A;
      bool                                ok = true;
      // lumped inertia of hanging nodes, by master dof (locally refined
      // grids)
      std::map<dealii::types::global_dof_index, double> hanging_inertia;
      // Rows added to friction nodes' tangential dofs through hanging
      // nodes: per tangential dof the coefficients of the columns (a
      // cell's dofs) and, last, the residual.
      std::map<dealii::types::global_dof_index, std::vector<double>> slip_rows;
      const auto add_slip_rows =
        [&](const std::vector<dealii::types::global_dof_index> &columns,
            const bool                                          matrix_too) {
          if (slip_rows.empty())
            return;
          std::vector<dealii::types::global_dof_index> rows;
          dealii::FullMatrix<double> k_rows(slip_rows.size(), columns.size());
          dealii::Vector<double>     r_rows(slip_rows.size());
          for (const auto &[t, row] : slip_rows)
            {
              const unsigned int r = rows.size();
              rows.push_back(t);
              for (unsigned int l = 0; l < columns.size(); ++l)
                k_rows(r, l) = row[l];
              r_rows[r] = row[columns.size()];
            }
          if (matrix_too)
            constraints.distribute_local_to_global(k_rows,
                                                   rows,
                                                   columns,
                                                   matrix);
          constraints.distribute_local_to_global(r_rows, rows, residual);
        };

      // The cells' contributions before friction and constraints, kept for
      // a re-assembly at the same iterate after a contact state update.
      const unsigned int block = max_dofs * max_dofs + max_dofs;
      const bool         keep_contributions =
        with_matrix && !grid.friction_boundaries.empty();
      const bool reuse_contributions =
        same_iterate && with_matrix && cell_contributions_current;
      if (keep_contributions && !reuse_contributions)
        cell_contributions.resize(cells.size() * block);
      cell_contributions_current = false;

      for (unsigned int cell_index = 0; cell_index < cells.size(); ++cell_index)
        {
          const CellCache   &c             = cells[cell_index];
          const unsigned int dofs_per_cell = c.dofs.size();
          if (!ok)
            break;
          k_local.reinit(dofs_per_cell, dofs_per_cell);
          r_local.reinit(dofs_per_cell);
          du_local.resize(dofs_per_cell);
          a_local.resize(dofs_per_cell);
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
                        stored + dofs_per_cell * dofs_per_cell + dofs_per_cell,
                        r_local.begin());
              // the hanging nodes' lumped inertia is not in the stored
              // block (it goes to the masters' diagonal below)
              if (with_inertia && !consistent_mass && has_hanging_nodes)
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  if (hanging_constraints.is_constrained(c.dofs[i]))
                    for (unsigned int q = 0; q < c.n; ++q)
                      {
                        const unsigned int k = c.first + q;
                        const double       m =
                          particles[k]->get_properties()[Properties::mass];
                        for (const auto &e :
                             *hanging_constraints.get_constraint_entries(
                               c.dofs[i]))
                          hanging_inertia[e.first] +=
                            e.second * m * shape_values[k * n_nodes + node[i]];
                      }
            }
          else
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  du_local[i] = conforming_value(du, c.dofs[i]);
                  a_local[i]  = with_inertia ?
                                  newmark.acceleration(
                                   du_local[i],
                                   conforming_value(velocity_n, c.dofs[i]),
                                   conforming_value(acceleration_n, c.dofs[i]),
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

                  // The dofs the point reaches (uGIMP: at most 3^dim of the
                  // 4^dim patch nodes, cpGIMP: up to all of them; linear:
                  // all, in order).
                  active.clear();
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    if (!gimp || N[node[i]] != 0. ||
                        dN[node[i]].norm_square() != 0.)
                      active.push_back(i);

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
                            for (const unsigned int j : active)
                              if (comp[j] == ci)
                                k_local(i, j) +=
                                  c_mass * m * N[node[i]] * N[node[j]];
                        }
                      else if (has_hanging_nodes &&
                               hanging_constraints.is_constrained(c.dofs[i]))
                        {
                          // the lumped mass on the conforming space: a
                          // hanging node's share goes to the diagonal of
                          // its masters (below), as the P2G condenses it
                          // into their nodal masses; through the cell
                          // matrix it would couple them (C^T M C)
                          for (const auto &e :
                               *hanging_constraints.get_constraint_entries(
                                 c.dofs[i]))
                            hanging_inertia[e.first] +=
                              e.second * m * N[node[i]];
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

                  const auto        &point_model = model_of(props);
                  const unsigned int n_point_history =
                    point_model.n_history_variables();
                  try
                    {
                      point_model.compute_stress(
                        embed<dim>(F_n),
                        embed<dim>(F_new),
                        dealii::ArrayView<const double>(props.data() +
                                                          Properties::history,
                                                        n_point_history),
                        dealii::ArrayView<double>(history_new.data(),
                                                  n_point_history),
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
                                    history_new.data(), n_point_history));
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

                  if (gimp)
                    {
                      // GIMP (3^dim, cpGIMP up to 4^dim nodes per point):
                      // the product G_a . A first, per node, then with G_b
                      // (a third of the operations of the loop below; that
                      // loop keeps the linear results bitwise).
                      active_nodes.clear();
                      for (unsigned int t = 0; t < active.size(); t += dim)
                        active_nodes.push_back(node[active[t]]);
                      for (unsigned int s = 0; s < active_nodes.size(); ++s)
                        {
                          const unsigned int a  = active_nodes[s];
                          const auto        &Ga = G[a];
                          for (unsigned int ci = 0; ci < dim; ++ci)
                            {
                              double f = 0.;
                              for (unsigned int J = 0; J < dim; ++J)
                                f += P[ci][J] * Ga[J];
                              r_local[a * dim + ci] -= V0 * f;
                            }
                          if (!with_matrix)
                            continue;
                          auto &B = GA[s];
                          for (unsigned int ci = 0; ci < dim; ++ci)
                            for (unsigned int cj = 0; cj < dim; ++cj)
                              for (unsigned int L = 0; L < dim; ++L)
                                {
                                  double b = 0.;
                                  for (unsigned int J = 0; J < dim; ++J)
                                    b += Ga[J] * A[ci][J][cj][L];
                                  B[ci][cj][L] = V0 * b;
                                }
                        }
                      if (with_matrix)
                        for (unsigned int s = 0; s < active_nodes.size(); ++s)
                          {
                            const unsigned int a = active_nodes[s];
                            const auto        &B = GA[s];
                            for (const unsigned int b : active_nodes)
                              {
                                const auto &Gb = G[b];
                                for (unsigned int ci = 0; ci < dim; ++ci)
                                  for (unsigned int cj = 0; cj < dim; ++cj)
                                    {
                                      double kij = 0.;
                                      for (unsigned int L = 0; L < dim; ++L)
                                        kij += B[ci][cj][L] * Gb[L];
                                      k_local(a * dim + ci, b * dim + cj) +=
                                        kij;
                                    }
                              }
                          }
                      continue;
                    }
                  for (const unsigned int i : active)
                    {
                      const unsigned int ci = comp[i];
                      const auto        &Gi = G[node[i]];
                      double             f  = 0.;
                      for (unsigned int J = 0; J < dim; ++J)
                        f += P[ci][J] * Gi[J];
                      r_local[i] -= V0 * f;
                      if (!with_matrix)
                        continue;
                      for (const unsigned int j : active)
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

          // (uGIMP, cpGIMP, CPDI: a cell's node patch reaches a cell
          // beyond its vertices, so every cell is looked at)
          if (!grid.friction_boundaries.empty() &&
              (gimp || cell_touches_friction[c.cell->active_cell_index()]))
            {
              // Unconstrained residual for the contact reactions, then the
              // Coulomb force of slipping nodes as a combination of rows:
              // r_t += mu * inward * s_t * r_n (exactly linearized).
              if (has_hanging_nodes)
                hanging_constraints.distribute_local_to_global(r_local,
                                                               c.dofs,
                                                               raw_residual);
              else
                raw_residual.add(c.dofs, r_local);
              // a hanging node's rows go to its masters with their
              // weights: where a master is a slipping friction node, its
              // tangential rows take the weighted normal row too
              if (has_hanging_nodes)
                {
                  slip_rows.clear();
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    if (hanging_constraints.is_constrained(c.dofs[i]))
                      for (const auto &e :
                           *hanging_constraints.get_constraint_entries(
                             c.dofs[i]))
                        {
                          const auto it = friction_node_of.find(e.first);
                          if (it == friction_node_of.end())
                            continue;
                          const FrictionNode &fn = friction_nodes[it->second];
                          if (fn.state != ContactState::slip || fn.mu == 0.)
                            continue;
                          for (unsigned int k = 0;
                               k < fn.tangential_dofs.size();
                               ++k)
                            {
                              auto &row = slip_rows[fn.tangential_dofs[k]];
                              row.resize(dofs_per_cell + 1, 0.);
                              const double factor =
                                e.second * fn.mu * fn.inward *
                                fn.slip_direction[fn.tangential_components[k]];
                              for (unsigned int l = 0; l < dofs_per_cell; ++l)
                                row[l] += factor * k_local(i, l);
                              row[dofs_per_cell] += factor * r_local[i];
                            }
                        }
                  add_slip_rows(c.dofs, with_matrix);
                }
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

      // The hanging nodes' lumped inertia, on the masters' diagonal: the
      // inertia force is then M a with the condensed nodal masses of the
      // P2G (nodal_mass), the mass of the energy accounts.
      if (ok)
        {
          std::vector<dealii::types::global_dof_index> master(1);
          dealii::FullMatrix<double>                   k_master(1, 1);
          dealii::Vector<double>                       r_master(1);
          for (const auto &[j, m] : hanging_inertia)
            {
              master[0]      = j;
              k_master(0, 0) = c_mass * m;
              r_master[0]    = -m * newmark.acceleration(du(j),
                                                      velocity_n(j),
                                                      acceleration_n(j),
                                                      dt);
              if (with_matrix)
                constraints.distribute_local_to_global(
                  k_master, r_master, master, matrix, residual);
              else
                constraints.distribute_local_to_global(r_master,
                                                       master,
                                                       residual);
              if (grid.friction_boundaries.empty())
                continue;
              // the friction nodes' unconstrained residual, and the
              // Coulomb force of a slipping master's normal inertia
              raw_residual.add(master, r_master);
              const auto it = friction_node_of.find(j);
              if (it == friction_node_of.end())
                continue;
              const FrictionNode &fn = friction_nodes[it->second];
              if (fn.state != ContactState::slip || fn.mu == 0.)
                continue;
              slip_rows.clear();
              for (unsigned int k = 0; k < fn.tangential_dofs.size(); ++k)
                {
                  const double factor =
                    fn.mu * fn.inward *
                    fn.slip_direction[fn.tangential_components[k]];
                  slip_rows[fn.tangential_dofs[k]] = {factor * k_master(0, 0),
                                                      factor * r_master[0]};
                }
              add_slip_rows(master, with_matrix);
            }
        }

      // Boundary particles in cells with at least one node that carries
      // mass: penalty forces on the material.
      const double end_contact_scale = end_contact_factor();
      std::vector<dealii::Tensor<1, dim>> dT(dofs_per_cell), df(dofs_per_cell);
      k_local.reinit(dofs_per_cell, dofs_per_cell);
      r_local.reinit(dofs_per_cell);
      du_local.resize(dofs_per_cell);
      for (const auto &c : boundary_cells)
        {
          if (!ok)
            break;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            du_local[i] = conforming_value(du, c.dofs[i]);
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
                  states[c.first_boundary + b] = bf.state;
                  bp.last_state                = bf.state;
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
              // (unilateral contact with its end-of-step force counts
              // 1/(2 beta) times: ContactTimeIntegration)
              const double s = bp.end_of_step ? end_contact_scale : 1.;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const double Ni = s * bp.N[node[i]];
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

      // Multi-velocity field: contact between the bodies' fields.
      if (ok)
        assemble_body_contact(du, with_matrix);

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
          // a changed contact state changes A (the trial-force stiffness
          // k N^T D N): the preconditioner of an earlier iterate no longer
          // fits it
          boundary_states_changed = states != assembled_states;
          assembled_states.swap(states);
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
      const int branch = static_cast<int>(
        model_of(particles[k]->get_properties()).return_branch(history));
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
      const unsigned int n_nodes       = shape_stride;
      const unsigned int dofs_per_cell = c.dofs.size();
      const unsigned int n_history     = points.n_history();

      std::vector<unsigned int> comp(dofs_per_cell), node(dofs_per_cell);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          comp[i] = internal::component_and_node<dim>(i).first;
          node[i] = internal::component_and_node<dim>(i).second;
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
        const auto         props = particles[c.first + q]->get_properties();
        const auto        &point_model = model_of(props);
        const unsigned int n_point_history = point_model.n_history_variables();
        try
          {
            point_model.compute_stress(
              embed<dim>(F_n[q]),
              embed<dim>(F),
              dealii::ArrayView<const double>(props.data() +
                                                Properties::history,
                                              n_point_history),
              dealii::ArrayView<double>(history_new.data(), n_point_history),
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
                                                        n_point_history));
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
      // the derivatives by forward AD with one slot per dof of the cell
      // (uGIMP: of the patch)
      const auto with_derivatives = [&](auto zero) {
        using AD = decltype(zero);
        std::vector<AD> u(dofs_per_cell), f_int(dofs_per_cell);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            u[i]     = AD(dofs_per_cell, i, du_local[i]);
            f_int[i] = 0.;
          }
        ok = fbar_internal_forces<dim>(
          c.n, n_nodes, comp, node, u, dN, F_n, V0, model_call, f_int, nullptr);
        if (ok)
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              r_local[i] -= f_int[i].val();
              for (unsigned int j = 0; j < dofs_per_cell; ++j)
                (*k_local)(i, j) += f_int[i].dx(j);
            }
      };
      if (k_local != nullptr)
        {
          if (gimp)
            with_derivatives(PatchAD<dim>());
          else
            with_derivatives(CellAD<dim>());
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
      const unsigned int n_nodes       = shape_stride;
      const unsigned int dofs_per_cell = c.dofs.size();
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
              const auto ci = internal::component_and_node<dim>(i);
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


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                                  \
  template bool MPMSolver<dim>::assemble(                                       \
    const dealii::TrilinosWrappers::MPI::Vector &du,                            \
    const bool                                   with_matrix,                   \
    const bool                                   with_inertia,                  \
    std::string                                 &failure,                       \
    const bool                                   same_iterate);                                                   \
  template void MPMSolver<dim>::record_branch(                                  \
    const unsigned int k, const dealii::ArrayView<const double> &history)       \
    const;                                                                      \
  template bool MPMSolver<dim>::fbar_cell(const CellCache            &c,        \
                                          const std::vector<double>  &du_local, \
                                          dealii::Vector<double>     &r_local,  \
                                          dealii::FullMatrix<double> *k_local,  \
                                          std::string &failure) const;          \
  template void MPMSolver<dim>::cell_deformation_gradients(                     \
    const CellCache                     &c,                                     \
    const std::vector<double>           &du_local,                              \
    std::vector<dealii::Tensor<2, dim>> &F_new) const;                          \
  template void MPMSolver<dim>::setup_ghost_penalty();

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
