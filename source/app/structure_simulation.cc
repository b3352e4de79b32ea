#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_simulation.h>
#include <talus/base/input.h>
#include <talus/structure/barrier_builder.h>
#include <talus/structure/continuum_solid.h>
#include <talus/structure/dynamic_solver.h>
#include <talus/structure/mesh_input.h>
#include <talus/structure/plane_string.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>
#include <talus/structure/structure_problem.h>

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_values.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace StructureSimulation
  {
    namespace
    {
      using namespace dealii;
      using StructureModels::create_model;
      using StructureModels::Model;
      using StructureModels::Parameters;
      using StructureModels::parse_parameters;
      using StructureModels::Result;
      using StructureModels::structure_columns;
      using Talus::Structure::Structure;
      using Talus::Structure::StructurePart;

      const std::string &S = StructureModels::structure_section;


      /**
       * Whether the free rotation of @p part (Structure::parts(),
       * can_rotate) is a mechanism to reject at set-up: in static runs
       * always when the part has a membrane or a solid; a part of cables
       * and trusses only when it is held at a single point (a cable held
       * at its two ends may swing about their line, stabilised by its
       * tension and load, e.g. the catenary). In dynamic runs a part with
       * mass may move freely (as for the translations).
       */
      bool
      rotation_is_mechanism(const Parameters    &p,
                            const Model         &model,
                            const StructurePart &part)
      {
        if (p.dynamic && !model.form_finding_before_dynamics() &&
            part.mass > 0.)
          return false;
        return part.has_continuum || part.held_at_one_point;
      }
    } // namespace


    void
    declare_parameters(ParameterHandler &prm)
    {
      StructureModels::declare_parameters(prm);
    }


    int
    run_parameter_file(const std::string &filename)
    {
      ParameterHandler prm;
      prm.declare_entry("problem", "structure", Patterns::Anything());
      prm.declare_entry("dimension", "3", Patterns::Integer(2, 3));
      declare_parameters(prm);
      prm.parse_input(filename);
      if (prm.get_integer("dimension") != 3)
        InputFile::reject("",
                          "dimension",
                          prm.get("dimension"),
                          "the structure models are three-dimensional "
                          "(remove the entry or set it to 3)");
      const Parameters p = parse_parameters(prm);
      try
        {
          std::filesystem::create_directories(p.directory);
        }
      catch (const std::exception &)
        {
          InputFile::reject(S + "/Output",
                            "output directory",
                            p.directory,
                            "the directory cannot be created");
        }

      std::cout << "Talus: barrier structure, model '" << p.model_text
                << "': " << create_model(p)->description() << '\n';
      ConvergenceTable                 table;
      std::vector<std::vector<Result>> level_results;
      for (unsigned int level = p.first_level;
           level < p.first_level + p.n_levels;
           ++level)
        {
          auto                               model = create_model(p);
          Talus::Structure::StructureProblem problem;
          problem.build(*model, level);
          Structure &structure = problem.get_structure();
          // A part held by no support (an unconnected component) makes the
          // static stiffness singular; in a dynamic run a part with mass
          // may move freely.
          for (const auto &part : structure.parts())
            if (!(part.held[0] && part.held[1] && part.held[2]) &&
                (!p.dynamic || model->form_finding_before_dynamics() ||
                 !(part.mass > 0.)))
              {
                std::string free;
                for (unsigned int d = 0; d < 3; ++d)
                  if (!part.held[d])
                    free +=
                      std::string(free.empty() ? "" : ", ") + char('x' + d);
                const bool nothing =
                  !(part.held[0] || part.held[1] || part.held[2]);
                std::ostringstream names, msg;
                for (unsigned int k = 0; k < part.meshes.size(); ++k)
                  names << (k > 0 ? ", " : "") << part.meshes[k];
                msg << "every part of the structure must be held by "
                       "supports in x, y and z, directly or through nodes it "
                       "shares with a held part (vertices of different "
                       "meshes closer than 1e-8 of the structure size are "
                       "tied), and the part made of mesh <"
                    << names.str() << "> (" << part.n_nodes
                    << " nodes, one at (" << part.a_node[0] << ", "
                    << part.a_node[1] << ", " << part.a_node[2] << ")) is "
                    << (nothing ? "connected to nothing" :
                                  "held by no support along " + free)
                    << ": its static stiffness would be singular (it can "
                       "translate freely along "
                    << free << ")";
                const auto what = model->support_parameter();
                InputFile::reject(what[0], what[1], what[2], msg.str());
              }
          // A part held in x, y and z whose supports lie at one point or on
          // one line can still rotate about that line (a rigid-body
          // mechanism: Newton would fail on a singular matrix later).
          for (const auto &part : structure.parts())
            if (part.can_rotate && rotation_is_mechanism(p, *model, part))
              {
                std::ostringstream names, msg;
                for (unsigned int k = 0; k < part.meshes.size(); ++k)
                  names << (k > 0 ? ", " : "") << part.meshes[k];
                // Round-off of the eigenvectors: print 0 for |v| < 1e-9.
                const auto clean = [](const double v) {
                  return std::abs(v) < 1e-9 ? 0. : v;
                };
                const auto point = [&](const Tensor<1, 3> &v) {
                  std::ostringstream o;
                  o << '(' << clean(v[0]) << ", " << clean(v[1]) << ", "
                    << clean(v[2]) << ')';
                  return o.str();
                };
                msg << "the part made of mesh <" << names.str() << "> ("
                    << part.n_nodes << " nodes, one at " << point(part.a_node)
                    << ") is held in x, y and z, but ";
                if (part.held_at_one_point)
                  msg << "all its supports are at one point, "
                      << point(part.axis_point)
                      << ", so it can rotate freely about that point";
                else
                  msg << "all its supports lie on the line through "
                      << point(part.axis_point) << " along "
                      << point(part.rotation_axis)
                      << ", so it can rotate freely about that line";
                msg << " (a rigid-body mechanism: its static stiffness "
                       "would be singular). "
                    << (part.held_at_one_point ?
                          "Hold it at three or more points that are not on "
                          "one line (e.g. a face)" :
                          "Hold it also at a point off that line (e.g. a "
                          "face)");
                const auto what = model->support_parameter();
                InputFile::reject(what[0], what[1], what[2], msg.str());
              }
          prm.enter_subsection(S);
          problem.parse_solver_parameters(prm);
          prm.leave_subsection();
          problem.setup_solvers(*model);
          auto &solver = problem.get_static_solver();

          unsigned int n_cells = 0;
          for (const auto &m : structure.line_meshes)
            n_cells += m->triangulation.n_active_cells();
          for (const auto &m : structure.membrane_meshes)
            n_cells += m->triangulation.n_active_cells();
          structure.for_each_solid_mesh([&](const auto &m) {
            n_cells += m.triangulation.n_active_cells();
          });
          std::cout << "Level " << level << ": " << structure.line_meshes.size()
                    << " line mesh(es), " << structure.membrane_meshes.size()
                    << " membrane mesh(es), "
                    << (structure.solid_meshes.empty() ?
                          std::string() :
                          std::to_string(structure.solid_meshes.size()) +
                            " solid mesh(es), ")
                    << (structure.plane_solid_meshes.empty() ?
                          std::string() :
                          std::to_string(structure.plane_solid_meshes.size()) +
                            " plane-strain solid mesh(es), ")
                    << n_cells << " cells, " << structure.n_nodes()
                    << " nodes, " << structure.n_dofs() << " DoFs\n";

          // Load factors to visit.
          std::vector<double> path;
          {
            const std::vector<double> legs =
              p.load_path.empty() ? std::vector<double>{1.} : p.load_path;
            double from = 0.;
            for (const double target : legs)
              {
                for (unsigned int k = 1; k <= solver.load_steps; ++k)
                  path.push_back(from +
                                 (target - from) * k / solver.load_steps);
                from = target;
              }
            if (p.load_path.empty())
              {
                for (const double x : model->extra_load_factors())
                  path.push_back(x);
                std::sort(path.begin(), path.end());
              }
          }

          const std::string csv_name =
            p.directory + "/load_steps" +
            (p.n_levels > 1 ? "_level" + std::to_string(level) : "") + ".csv";
          std::ofstream csv(csv_name);
          if (!csv)
            InputFile::reject(S + "/Output",
                              "output directory",
                              p.directory,
                              "the file <" + csv_name +
                                "> cannot be written there");
          csv << std::setprecision(10);
          bool header = false;

          double     last_lambda = 0.;
          const auto run_step    = [&](const unsigned int step,
                                    const double       lambda) {
            const auto status = step == 0 ?
                                     problem.solve_load_factor(lambda) :
                                     problem.solve_load_step(last_lambda, lambda);
            last_lambda       = lambda;
            if (!status.converged)
              {
                std::ostringstream msg;
                msg << "the load step to load factor " << lambda
                    << " did not converge: " << status.failure
                    << ". Use more 'load steps', more 'maximum Newton "
                          "iterations' or 'maximum step cuts' in subsection "
                          "Structure/Solver.";
                throw ExcSimulationFailed(msg.str());
              }
            auto values =
              model->monitor(structure, solver.displacement, lambda);
            for (const auto &c : structure_columns(structure))
              values.push_back(c);
            if (!header)
              {
                csv << "step,load_factor,newton_iterations,residual";
                for (const auto &v : values)
                  csv << ',' << v.first;
                csv << '\n';
                header = true;
              }
            csv << step << ',' << lambda << ',' << status.iterations << ','
                << status.residual;
            for (const auto &v : values)
              csv << ',' << v.second;
            csv << '\n';
            if (p.write_vtu)
              structure.write_vtu(solver.displacement,
                                  p.directory,
                                  step,
                                  lambda);
            if (!p.test_mode)
              std::cout << "  step " << std::setw(4) << step << "  load factor "
                        << std::setw(10) << lambda << "  Newton "
                        << std::setw(2) << status.iterations << "  |r| "
                        << std::scientific << std::setprecision(2)
                        << status.residual << std::defaultfloat
                        << std::setprecision(6) << '\n';
            return status;
          };

          const auto &dynamics = problem.get_dynamic_solver();
          prm.enter_subsection(S);
          problem.parse_dynamics_parameters(prm);
          prm.leave_subsection();
          if (dynamics.enabled)
            {
              if (model->form_finding_before_dynamics())
                {
                  // Stage 1 (the pre-stress step) and the model's further
                  // stages, then the motion under the full loads.
                  const auto status = problem.solve_load_factor(0.);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the pre-stress equilibrium did not converge: " +
                      status.failure);
                  std::cout << "  pre-stress equilibrium (load factor 0): "
                            << status.iterations << " Newton iterations\n";
                  model->before_load_steps(structure, solver);
                }
              problem.initialize();
              const auto energy = [&]() {
                return problem.kinetic_energy() + structure.strain_energy() +
                       structure.load_potential(solver.displacement, 1.);
              };
              model->time           = 0.;
              model->total_energy   = energy();
              model->kinetic_energy = problem.kinetic_energy();
              model->monitor(structure, solver.displacement, 0.);
              unsigned int       step = 0, newton = 0;
              double             t       = 0.;
              const unsigned int n_steps = static_cast<unsigned int>(
                std::max(1.,
                         std::round(dynamics.end_time / dynamics.time_step)));
              // Equal steps that end exactly at the end time.
              const double dt = dynamics.end_time / n_steps;
              while (step < n_steps)
                {
                  problem.prepare_step(t, dt);
                  const auto status = problem.solve_step();
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the time step from t = " + std::to_string(t) +
                      " s did not converge: " + status.failure +
                      ". Reduce 'time step' in subsection Structure/Dynamics.");
                  problem.commit_step();
                  t = (step + 1) * dt;
                  ++step;
                  newton += status.iterations;
                  // Energies at the committed state.
                  dealii::Vector<double> r;
                  structure.assemble(solver.displacement, 1., r, nullptr);
                  model->time           = t;
                  model->total_energy   = energy();
                  model->kinetic_energy = problem.kinetic_energy();
                  auto values =
                    model->monitor(structure, solver.displacement, t);
                  for (const auto &c : structure_columns(structure))
                    values.push_back(c);
                  if (step == 1)
                    {
                      csv << "step,newton_iterations,residual";
                      for (const auto &v : values)
                        csv << ',' << v.first;
                      csv << '\n';
                    }
                  csv << step << ',' << status.iterations << ','
                      << status.residual;
                  for (const auto &v : values)
                    csv << ',' << v.second;
                  csv << '\n';
                  if (p.write_vtu)
                    structure.write_vtu(solver.displacement,
                                        p.directory,
                                        step,
                                        t);
                }
              std::cout << "  " << step << " time steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / step
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
              path.clear();
              if (model->relax_to_equilibrium())
                {
                  const double T      = problem.kinetic_energy();
                  const auto   status = problem.solve_load_factor(1.);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "the static equilibrium after the dynamic relaxation "
                      "did not converge: " +
                      status.failure + ". Run the relaxation longer.");
                  std::cout << "  static equilibrium from the relaxed state "
                               "(kinetic energy "
                            << std::setprecision(3) << std::scientific << T
                            << " J): " << status.iterations
                            << " Newton iterations\n"
                            << std::defaultfloat << std::setprecision(6);
                }
            }
          else if (model->prestress_step())
            {
              const auto status = run_step(0, 0.);
              std::cout << "  pre-stress equilibrium (load factor 0): "
                        << (status.iterations == 0 ? "already in equilibrium" :
                                                     "reached")
                        << '\n';
            }
          if (!dynamics.enabled)
            model->before_load_steps(structure, solver);
          if (!dynamics.enabled && solver.control == "arc length")
            {
              // Arc-length steps: the load factor is an unknown.
              double                 lambda = 0.;
              dealii::Vector<double> direction;
              unsigned int           newton = 0;
              for (unsigned int k = 1; k <= solver.load_steps; ++k)
                {
                  const auto status =
                    problem.solve_arc_length_step(lambda, direction);
                  if (!status.converged)
                    throw ExcSimulationFailed(
                      "arc-length step " + std::to_string(k) +
                      " did not converge: " + status.failure + ".");
                  newton += status.iterations;
                  auto values =
                    model->monitor(structure, solver.displacement, lambda);
                  for (const auto &c : structure_columns(structure))
                    values.push_back(c);
                  if (k == 1)
                    {
                      csv << "step,load_factor,newton_iterations,residual";
                      for (const auto &v : values)
                        csv << ',' << v.first;
                      csv << '\n';
                    }
                  csv << k << ',' << lambda << ',' << status.iterations << ','
                      << status.residual;
                  for (const auto &v : values)
                    csv << ',' << v.second;
                  csv << '\n';
                  if (p.write_vtu)
                    structure.write_vtu(solver.displacement,
                                        p.directory,
                                        k,
                                        lambda);
                }
              std::cout << "  " << solver.load_steps << " arc-length steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / solver.load_steps
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
            }
          else if (!dynamics.enabled)
            {
              unsigned int newton = 0;
              for (unsigned int k = 0; k < path.size(); ++k)
                newton += run_step(k + 1, path[k]).iterations;
              std::cout << "  " << path.size() << " load steps, "
                        << std::setprecision(3)
                        << static_cast<double>(newton) / path.size()
                        << " Newton iterations per step\n"
                        << std::setprecision(6);
            }

          const auto results = model->results(structure, solver.displacement);
          std::cout << "  " << std::left << std::setw(44) << "quantity"
                    << std::right << std::setw(15) << "computed"
                    << std::setw(15) << "reference" << std::setw(12)
                    << "rel. error" << '\n';
          for (const auto &r : results)
            {
              std::cout << "  " << std::left << std::setw(44) << r.name
                        << std::right << std::setprecision(7) << std::setw(15)
                        << r.computed;
              if (r.checked)
                std::cout << std::setw(15) << r.reference << std::setw(12)
                          << std::setprecision(3) << std::scientific
                          << r.error() << std::defaultfloat;
              std::cout << '\n' << std::setprecision(6);
            }
          level_results.push_back(results);

          table.add_value("level", level);
          table.add_value("DoFs", structure.n_dofs());
          for (const auto &r : results)
            if (r.checked)
              {
                table.add_value(r.name, r.error());
                table.set_scientific(r.name, true);
                table.set_precision(r.name, 3);
              }
        }

      if (p.n_levels > 1)
        {
          for (const auto &r : level_results.back())
            if (r.checked)
              table.evaluate_convergence_rates(
                r.name, ConvergenceTable::reduction_rate_log2);
          std::cout << "Convergence table (relative errors; rate: log2 of "
                       "the error reduction per level):\n";
          table.write_text(
            std::cout, TableHandler::table_with_separate_column_description);
        }

      bool passed = true;
      if (p.tolerance > 0.)
        for (const auto &r : level_results.back())
          if (r.checked)
            {
              const double tolerance =
                r.tolerance > 0. ? r.tolerance : p.tolerance;
              const bool ok = r.error() <= tolerance;
              std::cout << "  check " << r.name << ": "
                        << (ok ? "ok" : "FAILED") << " (tolerance " << tolerance
                        << ")\n";
              passed = passed && ok;
            }
      if (p.n_levels > 1 && p.minimum_rate > 0.)
        {
          const auto &fine   = level_results[p.n_levels - 1];
          const auto &coarse = level_results[p.n_levels - 2];
          for (unsigned int i = 0; i < fine.size(); ++i)
            if (fine[i].checked && !fine[i].is_error)
              {
                const double rate =
                  std::log2(coarse[i].error() / fine[i].error());
                const bool ok = rate >= p.minimum_rate;
                std::cout << "  check rate of " << fine[i].name << ": "
                          << std::setprecision(3) << std::fixed << rate
                          << std::defaultfloat << std::setprecision(6)
                          << (ok ? "  ok" : "  FAILED") << " (minimum "
                          << p.minimum_rate << ")\n";
                passed = passed && ok;
              }
        }
      if (!passed)
        throw ExcVerificationFailed(
          "the structure misses its closed-form reference (see the checks "
          "above).");
      return 0;
    }
  } // namespace StructureSimulation
} // namespace Talus
