#!/bin/sh
# Installs the built project into a fresh prefix, builds the movie-only consumer against it with
# find_package(tactile COMPONENTS movie), runs it, and checks that neither its link line nor its
# executable's libraries name a GUI, USB or drawing library.
# usage: movie_consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR [LINK_FLAGS]
set -eu
build=$1 src=$2 work=$3 link_flags=${4:-}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS="$link_flags" > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
"$work/build/movie_consumer" "$work/movie.h5"
test -s "$work/movie.h5"
forbidden='glfw|libGL|imgui|usb|hidapi|cairo'
ninja -C "$work/build" -t commands movie_consumer | tail -n 1 > "$work/link.txt"
grep -q movie_consumer "$work/link.txt"
if grep -Eiq "$forbidden" "$work/link.txt"; then
  echo "movie_consumer link line names a GUI, USB or drawing library:" >&2
  cat "$work/link.txt" >&2
  exit 1
fi
ldd "$work/build/movie_consumer" > "$work/ldd.txt"
grep -q libstdc++ "$work/ldd.txt"
if grep -Ei "$forbidden" "$work/ldd.txt" >&2; then
  echo "movie_consumer depends on the libraries above" >&2
  exit 1
fi
echo "movie_consumer: links and loads no GUI, USB or drawing library"
