// Arrival time of the contact onset forecast
// (Talus::MPM::ContactForecast::arrival_time): the smallest t > 0 with
// s = v t + a t^2 / 2, against the roots of that quadratic evaluated by
// hand:
//   free fall from rest, s = 0.3 m, a = 9.81:  t = sqrt(2 s / a)
//                                             = 0.2473066...
//   constant speed, s = 0.5, v = 2, a = 0:     t = s / v = 0.25
//   decelerating, arrives, s = 1, v = 2, a = -1: t = 2 - sqrt(2)
//   moving away but pulled back, s = 0.5, v = -1, a = 10:
//                                             t = (1 + sqrt(11)) / 10
//   decelerating, stops short, s = 1, v = 1, a = -10: never (inf)
//   moving away, s = 1, v = -1, a = 0:         never (inf)
//   already touching, s = 0 or s < 0:          0
#include <talus/mpm/contact_forecast.h>

#include <cmath>
#include <iostream>
#include <limits>

namespace
{
  int failures = 0;

  void
  check(const char *what, const double value, const double expected)
  {
    const bool ok =
      std::isinf(expected) ?
        std::isinf(value) && value > 0. :
        std::abs(value - expected) <= 1e-14 * std::max(1., std::abs(expected));
    std::cout << what << ": " << value << (ok ? " ok" : " WRONG") << '\n';
    failures += ok ? 0 : 1;
  }
} // namespace

int
main()
{
  using Forecast     = Talus::MPM::ContactForecast<2>;
  const double never = std::numeric_limits<double>::infinity();
  check("free fall",
        Forecast::arrival_time(0.3, 0., 9.81),
        std::sqrt(2. * 0.3 / 9.81));
  check("constant speed", Forecast::arrival_time(0.5, 2., 0.), 0.25);
  check("decelerating, arrives",
        Forecast::arrival_time(1., 2., -1.),
        2. - std::sqrt(2.));
  check("moving away, pulled back",
        Forecast::arrival_time(0.5, -1., 10.),
        (1. + std::sqrt(11.)) / 10.);
  check("decelerating, stops short",
        Forecast::arrival_time(1., 1., -10.),
        never);
  check("moving away", Forecast::arrival_time(1., -1., 0.), never);
  check("touching", Forecast::arrival_time(0., 1., 0.), 0.);
  check("overlapping", Forecast::arrival_time(-0.1, -1., 0.), 0.);
  return failures == 0 ? 0 : 1;
}
