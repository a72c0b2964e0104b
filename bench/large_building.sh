#!/usr/bin/env bash
# A building of the MIT infinite corridor's class (issue 34: a 250 x 236 m building within
# 1 GB). The MIT log is not in ../shared/data, so two stand-ins, each aligned with
# /usr/bin/time (wall seconds, peak resident memory) and metrics.json's per-stage peak:
#   drawn  a drawing of a 250 x 236 m building (bench/large_building_plan.py: two crossing
#          corridors lined with 150 rooms, 5000 x 4720 pixels), made a dataset by
#          `simulate --from-plan` (a world built from it, a 1,586-scan tour, a drifted gridmap
#          of what the robot saw): the plan is the large map.
#   tiled  the office preset with its gridmap tiled 6 x 6 (5000 x 4720 cells, 250 x 236 m): the
#          gridmap is the large map. The run and the plan cover one tile, so the plan-match check
#          refuses it (exit 3) after every stage has run.
#
# Usage: [SEED=1] bench/large_building.sh [build-dir] [work-dir]
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
seed=${SEED:-1}
bin="$build/floorgrid"
py=/usr/bin/python3
here="$(cd "$(dirname "$0")" && pwd)"
[ -x "$bin" ] || { echo "no $bin: build the floorgrid target first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (Debian package time)" >&2; exit 1; }
mkdir -p "$work"

# run NAME DATASET: align it, then print its row.
run() {
  local name=$1 dataset=$2 out="$work/$1-aligned"
  rm -rf "$out"
  /usr/bin/time -f '%e %M' -o "$work/$name.time" "$bin" align "$dataset" --seed "$seed" \
    --out "$out" > "$work/$name.log" 2>&1
  local rc=$?
  # /usr/bin/time puts "Command exited with non-zero status N" above the figures
  read -r seconds kib < <(tail -n 1 "$work/$name.time")
  local stages="(no metrics.json)"
  if [ -f "$out/metrics.json" ]; then
    stages=$("$py" -c '
import json, sys
m = json.load(open(sys.argv[1]))
peak = m.get("peak_memory_mib", {})
order = ["load", "maps_alignment", "localize", "wall_slide", "fit", "write"]
print(" ".join(f"{k} {peak[k]:.0f}" for k in order if k in peak))' "$out/metrics.json")
  fi
  printf '%-6s align %7.1f s  peak %5.0f MB  exit %d  per stage (MiB): %s\n' "$name" "$seconds" \
    "$(( kib / 1000 ))" "$rc" "$stages"
}

echo "work folder $work, seed $seed"
"$py" "$here/large_building_plan.py" draw "$work/plan.pgm" || exit 1
rm -rf "$work/drawn"
"$bin" simulate --from-plan "$work/plan.pgm" --resolution 0.05 --seed "$seed" \
  --out "$work/drawn" > "$work/drawn-simulate.log" 2>&1 ||
  { cat "$work/drawn-simulate.log" >&2; exit 1; }
grep -E '^  (run|gridmap) ' "$work/drawn-simulate.log" | sed 's/^ */drawn  /'
run drawn "$work/drawn"

rm -rf "$work/tiled"
"$bin" simulate --preset office --seed "$seed" --out "$work/tiled" > /dev/null 2>&1 || exit 1
"$py" "$here/large_building_plan.py" tile "$work/tiled/gridmap.yaml" 6 || exit 1
run tiled "$work/tiled"
