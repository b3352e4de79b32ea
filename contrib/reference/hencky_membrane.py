#!/usr/bin/env python3
"""Hencky's clamped circular membrane under uniform pressure: the constants
c_w and c_sigma of w0 = c_w a (q a/(E h))^(1/3) and
sigma_centre = c_sigma (E q^2 a^2 / h^2)^(1/3).

Independent check for VERIFICATION.md section 3 (plain Python, no numpy).

Derivation (Foeppl membrane theory, axisymmetric, radius a, thickness h,
pressure q, edge u = w = 0). With N_r the radial force per length:
  vertical equilibrium  N_r w' = -q r / 2
  hoop equilibrium      N_t = (r N_r)'
  compatibility         eps_r = u' + w'^2/2, eps_t = u/r,
                        eps_r = (N_r - nu N_t)/(E h), eps_t = (N_t - nu N_r)/(E h)
eliminating u: r N_r'' + 3 N_r' + E h q^2 r / (8 N_r^2) = 0.
With r = a rho, N_r = h E Q^(2/3) S(rho), Q = q a/(E h):
  rho S'' + 3 S' + rho / (8 S^2) = 0,   S'(0) = 0,
  edge u(a) = 0  <=>  N_t = nu N_r  <=>  (1 - nu) S(1) + S'(1) = 0,
  w0 = a Q^(1/3) int_0^1 rho / (2 S) drho,  sigma_centre = S(0) E Q^(2/3).
So c_sigma = S(0) and c_w = int_0^1 rho/(2S) drho. S(0) is found by
shooting (bisection on the edge condition), the ODE by RK4 with the series
S = S0 - rho^2/(64 S0^2) near the axis.
"""
import sys


def shoot(S0, n=4000):
    """Integrate from rho = eps to 1; return (edge residual fn, c_w)."""
    eps = 1e-4
    S = S0 - eps**2 / (64 * S0**2)
    dS = -2 * eps / (64 * S0**2)
    # int_0^eps rho/(2S) ~ eps^2/(4 S0)
    cw = eps**2 / (4 * S0)

    def f(r, y):
        s, ds = y
        return (ds, (-3 * ds - r / (8 * s * s)) / r)

    h = (1 - eps) / n
    r = eps
    y = (S, dS)
    for _ in range(n):
        g0 = r / (2 * y[0])
        k1 = f(r, y)
        k2 = f(r + h / 2, (y[0] + h / 2 * k1[0], y[1] + h / 2 * k1[1]))
        k3 = f(r + h / 2, (y[0] + h / 2 * k2[0], y[1] + h / 2 * k2[1]))
        k4 = f(r + h, (y[0] + h * k3[0], y[1] + h * k3[1]))
        y = (y[0] + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
             y[1] + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))
        # Simpson for the integral with the RK midpoint estimate
        s_mid = y[0] * 0.5 + (y[0] - h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])) * 0.5
        g1 = (r + h) / (2 * y[0])
        gm = (r + h / 2) / (2 * s_mid)
        cw += h / 6 * (g0 + 4 * gm + g1)
        r += h
    return y, cw


def constants(nu, n=4000):
    lo, hi = 0.2, 1.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        (S1, dS1), _ = shoot(mid, n)
        if (1 - nu) * S1 + dS1 > 0:
            hi = mid
        else:
            lo = mid
    S0 = 0.5 * (lo + hi)
    (S1, dS1), cw = shoot(S0, n)
    return cw, S0, S1


if __name__ == "__main__":
    for nu in [0.25, 0.3, 0.5]:
        for n in [2000, 4000]:
            cw, cs, s_edge = constants(nu, n)
            print(f"nu = {nu}: n = {n}: c_w = {cw:.6f}  c_sigma = {cs:.6f}"
                  f"  sigma_r(edge)/(E Q^2/3) = {s_edge:.6f}")
