// The sub-solver contract of StructureProblem (doc/architecture.md, "The
// structure module"), on a bar of one Brake element (0,0,0)-(1,0,0): node 0
// held, node 1 free along x only, pulled by an interface force F along x
// (set_interface_forces, per global DoF). Brake: k_e = 1e6 N/m, F_a = 1 kN,
// H = 1e5 N/m, mass 2 kg/m (lumped: m = 1 kg at node 1).
//  - static mode, closed form of the brake: elongation
//    d = (F - F_a)/H + F/k_e, stroke s = (F - F_a)/H;
//    solve_step() repeated (also after a solve with other forces) gives
//    bitwise the same displacement; save_state(), a step with a larger
//    force + commit_step(), restore_state() gives back the saved stroke and
//    displacement, and the same step again the same result, bitwise;
//    dissipated energy D = F_a s + H s^2/2 (StructureProblem::
//    dissipated_energy()), restored with the state
//  - dynamic mode (Bossak-Newmark, alpha = 0): a force below F_a applied
//    suddenly: a spring-mass oscillation, first maximum 2F/k_e at
//    t = pi sqrt(m/k_e); a force above F_a: the first maximum u_max from the
//    work balance F u_max = int_0^u_max N du over the elastic-plastic
//    force-elongation curve (u_a = F_a/k_e, then the series stiffness
//    k_ep = k_e H/(k_e + H)); repeatability of solve_step() and
//    save/step/restore/step with the brake stroke as history, bitwise.

#include <talus/structure/line_elements.h>
#include <talus/structure/structure_problem.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>

using namespace dealii;
using namespace Talus::Structure;

namespace
{
  std::ofstream out("output");

  constexpr double k_e = 1e6, F_a = 1e3, H = 1e5, line_mass = 2.;

  /** The brake bar. */
  class BrakeBar : public StructureBuilder
  {
  public:
    void
    build(Structure &s, const unsigned int) override
    {
      auto brake              = std::make_shared<Brake>();
      brake->stiffness        = k_e;
      brake->activation_force = F_a;
      brake->hardening        = H;
      brake->mass             = line_mass;
      auto &tria              = s.add_line_mesh("brake", brake).triangulation;
      std::vector<Point<3>>    x = {Point<3>(0, 0, 0), Point<3>(1, 0, 0)};
      std::vector<CellData<1>> cells(1);
      cells[0].vertices = {0, 1};
      tria.create_triangulation(x, cells, SubCellData());
      s.setup_dofs();
      const unsigned int a = s.find_node(Point<3>(0, 0, 0), 1e-9);
      const unsigned int b = s.find_node(Point<3>(1, 0, 0), 1e-9);
      for (unsigned int c = 0; c < 3; ++c)
        s.prescribe(a, c);
      s.prescribe(b, 1);
      s.prescribe(b, 2);
    }
  };


  /** Set up a problem in static or dynamic mode (alpha = 0). */
  void
  setup(StructureProblem &problem, BrakeBar &bar, const bool dynamic)
  {
    ParameterHandler prm;
    StructureProblem::declare_parameters(prm);
    prm.enter_subsection("Dynamics");
    prm.set("dynamic", dynamic ? "true" : "false");
    prm.set("time step", "1e-5");
    prm.leave_subsection();
    problem.build(bar);
    problem.parse_solver_parameters(prm);
    problem.parse_dynamics_parameters(prm);
    problem.setup_solvers(bar);
  }


  types::global_dof_index
  free_dof(const StructureProblem &problem)
  {
    const Structure &s = problem.get_structure();
    return s.node_dof(s.find_node(Point<3>(1, 0, 0), 1e-9), 0);
  }


  void
  set_force(StructureProblem &problem, const double F)
  {
    Vector<double> f(problem.get_structure().n_dofs());
    f[free_dof(problem)] = F;
    problem.set_interface_forces(f);
  }


  double
  stroke(const StructureProblem &problem)
  {
    return problem.get_structure().line_meshes[0]->state[0].plastic;
  }


