#!/usr/bin/env bash
# `tactile experiment --slurm` on a real single-node Slurm cluster (cluster.sh), label `cluster`.
#
#   experiment_test.sh TACTILE grid       a 12-cell grid through --slurm --submit; the merged
#                                         rows equal the one-machine run's (timing aside)
#   experiment_test.sh TACTILE resubmit   one array task cancelled and one cell failing: the
#                                         merge does not run, --merge --status says why, and a
#                                         resubmission runs only the cells not done
#
# When the cluster cannot start, the test fails saying why: it never passes without a cluster.
set -uo pipefail

tactile=$1
mode=$2
here=$(cd "$(dirname "$0")" && pwd)
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# Short: Slurm's Unix sockets live below it.
work=$(mktemp -d /tmp/tce.XXXXXX) || fail "cannot make a temporary folder in /tmp"
cleanup() {
  bash "$here/cluster.sh" stop "$work/c"
  if [[ ${TACTILE_KEEP_TEST_DIRS:-0} == 1 ]]; then
    echo "kept $work"
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT

bash "$here/cluster.sh" start "$work/c" ||
  fail "the single-node Slurm cluster did not start (reason above); the cluster tests need munge, slurmctld, slurmd and slurm-client (tools/setup.sh)"
export SLURM_CONF=$work/c/slurm.conf

# 1 source x 2 layouts x 3 methods x 2 gains = 12 cells of a few milliseconds each.
cat >"$work/exp.json" <<'EOF'
{"name": "grid", "seed": 1,
 "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
 "layouts": ["stress", "latero"], "methods": ["integrated", "profile", "proportional"],
 "parameters": {"rate_hz": 100, "gain_um_per_strain": [500, 1000]}}
EOF

"$tactile" experiment "$work/exp.json" --out "$work/local" --quiet >"$work/local.log" 2>&1 ||
  fail "the one-machine run failed: $(cat "$work/local.log")"

# The metrics rows without the comment line and the timing column (the last).
rows() { grep -v '^#' "$1/metrics.csv" | sed 's/,[^,]*$//'; }

# Waits for job $1 to leave the queue (90 s at most); prints its final state.
final_state() {
  local state i
  for i in $(seq 900); do
    state=$(scontrol show job -o "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | head -n 1)
    state=${state#JobState=}
    case $state in
    PENDING | RUNNING | CONFIGURING | COMPLETING | SUSPENDED | "") sleep 0.1 ;;
    *)
      echo "$state"
      return 0
      ;;
    esac
  done
  echo "TIMEOUT(${state:-unknown})"
}

job_of() { sed -n "s/^$1 job \([0-9]*\)$/\1/p" "$2"; }

attempts() { sed -n 's/.*"attempts": \([0-9]*\).*/\1/p' "$1/status.json"; }

case $mode in
grid)
  "$tactile" experiment "$work/exp.json" --out "$work/s" --slurm --submit --max-parallel 2 \
    --cells-per-task 3 --time 5 >"$work/submit.log" 2>&1 || fail "--slurm --submit failed: $(cat "$work/submit.log")"
  cat "$work/submit.log"
  grep -q "12 of 12 cells to run in 4 array tasks" "$work/submit.log" || fail "expected 12 cells in 4 tasks"
  merge=$(job_of merge "$work/submit.log")
  [[ -n $(job_of cells "$work/submit.log") && -n $merge ]] || fail "no job ids printed"
  state=$(final_state "$merge")
  [[ $state == COMPLETED ]] || fail "merge job $merge ended $state; logs: $(cat "$work"/s/slurm/logs/* 2>/dev/null)"
  diff <(rows "$work/local") <(rows "$work/s") || fail "merged rows differ from the one-machine run"
  [[ $(rows "$work/s" | wc -l) == 13 ]] || fail "expected a header and 12 rows"
  "$tactile" experiment "$work/exp.json" --out "$work/s" --merge --status >"$work/status.log" ||
    fail "--merge --status failed"
  grep -q "12 cells: 12 done, 0 running, 0 failed, 0 missing" "$work/status.log" ||
    fail "status: $(cat "$work/status.log")"
  # The merge killed (here: its files removed) is made again by a resubmission with nothing
  # left to run: the printed command, as a person pastes it, submits the merge alone.
  rm "$work/s/metrics.csv"
  "$tactile" experiment "$work/exp.json" --out "$work/s" --slurm >"$work/again.log" 2>&1 ||
    fail "--slurm with every cell done failed: $(cat "$work/again.log")"
  grep -q "0 of 12 cells to run in 0 array tasks" "$work/again.log" || fail "$(cat "$work/again.log")"
  command=$(grep '^sbatch ' "$work/again.log")
  [[ $command == "sbatch --parsable $work/s/slurm/merge.sh" ]] || fail "printed '$command'"
  state=$(final_state "$(eval "$command")")
  [[ $state == COMPLETED && -s $work/s/metrics.csv ]] || fail "merge alone ended $state"
  diff <(rows "$work/local") <(rows "$work/s") || fail "merged rows differ after the merge alone"
  echo "PASS: 12 cells through Slurm merged to the one-machine rows; the merge alone resubmitted"
  ;;
