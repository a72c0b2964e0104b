#!/usr/bin/env bash
# An hour of driving (issue 34): the warehouse preset simulated for each run length
# (`simulate --duration`, 15 scans a second) and aligned. One row per run length, printed as soon
# as its run is done: scans, wall time and peak memory of simulate and of align
# (/usr/bin/time -f '%e %M', and the CPU seconds: on a shared machine the wall clock waits for
# cores), align's stages (metrics.json `timings_s`), its pairs and the best
# model's mean error against the truth; then each column's growth from the shortest run to the
# longest (the issue's bars: align on 60 minutes within 240 s and 4 GB, and within 4.8x the
# 15-minute run's time, every stage linear or better in the scans).
#
# Usage: [PRESET=warehouse] [SEED=1] [REUSE=1] bench/long_run.sh [build-dir] [work-dir]
#        [minutes list, default "15 30 60"]
# REUSE=1 keeps the datasets already simulated in work-dir (only align runs again).
# Outputs: work-dir/<preset>-<minutes>min/{dataset,aligned}, *.time, *.log, and summary.tsv.
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
minutes_list=${3:-15 30 60}
preset=${PRESET:-warehouse}
seed=${SEED:-1}
bin="$build/floorgrid"
py=/usr/bin/python3
[ -x "$bin" ] || { echo "no $bin: build the floorgrid target first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (Debian package time)" >&2; exit 1; }
mkdir -p "$work"
summary="$work/summary.tsv"
stages="load maps_alignment global_localization scale_search localize pairs wall_slide fit evaluate heat_maps write"

printf 'work folder %s, preset %s seed %s, run lengths (min): %s\n' "$work" "$preset" "$seed" \
  "$minutes_list"
header="minutes scans sim_s sim_MB align_s align_cpu_s align_MB $stages pairs best_mean_m rc"
printf '%s\n' "$header" | tr ' ' '\t' > "$summary"
printf '%-7s %7s %6s %6s %7s %11s %8s' minutes scans sim_s sim_MB align_s align_cpu_s align_MB
for s in $stages; do printf ' %*s' $(( ${#s} > 6 ? ${#s} : 6 )) "$s"; done
printf ' %8s %11s %3s\n' pairs best_mean_m rc

for minutes in $minutes_list; do
  run="$work/$preset-${minutes}min"
  mkdir -p "$run"
  seconds=$(( minutes * 60 ))
  if [ -z "${REUSE:-}" ] || [ ! -f "$run/dataset/dataset.yaml" ]; then
    /usr/bin/time -f '%e %M %U %S' -o "$run/simulate.time" "$bin" simulate --preset "$preset" \
      --seed "$seed" --duration "$seconds" --out "$run/dataset" > "$run/simulate.log" 2>&1 || {
      echo "$minutes min: simulate failed (see $run/simulate.log)"
      continue
    }
  fi
  /usr/bin/time -f '%e %M %U %S' -o "$run/align.time" "$bin" align "$run/dataset" \
    --out "$run/aligned" > "$run/align.log" 2>&1
  rc=$?
  "$py" - "$run" "$minutes" "$rc" "$stages" >> "$summary" <<'EOF'
import json, os, sys
run, minutes, rc, stages = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split()
def time_file(name):
    # /usr/bin/time writes "wall kilobytes user system" as its last line (after any message of
    # its own).
    try:
        with open(os.path.join(run, name)) as f:
            last = f.read().strip().splitlines()[-1].split()
        return float(last[0]), float(last[1]) / 1024.0, float(last[2]) + float(last[3])
    except (OSError, IndexError, ValueError):
        return float("nan"), float("nan"), float("nan")
sim_s, sim_mb, _ = time_file("simulate.time")
align_s, align_mb, align_cpu = time_file("align.time")
scans = "nan"
try:
    with open(os.path.join(run, "dataset", "truth.json")) as f:
        scans = json.load(f)["statistics"]["scans"]
except (OSError, KeyError, ValueError):
    pass
metrics = {}
try:
    with open(os.path.join(run, "aligned", "metrics.json")) as f:
        metrics = json.load(f)
except (OSError, ValueError):
    pass
timings = metrics.get("timings_s", {})
pairs = metrics.get("pairs", {}).get("count", "nan") if isinstance(metrics.get("pairs"), dict) else "nan"
best = float("nan")
for m in metrics.get("models", {}).values():
    mean = m.get("mean_error_m") if isinstance(m, dict) else None
    if isinstance(mean, (int, float)) and not (best <= mean):
        best = mean
row = [minutes, scans, f"{sim_s:.1f}", f"{sim_mb:.0f}", f"{align_s:.1f}", f"{align_cpu:.1f}",
       f"{align_mb:.0f}"]
row += [f"{timings.get(s, float('nan')):.1f}" for s in stages]
row += [pairs, f"{best:.4f}", rc]
print("\t".join(str(v) for v in row))
EOF
  # The row just written, aligned under the header.
  tail -n 1 "$summary" | "$py" -c '
import sys
row = sys.stdin.read().rstrip("\n").split("\t")
widths = [7, 7, 6, 6, 7, 11, 8] + [max(len(s), 6) for s in sys.argv[1].split()] + [8, 11, 3]
print(" ".join((v.ljust(w) if i == 0 else v.rjust(w)) for i, (v, w) in enumerate(zip(row, widths))))
' "$stages"
  # The peak memory at each stage's end (metrics.json peak_memory_mib: it only grows, so the
  # stage where it jumps is the one that raised it).
  "$py" - "$run/aligned/metrics.json" <<'EOF'
import json, sys
try:
    with open(sys.argv[1]) as f:
        peak = json.load(f).get("peak_memory_mib", {})
except (OSError, ValueError):
    peak = {}
order = ["load", "maps_alignment", "localize", "wall_slide", "fit", "write"]
if peak:
    print("        peak MiB at the end of: " +
          ", ".join(f"{s} {peak[s]:.0f}" for s in order if s in peak))
EOF
done

# Growth from the shortest run to the longest, column by column (60/15 with the default list).
"$py" - "$summary" <<'EOF'
import math, sys
with open(sys.argv[1]) as f:
    rows = [line.rstrip("\n").split("\t") for line in f]
header, rows = rows[0], rows[1:]
def number(v):
    try:
        return float(v)
    except ValueError:
        return float("nan")
rows = [r for r in rows if not math.isnan(number(r[0]))]
if len(rows) < 2:
    sys.exit(0)
rows.sort(key=lambda r: number(r[0]))
short, long_ = rows[0], rows[-1]
print(f"growth {long_[0]} min / {short[0]} min (scans x{number(long_[1]) / number(short[1]):.2f}):")
parts = []
for name, a, b in zip(header[2:-3], short[2:-3], long_[2:-3]):
    a, b = number(a), number(b)
    parts.append(f"{name} x{b / a:.2f}" if a > 0 and not math.isnan(b) else f"{name} n/a")
print("  " + ", ".join(parts))
EOF
