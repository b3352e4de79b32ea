#!/usr/bin/env python3
"""Closed-form values of the axial vibrating bar, VERIFICATION.md section 1.1.

Bar on [0, L], fixed at x = 0, free at x = L, wave speed c = sqrt(E/rho)
(nu = 0, or E the constrained modulus).  First mode, beta1 = pi/(2L),
omega1 = beta1 c, with u(x,0) = 0 and v(x,0) = v0 sin(beta1 x):
    u(x,t)     = (v0/omega1) sin(omega1 t) sin(beta1 x)
    v(x,t)     = v0 cos(omega1 t) sin(beta1 x)
    sigma(x,t) = E du/dx = rho c v0 sin(omega1 t) cos(beta1 x)
    T1 = 2 pi/omega1 = 4 L/c,  tip amplitude u(L) = v0/omega1,
    v_cm(t) = (1/L) int_0^L v dx = (2 v0/pi) cos(omega1 t),
    E_tot = 1/2 rho int v^2 dx + 1/2 int sigma^2/E dx = 1/4 rho L v0^2
            (per unit cross-section, constant in time).

The script prints the closed forms and checks them independently:
v_cm and E_tot by composite Simpson quadrature of the fields at several
times, and the fields against the wave equation rho u_tt = E u_xx and the
boundary conditions u(0) = 0, sigma(L) = 0 by central finite differences.

usage: vibrating_bar.py [--L 25] [--E 100] [--rho 1] [--v0 0.1]
"""

import argparse
import math


def simpson(fun, a, b, n=2000):
    """Composite Simpson rule with n (even) intervals."""
    h = (b - a) / n
    s = fun(a) + fun(b)
    s += sum((4 if i % 2 else 2) * fun(a + i * h) for i in range(1, n))
    return s * h / 3.0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--L", type=float, default=25.0, help="length [m]")
    p.add_argument("--E", type=float, default=100.0, help="modulus [Pa]")
    p.add_argument("--rho", type=float, default=1.0, help="density [kg/m^3]")
    p.add_argument("--v0", type=float, default=0.1, help="velocity [m/s]")
    a = p.parse_args()
    if min(a.L, a.E, a.rho) <= 0:
        p.error("L, E and rho must be positive")
    L, E, rho, v0 = a.L, a.E, a.rho, a.v0

    c = math.sqrt(E / rho)
    beta = math.pi / (2 * L)
    omega = beta * c
    T1 = 2 * math.pi / omega

    def u(x, t):
        return v0 / omega * math.sin(omega * t) * math.sin(beta * x)

    def v(x, t):
        return v0 * math.cos(omega * t) * math.sin(beta * x)

    def sigma(x, t):
        return rho * c * v0 * math.sin(omega * t) * math.cos(beta * x)

    print(f"Vibrating bar: L = {L:g} m, E = {E:g} Pa, rho = {rho:g} kg/m^3, "
          f"v0 = {v0:g} m/s")
    rows = [("wave speed c [m/s]", c),
            ("omega1 [rad/s]", omega),
            ("period T1 [s]", T1),
            ("tip amplitude v0/omega1 [m]", v0 / omega),
            ("stress amplitude rho c v0 [Pa]", rho * c * v0),
            ("v_cm(0) = 2 v0/pi [m/s]", 2 * v0 / math.pi),
            ("E_tot = rho L v0^2/4 [J/m^2]", rho * L * v0 ** 2 / 4)]
    for name, value in rows:
        print(f"  {name:34s} {value:.8g}")

    # Independent checks at a few times over one period.
    worst = 0.0
    for t in [0.0, 0.1 * T1, T1 / 4, 0.6 * T1, T1 / 2]:
        vcm = simpson(lambda x: v(x, t), 0.0, L) / L
        etot = simpson(lambda x: 0.5 * rho * v(x, t) ** 2
                       + 0.5 * sigma(x, t) ** 2 / E, 0.0, L)
        worst = max(worst,
                    abs(vcm - 2 * v0 / math.pi * math.cos(omega * t)) / v0,
                    abs(etot - rho * L * v0 ** 2 / 4) / (rho * L * v0 ** 2))
        hx, ht = 1e-3 * L, 1e-3 * T1
        x = 0.37 * L
        u_tt = (u(x, t + ht) - 2 * u(x, t) + u(x, t - ht)) / ht ** 2
        u_xx = (u(x + hx, t) - 2 * u(x, t) + u(x - hx, t)) / hx ** 2
        scale = E * v0 / omega * beta ** 2
        worst = max(worst, abs(rho * u_tt - E * u_xx) / scale,
                    abs(u(0.0, t)) / (v0 / omega),
                    abs(sigma(L, t)) / (rho * c * v0),
                    abs(E * (u(x + hx, t) - u(x - hx, t)) / (2 * hx)
                        - sigma(x, t)) / (rho * c * v0))
    print(f"  largest relative mismatch of the checks: {worst:.1e}")
    if worst > 1e-5:
        raise SystemExit("vibrating_bar.py: closed form fails its checks")


if __name__ == "__main__":
    main()
