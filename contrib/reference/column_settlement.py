#!/usr/bin/env python3
"""Reference top settlement of an elastic column under self weight.

Independent check for VERIFICATION.md section 1.3 (plain Python, no numpy).

Set-up: height l0, laterally restrained (uniaxial strain), base fixed,
nu = 0, Young's modulus E, density rho0, gravity g.  Y is the initial
(reference) height, lam(Y) = dy/dY the axial stretch; the lateral stretches
are 1, so J = det F = lam and the cross-section area does not change.

Equilibrium.  With constant area the nominal (1st Piola-Kirchhoff) stress
P = J sigma F^-T has P_yy = lam sigma_yy / lam = sigma_yy, and the reference
balance dP/dY = rho0 g with P(l0) = 0 gives, for ANY constitutive law,
    sigma(Y) = P(Y) = -rho0 g (l0 - Y),   base stress -rho0 g l0 = -40 kPa.

Settlement.  s = l0 - y(l0) = int_0^l0 (1 - lam(Y)) dY, where lam(Y) solves
    E f(lam) = sigma(Y)
for the law's stress-stretch function f (increasing on (0, 1]):
  (a) small strain, linear:   sigma = E (lam - 1)          f = lam - 1
  (b) Hencky, Kirchhoff:      tau = E ln lam, sigma = tau/J  f = ln(lam)/lam
      (the usual Hencky model tau = lambda tr(ln V) I + 2 mu ln V with nu = 0)
  (c) Hencky, Cauchy:         sigma = E ln lam               f = ln(lam)
      (the variant quoted in VERIFICATION.md, 0.98680 m)
  (d) compressible neo-Hookean P = mu (F - F^-T) + lambda ln(J) F^-T with
      nu = 0: lambda = 0, mu = E/2;  P_yy = mu (lam - 1/lam) and
      sigma_yy = P_yy F_yy / J = P_yy, so  f = (lam - 1/lam)/2.
      (All four have slope E at lam = 1.)

Two independent evaluations, which must agree:
  1. quadrature: composite 5-point Gauss-Legendre in Y, lam(Y) by bisection;
  2. closed form: substitute Y = l0 + sigma/(rho0 g), dY = (E/(rho0 g)) f'(lam)
     dlam, integrate by parts with f(1) = 0:
        s = (E/(rho0 g)) [ -(1 - lam_b) f(lam_b) + int_{lam_b}^1 f dlam ],
     lam_b the stretch at the base, with the antiderivatives F of f below.
"""

import math

L0 = 50.0       # column height [m]
E = 1.0e6       # Young's modulus [Pa]
RHO0 = 80.0     # reference density [kg/m^3]
G = 10.0        # gravity [m/s^2]

# name: (f(lam), antiderivative F(lam) of f, closed-form lam(s) or None)
LAWS = {
    "(a) small strain, sigma = E (lam - 1)":
        (lambda l: l - 1.0, lambda l: 0.5 * l * l - l,
         lambda s: 1.0 + s),
    "(b) Hencky, tau = E ln lam (sigma = E ln lam / lam)":
        (lambda l: math.log(l) / l, lambda l: 0.5 * math.log(l) ** 2,
         None),
    "(c) Hencky, sigma = E ln lam (VERIFICATION.md)":
        (lambda l: math.log(l), lambda l: l * math.log(l) - l,
         lambda s: math.exp(s)),
    "(d) neo-Hookean, nu = 0: sigma = E/2 (lam - 1/lam)":
        (lambda l: 0.5 * (l - 1.0 / l), lambda l: 0.25 * l * l - 0.5 * math.log(l),
         lambda s: s + math.sqrt(s * s + 1.0)),
}


def stress(Y):
    """Cauchy stress sigma_yy at initial height Y [Pa]."""
    return -RHO0 * G * (L0 - Y)


def stretch(f, s):
    """Solve f(lam) = s for lam in (0, 1] by bisection (f increasing, s <= 0)."""
    lo, hi = 0.5, 1.0
    while f(lo) > s:                      # widen the bracket towards 0
        lo *= 0.5
        if lo < 1e-300:
            raise ValueError(f"no stretch in (0, 1] for sigma/E = {s}")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) > s:
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-16:
            break
    return 0.5 * (lo + hi)


# 5-point Gauss-Legendre rule on [-1, 1]
GAUSS_X = [0.0, -0.5384693101056831, 0.5384693101056831,
           -0.9061798459386640, 0.9061798459386640]
GAUSS_W = [0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
           0.2369268850561891, 0.2369268850561891]


def settlement_quadrature(f, n_intervals=200):
    """int_0^l0 (1 - lam(Y)) dY, composite Gauss-Legendre."""
    h = L0 / n_intervals
    total = 0.0
    for i in range(n_intervals):
        mid = (i + 0.5) * h
        for x, w in zip(GAUSS_X, GAUSS_W):
            lam = stretch(f, stress(mid + 0.5 * h * x) / E)
            total += 0.5 * h * w * (1.0 - lam)
    return total


def settlement_closed_form(f, F, lam_b):
    """(E/(rho0 g)) [-(1 - lam_b) f(lam_b) + F(1) - F(lam_b)]."""
    return E / (RHO0 * G) * (-(1.0 - lam_b) * f(lam_b) + F(1.0) - F(lam_b))


def main():
    s_base = stress(0.0) / E
    print(f"Column under self weight: l0 = {L0} m, E = {E:g} Pa, nu = 0, "
          f"rho0 = {RHO0} kg/m^3, g = {G} m/s^2")
    print(f"Base stress sigma_yy(0) = {stress(0.0):.3f} Pa "
          f"({stress(0.0) / 1e3:.6f} kPa), sigma/E = {s_base:.6f}")
    print(f"Small-strain estimate rho0 g l0^2/(2E) = "
          f"{RHO0 * G * L0 ** 2 / (2 * E):.10f} m\n")
    print(f"{'law':54s} {'base stretch':>14s} {'settlement [m]':>16s} "
          f"{'closed form [m]':>16s} {'difference':>11s}")
    for name, (f, F, lam_exact) in LAWS.items():
        lam_b = stretch(f, s_base)
        if lam_exact is not None:         # check the bisection where we can
            assert abs(lam_b - lam_exact(s_base)) < 1e-14, name
        s_q = settlement_quadrature(f)
        s_c = settlement_closed_form(f, F, lam_b)
        print(f"{name:54s} {lam_b:14.10f} {s_q:16.10f} {s_c:16.10f} "
              f"{s_q - s_c:11.1e}")
        if abs(s_q - s_c) > 1e-9:
            raise SystemExit(f"column_settlement.py: quadrature and closed "
                             f"form disagree for {name}")


if __name__ == "__main__":
    main()
