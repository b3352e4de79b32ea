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
     * Line (1-based) where parameter @p entry of subsection
     * @p subsection_path is set in the file, or 0 if it is not set there (it
     * then has its default value) or the file cannot be read.
     *
     * @p subsection_path names the nested subsections separated by '/', as
     * passed to reject(): "Body", "Body/Initial velocity", "Solver/Body
     * force"; an empty path means the top level. The file is scanned the way
     * deal.II's ParameterHandler reads it: "subsection X" enters X, "end"
     * leaves it, everything after '#' is a comment, a line ending in a
     * backslash continues on the next one (the statement's first line is
     * reported), and the keywords are lower or upper case. If the entry is
     * set more than once, the last line is returned, since that is the value
     * deal.II keeps. Statements in files pulled in by "include" are not
     * followed.
     */
    static unsigned int
    line_of(const std::string &subsection_path, const std::string &entry);

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
   * Parse the whole of @p text (surrounding blanks allowed) as one finite
   * double; false if it is empty, not a number or followed by anything.
   */
  bool
  parse_double(const std::string &text, double &value);

  /**
   * Read a double from @p prm and require it to be strictly positive.
   */
  double
  get_positive(const dealii::ParameterHandler &prm,
               const std::string              &subsection,
               const std::string              &entry);

  /**
   * Read a double from @p prm and require it to be >= 0.
   */
  double
  get_non_negative(const dealii::ParameterHandler &prm,
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
