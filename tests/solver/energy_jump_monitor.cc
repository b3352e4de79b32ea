// The warning for a step whose energy balance jumps
// (Talus::EnergyJumpMonitor, subsection Time, 'energy jump warning' f =
// 0.01, 'energy jump outlier factor' c = 100, the default), against an energy
// moved of 1000 J (10 J at f):
// - balances 0, 0.5, 1, 1.5, 2, 150, 150.5: only the step 4 -> 5 (a jump
//   of 148 J, 14.8 % and 296 times the mean change 0.5 J) warns;
// - a steady drift of 15 J per step (1.5 %, but not above c times the
//   mean) does not warn;
// - the first steps (fewer than 3 changes before) are not assessed, even
//   with a jump of 50 %;
// - a jump in a step that lost points (reported on its own) does not warn;
// - f = 0 turns the monitor off.
#include <talus/base/energy_jump_monitor.h>

#include <deal.II/base/parameter_handler.h>

#include <iostream>
#include <vector>

namespace
{
  Talus::EnergyJumpMonitor
  monitor(const char *fraction)
  {
    dealii::ParameterHandler prm;
    prm.enter_subsection("Time");
    Talus::EnergyJumpMonitor::declare_parameters(prm);
    prm.set("energy jump warning", fraction);
    prm.leave_subsection();
    Talus::EnergyJumpMonitor m;
    m.parse_parameters(prm);
    return m;
  }

  int failures = 0;

  // the steps of @p balances that warn against those @p expected
  void
  run(const char                *what,
      Talus::EnergyJumpMonitor   m,
      const std::vector<double> &balances,
      const std::vector<bool>   &expected)
  {
    std::cout << what << '\n';
    for (unsigned int n = 0; n < balances.size(); ++n)
      {
        const std::string line = m.assess(n, 0.01 * n, balances[n], 1000.);
        std::cout << "  step " << n << ": "
                  << (line.empty() ? "-\n" : line.substr(2));
        if (line.empty() == expected[n])
          {
            std::cout << "  WRONG\n";
            ++failures;
          }
      }
  }
} // namespace

int
main()
{
  run("a jump after a quiet start",
      monitor("0.01"),
      {0., 0.5, 1., 1.5, 2., 150., 150.5},
      {false, false, false, false, false, true, false});
  run("a steady drift of 15 J per step",
      monitor("0.01"),
      {0., 15., 30., 45., 60., 75., 90.},
      {false, false, false, false, false, false, false});
  run("a jump in the first steps",
      monitor("0.01"),
      {0., 0.5, 500.},
      {false, false, false});
  run("off", monitor("0"), {0., 0.5, 1., 1.5, 2., 150.}, std::vector<bool>(6));
  {
    auto m = monitor("0.01");
    for (unsigned int n = 0; n < 5; ++n)
      m.assess(n, 0.01 * n, 0.5 * n, 1000.);
    const bool quiet = m.assess(5, 0.05, 150., 1000., true).empty();
    std::cout << "a jump with lost points: " << (quiet ? "no warning" : "WRONG")
              << '\n';
    failures += quiet ? 0 : 1;
  }
  std::cout << (failures == 0 ? "OK" : "FAILED") << '\n';
  return failures;
}
