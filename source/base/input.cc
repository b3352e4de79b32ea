#include <talus/base/input.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace Talus
{
  ExcInvalidInput::ExcInvalidInput(const std::string &message)
    : std::runtime_error(message)
  {}


  namespace
  {
    std::string &
    input_file_name()
    {
      static std::string name;
      return name;
    }
  } // namespace


  void
  InputFile::set_name(const std::string &filename)
  {
    input_file_name() = filename;
  }


  const std::string &
  InputFile::name()
  {
    return input_file_name();
  }


  unsigned int
  InputFile::line_of(const std::string &entry)
  {
    std::ifstream in(input_file_name());
    if (!in)
      return 0;
    const std::regex pattern(
      "^\\s*set\\s+" +
      std::regex_replace(entry,
                         std::regex(R"([.^$|()\[\]{}*+?\\])"),
                         R"(\$&)") +
      "\\s*=.*");
    std::string  line;
    unsigned int n = 0;
    while (std::getline(in, line))
      {
        ++n;
        if (std::regex_match(line, pattern))
          return n;
      }
    return 0;
  }


  void
  InputFile::reject(const std::string &subsection,
                    const std::string &entry,
                    const std::string &value,
                    const std::string &allowed)
  {
    std::ostringstream msg;
    msg << "Invalid input";
    if (!name().empty())
      {
        msg << " in file <" << name() << ">";
        const unsigned int line = line_of(entry);
        if (line > 0)
          msg << ", line " << line;
      }
    msg << ":\n  parameter <" << entry << "> in subsection <" << subsection
        << "> has the value <" << value << ">,\n  but " << allowed << ".";
    throw ExcInvalidInput(msg.str());
  }


  double
  get_positive(const dealii::ParameterHandler &prm,
               const std::string              &subsection,
               const std::string              &entry)
  {
    const double value = prm.get_double(entry);
    if (!(value > 0.))
      InputFile::reject(subsection,
                        entry,
                        prm.get(entry),
                        "it must be strictly positive");
    return value;
  }


  double
  get_in_open_interval(const dealii::ParameterHandler &prm,
                       const std::string              &subsection,
                       const std::string              &entry,
                       const double                    lower,
                       const double                    upper)
  {
    const double value = prm.get_double(entry);
    if (!(value > lower && value < upper))
      {
        std::ostringstream allowed;
        allowed << "it must lie strictly between " << lower << " and " << upper;
        InputFile::reject(subsection, entry, prm.get(entry), allowed.str());
      }
    return value;
  }
} // namespace Talus
