#!/usr/bin/env bash
# Builds every libFuzzer target and runs them for SECONDS of wall time, one per core at a time,
# each target for the same share: the firmware's frame decoder and each file reader (HDF5 strain
# and tactile movies, JSON layout, HJIF, calibration, pore-model and classifier-model files,
# recording CSV, pore marks, classifier labels CSV, experiment JSON with its ground-truth and
# synthetic scenes). Prints the executions per target and in all, and the load average (the
# count depends on the CPU the machine spares); exits 1 on a finding (its input is kept in
# build/release/tests/*fuzz*/).
#   bash tools/fuzz.sh 600
# Or a number of executions instead of a time, for the named targets (all when none is named),
# one after another on one core, each in its own folder as above:
#   bash tools/fuzz.sh --runs 10000000 hjif pore-marks
# Overnight, every fast reader past 10^7 executions: `bash tools/fuzz.sh 36000` (10 h) gives each
# of the 12 targets 6000 s of one core on a 2-core machine. Measured on such a machine (clang's
# libFuzzer with ASan and UBSan, 10 s a fast reader and 15 s a movie reader, load about 1):
# labels CSV 11000 executions a second, pore marks 8800, classifier model 5000, calibration
# 4400, pore model 4400, experiment 4000, HJIF 1800 (so at least 1.08 x 10^7 each in 6000 s if
# the rates hold as the corpus grows; they fall somewhat), the movie readers 280 (one reading
# child for all inputs; 30 when they forked one per input).
set -euo pipefail
cd "$(dirname "$0")/.."
usage="usage: tools/fuzz.sh SECONDS | tools/fuzz.sh --runs N [TARGET...]"
runs=""
if [[ ${1:-} == --runs ]]; then
  runs=${2:-}
  [[ "$runs" =~ ^[0-9]+$ && "$runs" -ge 1 ]] || {
    echo "tools/fuzz.sh: --runs must be a whole number >= 1, got '$runs'" >&2
    exit 2
  }
  shift 2
  seconds=0
else
  seconds=${1:?$usage}
  [[ "$seconds" =~ ^[0-9]+$ && "$seconds" -ge 10 ]] || {
    echo "tools/fuzz.sh: SECONDS must be a whole number >= 10, got '$seconds'" >&2
    exit 2
  }
  shift
fi
build=build/release/tests
readers=(strain-movie tactile-movie layout-json hjif calibration-json pore-model-json
  classifier-model-json recording-csv pore-marks labels-csv experiment-json)
targets=(frame-decoder "${readers[@]}")
if (($# > 0)); then
  for t in "$@"; do
    [[ " ${targets[*]} " == *" $t "* ]] || {
      echo "tools/fuzz.sh: unknown target '$t' (targets: ${targets[*]})" >&2
      exit 2
    }
  done
  targets=("$@")
fi
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake --preset release >/dev/null
cmake --build --preset release --target firmware_fuzz reader_fuzz >/dev/null

# One fuzzer per core at a time (libFuzzer's loop is single-threaded), in rounds; every target
# gets the same share of the wall time, so SECONDS is spent on each core.
jobs=$(nproc)
((jobs > ${#targets[@]})) && jobs=${#targets[@]}
[[ -n $runs ]] && jobs=1
rounds=$(((${#targets[@]} + jobs - 1) / jobs))
each=$((seconds / rounds))
((each >= 1)) || each=1
# libFuzzer's bound: a wall time, or a count of executions (then no time limit).
limit=(-max_total_time="$each")
[[ -n $runs ]] && limit=(-runs="$runs")

dir_of() {
  if [[ $1 == frame-decoder ]]; then echo "$build/fuzz/long"; else echo "$build/reader_fuzz/long-$1"; fi
}

# Runs one target to its bound; its log is $dir/log, its exit status $dir/status, its wall
# time in seconds $dir/seconds.
fuzz_one() {
  local target=$1 dir fuzzer leaks=1 timeout=10 asan=allocator_may_return_null=1 status=0
  dir=$(dir_of "$target")
  rm -rf "$dir" && mkdir -p "$dir/corpus" "$dir/seeds"
  if [[ $target == frame-decoder ]]; then
    fuzzer=$build/fuzz/frame_fuzz
    "$build/fuzz/make_seeds" "$dir/seeds"
  else
    fuzzer=$build/reader_fuzz/reader_fuzz
    TACTILE_FUZZ_READER=$target "$fuzzer" --write-seeds "$dir/seeds"
  fi
  if [[ $target == *movie ]]; then
    # HDF5 1.10 leaks a few bytes on some damaged files: leak checks only where the library is
    # ours. Above the movie readers' own bound for a stalled HDF5 (10 s for a small file).
    leaks=0
    timeout=20
    # The movie readers' reading child is forked again after every input that crashed it, and a
    # fork copies the page tables of everything the process has touched: AddressSanitizer's
    # quarantine of freed memory (256 MB by default) made each fork several times dearer. 16 MB
    # still holds the frees of many inputs for use-after-free checks.
    asan+=:quarantine_size_mb=16
  fi
  # A count of executions is for long runs beside other work, at a low priority: libFuzzer's
  # bound on one input is wall time, and a process starved of the CPU for seconds by others
  # then reports a slow input that is not (a pore-marks input reported at 14 s ran in 0.7 s
  # alone). Six times the bound still stops a real hang.
  [[ -n $runs ]] && timeout=$((timeout * 6))
  local start=$SECONDS
  ASAN_OPTIONS=detect_leaks=$leaks:$asan TACTILE_FUZZ_READER=$target "$fuzzer" \
    "${limit[@]}" -timeout="$timeout" -rss_limit_mb=2048 -detect_leaks=$leaks \
    -print_final_stats=1 -artifact_prefix="$dir/" "$dir/corpus" "$dir/seeds" >"$dir/log" 2>&1 ||
    status=$?
  echo "$status" >"$dir/status"
  echo $((SECONDS - start)) >"$dir/seconds"
}

running=0
for target in "${targets[@]}"; do
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$target" &
  running=$((running + 1))
done
wait || true

if [[ -n $runs ]]; then
  echo "$(nproc) core(s), one fuzzer at a time, $runs executions per target; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
else
  echo "$(nproc) core(s), $jobs fuzzer(s) at a time, $each s per target; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
fi
total=0
findings=0
for target in "${targets[@]}"; do
  dir=$(dir_of "$target")
  done_runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log" | tail -1)
  done_runs=${done_runs:-0}
  total=$((total + done_runs))
  took=$(cat "$dir/seconds" 2>/dev/null || echo "$each")
  ((took >= 1)) || took=1
  status=$(cat "$dir/status" 2>/dev/null || echo 1)
  if ((status != 0)); then
    findings=$((findings + 1))
    printf '%-24s %12s executions in %d s  FINDING (log: %s)\n' "$target" "$done_runs" "$took" "$dir/log"
    grep -m3 -E 'ERROR|SUMMARY|==[0-9]+==|deadly|terminate' "$dir/log" | sed 's/^/    /' || true
  else
    printf '%-24s %12s executions in %d s (%d a second)\n' "$target" "$done_runs" "$took" \
      $((done_runs / took))
  fi
done
printf '%-24s %12s executions, %d finding(s)\n' "total" "$total" "$findings"
((findings == 0))
