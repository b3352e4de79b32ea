// The contract of MPMProblem that the partitioned coupling relies on
// (issue 36, doc/architecture.md), on inputs of the test suite that cover
// every friction and contact option: grid Coulomb friction with the
// contact states guessed from the previous step (stick and slide), boundary
// particles with penalty, augmented Lagrangian, Lagrange multipliers and
// Nitsche, and material-point contact. Each input runs a few steps (so that
// the contacts are closed and their states carry history), then:
//  (a) the boundary-particle reactions read after solve_step() equal, to
//      the bit, the `reaction` property that commit_step() writes;
//  (b) prepare_step() + solve_step() repeated from the same committed
//      state give bitwise identical Newton histories and reactions, also
//      after a failed (too large) attempt in between;
//  (c) save_state(), a committed step, restore_state(), the same step
//      again: the committed state (every property of every material point
//      and boundary particle, the energy accounts) is bitwise identical.
//  (d) the coupling's re-preparation after a move of the boundaries only
//      (update_boundary_displacement(), which keeps the P2G and the
//      pattern): prepare_step() + solve_step() with one prescribed
//      displacement of boundary 0 (set from outside, as the coupling's
//      interface), then the displacement changed,
//      update_boundary_displacement() + solve_step() gives bitwise the
//      Newton history and reactions of prepare_step() + solve_step() with
//      the changed displacement; without boundaries, the same step again.
#include <talus/app/simulation.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/mpm/mpm_problem.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fstream>
#include <map>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  using Problem = Talus::MPM::MPMProblem<2>;

  /** Every location and property of the points and boundary particles. */
  std::vector<double>
  committed_state(const Problem &problem)
  {
    std::vector<double> s;
    for (const auto *handler : {&problem.points().particle_handler(),
                                &problem.boundaries().particle_handler()})
      for (const auto &p : *handler)
        {
          s.push_back(p.get_id());
          for (unsigned int d = 0; d < 2; ++d)
            s.push_back(p.get_location()[d]);
          for (const double v : p.get_properties())
            s.push_back(v);
        }
    const auto d = problem.diagnostics();
    for (const double v : {d.kinetic_energy,
                           d.strain_energy,
                           d.gravitational_energy,
                           d.plastic_dissipation,
                           d.friction_dissipation,
                           d.reset_dissipation,
                           d.transfer_dissipation,
                           d.grid_kinetic_energy})
      s.push_back(v);
    return s;
  }

  std::map<types::particle_index, Tensor<1, 2>>
  reactions(const Problem &problem)
  {
    std::map<types::particle_index, Tensor<1, 2>> r;
    for (const auto &[id, f] : problem.solver().boundary_reactions())
      r[id] = f;
    return r;
  }

  std::map<types::particle_index, Tensor<1, 2>>
  committed_reactions(const Problem &problem)
  {
    using BP = Talus::Boundaries::BoundaryParticleProperties<2>;
    std::map<types::particle_index, Tensor<1, 2>> r;
    for (const auto &p : problem.boundaries().particle_handler())
      {
        Tensor<1, 2> f;
        for (unsigned int d = 0; d < 2; ++d)
          f[d] = p.get_properties()[BP::reaction + d];
        if (f.norm() > 0.)
          r[p.get_id()] = f;
      }
    return r;
  }

  /** Drop the zero reactions (particles not pressed). */
  std::map<types::particle_index, Tensor<1, 2>>
  nonzero(const std::map<types::particle_index, Tensor<1, 2>> &r)
  {
    std::map<types::particle_index, Tensor<1, 2>> n;
    for (const auto &[id, f] : r)
      if (f.norm() > 0.)
        n[id] = f;
    return n;
  }

  const char *
  yes(const bool b)
  {
    return b ? "yes" : "NO";
  }

  void
  check(const std::string &file, const unsigned int n_steps, std::ostream &out)
  {
    ParameterHandler prm;
    Talus::Simulation<2>::declare_parameters(prm);
    prm.parse_input(file);

    TimerOutput        timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    Talus::TimeControl time_control;
    time_control.parse_parameters(prm);
    Problem problem(MPI_COMM_WORLD, time_control.newmark, timer);
    problem.parse_parameters(prm);
    problem.setup();
    problem.initialize(0.);

    const double dt = time_control.initial_dt;
    double       t  = 0.;
    for (unsigned int s = 0; s < n_steps; ++s, t += dt)
      {
        problem.prepare_step(t + dt, dt);
        const auto r = problem.solve_step();
        AssertThrow(r.converged, ExcMessage("step not converged"));
        problem.commit_step();
      }
    problem.save_state();
    const auto before = committed_state(problem);

    // (b) repeated solves from the same committed state
    problem.prepare_step(t + dt, dt);
    const auto first           = problem.solve_step();
    const auto first_reactions = reactions(problem);
    // a far too large attempt in between (it may or may not converge)
    problem.prepare_step(t + 50 * dt, 50 * dt);
    problem.solve_step();
    problem.prepare_step(t + dt, dt);
    const auto second = problem.solve_step();
    const bool same_solve =
      first.converged && second.converged &&
      first.iterations == second.iterations &&
      first.residual == second.residual &&
      first.linear_iterations == second.linear_iterations &&
      first_reactions == reactions(problem);

    // (a) trial reactions = committed reactions
    const auto trial = nonzero(reactions(problem));
    problem.commit_step();
    const auto after_first     = committed_state(problem);
    const bool with_boundaries = !problem.boundaries().empty();
    const bool same_reactions  = trial == committed_reactions(problem);

    // (c) restore, the same step again
    problem.restore_state();
    const bool restored = committed_state(problem) == before;
    problem.prepare_step(t + dt, dt);
    problem.solve_step();
    problem.commit_step();
    const bool same_commit = committed_state(problem) == after_first;

    // (d) re-preparation after a move of the boundary (last: it makes
    // boundary 0 moving)
    Tensor<1, 2> shift;
    if (with_boundaries)
      problem.boundaries().set_displacement(
        0, [&](const Point<2> &, const double time) {
          return time > t + 0.5 * dt ? shift : Tensor<1, 2>();
        });
    const auto solve_with = [&](const bool update) {
      if (update)
        problem.update_boundary_displacement();
      else
        problem.prepare_step(t + dt, dt);
      const auto r = problem.solve_step();
      return std::make_pair(r, reactions(problem));
    };
    t += dt; // the step after the redone one
    problem.prepare_step(t + dt, dt);
    problem.solve_step();
    shift[0]            = 2e-4;
    shift[1]            = -1e-4;
    const auto updated  = solve_with(true);
    const auto prepared = solve_with(false);
    const bool same_move =
      updated.first.converged && prepared.first.converged &&
      updated.first.iterations == prepared.first.iterations &&
      updated.first.residual == prepared.first.residual &&
      updated.first.linear_iterations == prepared.first.linear_iterations &&
      updated.second == prepared.second;

    const std::string name = file.substr(file.find("tests/") + 6);
    out << name << ": " << trial.size() << " pressed boundary particles\n";
    if (with_boundaries)
      out << "  (a) reactions after solve_step = after commit_step: "
          << yes(same_reactions) << '\n';
    out << "  (b) repeated solve bitwise identical: " << yes(same_solve) << '\n'
        << "  (c) restore_state gives the saved state: " << yes(restored)
        << ", the redone step equals the first commit: " << yes(same_commit)
        << '\n'
        << "  (d) update_boundary_displacement bitwise as prepare_step: "
        << yes(same_move) << '\n';
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");
  // the inputs of the suite, next to this file's folder
  const std::string here(__FILE__);
  const std::string tests = here.substr(0, here.rfind("/solver/")) + '/';
  // grid friction: the states of the friction nodes are committed state
  for (const std::string f : {"mpm/incline_slide_mu01_guess_previous.prm",
                              "mpm/incline_stick_guess_previous.prm"})
    check(tests + f, 30, out);
  for (const std::string f :
       {"boundaries/incline_rotated_30_mu01.prm",
        "boundaries/incline_rotated_30_stick.prm",
        "boundaries/incline_rotated_30_mu01_augmented_factor10.prm",
        "boundaries/incline_rotated_30_mu01_lagrange.prm",
        "boundaries/incline_rotated_30_mu01_nitsche.prm",
        "boundaries/incline_rotated_30_mu01_per_cell.prm",
        "boundaries/incline_rotated_30_mu01_points.prm"})
    check(tests + f, 10, out);
}
