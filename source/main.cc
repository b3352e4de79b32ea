// Talus: implicit Material Point Method and FEM for mass movements hitting
// flexible protective barriers. The executable only reads the command line;
// everything else is in the talus library.
#include <talus/app/input_check.h>
#include <talus/app/simulation.h>
#include <talus/base/input.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <iostream>
#include <string>

namespace
{
  const char *usage =
    "Usage: talus <parameter file>          run the simulation in the file\n"
    "       talus --print-parameters        list every parameter with its\n"
    "                                       allowed values, unit and meaning\n"
    "       talus --print-parameters prm    a complete parameter file with\n"
    "                                       all defaults\n"
    "       talus --check <file>...         parse and check the files, do not\n"
    "                                       run them (exit code 0: all valid)\n"
    "       talus --resume <dir> <file>     continue the run of the file from\n"
    "                                       the checkpoint <dir> (or the newest\n"
    "                                       one in the directory <dir>)\n"
    "       talus --help                    this text\n"
    "Run in parallel with: mpirun -np N talus <parameter file>\n"
    "Documentation: doc/ (parameters: doc/parameters.md).\n";
}


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                           comm = MPI_COMM_WORLD;
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  dealii::deal_II_exceptions::disable_abort_on_exception();

  if (argc < 2)
    {
      if (root)
        std::cerr << usage;
      return 2;
    }
  const std::string arg = argv[1];
  if (arg == "--help" || arg == "-h")
    {
      if (root)
        std::cout << usage;
      return 0;
    }
  if (arg == "--print-parameters")
    {
      const std::string format = argc > 2 ? argv[2] : "";
      if (format != "" && format != "prm")
        {
          if (root)
            std::cerr << "Error: unknown format <" << format
                      << "> for --print-parameters (allowed: none or 'prm').\n"
                      << usage;
          return 2;
        }
      if (root)
        Talus::print_parameters(std::cout, format);
      return 0;
    }
  if (arg == "--check")
    return Talus::check_input_files({argv + 2, argv + argc}, comm);
  std::string resume_from;
  std::string file = arg;
  if (arg == "--resume")
    {
      if (argc != 4)
        {
          if (root)
            std::cerr << "Error: --resume needs a checkpoint directory and "
                         "a parameter file.\n"
                      << usage;
          return 2;
        }
      resume_from = argv[2];
      file        = argv[3];
    }
  else if (arg.size() > 1 && arg[0] == '-')
    {
      if (root)
        std::cerr << "Error: unknown option <" << arg << ">.\n" << usage;
      return 2;
    }

  try
    {
      Talus::check_input_file(file, comm);
      return Talus::run_parameter_file(file, comm, resume_from);
    }
  catch (const Talus::ExcInvalidInput &e)
    {
      if (root)
        std::cerr << "\nError: " << e.what() << '\n';
    }
  catch (const Talus::ExcVerificationFailed &e)
    {
      if (root)
        std::cerr << "\nVerification failed: " << e.what() << '\n';
      return 3;
    }
  catch (const Talus::ExcSimulationFailed &e)
    {
      if (root)
        std::cerr << "\nError: the simulation failed: " << e.what() << '\n';
    }
  catch (const dealii::ExceptionBase &e)
    {
      if (root)
        {
          std::cerr << "\nError (input file <" << file << ">):\n";
          e.print_info(std::cerr);
        }
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "\nError: " << e.what() << '\n';
    }
  return 1;
}
