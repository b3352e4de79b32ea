#!/bin/bash
# Kratos runs of the Lube et al. 2005 columns (L0 = 0.1 m, phi 30 deg, psi 0, c 0,
# rho 2650, E 0.84 MPa, nu 0.3: the material of make_lube_series.py), no-slip floor,
# slip wall, quads with 2x2 points; in the scratch directory with the venv (README).
# Measured with measure_lube.py (the definitions of IO::DepositProfile) and jdist.py.
export OMP_NUM_THREADS=1
run() { name=$1; shift; python3 make_case.py runs/$name --floor fixed --wall slip --phi 30 "$@" &&
        (cd runs/$name && ../../venv/bin/python ../../run_case.py . --dump 0.1 > run.out 2>&1; tail -1 run.out); }
run k_a1p5_q10_fixed_dt1e-3 --h 0.01  --dt 1e-3 --lx 0.5 --ly 0.2  --body_w 0.1 --body_h 0.15 --tend 1.0
run k_a1p5_q10_fixed_dt5e-4 --h 0.01  --dt 5e-4 --lx 0.5 --ly 0.2  --body_w 0.1 --body_h 0.15 --tend 1.0
run k_a1p5_q5_fixed_dt5e-4  --h 0.005 --dt 5e-4 --lx 0.5 --ly 0.2  --body_w 0.1 --body_h 0.15 --tend 0.8
run k_a3_q10_fixed_dt1e-3   --h 0.01  --dt 1e-3 --lx 0.8 --ly 0.35 --body_w 0.1 --body_h 0.3  --tend 1.1
for c in k_a1p5_q10_fixed_dt1e-3 k_a1p5_q10_fixed_dt5e-4 k_a1p5_q5_fixed_dt5e-4; do python3 measure_lube.py runs/$c --a 1.5; done
python3 measure_lube.py runs/k_a3_q10_fixed_dt1e-3 --a 3
python3 jdist.py runs/k_*
