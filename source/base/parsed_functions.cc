#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>

#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <cmath>
#include <sstream>

namespace Talus
{
  template <int dim>
  void
  parse_function(dealii::ParameterHandler               &prm,
                 dealii::Functions::ParsedFunction<dim> &function,
                 const std::string                      &subsection_path)
  {
    const std::string expression = prm.get("Function expression");
    try
      {
        function.parse_parameters(prm);
        dealii::Vector<double> values(function.n_components);
        function.vector_value(dealii::Point<dim>(), values);
        for (unsigned int c = 0; c < values.size(); ++c)
          if (!std::isfinite(values[c]))
            {
              std::ostringstream at_origin;
              at_origin << values[c];
              InputFile::reject(subsection_path,
                                "Function expression",
                                expression,
                                "it must evaluate to finite values; at x = " +
                                  std::string(dim == 3 ? "y = z = " : "y = ") +
                                  "0, t = 0 component " + std::to_string(c) +
                                  " is " + at_origin.str());
            }
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::ostringstream what;
        e.print_info(what);
        InputFile::reject(subsection_path,
                          "Function expression",
                          expression,
                          "it must be " +
                            std::to_string(function.n_components) +
                            " muparser expression(s) in x, y" +
                            (dim == 3 ? ", z" : "") +
                            ", t and the 'Function constants', separated by "
                            "';' (muparser: " +
                            dealii::Utilities::trim(what.str()) + ")");
      }
  }

  template void
  parse_function<2>(dealii::ParameterHandler &,
                    dealii::Functions::ParsedFunction<2> &,
                    const std::string &);
  template void
  parse_function<3>(dealii::ParameterHandler &,
                    dealii::Functions::ParsedFunction<3> &,
                    const std::string &);
} // namespace Talus
