#include <talus/app/accepted_step.h>
#include <talus/app/run_console.h>
#include <talus/app/simulation.h>
#include <talus/base/contact_onset.h>
#include <talus/base/energy_jump_monitor.h>
#include <talus/base/input.h>
#include <talus/base/memory_usage.h>
#include <talus/base/parsed_functions.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/boundaries/material_behind_boundaries.h>
#include <talus/io/checkpointing.h>
#include <talus/io/deposit_profile.h>
#include <talus/io/point_dump.h>
#include <talus/io/probe_history.h>
#include <talus/io/time_series.h>
#include <talus/io/visualization_output.h>
#include <talus/materials/constitutive_model.h>
#include <talus/mpm/background_grid.h>
#include <talus/mpm/initial_stress.h>
#include <talus/mpm/load_balancing.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/mpm_problem.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

namespace Talus
{
  namespace
  {
    /** Entries of subsection "Verification" and "Convergence study". */
    template <int dim>
    void
    declare_verification_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Verification");
      {
        prm.declare_entry("compare with exact solution",
                          "false",
                          Patterns::Bool(),
                          "Measure the material points against the exact "
                          "displacement (and stress) below at the report "
                          "times and print the errors.");
        prm.declare_entry("report times",
                          "",
                          Patterns::List(Patterns::Double(0)),
                          "Times at which the errors are measured [s] (the "
                          "end time is always included).");
        prm.enter_subsection("Exact displacement");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
        prm.declare_entry("displacement error tolerance",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails (exit code 3) when the "
                          "displacement error at any report time exceeds "
                          "this value [m].");
        prm.declare_entry("relative displacement error tolerance",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails (exit code 3) when the "
                          "displacement error at any report time exceeds "
                          "this fraction of the exact displacement (the same "
                          "norm of u_ex; for 'compare center of mass' of "
                          "|u_ex(X_c)|; where u_ex = 0 the absolute error is "
                          "checked) [-].");
        prm.declare_entry("stress error tolerance",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails when the relative stress "
                          "error max|s - s_ex| / max|s_ex| exceeds this [-].");
        prm.declare_entry(
          "stress error norm",
          "max",
          Patterns::Selection("max|RMS"),
          "Which stress error 'stress error tolerance' checks: 'max', the "
          "largest deviation of any point, max|s - s_ex| / max|s_ex|; "
          "'RMS', the volume-weighted root mean square over the points, "
          "sqrt(sum_p V_p |s - s_ex|^2 / sum_p V_p) / max|s_ex| (|.|: the "
          "Euclidean norm of the components xx, yy, (zz,) xy, (yz, xz)). "
          "With 'RMS' both are printed.");
        prm.declare_entry("reference period",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the period of the oscillation is measured "
                          "from the zero crossings of the total momentum in x "
                          "and compared with this value [s].");
        prm.declare_entry("period tolerance",
                          "0.005",
                          Patterns::Double(0),
                          "Allowed relative error of the measured period [-].");
        prm.declare_entry("energy drift tolerance",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails when the total energy "
                          "(kinetic + strain + gravitational) drifts by more "
                          "than this fraction of its initial value [-].");
        prm.declare_entry("maximum final speed",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails when the largest speed of a "
                          "material point at the end exceeds this value "
                          "[m/s] (e.g. a body that must come to or stay at "
                          "rest).");
        prm.declare_entry(
          "final speed measure",
          "point velocity",
          Patterns::Selection("point velocity|grid velocity"),
          "Which speed 'maximum final speed' checks: 'point velocity', the "
          "velocity the material points carry (FLIP: it also holds particle "
          "velocity modes the grid does not see, which move nothing and are "
          "never damped); 'grid velocity', the grid velocity interpolated at "
          "the points, sum_I N_I(x_p) v_I, the velocity that moves them. "
          "Both are printed [-].");
        prm.declare_entry(
          "final speed window",
          "0",
          Patterns::Double(0),
          "If > 0: 'maximum final speed' bounds the largest speed of every "
          "step of the last this many seconds of the run, not only the end "
          "state: a body that must stay at rest, not just be slow at one "
          "instant [s].");
        prm.declare_entry("maximum penetration",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails when the largest "
                          "penetration of the material into a boundary of "
                          "subsection <Boundary particles> during the run "
                          "exceeds this value [m].");
        prm.declare_entry(
          "expected reaction",
          "0",
          Patterns::Double(0),
          "If > 0: the magnitude of the summed reaction of all boundaries of "
          "subsection <Boundary particles> at the end of the run is compared "
          "with this value [N], e.g. the weight m g of a body at rest "
          "(equilibrium); 0: off.");
        prm.declare_entry("reaction tolerance",
                          "1e-6",
                          Patterns::Double(0),
                          "Allowed relative error of the summed reaction "
                          "against 'expected reaction' [-].");
        prm.declare_entry("energy balance tolerance",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the run fails when the energy balance "
                          "B = kinetic + strain + gravitational + plastic "
                          "dissipation + friction dissipation + reset "
                          "dissipation + transfer dissipation (the kinetic "
                          "energy a PIC blend or XPIC removes relative "
                          "to FLIP; APIC's loss is not booked) changes "
                          "during "
                          "the run by more than this fraction of the "
                          "largest released gravitational energy "
                          "max|G(t) - G(0)| plus the initial kinetic energy "
                          "[-].");
        prm.declare_entry(
          "stress comparison axis",
          "",
          Patterns::List(Patterns::Double(), 0, 3),
          "If given (dim components): compare only the normal stress along "
          "this axis a, a.s.a against a.s_ex.a (e.g. the axial stress of a "
          "column along its axis), for both 'stress error norm's and "
          "relative to max|a.s_ex.a|. Empty: every component [-].");
        prm.declare_entry(
          "impulse normal",
          "",
          Patterns::List(Patterns::Double(), 0, 3),
          "If given (dim components): the unit normal n, pointing into the "
          "body, of the boundary whose impulse on the body is checked against "
          "Coulomb's law. The boundary impulse over the run is J = p(T) - "
          "p(0) - m g T (change of the total momentum minus the impulse of "
          "gravity; every boundary together); J_n = J.n, J_t = |J - J_n n|. "
          "Empty: no check [-].");
        prm.declare_entry("impulse ratio",
                          "0",
                          Patterns::Double(0),
                          "The expected ratio J_t / J_n of the boundary "
                          "impulse along 'impulse normal': the friction "
                          "coefficient mu for a body that slides during the "
                          "whole contact (Coulomb) [-].");
        prm.declare_entry("impulse ratio tolerance",
                          "0.01",
                          Patterns::Double(0),
                          "Allowed relative error of the measured impulse "
                          "ratio J_t / J_n (absolute error when 'impulse "
                          "ratio' is 0, a frictionless boundary) [-].");
        prm.declare_entry("compare center of mass",
                          "false",
                          Patterns::Bool(),
                          "Measure the displacement error of the center of "
                          "mass only, abs(sum m u / sum m - u_exact(X_c)) "
                          "with X_c the initial center of mass [-] (for "
                          "bodies that roll or deform, whose points do not "
                          "follow one rigid translation).");
        prm.declare_entry("compare stress",
                          "false",
                          Patterns::Bool(),
                          "Also measure the Cauchy stress against 'Exact "
                          "stress'.");
        prm.enter_subsection("Exact stress");
        Functions::ParsedFunction<dim>::declare_parameters(prm,
                                                           dim == 2 ? 3 : 6);
        prm.leave_subsection();
      }
      prm.leave_subsection();
      prm.enter_subsection("Convergence study");
      {
        prm.declare_entry("number of levels",
                          "1",
                          Patterns::Integer(1, 8),
                          "Run the problem on this many grids, each refined "
                          "once more (cells halved in every direction), and "
                          "print a convergence table of the errors with "
                          "their measured rates [-], 1 to 8. Needs 'compare "
                          "with exact solution' (errors against the exact "
                          "solution) or 'measure deposit' (the deposit "
                          "against its references, subsection <Deposit "
                          "profile>). Each level writes its files into "
                          "<output directory>/level-N.");
        prm.declare_entry("first level",
                          "0",
                          Patterns::Integer(0, 8),
                          "Refinement level of the first run [-].");
        prm.declare_entry("minimum rate",
                          "0",
                          Patterns::Double(0),
                          "If > 0: the study fails (exit code 3) when the "
                          "rate measured between the last two levels is "
                          "below this value for any report time [-].");
        prm.declare_entry("refine time step",
                          "true",
                          Patterns::Bool(),
                          "Halve the time step with every refinement.");
        prm.declare_entry(
          "refine bin width",
          "true",
          Patterns::Bool(),
          "Halve the deposit's 'bin width' (subsection <Deposit profile>) "
          "with every refinement, so that it stays the same multiple of the "
          "point spacing (false: the same bins on every grid) [-].");
        prm.declare_entry(
          "require shrinking deposit error",
          "false",
          Patterns::Bool(),
          "With 'measure deposit' (subsection <Deposit profile>) and a "
          "'reference runout': the study fails (exit code 3) unless the "
          "runout error |L - L_ref|/L_ref decreases at every refinement "
          "[-].");
        prm.declare_entry(
          "exempt coarse levels",
          "0",
          Patterns::Integer(0, 7),
          "Number of the study's coarsest levels whose deposit may miss the "
          "references of subsection <Deposit profile> (reported in the "
          "table, not a failure); every finer level must meet them [-]. "
          "Smaller than 'number of levels'.");
      }
      prm.leave_subsection();
    }


