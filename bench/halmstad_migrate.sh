#!/usr/bin/env bash
# Re-mapping on the Halmstad data (../shared/data/halmstad): for every sensor-to-sensor hand pair
# file `pairs-sensor/<B>__<A>.csv` (162 files; map A the old map, map B the new one), the old map
# A is aligned to the new map B by `floorgrid align --maps-only` (A as the floorplan, B as the
# gridmap, both at the nominal 0.05 m/px, no pair given), then `floorgrid migrate` carries the
# pairs' A points (as waypoints in A's metres) onto B, and each is compared with its hand-picked
# B point, which the alignment never sees. A file counts as a success when the median error at
# its pairs is under 1 m (20 px) and the alignment was accepted; a failed alignment (non-zero
# exit) counts as a failure. Printed per file and per building: success and mean error.
#
# With CONFIG=FILE in the environment, `align` reads it (`--config`): e.g. a lower
# align.maps_only.min_fitness, to see whether the alignments refused were right all the same.
#
# Usage: bench/halmstad_migrate.sh [build-dir] [work-dir] [max-files-per-building] [skip-per-building]
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
limit=${3:-1000}
skip=${4:-0}
config=()
[ -n "${CONFIG:-}" ] && config=(--config "$CONFIG")
bin="$build/floorgrid"
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/../shared/data/halmstad"
[ -d "$data" ] || { echo "no Halmstad data under $data"; exit 1; }
mkdir -p "$work"
py=/usr/bin/python3

printf '%-16s %6s %5s %7s %7s %7s %-7s %6s\n' pair accept pairs med_px mean_px mean_m success time_s
for env in E5 F5 HIH; do
  n=0
  for pairs in "$data/$env"/pairs-sensor/*.csv; do
    n=$((n + 1))
    [ "$n" -gt "$skip" ] || continue
    [ "$n" -le "$((skip + limit))" ] || break
    name=$(basename "$pairs" .csv)   # <B>__<A>
    new=${name%%__*}
    old=${name##*__}
    dir="$work/$name"
    mkdir -p "$dir"
    {
      echo "floorplan: $data/$env/pseudo_occupancy/$old.png"
      echo "floorplan_resolution: 0.05"
      echo "gridmap: $data/$env/pseudo_occupancy/$new.png"
      echo "gridmap_resolution: 0.05"
    } > "$dir/dataset.yaml"
    # The pairs' old-map points as waypoints (px x 0.05: metres, origin at the lower left as the
    # map images').
    "$py" - "$pairs" "$dir/waypoints.csv" <<'PY'
import csv, sys
with open(sys.argv[1]) as f, open(sys.argv[2], "w") as out:
    out.write("name,x,y\n")
    for i, row in enumerate(csv.DictReader(f)):
        out.write(f"p{i},{float(row['plan_x']) * 0.05:.6f},{float(row['plan_y']) * 0.05:.6f}\n")
PY
    start=$(date +%s%N)
    "$bin" align "$dir" --maps-only "${config[@]}" --out "$dir/align" > "$dir/align.log" 2>&1
    status=$?
    accepted=no
    if [ $status -eq 0 ] && [ -f "$dir/align/model.json" ]; then
      accepted=$("$py" -c "import json,sys; m=json.load(open(sys.argv[1])); print('yes' if m.get('maps_only',{}).get('accepted') else 'no')" "$dir/align/metrics.json" 2>/dev/null || echo no)
      "$bin" migrate --model "$dir/align/model.json" "$dir/waypoints.csv" --out "$dir/migrated" \
        > "$dir/migrate.log" 2>&1
    fi
    seconds=$(( ($(date +%s%N) - start) / 1000000 ))
    med=-; mean=-; mean_m=-; count=$(($(wc -l < "$pairs") - 1)); success=no
    if [ -f "$dir/migrated/waypoints.csv" ]; then
      read -r med mean mean_m < <("$py" - "$pairs" "$dir/migrated/waypoints.csv" <<'PY'
import csv, math, statistics, sys
hand = list(csv.DictReader(open(sys.argv[1])))
moved = list(csv.DictReader(open(sys.argv[2])))
e = []
for h, m in zip(hand, moved):
    if m["x"] == "":
        e.append(float("inf"))
        continue
    e.append(math.hypot(float(m["x"]) / 0.05 - float(h["grid_x"]), float(m["y"]) / 0.05 - float(h["grid_y"])))
finite = [x for x in e if math.isfinite(x)]
print(f"{statistics.median(e):.1f} {statistics.mean(finite):.1f} {statistics.mean(finite) * 0.05:.2f}")
PY
)
      success=$(awk -v m="$med" -v a="$accepted" 'BEGIN { print (m < 20 && a == "yes") ? "yes" : "no" }')
    fi
    printf '%-16s %6s %5s %7s %7s %7s %-7s %6s\n' "$name" "$accepted" "$count" "$med" "$mean" \
      "$mean_m" "$success" "$((seconds / 1000)).$(( (seconds % 1000) / 100 ))"
  done
done | tee "$work/table.txt"
"$py" - "$work/table.txt" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
print()
print("building  files  success  mean error at the pairs, successes (px / m)  all aligned (px / m)")
for env in ("E5", "F5", "HIH", ""):
    judged = [r for r in rows if r[0].startswith(env)]
    ok = [r for r in judged if r[6] == "yes"]
    e_ok = [float(r[4]) for r in ok]
    e_all = [float(r[4]) for r in judged if r[4] != "-"]
    m_ok = sum(e_ok) / len(e_ok) if e_ok else float("nan")
    m_all = sum(e_all) / len(e_all) if e_all else float("nan")
    print(f"{env or 'all':8s} {len(judged):6d} {len(ok):5d}/{len(judged):<3d} {m_ok:14.1f} px / {m_ok * 0.05:.2f} m"
          f" {m_all:16.1f} px / {m_all * 0.05:.2f} m")
PY
echo "outputs in $work"
