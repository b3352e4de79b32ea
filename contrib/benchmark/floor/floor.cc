// deal.II "floor" for contrib/benchmark/run_benchmarks.sh.
//
// What plain deal.II does on this machine for the work of one Newton
// iteration of the Talus benchmark, without any MPM bookkeeping: a block of
// N^dim Q1 cells (the block of the benchmark without the empty margin) with a
// fixed base, 2^dim Gauss points per cell (= the material points of the
// benchmark), linear elasticity plus a lumped Newmark mass term,
//   1. assembly of matrix and right-hand side (FEValues, step-8 style),
//   2. Trilinos ML AMG setup (the AdditionalData Talus uses),
//   3. CG to a relative residual of 1e-10 (Talus's default).
// Each stage is repeated 'repeats' times; the minimum wall time of each stage
// is printed on one line starting with "FLOOR".
//
//   usage: mpirun -np P talus-floor <dim> <N> [repeats = 3]
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/vector_tools.h>

#include <deal.II/distributed/tria.h>

#include <algorithm>
#include <iostream>
#include <limits>

using namespace dealii;

template <int dim>
int
run(const unsigned int N, const unsigned int repeats)
{
  const MPI_Comm     comm    = MPI_COMM_WORLD;
  const bool         root    = Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);

  parallel::distributed::Triangulation<dim> tria(comm);
  std::vector<unsigned int>                 subdivisions(dim, N);
  Point<dim>                                upper;
  for (unsigned int d = 0; d < dim; ++d)
    upper[d] = 1.;
  GridGenerator::subdivided_hyper_rectangle(
    tria, subdivisions, Point<dim>(), upper, true);

  const FESystem<dim> fe(FE_Q<dim>(1), dim);
  DoFHandler<dim>     dof_handler(tria);
  dof_handler.distribute_dofs(fe);
  const IndexSet owned = dof_handler.locally_owned_dofs();
  IndexSet       relevant;
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

  AffineConstraints<double> constraints(relevant);
  VectorTools::interpolate_boundary_values(dof_handler,
                                           2 * (dim - 1),
                                           Functions::ZeroFunction<dim>(dim),
                                           constraints);
  constraints.close();

  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  TrilinosWrappers::SparseMatrix matrix;
  matrix.reinit(owned, owned, dsp, comm);
  TrilinosWrappers::MPI::Vector rhs(owned, comm), x(owned, comm);

  // Benchmark material and step: E = 1e6, nu = 0.3, rho = 1000, dt = 0.01,
  // Newmark beta = 1/4 (mass factor 1 / (beta dt^2)).
  const double E = 1e6, nu = 0.3, rho = 1000., dt = 0.01;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu     = E / (2 * (1 + nu));
  const double c_mass = 1. / (0.25 * dt * dt);

  const QGauss<dim>  quadrature(2);
  FEValues<dim>      fe_values(fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
  const unsigned int dofs_per_cell = fe.n_dofs_per_cell();
  const unsigned int n_q           = quadrature.size();
  FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
  Vector<double>     cell_rhs(dofs_per_cell);
  std::vector<types::global_dof_index> dof_indices(dofs_per_cell);

  std::vector<std::vector<bool>> constant_modes;
  DoFTools::extract_constant_modes(dof_handler,
                                   ComponentMask(dim, true),
                                   constant_modes);

  double       t_assembly = std::numeric_limits<double>::max();
  double       t_amg      = t_assembly;
  double       t_cg       = t_assembly;
  unsigned int cg_its     = 0;
  Timer        timer(comm, true);

  for (unsigned int r = 0; r < repeats; ++r)
    {
      // 1. Assembly.
      timer.restart();
      matrix = 0.;
      rhs    = 0.;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_matrix = 0.;
            cell_rhs    = 0.;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const double JxW = fe_values.JxW(q);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    const unsigned int ci =
                      fe.system_to_component_index(i).first;
                    const Tensor<1, dim> gi = fe_values.shape_grad(i, q);
                    const double         Ni = fe_values.shape_value(i, q);
                    for (unsigned int j = 0; j < dofs_per_cell; ++j)
                      {
                        const unsigned int cj =
                          fe.system_to_component_index(j).first;
                        const Tensor<1, dim> gj = fe_values.shape_grad(j, q);
                        double               k =
                          gi[cj] * gj[ci] * mu + gi[ci] * gj[cj] * lambda;
                        if (ci == cj)
                          k += mu * (gi * gj);
                        cell_matrix(i, j) += k * JxW;
                      }
                    // lumped mass (row sum of N_i N_j = N_i)
                    cell_matrix(i, i) += c_mass * rho * Ni * JxW;
                    if (ci == dim - 1)
                      cell_rhs(i) -= 9.81 * rho * Ni * JxW;
                  }
              }
            cell->get_dof_indices(dof_indices);
            constraints.distribute_local_to_global(
              cell_matrix, cell_rhs, dof_indices, matrix, rhs);
          }
      matrix.compress(VectorOperation::add);
      rhs.compress(VectorOperation::add);
      t_assembly = std::min(t_assembly, timer.wall_time());

      // 2. AMG setup (as MPMSolver::solve_linear).
      timer.restart();
      TrilinosWrappers::PreconditionAMG                 amg;
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.constant_modes        = constant_modes;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      amg.initialize(matrix, data);
      t_amg = std::min(t_amg, timer.wall_time());

      // 3. CG.
      timer.restart();
      x = 0.;
      SolverControl control(2000, 1e-10 * rhs.l2_norm());
      SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
      cg.solve(matrix, x, rhs, amg);
      constraints.distribute(x);
      t_cg   = std::min(t_cg, timer.wall_time());
      cg_its = control.last_step();
    }

  if (root)
    std::cout << "FLOOR dim=" << dim << " N=" << N << " ranks=" << n_ranks
              << " cells=" << tria.n_global_active_cells()
              << " qpoints=" << tria.n_global_active_cells() * n_q
              << " dofs=" << dof_handler.n_dofs()
              << " assembly_s=" << t_assembly << " amg_setup_s=" << t_amg
              << " cg_s=" << t_cg << " cg_its=" << cg_its << std::endl;
  return 0;
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 3)
    {
      std::cerr << "usage: talus-floor <dim> <N> [repeats]\n";
      return 2;
    }
  const unsigned int dim     = std::stoi(argv[1]);
  const unsigned int N       = std::stoi(argv[2]);
  const unsigned int repeats = argc > 3 ? std::stoi(argv[3]) : 3;
  return dim == 2 ? run<2>(N, repeats) : run<3>(N, repeats);
}
