#!/usr/bin/env bash
# The main job on semi-real datasets made from every real log in ../shared/data (simulate
# --from-log: the log's own occupancy map as the gridmap, a plan drawn from it through a known
# bend, rotation and scale 0.5-2, no start, no scale given), one table row per log and seed:
# scans, converged fraction, plan scale true/estimated, its error against the true scale and
# against the scale of the exact warp's best global similarity (fit_err%: a bend stretches one
# side of the building and shrinks the other, so no global fit can find the nominal scale
# exactly; truth.json statistics.warp_fit_scale), pair median error against the truth,
# each model's mean error, auto's pick and its error over the best model's, time, exit status.
# Seed 3 draws the plan as DXF, the others as a raster with a map YAML.
# A second table: per row and model, how often the true error lies within std_m and 2 std_m
# (metrics.json models.<name>.calibration; the bar: 60-75% and 90-98%), and the median std_m.
# Last, the robustness issue's bars counted over the rows, with the rows that miss each, and
# how far std_m's level is off: median std_m over median true error per row and model.
#
# Then the real drawings (simulate --from-plan: a world built from the drawing, a robot's run
# through it, a SLAM-like gridmap with a bend and a turned room; the plan is the drawing as
# given): Freiburg 079's floorplan.png, the Halmstad E5/F5/HIH layouts, the Bonn FMap/GMap/
# YouBotMap, the DXF house plan and house site, seeds 1-3, the world differing from the drawing
# (--drawing-errors some) on seeds 2 and 3. The same columns; fmt is the drawing's (png, pgm,
# dxf), set says tuned or held-out and "+errors" where the world differs from the drawing.
#
# Usage: bench/real_matrix.sh [build-dir] [work-dir] [seeds] [options.yaml]   (seeds default
# "1 2 3"; the options file, as `floorgrid config --dump` prints it, is passed to every align;
# ROWS=logs or ROWS=drawings runs only the semi-real rows or only the drawings' rows)
# Set tuned: ACES seed 1 was looked at while developing; every other row is held out. (The wall
# slide's two rounds were chosen with seeds 1-3 in view; seeds 4 and 5 were run only after, as
# its held-out check: `bench/real_matrix.sh build DIR "4 5"`.) Drawings: fr079, F5, GMap and
# the house plan, seeds 1 and 2, are the ones to tune on; E5, HIH, FMap, YouBotMap and the house
# site, and seed 3 of every drawing, are held out.
set -uo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
seeds=${3:-1 2 3}
rows=${ROWS:-all}
config=()
[ -n "${4:-}" ] && config=(--config "$4")
bin="$build/floorgrid"
mkdir -p "$work"
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/../shared/data"
logs=()
for name in aces csail orebro fhw belgioioso seattle; do
  [ -f "$data/carmen/$name-corrected.log.gz" ] && logs+=("$data/carmen/$name-corrected.log.gz")
