#ifndef talus_coupling_range_checks_h
#define talus_coupling_range_checks_h

// Range checks of the Coupling parameters that base/input.h does not offer
// (a half-open interval, an integer bound), with the same messages.

#include <talus/base/input.h>

#include <deal.II/base/parameter_handler.h>

#include <sstream>
#include <string>

namespace Talus
{
  namespace Coupling
  {
    namespace internal
    {
      /** Read a double and require lower < value <= upper. */
      inline double
      get_in_half_open_interval(const dealii::ParameterHandler &prm,
                                const std::string              &subsection,
                                const std::string              &entry,
                                const double                    lower,
                                const double                    upper)
      {
        const double value = prm.get_double(entry);
        if (!(value > lower && value <= upper))
          {
            std::ostringstream allowed;
            allowed << "it must lie in (" << lower << ", " << upper << "]";
            InputFile::reject(subsection, entry, prm.get(entry), allowed.str());
          }
        return value;
      }


      /** Read an integer and require value >= minimum. */
      inline unsigned int
      get_integer_at_least(const dealii::ParameterHandler &prm,
                           const std::string              &subsection,
                           const std::string              &entry,
                           const int                       minimum)
      {
        const long value = prm.get_integer(entry);
        if (value < minimum)
          InputFile::reject(subsection,
                            entry,
                            prm.get(entry),
                            "it must be an integer >= " +
                              std::to_string(minimum));
        return static_cast<unsigned int>(value);
      }
    } // namespace internal
  }   // namespace Coupling
} // namespace Talus

#endif
