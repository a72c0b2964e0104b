#!/usr/bin/env bash
# Side by side with MRPT's Monte Carlo localization (pf-localization after carmen2rawlog;
# Debian's mrpt-apps, which install-deps does not install) on Freiburg 079: the same log with
# the same odometry noise, the same SLAM map, 2000 particles and 60 beams of a likelihood field
# on both sides, MRPT started around the start our gridmap filter found. Reports both times,
# their ratio and how far MRPT's poses are from ours. Skips, saying why, when MRPT or the data
# is missing. Usage: bench/mrpt_compare.sh [build-dir] [work-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
work=${2:-$(mktemp -d)}
data=${FLOORGRID_DATA:-$here/../../shared/data}
for tool in carmen2rawlog image2gridmap pf-localization; do
  if ! command -v "$tool" > /dev/null; then
    echo "mrpt_compare: skipped: $tool not found (MRPT's tools come with Debian's mrpt-apps:" \
         "apt-get install mrpt-apps)"
    exit 0
  fi
done
if [ ! -f "$data/fr079/slam_map.png" ]; then
  echo "mrpt_compare: skipped: $data/fr079 is missing"
  exit 0
fi
mkdir -p "$work"

# Ours: the whole dual localization; the noisy log it saw and the gridmap filter's poses.
"$build/bench/localization_accuracy_eval" "$here/../tests/fixtures/fr079" \
  --export-log "$work/noisy.log" --poses "$work/ours.csv" > "$work/ours.txt" 2>&1
ours_seconds=$(sed -n 's/^gridmap   filter pass \([0-9.]*\) s.*/\1/p' "$work/ours.txt")

# MRPT: the same log as a rawlog, the SLAM map as a gridmap with its origin at the image's
# lower-left corner as in the fixture's manifest (image2gridmap's --py counts from the bottom),
# started within 1 m and 20 degrees of our start.
carmen2rawlog -q -w -i "$work/noisy.log" -o "$work/fr079.rawlog" > "$work/carmen2rawlog.txt" 2>&1
image2gridmap -w -i "$data/fr079/slam_map.png" -r 0.05 --px 0 --py 0 \
  -o "$work/map.gridmap.gz" > "$work/image2gridmap.txt" 2>&1
read -r sx sy st < <(python3 - "$work/ours.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
first = next(r for r in rows if r["grid_converged"] == "1")
print(first["grid_x"], first["grid_y"], math.degrees(float(first["grid_theta"])))
PY
)
cat > "$work/pf.ini" <<EOF
[KLD_options]
KLD_binSize_PHI_deg=10
KLD_binSize_XY=0.10
KLD_delta=0.01
KLD_epsilon=0.01
KLD_maxSampleSize=40000
KLD_minSampleSize=150
KLD_minSamplesPerBin=0

[PF_options]
PF_algorithm=0
resamplingMethod=0
adaptiveSampleSize=0
BETA=0.5
sampleSize=1

[DummyOdometryParams]
minStdXY=0.05
minStdPHI=2.0

[LocalizationExperiment]
map_file=$work/map.gridmap.gz
rawlog_file=$work/fr079.rawlog
logOutput_dir=$work/mrpt_out
3DSceneFrequency=-1
SHOW_PROGRESS_3D_REAL_TIME=false
experimentRepetitions=1
particles_count=2000
init_PDF_mode=1
init_PDF_min_x=$(python3 -c "print($sx-1)")
init_PDF_max_x=$(python3 -c "print($sx+1)")
init_PDF_min_y=$(python3 -c "print($sy-1)")
init_PDF_max_y=$(python3 -c "print($sy+1)")
init_PDF_min_yaw_deg=$(python3 -c "print($st-20)")
init_PDF_max_yaw_deg=$(python3 -c "print($st+20)")

[MetricMap]
occupancyGrid_count=1
gasGrid_count=0
landmarksMap_count=0
pointsMap_count=0
beaconMap_count=0
likelihoodMapSelection=-1

[MetricMap_occupancyGrid_00_creationOpts]
resolution=0.05

[MetricMap_occupancyGrid_00_likelihoodOpts]
likelihoodMethod=4
LF_decimation=6
LF_stdHit=0.10
LF_maxCorrsDistance=0.5
LF_zHit=0.9
LF_zRandom=0.1
LF_maxRange=80
LF_alternateAverageMethod=0
EOF
start=$(date +%s.%N)
pf-localization "$work/pf.ini" < /dev/null > "$work/mrpt.txt" 2>&1 || {
  echo "mrpt_compare: pf-localization failed; its output is in $work/mrpt.txt:"
  tail -20 "$work/mrpt.txt"
  exit 1
}
end=$(date +%s.%N)

python3 - "$work" "$start" "$end" "$ours_seconds" <<'PY'
import csv, math, re, statistics, sys
work, start, end, ours = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
mrpt_seconds = end - start
number = r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
poses = []
for line in open(f"{work}/mrpt.txt"):
    m = re.search(r"PDF estimation:\s*\S?(" + number + r")[ ,]+(" + number + r")[ ,]+(" + number + ")", line)
    if m:
        poses.append(tuple(float(v) for v in m.groups()))
ours_rows = list(csv.DictReader(open(f"{work}/ours.csv")))
# MRPT logs one estimate per laser scan (the first before any update).
n = min(len(poses), len(ours_rows))
d = []
for k in range(n):
    r = ours_rows[k]
    if r["grid_converged"] != "1":
        continue
    d.append(math.hypot(poses[k][0] - float(r["grid_x"]), poses[k][1] - float(r["grid_y"])))
print(f"scans      ours {len(ours_rows)}, MRPT estimates {len(poses)}")
print(f"time       ours (gridmap filter, global localization included) {ours:.1f} s, "
      f"MRPT pf-localization {mrpt_seconds:.1f} s: MRPT takes {mrpt_seconds / ours:.1f}x as long")
if d:
    d.sort()
    within = sum(1 for v in d if v < 0.5) / len(d)
    print(f"distance   MRPT's mean pose to our gridmap filter's, over {len(d)} scans where ours "
          f"converged: median {statistics.median(d):.3f} m, p90 {d[int(0.9 * len(d))]:.3f} m, "
          f"within 0.5 m on {100 * within:.1f}% of them")
print(f"outputs in {work}")
PY
