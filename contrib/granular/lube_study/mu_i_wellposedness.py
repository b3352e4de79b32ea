#!/usr/bin/env python3
# Used by doc/verification.md, "Lube series at 10 mm, and what the grid
# dependence is not" (well-posedness of mu(I)).
"""Ill-posed ranges of the incompressible mu(I) rheology (Barker et al. 2015 criterion).

Pure Python (no numpy needed).  Run:  python3 contrib/granular/lube_study/mu_i_wellposedness.py

Criterion (2D, incompressible, high-wavenumber / frozen-coefficient analysis):

    C(I) = 4 nu^2 - 4 nu + mu^2 (1 - nu/2)^2,     nu = I mu'(I) / mu(I)

    C < 0  -> well posed,   C > 0 -> ill posed (growth rate ~ k^2, unbounded).

Here mu = |tau|/p is the ratio of the deviatoric-stress magnitude
|tau| = sqrt(tau:tau/2) to the (2D) pressure p, i.e. radius / centre of the
in-plane Mohr circle, and I = 2 d ||D|| / sqrt(p/rho) (= gammadot d/sqrt(p/rho)
in simple shear).  The expression is the one coded as "C equation 3.9 in
Barker & Gray 2017" in github.com/alexjarosch/OpenFOAM-muI
(muIreg/muIreg.C, utils/calc_IN1.py) and was re-derived by a
high-wavenumber analysis; self_check() below re-does it numerically.

Two ways of feeding the talus mu(I) into the criterion are evaluated:

  A  "mu(I)-fluid": Barker's mu is the mu(I) of the law itself
     (mu = tan phi_s + dmu I/(I0+I)); this is the classical incompressible
     mu(I) rheology the paper analyses.
  B  "plane-strain Mohr-Coulomb, psi = 0" (what talus does: it sets
     tan(phi) = mu(I) and uses phi in Mohr-Coulomb).  In plane strain with
     zero dilatancy the flowing state is a 2D incompressible mu-law with
     Mohr-circle ratio  mu_B = sin(phi) = mu/sqrt(1+mu^2),  and
     nu_B = I mu_B'/mu_B = nu/(1+mu^2).
"""
import math

DEG = math.pi / 180.0


# ----------------------------------------------------------------- criterion
def C_of(mu, nu):
    """Barker et al. (2015) discriminant; < 0 well posed, > 0 ill posed."""
    return 4.0 * nu * nu - 4.0 * nu + mu * mu * (1.0 - 0.5 * nu) ** 2


def jop(mu_s, dmu, I0):
    """Jop et al. mu(I) and its logarithmic slope nu = I mu'/mu."""
    def f(I):
        mu = mu_s + dmu * I / (I0 + I)
        dmu_dI = dmu * I0 / (I0 + I) ** 2
        return mu, I * dmu_dI / mu
    return f


def mc_plane_strain(law):
    """Mapping B: tan(phi) = mu(I) in plane-strain Mohr-Coulomb, psi = 0."""
    def f(I):
        mu, nu = law(I)
        return mu / math.sqrt(1.0 + mu * mu), nu / (1.0 + mu * mu)
    return f


def barker_gray_high(mu_s, mu_2, mu_inf, I0):
    """High-I branch of the Barker & Gray (2017) curve (eq. 6.3 as coded in
    OpenFOAM-muI): mu = (mu_s I0 + mu_2 I + mu_inf I^2)/(I0 + I)."""
    def f(I):
        num = mu_s * I0 + mu_2 * I + mu_inf * I * I
        mu = num / (I0 + I)
        dmu = ((mu_2 + 2.0 * mu_inf * I) * (I0 + I) - num) / (I0 + I) ** 2
        return mu, I * dmu / mu
    return f


def C_at(law, I):
    mu, nu = law(I)
    return C_of(mu, nu)


# -------------------------------------------------------------- root finding
def crossings(law, lo=1e-9, hi=1e4, n=4000):
    """Sign changes of C on a log grid, refined by bisection."""
    Is = [lo * (hi / lo) ** (k / n) for k in range(n + 1)]
    Cs = [C_at(law, I) for I in Is]
    roots = []
    for k in range(n):
        if (Cs[k] > 0) != (Cs[k + 1] > 0):
            a, b = Is[k], Is[k + 1]
            ca = Cs[k]
            for _ in range(200):
                m = math.sqrt(a * b)
                cm = C_at(law, m)
                if (cm > 0) == (ca > 0):
                    a, ca = m, cm
                else:
                    b = m
            roots.append((math.sqrt(a * b), "ill->well" if Cs[k] > 0 else "well->ill"))
    return roots, min(Cs)