  bool
  same(const Vector<double> &a, const Vector<double> &b)
  {
    if (a.size() != b.size())
      return false;
    for (unsigned int i = 0; i < a.size(); ++i)
      if (a[i] != b[i]) // bitwise identity is the contract
        return false;
    return true;
  }


  const char *
  yes(const bool b)
  {
    return b ? "yes" : "no";
  }


  /** Compare with the closed form (relative error below 1e-3); prints the
   * closed form and the verdict, not the computed value. */
  void
  check(const std::string &what, const double computed, const double exact)
  {
    const double error = std::abs(computed - exact) / std::abs(exact);
    out << what << ": closed form " << std::setprecision(6) << exact
        << ", computed within 1e-3: " << yes(error < 1e-3) << '\n';
  }


  void
  static_mode()
  {
    out << "static mode\n";
    StructureProblem problem;
    BrakeBar         bar;
    setup(problem, bar, false);
    problem.initialize();
    const unsigned int i = free_dof(problem);

    set_force(problem, 2e3);
    problem.prepare_step(0., 1.);
    const auto status = problem.solve_step();
    out << "  converged: " << yes(status.converged) << '\n';
    const Vector<double> u1 = problem.displacement();
    check("  elongation at F = 2 kN [m]", u1[i], (2e3 - F_a) / H + 2e3 / k_e);
    problem.solve_step();
    out << "  solve_step again: identical: "
        << yes(same(u1, problem.displacement())) << '\n';
    set_force(problem, 1.5e3);
    problem.solve_step();
    const bool other = !same(u1, problem.displacement());
    set_force(problem, 2e3);
    problem.solve_step();
    out << "  after a solve with F = 1.5 kN: other displacement: " << yes(other)
        << ", F = 2 kN again: identical: "
        << yes(same(u1, problem.displacement())) << '\n';
    out << "  committed stroke before commit_step: " << stroke(problem)
        << " m\n";
    problem.commit_step();
    check("  stroke after commit_step [m]", stroke(problem), (2e3 - F_a) / H);
    {
      const double s = (2e3 - F_a) / H;
      check("  dissipated energy F_a s + H s^2/2 [J]",
            problem.dissipated_energy(),
            F_a * s + 0.5 * H * s * s);
    }

    const double s_saved = stroke(problem);
    const double D_saved = problem.dissipated_energy();
    problem.save_state();
    set_force(problem, 3e3);
    problem.prepare_step(1., 1.);
    problem.solve_step();
    problem.commit_step();
    const Vector<double> u2 = problem.displacement();
    check("  elongation at F = 3 kN [m]", u2[i], (3e3 - F_a) / H + 3e3 / k_e);
    check("  stroke at F = 3 kN [m]", stroke(problem), (3e3 - F_a) / H);
    {
      const double s = (3e3 - F_a) / H;
      check("  dissipated energy at F = 3 kN [J]",
            problem.dissipated_energy(),
            F_a * s + 0.5 * H * s * s);
    }
    problem.restore_state();
    out << "  restore_state: dissipated energy as saved: "
        << yes(problem.dissipated_energy() == D_saved) << '\n';
    out << "  restore_state: displacement as saved: "
        << yes(same(u1, problem.displacement()))
        << ", stroke as saved: " << yes(stroke(problem) == s_saved) << ", time "
        << problem.time() << '\n';
    problem.prepare_step(1., 1.);
    problem.solve_step();
    problem.commit_step();
    out << "  the same step again: identical: "
        << yes(same(u2, problem.displacement())) << '\n';
  }


  /** Run the dynamic bar under a sudden force F to the first maximum of
   * the elongation; returns it and its time. */
  std::pair<double, double>
  first_maximum(const double F)
  {
    StructureProblem problem;
    BrakeBar         bar;
    setup(problem, bar, true);
    set_force(problem, F);
    problem.initialize();
    const unsigned int i  = free_dof(problem);
    const double       dt = 1e-5;
    double             t = 0., u_max = 0., t_max = 0.;
    for (unsigned int step = 0; step < 100000; ++step)
      {
        problem.prepare_step(t, dt);
        const auto status = problem.solve_step();
        AssertThrow(status.converged, ExcMessage(status.failure));
        problem.commit_step();
        t = problem.time();
        if (problem.displacement()[i] > u_max)
          {
            u_max = problem.displacement()[i];
            t_max = t;
          }
        if (problem.velocity()[i] < 0.)
          break;
      }
    return {u_max, t_max};
  }


