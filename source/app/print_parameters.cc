// talus --print-parameters: every parameter of every problem with its
// default, allowed values and documentation.

#include <talus/app/coupled_simulation.h>
#include <talus/app/input_check.h>
#include <talus/app/simulation.h>
#include <talus/app/structure_simulation.h>

#include <deal.II/base/parameter_handler.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <ostream>
#include <sstream>
#include <string>

namespace Talus
{
  namespace
  {
    void
    print_tree(std::ostream                      &out,
               const boost::property_tree::ptree &tree,
               const unsigned int                 indent)
    {
      const std::string pad(indent, ' ');
      // Entries first, then subsections (as in a parameter file).
      for (const auto &[name, node] : tree)
        if (node.get_child_optional("value"))
          {
            out << pad << "set " << demangle_parameter_name(name) << " = "
                << node.get<std::string>("default_value") << '\n'
                << pad << "    # allowed: "
                << node.get<std::string>("pattern_description") << '\n';
            std::istringstream doc(node.get<std::string>("documentation"));
            std::string        word, line;
            while (doc >> word)
              {
                if (line.size() + word.size() + pad.size() + 7 > 79)
                  {
                    out << pad << "    # " << line << '\n';
                    line.clear();
                  }
                line += (line.empty() ? "" : " ") + word;
              }
            if (!line.empty())
              out << pad << "    # " << line << '\n';
          }
      for (const auto &[name, node] : tree)
        if (!node.get_child_optional("value"))
          {
            out << '\n'
                << pad << "subsection " << demangle_parameter_name(name)
                << '\n';
            print_tree(out, node, indent + 2);
            out << pad << "end\n";
          }
    }
  } // namespace


  void
  print_parameters(std::ostream &out, const std::string &format)
  {
    dealii::ParameterHandler prm;
    Simulation<2>::declare_parameters(prm);
    StructureSimulation::declare_parameters(prm);
    CoupledSimulation<2>::declare_coupling_parameters(prm);
    if (format == "prm")
      {
        prm.print_parameters(out,
                             dealii::ParameterHandler::PRM |
                               dealii::ParameterHandler::KeepDeclarationOrder);
        return;
      }
    // Default, allowed values (pattern) and documentation of every entry.
    std::stringstream json;
    prm.print_parameters(json,
                         dealii::ParameterHandler::JSON |
                           dealii::ParameterHandler::KeepDeclarationOrder);
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    out
      << "# Every parameter of a Talus input file: default value, allowed\n"
         "# values and meaning (units in brackets). Defaults of vector\n"
         "# entries are shown for dimension = 2; in 3D they have a third\n"
         "# component. 'talus --print-parameters prm' prints an input file.\n\n";
    print_tree(out, tree, 0);
  }


} // namespace Talus
