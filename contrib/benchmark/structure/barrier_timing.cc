// Timing of the standard three-field barrier (BarrierBuilder) at a given net
// mesh size: time per Newton iteration of the static solves (form finding
// under gravity, then 20 kN on the middle field in 5 load steps with step
// cutting and the secant predictor) and per time step of the dynamics
// (Bossak-Newmark, lumped mass, the field load applied suddenly to the
// form-found state). Serial. Build: make barrier-timing; run:
//   barrier-timing H [N_STEPS] [DT] [STATIC_STEPS]
// H: net cell size [m] (cells per 5 m field: round(5/H); over the 3.55 m
// post length: round(3.55/H)); N_STEPS time steps of DT [s] (10, 5e-3);
// STATIC_STEPS load steps of the static field load (5; 0: skip it).
// Prints one line "key = value" per result.
// Parameters as tests/structure/barrier_field_load.prm (brakes F_a = 50 kN,
// so that no brake slides and the dynamic run can restart from the
// form-found state).

#include <talus/structure/barrier_builder.h>
#include <talus/structure/dynamic_solver.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/base/timer.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

using namespace dealii;
using namespace Talus::Structure;

int
main(int argc, char **argv)
{
  if (argc < 2)
    {
      std::cerr << "usage: barrier-timing H [N_STEPS] [DT] [STATIC_STEPS]\n";
      return 1;
    }
  const double       h        = std::atof(argv[1]);
  const unsigned int n_steps  = argc > 2 ? std::atoi(argv[2]) : 10;
  const double       dt       = argc > 3 ? std::atof(argv[3]) : 5e-3;
  const unsigned int n_static = argc > 4 ? std::atoi(argv[4]) : 5;
  if (!(h > 0.) || n_steps == 0 || !(dt > 0.))
    {
      std::cerr << "H and DT must be > 0, N_STEPS >= 1\n";
      return 1;
    }

  BarrierBuilder b;
  b.cells_per_field        = std::max(1l, std::lround(b.field_width / h));
  b.cells_over_height      = std::max(1l, std::lround(b.post_length() / h));
  b.net.material.thickness = 1e-3;
  b.net.material.set_isotropic(1e7, 0.3);
  b.net.material.prestress = Tensor<1, 3>({2e5, 5e5, 0.});
  b.net.density            = 7850.;
  b.brake_k                = 1e6;
  b.brake_Fa               = 5e4;
  b.brake_smax             = 1.;
  // 20 kN downslope on the middle field, scaled by the load factor.
  b.field_load = Tensor<1, 3>({0., -2e4, 0.});

  Timer     total;
  Structure s;
  b.build(s);
  s.gravity       = Tensor<1, 3>({0., 0., -9.81});
  s.scale_gravity = false;
  for (const unsigned int n : b.post_heads)
    for (unsigned int c = 0; c < 3; ++c)
      s.prescribe(n, c);
  s.setup_system();
  StaticSolver solver(s);
  solver.setup();
  std::cout << "net_cell_size_m = " << h << "\nnet_cells = "
            << s.membrane_meshes[0]->triangulation.n_active_cells()
            << "\nnodes = " << s.n_nodes() << "\ndofs = " << s.n_dofs() << '\n';

  const auto check = [](const NewtonStatus &st, const std::string &what) {
    if (!st.converged)
      throw std::runtime_error(what + " did not converge: " + st.failure);
    return st.iterations;
  };
  // Form finding under pre-stress and gravity: heads held, then released.
  unsigned int form_newton = 0;
  Timer        timer;
  form_newton += check(solver.solve(0.), "stage 1");
  {
    const Vector<double> u = solver.displacement;
    for (const unsigned int n : b.post_heads)
      for (unsigned int c = 0; c < 3; ++c)
        s.release(n, c);
    s.setup_system();
    solver.setup();
    solver.displacement = u;
  }
  form_newton += check(solver.solve(0.), "stage 2");
  timer.stop();
  std::cout << "form_finding_newton_iterations = " << form_newton
            << "\nform_finding_wall_s = " << timer.wall_time()
            << "\ntime_per_form_finding_newton_iteration_s = "
            << timer.wall_time() / form_newton << '\n';
  const Vector<double> u_formed = solver.displacement;

  // Static: the field load in 5 load steps, each cut in halves when
  // Newton fails (StaticSolver::solve_with_cuts).
  solver.max_step_cuts = 8;
  solver.predictor     = "secant";
  unsigned int newton = 0, converged_steps = 0;
  timer.restart();
  for (unsigned int k = 1; k <= n_static; ++k)
    {
      const auto st =
        solver.solve_with_cuts((k - 1.) / n_static, double(k) / n_static);
      newton += st.iterations;
      if (!st.converged)
        break; // reported; the time per iteration is still measured
      ++converged_steps;
    }
  timer.stop();
  std::cout << "static_field_load_converged_steps = " << converged_steps
            << " of " << n_static
            << "\nstatic_field_load_newton_iterations = " << newton
            << "\nstatic_field_load_wall_s = " << timer.wall_time() << '\n';
  if (newton > 0)
    std::cout << "time_per_static_newton_iteration_s = "
              << timer.wall_time() / newton << '\n';

  // Assembly alone (residual and tangent), for the split.
  {
    Vector<double>       r;
    SparseMatrix<double> K(s.get_sparsity_pattern());
    Timer                t;
    for (unsigned int k = 0; k < 5; ++k)
      s.assemble(solver.displacement, 1., r, &K);
    t.stop();
    std::cout << "assembly_with_tangent_s = " << t.wall_time() / 5 << '\n';
  }

  // Dynamics from the form-found state at rest, the field load applied
  // suddenly (load factor 1); the external nodal forces a coupling would set
  // before every step are set to zero here.
  solver.displacement = u_formed;
  DynamicSolver dynamics(s, solver);
  dynamics.enabled = true;
  dynamics.initialize();
  unsigned int dyn_newton = 0;
  Timer        dyn_timer;
  for (unsigned int k = 0; k < n_steps; ++k)
    {
      s.clear_external_forces();
      dyn_newton += check(dynamics.solve_step(dt), "time step");
      dynamics.commit_step();
    }
  dyn_timer.stop();
  std::cout << "time_steps = " << n_steps << "\ntime_step_s = " << dt
            << "\nnewton_iterations_per_step = " << double(dyn_newton) / n_steps
            << "\ntime_per_step_s = " << dyn_timer.wall_time() / n_steps
            << "\ntime_per_dynamic_newton_iteration_s = "
            << dyn_timer.wall_time() / dyn_newton
            << "\ntotal_wall_s = " << total.wall_time() << '\n';
  return 0;
}
