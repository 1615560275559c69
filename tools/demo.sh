#!/usr/bin/env bash
# Installs what is needed, builds the release configuration and runs `tactile demo` on the
# built-in scene. Extra arguments go to `tactile demo` (try --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
# As tools/test.sh: ccache keys on paths relative to the repository, so another copy of the same
# sources reuses what was compiled before.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target tactile
exec build/release/tools/tactile demo "$@"
