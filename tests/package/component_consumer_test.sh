#!/bin/sh
# Installs the movie library into a fresh prefix, builds the movie-only consumer against it with
# find_package(tactile COMPONENTS movie), runs it, and checks that neither its link line nor its
# executable's libraries name a GUI, USB or drawing library.
# usage: movie_consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR [LINK_FLAGS]
#   BUILD_DIR is installed whole. BUILD_DIR given as shared:SOURCE_DIR instead configures a
#   BUILD_SHARED_LIBS=ON build of SOURCE_DIR, builds tactile_movie alone (and common, which it
#   uses), installs those two components only, and checks that the consumer loads the installed
#   libtactile_movie.so: a shared build, its install and its RPATHs, for the cost of a configure
#   and the two libraries' sources.
set -eu
build=$1 src=$2 work=$3 link_flags=${4:-}
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
case $build in
  shared:*)
    # Both libraries found, and found in the installation (not in the build tree).
    for lib in libtactile_movie.so libtactile_common.so; do
      if ! grep "$lib" "$work/ldd.txt" | grep -q "$work/prefix/"; then
        echo "movie_consumer does not load $lib from $work/prefix:" >&2
        cat "$work/ldd.txt" >&2
        exit 1
      fi
    done
    echo "movie_consumer: links the shared tactile::movie installed alone, loads no GUI, USB or drawing library"
    ;;
  *) echo "movie_consumer: links and loads no GUI, USB or drawing library" ;;
esac
