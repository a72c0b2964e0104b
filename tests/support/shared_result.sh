#!/usr/bin/env bash
# A floorgrid result made once and shared by the tests that only read it. ctest runs every test
# in a process of its own (gtest's per-suite set-up runs again in each), so a suite of five
# tests on one aligned office aligned it five times. Here the first test to ask makes it, the
# others wait for it (flock) and reuse it until the floorgrid binary or the commands change.
#
#   shared_result.sh FLOORGRID CACHE_DIR NAME COMMAND...
#
# Each COMMAND is a floorgrid command line (its arguments, shell-quoted as needed) in which
# {} stands for the result's folder, for example 'simulate --preset office --seed 2 --out {}/data'.
# Prints the folder (CACHE_DIR/NAME) on stdout and exits 0; a command that fails leaves no result
# behind, and its output and exit status are passed on. Consumers copy what they change.
set -euo pipefail

if [[ $# -lt 4 ]]; then
  echo "usage: $0 FLOORGRID CACHE_DIR NAME COMMAND..." >&2
  exit 2
fi
floorgrid=$1
cache=$2
name=$3
shift 3
if [[ ! -x $floorgrid ]]; then
  echo "shared_result: $floorgrid is not an executable" >&2
  exit 2
fi
case $name in
  */* | . | .. | '') echo "shared_result: NAME must be a plain folder name, not '$name'" >&2; exit 2 ;;
esac

mkdir -p "$cache"
folder="$cache/$name"
# The key: the binary's bytes and the commands.
key="$(md5sum <"$floorgrid" | cut -d' ' -f1) $(printf '%s\n' "$@" | md5sum | cut -d' ' -f1)"

exec 9>"$cache/$name.lock"
flock 9
if [[ -f $folder/KEY && $(cat "$folder/KEY") == "$key" ]]; then
  echo "$folder"
  exit 0
fi
rm -rf "$folder"
mkdir -p "$folder"
quoted=$(printf '%q' "$folder")
for command in "$@"; do
  # The command line is a shell word list: its own quoting is kept, {} becomes the folder.
  line=${command//\{\}/$quoted}
  status=0
  output=$(eval "\"\$floorgrid\" $line" 2>&1) || status=$?
  if [[ $status -ne 0 ]]; then
    rm -rf "$folder"
    echo "shared_result: floorgrid $line failed (exit $status):" >&2
    echo "$output" >&2
    exit "$status"
  fi
done
echo "$key" >"$folder/KEY"
echo "$folder"