done
[ -f "$data/fr079/freiburg-079-corrected.log.gz" ] && logs+=("$data/fr079/freiburg-079-corrected.log.gz")
[ ${#logs[@]} -eq 0 ] && [ "$rows" != drawings ] && { echo "no logs under $data"; exit 1; }
calibration="$work/calibration.txt"
: > "$calibration"

# One row of the main table and one of the calibration table, from a row's folder ($d holds
# dataset/ and align/).
print_rows() {  # d name seed format seconds rc set
  local d=$1 name=$2 seed=$3 format=$4 seconds=$5 rc=$6 set_name=$7
  /usr/bin/python3 - "$d" "$name" "$seed" "$set_name" >> "$calibration" <<'PY'
import json, os, sys
d, name, seed, set_name = sys.argv[1:5]
path = f"{d}/align/metrics.json"
models = ["gt", "gt-affine", "lc", "ct", "gp", "gpgt", "dt", "tps", "auto"]
cells = []
metrics = json.load(open(path)) if os.path.exists(path) else {}
m = metrics.get("models", {})
noise = metrics.get("pairs", {}).get("noise_rms_m")
for k in models:
    c = m.get(k, {}).get("calibration")
    cells.append("-" if c is None else f"{100 * c['within_1sigma']:.0f}/{100 * c['within_2sigma']:.0f}")
    cells[-1] += "" if c is None else f"@{100 * c['median_std_m']:.1f}"
noise = "-" if noise is None else f"{100 * noise:.1f}"
print(f"{name:<11} {seed:>4} " + " ".join(f"{c:>12}" for c in cells) + f" {noise:>5} {set_name}")
PY
  /usr/bin/python3 - "$d" "$name" "$seed" "$format" "$seconds" "$rc" "$set_name" <<'PY'
import json, os, sys
d, name, seed, fmt, seconds, rc, set_name = sys.argv[1:8]
t = json.load(open(f"{d}/dataset/truth.json"))
true_scale = t["plan"]["plan_scale"]
fit_scale = true_scale * t["statistics"].get("warp_fit_scale", 1.0)
scans = t["statistics"]["scans"]
f = lambda v, p=3: "-" if v is None else f"{v:.{p}f}"
path = f"{d}/align/metrics.json"
if not os.path.exists(path):
    print(f"{name:<11} {seed:>4} {fmt:>3} {scans:5d} {'-':>6} {true_scale:7.4f} {'-':>7} {'-':>7} "
          f"{'-':>7} {'-':>7} {'-':>7} {'-':>7} {'-':>7} {'-':>7} {'-':>7} {'-':<5} {'-':>6} "
          f"{float(seconds):6.1f} {rc:>3} {set_name}")
    sys.exit(0)
m = json.load(open(path))
e = lambda k: m["models"].get(k, {}).get("mean_error_m")
errors = {k: v.get("mean_error_m") for k, v in m["models"].items()
          if k != "auto" and v.get("mean_error_m") is not None}
best = min(errors.values()) if errors else None
chosen = m.get("chosen_model") or "-"
auto = errors.get(chosen)
est = m.get("plan_scale")
print(f"{name:<11} {seed:>4} {fmt:>3} {scans:5d} {f(m['pairs'].get('converged_fraction'))+'':>6} "
      f"{true_scale:7.4f} {f(est, 4):>7} {f(None if est is None else 100 * (est / true_scale - 1), 2):>7} "
      f"{f(None if est is None else 100 * (est / fit_scale - 1), 2):>8} "
      f"{f(m['pairs'].get('error_median_m')):>7} {f(e('gt')):>7} {f(e('gp')):>7} {f(e('gpgt')):>7} "
      f"{f(e('tps')):>7} {f(e('dt')):>7} {chosen:<5} "
      f"{f(None if auto is None or not best else auto / best, 2):>6} {float(seconds):6.1f} {rc:>3} {set_name}")
PY
}

# Aligns the dataset in $d/dataset and prints its rows.
align_and_print() {  # d name seed format set
  local d=$1
  local start end rc
  start=$(date +%s.%N)
  "$bin" align "$d/dataset" "${config[@]}" --out "$d/align" > "$d/align.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  print_rows "$d" "$2" "$3" "$4" "$(echo "$end - $start" | bc)" "$rc" "$5"
}

printf '%-11s %4s %3s %5s %6s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %-5s %6s %6s %3s %s\n' \
  log seed fmt scans conv sc_true sc_est sc_err% fit_err% pair_md gt gp gpgt tps dt auto a/best \
  time_s rc set
if [ "$rows" != drawings ]; then
for log in "${logs[@]}"; do
  name=$(basename "$log" | sed 's/-corrected.log.gz//; s/freiburg-079/fr079/')
  for seed in $seeds; do
    d="$work/$name-$seed"
    format=png
    [ "$seed" = 3 ] && format=dxf
    set_name=held-out
    [ "$name" = aces ] && [ "$seed" = 1 ] && set_name=tuned
    "$bin" simulate --from-log "$log" --seed "$seed" --plan-format "$format" --out "$d/dataset" \
      > "$d.simulate.log" 2>&1 || { echo "$name $seed: simulate failed (see $d.simulate.log)"; continue; }
    align_and_print "$d" "$name" "$seed" "$format" "$set_name"
  done
done
fi

# The real drawings: name, file, what a bare image needs, whether seeds 1-2 are tuned on.
drawings=(
  "fr079|fr079/floorplan.png|--resolution 0.05|tuned"
  "E5|halmstad/E5/layout/E5_layout.png|--resolution 0.05|held-out"
  "F5|halmstad/F5/layout/F5_layout.png|--resolution 0.05|tuned"
  "HIH|halmstad/HIH/layout/HIH_layout.png|--resolution 0.05|held-out"
  "FMap|bonn/Faro/FMap.yaml||held-out"
  "GMap|bonn/GMap/GMap.yaml||tuned"
  "YouBot|bonn/2021_10_27/YouBotMap.yaml||held-out"
  "house|dxf/house_floorplan_r2004.dxf||tuned"
  "site|dxf/house_site_r2000.dxf||held-out"
)
if [ "$rows" != logs ]; then
[ "$rows" = drawings ] || echo
for entry in "${drawings[@]}"; do
  IFS='|' read -r name file args tuned <<< "$entry"
  [ -f "$data/$file" ] || { echo "$name: $data/$file missing, skipped"; continue; }
  image=$(basename "$data/$file")
  format=${image##*.}
  [ "$format" = yaml ] && format=$(sed -n 's/^image: *//p' "$data/$file" | sed 's/.*\.//')
  for seed in $seeds; do
    d="$work/plan-$name-$seed"
    errors=none
    [ "$seed" != 1 ] && errors=some
    set_name=held-out
    [ "$tuned" = tuned ] && [ "$seed" -le 2 ] && set_name=tuned
    [ "$errors" = some ] && set_name="$set_name+errors"
    # shellcheck disable=SC2086  # args holds words
    "$bin" simulate --from-plan "$data/$file" $args --seed "$seed" --drawing-errors "$errors" \
      --out "$d/dataset" > "$d.simulate.log" 2>&1 || {
      echo "$name $seed: simulate failed (see $d.simulate.log)"; continue; }
    align_and_print "$d" "$name" "$seed" "$format" "$set_name"
  done
done
fi
echo
echo "calibration: % of the truth errors within std_m / within 2 std_m @ median std_m (cm);"
echo "noise: the pairs' own noise the std_m leave out, rms cm (metrics.json pairs.noise_rms_m)"
printf '%-11s %4s %12s %12s %12s %12s %12s %12s %12s %12s %12s %5s %s\n' \
  log seed gt gt-affine lc ct gp gpgt dt tps auto noise set
cat "$calibration"
echo
# The robustness issue's bars over the rows above (each row's metrics.json and truth.json).
/usr/bin/python3 - "$work" <<'PY'
import glob, json, os, sys
rows = {}
for d in sorted(glob.glob(os.path.join(sys.argv[1], "*-[0-9]*"))):
    metrics, truth = f"{d}/align/metrics.json", f"{d}/dataset/truth.json"
    if os.path.isdir(d) and os.path.exists(truth):
        rows[os.path.basename(d)] = (json.load(open(metrics)) if os.path.exists(metrics) else None,
                                     json.load(open(truth)))
bars = {"both filters converged >= 90%": [], "plan scale error <= 0.1%": [],
        "best model <= 0.08 m (0.12 m with a 1 m bend)": [], "auto within 10% of the best": []}
calibrated = [0, 0]
levels = []  # per row x model: median std_m over median true error
for name, (m, t) in rows.items():
    if m is None:
        for out in bars.values():
            out.append(name)
        continue
    errors = {k: v["mean_error_m"] for k, v in m["models"].items()
              if k != "auto" and v.get("mean_error_m") is not None}
    best = min(errors.values()) if errors else float("inf")
    auto = errors.get(m.get("chosen_model"), float("inf"))
    bend = abs(t["parameters"].get("bend_m", 0.0))
    checks = [(m["pairs"].get("converged_fraction") or 0.0) >= 0.9,
              abs(m["plan_scale"] / t["plan"]["plan_scale"] - 1) <= 0.001,
              best <= (0.12 if bend >= 1.0 else 0.08), auto <= 1.1 * best]
    for (bar, out), ok in zip(bars.items(), checks):
        if not ok:
            out.append(name)
    for k, v in m["models"].items():
        c = v.get("calibration")
        if c and k not in ("auto", "gt-rigid"):
            calibrated[1] += 1
            calibrated[0] += (0.60 <= c["within_1sigma"] <= 0.75 and
                              0.90 <= c["within_2sigma"] <= 0.98)
            if v.get("median_error_m"):
                levels.append(c["median_std_m"] / v["median_error_m"])
print("bars over", len(rows), "rows:")
for bar, out in bars.items():
    print(f"  {bar:<48} {len(rows) - len(out):>3}/{len(rows)}" + (f"  out: {' '.join(out)}" if out else ""))
print(f"  {'calibration 1σ 60-75% and 2σ 90-98% (row x model)':<48} {calibrated[0]:>3}/{calibrated[1]}")
if levels:
    # A Rayleigh error whose std_m is right has median |e| = 0.83 std_m: the ratio 1.20.
    levels.sort()
    q = [levels[min(len(levels) - 1, int(f * len(levels)))] for f in (0.1, 0.25, 0.5, 0.75, 0.9)]
    print(f"  median std_m / median error, 10/25/50/75/90%: {' '.join(f'{x:.2f}' for x in q)}"
          " (1.20 when right)")
PY
# The real-drawings issue's bars (with align.models.ideal_pairs: true in the options file: each
# model's error over its error fitted on ideal pairs, the pipeline's own loss), the tuned and
# held-out rows apart.
/usr/bin/python3 - "$work" <<'PY'
import glob, json, os, statistics, sys
groups = {}
for d in sorted(glob.glob(os.path.join(sys.argv[1], "*-[0-9]*"))):
    metrics, truth = f"{d}/align/metrics.json", f"{d}/dataset/truth.json"
    if not (os.path.isdir(d) and os.path.exists(truth)):
        continue
    name = os.path.basename(d)
    kind = "drawings" if name.startswith("plan-") else "semi-real"
    held = not ((name.startswith("plan-") and name.split("-")[1] in ("fr079", "F5", "GMap", "house")
                 and name.split("-")[-1] in ("1", "2")) or name == "aces-1")
    m = json.load(open(metrics)) if os.path.exists(metrics) else None
    groups.setdefault((kind, "held-out" if held else "tuned"), []).append(
        (name, m, json.load(open(truth))))
models = ["gt", "gt-affine", "lc", "ct", "gp", "gpgt", "dt", "tps"]
for (kind, set_name), rows in sorted(groups.items()):
    print(f"{kind}, {set_name}: each model's mean error over its ideal-pair error; the bars")
    print(f"{'row':<16} " + " ".join(f"{k:>9}" for k in models) +
          f" {'conv':>5} {'fit_err%':>8} {'dom_err%':>8} {'1σ/2σ':>8} {'std/err':>7}"
          f" {'source':<6}")
    counts = {"converged >= 90%": 0, "scale within 0.15% of the truth's similarity": 0,
              "... of its similarity over the judged walls": 0,
              "every model within 1.5x of ideal": 0, "chosen 2σ >= 85% and 1σ >= 55%": 0,
              "chosen median std_m <= 3x median error": 0, "exit 0": 0}
    for name, m, t in rows:
        if m is None or not m.get("models"):
            print(f"{name:<16} (no models)")
            continue
        counts["exit 0"] += 1
        ratios = []
        for k in models:
            v = m["models"].get(k, {})
            ideal = (v.get("ideal") or {}).get("mean_error_m")
            err = v.get("mean_error_m")
            ratios.append(None if not ideal or err is None else err / ideal)
        fit_scale = t["plan"]["plan_scale"] * t["statistics"].get("warp_fit_scale", 1.0)
        fit_err = 100 * (m["plan_scale"] / fit_scale - 1)
        # The truth's similarity over the domain (metrics.json domain.truth_plan_scale), where
        # fit_scale's is over the whole drawing, parts of which the robot never mapped.
        domain_scale = m.get("domain", {}).get("truth_plan_scale")
        dom_err = None if not domain_scale else 100 * (m["plan_scale"] / domain_scale - 1)
        chosen = m["models"].get(m.get("chosen_model") or "auto", {})
        c = chosen.get("calibration") or {}
        level = (c.get("median_std_m") / chosen["median_error_m"]
                 if c.get("median_std_m") and chosen.get("median_error_m") else None)
        conv = m["pairs"].get("converged_fraction") or 0.0
        counts["converged >= 90%"] += conv >= 0.9
        counts["scale within 0.15% of the truth's similarity"] += abs(fit_err) <= 0.15
        counts["... of its similarity over the judged walls"] += (dom_err is not None and
                                                                 abs(dom_err) <= 0.15)
        counts["every model within 1.5x of ideal"] += all(r is not None and r <= 1.5 for r in ratios)
        counts["chosen 2σ >= 85% and 1σ >= 55%"] += (c.get("within_2sigma", 0) >= 0.85 and
                                                    c.get("within_1sigma", 0) >= 0.55)
        counts["chosen median std_m <= 3x median error"] += level is not None and level <= 3
        cal = "-" if not c else f"{100 * c['within_1sigma']:.0f}/{100 * c['within_2sigma']:.0f}"
        print(f"{name:<16} " + " ".join("        -" if r is None else f"{r:9.2f}" for r in ratios) +
              f" {conv:5.2f} {fit_err:8.2f} {'-' if dom_err is None else f'{dom_err:.2f}':>8}"
              f" {cal:>8} {'-' if level is None else f'{level:.2f}':>7}"
              f" {m['pairs'].get('source', '-'):<6}")
    for bar, n in counts.items():
        print(f"  {bar:<48} {n:>3}/{len(rows)}")
    print()
PY
echo "outputs in $work"
