// MPMSolver::friction_at_rest_warning() (doc/verification.md, "A block at
// rest whatever the cut"): the warning the time loops print outside test
// mode when a dynamic run holds material on a frictional boundary of
// particles at rest without numerical damping (Newmark gamma = 0.5) or
// without the ghost penalty. A block resting on a frictional floor of
// boundary particles (which cuts the cells at y = 0.11), set up as the
// time loop sets it up (MPMProblem::setup()), in variants where the
// warning must fire (each missing ingredient named) and where it must not
// (both ingredients, quasi-static, a moving friction boundary, contact
// without friction, no boundary particles). Prints the full text, so that
// its wording and its condition are pinned.
#include <talus/app/simulation.h>
#include <talus/base/time_control.h>
#include <talus/mpm/mpm_problem.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fstream>
#include <string>

using namespace dealii;

namespace
{
  // The block on its floor; the floor's condition, its displacement and
  // the Time and Solver settings are set by each case.
  const std::string block = R"(
set dimension = 2
subsection Background grid
  set lower corner = 0, 0
  set upper corner = 1, 0.5
  set subdivisions = 10, 5
end
subsection Body
  set lower corner = 0.3, 0.11
  set upper corner = 0.7, 0.31
  set points per cell per direction = 2
end
subsection Material
  set model = linear elastic
  set density = 2000
  set Young's modulus = 1e7
  set Poisson's ratio = 0.3
end
subsection Solver
  set gravity = 0, -9.81
  set linear solver = direct
end
subsection Time
  set end time = 0.1
  set time step = 0.01
end
subsection Output
  set format = none
  set test mode = true
end
)";

  const std::string floor_boundary = R"(
subsection Boundary particles
  subsection Boundary 1
    set geometry = line
    set name = floor
    set vertices = 0.05, 0.11; 0.95, 0.11
    set condition = friction
    set friction coefficient = 0.5
  end
end
)";

  const std::string damping = R"(
subsection Time
  set Newmark gamma = 0.6
  set Newmark beta = 0.3025
end
)";

  const std::string ghost_penalty = R"(
subsection Solver
  set ghost penalty factor = 1
end
)";

  /**
   * The warning of the solver of the problem set up from @p input, and
   * whether it is empty as @p fires says it must (not) be.
   */
  void
  check(const std::string &label,
        const std::string &input,
        const bool         fires,
        std::ostream      &out)
  {
    ParameterHandler prm;
    Talus::Simulation<2>::declare_parameters(prm);
    prm.parse_input_from_string(input);

    TimerOutput        timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    Talus::TimeControl time_control;
    time_control.parse_parameters(prm);
    Talus::MPM::MPMProblem<2> problem(MPI_COMM_WORLD,
                                      time_control.newmark,
                                      timer);
    problem.parse_parameters(prm);
    problem.setup();

    const std::string warning = problem.solver().friction_at_rest_warning();
    out << label << ": " << (warning.empty() ? "no warning" : "warning")
        << (warning.empty() == !fires ? " (as expected)" : " (WRONG)") << '\n';
    if (!warning.empty())
      out << "  " << warning;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");

  const std::string at_rest = block + floor_boundary;
  // fires: each missing ingredient is named
  check("gamma = 0.5, no ghost penalty", at_rest, true, out);
  check("gamma = 0.6, no ghost penalty", at_rest + damping, true, out);
  check("gamma = 0.5, ghost penalty factor = 1",
        at_rest + ghost_penalty,
        true,
        out);
  // the boundary named is the first frictional one at rest
  check("a moving friction belt and the floor at rest",
        block + R"(
subsection Boundary particles
  subsection Boundary 1
    set geometry = line
    set name = belt
    set vertices = 0.05, 0.4; 0.95, 0.4
    set condition = friction
    set friction coefficient = 0.5
    subsection Displacement
      set Function expression = 0.1 * t; 0
    end
  end
  subsection Boundary 2
    set geometry = line
    set name = floor
    set vertices = 0.05, 0.11; 0.95, 0.11
    set condition = friction
    set friction coefficient = 0.5
  end
end
)",
        true,
        out);

  // silent
  check("gamma = 0.6, ghost penalty factor = 1",
        at_rest + damping + ghost_penalty,
        false,
        out);
  check("quasi-static",
        at_rest + R"(
subsection Solver
  set analysis = quasi-static
end
)",
        false,
        out);
  check("the friction floor moving",
        at_rest + R"(
subsection Boundary particles
  subsection Boundary 1
    subsection Displacement
      set Function expression = 0.1 * t; 0
    end
  end
end
)",
        false,
        out);
  check("contact without friction",
        at_rest + R"(
subsection Boundary particles
  subsection Boundary 1
    set condition = contact
  end
end
)",
        false,
        out);
  check("no boundary particles", block, false, out);
}