def describe(label, law):
    roots, cmin = crossings(law)
    if not roots:
        state = "ILL POSED for every I in [1e-9, 1e4]" if cmin > 0 else "well posed everywhere"
        print(f"  {label:<44s} {state}  (min C = {cmin:+.4f})")
        return None
    txt = ", ".join(f"{r:.4g} ({d})" for r, d in roots)
    if len(roots) == 2 and roots[0][1] == "ill->well":
        I1, I2 = roots[0][0], roots[1][0]
        print(f"  {label:<44s} well posed for {I1:.4g} < I < {I2:.4g};"
              f" ill posed for I < {I1:.4g} and I > {I2:.4g}")
        return I1, I2
    print(f"  {label:<44s} sign changes at {txt}")
    return None


# ---------------------------------------------------------------- self check
def self_check():
    """Re-derivation check: for the 2D incompressible law
    tau = mu(I) p D/|D| the high-wavenumber growth rate of a mode with wave
    vector at angle theta is  lambda = -k^2 (mu p / (2 rho |D|)) F(theta),
        F = (s^2 - a s + nu c^2) / (1 - a s),  s = sin 2theta', c = cos 2theta',
        a = mu (1 - nu/2)
    (theta' measured from the principal axes of D).  Ill posed <=> min F < 0.
    Check that min F < 0 exactly when C > 0 over a grid of (mu, nu)."""
    bad = 0
    for i in range(1, 60):
        mu = 0.02 * i                    # 0.02 .. 1.18
        for j in range(0, 60):
            nu = 0.01 * j                # 0 .. 0.59
            a = mu * (1.0 - 0.5 * nu)
            if a >= 1.0:
                continue
            Fmin = min((s * s - a * s + nu * (1.0 - s * s)) / (1.0 - a * s)
                       for s in (-1.0 + 2.0 * k / 4000 for k in range(4001)))
            C = C_of(mu, nu)
            if abs(C) > 1e-6 and ((Fmin < -1e-12) != (C > 0)):
                bad += 1
    return bad