    std::string
    format_seconds(const double s)
    {
      std::ostringstream o;
      o << std::fixed << std::setprecision(1);
      if (s < 120)
        o << s << " s";
      else if (s < 7200)
        o << s / 60. << " min";
      else
        o << s / 3600. << " h";
      return o.str();
    }
  } // namespace


  template <int dim>
  Simulation<dim>::Simulation(const MPI_Comm communicator)
    : communicator(communicator)
  {}


  template <int dim>
  void
  Simulation<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                      const unsigned int        n_boundaries)
  {
    prm.declare_entry("problem",
                      "mpm",
                      dealii::Patterns::Selection("mpm|structure|coupled"),
                      "What to simulate: 'mpm' (the soil, everything but "
                      "subsections Structure and Coupling), 'structure' (a "
                      "barrier structure model of subsection Structure "
                      "alone) or 'coupled' (both, coupled through the "
                      "interface of subsection Coupling).");
    prm.declare_entry("dimension",
                      "2",
                      dealii::Patterns::Integer(2, 3),
                      "Space dimension of the problem [-]: 2 (plane strain) "
                      "or 3.");
    MPM::MPMProblem<dim>::declare_parameters(prm, n_boundaries);
    TimeControl::declare_parameters(prm);
    IO::VisualizationOutput<dim>::declare_parameters(prm);
    prm.enter_subsection("Output");
    prm.declare_entry("test mode",
                      "false",
                      dealii::Patterns::Bool(),
                      "Deterministic terminal output for the test suite: no "
                      "wall times, a rounded summary at the end, no timer "
                      "table.");
    prm.leave_subsection();
    declare_verification_parameters<dim>(prm);
    IO::DepositProfile<dim>::declare_parameters(prm);
    IO::ProbeHistory<dim>::declare_parameters(prm);
    IO::Checkpointing::declare_parameters(prm);
  }


  template <int dim>
  std::vector<VerificationErrors>
  Simulation<dim>::run(dealii::ParameterHandler &prm,
                       const unsigned int        refinement)
  {
    using Properties = MPM::MaterialPointProperties<dim>;
    RunConsole                  console(prm, communicator);
    const bool                  root      = console.root;
    const bool                  test_mode = console.test_mode;
    dealii::ConditionalOStream &pcout     = console.pcout;
    dealii::TimerOutput        &timer     = console.timer;

    // Build everything from the file.
    TimeControl time_control;
    time_control.parse_parameters(prm);
    ContactOnsetEvent contact_onset;
    contact_onset.parse_parameters(prm, time_control.initial_dt);
    EnergyJumpMonitor energy_jumps;
    energy_jumps.parse_parameters(prm);
    prm.enter_subsection("Convergence study");
    if (prm.get_bool("refine time step") && refinement > 0)
      {
        time_control.initial_dt /= std::pow(2., refinement);
        time_control.dt = time_control.initial_dt;
      }
    prm.leave_subsection();

    MPM::MPMProblem<dim> problem(communicator, time_control.newmark, timer);
    problem.parse_parameters(prm, refinement);
    auto                                     &grid       = problem.grid();
    auto                                     &points     = problem.points();
    auto                                     &solver     = problem.solver();
    auto                                     &boundaries = problem.boundaries();
    Boundaries::MaterialBehindBoundaries<dim> behind_boundaries(boundaries,
                                                                grid);

    IO::VisualizationOutput<dim> output;
    output.parse_parameters(prm);

    IO::DepositProfile<dim> deposit(communicator);
    deposit.parse_parameters(prm);
    IO::ProbeHistory<dim> probe(communicator);
    probe.parse_parameters(prm);

    // Checkpoints, and the one to resume from (checked on rank 0 first).
    IO::Checkpointing checkpointing;
    checkpointing.parse_parameters(prm, output.directory());
    std::string resume_path;
    if (!resume_from.empty() || checkpointing.resume_requested())
      {
        if (refinement > 0)
          InputFile::reject("Checkpoint",
                            "resume",
                            "true",
                            "a run on a refined grid of a convergence study "
                            "cannot be resumed");
        if (probe.enabled())
          InputFile::reject("Checkpoint",
                            "resume",
                            "true",
                            "a run with a probe (subsection <Probe "
                            "history>) cannot be resumed yet");
        if (deposit.enabled())
          InputFile::reject("Checkpoint",
                            "resume",
                            "true",
                            "a run with 'measure deposit = true' (subsection "
                            "<Deposit profile>) cannot be resumed yet");
        resume_path =
          IO::Checkpointing::find_and_check(resume_from.empty() ?
                                              checkpointing.directory() :
                                              resume_from,
                                            communicator);
      }
    const bool resuming = !resume_path.empty();

    // Verification.
    prm.enter_subsection("Verification");
    const bool          compare = prm.get_bool("compare with exact solution");
    std::vector<double> report_times = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("report times")));
    dealii::Functions::ParsedFunction<dim> exact_displacement(dim);
    prm.enter_subsection("Exact displacement");
    parse_function(prm, exact_displacement, "Verification/Exact displacement");
    prm.leave_subsection();
    const bool   compare_stress = prm.get_bool("compare stress");
    const bool   compare_center = prm.get_bool("compare center of mass");
    const double u_tolerance = prm.get_double("displacement error tolerance");
    const double u_relative_tolerance =
      prm.get_double("relative displacement error tolerance");
    const double s_tolerance = prm.get_double("stress error tolerance");
    const bool   stress_rms  = prm.get("stress error norm") == "RMS";
    // An optional direction of the subsection Verification: empty, or dim
    // components of a non-zero vector (returned normalised).
    const auto read_direction = [&](const std::string &entry) {
      const std::string         text = prm.get(entry);
      const std::vector<double> list = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(text));
      if (!list.empty() && list.size() != dim)
        InputFile::reject("Verification",
                          entry,
                          text,
                          "an empty value or " + std::to_string(dim) +
                            " components (one per space dimension) is "
                            "expected");
      dealii::Tensor<1, dim> v;
      for (unsigned int d = 0; d < list.size(); ++d)
        v[d] = list[d];
      if (!list.empty() && v.norm() == 0.)
        InputFile::reject("Verification",
                          entry,
                          text,
                          "a non-zero vector is expected");
      return std::make_pair(
        !list.empty(), list.empty() ? v : dealii::Tensor<1, dim>(v / v.norm()));
    };
    const auto axis_entry   = read_direction("stress comparison axis");
    const bool axial_stress = axis_entry.first;
    const dealii::Tensor<1, dim> stress_axis = axis_entry.second;
    const double reference_period = prm.get_double("reference period");
    const double period_tolerance = prm.get_double("period tolerance");
    const double drift_tolerance  = prm.get_double("energy drift tolerance");
    const double speed_limit      = prm.get_double("maximum final speed");
    const double speed_window     = prm.get_double("final speed window");
    if (speed_window > 0. && speed_limit <= 0.)
      InputFile::reject("Verification",
                        "final speed window",
                        prm.get("final speed window"),
                        "0 unless 'maximum final speed' is set (the window "
                        "is where that limit applies)");
    const double balance_tolerance = prm.get_double("energy balance tolerance");
    const double penetration_limit = prm.get_double("maximum penetration");
    const double expected_reaction = prm.get_double("expected reaction");
    const double reaction_tolerance = prm.get_double("reaction tolerance");
    if (expected_reaction > 0. && boundaries.empty())
      InputFile::reject("Verification",
                        "expected reaction",
                        prm.get("expected reaction"),
                        "0 unless subsection <Boundary particles> describes "
                        "a boundary (the reaction is theirs)");
    const bool speed_of_grid =
      prm.get("final speed measure") == "grid velocity";
    const auto normal_entry  = read_direction("impulse normal");
    const bool impulse_check = normal_entry.first;
    const dealii::Tensor<1, dim> impulse_normal = normal_entry.second;
    const double impulse_ratio = prm.get_double("impulse ratio");
    const double impulse_ratio_tolerance =
      prm.get_double("impulse ratio tolerance");
    dealii::Functions::ParsedFunction<dim> exact_stress(dim == 2 ? 3 : 6);
    prm.enter_subsection("Exact stress");
    parse_function(prm, exact_stress, "Verification/Exact stress");
    prm.leave_subsection();
    prm.leave_subsection();
    report_times.push_back(time_control.end_time);
    if (time_control.error_control.enabled())
      {
        if (solver.is_quasi_static())
          {
            prm.enter_subsection("Time");
            const std::string tolerance = prm.get("error tolerance");
            prm.leave_subsection();
            InputFile::reject("Time",
                              "error tolerance",
                              tolerance,
                              "it must be 0 in a quasi-static analysis "
                              "(subsection <Solver>: there are no "
                              "accelerations to estimate the error from)");
          }
        // the steps land on the output and report times
        time_control.set_event_interval(output.output_interval);
        if (compare)
          time_control.add_event_times(report_times);
      }

    // Generate the body and set up the solver.
    problem.setup();
    output.initialize(communicator);

    IO::TimeSeries<dim> series;
    if (!resuming)
      {
        std::vector<std::string> names;
        for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
          names.push_back(boundaries.boundary(b).name);
        series.open(output.directory() + "/time_series.csv",
                    communicator,
                    names,
                    time_control.error_control.enabled(),
                    problem.points().n_bodies(),
                    problem.solver().multi_velocity_field());
      }

    pcout << "Talus: " << dim << "D implicit MPM, "
          << dealii::Utilities::MPI::n_mpi_processes(communicator)
          << " MPI rank(s)\n";
    problem.print_summary(pcout);
    if (!test_mode &&
        dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cerr << solver.friction_at_rest_warning();
    if (!test_mode)
      pcout << "  " << problem.memory_estimate().summary() << '\n'
            << "  time: end " << time_control.end_time << " s, step "
            << time_control.initial_dt << " s\n";

    if (resuming)
      problem.load_checkpoint(resume_path);
    else
      problem.initialize(0.);
    auto initial = problem.diagnostics();
    if (!resuming)
      {
        MPM::NewtonResult none;
        series.write(0, 0., 0., none, initial, 0.);
        output.write(0., grid, points);
        deposit.initialize(points, output.directory());
        probe.open(output.directory());
        probe.record(0., points);
      }

    // Load balancing between steps (subsection Load balancing): the
    // committed state only, never inside a step.
    // (the imbalance over the run for the log: several ranks, no test mode)
    const bool track_imbalance =
      !test_mode && dealii::Utilities::MPI::n_mpi_processes(communicator) > 1;
    double       imbalance_sum = 0., imbalance_max = 0., imbalance_last = 1.;
    unsigned int imbalance_steps = 0, n_repartitions = 0;
    const auto   balance_load = [&]() {
      n_repartitions +=
        problem.balance_load(time_control.step, pcout).repartitioned ? 1 : 0;
    };

    // Errors against the exact solution at the current state.
    std::vector<VerificationErrors> errors;
    std::size_t                     next_report = 0;
    std::sort(report_times.begin(), report_times.end());
    report_times.erase(std::unique(report_times.begin(),
                                   report_times.end(),
                                   [](const double a, const double b) {
                                     return std::abs(a - b) <=
                                            1e-12 * std::max(1., std::abs(b));
                                   }),
                       report_times.end());
    const auto measure = [&](const double t) {
      VerificationErrors e;
      e.time = t;
      exact_displacement.set_time(t);
      exact_stress.set_time(t);
      double sum_u = 0., sum_v = 0., max_ds = 0., max_s = 0., sum_m = 0.,
             sum_ds = 0., sum_ex = 0.;
      dealii::Tensor<1, dim> sum_mu, sum_mX;
      for (const auto &p : points.particle_handler())
        {
          const auto         props = p.get_properties();
          dealii::Point<dim> X;
          for (unsigned int d = 0; d < dim; ++d)
            X[d] = props[Properties::initial_position + d];
          const double V0 = props[Properties::initial_volume];
          const double m  = props[Properties::mass];
          sum_m += m;
          for (unsigned int d = 0; d < dim; ++d)
            {
              sum_mu[d] += m * (p.get_location()[d] - X[d]);
              sum_mX[d] += m * X[d];
            }
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double u    = p.get_location()[d] - X[d];
              const double u_ex = exact_displacement.value(X, d);
              sum_u += V0 * std::pow(u - u_ex, 2);
              sum_ex += V0 * u_ex * u_ex;
            }
          sum_v += V0;
          if (compare_stress)
            {
              // 2D: xx yy xy; 3D: xx yy zz xy yz xz
              const std::vector<unsigned int> map =
                dim == 2 ? std::vector<unsigned int>{0, 1, 3} :
                           std::vector<unsigned int>{0, 1, 2, 3, 4, 5};
              if (axial_stress)
                {
                  // a.s.a from the components (symmetric tensor)
                  const std::vector<std::pair<unsigned int, unsigned int>> ij =
                    dim == 2 ?
                      std::vector<std::pair<unsigned int, unsigned int>>{
                        {0, 0}, {1, 1}, {0, 1}} :
                      std::vector<std::pair<unsigned int, unsigned int>>{
                        {0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
                  double s_h = 0., s_ex = 0.;
                  for (unsigned int c = 0; c < map.size(); ++c)
                    {
                      const double w = (ij[c].first == ij[c].second ? 1. : 2.) *
                                       stress_axis[ij[c].first] *
                                       stress_axis[ij[c].second];
                      s_h += w * props[Properties::stress + map[c]];
                      s_ex += w * exact_stress.value(X, c);
                    }
                  const double ds = s_h - s_ex;
                  max_ds          = std::max(max_ds, std::abs(ds));
                  sum_ds += V0 * ds * ds;
                  max_s = std::max(max_s, std::abs(s_ex));
                }
              else
                for (unsigned int c = 0; c < map.size(); ++c)
                  {
                    const double s_ex = exact_stress.value(X, c);
                    const double ds = props[Properties::stress + map[c]] - s_ex;
                    max_ds          = std::max(max_ds, std::abs(ds));
                    sum_ds += V0 * ds * ds;
                    max_s = std::max(max_s, std::abs(s_ex));
                  }
              if (std::getenv("TALUS_DEBUG_STRESS"))
                {
                  // (the point stresses of the comparison, for
                  // contrib/boundaries/column_ghost_study.py)
                  std::ostringstream line;
                  line << std::setprecision(10) << "DBGSTRESS " << X << ' '
                       << p.get_location();
                  for (unsigned int c = 0; c < map.size(); ++c)
                    line << ' ' << props[Properties::stress + map[c]] << ' '
                         << exact_stress.value(X, c);
                  line << ' ' << V0 << '\n';
                  std::cout << line.str();
                }
            }
        }
      sum_u                = dealii::Utilities::MPI::sum(sum_u, communicator);
      sum_v                = dealii::Utilities::MPI::sum(sum_v, communicator);
      max_ds               = dealii::Utilities::MPI::max(max_ds, communicator);
      max_s                = dealii::Utilities::MPI::max(max_s, communicator);
      sum_ds               = dealii::Utilities::MPI::sum(sum_ds, communicator);
      sum_ex               = dealii::Utilities::MPI::sum(sum_ex, communicator);
      e.displacement_error = std::sqrt(sum_u / sum_v);
      e.exact_displacement = std::sqrt(sum_ex / sum_v);
      if (compare_center)
        {
          sum_m  = dealii::Utilities::MPI::sum(sum_m, communicator);
          sum_mu = dealii::Utilities::MPI::sum(sum_mu, communicator);
          sum_mX = dealii::Utilities::MPI::sum(sum_mX, communicator);
          const dealii::Point<dim> X_c(sum_mX / sum_m);
          dealii::Tensor<1, dim>   du = sum_mu / sum_m;
          dealii::Tensor<1, dim>   u_ex;
          for (unsigned int d = 0; d < dim; ++d)
            u_ex[d] = exact_displacement.value(X_c, d);
          du -= u_ex;
          e.displacement_error = du.norm();
          e.exact_displacement = u_ex.norm();
        }
      e.stress_error = max_s > 0. ? max_ds / max_s : max_ds;
      e.stress_rms_error =
        std::sqrt(sum_ds / sum_v) / (max_s > 0. ? max_s : 1.);
      return e;
    };

    // Time loop.
    const auto wall_start   = std::chrono::steady_clock::now();
    const auto wall_seconds = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                           wall_start)
        .count();
    };
    // largest speed of a material point (collective)
    const auto max_point_speed = [&]() {
      double v = 0.;
      for (const auto &p : points.particle_handler())
        {
          double v2 = 0.;
          for (unsigned int d = 0; d < dim; ++d)
            v2 += dealii::Utilities::fixed_power<2>(
              p.get_properties()[Properties::velocity + d]);
          v = std::max(v, std::sqrt(v2));
        }
      return dealii::Utilities::MPI::max(v, communicator);
    };
    // largest speed (and its time) of the steps in the final window
    double              window_speed = 0., window_speed_time = 0.;
    double              max_drift          = 0.;
    double              max_balance_change = 0., max_released = 0.;
    double              max_penetration = 0.;
    double              last_momentum   = initial.momentum[0];
    std::vector<double> crossings;
    double              total_lost_mass               = 0.;
    unsigned int        total_lost_boundary_particles = 0;
    unsigned long       total_newton                  = 0;
    unsigned long       total_multiplier_updates      = 0;
    double              max_constraint_gap            = 0.;
    unsigned int        total_rejected                = 0;
    // the smallest and largest step chosen by the error
    double smallest_dt = std::numeric_limits<double>::max(), largest_dt = 0.;
    // steps accepted on the residual alone (MPM::NewtonResult)
    unsigned int total_without_descent = 0;

    // What the time loop keeps besides the problem (checkpoints).
    const auto loop_state = [&](auto &archive) {
      archive &time_control &output &initial &window_speed &window_speed_time
        &max_drift &max_balance_change &max_released &max_penetration
          &last_momentum &crossings &total_lost_mass
            &total_lost_boundary_particles &total_newton
              &total_multiplier_updates &max_constraint_gap &total_rejected
                &total_without_descent &errors &next_report;
      // the step chosen by the error
      double       &last_error       = time_control.last_error;
      unsigned int &error_rejections = time_control.error_rejections;
      archive &last_error &error_rejections &smallest_dt &largest_dt;
      // the contact onset event
      archive &contact_onset;
    };
    const std::string loop_tag = "talus-time-loop";
    // Write a checkpoint of the committed state; returns its path.
    const auto write_checkpoint = [&](const std::string &reason) {
      const auto path = checkpointing.write(
        time_control.step,
        time_control.time,
        reason,
        [&](const std::string &directory) {
          problem.save_checkpoint(directory);
          // (a file copy: the memory does not grow with the series)
          series.copy_to(directory + "/time_series.csv");
          if (root)
            IO::Checkpointing::save_archive(directory + "/time_loop",
                                            loop_tag,
                                            loop_state);
        },
        communicator);
      pcout << "  checkpoint (" << reason << ") at step " << time_control.step
            << ", t = " << time_control.time << " s: " << path << '\n';
      return path;
    };
    if (resuming)
      {
        IO::Checkpointing::load_archive(resume_path,
                                        resume_path + "/time_loop",
                                        loop_tag,
                                        loop_state);
        series.resume(output.directory() + "/time_series.csv",
                      communicator,
                      resume_path + "/time_series.csv",
                      time_control.error_control.enabled(),
                      problem.solver().multi_velocity_field());
        output.write_index(communicator);
        pcout << "  resumed from " << resume_path << " at step "
              << time_control.step << ", t = " << time_control.time << " s\n";
      }
    // 'energy jump action = reject' (EnergyJumpMonitor): an accepted step
    // is committed on a copy of the committed state and checked; whether
    // the step in hand was committed so, and its diagnostics
    bool                                 committed_for_check = false;
    std::optional<MPM::Diagnostics<dim>> checked_diagnostics;
    unsigned int energy_rejections = 0, energy_jumps_kept = 0;
    // true: keep the accepted step of size dt_try (committed if checked),
    // false: it jumps and was undone, retry with the halved step
    const auto keep_energy = [&](const double dt_try) {
      if (!energy_jumps.rejects())
        return true;
      problem.save_state();
      try
        {
          problem.commit_step();
          checked_diagnostics = solver.compute_diagnostics();
        }
      catch (...)
        {
          problem.restore_state();
          checked_diagnostics.reset();
          throw;
        }
      committed_for_check        = true;
      const auto       &d        = *checked_diagnostics;
      const double      released = std::max(max_released,
                                       std::abs(d.gravitational_energy -
                                                initial.gravitational_energy));
      const double      b        = d.energy_balance();
      const double      scale    = released + d.kinetic_energy;
      const std::string line     = energy_jump_rejection(energy_jumps,
                                                     b,
                                                     scale,
                                                     points.count_lost() > 0,
                                                     pcout,
                                                     time_control,
                                                     dt_try,
                                                     energy_jumps_kept);
      if (line.empty())
        return true;
      problem.restore_state();
      committed_for_check = false;
      checked_diagnostics.reset();
      ++total_rejected;
      ++energy_rejections;
      pcout << line;
      return false;
    };
    balance_load();
    while (!time_control.finished())
      {
        // the partition this step runs on
        if (track_imbalance)
          {
            imbalance_last =
              MPM::LoadBalancing<dim>::imbalance(points.particle_handler(),
                                                 communicator);
            imbalance_sum += imbalance_last;
            imbalance_max = std::max(imbalance_max, imbalance_last);
            ++imbalance_steps;
          }
        MPM::NewtonResult result;
        double            dt_taken = 0.;
        // an exception in the attempts stops the run with a checkpoint of
        // the last accepted step (solve_step() leaves it whole)
        solve_or_checkpoint(
          [&]() {
            while (true)
              {
                const double dt_try = time_control.next_step();
                problem.prepare_step(time_control.time + dt_try, dt_try);
                result   = problem.solve_step();
                dt_taken = dt_try;
                // the contact onset event (ContactOnsetEvent)
                if (result.converged && contact_onset.enabled() &&
                    contact_onset.assess(
                      time_control,
                      dt_try,
                      count_active_contacts(solver.boundary_reactions(),
                                            communicator)))
                  {
                    ++total_rejected;
                    if (!test_mode)
                      pcout << rejected_step_line(pcout.get_stream(),
                                                  time_control.step,
                                                  time_control.time,
                                                  dt_try,
                                                  "contact onset",
                                                  time_control.next_step());
                    continue;
                  }
                if (result.converged && !time_control.error_control.enabled())
                  {
                    if (keep_energy(dt_try))
                      break;
                    continue;
                  }
                if (result.converged)
                  {
                    // the step chosen by the error (TruncationErrorControl)
                    const double error = time_control.error_control.error(
                      solver.truncation_error_norms(),
                      dt_try,
                      time_control.newmark.beta);
                    if (time_control.assess_error(dt_try, error))
                      {
                        if (keep_energy(dt_try))
                          break;
                        continue;
                      }
                    ++total_rejected;
                    if (!test_mode)
                      pcout << error_rejected_step_line(pcout.get_stream(),
                                                        time_control,
                                                        dt_try,
                                                        error);
                    continue;
                  }
                ++total_rejected;
                pcout << rejected_step_line(pcout.get_stream(),
                                            time_control.step,
                                            time_control.time,
                                            dt_try,
                                            result.failure);
                if (!time_control.reject())
                  {
                    std::ostringstream msg;
                    msg << "The step from t = " << time_control.time
                        << " s could not be solved after "
                        << time_control.halvings
                        << " halvings of the time step (last dt = " << dt_try
                        << " s";
                    if (time_control.halvings < time_control.max_halvings)
                      msg << "; half of it is below the 'minimum time step' of "
                          << time_control.min_dt << " s";
                    msg
                      << "): " << result.failure
                      << ". Raise 'maximum Newton iterations' (or 'maximum "
                         "Newton iterations with state changes', the cap "
                         "including the iterations that change the return "
                         "branch of material points) in subsection "
                         "<Solver>, reduce 'time step' or 'minimum time step' "
                         "or raise 'maximum step halvings' in subsection "
                         "<Time>, or check the material parameters.";
                    if (checkpointing.enabled())
                      msg << failure_checkpoint_note(
                        time_control.step,
                        time_control.time,
                        write_checkpoint(
                          "failure: the step could not be solved"));
                    throw ExcSimulationFailed(msg.str());
                  }
                pcout << "    retrying with dt = " << time_control.next_step()
                      << " s\n";
              }
          },
          checkpointing,
          time_control.step,
          time_control.time,
          write_checkpoint,
          communicator);
        if (!committed_for_check)
          problem.commit_step();
        committed_for_check = false;
        time_control.accept(dt_taken);
        contact_onset.accepted(time_control);
        if (time_control.error_control.enabled() || contact_onset.enabled())
          {
            smallest_dt = std::min(smallest_dt, dt_taken);
            largest_dt  = std::max(largest_dt, dt_taken);
          }
        total_newton += result.iterations;
        total_without_descent += result.accepted_without_descent ? 1 : 0;
        total_multiplier_updates += result.multiplier_updates;
        max_constraint_gap =
          std::max(max_constraint_gap, result.constraint_gap);

        const auto         lost_region = points.take_lost_region();
        const unsigned int n_lost      = points.take_lost_count();
        const double       lost_mass   = points.take_lost_mass();
        // the message of a stop by lost points: the run stops at the end
        // of this step (its rows, output and records written), so that
        // its checkpoint continues as a scheduled one would
        std::string lost_points_stop;
        if (n_lost > 0)
          {
            total_lost_mass += lost_mass;
            std::ostringstream msg;
            msg << n_lost << " material point(s) with a mass of " << lost_mass
                << " kg left the background grid at t = " << time_control.time
                << " s at x in [" << lost_region.first << "] .. ["
                << lost_region.second
                << "] m and were removed (lost so far: " << total_lost_mass
                << " kg)";
            if (solver.abort_on_lost_points)
              lost_points_stop = msg.str() +
                                 "; 'abort on lost material points' is set. "
                                 "Enlarge the background grid.";
            else
              pcout << "  Warning: " << msg.str() << '\n';
          }
        {
          const auto lost_boundary = boundaries.take_lost_per_boundary();
          for (unsigned int b = 0; b < lost_boundary.size(); ++b)
            if (lost_boundary[b] > 0)
              {
                total_lost_boundary_particles += lost_boundary[b];
                pcout << "  Warning: " << lost_boundary[b]
                      << " boundary particle(s) of boundary '"
                      << boundaries.name(b)
                      << "' left the background grid at t = "
                      << time_control.time
                      << " s and were removed: that part of the boundary no "
                         "longer acts, also if it comes back (lost so far: "
                      << total_lost_boundary_particles
                      << "). Enlarge the background grid.\n";
              }
        }

        pcout << behind_boundaries.assess(
          behind_boundaries.survey(points.particle_handler(),
                                   MPM::MaterialPointProperties<dim>::mass,
                                   communicator),
          time_control.time);

        const auto diagnostics = checked_diagnostics ?
                                   *checked_diagnostics :
                                   solver.compute_diagnostics();
        checked_diagnostics.reset();
        if (speed_window > 0. &&
            time_control.time >=
              time_control.end_time - speed_window * (1. + 1e-9))
          {
            const double v =
              speed_of_grid ? diagnostics.max_grid_speed : max_point_speed();
            if (v >= window_speed)
              {
                window_speed      = v;
                window_speed_time = time_control.time;
              }
          }
        {
          const double e0 = initial.kinetic_energy + initial.strain_energy +
                            initial.gravitational_energy;
          const double e = diagnostics.kinetic_energy +
                           diagnostics.strain_energy +
                           diagnostics.gravitational_energy;
          max_drift =
            std::max(max_drift,
                     std::abs(e - e0) / std::max(std::abs(e0), 1e-300));
          const double b0    = initial.energy_balance();
          const double b     = diagnostics.energy_balance();
          max_balance_change = std::max(max_balance_change, std::abs(b - b0));
          for (const auto &b : diagnostics.boundaries)
            max_penetration = std::max(max_penetration, b.penetration);
          max_released = std::max(max_released,
                                  std::abs(diagnostics.gravitational_energy -
                                           initial.gravitational_energy));
          pcout << energy_jumps.assess(time_control.step,
                                       time_control.time,
                                       b,
                                       max_released +
                                         diagnostics.kinetic_energy,
                                       n_lost > 0);
          const double p = diagnostics.momentum[0];
          if (p * last_momentum < 0.)
            crossings.push_back(time_control.time -
                                dt_taken * p / (p - last_momentum));
          last_momentum = p;
        }
        series.write(time_control.step,
                     time_control.time,
                     dt_taken,
                     result,
                     diagnostics,
                     lost_mass,
                     time_control.last_error);
        deposit.step(time_control.step, time_control.time, points);
        probe.record(time_control.time, points);

        if (output.due(time_control.time) || time_control.finished())
          {
            {
              dealii::TimerOutput::Scope s(timer, "output");
              output.write(time_control.time,
                           grid,
                           points,
                           &solver.grid_velocity());
            }
            if (!test_mode)
              {
                const double wall = wall_seconds();
                const double left = wall / time_control.time *
                                    (time_control.end_time - time_control.time);
                pcout << "step " << std::setw(6) << time_control.step
                      << "  t = " << std::scientific << std::setprecision(4)
                      << time_control.time
                      << " s  dt = " << std::setprecision(2) << dt_taken
                      << " s";
                if (time_control.error_control.enabled())
                  pcout << "  error " << time_control.last_error;
                pcout << "  Newton " << std::setw(2) << result.iterations
                      << "  linear " << std::setw(4) << result.linear_iterations
                      << "  |R| " << result.residual << std::defaultfloat
                      << "  wall " << format_seconds(wall) << "  left ~"
                      << format_seconds(left) << '\n';
              }
          }

        while (compare && next_report < report_times.size() &&
               time_control.time >= report_times[next_report] - 0.5 * dt_taken)
          {
            errors.push_back(measure(time_control.time));
            // Name the error by the requested time, so that the columns of
            // a convergence study line up even if a step was halved.
            errors.back().time = report_times[next_report];
            ++next_report;
          }

        end_accepted_step(
          checkpointing,
          time_control.step,
          time_control.time,
          time_control.finished(),
          lost_points_stop,
          write_checkpoint,
          [&]() { balance_load(); },
          communicator);
      }

    // (debugging and the checkpoint tests: every point in full precision)
    if (const char *dump = std::getenv("TALUS_DEBUG_DUMP_POINTS"))
      IO::write_points_text(points, dump, communicator);

    // Summary.
    const auto final_state = solver.compute_diagnostics();
    if (test_mode)
      {
        // Extreme displacements of the points.
        dealii::Tensor<1, dim> u_min, u_max;
        double                 v_max = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            u_min[d] = 1e300;
            u_max[d] = -1e300;
          }
        for (const auto &p : points.particle_handler())
          {
            const auto props = p.get_properties();
            double     v2    = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double u =
                  p.get_location()[d] - props[Properties::initial_position + d];
                u_min[d] = std::min(u_min[d], u);
                u_max[d] = std::max(u_max[d], u);
                v2 += std::pow(props[Properties::velocity + d], 2);
              }
            v_max = std::max(v_max, std::sqrt(v2));
          }
        for (unsigned int d = 0; d < dim; ++d)
          {
            u_min[d] = dealii::Utilities::MPI::min(u_min[d], communicator);
            u_max[d] = dealii::Utilities::MPI::max(u_max[d], communicator);
          }
        v_max            = dealii::Utilities::MPI::max(v_max, communicator);
        const auto round = [](const double x) {
          std::ostringstream o;
          const double       y = std::abs(x) < 1e-10 ? 0. : x;
          o << std::setprecision(6) << y;
          return o.str();
        };
        pcout << "Summary at t = " << round(time_control.time) << " s after "
              << time_control.step << " steps\n"
              << "  material points: " << points.n_global_points() << '\n'
              << "  mass: " << round(final_state.mass) << " kg (initial "
              << round(initial.mass) << ")\n"
              << "  momentum:";
        for (unsigned int d = 0; d < dim; ++d)
          pcout << ' ' << round(final_state.momentum[d]);
        pcout << "\n  kinetic energy: " << round(final_state.kinetic_energy)
              << "\n  strain energy: " << round(final_state.strain_energy);
        if (problem.solver().multi_velocity_field())
          pcout << "\n  body contact dissipation: "
                << round(final_state.body_contact_dissipation)
                << " J, nodes in contact: " << final_state.body_contact_nodes;
        for (unsigned int b = 0; b < final_state.body_mass.size(); ++b)
          {
            pcout << "\n  body " << b + 1 << ": mass "
                  << round(final_state.body_mass[b]) << " kg, momentum";
            for (unsigned int d = 0; d < dim; ++d)
              pcout << ' ' << round(final_state.body_momentum[b][d]);
            pcout << ", kinetic energy "
                  << round(final_state.body_kinetic_energy[b])
                  << ", strain energy "
                  << round(final_state.body_strain_energy[b]);
          }
        if (points.n_global_points() > 0)
          {
            pcout << "\n  displacement min:";
            for (unsigned int d = 0; d < dim; ++d)
              pcout << ' ' << round(u_min[d]);
            pcout << "\n  displacement max:";
            for (unsigned int d = 0; d < dim; ++d)
              pcout << ' ' << round(u_max[d]);
          }
        pcout << "\n  max speed: " << round(v_max)
              << "\n  lost mass: " << round(total_lost_mass) << " kg\n";
        pcout << behind_boundaries.summary();
        problem.print_adaptive_grid(pcout);
        if (time_control.error_control.enabled())
          pcout << "  steps chosen by the error: " << time_control.step
                << " steps, " << time_control.error_rejections
                << " rejected for their error, dt " << std::setprecision(4)
                << smallest_dt << " .. " << largest_dt << " s"
                << std::setprecision(6) << '\n';
        if (contact_onset.enabled())
          pcout << "  contact onset: " << contact_onset.rejections
                << " steps rejected at a sharp change of the active set "
                   "(onset step "
                << contact_onset.onset_dt << " s), dt " << std::setprecision(4)
                << smallest_dt << " .. " << largest_dt << " s"
                << std::setprecision(6) << '\n';
        if (total_without_descent > 0)
          pcout << "  steps accepted on the residual alone (no descent "
                   "along the last correction): "
                << total_without_descent << '\n';
        if (boundaries.any_augmented())
          pcout << "  multiplier updates: " << total_multiplier_updates
                << " in " << time_control.step << " steps, largest gap left "
                << std::setprecision(2) << std::scientific << max_constraint_gap
                << std::defaultfloat << std::setprecision(6) << " m (tolerance "
                << boundaries.multiplier_tolerance() << " m)\n";
        if (boundaries.any_lagrange_multiplier())
          pcout << "  Lagrange multipliers: largest constraint residual at "
                   "convergence "
                << std::setprecision(2) << std::scientific << max_constraint_gap
                << std::defaultfloat << std::setprecision(6) << " m (tolerance "
                << boundaries.multiplier_tolerance() << " m)\n";
        if (total_lost_boundary_particles > 0)
          pcout << "  lost boundary particles: "
                << total_lost_boundary_particles << '\n';
        if (solver.ghost_penalty() > 0.)
          pcout << "  ghost-penalty faces in the last step: "
                << solver.n_ghost_penalty_faces() << '\n';
      }
    else
      pcout
        << "Done: " << time_control.step << " steps (" << total_rejected
        << " rejected), "
        << static_cast<double>(total_newton) / std::max(1u, time_control.step)
        << " Newton iterations per step, "
        << (total_without_descent > 0 ? std::to_string(total_without_descent) +
                                          " accepted on the residual alone, " :
                                        std::string())
        << (boundaries.any_augmented() ?
              std::to_string(total_multiplier_updates) +
                " multiplier updates in " + std::to_string(time_control.step) +
                " steps, " :
              std::string())
        << "lost mass " << total_lost_mass << " kg, "
        << (time_control.error_control.enabled() ?
              std::to_string(time_control.error_rejections) +
                " rejected for their error, dt " + std::to_string(smallest_dt) +
                " .. " + std::to_string(largest_dt) + " s, " :
              std::string())
        << (total_lost_boundary_particles > 0 ?
              std::to_string(total_lost_boundary_particles) +
                " boundary particles lost, " :
              std::string())
        << "wall time " << format_seconds(wall_seconds()) << "\n"
        << "Output in " << output.directory() << "/\n";
    // (counted in this process: a checkpoint does not carry them)
    if (energy_jumps.rejects())
      pcout << "  energy jumps ('energy jump action = reject'): "
            << energy_rejections << " steps rejected, " << energy_jumps_kept
            << " committed with their jump (no halving left)\n";
    // (not in test mode: a diagnostic of this process's run, which a
    // checkpoint does not carry)
    if (solver.convected_point_domains())
      {
        const auto capped = solver.capped_point_domains();
        if (!test_mode)
          pcout << (solver.shape_functions() == "CPDI" ?
                      "  CPDI point domains scaled down to keep their "
                      "corners in the node patch and the grid, capped: " :
                      "  cpGIMP point domains capped at the cell size: ")
                << capped.first << " of " << capped.second
                << " point evaluations\n";
      }
    // (not in test mode: the test outputs do not depend on the machine)
    {
      const std::string memory = memory_summary(communicator);
      if (!test_mode)
        pcout << memory;
    }
    if (track_imbalance && imbalance_steps > 0)
      pcout << "  imbalance of the material points (largest rank / mean) "
               "at the start of the steps: mean "
            << std::setprecision(4) << imbalance_sum / imbalance_steps
            << ", largest " << imbalance_max << ", at the end "
            << imbalance_last << std::defaultfloat << "; " << n_repartitions
            << " repartition(s)\n";
    if (compare)
      for (const auto &e : errors)
        {
          pcout << "  error at t = " << std::setprecision(6) << e.time
                << ": displacement " << std::setprecision(4) << std::scientific
                << e.displacement_error;
          if (compare_stress)
            pcout << (axial_stress ? ", axial stress" : ", stress")
                  << " (relative, max) " << e.stress_error;
          if (compare_stress && stress_rms)
            pcout << ", (relative, RMS) " << e.stress_rms_error;
          pcout << std::defaultfloat << '\n';
        }
    // Checks against the references given in the file.
    bool       passed = true;
    const auto check =
      [&](const std::string &what, const double value, const double tolerance) {
        const bool ok = value <= tolerance;
        pcout << "  check " << what << ": " << std::setprecision(3)
              << std::scientific << value << (ok ? " <= " : " > ") << tolerance
              << std::defaultfloat << (ok ? "  ok" : "  FAILED") << '\n';
        passed = passed && ok;
      };
    if (compare)
      for (const auto &e : errors)
        {
          if (u_tolerance > 0.)
            check("displacement error", e.displacement_error, u_tolerance);
          if (u_relative_tolerance > 0.)
            check("relative displacement error",
                  e.exact_displacement > 0. ?
                    e.displacement_error / e.exact_displacement :
                    e.displacement_error,
                  u_relative_tolerance);
          if (compare_stress && s_tolerance > 0.)
            check(std::string(axial_stress ? "axial " : "") +
                    (stress_rms ? "stress error (RMS)" : "stress error"),
                  stress_rms ? e.stress_rms_error : e.stress_error,
                  s_tolerance);
        }
    if (drift_tolerance > 0.)
      check("energy drift", max_drift, drift_tolerance);
    if (balance_tolerance > 0.)
      {
        const double scale = max_released + initial.kinetic_energy;
        pcout << "  energy balance: largest change " << std::setprecision(4)
              << max_balance_change << " J, released gravitational energy "
              << max_released << " J, plastic dissipation "
              << final_state.plastic_dissipation << " J, friction dissipation "
              << final_state.friction_dissipation << " J, reset dissipation "
              << final_state.reset_dissipation << " J, transfer dissipation "
              << final_state.transfer_dissipation
              << " J, integrator dissipation "
              << final_state.integrator_dissipation << " J, spring energy "
              << final_state.spring_energy() << " J\n";
        check("energy balance",
              max_balance_change / std::max(scale, 1e-300),
              balance_tolerance);
      }
    if (!boundaries.empty())
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &r = final_state.boundaries[b];
          pcout << "  boundary " << boundaries.boundary(b).name << ": reaction";
          for (unsigned int d = 0; d < dim; ++d)
            pcout << ' ' << std::setprecision(6)
                  << (std::abs(r.force[d]) < 1e-8 ? 0. : r.force[d]);
          pcout << " N, normal " << r.normal_force << " N, tangential "
                << (r.tangential_force < 1e-8 ? 0. : r.tangential_force)
                << " N, " << r.active << " particles in contact\n";
        }
    if (expected_reaction > 0.)
      {
        dealii::Tensor<1, dim> total;
        for (const auto &r : final_state.boundaries)
          total += r.force;
        pcout << "  summed reaction: " << std::setprecision(10) << total.norm()
              << " N (expected " << expected_reaction << " N)\n";
        check("relative reaction error",
              std::abs(total.norm() - expected_reaction) / expected_reaction,
              reaction_tolerance);
      }
    if (penetration_limit > 0.)
      check("penetration", max_penetration, penetration_limit);
    if (impulse_check)
      {
        // Impulse of the boundaries: momentum change minus gravity's.
        const dealii::Tensor<1, dim> J =
          final_state.momentum - initial.momentum -
          (final_state.mass * time_control.time) * solver.gravity();
        const double J_n = J * impulse_normal;
        const double J_t = (J - J_n * impulse_normal).norm();
        pcout << "  boundary impulse: normal " << std::setprecision(6) << J_n
              << " N s, tangential " << J_t << " N s, ratio "
              << J_t / std::max(std::abs(J_n), 1e-300) << " (expected "
              << impulse_ratio << ")\n";
        check(impulse_ratio > 0. ? "relative impulse ratio error" :
                                   "impulse ratio error",
              J_n > 0. ? std::abs(J_t / J_n - impulse_ratio) /
                           (impulse_ratio > 0. ? impulse_ratio : 1.) :
                         std::numeric_limits<double>::infinity(),
              impulse_ratio_tolerance);
      }
    if (speed_limit > 0.)
      {
        const double v_end = max_point_speed();
        pcout << "  final speed: point velocity " << std::setprecision(6)
              << v_end << " m/s, grid velocity " << final_state.max_grid_speed
              << " m/s; kinetic energy of the grid velocity "
              << final_state.grid_kinetic_energy << " J\n";
        if (speed_window > 0.)
          {
            pcout << "  largest " << (speed_of_grid ? "grid" : "point")
                  << " speed over the last " << speed_window
                  << " s: " << std::setprecision(6) << window_speed
                  << " m/s at t = " << window_speed_time << " s\n";
            check(speed_of_grid ? "speed in the final window (grid velocity)" :
                                  "speed in the final window",
                  window_speed,
                  speed_limit);
          }
        else
          check(speed_of_grid ? "final speed (grid velocity)" : "final speed",
                speed_of_grid ? final_state.max_grid_speed : v_end,
                speed_limit);
      }
    if (reference_period > 0.)
      {
        if (crossings.size() < 2)
          {
            pcout << "  check period: fewer than two zero crossings of the "
                     "momentum  FAILED\n";
            passed = false;
          }
        else
          {
            const double period = 2. * (crossings.back() - crossings.front()) /
                                  (crossings.size() - 1);
            pcout << "  period: " << std::setprecision(6) << period
                  << " s (reference " << reference_period << " s)\n";
            check("relative period error",
                  std::abs(period - reference_period) / reference_period,
                  period_tolerance);
          }
      }
    passed = probe.finalize(pcout.get_stream()) && passed;
    const bool deposit_passed =
      deposit.finalize(points, pcout.get_stream(), test_mode);
    if (deposit.enabled())
      {
        const auto &c                   = deposit.comparison();
        deposit_result                  = DepositErrors();
        deposit_result.cell_size        = grid.cell_extent[0];
        deposit_result.runout           = c.runout;
        deposit_result.runout_error     = c.runout_error;
        deposit_result.max_height_error = c.max_height_error;
        deposit_result.rms_height_error = c.rms_height_error;
        deposit_result.passed           = c.passed;
      }
    if (!deposit_passed && !deposit_misses_fatal && passed)
      return errors;
    if (!deposit_passed)
      throw ExcVerificationFailed(
        passed ? "the deposit misses the reference values given in "
                 "subsection <Deposit profile> (table above)." :
                 "the results miss the reference values given in "
                 "subsections <Verification> and <Deposit profile>.");
    if (!passed)
      throw ExcVerificationFailed("the results miss the reference values "
                                  "given in subsection <Verification>.");
    return errors;
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Talus
