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
echo "results: $out"
