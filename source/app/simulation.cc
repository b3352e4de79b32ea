#include <talus/app/accepted_step.h>
#include <talus/app/run_console.h>
#include <talus/app/run_verification.h>
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
#include <talus/mpm/contact_forecast.h>
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
    RunVerification<dim>::declare_parameters(prm);
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
    const MPM::ContactForecast<dim>           contact_forecast(
      boundaries,
      behind_boundaries,
      grid.minimal_cell_diameter,
      [&solver](const auto &F) { return solver.point_domain_half_extent(F); });

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

    RunVerification<dim> verification(communicator);
    verification.parse_parameters(prm, boundaries, time_control.end_time);
    if (time_control.error_control.mass_weighted_coupled)
      InputFile::reject("Time",
                        "coupled error norm",
                        "mass weighted",
                        "it applies to 'problem = coupled' only (an MPM "
                        "problem has one field); leave it at 'larger field'");
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
        if (verification.compares())
          time_control.add_event_times(verification.report_times());
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
    verification.start(initial);
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

    // Time loop.
    const auto wall_start   = std::chrono::steady_clock::now();
    const auto wall_seconds = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                           wall_start)
        .count();
    };
    // largest speed of a material point (collective)
    double        total_lost_mass               = 0.;
    unsigned int  total_lost_boundary_particles = 0;
    unsigned long total_newton                  = 0;
    unsigned long total_multiplier_updates      = 0;
    double        max_constraint_gap            = 0.;
    unsigned int  total_rejected                = 0;
    // the smallest and largest step chosen by the error
    double smallest_dt = std::numeric_limits<double>::max(), largest_dt = 0.;
    // steps accepted on the residual alone (MPM::NewtonResult)
    unsigned int total_without_descent = 0;

    // steps rejected for an energy jump, jumps kept at the step limit
    unsigned int energy_rejections = 0, energy_jumps_kept = 0;

    // What the time loop keeps besides the problem (checkpoints).
    const auto loop_state = [&](auto &archive) {
      archive &time_control &output &initial;
      // (the order of the checkpoint format)
      verification.serialize_records(archive);
      archive &total_lost_mass &total_lost_boundary_particles &total_newton
        &total_multiplier_updates &max_constraint_gap &total_rejected
          &total_without_descent;
      verification.serialize_errors(archive);
      // the step chosen by the error
      double       &last_error       = time_control.last_error;
      unsigned int &error_rejections = time_control.error_rejections;
      archive &last_error &error_rejections &smallest_dt &largest_dt;
      // the contact onset event
      archive &contact_onset;
      // the energy jumps (EnergyJumpMonitor)
      archive &energy_jumps &energy_rejections &energy_jumps_kept;
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
      const double      released = std::max(verification.released(),
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
        // shorten the step ahead of a forecast contact onset
        contact_forecast.shorten_ahead(contact_onset,
                                       time_control,
                                       points.particle_handler(),
                                       solver.gravity(),
                                       communicator);
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
        verification.record_step(initial,
                                 diagnostics,
                                 points,
                                 time_control.time,
                                 dt_taken,
                                 time_control.end_time);
        pcout << energy_jumps.assess(time_control.step,
                                     time_control.time,
                                     diagnostics.energy_balance(),
                                     verification.released() +
                                       diagnostics.kinetic_energy,
                                     n_lost > 0);
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

        verification.measure_due(time_control.time, dt_taken, points);

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
          pcout << "  contact onset: " << contact_onset.shortened
                << " steps shortened ahead of a forecast onset, "
                << contact_onset.rejections
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
    bool passed = verification.report(pcout,
                                      initial,
                                      final_state,
                                      boundaries,
                                      points,
                                      solver.gravity(),
                                      time_control.time);
    passed      = probe.finalize(pcout.get_stream()) && passed;
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
      return verification.errors();
    if (!deposit_passed)
      throw ExcVerificationFailed(
        passed ? "the deposit misses the reference values given in "
                 "subsection <Deposit profile> (table above)." :
                 "the results miss the reference values given in "
                 "subsections <Verification> and <Deposit profile>.");
    if (!passed)
      throw ExcVerificationFailed("the results miss the reference values "
                                  "given in subsection <Verification>.");
    return verification.errors();
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Talus
