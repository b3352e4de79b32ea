#!/usr/bin/env python3
"""Print, for the sliding-block case, the friction state of the floor nodes under
the block after each of the first steps: NORMAL, NODAL_AREA, scaled tangential
penalty, STICK_FORCE (normal force in x-slot, tangential in y), REACTION
(friction force applied, in rotated frame), FRICTION_STATE (0 sliding, 1 stick).
Usage: friction_debug.py CASEDIR [nsteps]"""
import os
import sys

os.environ.setdefault("OMP_NUM_THREADS", "1")
import KratosMultiphysics as KM
import KratosMultiphysics.MPMApplication as KMPM
from KratosMultiphysics.MPMApplication.mpm_analysis import MpmAnalysis

d = sys.argv[1]
nsteps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
os.chdir(d)
KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)
params = KM.Parameters(open("ProjectParameters.json").read())
model = KM.Model()
sim = MpmAnalysis(model, params)
sim.Initialize()
grid = model["Background_Grid"]
mass_total = sum(e.CalculateOnIntegrationPoints(KMPM.MP_MASS, grid.ProcessInfo)[0]
                 for e in model["MPM_Material"].Elements)
print(f"block mass per unit thickness = {mass_total:.4f} kg, weight = {mass_total*9.81:.3f} N, "
      f"mu*W (0.36) = {0.36*mass_total*9.81:.3f} N")
for step in range(nsteps):
    sim.time = sim._AdvanceTime()
    sim.InitializeSolutionStep()
    sim._GetSolver().SolveSolutionStep()
    sim.FinalizeSolutionStep()
    nit = grid.ProcessInfo[KM.NL_ITERATION_NUMBER]
    print(f"--- step {step+1} t={sim.time:.4f} Newton iterations {nit}")
    sumN = 0.0
    sumT = 0.0
    for n in grid.Nodes:
        if n.Y > 1e-9 or not n.Is(KM.SLIP):
            continue
        m = n.GetSolutionStepValue(KM.NODAL_MASS)
        if m <= 0:
            continue
        sf = n.GetSolutionStepValue(KMPM.STICK_FORCE)
        sf1 = n.GetSolutionStepValue(KMPM.STICK_FORCE, 1)
        r = n.GetSolutionStepValue(KM.REACTION)
        st = n.GetSolutionStepValue(KMPM.FRICTION_STATE)
        nrm = n.GetSolutionStepValue(KM.NORMAL)
        print(f"  x={n.X:.3f} m={m:.4f} N=({nrm[0]:+.2f},{nrm[1]:+.2f}) area={n.GetValue(KM.NODAL_AREA):.4g} "
              f"kt={n.GetValue(KMPM.TANGENTIAL_PENALTY_COEFFICIENT):.3g} stick=({sf[0]:+.4g},{sf[1]:+.4g}) "
              f"stick_prev=({sf1[0]:+.4g}) reaction=({r[0]:+.4g},{r[1]:+.4g}) state={st} "
              f"v=({n.GetSolutionStepValue(KM.VELOCITY_X):+.4f})")
        sumN += sf1[0]
        sumT += r[1]
    print(f"  sum normal force (prev step) = {sumN:.4f} N, sum applied tangential reaction = {sumT:.4f} N")
