#!/usr/bin/env bash
# Runs every Google Benchmark executable of a build and keeps the JSON results in
# <build>/bench-results/. Usage: scripts/run-benchmarks.sh [build-dir] [benchmark filter]
set -euo pipefail
build=${1:-build}
filter=${2:-.}
out="$build/bench-results"
mkdir -p "$out"
for exe in "$build"/bench/*_bench; do
  [ -x "$exe" ] || continue
  name=$(basename "$exe")
  echo "== $name"
  "$exe" --benchmark_filter="$filter" --benchmark_out="$out/$name.json" \
         --benchmark_out_format=json
done
# End to end: the dual localization of the real Freiburg 079 run (2 x 2000 particles, 60 beams).
fixture="$(dirname "$0")/../tests/fixtures/fr079"
if [ -d "$(dirname "$0")/../../shared/data/fr079" ] && [ "$filter" = "." ]; then
  echo "== fr079 end to end (bench/localization_accuracy_eval)"
  "$build/bench/localization_accuracy_eval" "$fixture" | tee "$out/fr079_localization.txt" |
    grep -E "^(time|gridmap|tracking|scale|converged)"
fi
# The viewer's API: 10,000 requests of 100 points each from 8 concurrent clients on loopback.
if [ "$filter" = "." ]; then
  echo "== viewer API load (bench/viewer_load)"
  "$build/bench/viewer_load" | tee "$out/viewer_load.txt"
fi
echo "results: $out"
