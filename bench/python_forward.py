#!/usr/bin/python3
"""Times floorgrid.Model.forward from Python on a million points against the C++ benchmark of
the same call (build/bench/api_bench, BM_ModelForwardMillionPoints) on the same model file and
lattice of points. The module must be built (build/python) or installed (make python).

    /usr/bin/python3 bench/python_forward.py [--build build] [--model FILE] [--repeat 5]
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def lattice(model_file: Path, unit: float, side: int = 1000) -> np.ndarray:
    """bench/api_bench.cpp's lattice: the support plan points' box grown by 1 m, x fastest."""
    plan = np.array(json.loads(model_file.read_text())["support"]["plan"], dtype=float)
    plan = plan.reshape(-1, 2) / unit
    low, high = plan.min(axis=0) - 1.0, plan.max(axis=0) + 1.0
    step = (high - low) / (side - 1)
    i = np.arange(side, dtype=float)
    xs, ys = np.meshgrid(low[0] + step[0] * i, low[1] + step[1] * i)
    return np.column_stack([xs.ravel(), ys.ravel()])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--model", default=str(ROOT / "tests" / "fixtures" / "models" / "tps.json"))
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    sys.path.insert(0, str(Path(args.build) / "python"))
    import floorgrid

    model = floorgrid.Model.load(args.model)
    points = lattice(Path(args.model), model.unit)
    model.forward(points[:1000])  # a GP builds its lattice on first use: not timed
    seconds = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        mapped = model.forward(points)
        seconds.append(time.perf_counter() - start)
    python_ms = 1000 * min(seconds)
    print(f"python  {model.name}: {len(points):,} points forward, best of {args.repeat}: "
          f"{python_ms:.1f} ms ({mapped.flag_names.count('ok'):,} ok)")

    bench = Path(args.build) / "bench" / "api_bench"
    result = subprocess.run(
        [str(bench), "--benchmark_filter=BM_ModelForwardMillionPoints",
         f"--benchmark_repetitions={args.repeat}", "--benchmark_format=json"],
        capture_output=True, text=True, check=True,
        env={**os.environ, "FLOORGRID_BENCH_MODEL": args.model})
    runs = [b for b in json.loads(result.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    cpp_ms = min(b["real_time"] for b in runs)
    print(f"c++     {model.name}: the same points, best of {len(runs)}: {cpp_ms:.1f} ms")
    ratio = python_ms / cpp_ms
    print(f"python / c++ = {ratio:.2f} ({'within' if ratio <= 1.5 else 'NOT within'} 1.5x)")
    sys.exit(0 if ratio <= 1.5 else 1)


if __name__ == "__main__":
    main()
