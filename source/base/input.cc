#include <talus/base/input.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

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


  namespace
  {
    std::string
    trim(const std::string &s)
    {
      std::size_t begin = 0;
      std::size_t end   = s.size();
      while (begin < end &&
             std::isspace(static_cast<unsigned char>(s[begin])) != 0)
        ++begin;
      while (end > begin &&
             std::isspace(static_cast<unsigned char>(s[end - 1])) != 0)
        --end;
      return s.substr(begin, end - begin);
    }


    bool
    starts_with(const std::string &s, const std::string &prefix)
    {
      return s.compare(0, prefix.size(), prefix) == 0;
    }


    /**
     * Split "Body/Initial velocity" into {"Body", "Initial velocity"};
     * empty components (an empty path: the top level) are dropped.
     */
    std::vector<std::string>
    split_subsection_path(const std::string &path)
    {
      std::vector<std::string> components;
      std::size_t              begin = 0;
      while (begin <= path.size())
        {
          std::size_t end = path.find('/', begin);
          if (end == std::string::npos)
            end = path.size();
          const std::string component = trim(path.substr(begin, end - begin));
          if (!component.empty())
            components.push_back(component);
          begin = end + 1;
        }
      return components;
    }
  } // namespace


  unsigned int
  InputFile::line_of(const std::string &subsection_path,
                     const std::string &entry)
  {
    std::ifstream in(input_file_name());
    if (!in)
      return 0;

    const std::vector<std::string> wanted_path =
      split_subsection_path(subsection_path);
    const std::string wanted_entry = trim(entry);

    std::vector<std::string> current_path;
    unsigned int             found = 0;

    // One logical line (continuations already joined), interpreted as
    // dealii::ParameterHandler::scan_line() does. Lines deal.II would reject
    // cannot occur here (the file has been parsed successfully before any
    // value is checked) and are simply skipped.
    const auto scan = [&](std::string line, const unsigned int line_n) {
      const std::size_t comment = line.find('#');
      if (comment != std::string::npos)
        line.erase(comment);
      std::replace(line.begin(), line.end(), '\t', ' ');
      line = trim(line);

      if (starts_with(line, "subsection ") || starts_with(line, "SUBSECTION "))
        current_path.push_back(trim(line.substr(11)));
      else if (starts_with(line, "end") || starts_with(line, "END"))
        {
          if (trim(line.substr(3)).empty() && !current_path.empty())
            current_path.pop_back();
        }
      else if (starts_with(line, "set ") || starts_with(line, "SET "))
        {
          const std::size_t equals = line.find('=', 4);
          if (equals != std::string::npos &&
              trim(line.substr(4, equals - 4)) == wanted_entry &&
              current_path == wanted_path)
            found = line_n;
        }
    };

    std::string  physical_line;
    std::string  logical_line;
    bool         continued      = false;
    unsigned int line_n         = 0;
    unsigned int logical_line_n = 0;
    while (std::getline(in, physical_line))
      {
        ++line_n;
        if (!continued)
          {
            logical_line.clear();
            logical_line_n = line_n;
          }
        physical_line = trim(physical_line);
        if (!physical_line.empty() && physical_line.back() == '\\')
          {
            physical_line.pop_back();
            logical_line += physical_line;
            continued = true;
          }
        else
          {
            logical_line += physical_line;
            continued = false;
            scan(logical_line, logical_line_n);
          }
      }
    // deal.II also accepts a backslash on the very last line.
    if (continued)
      scan(logical_line, logical_line_n);

    return found;
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
        const unsigned int line = line_of(subsection, entry);
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
  get_non_negative(const dealii::ParameterHandler &prm,
                   const std::string              &subsection,
                   const std::string              &entry)
  {
    const double value = prm.get_double(entry);
    if (!(value >= 0.))
      InputFile::reject(subsection,
                        entry,
                        prm.get(entry),
                        "it must not be negative");
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


  bool
  parse_double(const std::string &text, double &value)
  {
    std::istringstream in(text);
    in >> value;
    if (in.fail() || !std::isfinite(value))
      return false;
    in >> std::ws;
    return in.eof();
  }
} // namespace Talus
