#!/usr/bin/env bash
# Makes a report with `floorgrid align` on a small simulated office, then opens it in chromium
# (report/test/report.test.mjs). Exit 77 (ctest's skip) when chromium or report/node_modules is
# missing.  Usage: report_browser_test.sh FLOORGRID NODE SOURCE_DIR WORK_DIR [CACHE_DIR]
# With CACHE_DIR the office is the one the other tests share (tests/support/shared_office.sh).
set -euo pipefail
floorgrid=$1 node=$2 source=$3 work=$4 cache=${5:-}
if [ ! -x /usr/bin/chromium ]; then
  echo "SKIP: /usr/bin/chromium is missing (scripts/install-deps.sh installs it)"
  exit 77
fi
if [ ! -d "$source/report/node_modules/playwright-core" ]; then
  echo "SKIP: report/node_modules/playwright-core is missing (run scripts/install-deps.sh)"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
if [ -n "$cache" ]; then
  shared=$("$source/tests/support/shared_office.sh" "$floorgrid" "$cache")
  cp -r "$shared/align" "$work/align"
else
  "$floorgrid" simulate --preset office --seed 2 --out "$work/data" >/dev/null
  "$floorgrid" align "$work/data" --out "$work/align" >/dev/null
fi
exec "$node" "$source/report/test/report.test.mjs" "$work/align/report.html" "$work/screenshots"
