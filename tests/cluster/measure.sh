#!/usr/bin/env bash
# Measures a grid of 204 small cells on the single-node test cluster against the one-machine run:
#   bash tests/cluster/measure.sh TACTILE [CELLS_PER_TASK...]
# Prints the wall time of the local run and of each Slurm run (submission to merged), and the
# overhead per cell. Not a test: figures for docs/experiments.md.
set -uo pipefail
tactile=$(realpath "$1")
shift
sizes=("${@:-1}")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/tcm.XXXXXX)
trap 'bash "$here/cluster.sh" stop "$work/c"; rm -rf "$work"' EXIT
bash "$here/cluster.sh" start "$work/c" || exit 1
export SLURM_CONF=$work/c/slurm.conf
gains=$(seq -s, 100 100 3400)
cat >"$work/exp.json" <<EOF
{"name": "measure", "seed": 1,
 "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
 "layouts": ["stress", "latero"], "methods": ["integrated", "profile", "proportional"],
 "parameters": {"rate_hz": 100, "gain_um_per_strain": [$gains]}}
EOF
rows() { grep -v '^#' "$1/metrics.csv" | sed 's/,[^,]*$//'; }
t0=$(date +%s.%N)
"$tactile" experiment "$work/exp.json" --out "$work/local" --quiet --threads 2 | tail -n 1
t1=$(date +%s.%N)
cells=$(($(grep -c . "$work/local/manifest.tsv") - 3))
local_s=$(echo "$t1 - $t0" | bc -l)
printf 'local: %d cells, %.2f s wall (2 threads)\n' "$cells" "$local_s"
for n in "${sizes[@]}"; do
  out=$work/s$n
  t0=$(date +%s.%N)
  "$tactile" experiment "$work/exp.json" --out "$out" --slurm --submit --max-parallel 2 \
    --cells-per-task "$n" >"$work/submit$n.log" || exit 1
  merge=$(sed -n 's/^merge job //p' "$work/submit$n.log")
  while scontrol show job -o "$merge" | grep -qE 'JobState=(PENDING|RUNNING|COMPLETING|CONFIGURING)'; do
    sleep 0.1
  done
  t1=$(date +%s.%N)
  state=$(scontrol show job -o "$merge" | grep -o 'JobState=[A-Z]*')
  same=$(diff -q <(rows "$work/local") <(rows "$out") >/dev/null && echo "same rows" || echo "ROWS DIFFER")
  s=$(echo "$t1 - $t0" | bc -l)
  printf 'slurm --max-parallel 2 --cells-per-task %d: %.2f s wall, %s, %s, overhead %.3f s per cell\n' \
    "$n" "$s" "$state" "$same" "$(echo "($s - $local_s) / $cells" | bc -l)"
  "$tactile" experiment "$work/exp.json" --out "$out" --merge --status | sed -n '1,3p'
done
