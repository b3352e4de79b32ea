#!/usr/bin/env python3
"""Compare two Talus runs: their time-series CSVs and their final material
points (written by TALUS_DEBUG_DUMP_POINTS: id, position, properties).

usage: compare_runs.py REF_DIR RUN_DIR TOLERANCE LABEL KEY_COLUMNS [CSV_FILES
                      [SKIPPED_COLUMNS]]

Each directory holds the CSV files (CSV_FILES, comma-separated: default
time_series.csv; a coupled run: coupling.csv,structure.csv) and points.txt. Every CSV column and
every point quantity is compared relative to the largest magnitude of that
column in the reference (so that quantities near zero are not divided by
themselves); the largest such difference must be <= TOLERANCE. The rows
(step or time, the first column) must be the same. The points are matched by the values of
KEY_COLUMNS (comma-separated quantity numbers after the id: the initial
position X, 18,19 in 2D), since their ids depend on the number of ranks
that generated them. SKIPPED_COLUMNS (comma-separated CSV column names)
are not compared: iteration counts, residuals and columns of round-off
size, which a run on another number of ranks changes. Prints the measured
differences; exit code 0 when they agree.
"""
import csv
import sys


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def read_points(path, keys):
    points = {}
    with open(path) as f:
        for line in f:
            values = [float(x) for x in line.split()[1:]]
            points[tuple(round(values[k], 9) for k in keys)] = values
    return points


def relative_difference(a_rows, b_rows, skipped=()):
    """Largest |a - b| / max|a| over the columns (but the skipped column
    numbers), and its column."""
    worst, where = 0.0, 0
    for c in range(len(a_rows[0])):
        if c in skipped:
            continue
        scale = max(abs(r[c]) for r in a_rows)
        diff = max(abs(a[c] - b[c]) for a, b in zip(a_rows, b_rows))
        rel = diff / scale if scale > 0 else diff
        if rel > worst:
            worst, where = rel, c
    return worst, where


def main():
    ref, run, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
    label = sys.argv[4]
    keys = [int(k) for k in sys.argv[5].split(",")]
    csv_files = (sys.argv[6] if len(sys.argv) > 6 else
                 "time_series.csv").split(",")
    skipped_names = sys.argv[7].split(",") if len(sys.argv) > 7 else []
    ok = True

    for name in csv_files:
        header, a = read_csv(ref + "/" + name)
        header_b, b = read_csv(run + "/" + name)
        if header != header_b or len(a) != len(b):
            print(f"{label}: {name} differs in shape: {len(a)} rows "
                  f"(reference) and {len(b)} rows")
            return 1
        if any(x[0] != y[0] for x, y in zip(a, b)):
            print(f"{label}: the steps (times) of {name} differ")
            return 1
        skipped = [c for c, n in enumerate(header) if n in skipped_names]
        csv_diff, column = relative_difference(a, b, skipped)
        print(f"{label}: {name}: {len(a)} CSV rows, largest relative "
              f"difference {csv_diff:.3e} (column {header[column]}"
              + (f"; {len(skipped)} columns not compared" if skipped
                 else "") + ")")
        ok = ok and csv_diff <= tol

    pa = read_points(ref + "/points.txt", keys)
    pb = read_points(run + "/points.txt", keys)
    if sorted(pa) != sorted(pb):
        print(f"{label}: the material points differ "
              f"({len(pa)} and {len(pb)} points)")
        return 1
    ids = sorted(pa)
    point_diff, column = relative_difference([pa[i] for i in ids],
                                             [pb[i] for i in ids])
    print(f"{label}: {len(ids)} material points, largest relative difference "
          f"{point_diff:.3e} (quantity {column}: position, then the "
          f"properties)")
    ok = ok and point_diff <= tol
    print(f"{label}: {'agree' if ok else 'DIFFER'} within {tol:g}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
