#include <talus/app/coupled_simulation.h>
#include <talus/app/input_check.h>
#include <talus/app/simulation.h>
#include <talus/app/structure_simulation.h>
#include <talus/base/input.h>
#include <talus/mpm/memory_estimate.h>

#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

namespace Talus
{
  std::string
  demangle_parameter_name(const std::string &s)
  {
    std::string r;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i] == '_' && i + 2 < s.size())
        {
          r += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
          i += 2;
        }
      else
        r += s[i];
    return r;
  }


  namespace InputCheck
  {
    namespace
    {
      /** The first token of @p value that is a non-finite number, or "". */
      std::string
      non_finite_token(const std::string &value)
      {
        // Separators of lists (',' ';' ':'), of function constants ('='),
        // and operators of expressions that cannot occur inside a number.
        const std::string separators = " \t,;:=()[]{}*/^<>!&|?";
        std::size_t       begin      = 0;
        while (begin < value.size())
          {
            begin = value.find_first_not_of(separators, begin);
            if (begin == std::string::npos)
              break;
            std::size_t end = value.find_first_of(separators, begin);
            if (end == std::string::npos)
              end = value.size();
            const std::string token = value.substr(begin, end - begin);
            // Only a token that is a number as a whole ("nan", "-inf",
            // "1e400"); a sign in front of it belongs to it.
            const char *first = token.c_str();
            char       *last  = nullptr;
            errno             = 0;
            const double d    = std::strtod(first, &last);
            if (last != first && *last == '\0' && !std::isfinite(d))
              return token;
            begin = end;
          }
        return "";
      }


      void
      check_tree(const boost::property_tree::ptree &tree,
                 const std::string                 &path)
      {
        for (const auto &[mangled, node] : tree)
          {
            const std::string name = demangle_parameter_name(mangled);
            if (const auto value = node.get_optional<std::string>("value"))
              {
                const std::string token = non_finite_token(*value);
                if (!token.empty())
                  InputFile::reject(path,
                                    name,
                                    *value,
                                    "every number in it must be finite (<" +
                                      token +
                                      "> is not: nan, inf and numbers "
                                      "beyond +-1.8e308 are not allowed)");
              }
            else
              check_tree(node, path.empty() ? name : path + "/" + name);
          }
      }
    } // namespace


    void
    require_statements(const std::string &filename)
    {
      std::ifstream in(filename);
      if (!in)
        throw ExcInvalidInput("Cannot open the parameter file <" + filename +
                              ">.");
      std::string line;
      while (std::getline(in, line))
        {
          line = dealii::Utilities::trim(line.substr(0, line.find('#')));
          std::string keyword = line.substr(0, line.find_first_of(" \t"));
          std::transform(keyword.begin(),
                         keyword.end(),
                         keyword.begin(),
                         [](const unsigned char c) { return std::tolower(c); });
          if (keyword == "set" || keyword == "include")
            return;
        }
      throw ExcInvalidInput(
        "Invalid input in file <" + filename +
        ">:\n  it sets no parameter (it is empty or holds only comments and "
        "subsections),\n  but an input file must set at least one parameter "
        "with 'set <name> = <value>' (a complete file with every default: "
        "talus --print-parameters prm).");
    }


    std::string
    problem_and_dimension(const std::string &filename, unsigned int &dimension)
    {
      dealii::ParameterHandler pre;
      pre.declare_entry("problem",
                        "mpm",
                        dealii::Patterns::Selection("mpm|structure|coupled"));
      pre.declare_entry("dimension", "2", dealii::Patterns::Integer(2, 3));
      pre.parse_input(filename, "", true);
      dimension = pre.get_integer("dimension");
      return pre.get("problem");
    }


    std::string
    parse(const std::string        &filename,
          dealii::ParameterHandler &prm,
          unsigned int             &dimension)
    {
      // First pass, as run_parameter_file(): only the problem and the
      // dimension.
      const std::string problem = problem_and_dimension(filename, dimension);
      // Second pass: every declaration of that problem (as
      // StructureSimulation::run_parameter_file() and run_parameter_file()).
      if (problem == "structure")
        {
          prm.declare_entry("problem",
                            "structure",
                            dealii::Patterns::Anything());
          prm.declare_entry("dimension", "3", dealii::Patterns::Integer(2, 3));
          StructureSimulation::declare_parameters(prm);
        }
      else if (problem == "coupled" && dimension == 2)
        CoupledSimulation<2>::declare_parameters(
          prm,
          Boundaries::BoundaryParticles<2>::n_boundaries_in_file(filename));
      else if (problem == "coupled")
        CoupledSimulation<3>::declare_parameters(
          prm,
          Boundaries::BoundaryParticles<3>::n_boundaries_in_file(filename));
      else if (dimension == 2)
        Simulation<2>::declare_parameters(
          prm,
          Boundaries::BoundaryParticles<2>::n_boundaries_in_file(filename));
      else
        Simulation<3>::declare_parameters(
          prm,
          Boundaries::BoundaryParticles<3>::n_boundaries_in_file(filename));
      prm.parse_input(filename);
      return problem;
    }


    void
    require_finite_numbers(const dealii::ParameterHandler &prm)
    {
      std::stringstream json;
      prm.print_parameters(json, dealii::ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      check_tree(tree, "");
    }


    void
    require_memory(const dealii::ParameterHandler &prm_in,
                   const unsigned int              dimension,
                   const MPI_Comm                  communicator)
    {
      // get() needs a non-const handler to enter subsections; nothing is
      // changed.
      auto &prm = const_cast<dealii::ParameterHandler &>(prm_in);
      prm.enter_subsection("Convergence study");
      const unsigned int level = prm.get_integer("first level") +
                                 prm.get_integer("number of levels") - 1;
      prm.leave_subsection();
      // Without the model's internal variables (a lower bound): the run
      // checks again with them before it creates the grid.
      if (dimension == 2)
        {
          MPM::MemoryEstimate<2> memory;
          memory.parse_parameters(prm, communicator, level, 0);
          memory.check(prm);
        }
      else
        {
          MPM::MemoryEstimate<3> memory;
          memory.parse_parameters(prm, communicator, level, 0);
          memory.check(prm);
        }
    }
  } // namespace InputCheck


  std::string
  check_input_file(const std::string &filename, const MPI_Comm communicator)
  {
    InputFile::set_name(filename);
    InputCheck::require_statements(filename);
    dealii::ParameterHandler prm;
    unsigned int             dimension = 2;
    const std::string problem = InputCheck::parse(filename, prm, dimension);
    InputCheck::require_finite_numbers(prm);
    if (problem != "structure")
      InputCheck::require_memory(prm, dimension, communicator);
    return "problem = " + problem +
           (problem != "structure" ?
              ", dimension = " + std::to_string(dimension) :
              std::string());
  }


  int
  check_input_files(const std::vector<std::string> &filenames,
                    const MPI_Comm                  communicator)
  {
    const bool root =
      dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    if (filenames.empty())
      {
        if (root)
          std::cerr << "Error: talus --check needs at least one file.\n";
        return 2;
      }
    int status = 0;
    for (const auto &file : filenames)
      {
        std::ostringstream error;
        try
          {
            const std::string summary = check_input_file(file, communicator);
            if (root)
              std::cout << "talus --check: <" << file << "> is valid ("
                        << summary << ")" << std::endl;
            continue;
          }
        catch (const ExcInvalidInput &e)
          {
            error << "Error: " << e.what() << '\n';
          }
        catch (const dealii::ExceptionBase &e)
          {
            error << "Error (input file <" << file << ">):\n";
            e.print_info(error);
          }
        catch (const std::exception &e)
          {
            error << "Error: " << e.what() << '\n';
          }
        status = 1;
        if (root)
          std::cerr << "talus --check: <" << file << "> is not valid:\n"
                    << error.str() << std::flush;
      }
    return status;
  }
} // namespace Talus
