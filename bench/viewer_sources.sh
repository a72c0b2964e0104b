#!/usr/bin/env bash
# The viewer on fr079 read two ways: the real CARMEN log, and a ROS 1 bag written from it by the
# test writers (independent of floorgrid's readers). Aligns both, serves both, and compares what
# the viewer shows: /api/info, the maps, the overlay and the heat maps (byte for byte), and
# 1,000 random points mapped each way (distance, std_m and flags).
#   bench/viewer_sources.sh [BUILD_DIR] [WORK_DIR]      (under a minute on 2 cores)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build=$(cd "${1:-$here/build}" && pwd)
work=${2:-/tmp/floorgrid-viewer-sources}
data="$here/../shared/data/fr079"
python=/usr/bin/python3
if [ ! -d "$data" ]; then
  echo "viewer_sources: $data is missing"
  exit 1
fi
rm -rf "$work"
mkdir -p "$work"
cd "$work"
"$python" "$here/tests/bags/carmen_to_records.py" "$data/freiburg-079-corrected.log.gz" fr079.jsonl
"$python" "$here/tests/bags/write_ros1_bag.py" fr079.jsonl fr079.bag --compression lz4
sed -e "s|\.\./\.\./\.\./\.\./shared|$here/../shared|" "$here/tests/fixtures/fr079/dataset.yaml" \
  >carmen.yaml
sed -e "s|^log: .*|log: $work/fr079.bag|" carmen.yaml >bag.yaml
for source in carmen bag; do
  echo "== align $source"
  /usr/bin/time -f "   %e s" "$build/floorgrid" align "$source.yaml" --out "align-$source" |
    grep -E "^(pairs|model|tps|auto) "
done

pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT
for source in carmen bag; do
  "$build/floorgrid" serve "align-$source" --port 0 >"serve-$source.log" 2>&1 &
  pids+=($!)
done
urls=()
for source in carmen bag; do
  for _ in $(seq 1 100); do
    url=$(sed -n 's|^serving .* at \(http://[^ ]*\) (Ctrl-C stops).*|\1|p' "serve-$source.log")
    [ -n "$url" ] && break
    sleep 0.2
  done
  urls+=("$url")
done
"$python" - "${urls[@]}" <<'PY'
import hashlib, json, sys, urllib.request
import numpy as np
carmen, bag = sys.argv[1], sys.argv[2]
def get(url, path):
    return urllib.request.urlopen(url + path.lstrip("/")).read()
def post(url, body):
    r = urllib.request.Request(url + "api/map", data=json.dumps(body).encode(), method="POST",
                               headers={"Content-Type": "application/json"})
    return json.load(urllib.request.urlopen(r))["points"]
info = [json.loads(get(u, "/api/info")) for u in (carmen, bag)]
for i in info:
    i.pop("dataset")
print("api/info equal (but the name):", info[0] == info[1])
failed = info[0] != info[1]
for path in ("/api/maps/plan.png", "/api/maps/grid.png", "/api/overlay.png",
             "/api/heatmap.png?kind=std"):
    same = hashlib.sha256(get(carmen, path)).digest() == hashlib.sha256(get(bag, path)).digest()
    print(f"{path:28s} byte for byte: {same}")
    failed |= not same
rng = np.random.default_rng(1)
plan, grid = info[0]["plan"]["bounds"], info[0]["grid"]["bounds"]
for frm, b in (("plan", plan), ("grid", grid)):
    pts = np.column_stack([rng.uniform(b[0][0], b[1][0], 1000), rng.uniform(b[0][1], b[1][1], 1000),
                           rng.uniform(-3, 3, 1000)]).tolist()
    a, c = post(carmen, {"from": frm, "points": pts}), post(bag, {"from": frm, "points": pts})
    d = max((np.hypot(p["x"] - q["x"], p["y"] - q["y"]) for p, q in zip(a, c)
             if p["x"] is not None and q["x"] is not None), default=0.0)
    flags = sum(p["flag"] != q["flag"] for p, q in zip(a, c))
    print(f"from {frm}: 1000 points, max |carmen - bag| {d:.2g} m, flags differing {flags}")
    failed |= d > 1e-6 or flags > 0
sys.exit(1 if failed else 0)
PY
