#!/usr/bin/env bash
# Where the pairs come from, compared: every semi-real dataset (simulate --from-log on each real
# log in ../shared/data, as bench/real_matrix.sh makes them) and fr079 (tests/fixtures/fr079,
# judged at its 56 hand-made pairs) aligned three times, with the pairs from the robot run
# (`--pairs-from run`), from the maps alone (`--maps-only`) and from both (`--pairs-from both`).
# One row per dataset and source: pairs, the maps-only fitness, each model's mean error against
# the truth, the best model's, auto's pick, and the best's ratio to the run-based best (the
# maps-only issue's bar: within 1.5x), time and exit status.
#
# Usage: [REUSE="run"] bench/pairs_sources.sh [build-dir] [work-dir] [seeds]   (seeds default
# "1 2 3"; "": fr079 alone; REUSE keeps the named sources' outputs already in work-dir)
# Nothing of the maps-only alignment was tuned on these datasets (it was tuned on the Halmstad
# maps and the simulator); the run-based path's tuning set is ACES seed 1 (bench/real_matrix.sh).
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
seeds=${3-1 2 3}
bin="$build/floorgrid"
mkdir -p "$work"
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/../shared/data"
py=/usr/bin/python3

datasets=()
for name in aces csail orebro fhw belgioioso seattle fr079; do
  log="$data/carmen/$name-corrected.log.gz"
  [ "$name" = fr079 ] && log="$data/fr079/freiburg-079-corrected.log.gz"
  [ -f "$log" ] || continue
  for seed in $seeds; do
    d="$work/$name-$seed"
    format=png
    [ "$seed" = 3 ] && format=dxf
    if [ ! -f "$d/dataset/dataset.yaml" ]; then
      "$bin" simulate --from-log "$log" --seed "$seed" --plan-format "$format" --out "$d/dataset" \
        > "$d.simulate.log" 2>&1 || { echo "$name $seed: simulate failed (see $d.simulate.log)"; continue; }
    fi
    datasets+=("$d|$d/dataset")
  done
done
if [ -f "$data/fr079/slam_map.png" ]; then
  # The fixture with its hand-made pairs as the truth.
  mkdir -p "$work/fr079-real/dataset"
  sed "s|\.\./\.\./\.\./\.\./shared|$here/../shared|" "$here/tests/fixtures/fr079/dataset.yaml" \
    > "$work/fr079-real/dataset/dataset.yaml"
  printf 'truth:\n  manual_pairs: %s\n' "$here/tests/fixtures/fr079/manual_pairs.csv" \
    >> "$work/fr079-real/dataset/dataset.yaml"
  datasets+=("$work/fr079-real|$work/fr079-real/dataset")
fi
[ ${#datasets[@]} -eq 0 ] && { echo "no logs under $data"; exit 1; }

printf '%-13s %-5s %6s %6s %7s %7s %7s %7s %7s %7s %-6s %6s %6s %3s\n' dataset pairs count \
  fit gt gp gpgt tps dt best auto vs_run time_s rc
summary="$work/summary.txt"
: > "$summary"
for entry in "${datasets[@]}"; do
  d=${entry%%|*}
  dataset=${entry#*|}
  name=$(basename "$d")
  for source in run maps both; do
    mkdir -p "$d"
    out="$d/align-$source"
    if [ -n "${REUSE:-}" ] && [[ " $REUSE " == *" $source "* ]] && [ -f "$out/metrics.json" ]; then
      rc=0  # kept from an earlier run (REUSE="run": the run-based path did not change)
      seconds=$(cat "$out.seconds" 2>/dev/null || echo 0)
    else
      start=$(date +%s.%N)
      "$bin" align "$dataset" --pairs-from "$source" --out "$out" > "$out.log" 2>&1
      rc=$?
      seconds=$(echo "$(date +%s.%N) - $start" | bc)
      echo "$seconds" > "$out.seconds"
    fi
    "$py" - "$out/metrics.json" "$d/align-run/metrics.json" "$name" "$source" "$seconds" "$rc" \
      "$summary" <<'PY'
import json, os, sys
path, run_path, name, source, seconds, rc, summary = sys.argv[1:8]
f = lambda v, p=3: "-" if v is None else f"{v:.{p}f}"
def best_of(p):
    if not os.path.exists(p):
        return None, {}
    m = json.load(open(p))
    errors = {k: v.get("mean_error_m") for k, v in m.get("models", {}).items()
              if k != "auto" and v.get("mean_error_m") is not None}
    return m, errors
m, errors = best_of(path)
_, run_errors = best_of(run_path)
best = min(errors.values()) if errors else None
run_best = min(run_errors.values()) if run_errors else None
ratio = None if best is None or not run_best else best / run_best
e = lambda k: errors.get(k)
count = fit = auto = None
if m:
    count = m["pairs"]["count"]
    fit = m.get("maps_only", {}).get("fitness")
    auto = m.get("chosen_model")
print(f"{name:<13} {source:<5} {count if count is not None else '-':>6} {f(fit, 2):>6} "
      f"{f(e('gt')):>7} {f(e('gp')):>7} {f(e('gpgt')):>7} {f(e('tps')):>7} {f(e('dt')):>7} "
      f"{f(best):>7} {auto or '-':<6} {f(ratio, 2):>6} {float(seconds):6.1f} {rc:>3}")
with open(summary, "a") as out:
    out.write(f"{name} {source} {'-' if ratio is None else ratio} {rc}\n")
PY
  done
done
echo
# The bar: the maps-only best within 1.5x of the run-based best, per dataset.
"$py" - "$summary" <<'PY'
import sys
rows = [line.split() for line in open(sys.argv[1])]
for source in ("maps", "both"):
    ratios = [(r[0], r[2]) for r in rows if r[1] == source]
    ok = [n for n, x in ratios if x != "-" and float(x) <= 1.5]
    miss = [n for n, x in ratios if n not in ok]
    finite = sorted(float(x) for _, x in ratios if x != "-")
    median = finite[len(finite) // 2] if finite else float("nan")
    print(f"{source:<5} best within 1.5x of the run's: {len(ok)}/{len(ratios)}, median ratio "
          f"{median:.2f}" + (f"; out: {' '.join(miss)}" if miss else ""))
PY
echo "outputs in $work"
