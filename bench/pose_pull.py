#!/usr/bin/python3
"""Where each filter's poses lie against a simulated dataset's truth, along the robot's heading.

For each row folder (holding dataset/truth.json from `floorgrid simulate` and align/scans.csv
from `floorgrid align`), over the scans where both filters converged: the plan filter's and the
gridmap filter's position error (world metres) split into along the robot's true heading
(positive: ahead of the robot) and across it, and the pull, the plan's along-heading error less
the gridmap's (per scan, then the median); of the filters' mean poses, and of their scan-matched
poses (the ones pairs are made from) where both matches were accepted. A 180-degree laser sees no
wall behind it, so whatever makes the walls ahead look farther in one map than the laser
measures pulls that map's poses forward.

Usage: bench/pose_pull.py ROW_DIR...   (e.g. the plan-* folders of bench/real_matrix.sh)
"""
import csv
import json
import math
import sys

import numpy as np


def pull(row):
    truth = json.load(open(f"{row}/dataset/truth.json"))
    plan_per_world = truth["plan"]["plan_per_world"]
    poses = np.array(truth["trajectory"]["poses"])  # time, world x y theta, grid x y theta
    times = poses[:, 0]
    out = {"plan_along": [], "plan_across": [], "grid_along": [], "pull": [], "matched_pull": []}
    for r in csv.DictReader(open(f"{row}/align/scans.csv")):
        if r["plan_converged"] != "1" or r["grid_converged"] != "1":
            continue
        i = int(np.argmin(np.abs(times - float(r["time"]))))
        if abs(times[i] - float(r["time"])) > 1e-3:
            continue
        heading = poses[i, 3]
        ahead = np.array([math.cos(heading), math.sin(heading)])
        plan_error = (np.array([float(r["plan_x"]), float(r["plan_y"])]) / plan_per_world
                      - poses[i, 1:3])
        grid_heading = poses[i, 6]
        grid_ahead = np.array([math.cos(grid_heading), math.sin(grid_heading)])
        grid_error = np.array([float(r["grid_x"]), float(r["grid_y"])]) - poses[i, 4:6]
        out["plan_along"].append(plan_error @ ahead)
        out["plan_across"].append(plan_error @ np.array([-ahead[1], ahead[0]]))
        out["grid_along"].append(grid_error @ grid_ahead)
        out["pull"].append(out["plan_along"][-1] - out["grid_along"][-1])
        if r.get("plan_matched_x") and r.get("grid_matched_x"):
            plan_matched = (np.array([float(r["plan_matched_x"]), float(r["plan_matched_y"])])
                            / plan_per_world - poses[i, 1:3])
            grid_matched = (np.array([float(r["grid_matched_x"]), float(r["grid_matched_y"])])
                            - poses[i, 4:6])
            out["matched_pull"].append(plan_matched @ ahead - grid_matched @ grid_ahead)
    medians = {k: float(np.median(v)) if v else float("nan") for k, v in out.items()}
    return medians, len(out["pull"]), len(out["matched_pull"])


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print(f"{'row':<24} {'scans':>6} {'plan ahead':>10} {'across':>8} {'grid ahead':>10} "
          f"{'pull':>7} {'matched':>8} {'pull':>7}   (medians, world metres)")
    pulls, matched = [], []
    for row in sys.argv[1:]:
        try:
            m, n, n_matched = pull(row)
        except (OSError, KeyError, ValueError) as e:
            print(f"{row}: skipped ({e})")
            continue
        pulls.append(m["pull"])
        if n_matched:
            matched.append(m["matched_pull"])
        print(f"{row.rstrip('/').split('/')[-1]:<24} {n:>6} {m['plan_along']:>10.3f} "
              f"{m['plan_across']:>8.3f} {m['grid_along']:>10.3f} {m['pull']:>7.3f} "
              f"{n_matched:>8} {m['matched_pull']:>7.3f}")
    for name, values in (("pull of the mean poses", pulls), ("pull of the matched poses", matched)):
        if values:
            print(f"median {name} over {len(values)} rows: {np.median(values):.3f} m "
                  f"({min(values):.3f} to {max(values):.3f})")


if __name__ == "__main__":
    main()
