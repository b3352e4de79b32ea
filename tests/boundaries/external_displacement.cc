// A boundary whose displacement is set from outside, as the partitioned
// coupling will set the net's displacement (doc/architecture.md): the block
// bonded to a line rotated by 30 degrees against the grid of
// moving_line_bonded_block.prm, but the line's motion
// u_bar = A (1 - cos omega t) along the line (A = 0.05 m, omega = 2.5 pi
// 1/s) comes from
// BoundaryParticles::set_displacement(). Every step runs two "coupling
// iterations": a first guess (the boundary held at its start position) and
// the right motion, each as prepare_step() + solve_step(); only the last
// one is committed. Checks:
//  - the points next to the boundary start with its acceleration
//    A omega^2 = 3.084 m/s^2 (largest point acceleration within 2 %
//    below it, interpolated from the nodes);
//  - the points follow the line as a rigid body (error < 1e-3 m, as the
//    .prm test with the parsed function);
//  - the committed step does not depend on the discarded first iteration:
//    the same run without it gives the same positions (< 1e-12 m);
//  - the line handed over as a Triangulation<1, 2> of the program
//    (geometry = external, BoundaryParticles::set_surface(), as the
//    structure coupling will hand over the net) gives the positions of the
//    'line' boundary (< 1e-12 m).
#include <talus/base/input.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/materials/constitutive_model.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>

using namespace dealii;

namespace
{
  const double A     = 0.05;
  const double omega = 2.5 * numbers::PI; // period 0.8 s
  const double c = std::cos(numbers::PI / 6.), s = std::sin(numbers::PI / 6.);

  Tensor<1, 2>
  motion(const double t)
  {
    Tensor<1, 2> u;
    u[0] = A * (1. - std::cos(omega * t)) * c;
    u[1] = A * (1. - std::cos(omega * t)) * s;
    return u;
  }

