#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/mpi.h>

#include <Amesos.h>
#include <Epetra_MultiVector.h>

#include <map>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    std::vector<std::vector<
      std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>>
    MPMSolver<dim>::linearised_boundary_reactions(
      const std::function<
        dealii::Tensor<1, dim>(const dealii::types::particle_index,
                               const unsigned int)> &delta_bar,
      const unsigned int                             n_columns)
    {
      Assert(solved, dealii::ExcMessage("solve_step() first"));
      AssertThrow(!with_lagrange_multipliers,
                  dealii::ExcMessage(
                    "the linearised boundary reactions are not available "
                    "with Lagrange multiplier boundaries"));
      using Id                         = dealii::types::particle_index;
      const auto        &fe            = grid.fe;
      const unsigned int n_nodes       = fe.base_element(0).dofs_per_cell;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      const MPI_Comm     comm          = grid.mpi_communicator;

      // The boundary points that carry a force at the converged iterate:
      // D_p = dF_p/du, the share of their force on nodes with mass.
      struct Loaded
      {
        const BoundaryPoint   *bp;
        const CellCache       *cell;
        dealii::Tensor<2, dim> D;
        double                 active_share;
      };
      std::vector<Loaded> loaded;
      std::vector<double> du_local(dofs_per_cell);
      for (const auto &c : boundary_cells)
        {
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            du_local[i] = conforming_value(displacement, c.dofs[i]);
          for (unsigned int b = 0; b < c.n_boundary; ++b)
            {
              const BoundaryPoint   &bp = boundary_points[c.first_boundary + b];
              dealii::Tensor<1, dim> du_b;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  du_b[ci.first] += bp.N[ci.second] * du_local[i];
                }
              AssertThrow(!(bp.nitsche && bp.with_stress),
                          dealii::ExcMessage(
                            "the linearised boundary reactions are not "
                            "available for Nitsche boundaries"));
              const BoundaryForce bf = boundary_force(bp, du_b);
              if (bf.state == 0)
                continue;
              double active_share = 1.;
              if (!bp.on_material_point)
                {
                  active_share = 0.;
                  for (unsigned int k = 0; k < n_nodes; ++k)
                    active_share +=
                      bp.N[k] *
                      mass_share(c.dofs[fe.component_to_system_index(0, k)]);
                }
              loaded.push_back({&bp, &c, bf.dforce_du, active_share});
            }
        }

      if (!dealii::Utilities::MPI::logical_or(!loaded.empty(), comm))
        return std::vector<std::vector<std::pair<Id, dealii::Tensor<1, dim>>>>(
          n_columns);

      // the prescribed change of a point: its particle's, the weighted
      // mean of a merged point's members (their shares S taken as the
      // merged point's), the surface particle's for a material point in
      // contact
      const auto point_delta = [&](const BoundaryPoint &bp,
                                   const unsigned int   column) {
        if (bp.on_material_point)
          return delta_bar(bp.surface_particle, column);
        if (bp.members.empty())
          return delta_bar(bp.particle->get_id(), column);
        dealii::Tensor<1, dim> d;
        for (unsigned int m = 0; m < bp.members.size(); ++m)
          d += (bp.member_weights[m] / bp.weight) *
               delta_bar(bp.members[m]->get_id(), column);
        return d;
      };

      const bool fast_direct = linear_solver_type == "direct" &&
                               !factorisation &&
                               direct_package != "Amesos_Mumps";
      std::vector<std::vector<std::pair<Id, dealii::Tensor<1, dim>>>> result(
        n_columns);
      dealii::TrilinosWrappers::MPI::Vector b(grid.locally_owned_dofs, comm),
        x(grid.locally_owned_dofs, comm),
        x_ghosted(grid.locally_owned_dofs, grid.locally_relevant_dofs, comm);
      dealii::Vector<double>              b_local(dofs_per_cell);
      std::vector<dealii::Tensor<1, dim>> delta(loaded.size());
      for (unsigned int column = 0; column < n_columns; ++column)
        {
          // right-hand side sum_p N_p^T (-D_p) d_bar_p
          b = 0.;
          for (unsigned int l = 0; l < loaded.size(); ++l)
            {
              // the nodes without mass stand for the boundary: a boundary
              // particle's increment enters with the share S of the nodes
              // with mass (g = g_old + N du - S du_bar,
              // cache_boundary_particles())
              delta[l] =
                loaded[l].active_share * point_delta(*loaded[l].bp, column);
              // (a force that acts with its end value counts 1/(2 beta)
              // times in the residual, ContactTimeIntegration; the
              // reaction below is the force itself)
              const double s =
                loaded[l].bp->end_of_step ? end_contact_factor() : 1.;
              const dealii::Tensor<1, dim> f = -s * (loaded[l].D * delta[l]);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  b_local[i]    = loaded[l].bp->N[ci.second] * f[ci.first];
                }
              constraints.distribute_local_to_global(b_local,
                                                     loaded[l].cell->dofs,
                                                     b);
            }
          b.compress(dealii::VectorOperation::add);
          if (fast_direct && column > 0 && direct_solver)
            {
              // back-substitution with the factorisation of the first
              // column (the tangent of the last Newton iteration)
              x = 0.;
              direct_problem->SetLHS(&x.trilinos_vector());
              direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
                static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
              AssertThrow(direct_solver->Solve() == 0,
                          dealii::ExcMessage(
                            "the direct solve with the tangent failed"));
              constraints.distribute(x);
            }
          else
            solve_with_tangent(x, b, 1e-10);
          x_ghosted = x;
          // dF_p = D_p (N_p du - d_bar_p); the reaction changes by -dF_p
          std::map<Id, dealii::Tensor<1, dim>> booked;
          for (unsigned int l = 0; l < loaded.size(); ++l)
            {
              const BoundaryPoint   &bp = *loaded[l].bp;
              dealii::Tensor<1, dim> du_b;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  du_b[ci.first] +=
                    bp.N[ci.second] *
                    conforming_value(x_ghosted, loaded[l].cell->dofs[i]);
                }
              const dealii::Tensor<1, dim> dF = loaded[l].D * (du_b - delta[l]);
              if (bp.on_material_point)
                booked[bp.surface_particle] -= dF;
              else if (bp.members.empty())
                result[column].emplace_back(bp.particle->get_id(),
                                            -loaded[l].active_share * dF);
              else
                for (unsigned int m = 0; m < bp.members.size(); ++m)
                  result[column].emplace_back(bp.members[m]->get_id(),
                                              -(bp.member_weights[m] /
                                                bp.weight) *
                                                loaded[l].active_share * dF);
            }
          result[column].insert(result[column].end(),
                                booked.begin(),
                                booked.end());
        }
      return result;
    }


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                         \
  template std::vector<std::vector<                                    \
    std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>> \
  MPMSolver<dim>::linearised_boundary_reactions(                       \
    const std::function<dealii::Tensor<1, dim>(                        \
      const dealii::types::particle_index, const unsigned int)> &,     \
    const unsigned int);

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
