// The normalised truncation error of a step shared by several fields
// (Talus::TruncationErrorControl::mass_weighted_error, 'coupled error norm
// = mass weighted') against values worked out by hand from
//   eta = (sum_f m_f e_f^2 / sum_f m_f)^(1/2)
//         / ((sum_f m_f du_f^2 / sum_f m_f)^(1/2) + u_0),
//   e_f = dt^2 |beta_f - 1/6| ||a_{n+1} - a_n||_f:
//   one field:                       the single-field error() exactly
//   two equal fields:                the single-field error() exactly
//   a massless second field:         ignored
//   dt = 0.1, u_0 = 0,
//   field 1 (m = 3, beta = 1/4, ||da|| = 12, ||du|| = 0.02):
//                                    e_1 = 0.01 / 12 * 12 = 0.01
//   field 2 (m = 1, beta = 0.3025, ||da|| = 0, ||du|| = 0.04):
//                                    e_2 = 0
//     eta = (3/4 * 1e-4)^(1/2) / ((3/4 * 4e-4 + 1/4 * 16e-4)^(1/2))
//         = sqrt(0.75e-4) / sqrt(7e-4) = sqrt(3/28)
//   the same with e_2 = e_1 = 0.01 (||da||_2 = 0.01 / (dt^2 |0.3025 -
//     1/6|)): eta = 0.01 / sqrt(7e-4)
//   the larger field's error of the first pair: 0.01 / 0.02 = 0.5
//   no mass at all:                  0
#include <talus/base/step_size_controller.h>

#include <cmath>
#include <iostream>

#include "check_close.h"


int
main()
{
  Talus::TruncationErrorControl control;
  control.tolerance = 1e-3;
  control.floor     = 0.;

  Talus::TruncationErrorNorms a;
  a.acceleration_change = 12.;
  a.increment           = 0.02;
  a.mass                = 3.;
  const double dt       = 0.1;

  check("one field",
        control.mass_weighted_error({{a, 0.25}}, dt),
        control.error(a, dt, 0.25));
  check("two equal fields",
        control.mass_weighted_error({{a, 0.25}, {a, 0.25}}, dt),
        control.error(a, dt, 0.25));
  Talus::TruncationErrorNorms massless = a;
  massless.acceleration_change         = 1e6;
  massless.mass                        = 0.;
  check("a massless field",
        control.mass_weighted_error({{a, 0.25}, {massless, 0.25}}, dt),
        control.error(a, dt, 0.25));

  Talus::TruncationErrorNorms b;
  b.acceleration_change = 0.;
  b.increment           = 0.04;
  b.mass                = 1.;
  check("field 2 without error",
        control.mass_weighted_error({{a, 0.25}, {b, 0.3025}}, dt),
        std::sqrt(3. / 28.));
  b.acceleration_change = 0.01 / (dt * dt * std::abs(0.3025 - 1. / 6.));
  check("field 2 with the error of field 1",
        control.mass_weighted_error({{a, 0.25}, {b, 0.3025}}, dt),
        0.01 / std::sqrt(7e-4));
  check("larger field of the first pair", control.error(a, dt, 0.25), 0.5);
  Talus::TruncationErrorNorms none;
  check("no mass", control.mass_weighted_error({{none, 0.25}}, dt), 0.);

  std::cout << (failures == 0 ? "PASS" : "FAIL") << '\n';
  return failures == 0 ? 0 : 1;
}