# ---------------------------------------------------------------------- main
def main():
    I0 = 0.279
    dmu = 0.2616
    print("Barker et al. (2015) criterion, C = 4nu^2 - 4nu + mu^2(1-nu/2)^2,"
          " nu = I mu'/mu;  C<0 well posed\n")
    print(f"self-check of the derivation (sign(min F) vs sign(C), 3540 (mu,nu) pairs):"
          f" {self_check()} mismatches\n")

    print("0. Coulomb limit (rate independent, nu = 0): C = mu^2 > 0 -> ill posed"
          " for every mu > 0 (Schaeffer 1987)\n")

    print("1. Check case: Jop et al. glass beads, mu_s = tan 20.9, mu_2 = tan 32.76,"
          " I0 = 0.279")
    gb = jop(math.tan(20.9 * DEG), math.tan(32.76 * DEG) - math.tan(20.9 * DEG), I0)
    describe("A mu(I) fluid (the case Barker et al. treat)", gb)
    describe("B plane-strain MC, tan(phi)=mu(I), psi=0", mc_plane_strain(gb))
    print()

    cases = [("phi_s = 19.8 deg", 19.8), ("phi_s = 30 deg", 30.0), ("phi_s = 33 deg", 33.0)]
    print(f"2. talus cases: mu_2 - mu_s = {dmu}, I0 = {I0}")
    for name, phi in cases:
        law = jop(math.tan(phi * DEG), dmu, I0)
        print(f" {name}: mu_s = {math.tan(phi*DEG):.4f}, mu_2 = {math.tan(phi*DEG)+dmu:.4f}"
              f" (phi_2 = {math.atan(math.tan(phi*DEG)+dmu)/DEG:.2f} deg)")
        describe("A mu(I) fluid", law)
        describe("B plane-strain MC, tan(phi)=mu(I), psi=0", mc_plane_strain(law))
    print()

    print("3. C(I) at the inertial numbers of the flowing layers (C<0 well posed)")
    Is = [1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0]
    print("   " + "case".ljust(30) + "".join(f"{I:>9.0e}" for I in Is))
    for name, phi in cases:
        law = jop(math.tan(phi * DEG), dmu, I0)
        for tag, lw in (("A", law), ("B", mc_plane_strain(law))):
            print("   " + f"{tag} {name}".ljust(30) + "".join(f"{C_at(lw, I):+9.4f}" for I in Is))
    print()

    print("   max of nu = I mu'/mu (reached at I = I0 sqrt(mu_s/mu_2)) and the mu^2 it"
          " has to beat:")
    for name, phi in cases + [("glass beads", None)]:
        if phi is None:
            ms, m2 = math.tan(20.9 * DEG), math.tan(32.76 * DEG)
        else:
            ms, m2 = math.tan(phi * DEG), math.tan(phi * DEG) + dmu
        law = jop(ms, m2 - ms, I0)
        Ist = I0 * math.sqrt(ms / m2)
        mu, nu = law(Ist)
        print(f"   {name:<18s} I* = {Ist:.4f}: mu = {mu:.4f}, nu_max = {nu:.4f},"
              f" C(I*) = {C_of(mu, nu):+.4f}")
    # largest mu_s that still has a well-posed window (mapping A and B)
    for tag, wrap in (("A", lambda l: l), ("B", mc_plane_strain)):
        lo, hi = 0.05, 1.5
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            _, cmin = crossings(wrap(jop(mid, dmu, I0)), n=800)
            if cmin < 0:
                lo = mid
            else:
                hi = mid
        print(f"   {tag}: with mu_2 - mu_s = {dmu}, I0 = {I0}, a well-posed window exists only for"
              f" mu_s < {lo:.4f} (phi_s < {math.atan(lo)/DEG:.2f} deg)")
    # smallest dmu = mu_2 - mu_s that opens a window for the stiffer materials
    for name, phi in cases[1:]:
        ms = math.tan(phi * DEG)
        lo, hi = 0.0, 5.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            _, cmin = crossings(jop(ms, mid, I0), n=800)
            if cmin < 0:
                hi = mid
            else:
                lo = mid
        print(f"   A: {name}: a well-posed window needs mu_2 - mu_s > {hi:.4f}"
              f" (phi_2 > {math.atan(ms+hi)/DEG:.2f} deg); I0 does not matter (C depends on I/I0 only)")
    print()

    print("3b. Dimensionless growth coefficient G(I) = max(0, -(mu/I) min_theta F) of the")
    print("    rigid-viscoplastic limit: growth rate lambda(k) = G k^2 d sqrt(p/rho)  (0 = well posed)")
    print("   " + "case".ljust(30) + "".join(f"{I:>9.0e}" for I in Is))
    for name, phi in cases:
        law = jop(math.tan(phi * DEG), dmu, I0)
        row = []
        for I in Is:
            mu, nu = law(I)
            a = mu * (1.0 - 0.5 * nu)
            Fmin = min((s * s - a * s + nu * (1.0 - s * s)) / (1.0 - a * s)
                       for s in (-1.0 + 2.0 * k / 4000 for k in range(4001)))
            row.append(max(0.0, -(mu / I) * Fmin))
        print("   " + f"A {name}".ljust(30) + "".join(f"{g:9.3g}" for g in row))
    print()

    print("4. Barker & Gray (2017) partially regularised curve (form as coded in OpenFOAM-muI):")
    print("   mu = sqrt(alpha / ln(A_minus / I))                     for I <= I1N")
    print("   mu = (mu_s I0 + mu_2 I + mu_inf I^2) / (I0 + I)        for I >  I1N")
    print("   A_minus = I1N exp(alpha (I0 + I1N)^2 / (mu_s I0 + mu_2 I1N + mu_inf I1N^2)^2)")
    print("   (low-I branch: nu = mu^2/(2 alpha), so C = nu[(2alpha-4) + (4-2alpha)nu + alpha nu^2/2]"
          " -> well posed as I->0 iff alpha < 2)")
    alpha, mu_inf = 1.9, 0.05
    sets = [("OpenFOAM-muI tutorial (mu_s .342, mu_2 .557, I0 .069)", 0.342, 0.557, 0.069),
            ("glass beads (tan20.9, tan32.76, .279)", math.tan(20.9 * DEG), math.tan(32.76 * DEG), I0)]
    for name, phi in cases:
        sets.append((f"{name} (dmu {dmu}, I0 {I0})", math.tan(phi * DEG), math.tan(phi * DEG) + dmu, I0))
    for name, ms, m2, i0 in sets:
        hb = barker_gray_high(ms, m2, mu_inf, i0)
        roots, cmin = crossings(hb)
        up = [r for r, d in roots if d == "ill->well"]
        dn = [r for r, d in roots if d == "well->ill"]
        if not up:
            print(f"   {name}: high-I branch with mu_inf={mu_inf} is ill posed for all I"
                  f" (min C = {cmin:+.4f}) -> no I1N, recipe not applicable")
            continue
        I1N = up[0]
        A = I1N * math.exp(alpha * (i0 + I1N) ** 2 / (ms * i0 + m2 * I1N + mu_inf * I1N ** 2) ** 2)
        I2N = dn[0] if dn else float("inf")
        # check the low-I branch
        low_ok = all(C_of(math.sqrt(alpha / math.log(A / I)), alpha / math.log(A / I) / (2 * alpha)) < 0
                     for I in (I1N * 10 ** (-k / 10) for k in range(1, 120)))
        print(f"   {name}: I1N = {I1N:.4g}, A_minus = {A:.4g}, upper limit I2N = {I2N:.4g},"
              f" low-I branch well posed below I1N: {low_ok}")


if __name__ == "__main__":
    main()
