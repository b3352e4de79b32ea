#!/usr/bin/env python3
"""Pre-stressed square membrane under a small uniform pressure: the constant
k of w_max = k q a^2 / N0 (VERIFICATION.md section 3; plain Python).

Small deflection: N0 (w_xx + w_yy) = -q on the square (0, a)^2, w = 0 on
the edges. With the double sine series of q (odd m, n only),
  q = sum 16 q / (pi^2 m n) sin(m pi x/a) sin(n pi y/a),
  w = sum 16 q a^2 / (pi^4 N0 m n (m^2 + n^2)) sin(m pi x/a) sin(n pi y/a),
and at the centre sin(m pi/2) sin(n pi/2) = (-1)^((m+n)/2 - 1).
Partial sums with M terms per direction are printed to show convergence.
"""
import math

for M in (100, 200, 400, 800):
    k = 0.0
    for m in range(1, 2 * M, 2):
        for n in range(1, 2 * M, 2):
            k += 16.0 / (math.pi**4 * m * n * (m * m + n * n)) * \
                (-1) ** ((m + n) // 2 - 1)
    print(f"{M} terms per direction: k = {k:.8f}")
print("circular membrane, radius R: w_max = q R^2 / (4 N0) (exact)")
