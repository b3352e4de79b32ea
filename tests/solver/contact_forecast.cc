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
// and the entry time of a path x + v t + a t^2 / 2 into a box
// (ContactForecast::box_entry_time, the halo of the boundary particles'
// cells) in the unit square [0, 1]^2, against the same by hand:
//   falling from (0.5, 2) from rest, g = 9.81: y = 1 at t = sqrt(2 / g)
//   the same with the horizon 0.3 s:            never (inf)
//   inside:                                     0
//   constant speed from (-1, 0.5), v = (2, 0):  t = 0.5
//   falling beside the box from (2, 2):         never
//   decelerating from (0.5, 2), v = (0, -1), a = (0, 1): turns at y = 1.5,
//                                               never
//   thrown up from (0.5, -0.5), v = (0, 4), g:  t = (4 - sqrt(16 - g)) / g
//   diagonal from (-1, -1), v = (1, 2): y enters at 0.5, x only at 1:
//                                               t = 1
#include <talus/mpm/contact_forecast.h>

#include <cmath>
#include <iostream>
#include <limits>

#include "check_close.h"


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

  const dealii::BoundingBox<2> box(
    std::make_pair(dealii::Point<2>(0., 0.), dealii::Point<2>(1., 1.)));
  const double               g = 9.81;
  const dealii::Tensor<1, 2> zero;
  dealii::Tensor<1, 2>       gravity;
  gravity[1] = -g;
  check("box: falling from rest",
        Forecast::box_entry_time(
          dealii::Point<2>(0.5, 2.), zero, gravity, box, 10.),
        std::sqrt(2. / g));
  check("box: falling, beyond the horizon",
        Forecast::box_entry_time(
          dealii::Point<2>(0.5, 2.), zero, gravity, box, 0.3),
        never);
  check("box: inside",
        Forecast::box_entry_time(
          dealii::Point<2>(0.5, 0.5), zero, gravity, box, 10.),
        0.);
  dealii::Tensor<1, 2> v;
  v[0] = 2.;
  check("box: constant speed",
        Forecast::box_entry_time(dealii::Point<2>(-1., 0.5), v, zero, box, 10.),
        0.5);
  check(
    "box: falling beside",
    Forecast::box_entry_time(dealii::Point<2>(2., 2.), zero, gravity, box, 10.),
    never);
  v[0] = 0.;
  v[1] = -1.;
  dealii::Tensor<1, 2> a;
  a[1] = 1.;
  check("box: decelerating, turns before",
        Forecast::box_entry_time(dealii::Point<2>(0.5, 2.), v, a, box, 10.),
        never);
  v[1] = 4.;
  check(
    "box: thrown up from below",
    Forecast::box_entry_time(dealii::Point<2>(0.5, -0.5), v, gravity, box, 10.),
    (4. - std::sqrt(16. - g)) / g);
  v[0] = 1.;
  v[1] = 2.;
  check("box: diagonal, the later direction",
        Forecast::box_entry_time(dealii::Point<2>(-1., -1.), v, zero, box, 10.),
        1.);
  return failures == 0 ? 0 : 1;
}
