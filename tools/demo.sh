#!/usr/bin/env bash
# Installs what is needed, builds the release configuration and runs `tactile demo` on the
# built-in scene. Extra arguments go to `tactile demo` (try --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target tactile
exec build/release/tools/tactile demo "$@"
