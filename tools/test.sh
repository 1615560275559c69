#!/usr/bin/env bash
# Installs what is needed, builds, and runs every test:
#   1. release build, all CTest labels (unit, e2e, ...);
#   2. RelWithDebInfo build with address + undefined-behaviour sanitizers, all labels again (of
#      the vm label only vm.play_libusb: tests/vm.cmake says why); its debug information is line
#      tables only (-g1, CMakePresets.json): a sanitizer's report still names each frame's file
#      and line, and a file compiles in about a fifth less time than with full debug information
#      (four of the heaviest: 13-22 s, was 17-28 s).
# Set TACTILE_SKIP_ASAN=1 to run only the first (quicker while developing).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
jobs=$(nproc)
# ccache keys on paths relative to the repository, so a fresh copy of the same sources (CI's)
# reuses what an earlier build in another folder compiled.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1

# Every label runs, `cluster` included: each of its tests starts a single-node Slurm cluster
# (tests/cluster/cluster.sh) and, when the cluster cannot start, fails saying why; CTest then
# lists it among the failed tests and this script exits non-zero.
echo "== release build and tests"
cmake --preset release >/dev/null
cmake --build --preset release -j"$jobs"
ctest --preset release -j"$jobs"

if [[ "${TACTILE_SKIP_ASAN:-0}" != 1 ]]; then
  echo "== sanitizer (address, undefined) build and tests"
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j"$jobs"
  ctest --preset asan -j"$jobs"
fi
