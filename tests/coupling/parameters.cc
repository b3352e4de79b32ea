// Subsection `Coupling` (CouplingParameters with AccelerationParameters,
// ConvergenceCriterion and InterfacePredictor): the defaults parse, a valid
// file is read, and every value outside its range is rejected with
// ExcInvalidInput naming the parameter and the allowed range (the message
// is printed). A value read from a file names the file and the line.

#include <talus/base/input.h>
#include <talus/coupling/accelerators.h>
#include <talus/coupling/coupling_parameters.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

using namespace dealii;
using namespace Talus;
using namespace Talus::Coupling;

namespace
{
  std::ofstream out("output");


  void
  print(const CouplingParameters &p)
  {
    const auto accelerator = create_accelerator(p.acceleration);
    out << "  scheme "
        << (p.scheme == CouplingParameters::Scheme::strong ? "strong" : "weak")
        << ", order "
        << (p.order == CouplingParameters::Order::MPM_first ? "MPM first" :
                                                              "structure first")
        << ", accelerator " << accelerator->name() << ", relaxation "
        << p.acceleration.relaxation << ", initial relaxation "
        << p.acceleration.initial_relaxation << ", reuse "
        << p.acceleration.reuse << ", maximum columns "
        << p.acceleration.maximum_columns << ", filter "
        << (p.acceleration.filter == IQNILS::Filter::none ? "none" :
            p.acceleration.filter == IQNILS::Filter::QR1  ? "QR1" :
                                                            "QR2")
        << " " << p.acceleration.filter_tolerance << ", maximum iterations "
        << p.criterion.maximum_iterations() << ", relative tolerance "
        << p.criterion.relative_tolerance() << ", absolute tolerance "
        << p.criterion.absolute_tolerance() << ", predictor order "
        << static_cast<int>(p.predictor.order()) << '\n';
  }


  /** Parse with @p entry = @p value; print the error, return whether one
   * was thrown. */
  bool
  rejected(const std::string &entry, const std::string &value)
  {
    ParameterHandler prm;
    CouplingParameters::declare_parameters(prm);
    prm.enter_subsection("Coupling");
    prm.set(entry, value);
    prm.leave_subsection();
    CouplingParameters parameters;
    try
      {
        parameters.parse_parameters(prm);
      }
    catch (const ExcInvalidInput &e)
      {
        out << e.what() << '\n';
        return std::string(e.what()).find("<" + entry + ">") !=
               std::string::npos;
      }
    out << "  (accepted)\n";
    return false;
  }
} // namespace


int
main()
{
  out << "Defaults:\n";
  {
    ParameterHandler prm;
    CouplingParameters::declare_parameters(prm);
    CouplingParameters parameters;
    parameters.parse_parameters(prm);
    print(parameters);
  }

  out << "A valid file:\n";
  {
    std::ofstream file("coupling_good.prm");
    file << "subsection Coupling\n"
            "  set acceleration = Aitken\n"
            "  set initial relaxation = 0.5\n"
            "  set relaxation = 1\n"
            "  set IQN-ILS reuse = 0\n"
            "  set QR filter = QR1\n"
            "  set QR filter tolerance = 1e-6\n"
            "  set maximum coupling iterations = 1\n"
            "  set relative tolerance = 1e-4\n"
            "  set absolute tolerance = 1e-12\n"
            "  set force tolerance = 1e-3\n"
            "  set predictor = quadratic\n"
            "  set scheme = weak\n"
            "  set order = structure first\n"
            "end\n";
  }
  {
    ParameterHandler prm;
    CouplingParameters::declare_parameters(prm);
    prm.parse_input("coupling_good.prm");
    CouplingParameters parameters;
    parameters.parse_parameters(prm);
    print(parameters);
  }

  out << "\nBad values:\n";
  const std::vector<std::pair<std::string, std::string>> bad = {
    {"relaxation", "0"},
    {"relaxation", "-0.5"},
    {"relaxation", "1.5"},
    {"initial relaxation", "0"},
    {"initial relaxation", "2"},
    {"IQN-ILS reuse", "-1"},
    {"IQN-ILS maximum columns", "0"},
    {"QR filter tolerance", "0"},
    {"maximum coupling iterations", "0"},
    {"maximum coupling iterations", "-3"},
    {"relative tolerance", "0"},
    {"relative tolerance", "-1e-6"},
    {"absolute tolerance", "0"},
    {"force tolerance", "-1e-3"}};
  unsigned int n_rejected = 0;
  for (const auto &[entry, value] : bad)
    {
      out << entry << " = " << value << ":\n";
      if (rejected(entry, value))
        ++n_rejected;
    }
  out << n_rejected << " of " << bad.size()
      << " bad values rejected, naming the parameter\n";
  AssertThrow(n_rejected == bad.size(),
              ExcMessage("a bad Coupling value was accepted"));

  out << "\nFrom a file (the line is named):\n";
  {
    std::ofstream file("coupling_bad.prm");
    file << "# a coupling setup with a relaxation out of range\n"
            "subsection Coupling\n"
            "  set acceleration = constant\n"
            "  set relaxation   = 1.2\n"
            "end\n";
  }
  {
    ParameterHandler prm;
    CouplingParameters::declare_parameters(prm);
    prm.parse_input("coupling_bad.prm");
    InputFile::set_name("coupling_bad.prm");
    CouplingParameters parameters;
    bool               thrown = false;
    try
      {
        parameters.parse_parameters(prm);
      }
    catch (const ExcInvalidInput &e)
      {
        out << e.what() << '\n';
        thrown = std::string(e.what()).find("line 4") != std::string::npos;
      }
    AssertThrow(thrown, ExcMessage("the line of the bad value is not named"));
    InputFile::set_name("");
  }

  out << "\nA selection outside its list is rejected by the "
         "ParameterHandler:\n";
  {
    ParameterHandler prm;
    CouplingParameters::declare_parameters(prm);
    prm.enter_subsection("Coupling");
    bool thrown = false;
    try
      {
        prm.set("acceleration", "Broyden");
      }
    catch (const ExceptionBase &)
      {
        thrown = true;
      }
    prm.leave_subsection();
    out << "  acceleration = Broyden: " << (thrown ? "rejected" : "accepted")
        << '\n';
    AssertThrow(thrown, ExcMessage("acceleration = Broyden accepted"));
  }
  return 0;
}
