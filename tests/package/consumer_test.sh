#!/bin/sh
# Installs the built project into a fresh prefix, configures and builds the consumer program
# against it with find_package(tactile) alone, and runs it on a strain movie.
# usage: consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR STRAIN_H5 [LINK_FLAGS]
# (LINK_FLAGS: the sanitizer flags when the installed libraries were built with them)
set -eu
build=$1 src=$2 work=$3 strain=$4 link_flags=${5:-}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
# Nothing of the source or build tree may leak in: only the prefix is given.
cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS="$link_flags" > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
"$work/build/consumer" "$strain" "$work/movie.h5"
test -s "$work/movie.h5"
