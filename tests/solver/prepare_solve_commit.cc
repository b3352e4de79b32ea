// The sub-solver contract the coupling relies on (doc/architecture.md):
//  1. solve_step() has no side effect on the material points: solving the
//     same step twice gives the same Newton history and the same result;
//  2. save_state() / restore_state() bring back the last accepted step:
//     after commit + restore, redoing the step reproduces the first commit.
// Problem: a neo-Hookean block dropped on a fixed floor (nonlinear, 2D).
#include <talus/base/input.h>
#include <talus/base/time_control.h>
#include <talus/materials/constitutive_model.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fstream>
#include <iomanip>
#include <sstream>

using namespace dealii;

namespace
{
  std::vector<Point<2>>
  positions(const Talus::MPM::MaterialPoints<2> &points)
  {
    std::vector<Point<2>> x;
    for (const auto &p : points.particle_handler())
      x.push_back(p.get_location());
    return x;
  }

  double
  max_distance(const std::vector<Point<2>> &a, const std::vector<Point<2>> &b)
  {
    double d = 0.;
    for (unsigned int i = 0; i < a.size(); ++i)
      d = std::max(d, a[i].distance(b[i]));
    return d;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");

  ParameterHandler prm;
  Talus::MPM::BackgroundGrid<2>::declare_parameters(prm);
  Talus::MPM::MaterialPoints<2>::declare_parameters(prm);
  Talus::Materials::declare_parameters(prm);
  Talus::MPM::MPMSolver<2>::declare_parameters(prm);
  prm.parse_input_from_string(R"(
subsection Background grid
  set upper corner = 2, 2
  set subdivisions = 8, 8
  set fixed boundaries = 2
end
subsection Body
  set lower corner = 0.5, 0
  set upper corner = 1.5, 1
end
subsection Material
  set model = neo-Hookean
  set Young's modulus = 1e5
end
subsection Solver
  set linear solver = direct
end
)");

  TimerOutput                   timer(MPI_COMM_WORLD,
                    out,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  Talus::MPM::BackgroundGrid<2> grid(MPI_COMM_WORLD);
  grid.parse_parameters_and_create(prm);
  const auto                    model = Talus::Materials::create_model(prm);
  Talus::MPM::MaterialPoints<2> points(grid);
  points.parse_parameters(prm);
  points.generate(1000., 0, [](const ArrayView<double> &) {});
  Talus::NewmarkBeta       newmark;
  Talus::MPM::MPMSolver<2> solver(grid, points, *model, newmark, timer);
  solver.parse_parameters(prm);
  solver.setup();
  solver.initialize_acceleration(0.);

  const double dt = 0.02;
  const auto   x0 = positions(points);

  // 1. Repeatable solve.
  solver.prepare_step(dt, dt);
  const auto first         = solver.solve_step();
  const auto x_after_solve = positions(points);
  const auto second        = solver.solve_step();
  out << "converged: " << first.converged << ' ' << second.converged << '\n'
      << "same Newton iterations: "
      << (first.iterations == second.iterations ? "yes" : "no") << '\n'
      << "same final residual (relative difference < 1e-12): "
      << (std::abs(first.residual - second.residual) <=
              1e-12 * std::max(first.residual, 1e-300) + 1e-300 ?
            "yes" :
            "no")
      << '\n'
      << "points untouched by solve_step: "
      << (max_distance(x0, x_after_solve) == 0. ? "yes" : "no") << '\n';

  // 2. Commit, restore, redo.
  points.save_state();
  solver.commit_step();
  const auto x_committed = positions(points);
  out << "points moved by the commit: "
      << (max_distance(x0, x_committed) > 1e-4 ? "yes" : "no") << '\n';
  points.restore_state();
  out << "restore_state brings the points back exactly: "
      << (max_distance(x0, positions(points)) == 0. ? "yes" : "no") << '\n';
  solver.prepare_step(dt, dt);
  const auto redo = solver.solve_step();
  solver.commit_step();
  out << "redone step converged: " << redo.converged << '\n'
      << "redone step equals the first commit (max distance < 1e-14 m): "
      << (max_distance(x_committed, positions(points)) < 1e-14 ? "yes" : "no")
      << '\n';
}
