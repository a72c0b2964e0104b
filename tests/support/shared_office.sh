#!/usr/bin/env bash
# The simulated office of seed 2 aligned with the defaults, made once per floorgrid binary and
# shared by the tests that read it (EvaluateCommand, the report's and the viewer's browser
# tests): prints the folder holding data/ and align/. Consumers copy what they change.
#
#   shared_office.sh FLOORGRID CACHE_DIR
set -euo pipefail
if [[ $# -ne 2 ]]; then
  echo "usage: $0 FLOORGRID CACHE_DIR" >&2
  exit 2
fi
exec "$(dirname "$0")/shared_result.sh" "$1" "$2" office-2-aligned \
  'simulate --preset office --seed 2 --out {}/data' 'align {}/data --out {}/align'
