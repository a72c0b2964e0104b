#!/usr/bin/env bash
# Runs every fuzz target of a fuzz build (make fuzz) for a given time on its seed corpus, two at a
# time, and prints a table of what each did. Inputs that crash, leak, hang (10 s) or allocate
# more than 2 GB are kept in BUILD/fuzz-findings/<target>/ and make the script fail.
# With FUZZ_RUNS=N each target stops after N executions (or SECONDS, whichever comes first).
# Usage: scripts/run-fuzz.sh BUILD_DIR SECONDS [TARGET...]
set -euo pipefail
build=${1:?usage: run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for exe in "$build"/fuzz/*_fuzz; do targets+=("$(basename "$exe" _fuzz)"); done
fi
corpus="$build/fuzz-corpus"
/usr/bin/python3 "$root/fuzz/make_corpus.py" "$corpus" "$root/../shared/data"

run_one() {
  local build=$1 seconds=$2 target=$3
  local max_len=8192
  [ "$target" = model_json ] && max_len=16384
  mkdir -p "$build/fuzz-findings/$target" "$build/fuzz-logs"
  # The corpus grows with what the fuzzer finds: later runs start from there.
  # alloc_dealloc_mismatch=0: libdime frees an unknown DXF table's name (new[]) with delete.
  ASAN_OPTIONS="${ASAN_OPTIONS:-alloc_dealloc_mismatch=0}" "$build/fuzz/${target}_fuzz" "$build/fuzz-corpus/$target" \
    -max_total_time="$seconds" -runs="${FUZZ_RUNS:--1}" -max_len="$max_len" -timeout=10 \
    -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -print_final_stats=1 -detect_leaks=1 \
    -artifact_prefix="$build/fuzz-findings/$target/" > "$build/fuzz-logs/$target.log" 2>&1
}
export -f run_one
status=0
printf '%s\n' "${targets[@]}" | xargs -P 2 -I{} bash -c 'run_one "$@"' _ "$build" "$seconds" {} ||
  status=1

printf '%-14s %12s %10s %8s %8s %s\n' target execs exec/s cov features findings
for target in "${targets[@]}"; do
  log="$build/fuzz-logs/$target.log"
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo 0)
  ft=$(grep -oE 'ft: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo 0)
  findings=$(find "$build/fuzz-findings/$target" -type f | wc -l)
  printf '%-14s %12s %10s %8s %8s %s\n' "$target" "${execs:-0}" "${speed:-0}" "${cov:-0}" \
    "${ft:-0}" "$findings"
  if [ "$findings" -gt 0 ]; then
    status=1
    grep -m 3 -E 'ERROR|runtime error|==[0-9]+==' "$log" | sed 's/^/    /'
  fi
done
exit $status
