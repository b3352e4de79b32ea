#include <talus/app/coupled_simulation.h>
#include <talus/app/input_check.h>
#include <talus/app/simulation.h>
#include <talus/app/structure_simulation.h>
#include <talus/base/input.h>

#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
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


      /** Comma-separated numbers; empty if any is not a number. */
      std::vector<double>
      numbers(const std::string &text, const char separator = ',')
      {
        std::vector<double> result;
        for (const auto &s :
             dealii::Utilities::split_string_list(text, separator))
          {
            double v;
            if (!parse_double(s, v))
              return {};
            result.push_back(v);
          }
        return result;
      }


      std::string
      gigabytes(const double bytes)
      {
        std::ostringstream s;
        s << std::setprecision(3) << bytes / 1e9 << " GB";
        return s.str();
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


    std::uint64_t
    machine_memory()
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      std::uint64_t kilobytes;
      std::string   unit;
      while (meminfo >> key >> kilobytes >> unit)
        if (key == "MemTotal:")
          return kilobytes * 1024;
      const long pages     = sysconf(_SC_PHYS_PAGES);
      const long page_size = sysconf(_SC_PAGESIZE);
      if (pages > 0 && page_size > 0)
        return static_cast<std::uint64_t>(pages) *
               static_cast<std::uint64_t>(page_size);
      return 0;
    }


    template <int dim>
    double
    estimate_mpm_memory(const dealii::ParameterHandler &prm_in,
                        std::string                    &responsible_subsection,
                        std::string                    &responsible_entry,
                        std::string                    &details)
    {
      // get() needs a non-const handler to enter subsections; nothing is
      // changed.
      auto &prm = const_cast<dealii::ParameterHandler &>(prm_in);

      prm.enter_subsection("Convergence study");
      const unsigned int level = prm.get_integer("first level") +
                                 prm.get_integer("number of levels") - 1;
      prm.leave_subsection();

      prm.enter_subsection("Background grid");
      const bool                box_grid     = prm.get("type") == "box";
      const std::vector<double> lower        = numbers(prm.get("lower corner"));
      const std::vector<double> upper        = numbers(prm.get("upper corner"));
      const std::vector<double> subdivisions = numbers(prm.get("subdivisions"));
      prm.leave_subsection();
      // A grid from a mesh file, or corners the grid will reject itself.
      if (!box_grid || lower.size() != dim || upper.size() != dim ||
          subdivisions.size() != dim)
        return 0.;

      // Cells and Q1 vertices of the finest level.
      double cells = 1., vertices = 1., cell_volume = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double n = subdivisions[d] * std::pow(2., level);
          cells *= n;
          vertices *= n + 1.;
          cell_volume *= std::abs(upper[d] - lower[d]) / n;
        }
      const double dofs = dim * vertices;

      // Material points: the body's share of the grid times n^dim.
      prm.enter_subsection("Body");
      const std::string geometry = prm.get("geometry");
      const double      n_per_direction =
        prm.get_integer("points per cell per direction");
      double body_volume = 0.;
      if (geometry == "box")
        {
          const std::vector<double> body_lower =
            numbers(prm.get("lower corner"));
          const std::vector<double> body_upper =
            numbers(prm.get("upper corner"));
          if (body_lower.size() == dim && body_upper.size() == dim)
            {
              body_volume = 1.;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  // only the part inside the grid holds points
                  const double lo =
                    std::max(std::min(body_lower[d], body_upper[d]),
                             std::min(lower[d], upper[d]));
                  const double hi =
                    std::min(std::max(body_lower[d], body_upper[d]),
                             std::max(lower[d], upper[d]));
                  body_volume *= std::max(hi - lo, 0.);
                }
            }
        }
      else if (geometry == "polygon" && dim == 2)
        {
          // shoelace area of the vertices 'x, y; x, y; ...'
          std::vector<std::vector<double>> v;
          for (const auto &pair :
               dealii::Utilities::split_string_list(prm.get("vertices"), ';'))
            v.push_back(numbers(pair));
          double twice_area = 0.;
          bool   valid      = v.size() >= 3;
          for (std::size_t i = 0; valid && i < v.size(); ++i)
            {
              const auto &a = v[i];
              const auto &b = v[(i + 1) % v.size()];
              valid         = a.size() == 2 && b.size() == 2;
              if (valid)
                twice_area += a[0] * b[1] - b[0] * a[1];
            }
          if (valid)
            body_volume = std::abs(twice_area) / 2.;
        }
      prm.leave_subsection();
      const double points =
        cell_volume > 0. ?
          body_volume / cell_volume * std::pow(n_per_direction, dim) :
          0.;

      // Bytes per cell (triangulation, DoF handler, cell data), per degree
      // of freedom (Trilinos tangent with its sparsity pattern, 3^dim * dim
      // entries a row, and the solution vectors) and per material point
      // (position, volume, F, stresses, internal variables, cell
      // iterator): deliberately low, so that only runs that certainly do
      // not fit are stopped. A 2D run of 300 x 300 cells (181,202 DoFs,
      // 180,000 points, one step) peaked at 531 MB resident; these
      // numbers give 198 MB for it.
      const double bytes_per_cell  = dim == 2 ? 600. : 1500.;
      const double bytes_per_dof   = dim == 2 ? 300. : 700.;
      const double bytes_per_point = dim == 2 ? 500. : 900.;
      const double grid_bytes  = cells * bytes_per_cell + dofs * bytes_per_dof;
      const double point_bytes = points * bytes_per_point;

      std::ostringstream counts;
      counts << std::setprecision(3) << cells << " cells and " << dofs
             << " degrees of freedom (" << gigabytes(grid_bytes) << "), "
             << points << " material points (" << gigabytes(point_bytes) << ")";
      if (level > 0)
        counts << " on refinement level " << level
               << " of subsection <Convergence study>";
      details = counts.str();
      if (grid_bytes >= point_bytes)
        {
          responsible_subsection = "Background grid";
          responsible_entry      = "subdivisions";
        }
      else
        {
          responsible_subsection = "Body";
          responsible_entry      = "points per cell per direction";
        }
      return grid_bytes + point_bytes;
    }


    void
    require_memory(const dealii::ParameterHandler &prm,
                   const unsigned int              dimension,
                   const MPI_Comm                  communicator)
    {
      std::string  subsection, entry, details;
      const double total =
        dimension == 2 ?
          estimate_mpm_memory<2>(prm, subsection, entry, details) :
          estimate_mpm_memory<3>(prm, subsection, entry, details);
      const double machine = machine_memory();
      if (total <= 0. || machine <= 0.)
        return;

      // This node holds its ranks' share of the run.
      int n_ranks = 1, n_node_ranks = 1;
      int mpi_initialized = 0;
      MPI_Initialized(&mpi_initialized);
      if (mpi_initialized != 0)
        {
          MPI_Comm_size(communicator, &n_ranks);
          MPI_Comm node;
          MPI_Comm_split_type(
            communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
          MPI_Comm_size(node, &n_node_ranks);
          MPI_Comm_free(&node);
        }
      const double on_this_node = total * n_node_ranks / n_ranks;
      if (on_this_node <= machine)
        return;

      auto &p = const_cast<dealii::ParameterHandler &>(prm);
      p.enter_subsection(subsection);
      const std::string value = p.get(entry);
      p.leave_subsection();
      std::ostringstream allowed;
      allowed << "the run would need at least " << gigabytes(on_this_node)
              << " of memory on this machine (" << details << ", "
              << n_node_ranks << " of " << n_ranks
              << " MPI ranks here), more than its " << gigabytes(machine)
              << " (MemTotal in /proc/meminfo): use fewer cells or points, or "
                 "more machines";
      InputFile::reject(subsection, entry, value, allowed.str());
    }


    template double
    estimate_mpm_memory<2>(const dealii::ParameterHandler &,
                           std::string &,
                           std::string &,
                           std::string &);
    template double
    estimate_mpm_memory<3>(const dealii::ParameterHandler &,
                           std::string &,
                           std::string &,
                           std::string &);
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