resubmit)
  out=$work/r
  "$tactile" experiment "$work/exp.json" --out "$out" --slurm --max-parallel 1 --cells-per-task 3 \
    >"$work/plan.log" 2>&1 || fail "--slurm failed: $(cat "$work/plan.log")"
  # Cell 4 fails once: a folder stands where its movie goes.
  movie=$(awk -F'\t' '$1 == 4 {print $4}' "$out/manifest.tsv")
  mkdir -p "$out/movies/$movie.h5/in-the-way"
  # The array held, its last task (cells 9-11) cancelled before it runs, then released; the
  # merge depends on it as printed.
  array=$(sbatch --parsable --hold "$out/slurm/cells.sh") || fail "sbatch of the array failed"
  array=${array%%;*}
  scancel "${array}_3" || fail "scancel ${array}_3 failed"
  scontrol release "$array" || fail "scontrol release $array failed"
  merge=$(sbatch --parsable --dependency=afterok:"$array" "$out/slurm/merge.sh") ||
    fail "sbatch of the merge failed"
  state=$(final_state "$merge")
  [[ $state == CANCELLED ]] || fail "the merge after a failed array ended $state, not CANCELLED"
  # Every released task has ended when the merge is cancelled? Wait for the array too.
  for t in 0 1 2; do final_state "${array}_$t" >/dev/null; done
  "$tactile" experiment "$work/exp.json" --out "$out" --merge --status >"$work/status1.log" ||
    fail "--merge --status failed"
  cat "$work/status1.log"
  grep -q "12 cells: 8 done, 0 running, 1 failed, 3 missing" "$work/status1.log" ||
    fail "status after a failed cell and a cancelled task"
  grep -q "4 run-[0-9a-f]* ($movie): failed" "$work/status1.log" || fail "status names no failed cell 4"
  "$tactile" experiment "$work/exp.json" --out "$out" --merge >"$work/merge1.log" 2>&1
  [[ $? == 1 ]] || fail "--merge with cells not done must exit 1"
  grep -q "4 of 12 cells are not done" "$work/merge1.log" || fail "merge: $(cat "$work/merge1.log")"
  [[ ! -e $out/metrics.csv ]] || fail "an incomplete merge wrote metrics.csv"

  rm -r "$out/movies/$movie.h5"
  "$tactile" experiment "$work/exp.json" --out "$out" --slurm --submit --max-parallel 1 \
    --cells-per-task 3 >"$work/submit2.log" 2>&1 || fail "resubmission failed: $(cat "$work/submit2.log")"
  cat "$work/submit2.log"
  grep -q "4 of 12 cells to run in 2 array tasks" "$work/submit2.log" ||
    fail "the resubmission must run the 4 cells not done"
  state=$(final_state "$(job_of merge "$work/submit2.log")")
  [[ $state == COMPLETED ]] || fail "merge after resubmission ended $state"
  diff <(rows "$work/local") <(rows "$out") || fail "merged rows differ from the one-machine run"
  # Each cell ran once, but cell 4, which failed once; the cancelled task's cells ran once.
  while IFS=$'\t' read -r index id kind name inputs folder; do
    [[ $index =~ ^[0-9]+$ ]] || continue
    expected=1
    [[ $index == 4 ]] && expected=2
    [[ $(attempts "$out/$folder") == "$expected" ]] ||
      fail "cell $index was started $(attempts "$out/$folder") times, expected $expected"
  done <"$out/manifest.tsv"
  echo "PASS: a cancelled task and a failed cell, then only the 4 cells not done resubmitted"
  ;;
*) fail "unknown mode '$mode' (grid or resubmit)" ;;
esac
