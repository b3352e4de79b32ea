#!/usr/bin/env python3
"""Run a case written by make_case.py with Kratos MPMAnalysis (1 thread).

Writes in the case directory:
  mp_t<time>.csv  x, y, volume, mass of every material point every dump interval
  run_log.csv     step, time, Newton iterations, converged flag, wall time
  run_summary.json
Usage: run_case.py CASEDIR [--dump 0.1] [--max_wall 1500]
"""
import argparse
import csv
import json
import os
import sys
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import KratosMultiphysics as KM
import KratosMultiphysics.MPMApplication as KMPM
from KratosMultiphysics.MPMApplication.mpm_analysis import MpmAnalysis


class Run(MpmAnalysis):
    def __init__(self, model, params, dump, max_wall):
        super().__init__(model, params)
        self.dump = dump
        self.next_dump = 0.0
        self.max_wall = max_wall
        self.t0 = time.time()
        self.log = []
        self.n_fail = 0

    def write_mps(self, t):
        mp = self.model["MPM_Material"]
        pi = mp.ProcessInfo
        rows = []
        for e in mp.Elements:
            x = e.CalculateOnIntegrationPoints(KMPM.MP_COORD, pi)[0]
            v = e.CalculateOnIntegrationPoints(KMPM.MP_VOLUME, pi)[0]
            m = e.CalculateOnIntegrationPoints(KMPM.MP_MASS, pi)[0]
            vel = e.CalculateOnIntegrationPoints(KMPM.MP_VELOCITY, pi)[0]
            rows.append((x[0], x[1], v, m, vel[0], vel[1]))
        with open(f"mp_t{t:.3f}.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["x", "y", "volume", "mass", "vx", "vy"])
            w.writerows(rows)

    def RunSolutionLoop(self):
        self.write_mps(0.0)
        self.next_dump = self.dump
        while self.KeepAdvancingSolutionLoop():
            self.time = self._AdvanceTime()
            self.InitializeSolutionStep()
            converged = self.SolveSolutionStep()
            self.FinalizeSolutionStep()
            self.OutputSolutionStep()
            pi = self._GetSolver().GetComputingModelPart().ProcessInfo
            nit = pi[KM.NL_ITERATION_NUMBER]
            if not converged:
                self.n_fail += 1
            self.log.append((pi[KM.STEP], self.time, nit, int(bool(converged)),
                             time.time() - self.t0))
            if self.time >= self.next_dump - 1e-9:
                self.write_mps(self.time)
                self.next_dump += self.dump
            if time.time() - self.t0 > self.max_wall:
                print(f"STOP: wall time limit at t = {self.time}", flush=True)
                self.stopped = self.time
                break
            if len(self.log) % 100 == 0:
                print(f"t={self.time:.4f} steps={len(self.log)} nit={nit} "
                      f"fails={self.n_fail} wall={time.time()-self.t0:.0f}s", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("casedir")
    ap.add_argument("--dump", type=float, default=0.1)
    ap.add_argument("--max_wall", type=float, default=1500.0)
    a = ap.parse_args()
    os.chdir(a.casedir)
    KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)
    with open("ProjectParameters.json") as f:
        params = KM.Parameters(f.read())
    model = KM.Model()
    sim = Run(model, params, a.dump, a.max_wall)
    sim.stopped = None
    sim.crashed = None
    sim.time = 0.0
    try:
        sim.Run()
    except RuntimeError as e:
        msg = str(e).strip().splitlines()
        sim.crashed = {"time": sim.time, "error": next((l for l in msg if "Error" in l and "parallel" not in l), msg[0] if msg else "")[:200]}
        print(f"CRASH at t = {sim.time}: {sim.crashed['error']}", flush=True)
    wall = time.time() - sim.t0
    with open("run_log.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["step", "time", "newton_iterations", "converged", "wall_s"])
        w.writerows(sim.log)
    its = [r[2] for r in sim.log]
    summ = {"steps": len(sim.log), "not_converged_steps": sim.n_fail,
            "mean_newton": sum(its) / max(1, len(its)), "max_newton": max(its) if its else 0,
            "wall_s": wall, "end_time": sim.time, "stopped_early_at": sim.stopped, "crashed": sim.crashed,
            "kratos_version": KM.KratosGlobals.Kernel.Version() if hasattr(KM.KratosGlobals, "Kernel") else "",
            "omp_threads": os.environ.get("OMP_NUM_THREADS")}
    with open("run_summary.json", "w") as f:
        json.dump(summ, f, indent=2)
    print(json.dumps(summ), flush=True)


if __name__ == "__main__":
    main()
