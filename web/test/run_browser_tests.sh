#!/usr/bin/env bash
# The viewer's browser tests as ctest runs them: a small simulated dataset is aligned, served by
# `floorgrid serve` on a free port, and web/test/viewer.test.mjs, then
# web/test/layers.test.mjs (zones and waypoints), drive Debian's chromium against it.
#
#   web/test/run_browser_tests.sh FLOORGRID NODE SOURCE_DIR WORK_DIR [CACHE_DIR]
#
# With CACHE_DIR the office is the one the other tests share (tests/support/shared_office.sh),
# copied into WORK_DIR: the viewer may write into its folder.
# Exit 0: passed; 77: skipped (no chromium, or web/node_modules not installed); else failed.
# Screenshots go to WORK_DIR/screenshots.
set -euo pipefail

if [[ $# -ne 4 && $# -ne 5 ]]; then
  echo "usage: $0 FLOORGRID NODE SOURCE_DIR WORK_DIR [CACHE_DIR]" >&2
  exit 2
fi
floorgrid=$1
node=$2
source=$3
work=$4
cache=${5:-}
readonly SKIP=77

if [[ ! -x /usr/lib/chromium/chromium && ! -x /usr/bin/chromium ]]; then
  echo "SKIP: no chromium (scripts/install-deps.sh installs Debian's chromium)"
  exit $SKIP
fi
for package in playwright-core leaflet; do
  if [[ ! -d "$source/web/node_modules/$package" ]]; then
    echo "SKIP: $source/web/node_modules/$package is missing (scripts/install-deps.sh runs npm ci in web/)"
    exit $SKIP
  fi
done

rm -rf "$work/data" "$work/align" "$work/screenshots"
mkdir -p "$work"
if [[ -n $cache ]]; then
  shared=$("$source/tests/support/shared_office.sh" "$floorgrid" "$cache")
  cp -r "$shared/data" "$work/data"
  cp -r "$shared/align" "$work/align"
else
  "$floorgrid" simulate --preset office --seed 2 --out "$work/data" >/dev/null
  "$floorgrid" align "$work/data" --out "$work/align" >/dev/null
fi

server_pid=
stop_server() {
  if [[ -n $server_pid ]] && kill -0 "$server_pid" 2>/dev/null; then
    kill "$server_pid" 2>/dev/null || true
    wait "$server_pid" 2>/dev/null || true
  fi
}
trap stop_server EXIT

"$floorgrid" serve "$work/align" --port 0 --web "$source/web" >"$work/serve.log" 2>&1 &
server_pid=$!

# Its line: "serving   NAME with model M at http://127.0.0.1:PORT/ (Ctrl-C stops)".
url=
for _ in $(seq 1 200); do
  url=$(sed -n 's|^serving .* at \(http://[^ ]*\) (Ctrl-C stops).*|\1|p' "$work/serve.log" | head -n 1)
  [[ -n $url ]] && break
  if ! kill -0 "$server_pid" 2>/dev/null; then
    echo "floorgrid serve exited before it listened:" >&2
    cat "$work/serve.log" >&2
    exit 1
  fi
  sleep 0.1
done
if [[ -z $url ]]; then
  echo "floorgrid serve did not say where it listens within 20 s:" >&2
  cat "$work/serve.log" >&2
  exit 1
fi
echo "server at $url (log: $work/serve.log)"

status=0
FLOORGRID_URL="$url" SCREENSHOT_DIR="$work/screenshots" \
  "$node" --test --test-concurrency=1 "$source/web/test/viewer.test.mjs" \
  "$source/web/test/layers.test.mjs" || status=$?
echo "screenshots in $work/screenshots"
exit $status
