#!/usr/bin/env python3
"""Tables of the Talus benchmark (contrib/benchmark/run_benchmarks.sh).

Reads the run folders in a result directory (log with the TimerOutput table
and the per-rank RANKTIME lines of /usr/bin/time, time_series.csv, status,
load_before) and the deal.II floor logs, and writes results.md (Markdown)
and results.csv there; results.md is also printed.

    usage: python3 contrib/benchmark/parse_results.py <result directory>

Definitions (P particles, R ranks, S steps, n Newton iterations in total,
T_x wall time of TimerOutput section x on rank 0):
  step time         (T_P2G / calls_P2G) + (T_Newton + T_commit) / S
                    (the P2G section has one extra call: the initial
                    acceleration); the untimed rest of the loop (energy
                    diagnostics, CSV) is not included
  us/particle/it    T_Newton * R / (P n) * 1e6: core-microseconds per
                    particle and Newton iteration (assembly + linear solve;
                    the Newton section holds n + S assemblies and n solves)
  assembly          P * calls_assembly / (T_assembly R)   [particles/s/core]
  P2G               P * calls_P2G / (T_P2G R)             [particles/s/core]
  G2P+sort          P * S / (T_commit R)                  [particles/s/core]
  lin. share        T_linear / (S * step time)
  AMG setup         TimerOutput section "AMG setup" inside "linear solver"
                    (Talus >= 8c62bab; builds = number of AMG setups)
  CG its/solve      linear iterations / Newton iterations (time_series.csv)
  init              TimerOutput total - time loop wall ("Done:" line): grid,
                    particle generation, setup, initial acceleration
  CPU use           sum over ranks of (user + sys) / (R * wall): well below
                    1 means the ranks waited for a core (shared machine)
"""
import csv
import glob
import os
import re
import sys

TARGET_US_2D = 8.0
TARGET_US_3D = 20.0
TARGET_AMG_GROWTH = 1.5
TARGET_SPEEDUP = 1.7


def read(path, default=""):
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return default


