#!/usr/bin/env bash
# Maps-only alignment on the Halmstad data (../shared/data/halmstad): every Tango sensor map of
# E5, F5 and HIH aligned to its building's layout by `floorgrid align --maps-only` with no pair
# and no scale given (both images taken at the layout's nominal 0.05 m/px), then judged at the
# hand-picked pairs, which the alignment never sees: each pair's layout point mapped by the
# chosen model (model.json) against its hand-picked sensor-map point, in px and in metres at
# 0.05 m/px. A map counts as a success when the median error at its pairs is under 1 m (20 px)
# and the alignment was accepted (its fitness at least align.maps_only.min_fitness); maps
# without pairs are aligned and reported (fitness, pairs, overlays) but not judged.
# The published comparison (Shahbandi, Magnusson, Iagnemma, RA-L 2018, on this data): 80.41%
# success by eye, mean point-to-point error 1.78 m over 40 maps.
#
# With `negatives` as the third argument it then aligns every sensor map to the two other
# buildings' layouts too, where every answer is wrong: each must end in "no alignment found"
# (a non-zero exit) and the table counts those that did not (the fitness measure's misses).
#
# Usage: bench/halmstad_maps_only.sh [build-dir] [work-dir] [negatives]
# Each map's output (report.html, overlays/) is in work-dir/<map>/align.
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
negatives=${3:-}
bin="$build/floorgrid"
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/../shared/data/halmstad"
[ -d "$data" ] || { echo "no Halmstad data under $data"; exit 1; }
mkdir -p "$work"
py=/usr/bin/python3

printf '%-8s %6s %6s %5s %7s %7s %7s %7s %-7s %6s\n' map fit accept pairs med_px mean_px \
  mean_m model success time_s
