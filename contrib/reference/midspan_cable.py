#!/usr/bin/env python3
"""Cable between two anchors, point load P at midspan: the sag w of the
two-bar truss for the engineering and the Green-Lagrange axial law
(tests/structure/midspan_cable_*.prm; plain Python, decimal arithmetic
with 40 digits, bisection to 1e-30 m).

Half span b, reference length of a half b, pre-stress sigma_0 (the axial
stress at the reference length): half length l = sqrt(b^2 + w^2),
  2 N(l/b) w/l = P,
  engineering:    N = EA (l - l0)/l0, l0 = b/(1 + sigma_0/E),
  Green-Lagrange: N = A (E (lambda^2 - 1)/2 + sigma_0) lambda, lambda = l/b.
"""
from decimal import Decimal as D, getcontext

getcontext().prec = 40
E, A = D("1.2e11"), D("2e-4")
EA, b, P = E * A, D(5), D("2e5")


def engineering(lam, s0):
    return EA * (lam * (1 + s0 / E) - 1)


def green_lagrange(lam, s0):
    return A * (E * (lam * lam - 1) / 2 + s0) * lam


for s0 in (D(0), D("2e8")):
    for name, N in (("engineering", engineering),
                    ("Green-Lagrange", green_lagrange)):
        def balance(w):
            l = (b * b + w * w).sqrt()
            return 2 * max(D(0), N(l / b, s0)) * w / l - P
        lo, hi = D(0), D(5)
        while hi - lo > D("1e-30"):
            mid = (lo + hi) / 2
            if balance(mid) < 0:
                lo = mid
            else:
                hi = mid
        w = (lo + hi) / 2
        lam = (b * b + w * w).sqrt() / b
        print(f"sigma_0 = {s0:.1e} Pa, {name}: w = {w:.19f} m, "
              f"N = {N(lam, s0):.14f} N, (l - b)/b = {lam - 1:.9f}")
