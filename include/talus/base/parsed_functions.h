#ifndef talus_base_parsed_functions_h
#define talus_base_parsed_functions_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>

#include <string>

namespace Talus
{
  /**
   * Parse a Functions::ParsedFunction from the current subsection of @p prm
   * and evaluate it once, so that an expression muparser cannot parse is
   * reported at start-up, on every rank, as an input error naming
   * @p subsection_path (deal.II 9.4 parses expressions lazily, at the first
   * evaluation).
   */
  template <int dim>
  void
  parse_function(dealii::ParameterHandler               &prm,
                 dealii::Functions::ParsedFunction<dim> &function,
                 const std::string                      &subsection_path);
} // namespace Talus

#endif
