// The entry point of a run: the problem and dimension of a parameter file
// (mpm, structure or coupled), and for the MPM the refinement study of
// subsection "Convergence study" (one Simulation per level, the deposit
// or verification errors tabulated with their rates).

#include <talus/app/coupled_simulation.h>
#include <talus/app/input_check.h>
#include <talus/app/simulation.h>
#include <talus/app/structure_simulation.h>
#include <talus/base/input.h>
#include <talus/boundaries/boundary_particles.h>
#include <talus/io/deposit_profile.h>

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace Talus
{
  namespace
  {
    /**
     * The deposit of a refinement study, level by level: print a
     * convergence table (runout, its error against the reference, the
     * change per refinement with its rate, the surface errors) and check
     * the study's requirements. Returns false if one is missed.
     */
    bool
    check_deposit_study(const std::vector<DepositErrors> &deposits,
                        const unsigned int                first_level,
                        const unsigned int                exempt_levels,
                        const bool                        require_shrinking,
                        const MPI_Comm                    communicator)
    {
      dealii::ConvergenceTable table;
      bool                     passed = true;
      std::ostringstream       checks;
      for (unsigned int k = 0; k < deposits.size(); ++k)
        {
          const DepositErrors &d = deposits[k];
          table.add_value("level", first_level + k);
          table.add_value("cell [m]", d.cell_size);
          table.add_value("runout L [m]", d.runout);
          table.add_value("(L-Lref)/Lref", d.runout_error);
          table.add_value("|L-Lref|/Lref", std::abs(d.runout_error));
          // the change from the coarser level estimates the discretisation
          // error; its rate from the third level on
          if (k == 0)
            table.add_value("|L-L_coarser| [m]", std::string("-"));
          else
            table.add_value("|L-L_coarser| [m]",
                            std::abs(d.runout - deposits[k - 1].runout));
          if (k < 2)
            table.add_value("rate", std::string("-"));
          else
            table.add_value("rate",
                            std::log2(
                              std::abs(deposits[k - 1].runout -
                                       deposits[k - 2].runout) /
                              std::abs(d.runout - deposits[k - 1].runout)));
          // '-' where there is no reference profile
          for (const auto &[column, value] :
               {std::make_pair("max |h-href| [m]", d.max_height_error),
                std::make_pair("RMS h-href [m]", d.rms_height_error)})
            if (std::isnan(value))
              table.add_value(column, std::string("-"));
            else
              table.add_value(column, value);
          table.add_value("references", d.passed ? "met" : "missed");
          const bool exempt = k < exempt_levels;
          if (!d.passed && !exempt)
            {
              passed = false;
              checks << "  check level " << first_level + k
                     << ": the deposit misses its references  FAILED\n";
            }
          if (require_shrinking && k > 0)
            {
              // by more than round-off (1e-9 of the reference runout)
              const bool shrinks =
                std::abs(d.runout_error) <
                std::abs(deposits[k - 1].runout_error) - 1e-9;
              passed = passed && shrinks;
              checks << "  check runout error shrinks, level "
                     << first_level + k - 1 << " -> " << first_level + k << ": "
                     << std::setprecision(4)
                     << 100. * std::abs(deposits[k - 1].runout_error)
                     << " % -> " << 100. * std::abs(d.runout_error) << " %"
                     << (shrinks ? "  ok" : "  FAILED") << '\n';
            }
        }
      for (const std::string column : {"cell [m]",
                                       "runout L [m]",
                                       "(L-Lref)/Lref",
                                       "|L-Lref|/Lref",
                                       "|L-L_coarser| [m]",
                                       "max |h-href| [m]",
                                       "RMS h-href [m]"})
        {
          table.set_precision(column, 4);
          table.set_scientific(column, column != "runout L [m]");
        }
      table.evaluate_convergence_rates(
        "|L-Lref|/Lref", dealii::ConvergenceTable::reduction_rate_log2);
      table.set_precision("rate", 2);
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::cout << "Deposit under refinement (rate: log2 of the "
                       "reduction per refinement):\n";
          table.write_text(
            std::cout,
            dealii::TableHandler::table_with_separate_column_description);
          std::cout << checks.str() << std::flush;
        }
      return passed;
    }


    template <int dim>
    int
    run_dimension(dealii::ParameterHandler &prm,
                  const MPI_Comm            communicator,
                  const std::string        &resume_from)
    {
      prm.enter_subsection("Convergence study");
      const unsigned int n_levels     = prm.get_integer("number of levels");
      const unsigned int first_level  = prm.get_integer("first level");
      const double       minimum_rate = prm.get_double("minimum rate");
      const bool         require_shrinking =
        prm.get_bool("require shrinking deposit error");
      const unsigned int exempt_levels =
        prm.get_integer("exempt coarse levels");
      const bool refine_bins = prm.get_bool("refine bin width");
      prm.leave_subsection();
      std::vector<std::vector<double>> level_errors;
      prm.enter_subsection("Verification");
      const bool compare = prm.get_bool("compare with exact solution");
      prm.leave_subsection();
      prm.enter_subsection("Deposit profile");
      const bool   deposit_study    = prm.get_bool("measure deposit");
      const double reference_runout = prm.get_double("reference runout");
      const double bin_width        = prm.get_double("bin width");
      prm.leave_subsection();
      if (n_levels > 1 && !compare && !deposit_study)
        InputFile::reject("Convergence study",
                          "number of levels",
                          std::to_string(n_levels),
                          "a convergence study needs 'compare with exact "
                          "solution = true' in subsection <Verification> or "
                          "'measure deposit = true' in subsection <Deposit "
                          "profile>");
      if (require_shrinking && (!deposit_study || reference_runout <= 0.))
        InputFile::reject("Convergence study",
                          "require shrinking deposit error",
                          "true",
                          "it needs 'measure deposit = true' and a 'reference "
                          "runout' in subsection <Deposit profile>");
      if (exempt_levels > 0 && (!deposit_study || exempt_levels >= n_levels))
        InputFile::reject("Convergence study",
                          "exempt coarse levels",
                          std::to_string(exempt_levels),
                          "it needs 'measure deposit = true' in subsection "
                          "<Deposit profile> and must be smaller than "
                          "'number of levels' (" +
                            std::to_string(n_levels) + ")");
      prm.enter_subsection("Checkpoint");
      const bool checkpoints = prm.get_integer("every steps") > 0 ||
                               prm.get_double("every minutes") > 0. ||
                               prm.get_bool("resume");
      prm.leave_subsection();
      if (n_levels > 1 && (checkpoints || !resume_from.empty()))
        InputFile::reject("Convergence study",
                          "number of levels",
                          std::to_string(n_levels),
                          "1 when checkpoints are written or resumed "
                          "(subsection <Checkpoint>, --resume): a study "
                          "cannot be checkpointed");
      // A study writes each level's files into <output directory>/level-N.
      prm.enter_subsection("Output");
      const std::string output_directory = prm.get("output directory");
      prm.leave_subsection();

      dealii::ConvergenceTable   table;
      std::vector<DepositErrors> deposits;
      for (unsigned int level = first_level; level < first_level + n_levels;
           ++level)
        {
          if (n_levels > 1)
            {
              prm.enter_subsection("Output");
              prm.set("output directory",
                      output_directory + "/level-" + std::to_string(level));
              prm.leave_subsection();
              if (deposit_study && refine_bins)
                {
                  prm.enter_subsection("Deposit profile");
                  prm.set("bin width", bin_width / std::pow(2., level));
                  prm.leave_subsection();
                }
            }
          Simulation<dim> simulation(communicator);
          simulation.set_resume(resume_from);
          // the deposit of a level is judged with the others (below)
          simulation.set_deposit_misses_fatal(n_levels == 1);
          const auto errors = simulation.run(prm, level);
          deposits.push_back(simulation.deposit_errors());
          level_errors.emplace_back();
          for (const auto &e : errors)
            level_errors.back().push_back(e.displacement_error);
          if (n_levels > 1 && compare)
            {
              table.add_value("level", level);
              for (const auto &e : errors)
                {
                  std::ostringstream name;
                  name << "u t=" << e.time;
                  table.add_value(name.str(), e.displacement_error);
                  table.set_scientific(name.str(), true);
                  table.set_precision(name.str(), 3);
                  table.evaluate_convergence_rates(
                    name.str(), dealii::ConvergenceTable::reduction_rate_log2);
                }
            }
        }
      const bool deposit_study_passed = n_levels == 1 || !deposit_study ||
                                        check_deposit_study(deposits,
                                                            first_level,
                                                            exempt_levels,
                                                            require_shrinking,
                                                            communicator);
      if (n_levels > 1 && compare &&
          dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::cout << "Convergence table (rate: log2 of the error "
                       "reduction per refinement):\n";
          table.write_text(
            std::cout,
            dealii::TableHandler::table_with_separate_column_description);
        }
      if (n_levels > 1 && minimum_rate > 0.)
        {
          bool        passed = true;
          const auto &fine   = level_errors[n_levels - 1];
          const auto &coarse = level_errors[n_levels - 2];
          for (unsigned int k = 0; k < std::min(fine.size(), coarse.size());
               ++k)
            {
              const double rate = std::log2(coarse[k] / fine[k]);
              const bool   ok   = rate >= minimum_rate;
              passed            = passed && ok;
              if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
                std::cout << "  check rate (report time " << k + 1
                          << ", last two levels): " << std::setprecision(3)
                          << std::fixed << rate << (ok ? " >= " : " < ")
                          << minimum_rate << std::defaultfloat
                          << (ok ? "  ok" : "  FAILED") << '\n';
            }
          if (!passed)
            throw ExcVerificationFailed("the measured convergence rate is "
                                        "below 'minimum rate'.");
        }
      if (!deposit_study_passed)
        throw ExcVerificationFailed(
          "the deposit refinement study misses its requirements (table "
          "above).");
      return 0;
    }
  } // namespace


  int
  run_parameter_file(const std::string &filename,
                     const MPI_Comm     communicator,
                     const std::string &resume_from)
  {
    InputFile::set_name(filename);
    {
      std::ifstream in(filename);
      if (!in)
        throw ExcInvalidInput("Cannot open the parameter file <" + filename +
                              ">.");
    }
    // First pass: only the problem and the dimension.
    unsigned int dimension;
    if (InputCheck::problem_and_dimension(filename, dimension) == "structure")
      {
        if (!resume_from.empty())
          throw ExcInvalidInput("--resume: checkpoints exist only for 'problem "
                                "= mpm' and 'problem = coupled', the file <" +
                                filename + "> sets 'problem = structure'.");
        return StructureSimulation::run_parameter_file(filename);
      }
    const std::string problem =
      InputCheck::problem_and_dimension(filename, dimension);
    dealii::ParameterHandler prm;
    // as many boundary subsections as the file has (no fixed limit)
    const unsigned int n_boundaries =
      Boundaries::BoundaryParticles<2>::n_boundaries_in_file(filename);
    if (problem == "coupled")
      {
        if (dimension == 2)
          {
            CoupledSimulation<2>::declare_parameters(prm, n_boundaries);
            prm.parse_input(filename);
            CoupledSimulation<2> simulation(communicator);
            simulation.set_resume(resume_from);
            return simulation.run(prm);
          }
        CoupledSimulation<3>::declare_parameters(prm, n_boundaries);
        prm.parse_input(filename);
        CoupledSimulation<3> simulation(communicator);
        simulation.set_resume(resume_from);
        return simulation.run(prm);
      }
    if (dimension == 2)
      {
        Simulation<2>::declare_parameters(prm, n_boundaries);
        prm.parse_input(filename);
        return run_dimension<2>(prm, communicator, resume_from);
      }
    else
      {
        Simulation<3>::declare_parameters(prm, n_boundaries);
        prm.parse_input(filename);
        return run_dimension<3>(prm, communicator, resume_from);
      }
  }
} // namespace Talus
