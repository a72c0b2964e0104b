#!/usr/bin/env bash
# The main job on every simulated preset and seed 1-3 (and office-inches), from the noisy
# odometry in the log: median pair error, plan scale against the truth, and the models' mean
# errors over SPEC's domain. Usage: bench/alignment_matrix.sh [build-dir] [work-dir] [options.yaml]
# (the options file, as `floorgrid config --dump` prints it, is passed to every align)
set -euo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
config=()
[ -n "${3:-}" ] && config=(--config "$3")
bin="$build/floorgrid"
printf '%-14s %4s %8s %8s %9s %9s %8s %8s %8s %8s %8s %6s\n' preset seed pair_med conv scale true_sc gt gpgt gp tps dt time_s
for preset in office warehouse bent-office office-inches; do
  seeds="1 2 3"
  [ "$preset" = office-inches ] && seeds=1
  for seed in $seeds; do
    d="$work/$preset-$seed"
    "$bin" simulate --preset "$preset" --seed "$seed" --out "$d/dataset" > /dev/null
    start=$(date +%s.%N)
    "$bin" align "$d/dataset" "${config[@]}" --out "$d/align" > "$d/align.log" 2>&1 || { echo "$preset $seed: align failed (see $d/align.log)"; continue; }
    end=$(date +%s.%N)
    python3 - "$d" "$preset" "$seed" "$(echo "$end - $start" | bc)" <<'PY'
import json, sys
d, preset, seed, seconds = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
m = json.load(open(f"{d}/align/metrics.json"))
t = json.load(open(f"{d}/dataset/truth.json"))
e = lambda k: m["models"].get(k, {}).get("mean_error_m")
f = lambda v: "-" if v is None else f"{v:.3f}"
print(f"{preset:<14} {seed:>4} {f(m['pairs']['error_median_m']):>8} {m['pairs']['converged_fraction']:8.3f} "
      f"{m['plan_scale']:9.5f} {t['plan']['plan_scale']:9.5f} {f(e('gt')):>8} {f(e('gpgt')):>8} {f(e('gp')):>8} "
      f"{f(e('tps')):>8} {f(e('dt')):>8} {seconds:6.1f}")
PY
  done
done
echo "outputs in $work"
