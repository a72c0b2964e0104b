#!/usr/bin/env bash
# The thesis's experiments (ch. 6) on our datasets, printed beside its published numbers:
#  - Table 6.1: each model's mean error over the plan's wall samples in the truth's domain, on the
#    simulated office, warehouse and bent-office (seeds 1-3, exact warp as truth) and on fr079
#    (truth: the 56 hand-annotated pairs of tests/fixtures/fr079/manual_pairs.csv through the
#    Delaunay model, as the thesis; see MANUAL_PAIRS.md);
#  - Table 6.3: the largest back-and-forth drift (100 round trips) of each model;
#  - the Halmstad hand-picked pairs, leave-one-out (bench/mapping_accuracy_eval).
# Usage: bench/thesis_tables.sh [build-dir] [work-dir]
set -euo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
root=$(cd "$(dirname "$0")/.." && pwd)
data="$root/../shared/data"
bin="$build/floorgrid"
mkdir -p "$work"
models="gt gp gpgt ct dt tps lc auto"

run() {  # name dataset-folder
  local name=$1 dataset=$2
  if ! "$bin" align "$dataset" --out "$work/$name" > "$work/$name.log" 2>&1; then
    echo "$name: align failed (see $work/$name.log)" >&2
    return
  fi
  echo "$name" >> "$work/rows.txt"
}

: > "$work/rows.txt"
for preset in office warehouse bent-office; do
  for seed in 1 2 3; do
    "$bin" simulate --preset "$preset" --seed "$seed" --out "$work/data-$preset-$seed" > /dev/null
    run "$preset-$seed" "$work/data-$preset-$seed"
  done
done
if [ -d "$data/fr079" ]; then
  mkdir -p "$work/data-fr079"
  sed "s|\.\./\.\./\.\./\.\./shared|$root/../shared|" "$root/tests/fixtures/fr079/dataset.yaml" \
    > "$work/data-fr079/dataset.yaml"
  printf 'truth:\n  manual_pairs: %s\n' "$root/tests/fixtures/fr079/manual_pairs.csv" \
    >> "$work/data-fr079/dataset.yaml"
  run fr079 "$work/data-fr079"
fi

/usr/bin/python3 - "$work" $models <<'PY'
import json, sys
work, models = sys.argv[1], sys.argv[2:]
rows = [r.strip() for r in open(f"{work}/rows.txt") if r.strip()]
f = lambda v: "-" if v is None else f"{v:.3f}"
g = lambda v: "-" if v is None else f"{v:.1e}"
print("Table 6.1: mean error (m) over the plan's wall samples in the truth's domain")
print(f"{'dataset':<16}" + "".join(f"{m:>8}" for m in models) + "  chosen")
drift, lost, followed = {}, {}, {}
for r in rows:
    m = json.load(open(f"{work}/{r}/metrics.json"))
    e = [m["models"].get(k, {}).get("mean_error_m") for k in models]
    print(f"{r:<16}" + "".join(f"{f(v):>8}" for v in e) + f"  {m.get('chosen_model', '-')}")
    for k in models:
        bf = m["models"].get(k, {}).get("back_and_forth", {})
        if bf.get("max_m") is not None:
            drift[k] = max(drift.get(k, 0.0), bf["max_m"])
            lost[k] = lost.get(k, 0) + bf.get("not_invertible", 0)
            followed[k] = followed.get(k, 0) + bf.get("points", 0)
print("thesis, Table 6.1 (buildings 79 / 74 / 106 / factory; bent building 74):")
print("  GT 0.265 / 0.226 / 0.157 / 0.151; GP 0.692 / 0.455 / 0.172 / 0.170;")
print("  GPGT 0.419 / 0.268 / 0.173 / 0.202; CT 1.705 / 0.458; bent 74: GT 1.75, CT 1.81,")
print("  GP 0.71, GPGT 0.798")
print()
print("Table 6.3: largest back-and-forth drift (m) over 100 round trips, all datasets above")
print("".join(f"{k:>10}" for k in models))
print("".join(f"{g(drift.get(k)):>10}" for k in models))
print("not invertible (points whose grid point has more than one plan point, or none), of all followed:")
print("".join(f"{lost.get(k, 0):>6}/{followed.get(k, 0):<3}" for k in models))
print("thesis, Table 6.3: 0.02 m up to 50 m")
PY

if [ -x "$build/bench/mapping_accuracy_eval" ] && [ -d "$data/halmstad" ]; then
  echo
  echo "Halmstad hand-picked pairs, leave-one-out (bench/mapping_accuracy_eval):"
  "$build/bench/mapping_accuracy_eval" | tee "$work/mapping_accuracy.txt"
fi
echo "outputs in $work"
