// The coupled application: MPM + barrier structure, partitioned
// (set problem = coupled).

#include <talus/app/accepted_step.h>
#include <talus/app/coupled_simulation.h>
#include <talus/app/run_console.h>
#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/base/contact_onset.h>
#include <talus/base/energy_jump_monitor.h>
#include <talus/base/input.h>
#include <talus/base/memory_usage.h>
#include <talus/base/time_control.h>
#include <talus/boundaries/material_behind_boundaries.h>
#include <talus/coupling/coupling_parameters.h>
#include <talus/coupling/gauss_seidel_coupling.h>
#include <talus/coupling/structure_interface.h>
#include <talus/io/checkpointing.h>
#include <talus/io/point_dump.h>
#include <talus/io/structure_time_series.h>
#include <talus/io/visualization_output.h>
#include <talus/mpm/contact_forecast.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/mpm_problem.h>
#include <talus/structure/structure_problem.h>
#include <talus/structure/truncation_error.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

namespace Talus
{
  namespace
  {
    const std::string verification_section = "Coupling/Verification";

    /** A vector entry: empty, or @p dim components. */
    template <int dim>
    std::pair<bool, dealii::Tensor<1, dim>>
    optional_vector(const dealii::ParameterHandler &prm,
                    const std::string              &entry)
    {
      const std::string         text = prm.get(entry);
      const std::vector<double> v    = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(text));
      if (!v.empty() && v.size() != dim)
        InputFile::reject(verification_section,
                          entry,
                          text,
                          "an empty value or " + std::to_string(dim) +
                            " components");
      dealii::Tensor<1, dim> t;
      for (unsigned int d = 0; d < v.size(); ++d)
        t[d] = v[d];
      return {!v.empty(), t};
    }

    /** The brakes of a structure at its committed state: the largest
     * stroke s [m], the dissipated energy D summed increment by increment
     * over all brakes and its closed form sum F_a s + H s^2 / 2 [J]. */
    struct BrakeAccount
    {
      double       largest_stroke = 0., dissipated = 0., closed_form = 0.;
      unsigned int n_brakes = 0;
    };

    BrakeAccount
    brake_account(const Structure::Structure &s)
    {
      BrakeAccount a;
      for (const auto &mesh : s.line_meshes)
        if (const auto *brake =
              dynamic_cast<const Structure::Brake *>(mesh->element.get()))
          for (const auto &state : mesh->state)
            {
              const double stroke = state.plastic;
              a.largest_stroke    = std::max(a.largest_stroke, stroke);
              a.dissipated += state.accumulated;
              a.closed_form += brake->activation_force * stroke +
                               0.5 * brake->hardening * stroke * stroke;
              ++a.n_brakes;
            }
      return a;
    }