  const char *input = R"(
subsection Background grid
  set lower corner = 0, 0
  set upper corner = 1.2, 1
  set subdivisions = 24, 20
end
subsection Body
  set geometry = polygon
  set vertices = 0.3866025404, 0.187; 0.7330127019, 0.387; 0.6330127019, 0.5602050808; 0.2866025404, 0.3602050808
  set points per cell per direction = 2
end
subsection Material
  set model = neo-Hookean
  set density = 2000
  set Young's modulus = 1e7
  set Poisson's ratio = 0.3
end
subsection Boundary particles
  subsection Boundary 1
    set geometry = line
    set name = conveyor
    set vertices = 0.1267949192, 0.037; 1.0, 0.5412
    set condition = fixed
  end
end
subsection Solver
  set gravity = 0, 0
  set linear solver = direct
end
)";

  // Run 25 steps of 0.01 s; returns the final positions and writes the
  // largest error against the rigid motion to max_error.
  std::map<types::particle_index, Point<2>>
  run(const bool with_first_guess,
      double    &max_error,
      bool      &all_converged,
      double    &largest_initial_acceleration,
      const bool external_surface = false)
  {
    largest_initial_acceleration = 0.;
    ParameterHandler prm;
    Talus::MPM::BackgroundGrid<2>::declare_parameters(prm);
    Talus::MPM::MaterialPoints<2>::declare_parameters(prm);
    Talus::Materials::declare_parameters(prm);
    Talus::MPM::MPMSolver<2>::declare_parameters(prm);
    Talus::Boundaries::BoundaryParticles<2>::declare_parameters(prm);
    prm.parse_input_from_string(input);
    if (external_surface)
      {
        prm.enter_subsection("Boundary particles");
        prm.enter_subsection("Boundary 1");
        prm.set("geometry", "external");
        prm.leave_subsection();
        prm.leave_subsection();
      }

    TimerOutput                   timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    Talus::MPM::BackgroundGrid<2> grid(MPI_COMM_WORLD);
    grid.parse_parameters_and_create(prm);
    const auto                    model = Talus::Materials::create_model(prm);
    Talus::MPM::MaterialPoints<2> points(grid);
    points.parse_parameters(prm);
    points.generate(2000., 0, [](const ArrayView<double> &) {});
    Talus::NewmarkBeta       newmark(0.3025, 0.6);
    Talus::MPM::MPMSolver<2> solver(grid, points, *model, newmark, timer);
    solver.parse_parameters(prm);
    solver.setup();
    Talus::Boundaries::BoundaryParticles<2> boundaries(grid);
    boundaries.parse_parameters(prm);
    if (external_surface)
      {
        // the conveyor line as the program's own codimension-one mesh
        Triangulation<1, 2>         line;
        const std::vector<Point<2>> vertices = {Point<2>(0.1267949192, 0.037),
                                                Point<2>(1.0, 0.5412)};
        std::vector<CellData<1>>    cells(1);
        cells[0].vertices = {0, 1};
        line.create_triangulation(vertices, cells, SubCellData());
        boundaries.set_surface(0, line);
      }
    boundaries.generate(model->p_wave_modulus());
    solver.attach_boundary_particles(boundaries);

    // points are identified by their id: the handler reorders them
    std::map<types::particle_index, Point<2>> x0;
    for (const auto &p : points.particle_handler())
      x0[p.get_id()] = p.get_location();

    // the coupling's current guess of the boundary motion at the end of
    // the step (linear in time within the step)
    double       t_n = 0., dt = 0.01;
    bool         stepping = false;
    Tensor<1, 2> u_start, u_end;
    boundaries.set_displacement(
      0, [&](const Point<2> &, const double t) -> Tensor<1, 2> {
        if (!stepping || t <= t_n)
          return motion(t); // before the first step, or committed history
        return u_start + (t - t_n) / dt * (u_end - u_start);
      });
    solver.initialize_acceleration(0.);
    // At rest and stress free, only the points next to the boundary start
    // with its acceleration A omega^2 (the rest of the block follows
    // through the stresses): the largest initial point acceleration.
    {
      using P = Talus::MPM::MaterialPointProperties<2>;
      for (const auto &p : points.particle_handler())
        {
          Tensor<1, 2> a;
          for (unsigned int d = 0; d < 2; ++d)
            a[d] = p.get_properties()[P::acceleration + d];
          largest_initial_acceleration =
            std::max(largest_initial_acceleration, a.norm());
        }
    }
    stepping = true;

    all_converged = true;
    max_error     = 0.;
    for (unsigned int step = 0; step < 25; ++step)
      {
        u_start = motion(t_n);
        if (with_first_guess)
          {
            u_end = u_start; // first guess: the boundary stays
            solver.prepare_step(t_n + dt, dt);
            all_converged = solver.solve_step().converged && all_converged;
          }
        u_end = motion(t_n + dt);
        solver.prepare_step(t_n + dt, dt);
        all_converged = solver.solve_step().converged && all_converged;
        solver.commit_step();
        t_n += dt;
        for (const auto &p : points.particle_handler())
          max_error =
            std::max(max_error,
                     (p.get_location() - x0[p.get_id()] - motion(t_n)).norm());
      }
    std::map<types::particle_index, Point<2>> x;
    for (const auto &p : points.particle_handler())
      x[p.get_id()] = p.get_location();
    return x;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");

  double     error_iterated, error_direct, a_max, a_max_direct;
  bool       converged_iterated, converged_direct;
  const auto x_iterated = run(true, error_iterated, converged_iterated, a_max);
  const auto x_direct =
    run(false, error_direct, converged_direct, a_max_direct);
  const double a_bar      = A * omega * omega;
  double       difference = 0.;
  for (const auto &[id, x] : x_direct)
    difference = std::max(difference, x.distance(x_iterated.at(id)));
  double     error_external, a_max_external;
  bool       converged_external;
  const auto x_external =
    run(false, error_external, converged_external, a_max_external, true);
  double difference_external = 0.;
  for (const auto &[id, x] : x_direct)
    difference_external =
      std::max(difference_external, x.distance(x_external.at(id)));

  out << "largest initial point acceleration within 2 % below A omega^2 "
         "(and not above it): "
      << (a_max > 0.98 * a_bar && a_max < 1.001 * a_bar ? "yes" : "no") << '\n'
      << "every solve converged: "
      << (converged_iterated && converged_direct ? "yes" : "no") << '\n'
      << "largest error against the rigid motion below 1e-3 m: "
      << (error_iterated < 1e-3 ? "yes" : "no") << '\n'
      << "committed steps independent of the discarded iteration "
         "(< 1e-12 m): "
      << (difference < 1e-12 ? "yes" : "no") << '\n'
      << "the line handed over as a Triangulation<1, 2> (geometry = "
         "external) gives the same positions (< 1e-12 m): "
      << (converged_external && difference_external < 1e-12 ? "yes" : "no")
      << '\n';
  std::cout << "largest initial acceleration " << a_max << " (A omega^2 "
            << a_bar << "), largest error " << error_iterated << " m (direct "
            << error_direct << " m), difference " << difference
            << " m, external surface against line " << difference_external
            << " m" << std::endl;
}
