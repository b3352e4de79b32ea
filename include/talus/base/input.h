#ifndef talus_base_input_h
#define talus_base_input_h

#include <deal.II/base/parameter_handler.h>

#include <stdexcept>
#include <string>

namespace Talus
{
  /**
   * An error in the user's input: a parameter value outside its allowed
   * range, an inconsistent combination, an unreadable file. The message
   * names the input file, the line (when it can be found), the parameter
   * and what is allowed. The application prints it and exits with a
   * non-zero code; it is never caught silently.
   */
  class ExcInvalidInput : public std::runtime_error
  {
  public:
    explicit ExcInvalidInput(const std::string &message);
  };

  /**
   * The parameter file being read, so that range checks done after parsing
   * can still point at the line where the user set a value.
   */
  class InputFile
  {
  public:
    /** Set the file name used in messages (empty: no file). */
    static void
    set_name(const std::string &filename);

    static const std::string &
    name();

    /**
     * Line (1-based) of the first "set <entry> =" in the file, or 0 if the
     * entry is not set there (it then has its default value).
     */
    static unsigned int
    line_of(const std::string &entry);

    /**
     * Throw ExcInvalidInput for parameter @p entry of subsection
     * @p subsection with value @p value, explaining what is @p allowed.
     */
    [[noreturn]] static void
    reject(const std::string &subsection,
           const std::string &entry,
           const std::string &value,
           const std::string &allowed);
  };

  /**
   * Read a double from @p prm and require it to be strictly positive.
   */
  double
  get_positive(const dealii::ParameterHandler &prm,
               const std::string              &subsection,
               const std::string              &entry);

  /**
   * Read a double from @p prm and require lower < value < upper (strict).
   */
  double
  get_in_open_interval(const dealii::ParameterHandler &prm,
                       const std::string              &subsection,
                       const std::string              &entry,
                       const double                    lower,
                       const double                    upper);
} // namespace Talus

#endif
