#!/usr/bin/env bash
# Builds every libFuzzer target and runs them for SECONDS in total, split evenly: the firmware's
# frame decoder and each file reader (HDF5 strain and tactile movies, JSON layout, HJIF, calibration,
# pore-model and classifier-model files, recording CSV, pore marks, classifier labels CSV,
# experiment JSON with its ground-truth and synthetic scenes). Prints the executions per
# target and in all; exits 1 on a finding (its input is kept in build/release/tests/*fuzz*/).
#   bash tools/fuzz.sh 600
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: tools/fuzz.sh SECONDS}
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -ge 10 ]] || {
  echo "tools/fuzz.sh: SECONDS must be a whole number >= 10, got '$seconds'" >&2
  exit 2
}
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake --preset release >/dev/null
cmake --build --preset release --target firmware_fuzz reader_fuzz >/dev/null

build=build/release/tests
readers=(strain-movie tactile-movie layout-json hjif calibration-json pore-model-json
  classifier-model-json recording-csv pore-marks labels-csv experiment-json)
targets=(frame-decoder "${readers[@]}")
each=$((seconds / ${#targets[@]}))
((each >= 1)) || each=1
total=0
findings=0
for target in "${targets[@]}"; do
  if [[ $target == frame-decoder ]]; then
    dir=$build/fuzz/long
    fuzzer=$build/fuzz/frame_fuzz
    rm -rf "$dir" && mkdir -p "$dir/corpus" "$dir/seeds"
    "$build/fuzz/make_seeds" "$dir/seeds"
  else
    dir=$build/reader_fuzz/long-$target
    fuzzer=$build/reader_fuzz/reader_fuzz
    rm -rf "$dir" && mkdir -p "$dir/corpus" "$dir/seeds"
    TACTILE_FUZZ_READER=$target "$fuzzer" --write-seeds "$dir/seeds"
  fi
  # HDF5 1.10 leaks a few bytes on some damaged files: leak checks only where the library is ours.
  leaks=1
  timeout=10
  # Above the movie readers' own bound for a stalled HDF5 (10 s for a small file).
  [[ $target == *movie ]] && leaks=0 && timeout=20
  status=0
  ASAN_OPTIONS=detect_leaks=$leaks:allocator_may_return_null=1 TACTILE_FUZZ_READER=$target "$fuzzer" -max_total_time="$each" -timeout="$timeout" -rss_limit_mb=2048 \
    -detect_leaks=$leaks \
    -print_final_stats=1 -artifact_prefix="$dir/" "$dir/corpus" "$dir/seeds" >"$dir/log" 2>&1 ||
    status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log" | tail -1)
  runs=${runs:-0}
  total=$((total + runs))
  if ((status != 0)); then
    findings=$((findings + 1))
    printf '%-24s %12s executions in %d s  FINDING (log: %s)\n' "$target" "$runs" "$each" "$dir/log"
    grep -m3 -E 'ERROR|SUMMARY|==[0-9]+==|deadly|terminate' "$dir/log" | sed 's/^/    /' || true
  else
    printf '%-24s %12s executions in %d s\n' "$target" "$runs" "$each"
  fi
done
printf '%-24s %12s executions, %d finding(s)\n' "total" "$total" "$findings"
((findings == 0))
