// The 1D GIMP weights of 'shape functions = uGIMP' and 'cpGIMP'
// (Talus::MPM::internal::gimp_weight, include/talus/mpm/point_tensors.h):
// the hat function N(s) = max(0, 1 - |s|/h) averaged over a point's domain
// [x_p - l, x_p + l]. Checked for h = 0.25 m and the half-widths l/h =
// 0, 0.125, 0.25 (uGIMP with 2 and 1 points per direction), 0.5 and the
// convected (cpGIMP) 0.5 + 1e-12, 0.7, 1:
//  - l <= h/2: identical (bit for bit) to ugimp_weight, the closed form of
//    Steffen, Kirby and Berzins 2008 (eq. 17);
//  - partition of unity sum_I S_I = 1 and sum_I dS_I = 0 over the nodes of
//    the 4-node patch around a point anywhere in its cell (to 1e-14; for
//    l = 0, the linear hat, not at the nodes, where dS jumps);
//  - the weight equals the average of N over the domain by the midpoint
//    rule with 2e5 intervals (to 1e-9);
//  - dS/dx_p equals the central difference of S (step 1e-7 h, to 1e-5 1/m,
//    2.5e-6 of 1/h: the second derivative jumps at the kinks);
//  - continuity in l across l = h/2 (the closed form and the antiderivative
//    form agree to 1e-12);
//  - the support: zero weight at |r| >= h + l, so l <= h keeps a point in
//    the 4^dim patch of its cell.
#include <talus/mpm/point_tensors.h>

#include <cmath>
#include <iostream>

namespace
{
  int failures = 0;

  void
  check(const char  *what,
        const double l_over_h,
        const double error,
        const double tolerance)
  {
    const bool ok = error <= tolerance;
    std::cout << what << " (l/h = " << l_over_h
              << "): " << (ok ? "ok" : "WRONG") << '\n';
    if (!ok)
      std::cout << "  error " << error << " > " << tolerance << '\n';
    failures += ok ? 0 : 1;
  }
} // namespace

int
main()
{
  using Talus::MPM::internal::gimp_weight;
  using Talus::MPM::internal::ugimp_weight;
  const double h = 0.25;
  for (const double lh : {0., 0.125, 0.25, 0.5, 0.5 + 1e-12, 0.7, 1.})
    {
      const double l      = lh * h;
      double       closed = 0., unity = 0., gradient_sum = 0., average = 0.,
             derivative = 0., support = 0.;
      for (int k = 0; k <= 40; ++k)
        {
          // a point at x_p = k/40 h in the cell [0, h]; nodes at -h .. 2h
          if (l == 0. && (k == 0 || k == 40))
            continue;
          const double x   = k / 40. * h;
          double       sum = 0., dsum = 0.;
          for (int node = -1; node <= 2; ++node)
            {
              const double r = x - node * h;
              double       dS;
              const double S = gimp_weight(r, h, l, dS);
              sum += S;
              dsum += dS;
              if (lh <= 0.5)
                {
                  double       dU;
                  const double U = ugimp_weight(r, h, l, dU);
                  closed =
                    std::max(closed, std::abs(U - S) + std::abs(dU - dS));
                }
              if (l > 0.)
                {
                  const int n    = 200000;
                  double    mean = 0.;
                  for (int i = 0; i < n; ++i)
                    {
                      const double s = r - l + (i + 0.5) * 2. * l / n;
                      mean += std::max(0., 1. - std::abs(s) / h);
                    }
                  average = std::max(average, std::abs(mean / n - S));
                }
              const double eps = 1e-7 * h;
              double       d;
              const double Sp = gimp_weight(r + eps, h, l, d);
              const double Sm = gimp_weight(r - eps, h, l, d);
              derivative =
                std::max(derivative, std::abs((Sp - Sm) / (2. * eps) - dS));
              // two cells away from the point's cell: beyond the support
              double dz;
              support = std::max(support,
                                 std::abs(gimp_weight(x + 2. * h, h, l, dz)) +
                                   std::abs(gimp_weight(x - 3. * h, h, l, dz)));
            }
          unity        = std::max(unity, std::abs(sum - 1.));
          gradient_sum = std::max(gradient_sum, std::abs(dsum));
        }
      if (lh <= 0.5)
        check("equal to the uGIMP closed form", lh, closed, 0.);
      check("partition of unity", lh, unity, 1e-14);
      check("gradients sum to zero", lh, gradient_sum, 1e-12);
      if (l > 0.)
        check("average of the hat over the domain", lh, average, 1e-9);
      check("derivative against central differences", lh, derivative, 1e-5);
      check("zero beyond h + l", lh, support, 0.);
    }
  // continuity in l at h/2: the closed form just below, the antiderivative
  // form just above
  double jump = 0.;
  for (int k = -80; k <= 80; ++k)
    {
      const double r = k / 40. * h;
      double       d1, d2;
      const double a = gimp_weight(r, h, 0.5 * h, d1);
      const double b = gimp_weight(r, h, 0.5 * h * (1. + 1e-13), d2);
      jump           = std::max(jump, std::abs(a - b) + h * std::abs(d1 - d2));
    }
  check("continuous in l across h/2", 0.5, jump, 1e-12);
  std::cout << (failures == 0 ? "all checks passed" : "FAILED") << '\n';
  return failures == 0 ? 0 : 1;
}
