#!/usr/bin/env bash
# Makes sure the Debian packages a make target needs are installed.
# Usage: scripts/deps.sh test|demo|bench
# As root it installs what is missing; otherwise it prints the one command to
# run and exits 1. Header-only use needs none of this: only libc and libm.
set -u
case "${1:-test}" in
  test)  pkgs="gcc g++ clang make pkg-config libclang-rt-14-dev libembree-dev libopenimageio-dev libboost-dev libgsl-dev locales" ;;
  demo)  pkgs="gcc g++ make libembree-dev libopenimageio-dev" ;;
  bench) pkgs="gcc g++ clang make libembree-dev libopenimageio-dev libboost-dev libgsl-dev gnuplot-nox" ;;
  fuzz)  pkgs="clang libclang-rt-14-dev" ;;
  *) echo "deps.sh: unknown target '$1' (use test, demo, bench or fuzz)"; exit 2 ;;
esac
missing=""
for p in $pkgs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if ! command -v apt-get >/dev/null 2>&1; then
  echo "filigree: missing packages:$missing (this is not a Debian machine: install their equivalents)"; exit 1
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "filigree: missing packages. Run: sudo apt-get install -y$missing"; exit 1
fi
echo "filigree: installing$missing" >&2
export DEBIAN_FRONTEND=noninteractive
{ apt-get update -qq && apt-get install -y -qq --no-install-recommends $missing; } > build_deps.log 2>&1 \
  || { echo "filigree: apt-get install$missing failed; see build_deps.log"; exit 1; }
rm -f build_deps.log