def parse_timer(log):
    """{section: (calls, wall seconds)} and the total wall time."""
    sections, total = {}, None
    for line in log.splitlines():
        m = re.match(r"\|\s*Total wallclock time elapsed since start\s*\|\s*"
                     r"([0-9.eE+-]+)s", line)
        if m:
            total = float(m.group(1))
            continue
        m = re.match(r"\|\s*([^|]+?)\s*\|\s*(\d+)\s*\|\s*([0-9.eE+-]+)s\s*\|",
                     line)
        if m:
            sections[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return sections, total


def parse_ranktime(log):
    ranks = []
    for m in re.finditer(r"RANKTIME wall=([0-9.]+) user=([0-9.]+) "
                         r"sys=([0-9.]+) maxrss_kb=(\d+)", log):
        ranks.append(tuple(float(x) for x in m.groups()))
    return ranks


def parse_run(d):
    name = os.path.basename(d)
    m = re.match(r"(\d)d_N(\d+)_np(\d+)$", name)
    r = {"name": name, "dim": int(m.group(1)), "N": int(m.group(2)),
         "ranks": int(m.group(3)),
         "status": read(os.path.join(d, "status"), "not run").strip(),
         "load": read(os.path.join(d, "load_before")).strip()}
    log = read(os.path.join(d, "log"))
    m = re.search(r"background grid: (\d+) cells, (\d+) DoFs", log)
    if m:
        r["cells"], r["dofs"] = int(m.group(1)), int(m.group(2))
    m = re.search(r"material points: (\d+)", log)
    if m:
        r["particles"] = int(m.group(1))
    rt = parse_ranktime(log)
    if rt:
        r["maxrss_mb"] = max(x[3] for x in rt) / 1024.
        r["cpu_use"] = sum(x[1] + x[2] for x in rt) / \
            (len(rt) * max(x[0] for x in rt))
    if r["status"] != "ok":
        return r
    sec, total = parse_timer(log)
    r["total_wall"] = total
    m = re.search(r"Done: .* wall time ([0-9.]+) (s|min|h)", log)
    if m:
        loop = float(m.group(1)) * {"s": 1, "min": 60, "h": 3600}[m.group(2)]
        r["loop_wall"] = loop
        r["init_s"] = total - loop
    newton = linear = steps = 0
    with open(os.path.join(d, "time_series.csv")) as f:
        for row in csv.DictReader(f):
            if int(row["step"]) == 0:
                continue
            steps += 1
            newton += int(row["newton_iterations"])
            linear += int(row["linear_iterations"])
    P, R, S = r["particles"], r["ranks"], steps
    c_p2g, t_p2g = sec["prepare (P2G)"]
    c_asm, t_asm = sec["assembly"]
    _, t_lin = sec["linear solver"]
    # "AMG setup" (inside "linear solver") exists from 8c62bab on.
    c_amg, t_amg = sec.get("AMG setup", (None, None))
    _, t_newton = sec["solve (Newton)"]
    _, t_commit = sec["commit (G2P, move, sort)"]
    _, t_sort = sec.get("sort particles", (0, 0.))
    step = t_p2g / c_p2g + (t_newton + t_commit) / S
    r.update({
        "steps": S, "newton": newton, "linear": linear,
        "newton_per_step": newton / S,
        "cg_per_solve": linear / newton if newton else 0.,
        "step_s": step,
        "t_p2g_step": t_p2g / c_p2g, "t_asm_step": t_asm / S,
        "t_lin_step": t_lin / S, "t_commit_step": t_commit / S,
        "t_amg_step": None if t_amg is None else t_amg / S,
        "amg_builds": c_amg,
        "t_sort_step": t_sort / S,
        "t_newton_other_step": (t_newton - t_asm - t_lin) / S,
        "us_per_particle_it": t_newton * R / (P * newton) * 1e6,
        "us_asm_per_particle_it": t_asm * R / (P * newton) * 1e6,
        "us_lin_per_particle_it": t_lin * R / (P * newton) * 1e6,
        "us_amg_per_particle_it": None if t_amg is None else
        t_amg * R / (P * newton) * 1e6,
        "asm_rate": P * c_asm / (t_asm * R),
        "p2g_rate": P * c_p2g / (t_p2g * R),
        "g2p_rate": P * S / (t_commit * R),
        "lin_share": t_lin / (S * step),
        "asm_share": t_asm / (S * step),
    })
    return r


def parse_floor(path):
    name = os.path.basename(path)
    m = re.match(r"floor_(\d)d_N(\d+)_np(\d+)$", name)
    r = {"dim": int(m.group(1)), "N": int(m.group(2)),
         "ranks": int(m.group(3)),
         "status": read(os.path.join(path, "status"), "not run").strip()}
    log = read(os.path.join(path, "log"))
    m = re.search(r"FLOOR (.*)", log)
    if r["status"] != "ok" or not m:
        return r
    for kv in m.group(1).split():
        k, v = kv.split("=")
        r[k] = float(v) if k not in ("dim", "N", "ranks") else int(v)
    q, R = r["qpoints"], r["ranks"]
    r["us_rebuild"] = (r["assembly_s"] + r["amg_setup_s"] + r["cg_s"]) \
        * R / q * 1e6
    r["us_reuse"] = (r["assembly_s"] + r["cg_s"]) * R / q * 1e6
    r["us_asm"] = r["assembly_s"] * R / q * 1e6
    r["us_amg"] = r["amg_setup_s"] * R / q * 1e6
    r["us_cg"] = r["cg_s"] * R / q * 1e6
    return r


def fmt(x, digits=3):
    if x is None:
        return "–"
    if isinstance(x, int):
        return f"{x:,}"
    if abs(x) < 1e-9:
        return "0"
    if abs(x) >= 1e4:
        return f"{x:.3g}" if abs(x) < 1e5 else f"{x:.2e}"
    return f"{x:.{digits}g}"


def rate(x):
    return "–" if x is None else f"{x / 1e3:,.0f}k"


def main(out):
    runs = sorted((parse_run(d) for d in glob.glob(os.path.join(out, "*d_N*_np*"))
                   if re.match(r"\dd_", os.path.basename(d))),
                  key=lambda r: (r["dim"], r["N"], r["ranks"]))
    floors = sorted((parse_floor(d) for d in glob.glob(os.path.join(out, "floor_*"))),
                    key=lambda r: (r["dim"], r["N"], r["ranks"]))
    floor_of = {(f["dim"], f["N"], f["ranks"]): f for f in floors}
    L = []
    machine = read(os.path.join(out, "machine.txt")).strip().splitlines()
    L.append("Machine and run: " + "; ".join(machine) + "\n")

    # Table 1: runs.
    L.append("### Talus runs\n")
    L.append("| dim | ranks | particles | DoFs | steps | Newton its/step "
             "| CG its/solve | step wall [s] | µs/particle/Newton it "
             "(asm + lin [of which AMG setup]) | assembly [p/s/core] | P2G [p/s/core] "
             "| G2P+sort [p/s/core] | linear solver share | peak RSS/rank "
             "[MB] | CPU use | init [s] | load before |")
    L.append("|" + "---|" * 17)
    for r in runs:
        if r["status"] != "ok":
            L.append(f"| {r['dim']}D | {r['ranks']} | "
                     f"{fmt(r.get('particles', (2 ** r['dim']) * r['N'] ** r['dim']))} "
                     f"| {fmt(r.get('dofs'))} | – | – | – | – | – | – | – | – | – "
                     f"| {fmt(r.get('maxrss_mb'))} | – | – | {r['load'] or '–'} |"
                     f" *{r['status']}*")
            continue
        L.append(
            f"| {r['dim']}D | {r['ranks']} | {fmt(r['particles'])} "
            f"| {fmt(r['dofs'])} | {r['steps']} | {r['newton_per_step']:.2g} "
            f"| {r['cg_per_solve']:.1f} | {fmt(r['step_s'])} "
            f"| {r['us_per_particle_it']:.1f} ({r['us_asm_per_particle_it']:.1f} + "
            f"{r['us_lin_per_particle_it']:.1f}"
            + ("" if r["us_amg_per_particle_it"] is None else
               f" [AMG {r['us_amg_per_particle_it']:.1f}]")
            + f") | {rate(r['asm_rate'])} "
            f"| {rate(r['p2g_rate'])} | {rate(r['g2p_rate'])} "
            f"| {100 * r['lin_share']:.0f}% | {r['maxrss_mb']:.0f} "
            f"| {100 * r['cpu_use']:.0f}% | {fmt(r.get('init_s'))} "
            f"| {r['load']} |")
    L.append("")

    # Table 2: where a step goes.
    L.append("### Time per step by phase (rank 0, seconds)\n")
    L.append("| dim | ranks | particles | P2G | assembly | linear solver "
             "| AMG setup (builds in run, s/step) | Newton other | G2P+move | sort "
             "| step |")
    L.append("|" + "---|" * 11)
    for r in runs:
        if r["status"] != "ok":
            continue
        L.append(f"| {r['dim']}D | {r['ranks']} | {fmt(r['particles'])} "
                 f"| {fmt(r['t_p2g_step'])} | {fmt(r['t_asm_step'])} "
                 f"| {fmt(r['t_lin_step'])} "
                 + ("| – " if r["t_amg_step"] is None else
                    f"| {r['amg_builds']}, {fmt(r['t_amg_step'])} ")
                 + f"| {fmt(r['t_newton_other_step'])} "
                 f"| {fmt(r['t_commit_step'] - r['t_sort_step'])} "
                 f"| {fmt(r['t_sort_step'])} | {fmt(r['step_s'])} |")
    L.append("")

    # Table 3: floor.
    if floors:
        L.append("### deal.II floor (same block without margin, Q1, 2^dim "
                 "Gauss points per cell = particles, linear elasticity + "
                 "lumped mass, same AMG/CG; best of 2)\n")
        L.append("| dim | ranks | quadrature points | DoFs | assembly [s] "
                 "| AMG setup [s] | CG [s] | CG its | µs/point/it, AMG rebuilt "
                 "(asm + AMG + CG) | µs/point/it, AMG reused | Talus / floor "
                 "(rebuilt) |")
        L.append("|" + "---|" * 11)
        for f in floors:
            if f["status"] != "ok" or "qpoints" not in f:
                L.append(f"| {f['dim']}D | {f['ranks']} | – | – | – | – | – "
                         f"| – | – | – | – | *{f['status']}*")
                continue
            t = next((r for r in runs if (r["dim"], r["N"], r["ranks"]) ==
                      (f["dim"], f["N"], f["ranks"]) and r["status"] == "ok"),
                     None)
            ratio = (f"{t['us_per_particle_it'] / f['us_rebuild']:.1f}x"
                     if t else "–")
            L.append(f"| {f['dim']}D | {f['ranks']} | {fmt(int(f['qpoints']))} "
                     f"| {fmt(int(f['dofs']))} | {fmt(f['assembly_s'])} "
                     f"| {fmt(f['amg_setup_s'])} | {fmt(f['cg_s'])} "
                     f"| {int(f['cg_its'])} | {f['us_rebuild']:.1f} "
                     f"({f['us_asm']:.1f} + {f['us_amg']:.1f} + {f['us_cg']:.1f}) "
                     f"| {f['us_reuse']:.1f} | {ratio} |")
        L.append("")

    # Table 4: targets.
    L.append("### Targets\n")
    L.append("| target | measured | met? | where it is missed |")
    L.append("|---|---|---|---|")
    ok = [r for r in runs if r["status"] == "ok"]

    def largest(dim, ranks):
        c = [r for r in ok if r["dim"] == dim and r["ranks"] == ranks]
        return max(c, key=lambda r: r["particles"]) if c else None

    def missing(dim, ranks, what):
        sizes = sorted(r["N"] for r in runs if r["dim"] == dim)
        if not sizes:
            return f"| {what} | not run | – | |"
        return f"| {what} | not measured (runs missing) | – | |"

    for dim, target in ((2, TARGET_US_2D), (3, TARGET_US_3D)):
        what = (f"{dim}D: Newton iteration <= {target:g} µs per particle, "
                "1 core (largest size run)")
        r = largest(dim, 1)
        if r is None:
            L.append(missing(dim, 1, what))
            continue
        met = r["us_per_particle_it"] <= target
        f = floor_of.get((dim, r["N"], 1))
        why = ""
        if not met:
            lin = "linear solver (AMG setup + CG)"
            if r["us_amg_per_particle_it"] is not None:
                lin = (f"linear solver (AMG setup "
                       f"{r['us_amg_per_particle_it']:.1f} µs + CG)")
            parts = sorted(((lin, r["us_lin_per_particle_it"]),
                            ("assembly", r["us_asm_per_particle_it"])),
                           key=lambda p: -p[1])
            why = (f"{parts[0][0]} {parts[0][1]:.1f} µs "
                   f"({100 * parts[0][1] / r['us_per_particle_it']:.0f}%), "
                   f"{parts[1][0]} {parts[1][1]:.1f} µs; "
                   f"{r['cg_per_solve']:.0f} CG its/solve")
            if f and "us_rebuild" in f:
                why += (f"; deal.II floor here: {f['us_rebuild']:.1f} µs "
                        f"(asm {f['us_asm']:.1f} + AMG {f['us_amg']:.1f} + "
                        f"CG {f['us_cg']:.1f})")
        L.append(f"| {what} | {r['us_per_particle_it']:.1f} µs at "
                 f"{fmt(r['particles'])} particles | "
                 f"{'yes' if met else '**no**'} | {why} |")

    for dim in (2, 3):
        what = (f"{dim}D: AMG (CG) iterations grow < {TARGET_AMG_GROWTH:g}x "
                "when the problem grows ~8x (two largest sizes, 1 rank)")
        c = sorted((r for r in ok if r["dim"] == dim and r["ranks"] == 1),
                   key=lambda r: r["particles"])
        if len(c) < 2:
            L.append(missing(dim, 1, what))
            continue
        a, b = c[-2], c[-1]
        g = b["cg_per_solve"] / a["cg_per_solve"]
        met = g < TARGET_AMG_GROWTH
        why = "" if met else (
            f"CG its/solve {a['cg_per_solve']:.1f} -> {b['cg_per_solve']:.1f}")
        L.append(f"| {what} | {g:.2f}x ({a['cg_per_solve']:.1f} -> "
                 f"{b['cg_per_solve']:.1f} its/solve, {fmt(a['particles'])} -> "
                 f"{fmt(b['particles'])} particles, "
                 f"{b['particles'] / a['particles']:.1f}x) | "
                 f"{'yes' if met else '**no**'} | {why} |")

    what = (f"3D: 2 ranks >= {TARGET_SPEEDUP:g}x faster than 1 on the largest "
            "3D case (step wall time)")
    r1, r2 = largest(3, 1), largest(3, 2)
    if r1 is None or r2 is None or r1["N"] != r2["N"]:
        L.append(missing(3, 2, what))
    else:
        s = r1["step_s"] / r2["step_s"]
        met = s >= TARGET_SPEEDUP
        why = ""
        if not met:
            ph = [("P2G", "t_p2g_step"), ("assembly", "t_asm_step"),
                  ("linear solver", "t_lin_step"),
                  ("G2P+sort", "t_commit_step")]
            why = ", ".join(f"{n} {r1[k] / r2[k]:.2f}x" for n, k in ph) + \
                ""
            f1, f2 = floor_of.get((3, r1["N"], 1)), floor_of.get((3, r1["N"], 2))
            if f1 and f2 and "us_rebuild" in f1 and "us_rebuild" in f2:
                tf1 = f1["assembly_s"] + f1["amg_setup_s"] + f1["cg_s"]
                tf2 = f2["assembly_s"] + f2["amg_setup_s"] + f2["cg_s"]
                why += f"; deal.II floor speedup {tf1 / tf2:.2f}x"
        L.append(f"| {what} | {s:.2f}x ({fmt(r1['step_s'])} s -> "
                 f"{fmt(r2['step_s'])} s per step, {fmt(r1['particles'])} "
                 f"particles; CPU use {100 * r1['cpu_use']:.0f}% / "
                 f"{100 * r2['cpu_use']:.0f}%) | {'yes' if met else '**no**'} "
                 f"| {why} |")
    L.append("")

    # Table 5: particle generation.
    gens = []
    for d in glob.glob(os.path.join(out, "gen_2d_N*_k*")):
        m = re.match(r"gen_2d_N(\d+)_k(\d+)$", os.path.basename(d))
        g = {"N": int(m.group(1)), "k": int(m.group(2)),
             "status": read(os.path.join(d, "status"), "not run").strip()}
        prm = read(os.path.join(d, "input.prm"))
        sub = re.search(r"set subdivisions\s*=\s*([\d, ]+)", prm)
        lev = re.search(r"set first level\s*=\s*(\d+)", prm)
        if sub and lev:
            g["coarse"] = 1
            for x in sub.group(1).split(","):
                g["coarse"] *= int(x)
            g["level"] = int(lev.group(1))
        log = read(os.path.join(d, "log"))
        mp = re.search(r"material points: (\d+)", log)
        _, total = parse_timer(log)
        ml = re.search(r"Done: .* wall time ([0-9.]+) (s|min|h)", log)
        if mp and total is not None and ml:
            g["particles"] = int(mp.group(1))
            g["init"] = total - float(ml.group(1)) * \
                {"s": 1, "min": 60, "h": 3600}[ml.group(2)]
        gens.append(g)
    if gens:
        gens.sort(key=lambda g: (g["N"], g["k"]))
        L.append("### Particle generation (2D, 1 rank; init = TimerOutput "
                 "total - time loop)\n")
        L.append("| particles | coarse cells | refinements | init [s] |")
        L.append("|---|---|---|---|")
        for g in gens:
            L.append(f"| {fmt(g.get('particles', 4 * g['N'] ** 2))} "
                     f"| {fmt(g.get('coarse'))} | {g.get('level', '–')} "
                     f"| {fmt(g.get('init')) if 'init' in g else g['status']} |")
        L.append("")

    skipped = [r["name"] for r in runs if r["status"] != "ok"]
    if skipped:
        L.append("Not completed: " + ", ".join(
            f"{r['name']} ({r['status']})" for r in runs
            if r["status"] != "ok") + "\n")

    text = "\n".join(L)
    with open(os.path.join(out, "results.md"), "w") as f:
        f.write(text + "\n")
    keys = ["dim", "N", "ranks", "status", "particles", "dofs", "steps",
            "newton", "linear", "newton_per_step", "cg_per_solve", "step_s",
            "t_p2g_step", "t_asm_step", "t_lin_step", "t_newton_other_step",
            "t_commit_step", "t_sort_step", "t_amg_step", "amg_builds",
            "us_per_particle_it", "us_amg_per_particle_it",
            "us_asm_per_particle_it", "us_lin_per_particle_it", "asm_rate",
            "p2g_rate", "g2p_rate", "lin_share", "maxrss_mb", "cpu_use",
            "total_wall", "loop_wall", "init_s", "load"]
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys, extrasaction="ignore")
        w.writeheader()
        for r in runs:
            w.writerow(r)
    print(text)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
