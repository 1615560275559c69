#!/bin/sh
# Installs the project (or some components of it) into a fresh prefix, builds a consumer that asks
# for some components with find_package(tactile COMPONENTS ...), runs it, and checks that neither
# its link line nor the libraries its executable loads match FORBIDDEN (an extended regex): a
# program that uses only those components links nothing more.
# usage: component_consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR OUTPUT FORBIDDEN
#                                   [LINK_FLAGS]
#   The consumer's program is named after CONSUMER_SOURCE_DIR and takes one output file, which
#   it must write, named OUTPUT in WORK_DIR. BUILD_DIR is installed whole. BUILD_DIR given as shared:SOURCE_DIR instead
#   configures a BUILD_SHARED_LIBS=ON build of SOURCE_DIR, builds tactile_movie alone (and
#   common, which it uses), installs those two components only, and checks that the consumer
#   loads the installed libtactile_movie.so: a shared build, its install and its RPATHs, for the
#   cost of a configure and the two libraries' sources.
set -eu
build=$1 src=$2 work=$3 output=$4 forbidden=$5 link_flags=${6:-}
program=$(basename "$src")
rm -rf "$work"
mkdir -p "$work"
case $build in
  shared:*)
    cmake -S "${build#shared:}" -B "$work/shared" -G Ninja -DCMAKE_BUILD_TYPE=Release \
          -DBUILD_SHARED_LIBS=ON -DTACTILE_BUILD_TESTS=OFF -DTACTILE_PYTHON=OFF \
          > "$work/shared-configure.log"
    cmake --build "$work/shared" --target tactile_movie > "$work/shared-build.log"
    for component in common movie; do
      cmake --install "$work/shared" --prefix "$work/prefix" --component $component \
            >> "$work/install.log"
    done
    ;;
  *) cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" ;;
esac
cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS="$link_flags" > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
"$work/build/$program" "$work/$output"
test -s "$work/$output"
ninja -C "$work/build" -t commands "$program" | tail -n 1 > "$work/link.txt"
grep -q "$program" "$work/link.txt"
if grep -Eq "$forbidden" "$work/link.txt"; then
  echo "$program: its link line names a library matching $forbidden:" >&2
  cat "$work/link.txt" >&2
  exit 1
fi
ldd "$work/build/$program" > "$work/ldd.txt"
grep -q libstdc++ "$work/ldd.txt"
if grep -E "$forbidden" "$work/ldd.txt" >&2; then
  echo "$program loads the libraries above (matching $forbidden)" >&2
  exit 1
fi
case $build in
  shared:*)
    # Both libraries found, and found in the installation (not in the build tree).
    for lib in libtactile_movie.so libtactile_common.so; do
      if ! grep "$lib" "$work/ldd.txt" | grep -q "$work/prefix/"; then
        echo "$program does not load $lib from $work/prefix:" >&2
        cat "$work/ldd.txt" >&2
        exit 1
      fi
    done
    echo "$program: links the shared libraries installed alone, loads nothing matching $forbidden"
    ;;
  *) echo "$program: links and loads nothing matching $forbidden" ;;
esac