    /** Copy the file @p from to @p to (replacing it); false if that
     * fails. A checkpoint keeps the CSV files as copies, so that the memory
     * of a long run does not grow with them. */
    bool
    copy_file(const std::string &from, const std::string &to)
    {
      std::error_code error;
      std::filesystem::copy_file(
        from, to, std::filesystem::copy_options::overwrite_existing, error);
      return !error;
    }
  } // namespace


  template <int dim>
  CoupledSimulation<dim>::CoupledSimulation(const MPI_Comm communicator)
    : communicator(communicator)
  {}


  template <int dim>
  void
  CoupledSimulation<dim>::declare_coupling_parameters(
    dealii::ParameterHandler &prm)
  {
    Coupling::CouplingParameters::declare_parameters(prm);
    prm.enter_subsection("Coupling");
    prm.declare_entry(
      "initial structure state",
      "loaded",
      dealii::Patterns::Selection("loaded|unloaded"),
      "The structure's state at t = 0, where the material points start "
      "stress-free and the boundary particles are made at the deformed "
      "interface (the MPM sees the interface's motion from then on): "
      "'loaded', in equilibrium under its pre-stress and its own loads "
      "(gravity, point loads) before the coupling (a barrier that hangs "
      "before the material arrives); 'unloaded', under its pre-stress only, "
      "its own loads acting from the first coupled step on, together with "
      "the MPM's gravity (one body split into two fields, e.g. "
      "tests/coupled/split_cantilever: with 'loaded' the material would be "
      "tied to the face as the structure's weight had already deformed "
      "it).");
    prm.enter_subsection("Interface");
    Coupling::StructureInterface<dim>::declare_parameters(prm);
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    prm.declare_entry("expected interface force",
                      "",
                      dealii::Patterns::Anything(),
                      "Empty, or the sum of the interface forces on the "
                      "structure at the end of the run, one component per "
                      "space dimension [N] (e.g. the weight of a block at "
                      "rest): checked with 'interface force tolerance'.");
    prm.declare_entry("interface force tolerance",
                      "1e-6",
                      dealii::Patterns::Double(0.),
                      "Largest |F - F_expected| / |F_expected| [-].");
    prm.declare_entry("maximum mean coupling iterations",
                      "0",
                      dealii::Patterns::Double(0.),
                      "If > 0: the coupling iterations per accepted step, "
                      "averaged over the run, must not exceed it.");
    prm.declare_entry(
      "energy balance tolerance",
      "0",
      dealii::Patterns::Double(0.),
      "If > 0: the largest change of the coupled system's energy (kinetic, "
      "strain and gravitational energy of both fields plus the MPM's "
      "dissipation) over the run, relative to the largest released "
      "gravitational energy of the material, must not exceed it.");
    prm.declare_entry(
      "barrier energy tolerance",
      "0",
      dealii::Patterns::Double(0.),
      "If > 0: the barrier's own energy account, the change of its kinetic "
      "and strain energy and its dissipation less the work of the interface "
      "force on it (the coupling.csv column interface_work: F_{n+1} . du "
      "per step with 'interface force in time = end of step', else the "
      "trapezoidal (F_n + F_{n+1})/2 . du), relative to the largest "
      "released gravitational energy of the material, must not exceed it "
      "at any step.");
    prm.declare_entry(
      "expected largest structure displacement",
      "0",
      dealii::Patterns::Double(0.),
      "If > 0: the largest nodal displacement |u| of the structure at the "
      "end of the run [m] (e.g. the static sag under a block at rest from "
      "a closed form), checked with 'structure displacement tolerance'.");
    prm.declare_entry("structure displacement tolerance",
                      "0.01",
                      dealii::Patterns::Double(0.),
                      "Largest |u_max - u_expected| / u_expected [-].");
    prm.declare_entry(
      "probe lower corner",
      "",
      dealii::Patterns::Anything(),
      "Empty, or the lower corner of a box (one coordinate per space "
      "dimension) [m]: the material points whose initial position lies in "
      "the box between it and 'probe upper corner' form the probe, whose "
      "mass-weighted mean displacement at the end of the run is printed "
      "(e.g. the last column of grid cells of a cantilever: its mean "
      "deflection).");
    prm.declare_entry("probe upper corner",
                      "",
                      dealii::Patterns::Anything(),
                      "Upper corner of the probe box [m] (with 'probe lower "
                      "corner').");
    prm.declare_entry(
      "expected probe displacement",
      "",
      dealii::Patterns::Anything(),
      "Empty, or the expected mean displacement of the probe at the end of "
      "the run, one component per space dimension [m] (e.g. the same mean "
      "of a monolithic solution): checked with 'probe displacement "
      "tolerance'.");
    prm.declare_entry("probe displacement tolerance",
                      "1e-2",
                      dealii::Patterns::Double(0.),
                      "Largest |u - u_expected| / |u_expected| of the "
                      "probe's mean displacement [-].");
    prm.declare_entry(
      "maximum final kinetic energy",
      "0",
      dealii::Patterns::Double(0.),
      "If > 0: the run must end at rest: the kinetic energy of both fields "
      "at the end, relative to the largest released gravitational energy "
      "of the material, must not exceed it [-].");
    prm.declare_entry(
      "minimum brake stroke",
      "0",
      dealii::Patterns::Double(0.),
      "If > 0: the largest brake stroke at the end must be at least this "
      "[m] (the brakes activated), and the brakes' dissipated energy, "
      "summed increment by increment, must equal its closed form sum F_a "
      "s + H s^2 / 2 over the brakes' strokes s within 'brake energy "
      "tolerance'.");
    prm.declare_entry("brake energy tolerance",
                      "1e-10",
                      dealii::Patterns::Double(0.),
                      "Largest |D - sum (F_a s + H s^2/2)| / D of the "
                      "brakes (with 'minimum brake stroke') [-].");
    prm.declare_entry(
      "conservation tolerance",
      "1e-10",
      dealii::Patterns::Double(0.),
      "Largest relative difference between the interface work of the "
      "structure's nodal vectors U . F and of the boundary particles "
      "sum u_p . f_p (the transfer is conservative: round-off).");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  CoupledSimulation<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                             const unsigned int n_boundaries)
  {
    Simulation<dim>::declare_parameters(prm, n_boundaries);
    StructureModels::declare_parameters(prm);
    declare_coupling_parameters(prm);
  }


  template <int dim>
  int
  CoupledSimulation<dim>::run(dealii::ParameterHandler &prm)
  {
    RunConsole                  console(prm, communicator);
    const bool                  root      = console.root;
    const bool                  test_mode = console.test_mode;
    dealii::ConditionalOStream &pcout     = console.pcout;
    dealii::TimerOutput        &timer     = console.timer;

    // The MPM.
    TimeControl time_control;
    time_control.parse_parameters(prm);
    ContactOnsetEvent contact_onset;
    contact_onset.parse_parameters(prm, time_control.initial_dt);
    EnergyJumpMonitor energy_jumps;
    energy_jumps.parse_parameters(prm);
    MPM::MPMProblem<dim> mpm(communicator, time_control.newmark, timer);
    mpm.parse_parameters(prm);
    IO::VisualizationOutput<dim> output;
    output.parse_parameters(prm);
    if (time_control.error_control.enabled())
      {
        if (mpm.solver().is_quasi_static())
          {
            prm.enter_subsection("Time");
            const std::string tolerance = prm.get("error tolerance");
            prm.leave_subsection();
            InputFile::reject("Time",
                              "error tolerance",
                              tolerance,
                              "0 with a quasi-static MPM (subsection "
                              "<Solver>: there are no accelerations to "
                              "estimate the error from)");
          }
        // the steps land on the output times
        time_control.set_event_interval(output.output_interval);
      }

    // Checkpoints (doc/checkpoint.md), and the one to resume from (checked
    // on rank 0 first: a complete checkpoint of a coupled run).
    IO::Checkpointing checkpointing;
    checkpointing.parse_parameters(prm, output.directory());
    checkpointing.set_problem("coupled");
    std::string resume_path;
    if (!resume_from.empty() || checkpointing.resume_requested())
      resume_path =
        IO::Checkpointing::find_and_check(resume_from.empty() ?
                                            checkpointing.directory() :
                                            resume_from,
                                          communicator,
                                          "coupled");
    const bool resuming = !resume_path.empty();

    // The structure, in equilibrium under its pre-stress and, 'loaded', its
    // loads.
    const StructureModels::Parameters sp =
      StructureModels::parse_parameters(prm);
    prm.enter_subsection("Coupling");
    const bool loaded_initially =
      prm.get("initial structure state") == "loaded";
    prm.leave_subsection();
    if (sp.dynamic)
      {
        const auto probe = StructureModels::create_model(sp);
        if (!probe->supports_dynamics())
          InputFile::reject("Structure/Dynamics",
                            "dynamic",
                            "true",
                            "false for model '" + sp.model_text +
                              "' (it has no dynamic form)");
      }
    auto                        model = StructureModels::create_model(sp);
    Structure::StructureProblem structure;
    structure.build(*model, 0);
    prm.enter_subsection(StructureModels::structure_section);
    structure.parse_solver_parameters(prm);
    structure.parse_dynamics_parameters(prm);
    prm.leave_subsection();
    structure.setup_solvers(*model);
    {
      dealii::TimerOutput::Scope scope(timer, "structure: initial state");
      if (model->prestress_step())
        {
          const auto status = structure.solve_load_factor(0.);
          if (!status.converged)
            throw ExcSimulationFailed(
              "the structure's pre-stress equilibrium did not converge: " +
              status.failure);
        }
      model->before_load_steps(structure.get_structure(),
                               structure.get_static_solver());
      if (loaded_initially)
        {
          const auto status = structure.solve_load_step(0., 1.);
          if (!status.converged)
            throw ExcSimulationFailed(
              "the structure's equilibrium under its loads (before the "
              "coupling) did not converge: " +
              status.failure);
        }
      structure.initialize();
    }

    // The coupling.
    Coupling::CouplingParameters parameters;
    parameters.parse_parameters(prm);
    Coupling::StructureInterface<dim> interface;
    prm.enter_subsection("Coupling");
    prm.enter_subsection("Interface");
    interface.parse_parameters(prm);
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    const auto expected_force =
      optional_vector<dim>(prm, "expected interface force");
    const double force_tolerance = prm.get_double("interface force tolerance");
    const double max_mean_iterations =
      prm.get_double("maximum mean coupling iterations");
    const double balance_tolerance = prm.get_double("energy balance tolerance");
    const double barrier_tolerance = prm.get_double("barrier energy tolerance");
    const double max_final_kinetic =
      prm.get_double("maximum final kinetic energy");
    const double conservation_tolerance =
      prm.get_double("conservation tolerance");
    const double min_brake_stroke = prm.get_double("minimum brake stroke");
    const double brake_tolerance  = prm.get_double("brake energy tolerance");
    const double expected_displacement =
      prm.get_double("expected largest structure displacement");
    const double displacement_tolerance =
      prm.get_double("structure displacement tolerance");
    const auto probe_lower = optional_vector<dim>(prm, "probe lower corner");
    const auto probe_upper = optional_vector<dim>(prm, "probe upper corner");
    const auto expected_probe =
      optional_vector<dim>(prm, "expected probe displacement");
    const double probe_tolerance =
      prm.get_double("probe displacement tolerance");
    const std::string probe_lower_text = prm.get("probe lower corner");
    const std::string probe_upper_text = prm.get("probe upper corner");
    const std::string expected_probe_text =
      prm.get("expected probe displacement");
    prm.leave_subsection();
    prm.leave_subsection();
    if (probe_lower.first != probe_upper.first)
      InputFile::reject(verification_section,
                        probe_lower.first ? "probe upper corner" :
                                            "probe lower corner",
                        "",
                        "a value: both corners of the probe box or neither");
    for (unsigned int d = 0; d < dim && probe_lower.first; ++d)
      if (!(probe_lower.second[d] < probe_upper.second[d]))
        InputFile::reject(verification_section,
                          "probe upper corner",
                          probe_upper_text,
                          "larger than 'probe lower corner' in every "
                          "coordinate");
    if (expected_probe.first && !probe_lower.first)
      InputFile::reject(verification_section,
                        "expected probe displacement",
                        expected_probe_text,
                        "empty without a probe box ('probe lower corner', "
                        "'probe upper corner')");

    interface.attach(structure.get_structure(), mpm.boundaries());
    // (before the MPM's setup, which checks the interface boundaries)
    if (parameters.interface_force_at_end)
      {
        for (const unsigned int b : interface.boundary_indices())
          mpm.boundaries().set_end_of_step_force(b);
        structure.set_interface_force_at_end();
      }
    mpm.setup();
    output.initialize(communicator);
    interface.setup(mpm.boundaries(), communicator);

    // The probe: mass-weighted mean displacement of the material points
    // that start in the probe box (collective), and their number.
    const auto probe = [&]() {
      using Properties = MPM::MaterialPointProperties<dim>;
      dealii::Tensor<1, dim> mu;
      double                 mass = 0., n = 0.;
      for (const auto &p : mpm.points().particle_handler())
        {
          const auto         props = p.get_properties();
          dealii::Point<dim> X;
          for (unsigned int d = 0; d < dim; ++d)
            X[d] = props[Properties::initial_position + d];
          bool inside = true;
          for (unsigned int d = 0; d < dim; ++d)
            inside = inside && X[d] >= probe_lower.second[d] &&
                     X[d] <= probe_upper.second[d];
          if (!inside)
            continue;
          const double m = props[Properties::mass];
          mu += m * (p.get_location() - X);
          mass += m;
          n += 1.;
        }
      mu   = dealii::Utilities::MPI::sum(mu, communicator);
      mass = dealii::Utilities::MPI::sum(mass, communicator);
      n    = dealii::Utilities::MPI::sum(n, communicator);
      return std::make_pair(mass > 0. ? mu / mass : mu,
                            static_cast<unsigned int>(n));
    };
    if (probe_lower.first && probe().second == 0)
      InputFile::reject(verification_section,
                        "probe lower corner",
                        probe_lower_text,
                        "a probe box that holds material points (this one, "
                        "up to 'probe upper corner', holds none)");

    Coupling::GaussSeidelCoupling<dim> coupling(
      mpm, structure, interface, parameters, timer, communicator);

    pcout << "Talus: " << dim << "D coupled MPM + structure, "
          << dealii::Utilities::MPI::n_mpi_processes(communicator)
          << " MPI rank(s)\n";
    mpm.print_summary(pcout);
    if (!test_mode &&
        dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cerr << mpm.solver().friction_at_rest_warning();
    if (!test_mode)
      pcout << "  " << mpm.memory_estimate().summary() << '\n';
    pcout << "  structure: model '" << sp.model_text << "' ("
          << model->description() << "), " << structure.get_structure().n_dofs()
          << " DoFs, " << (structure.is_dynamic() ? "dynamic" : "static")
          << (loaded_initially ? "" : ", unloaded at t = 0") << '\n'
          << "  interface: mesh '" << interface.mesh_name() << "', "
          << interface.n_points() << " boundary particles; "
          << (parameters.scheme ==
                  Coupling::CouplingParameters::Scheme::strong ?
                "strong" :
                "weak")
          << " coupling, "
          << (parameters.order ==
                  Coupling::CouplingParameters::Order::MPM_first ?
                "MPM first" :
                "structure first")
          << ", " << coupling.accelerator().name() << '\n';

    if (resuming)
      coupling.load_checkpoint(resume_path, sp.model_text);
    else
      coupling.initialize(0.);
    // Load balancing of the MPM (subsection Load balancing) between
    // committed steps: the interface is keyed by the boundary particles'
    // ids and reference positions, which a repartition carries. (A resumed
    // run: after its time control is read, below.)
    if (!resuming)
      mpm.balance_load(time_control.step, pcout);

    // Energies of both fields at the committed state.
    auto &S = structure.get_structure();
    struct Energies
    {
      double mpm = 0., structure = 0., dissipation = 0., released = 0.;
    };
    const auto energies = [&](const MPM::Diagnostics<dim> &d) {
      dealii::Vector<double> r;
      S.assemble(structure.displacement(), 1., r, nullptr);
      Energies e;
      // with the penalty springs of the boundaries (the interface's contact)
      e.mpm = d.mechanical_energy();
      // the structure's own loads only: the interface force is internal
      // to the coupled system (load_potential() includes -F . u)
      e.structure = structure.kinetic_energy() + S.strain_energy() +
                    S.load_potential(structure.displacement(), 1.) +
                    S.external_forces * structure.displacement();
      e.dissipation = d.dissipated_energy() + structure.dissipated_energy();
      return e;
    };
    // (a resumed run: those of t = 0, from the checkpoint)
    auto   initial_diagnostics = mpm.diagnostics();
    double initial_total       = 0.;
    if (!resuming)
      {
        const auto initial = energies(initial_diagnostics);
        initial_total = initial.mpm + initial.structure + initial.dissipation;
      }

    // What the time loop keeps besides the fields and the coupling
    // (checkpoints): the time control, the visualization records, the
    // CSV files up to the checkpoint and the running quantities of the
    // summary and the verification.
    unsigned long total_iterations = 0, total_rejected = 0, total_restarts = 0;
    double        max_u       = 0.; // the structure's largest nodal |u| [m]
    double        max_balance = 0., max_released = 0.;
    double        max_conservation = 0.;
    double        final_kinetic    = 0.; // both fields, at the end [J]
    double        final_mass       = initial_diagnostics.mass;
    // the step chosen by the error: the smallest and largest step
    double smallest_dt = std::numeric_limits<double>::max(), largest_dt = 0.;
    // an adaptive MPM grid: the passes that changed it, the coupling
    // iterations of the steps right after them and of the others, the
    // largest displacement of an interface point between two passes [m]
    // (from the structure displacement at the last pass, changed or
    // not), the largest
    // relative difference between the boundary particles' forces on the
    // grid (hanging nodes condensed) and their reactions
    const bool    adaptive_grid = mpm.adaptive_grid().enabled();
    unsigned long grid_changes = 0, iterations_after_change = 0,
                  steps_after_change            = 0;
    bool                   changed_before_step  = false;
    double                 max_interface_travel = 0., max_reaction_balance = 0.;
    dealii::Vector<double> displacement_at_pass = structure.displacement();
    // steps rejected for an energy jump, jumps kept at the step limit
    unsigned int energy_rejections = 0, energy_jumps_kept = 0;
    // the barrier's account: the interface force's work on it, its energy
    // and dissipation at the start, the largest difference [J]
    double interface_work = 0., initial_barrier = 0., max_barrier_gap = 0.;
    if (!resuming)
      initial_barrier =
        energies(initial_diagnostics).structure + structure.dissipated_energy();
    const auto loop_state = [&](auto &archive) {
      archive &time_control &output &initial_diagnostics &initial_total
        &total_iterations &total_rejected &total_restarts &max_u &max_balance
          &max_released &max_conservation &final_kinetic &final_mass &S
            .vtu_records();
      // the step chosen by the error and the contact onset event
      double       &last_error       = time_control.last_error;
      unsigned int &error_rejections = time_control.error_rejections;
      archive &last_error &error_rejections &smallest_dt &largest_dt
        &contact_onset;
      archive &grid_changes &iterations_after_change &steps_after_change
        &changed_before_step &max_interface_travel &max_reaction_balance
          &displacement_at_pass;
      // the energy jumps (EnergyJumpMonitor)
      archive &energy_jumps &energy_rejections &energy_jumps_kept;
      archive &interface_work &initial_barrier &max_barrier_gap;
    };
    const std::string loop_tag = "talus-coupled-time-loop";
    if (resuming)
      {
        IO::Checkpointing::load_archive(resume_path,
                                        resume_path + "/time_loop",
                                        loop_tag,
                                        loop_state);
        mpm.balance_load(time_control.step, pcout);
      }

    std::ofstream csv;
    if (root && resuming)
      {
        // the rows up to the checkpoint (a killed run's later rows go)
        if (copy_file(resume_path + "/coupling.csv",
                      output.directory() + "/coupling.csv"))
          csv.open(output.directory() + "/coupling.csv", std::ios::app);
        if (!csv.is_open() || !csv)
          throw ExcSimulationFailed("cannot write <" + output.directory() +
                                    "/coupling.csv> (a copy of <" +
                                    resume_path + "/coupling.csv>)");
        csv << std::setprecision(12);
      }
    else if (root)
      {
        csv.open(output.directory() + "/coupling.csv");
        if (!csv)
          throw ExcSimulationFailed("cannot write <" + output.directory() +
                                    "/coupling.csv>");
        csv << "step,time,dt,coupling_iterations,interface_residual,"
               "relaxation,mpm_newton,structure_newton";
        for (unsigned int d = 0; d < dim; ++d)
          csv << ",interface_force_" << char('x' + d);
        csv << ",work_structure,work_points,mpm_energy,structure_energy,"
               "dissipation,energy_change,max_structure_displacement,"
               "penetration,mass,kinetic_energy,gravitational_energy,"
               "strain_energy,spring_energy,plastic_dissipation,"
               "friction_dissipation,numerical_dissipation,barrier_kinetic,"
               "barrier_dissipation,interface_work";
        // the friction dissipation split by boundary (slope, net, ...)
        for (unsigned int b = 0; b < mpm.boundaries().n_boundaries(); ++b)
          csv << ',' << mpm.boundaries().name(b) << "_friction_dissipation";
        csv << '\n';
        csv << std::setprecision(12);
      }
    // the barrier's member forces, brake strokes and dissipation
    IO::StructureTimeSeries barrier_series;
    const auto              impact_columns = [&]() {
      const auto columns = model->impact_columns(S,
                                                 structure.displacement(),
                                                 structure.interface_forces());
      std::pair<std::vector<std::string>, std::vector<double>> split;
      for (const auto &[name, value] : columns)
        {
          split.first.push_back(name);
          split.second.push_back(value);
        }
      return split;
    };
    if (resuming)
      {
        barrier_series.resume(output.directory() + "/structure.csv",
                              resume_path + "/structure.csv",
                              root,
                              impact_columns().first.size());
        output.write_index(communicator);
        pcout << "  resumed from " << resume_path << " at step "
              << time_control.step << ", t = " << time_control.time << " s\n";
      }
    else
      {
        barrier_series.open(output.directory() + "/structure.csv",
                            S,
                            root,
                            impact_columns().first);
        barrier_series.write(0.,
                             S,
                             structure.displacement(),
                             structure.dissipated_energy(),
                             impact_columns().second);
      }

    // Write a checkpoint of the committed state; returns its path.
    const auto write_checkpoint = [&](const std::string &reason) {
      const auto path = checkpointing.write(
        time_control.step,
        time_control.time,
        reason,
        [&](const std::string &directory) {
          coupling.save_checkpoint(directory, sp.model_text);
          if (root)
            {
              // (the rows up to this step: both files are flushed by row)
              csv.flush();
              // (a failed copy leaves the file out: the resume says so;
              // no exception on one rank inside the collective write)
              for (const std::string name : {"coupling.csv", "structure.csv"})
                if (!copy_file(output.directory() + "/" + name,
                               directory + "/" + name))
                  std::cerr << "Warning: cannot copy <" << output.directory()
                            << "/" << name << "> into the checkpoint <"
                            << directory << ">\n";
              IO::Checkpointing::save_archive(directory + "/time_loop",
                                              loop_tag,
                                              loop_state);
            }
        },
        communicator);
      pcout << "  checkpoint (" << reason << ") at step " << time_control.step
            << ", t = " << time_control.time << " s: " << path << '\n';
      return path;
    };

    const auto wall_start = std::chrono::steady_clock::now();
    Coupling::CoupledStepResult<dim> result;
    // the structure's committed displacement (its error estimate)
    dealii::Vector<double> structure_committed = structure.displacement();
    // The estimated truncation error of the solved coupled step of size
    // dt: the larger of the MPM's and the dynamic structure's.
    const auto step_error = [&](const double dt) {
      const auto  &control   = time_control.error_control;
      const auto   mpm_norms = mpm.solver().truncation_error_norms();
      const double e_mpm =
        control.error(mpm_norms, dt, time_control.newmark.beta);
      if (!structure.is_dynamic())
        return e_mpm;
      const auto structure_norms =
        Structure::truncation_error_norms(structure, structure_committed, dt);
      const double beta_structure = Structure::newmark_beta(structure);
      const double e_structure =
        control.error(structure_norms, dt, beta_structure);
      const double e_combined =
        control.mass_weighted_error({{mpm_norms, time_control.newmark.beta},
                                     {structure_norms, beta_structure}},
                                    dt);
      if (std::getenv("TALUS_DEBUG_ERROR_ESTIMATE") && root)
        std::cerr << "t = " << time_control.time << " dt = " << dt
                  << " error: MPM " << e_mpm << " structure " << e_structure
                  << " mass weighted " << e_combined << '\n';
      return control.mass_weighted_coupled ? e_combined :
                                             std::max(e_mpm, e_structure);
    };
    // the balance of the interface forces on a locally refined grid
    // (before the commit of the step solved last)
    const auto reaction_balance = [&]() {
      // the interface reactions are conservative across hanging
      // nodes: the particles' forces on the grid (condensed by
      // deal.II) and their reactions add up to zero
      const auto [on_grid, reactions] = mpm.solver().boundary_force_balance();
      const double scale = std::max(on_grid.norm(), reactions.norm());
      return scale > 0. ? (on_grid + reactions).norm() / scale : 0.;
    };
    // 'energy jump action = reject' (EnergyJumpMonitor): an accepted step
    // is committed on a copy of the committed state of both fields and
    // the coupling and checked; whether the step in hand was committed
    // so, and its reaction balance
    bool                  committed_for_check = false;
    std::optional<double> checked_reaction_balance;
    // true: keep the accepted step of size dt (committed if checked),
    // false: it jumps and was undone, retry with the halved step
    const auto keep_energy = [&](const double dt) {
      if (!energy_jumps.rejects())
        return true;
      if (adaptive_grid)
        checked_reaction_balance = reaction_balance();
      coupling.save_state();
      double change = 0., scale = 0.;
      try
        {
          coupling.commit_step();
          const auto d = mpm.diagnostics();
          const auto e = energies(d);
          change       = e.mpm + e.structure + e.dissipation - initial_total;
          const double released =
            std::max(max_released,
                     std::abs(d.gravitational_energy -
                              initial_diagnostics.gravitational_energy));
          scale = released + d.kinetic_energy + structure.kinetic_energy();
        }
      catch (...)
        {
          coupling.restore_state(time_control.time);
          checked_reaction_balance.reset();
          throw;
        }
      committed_for_check = true;
      const std::string line =
        energy_jump_rejection(energy_jumps,
                              change,
                              scale,
                              mpm.points().count_lost() > 0,
                              pcout,
                              time_control,
                              dt,
                              energy_jumps_kept);
      if (line.empty())
        return true;
      coupling.restore_state(time_control.time);
      committed_for_check = false;
      checked_reaction_balance.reset();
      ++total_rejected;
      ++energy_rejections;
      pcout << line;
      return false;
    };
    double dt_taken = 0.;

    Boundaries::MaterialBehindBoundaries<dim> behind_boundaries(
      mpm.boundaries(), mpm.grid());
    const MPM::ContactForecast<dim> contact_forecast(
      mpm.boundaries(),
      behind_boundaries,
      mpm.grid().minimal_cell_diameter,
      [&mpm](const auto &F) {
        return mpm.solver().point_domain_half_extent(F);
      });
    while (!time_control.finished())
      {
        // shorten the step ahead of a forecast contact onset
        contact_forecast.shorten_ahead(contact_onset,
                                       time_control,
                                       mpm.points().particle_handler(),
                                       mpm.solver().gravity(),
                                       communicator);
        // an exception in the attempts stops the run with a checkpoint of
        // the last accepted step (the attempts change trial state only;
        // the accelerator's window is dropped as for a rejected step)
        solve_or_checkpoint(
          [&]() {
            while (true)
              {
                const double dt = time_control.next_step();
                try
                  {
                    result = coupling.solve_step(time_control.time, dt);
                  }
                catch (...)
                  {
                    coupling.reject_step();
                    throw;
                  }
                dt_taken = dt;
                if (result.converged)
                  {
                    // the contact onset event (ContactOnsetEvent)
                    if (contact_onset.enabled() &&
                        contact_onset.assess(
                          time_control,
                          dt,
                          count_active_contacts(
                            mpm.solver().boundary_reactions(), communicator)))
                      {
                        ++total_rejected;
                        coupling.reject_step();
                        if (!test_mode)
                          pcout << rejected_step_line(pcout.get_stream(),
                                                      time_control.step,
                                                      time_control.time,
                                                      dt,
                                                      "contact onset",
                                                      time_control.next_step());
                        continue;
                      }
                    if (!time_control.error_control.enabled())
                      {
                        if (keep_energy(dt))
                          break;
                        continue;
                      }
                    // the step chosen by the error (TruncationErrorControl)
                    const double error = step_error(dt);
                    if (time_control.assess_error(dt, error))
                      {
                        if (keep_energy(dt))
                          break;
                        continue;
                      }
                    ++total_rejected;
                    coupling.reject_step();
                    if (!test_mode)
                      pcout << error_rejected_step_line(pcout.get_stream(),
                                                        time_control,
                                                        dt,
                                                        error);
                    continue;
                  }
                ++total_rejected;
                coupling.reject_step();
                pcout << rejected_step_line(pcout.get_stream(),
                                            time_control.step,
                                            time_control.time,
                                            dt,
                                            result.failure);
                if (!time_control.reject())
                  {
                    std::ostringstream msg;
                    msg << "The coupled step from t = " << time_control.time
                        << " s could not be solved after "
                        << time_control.halvings
                        << " halvings of the time step (last dt = " << dt
                        << " s): " << result.failure
                        << ". Raise 'maximum coupling iterations' or change "
                           "'acceleration' in subsection <Coupling>, reduce "
                           "'time step' or raise 'maximum step halvings' in "
                           "subsection <Time>.";
                    if (checkpointing.enabled())
                      msg << failure_checkpoint_note(
                        time_control.step,
                        time_control.time,
                        write_checkpoint("failure: coupled step not solved"));
                    throw ExcSimulationFailed(msg.str());
                  }
              }
          },
          checkpointing,
          time_control.step,
          time_control.time,
          write_checkpoint,
          communicator);
        const double dt = dt_taken;
        if (adaptive_grid)
          max_reaction_balance =
            std::max(max_reaction_balance,
                     checked_reaction_balance ? *checked_reaction_balance :
                                                reaction_balance());
        checked_reaction_balance.reset();
        if (!committed_for_check)
          coupling.commit_step();
        committed_for_check = false;
        structure_committed = structure.displacement();
        time_control.accept(dt);
        contact_onset.accepted(time_control);
        if (time_control.error_control.enabled() || contact_onset.enabled())
          {
            smallest_dt = std::min(smallest_dt, dt);
            largest_dt  = std::max(largest_dt, dt);
          }
        if (adaptive_grid)
          {
            // the interface's travel since the last pass of the grid, in
            // cells of the finest level (the band of 'neighbour layers'
            // around the boundary particles must hold it)
            dealii::Vector<double> travel = structure.displacement();
            travel -= displacement_at_pass;
            for (const auto &u : interface.point_displacements(travel))
              max_interface_travel = std::max(max_interface_travel, u.norm());
            if (changed_before_step)
              {
                iterations_after_change += result.iterations;
                ++steps_after_change;
              }
          }
        changed_before_step = false;
        if (!time_control.finished())
          {
            // (a pass of the adaptive grid is due after this step: the
            // interface's travel counts from here)
            if (mpm.adaptive_grid().due(time_control.step))
              displacement_at_pass = structure.displacement();
            const auto record = mpm.balance_load(time_control.step, pcout);
            if (record.adapted)
              {
                ++grid_changes;
                changed_before_step = true;
                // (the check that the accelerator's history survives a
                // grid change, doc/debugging.md: drop it there instead)
                if (std::getenv("TALUS_DEBUG_RESET_ACCELERATOR_AT_GRID_CHANGE"))
                  coupling.reject_step();
              }
          }
        total_iterations += result.iterations;
        total_restarts += result.restarts;

        const auto lost = mpm.take_losses();
        // the message of a stop by lost points: the run stops at the end
        // of this step (its rows and output written), so that its
        // checkpoint continues as a scheduled one would
        std::string lost_points_stop;
        if (lost.n_points > 0)
          {
            std::ostringstream msg;
            msg << lost.n_points << " material point(s) with a mass of "
                << lost.mass
                << " kg left the background grid at t = " << time_control.time
                << " s";
            if (mpm.solver().abort_on_lost_points)
              lost_points_stop = msg.str() +
                                 "; 'abort on lost material points' is set. "
                                 "Enlarge the background grid.";
            else
              pcout << "  Warning: " << msg.str() << '\n';
          }
        for (unsigned int b = 0; b < lost.boundary_particles.size(); ++b)
          if (lost.boundary_particles[b] > 0)
            pcout << "  Warning: " << lost.boundary_particles[b]
                  << " boundary particle(s) of boundary '"
                  << mpm.boundaries().name(b)
                  << "' left the background grid at t = " << time_control.time
                  << " s and no longer act.\n";

        pcout << behind_boundaries.assess(
          behind_boundaries.survey(mpm.points().particle_handler(),
                                   MPM::MaterialPointProperties<dim>::mass,
                                   communicator),
          time_control.time);

        const auto diagnostics = mpm.diagnostics();
        const auto e           = energies(diagnostics);
        final_kinetic = diagnostics.kinetic_energy + structure.kinetic_energy();
        final_mass    = diagnostics.mass;
        const double change =
          e.mpm + e.structure + e.dissipation - initial_total;
        max_balance = std::max(max_balance, std::abs(change));
        interface_work += result.interface_work;
        max_barrier_gap =
          std::max(max_barrier_gap,
                   std::abs(e.structure + structure.dissipated_energy() -
                            initial_barrier - interface_work));
        max_released =
          std::max(max_released,
                   std::abs(diagnostics.gravitational_energy -
                            initial_diagnostics.gravitational_energy));
        pcout << energy_jumps.assess(time_control.step,
                                     time_control.time,
                                     change,
                                     max_released + final_kinetic,
                                     lost.n_points > 0);
        const double scale = std::max({std::abs(result.work_structure),
                                       std::abs(result.work_points),
                                       1e-300});
        max_conservation =
          std::max(max_conservation,
                   std::abs(result.work_structure - result.work_points) /
                     scale);
        max_u = 0.;
        for (unsigned int k = 0; k < S.n_nodes(); ++k)
          max_u =
            std::max(max_u,
                     S.node_displacement(structure.displacement(), k).norm());
        double penetration = 0.;
        for (const auto &b : diagnostics.boundaries)
          penetration = std::max(penetration, b.penetration);
        if (root)
          {
            csv << time_control.step << ',' << time_control.time << ',' << dt
                << ',' << result.iterations << ',' << result.status.residual
                << ',' << result.relaxation << ',' << result.mpm_newton << ','
                << result.structure_newton;
            for (unsigned int d = 0; d < dim; ++d)
              csv << ',' << result.interface_force[d];
            csv << ',' << result.work_structure << ',' << result.work_points
                << ',' << e.mpm << ',' << e.structure << ',' << e.dissipation
                << ',' << change << ',' << max_u << ',' << penetration << ','
                << diagnostics.mass;
            // the energies by category: the material's (kinetic,
            // gravitational, strain, penalty springs), its dissipation
            // (plastic flow, friction on every boundary, the numerical
            // dissipation of velocity resets, the transfer and the time
            // integrator), the
            // barrier's kinetic energy and dissipation (brakes, damping,
            // plasticity); the barrier's elastic energy is
            // structure_energy - barrier_kinetic
            const double springs = diagnostics.spring_energy();
            csv << ',' << diagnostics.kinetic_energy << ','
                << diagnostics.gravitational_energy << ','
                << diagnostics.strain_energy << ',' << springs << ','
                << diagnostics.plastic_dissipation << ','
                << diagnostics.friction_dissipation << ','
                << diagnostics.reset_dissipation +
                     diagnostics.transfer_dissipation +
                     diagnostics.integrator_dissipation
                << ',' << structure.kinetic_energy() << ','
                << structure.dissipated_energy() << ',' << interface_work;
            for (const double w : diagnostics.boundary_friction_dissipation)
              csv << ',' << w;
            csv << '\n';
            csv.flush();
          }
        // S was assembled at the committed state by energies()
        barrier_series.write(time_control.time,
                             S,
                             structure.displacement(),
                             structure.dissipated_energy(),
                             impact_columns().second);
        if (output.due(time_control.time) || time_control.finished())
          {
            dealii::TimerOutput::Scope s(timer, "output");
            output.write(time_control.time,
                         mpm.grid(),
                         mpm.points(),
                         &mpm.solver().grid_velocity());
            if (root && output.writes_files())
              S.write_vtu(structure.displacement(),
                          output.directory(),
                          time_control.step,
                          time_control.time);
            if (!test_mode)
              {
                const double wall =
                  std::chrono::duration<double>(
                    std::chrono::steady_clock::now() - wall_start)
                    .count();
                pcout << "step " << std::setw(6) << time_control.step
                      << "  t = " << std::scientific << std::setprecision(4)
                      << time_control.time
                      << " s  dt = " << std::setprecision(2) << dt
                      << " s  coupling " << result.iterations << "  |r| "
                      << result.status.residual << "  omega "
                      << result.relaxation
                      << (result.restarts > 0 ?
                            "  restarts " + std::to_string(result.restarts) :
                            std::string())
                      << (result.contact_restarts > 0 ?
                            "  contact restarts " +
                              std::to_string(result.contact_restarts) :
                            std::string())
                      << "  Newton MPM " << result.mpm_newton << " structure "
                      << result.structure_newton
                      << "  F = " << result.interface_force << std::defaultfloat
                      << "  wall " << std::setprecision(3) << wall << " s\n";
              }
          }
        end_accepted_step(checkpointing,
                          time_control.step,
                          time_control.time,
                          time_control.finished(),
                          lost_points_stop,
                          write_checkpoint,
                          std::function<void()>(),
                          communicator);
      }

    // (debugging and the checkpoint tests: every point in full precision)
    if (const char *dump = std::getenv("TALUS_DEBUG_DUMP_POINTS"))
      IO::write_points_text(mpm.points(), dump, communicator);
    // (the error studies: the structure's displacement, one dof per line)
    if (const char *dump = std::getenv("TALUS_DEBUG_DUMP_STRUCTURE"))
      if (root)
        {
          std::ofstream file(dump);
          file << std::setprecision(17);
          for (const double u : structure.displacement())
            file << u << '\n';
        }

    const double mean_iterations =
      static_cast<double>(total_iterations) / std::max(1u, time_control.step);
    pcout << "Done: " << time_control.step << " coupled steps ("
          << total_rejected << " rejected), " << std::setprecision(3)
          << mean_iterations << " coupling iterations per step"
          << (total_restarts > 0 ? ", " + std::to_string(total_restarts) +
                                     " safeguarded accelerator restarts" :
                                   std::string())
          << "\n"
          << std::setprecision(8)
          << "  interface force at the end: " << result.interface_force
          << " N\n";
    // (counted in this process: a checkpoint does not carry them)
    if (energy_jumps.rejects())
      pcout << "  energy jumps ('energy jump action = reject'): "
            << energy_rejections << " steps rejected, " << energy_jumps_kept
            << " committed with their jump (no halving left)\n";
    if (time_control.error_control.enabled())
      pcout << "  steps chosen by the error: " << time_control.step
            << " steps, " << time_control.error_rejections
            << " rejected for their error, dt " << std::setprecision(4)
            << smallest_dt << " .. " << largest_dt << " s\n";
    if (contact_onset.enabled())
      pcout << "  contact onset: " << contact_onset.shortened
            << " steps shortened ahead of a forecast onset, "
            << contact_onset.rejections
            << " steps rejected at a sharp change of the active set (onset "
               "step "
            << contact_onset.onset_dt << " s), dt " << std::setprecision(4)
            << smallest_dt << " .. " << largest_dt << " s\n";
    pcout << "  largest energy change " << std::setprecision(3) << max_balance
          << " J (largest released gravitational energy " << max_released
          << " J)\n"
          << "  interface work, structure vs points: largest relative "
             "difference "
          << (max_conservation < 1e-12 ? std::string("< 1e-12") :
                                         std::to_string(max_conservation))
          << '\n';
    if (adaptive_grid)
      {
        const auto &grid = mpm.grid();
        double      h    = grid.minimal_cell_diameter / std::sqrt(1. * dim);
        if (grid.is_cartesian)
          h = *std::min_element(grid.cell_extent.begin_raw(),
                                grid.cell_extent.end_raw());
        const auto        &adaptive = mpm.adaptive_grid();
        const unsigned int other_steps =
          time_control.step -
          std::min<unsigned long>(time_control.step, steps_after_change);
        const unsigned long other_iterations =
          total_iterations - iterations_after_change;
        pcout << "  adaptive grid: " << grid_changes
              << " passes changed the grid; at the end "
              << grid.triangulation.n_global_active_cells() << " cells, "
              << grid.dof_handler.n_dofs() << " DoFs\n";
        mpm.print_adaptive_grid(pcout);
        pcout << "  adaptive grid: largest interface displacement between "
                 "two passes "
              << std::setprecision(3) << max_interface_travel / h
              << " cells of the finest level (neighbour layers "
              << adaptive.neighbour_layers() << ")\n";
        if (max_interface_travel > adaptive.neighbour_layers() * h)
          pcout << "  Warning: the interface travelled farther than the "
                   "band of 'neighbour layers' around its boundary "
                   "particles between two passes of the grid, so it may "
                   "have reached coarser cells within a step: raise "
                   "'neighbour layers' or lower 'refine every steps' in "
                   "subsection <Adaptive grid>.\n";
        pcout << "  adaptive grid: coupling iterations per step "
              << (steps_after_change > 0 ?
                    static_cast<double>(iterations_after_change) /
                      steps_after_change :
                    0.)
              << " right after a grid change (" << steps_after_change
              << " steps), "
              << (other_steps > 0 ?
                    static_cast<double>(other_iterations) / other_steps :
                    0.)
              << " otherwise (" << other_steps << " steps)\n"
              << "  boundary particle forces on the grid (hanging nodes "
                 "condensed) vs their reactions: largest relative "
                 "difference "
              << (max_reaction_balance < 1e-12 ?
                    std::string("< 1e-12") :
                    (std::ostringstream()
                     << std::scientific << std::setprecision(2)
                     << max_reaction_balance)
                      .str())
              << '\n';
      }
    {
      // mass of the material points: exact unless points left the grid
      const double change = std::abs(final_mass - initial_diagnostics.mass) /
                            std::max(initial_diagnostics.mass, 1e-300);
      pcout << "  mass of the material points: relative change "
            << (change < 1e-14 ? std::string("< 1e-14") :
                                 std::to_string(change))
            << '\n';
    }
    pcout << behind_boundaries.summary();
    // (not in test mode: the test outputs do not depend on the machine)
    {
      const std::string memory = memory_summary(communicator);
      if (!test_mode)
        pcout << memory;
    }

    if (std::getenv("TALUS_DEBUG_COUPLING") && root)
      for (unsigned int k = 0; k < S.n_nodes(); ++k)
        std::cerr << "node " << S.node_position(k) << "  u "
                  << S.node_displacement(structure.displacement(), k) << "  F "
                  << S.external_force(k) << '\n';

    // Verification.
    std::vector<std::string> failed;
    if (expected_force.first)
      {
        const double error =
          (result.interface_force - expected_force.second).norm() /
          std::max(expected_force.second.norm(), 1e-300);
        pcout << "  interface force error " << error << " (tolerance "
              << force_tolerance << ")\n";
        if (!(error <= force_tolerance))
          failed.push_back("interface force");
      }
    if (probe_lower.first)
      {
        const auto [u, n] = probe();
        pcout << "  probe: mean displacement of " << n << " material points "
              << std::setprecision(6) << u << " m\n";
        if (expected_probe.first)
          {
            const double error = (u - expected_probe.second).norm() /
                                 std::max(expected_probe.second.norm(), 1e-300);
            pcout << "  probe displacement error " << std::setprecision(3)
                  << error << " (tolerance " << probe_tolerance << ")\n";
            if (!(error <= probe_tolerance))
              failed.push_back("probe displacement");
          }
      }
    if (max_mean_iterations > 0. && mean_iterations > max_mean_iterations)
      failed.push_back("mean coupling iterations");
    if (balance_tolerance > 0.)
      {
        const double relative = max_balance / std::max(max_released, 1e-300);
        pcout << "  energy balance: largest change / released = " << relative
              << " (tolerance " << balance_tolerance << ")\n";
        if (!(relative <= balance_tolerance))
          failed.push_back("energy balance");
      }
    if (barrier_tolerance > 0.)
      {
        const double relative =
          max_barrier_gap / std::max(max_released, 1e-300);
        pcout << "  barrier energy: largest change less the interface "
                 "force's work / released = "
              << relative << " (tolerance " << barrier_tolerance << ")\n";
        if (!(relative <= barrier_tolerance))
          failed.push_back("barrier energy");
      }
    if (expected_displacement > 0.)
      {
        const double error =
          std::abs(max_u - expected_displacement) / expected_displacement;
        pcout << "  largest structure displacement " << std::setprecision(6)
              << max_u << " m (expected " << expected_displacement
              << " m, relative error " << std::setprecision(3) << error
              << ", tolerance " << displacement_tolerance << ")\n";
        if (!(error <= displacement_tolerance))
          failed.push_back("structure displacement");
      }
    if (max_final_kinetic > 0.)
      {
        const double relative = final_kinetic / std::max(max_released, 1e-300);
        pcout << "  kinetic energy at the end / released = "
              << std::setprecision(3) << relative << " (at most "
              << max_final_kinetic << ")\n";
        if (!(relative <= max_final_kinetic))
          failed.push_back("rest at the end");
      }
    if (min_brake_stroke > 0.)
      {
        const BrakeAccount brakes = brake_account(S);
        if (brakes.n_brakes == 0)
          InputFile::reject(verification_section,
                            "minimum brake stroke",
                            std::to_string(min_brake_stroke),
                            "0: the structure has no brakes");
        const double error = std::abs(brakes.dissipated - brakes.closed_form) /
                             std::max(brakes.dissipated, 1e-300);
        pcout << "  brakes: largest stroke " << std::setprecision(4)
              << brakes.largest_stroke << " m (at least " << min_brake_stroke
              << " m); dissipated " << std::setprecision(6) << brakes.dissipated
              << " J, sum F_a s + H s^2/2 = " << brakes.closed_form
              << " J, relative difference "
              << (error < 1e-12 ? std::string("< 1e-12") :
                                  std::to_string(error))
              << " (tolerance " << brake_tolerance << ")\n";
        if (!(brakes.largest_stroke >= min_brake_stroke))
          failed.push_back("brake stroke");
        if (!(error <= brake_tolerance))
          failed.push_back("brake energy");
      }
    if (!(max_conservation <= conservation_tolerance))
      failed.push_back("interface conservation");
    if (!(max_reaction_balance <= conservation_tolerance))
      failed.push_back("reactions on the adaptive grid");
    if (!failed.empty())
      {
        std::string list;
        for (const auto &f : failed)
          list += (list.empty() ? "" : ", ") + f;
        throw ExcVerificationFailed("coupled verification failed: " + list);
      }
    return 0;
  }


  template class CoupledSimulation<2>;
  template class CoupledSimulation<3>;
} // namespace Talus
