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
#include <Epetra_Vector.h>
#include <Sacado.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
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
      /** An Epetra linear problem that owns its operator. */
      struct OwningLinearProblem : public Epetra_LinearProblem
      {
        std::unique_ptr<Epetra_CrsMatrix> matrix;
      };
    } // namespace


    template <int dim>
    unsigned int
    MPMSolver<dim>::solve_linear(dealii::TrilinosWrappers::MPI::Vector &x,
                                 const double relative_tolerance)
    {
      dealii::TimerOutput::Scope scope(timer, "linear solver");
      if (with_lagrange_multipliers)
        return solve_saddle_point(x);
      return solve_with_tangent(x, residual, relative_tolerance);
    }


    template <int dim>
    void
    MPMSolver<dim>::build_amg()
    {
      dealii::TimerOutput::Scope s(timer, "AMG setup");
      if (preconditioner_type == "ILU")
        {
          auto ilu =
            std::make_unique<dealii::TrilinosWrappers::PreconditionILU>();
          ilu->initialize(
            matrix,
            dealii::TrilinosWrappers::PreconditionILU::AdditionalData(
              ilu_fill));
          ifpack_preconditioner = std::move(ilu);
          return;
        }
      if (preconditioner_type == "Jacobi")
        {
          auto jacobi =
            std::make_unique<dealii::TrilinosWrappers::PreconditionJacobi>();
          jacobi->initialize(matrix);
          ifpack_preconditioner = std::move(jacobi);
          return;
        }
      AssertThrow(preconditioner_type == "AMG",
                  dealii::ExcMessage("unknown preconditioner '" +
                                     preconditioner_type + "'"));
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.constant_modes        = constant_modes;
      data.elliptic              = amg_elliptic;
      data.w_cycle               = amg_w_cycle;
      data.higher_order_elements = false;
      data.smoother_sweeps       = amg_sweeps;
      data.smoother_type         = amg_smoother.c_str();
      data.aggregation_threshold = amg_threshold;
      // TALUS_DEBUG_AMG: ML prints its hierarchy (levels, rows, smoothers)
      data.output_details = std::getenv("TALUS_DEBUG_AMG") != nullptr;
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
      parameters.set("coarse: max size", static_cast<int>(amg_coarse_size));
      parameters.set("null space: type", "pre-computed");
      parameters.set("null space: dimension", static_cast<int>(n_modes));
      parameters.set("null space: vectors", rigid_body_modes->Values());
      amg = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
      amg->initialize(matrix, parameters);
    }


    template <int dim>
    bool
    MPMSolver<dim>::preconditioner_built() const
    {
      return preconditioner_type == "AMG" ? amg != nullptr :
                                            ifpack_preconditioner != nullptr;
    }


    template <int dim>
    const dealii::TrilinosWrappers::PreconditionBase &
    MPMSolver<dim>::preconditioner() const
    {
      Assert(preconditioner_built(), dealii::ExcInternalError());
      if (preconditioner_type == "AMG")
        return *amg;
      return *ifpack_preconditioner;
    }


    template <int dim>
    void
    MPMSolver<dim>::print_linear_diagnostics(
      const dealii::SolverControl                 &control,
      const dealii::TrilinosWrappers::MPI::Vector &b,
      const std::string                           &label) const
    {
      const MPI_Comm comm = grid.mpi_communicator;
      // the diagonal of the rows that are not constrained
      std::vector<double> diagonal;
      for (const auto i : grid.locally_owned_dofs)
        if (!constraints.is_constrained(i))
          diagonal.push_back(matrix.diag_element(i));
      const double d_max = dealii::Utilities::MPI::max(
        diagonal.empty() ? 0. :
                           *std::max_element(diagonal.begin(), diagonal.end()),
        comm);
      const double d_min = dealii::Utilities::MPI::min(
        diagonal.empty() ? d_max :
                           *std::min_element(diagonal.begin(), diagonal.end()),
        comm);
      unsigned int n_small = 0, n_negative = 0;
      for (const double d : diagonal)
        {
          n_small += std::abs(d) < 1e-6 * d_max;
          n_negative += d <= 0.;
        }
      n_small    = dealii::Utilities::MPI::sum(n_small, comm);
      n_negative = dealii::Utilities::MPI::sum(n_negative, comm);
      const unsigned int n_rows =
        dealii::Utilities::MPI::sum<unsigned int>(diagonal.size(), comm);
      // non-symmetry |(A - A^T) v| / |A v| for v = b
      Epetra_Vector Av(matrix.trilinos_matrix().RangeMap()),
        ATv(matrix.trilinos_matrix().DomainMap());
      const Epetra_MultiVector &v = b.trilinos_vector();
      matrix.trilinos_matrix().Multiply(false, v, Av);
      matrix.trilinos_matrix().Multiply(true, v, ATv);
      double norm_Av = 0., norm_diff = 0.;
      Av.Norm2(&norm_Av);
      ATv.Update(1., Av, -1.);
      ATv.Norm2(&norm_diff);
      const auto &history = control.get_history_data();
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      std::cerr << "    Krylov failure (" << label << ", " << linear_solver_type
                << ", " << preconditioner_type << "): |b| " << b.l2_norm()
                << ", target " << control.tolerance() << ", last residual "
                << control.last_value() << " after " << control.last_step()
                << " iterations\n      free rows " << n_rows << ", diagonal "
                << d_min << " .. " << d_max << ", " << n_small
                << " below 1e-6 max, " << n_negative
                << " not positive; |(A - A^T) b| / |A b| "
                << norm_diff / std::max(norm_Av, 1e-300) << "\n      history:";
      const std::size_t stride = std::max<std::size_t>(1, history.size() / 20);
      for (std::size_t k = 0; k < history.size(); k += stride)
        std::cerr << ' ' << k << ':' << history[k];
      std::cerr << std::endl;
    }


    template <int dim>
    unsigned int
    MPMSolver<dim>::solve_with_tangent(
      dealii::TrilinosWrappers::MPI::Vector       &x,
      const dealii::TrilinosWrappers::MPI::Vector &b,
      const double                                 relative_tolerance)
    {
      x = 0.;
      if (linear_solver_type == "direct")
        {
          if (factorisation)
            factorisation->solve(x, b);
          else
            {
              const bool mumps = direct_package == "Amesos_Mumps";
              if (!direct_solver)
                {
                  if (mumps)
                    {
                      // MUMPS releases its factors through the operator's
                      // communicator, also when the solver is destroyed
                      // after the matrix: the problem keeps its own copy
                      // (refreshed before each factorisation)
                      auto problem    = std::make_unique<OwningLinearProblem>();
                      problem->matrix = std::make_unique<Epetra_CrsMatrix>(
                        matrix.trilinos_matrix());
                      problem->SetOperator(problem->matrix.get());
                      direct_problem = std::move(problem);
                    }
                  else
                    {
                      direct_problem = std::make_unique<Epetra_LinearProblem>();
                      direct_problem->SetOperator(
                        const_cast<Epetra_CrsMatrix *>(
                          &matrix.trilinos_matrix()));
                    }
                  Amesos factory;
                  direct_solver.reset(
                    factory.Create(direct_package.c_str(), *direct_problem));
                  AssertThrow(direct_solver != nullptr,
                              dealii::ExcMessage(direct_package +
                                                 " is not available in this "
                                                 "Trilinos"));
                  // Later factorisations of the step reuse the pivot
                  // sequence of its first (klu_refactor); Amesos falls back
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
                                "the symbolic factorisation of the tangent (" +
                                direct_package + ") failed"));
                }
              direct_problem->SetLHS(&x.trilinos_vector());
              direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
                static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
              // The symbolic analysis lives as long as the step's sparsity
              // pattern, also over several steps and coupling iterations
              // (make_step_sparsity_pattern()); the first factorisation
              // after each prepare_step() pivots anew, as with a new
              // solver, so that its result does not depend on the
              // preparations before.
              const auto refactorize = [this](const bool on) {
                Teuchos::ParameterList parameters;
                parameters.set("Refactorize", on);
                direct_solver->SetParameters(parameters);
              };
              if (mumps)
                *static_cast<OwningLinearProblem &>(*direct_problem).matrix =
                  matrix.trilinos_matrix();
              if (direct_pivoting)
                refactorize(false);
              const int factorised = direct_solver->NumericFactorization();
              if (direct_pivoting)
                refactorize(true);
              direct_pivoting = false;
              if (factorised != 0 && std::getenv("TALUS_DEBUG_SINGULAR"))
                for (const auto r : grid.locally_owned_dofs)
                  {
                    double rowsum = 0.;
                    for (auto it = matrix.begin(r); it != matrix.end(r); ++it)
                      rowsum += std::abs(it->value());
                    if (std::abs(matrix.diag_element(r)) < 1e-12 * rowsum ||
                        rowsum == 0.)
                      std::cerr
                        << "singular? row " << r << " diag "
                        << matrix.diag_element(r) << " rowsum " << rowsum
                        << " mass " << nodal_mass(r) << " constrained "
                        << constraints.is_constrained(r) << " at "
                        << owned_support_points[grid.locally_owned_dofs
                                                  .index_within_set(r)] +
                             0.5 * (grid.lower_corner - dealii::Point<dim>() +
                                    grid.upper_corner)
                        << " hanging "
                        << (has_hanging_nodes &&
                            hanging_constraints.is_constrained(r))
                        << std::endl;
                  }
              AssertThrow(factorised == 0,
                          dealii::ExcMessage(
                            "the factorisation of the tangent (" +
                            direct_package + ") failed with error code " +
                            std::to_string(factorised) +
                            " (a singular tangent?)"));
              const int solve_status = direct_solver->Solve();
              AssertThrow(solve_status == 0,
                          dealii::ExcMessage(
                            "the direct solve with the tangent (" +
                            direct_package + ") failed with error code " +
                            std::to_string(solve_status)));
            }
          constraints.distribute(x);
          return 1;
        }

      // The AMG hierarchy is built at the first Newton iteration of a step
      // and reused by the later ones (the tangent changes little); if the
      // Krylov solver fails with a reused hierarchy, it is rebuilt once.
      bool fresh = false;
      if (!preconditioner_built() || !reuse_preconditioner || !amg_current)
        {
          build_amg();
          amg_current = true;
          fresh       = true;
        }

      const auto krylov = [&](dealii::SolverControl &control) {
        x = 0.;
        const dealii::TrilinosWrappers::PreconditionBase &prec =
          preconditioner();
        if (linear_solver_type == "CG")
          {
            dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> solver(
              control);
            solver.solve(matrix, x, b, prec);
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
            data.max_n_tmp_vectors     = gmres_restart + 2;
            dealii::SolverGMRES<dealii::TrilinosWrappers::MPI::Vector> solver(
              control, data);
            solver.solve(matrix, x, b, prec);
          }
      };
      dealii::SolverControl control(max_linear_iterations,
                                    relative_tolerance * b.l2_norm());
      const bool debug = std::getenv("TALUS_DEBUG_LINEAR") != nullptr;
      if (debug)
        control.enable_history_data();
      try
        {
          try
            {
              krylov(control);
            }
          catch (const dealii::SolverControl::NoConvergence &)
            {
              if (fresh)
                throw;
              if (debug)
                print_linear_diagnostics(control, b, "reused preconditioner");
              build_amg();
              krylov(control);
            }
        }
      catch (const dealii::SolverControl::NoConvergence &)
        {
          if (debug)
            print_linear_diagnostics(control, b, "fresh preconditioner");
          throw;
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
        n_iterations += solve_with_tangent(z, t, linear_tolerance);
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
              factorisation_control,
              dealii::TrilinosWrappers::SolverDirect::AdditionalData(
                false, direct_package));
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
                (!preconditioner_built() || !reuse_preconditioner ||
                 !amg_current))
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
                this->preconditioner().vmult(dst, src);
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
          n_iterations += solve_with_tangent(x, residual, linear_tolerance);
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
          n_iterations += solve_with_tangent(z, t, linear_tolerance);
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


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                \
  template unsigned int MPMSolver<dim>::solve_linear(         \
    dealii::TrilinosWrappers::MPI::Vector &x, const double);  \
  template void MPMSolver<dim>::build_amg();                  \
  template bool MPMSolver<dim>::preconditioner_built() const; \
  template const dealii::TrilinosWrappers::PreconditionBase               & \
  MPMSolver<dim>::preconditioner() const;       \
  template void MPMSolver<dim>::print_linear_diagnostics(     \
    const dealii::SolverControl &,                            \
    const dealii::TrilinosWrappers::MPI::Vector &,            \
    const std::string &) const;                               \
  template unsigned int MPMSolver<dim>::solve_with_tangent(   \
    dealii::TrilinosWrappers::MPI::Vector       &x,           \
    const dealii::TrilinosWrappers::MPI::Vector &b,           \
    const double);                                            \
  template unsigned int MPMSolver<dim>::solve_saddle_point(   \
    dealii::TrilinosWrappers::MPI::Vector &x);

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
