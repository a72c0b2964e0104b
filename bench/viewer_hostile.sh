#!/usr/bin/env bash
# `floorgrid serve` under the hostile loads of issue 31 (slow headers, a chunked bomb, paths
# that are not UTF-8, 4 and 8 requests of 1,000,000 points at once), with the server's peak
# memory (VmHWM) above its memory with the model loaded; see bench/viewer_hostile.py.
#   bench/viewer_hostile.sh [BUILD_DIR] [ALIGN_DIR] [LOAD ...]
# Without ALIGN_DIR, `floorgrid demo` makes one in /tmp/floorgrid-hostile (a few minutes).
# Takes about 2 minutes on 2 cores; run it alone.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build=$(cd "${1:-$here/build}" && pwd)
align=${2:-}
if [ -z "$align" ]; then
  align=/tmp/floorgrid-hostile/demo/align
  if [ ! -f "$align/model.json" ]; then
    "$build/floorgrid" demo --out /tmp/floorgrid-hostile/demo >/tmp/floorgrid-hostile-demo.log
  fi
fi
shift $(($# > 2 ? 2 : $#))
exec /usr/bin/python3 "$here/bench/viewer_hostile.py" "$build/floorgrid" "$align" "$@"