for env in E5 F5 HIH; do
  for sensor in "$data/$env"/pseudo_occupancy/*.png; do
    name=$(basename "$sensor" .png)
    dir="$work/$name"
    mkdir -p "$dir"
    layout="$data/$env/layout/${env}_layout.png"
    pairs="$data/$env/pairs/${name}__${env}_layout.csv"
    {
      echo "floorplan: $layout"
      echo "floorplan_resolution: 0.05"
      echo "gridmap: $sensor"
      echo "gridmap_resolution: 0.05"
      if [ -f "$pairs" ]; then
        echo "truth:"
        echo "  manual_pairs: manual_pairs.csv"
      fi
    } > "$dir/dataset.yaml"
    if [ -f "$pairs" ]; then
      # The hand pairs in metres (px x 0.05, origin at the lower left as the map images'), for
      # the report's truth; the error at the pairs is measured below in px.
      "$py" - "$pairs" "$dir" <<'PY'
import csv, sys
src, out = sys.argv[1], sys.argv[2]
with open(src) as f, open(f"{out}/manual_pairs.csv", "w") as m, open(f"{out}/plan_points.csv", "w") as p:
    m.write("plan_x,plan_y,grid_x,grid_y\n")
    p.write("x,y\n")
    for row in csv.DictReader(f):
        v = [float(row[k]) * 0.05 for k in ("plan_x", "plan_y", "grid_x", "grid_y")]
        m.write(",".join(f"{x:.6f}" for x in v) + "\n")
        p.write(f"{v[0]:.6f},{v[1]:.6f}\n")
PY
    fi
    start=$(date +%s%N)
    "$bin" align "$dir" --maps-only --out "$dir/align" > "$dir/align.log" 2>&1
    status=$?
    seconds=$(( ($(date +%s%N) - start) / 1000000 ))
    metrics="$dir/align/metrics.json"
    read -r fit accepted count model < <("$py" - "$metrics" <<'PY'
import json, sys
try:
    m = json.load(open(sys.argv[1]))
    o = m.get("maps_only", {})
    print(f"{o.get('fitness', float('nan')):.2f}", "yes" if o.get("accepted") else "no",
          m["pairs"]["count"], m.get("chosen_model") or "-")
except Exception:
    print("nan no 0 -")
PY
)
    med=-; mean=-; mean_m=-; success=-
    if [ -f "$pairs" ] && [ $status -eq 0 ] && [ -f "$dir/align/model.json" ]; then
      "$bin" map --model "$dir/align/model.json" --points "$dir/plan_points.csv" \
        --out "$dir/mapped.csv" > /dev/null 2>&1
      read -r med mean mean_m < <("$py" - "$pairs" "$dir/mapped.csv" <<'PY'
import csv, math, statistics, sys
hand = list(csv.DictReader(open(sys.argv[1])))
mapped = list(csv.DictReader(open(sys.argv[2])))
e = [math.hypot(float(m["x"]) / 0.05 - float(h["grid_x"]), float(m["y"]) / 0.05 - float(h["grid_y"]))
     for h, m in zip(hand, mapped)]
print(f"{statistics.median(e):.1f} {statistics.mean(e):.1f} {statistics.mean(e) * 0.05:.2f}")
PY
)
      success=$(awk -v m="$med" -v a="$accepted" 'BEGIN { print (m < 20 && a == "yes") ? "yes" : "no" }')
    elif [ -f "$pairs" ]; then
      success=no
    fi
    printf '%-8s %6s %6s %5s %7s %7s %7s %7s %-7s %6s\n' "$name" "$fit" "$accepted" "$count" \
      "$med" "$mean" "$mean_m" "$model" "$success" "$((seconds / 1000)).$(( (seconds % 1000) / 100 ))"
  done
done | tee "$work/table.txt"
"$py" - "$work/table.txt" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
print()
print("environment  judged  success  mean error at the pairs (px / m)   paper (all 40 maps): 1.78 m")
for env in ("E5", "F5", "HIH", ""):
    judged = [r for r in rows if r[0].startswith(env) and r[8] in ("yes", "no")]
    ok = [r for r in judged if r[8] == "yes"]
    errs = [float(r[5]) for r in judged if r[5] != "-"]
    mean = sum(errs) / len(errs) if errs else float("nan")
    print(f"{env or 'all':11s} {len(judged):6d} {len(ok):5d}/{len(judged):<3d} {mean:10.1f} px / {mean * 0.05:.2f} m")
PY
# Every map's overlay on one page: the plan's walls through the chosen model (red) and through
# the hand pairs (green; none where a map has no pairs) on the sensor map.
{
  echo '<!DOCTYPE html><html><head><meta charset="utf-8"><title>Halmstad maps-only overlays</title>'
  echo '<style>figure{display:inline-block;margin:4px;width:32%}img{width:100%}</style></head><body>'
  while read -r name fit accepted _ med _ mean_m model success _; do
    echo "<figure><a href=\"$name/align/report.html\"><img src=\"$name/align/overlays/overlay-auto.png\" alt=\"$name\"></a>"
    echo "<figcaption>$name: fitness $fit ($accepted), median $med px, mean $mean_m m, $model, success $success</figcaption></figure>"
  done < "$work/table.txt"
  echo '</body></html>'
} > "$work/overlays.html"
echo "every map's overlay: $work/overlays.html"
[ "$negatives" = negatives ] || { echo "outputs in $work"; exit 0; }

# Every sensor map on the other buildings' layouts: a wrong building, so "no alignment found".
echo
printf '%-8s %-7s %6s %8s %6s %3s %s\n' map layout fit runner reg rc flagged
for env in E5 F5 HIH; do
  for sensor in "$data/$env"/pseudo_occupancy/*.png; do
    name=$(basename "$sensor" .png)
    for other in E5 F5 HIH; do
      [ "$other" = "$env" ] && continue
      dir="$work/wrong/$name-on-$other"
      mkdir -p "$dir"
      {
        echo "floorplan: $data/$other/layout/${other}_layout.png"
        echo "floorplan_resolution: 0.05"
        echo "gridmap: $sensor"
        echo "gridmap_resolution: 0.05"
      } > "$dir/dataset.yaml"
      "$bin" align "$dir" --maps-only --out "$dir/align" > "$dir/align.log" 2>&1
      rc=$?
      flagged=no
      [ $rc -ne 0 ] && grep -q "no alignment found" "$dir/align.log" && flagged=yes
      # A rejected alignment writes no outputs: its figures are in the message (the first
      # fitness; an accepted one notes its runner-up's after it).
      read -r fit runner reg < <("$py" - "$dir/align.log" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
fit = re.findall(r"fitness (-?[0-9.]+)", text)
reg = re.search(r"score (-?[0-9.]+) \(runner-up (-?[0-9.]+)\)", text)
print(fit[0] if fit else "-", reg.group(2) if reg else "-", reg.group(1) if reg else "-")
PY
)
      printf '%-8s %-7s %6s %8s %6s %3s %s\n' "$name" "$other" "$fit" "$runner" "$reg" "$rc" "$flagged"
    done
  done
done | tee "$work/wrong.txt"
echo
awk '{ n++; if ($7 == "yes") ok++; else miss = miss " " $1 "-on-" $2 }
     END { printf "wrong building flagged: %d/%d%s\n", ok, n, (miss ? "; not flagged:" miss : "") }' \
  "$work/wrong.txt"
echo "outputs in $work"
