#!/usr/bin/env bash
# Fresh clone to the demo's report on a fresh Debian 12 machine (issue 34), measured in a chroot:
# `debootstrap --variant=minbase bookworm` into work-dir, given what this workplace's machines
# come with (g++, cmake, make, git, Node 20 and npm copied from this machine, its CA bundle),
# a `git clone` of this checkout's HEAD, then, timed: `make deps-demo` (the packages and npm
# packages the program needs) and `make demo` (configure, build, the demo). With FULL=1 it then
# times the full `scripts/install-deps.sh` as well (what `make test` adds).
#
# Usage (as root; needs debootstrap): [FULL=1] bench/fresh_machine.sh [work-dir]
# The chroot's mounts are undone at the end; remove work-dir by hand afterwards.
set -euo pipefail
work=${1:-$(mktemp -d)}
root="$work/root"
here="$(cd "$(dirname "$0")/.." && pwd)"
[ "$(id -u)" -eq 0 ] || { echo "fresh_machine: run as root" >&2; exit 1; }
command -v debootstrap >/dev/null ||
  { echo "fresh_machine: needs debootstrap (apt-get install debootstrap)" >&2; exit 1; }
[ ! -e "$root" ] || { echo "fresh_machine: $root exists: give an empty work folder" >&2; exit 1; }
mkdir -p "$work"

mounts=()
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    umount -R -l "${mounts[$i]}" 2>/dev/null || true
  done
}
trap cleanup EXIT
bind() { mkdir -p "$2"; mount "${@:3}" --rbind "$1" "$2"; mounts+=("$2"); }

echo "fresh_machine: debootstrap into $root"
debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian \
  > "$work/debootstrap.log" 2>&1
cp /etc/apt/sources.list.d/debian.sources "$root/etc/apt/sources.list.d/" 2>/dev/null &&
  rm -f "$root/etc/apt/sources.list"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"; mounts+=("$root/proc")
bind /sys "$root/sys"
bind /dev "$root/dev"
echo "fresh_machine: what a new machine comes with (g++, cmake, make, git, Node and npm)"
chroot "$root" /bin/bash -c "export DEBIAN_FRONTEND=noninteractive; apt-get update -qq &&
  apt-get install -y -qq --no-install-recommends g++ cmake make git ca-certificates python3" \
  > "$work/base.log" 2>&1
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/ca-certificates.crt"
cp "$(readlink -f "$(command -v node)")" "$root/usr/bin/node"
mkdir -p "$root/usr/lib/node_modules"
cp -a "$(dirname "$(dirname "$(readlink -f "$(command -v npm)")")")" "$root/usr/lib/node_modules/"
ln -sf ../lib/node_modules/npm/bin/npm-cli.js "$root/usr/bin/npm"
[ -f ~/.npmrc ] && cp ~/.npmrc "$root/root/.npmrc"
# The checkout's layout: the clone at /work/main, the shared data beside it (read-only).
git clone -q "$here" "$root/work/main"
[ -d "$here/../shared" ] && bind "$here/../shared" "$root/work/shared" -o ro

timed() {  # timed LABEL COMMAND: runs it in the chroot, prints its seconds
  local start=$SECONDS
  if chroot "$root" /bin/bash -c "export NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt
      cd /work/main && $2" > "$work/$1.log" 2>&1; then
    printf 'fresh_machine: %-22s %5d s\n' "$1" $(( SECONDS - start ))
  else
    printf 'fresh_machine: %-22s FAILED after %d s (see %s)\n' "$1" $(( SECONDS - start )) \
      "$work/$1.log"
    exit 1
  fi
}
all=$SECONDS
timed deps-demo "make deps-demo"
timed demo "make demo"
printf 'fresh_machine: %-22s %5d s (report: %s)\n' "fresh clone to report" $(( SECONDS - all )) \
  "$root/work/main/demo-out/align/report.html"
if [ "${FULL:-0}" = 1 ]; then
  timed install-deps-full "./scripts/install-deps.sh"
fi