  void
  dynamic_mode()
  {
    out << "dynamic mode (Bossak-Newmark, alpha = 0, dt = 1e-5 s)\n";
    const double m = 0.5 * line_mass;
    {
      const auto [u_max, t_max] = first_maximum(500.);
      check("  elastic (F = 0.5 kN): first maximum [m]",
            u_max,
            2. * 500. / k_e);
      out << "  time of the first maximum: pi sqrt(m/k_e) = "
          << std::setprecision(6) << M_PI * std::sqrt(m / k_e)
          << " s, computed within two steps: "
          << yes(std::abs(t_max - M_PI * std::sqrt(m / k_e)) < 2e-5) << '\n';
    }
    {
      const double F = 2e3, u_a = F_a / k_e, k_ep = k_e * H / (k_e + H);
      // F (u_a + x) = F_a u_a/2 + F_a x + k_ep x^2/2.
      const double a = 0.5 * k_ep, b = -(F - F_a),
                   c = -(F * u_a - 0.5 * F_a * u_a);
      const double x = (-b + std::sqrt(b * b - 4. * a * c)) / (2. * a);
      check("  elastic-plastic (F = 2 kN): first maximum [m]",
            first_maximum(F).first,
            u_a + x);
    }

    // The contract in the plastic phase.
    StructureProblem problem;
    BrakeBar         bar;
    setup(problem, bar, true);
    set_force(problem, 2e3);
    problem.initialize();
    const double dt = 1e-5;
    for (unsigned int step = 0; step < 200; ++step)
      {
        problem.prepare_step(problem.time(), dt);
        problem.solve_step();
        problem.commit_step();
      }
    out << "  after 200 steps: the brake slips: " << yes(stroke(problem) > 0.)
        << '\n';
    problem.prepare_step(problem.time(), dt);
    problem.solve_step();
    const Vector<double> u1 = problem.displacement(), v1 = problem.velocity();
    problem.solve_step();
    const bool again =
      same(u1, problem.displacement()) && same(v1, problem.velocity());
    set_force(problem, 3e3);
    problem.solve_step();
    const bool other = !same(u1, problem.displacement());
    set_force(problem, 2e3);
    problem.solve_step();
    out << "  solve_step again: identical: " << yes(again)
        << "; with F = 3 kN: other displacement: " << yes(other)
        << "; F = 2 kN again: identical displacement and velocity: "
        << yes(same(u1, problem.displacement()) && same(v1, problem.velocity()))
        << '\n';

    problem.commit_step();
    problem.save_state();
    const double         s0 = stroke(problem), t0 = problem.time();
    const Vector<double> u0  = problem.displacement();
    const auto           run = [&]() {
      for (unsigned int step = 0; step < 200; ++step)
        {
          problem.prepare_step(problem.time(), dt);
          problem.solve_step();
          problem.commit_step();
        }
    };
    run();
    const Vector<double> u2 = problem.displacement(), v2 = problem.velocity();
    const double         s2 = stroke(problem);
    problem.restore_state();
    out << "  save_state, 200 steps (stroke grew: " << yes(s2 > s0)
        << "), restore_state: displacement, stroke and time as saved: "
        << yes(same(u0, problem.displacement()) && stroke(problem) == s0 &&
               problem.time() == t0)
        << '\n';
    run();
    out << "  the same 200 steps again: identical displacement, velocity and "
           "stroke: "
        << yes(same(u2, problem.displacement()) &&
               same(v2, problem.velocity()) && stroke(problem) == s2)
        << '\n';
  }
} // namespace


int
main()
{
  static_mode();
  dynamic_mode();
}
