#!/usr/bin/env bash
# A single-node Slurm cluster on this machine for the tests, from Debian's slurmctld, slurmd and
# munge packages: its own munge key and socket, slurm.conf, spool and state in one short folder,
# every daemon on loopback (the address of this machine's name) on free ports, no accounting,
# no cgroups.
#
#   cluster.sh start DIR   DIR must not exist and be short (Unix socket paths hold 108 bytes);
#                          prints nothing on success; exit 1 with the reason when the cluster
#                          cannot start (its logs are printed).
#   cluster.sh stop DIR    cancels this cluster's jobs and stops its daemons by their pids.
#   cluster.sh env DIR     prints `export SLURM_CONF=...` for the clients (sbatch, scontrol).
#
# Several such clusters (other tests, other users) can run at once: nothing is shared but the
# programs.
set -uo pipefail

die() {
  echo "cluster.sh: $*" >&2
  exit 1
}

[[ $# -eq 2 ]] || die "usage: cluster.sh start|stop|env DIR"
action=$1
dir=$2

show_logs() {
  local f
  for f in "$dir"/log/*.log; do
    [[ -s $f ]] || continue
    echo "---- $f (last lines)" >&2
    tail -n 15 "$f" >&2
  done
}

stop_pid_file() {
  local file=$1 pid i
  [[ -s $file ]] || return 0
  pid=$(cat "$file")
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for i in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -KILL "$pid" 2>/dev/null
}

case $action in
env)
  echo "export SLURM_CONF=$dir/slurm.conf"
  exit 0
  ;;
stop)
  [[ -d $dir ]] || exit 0
  if [[ -s $dir/pids/slurmctld ]]; then
    SLURM_CONF=$dir/slurm.conf timeout 10 scancel --full --user="$(id -un)" 2>/dev/null
    sleep 0.5
  fi
  stop_pid_file "$dir/pids/slurmd"
  stop_pid_file "$dir/pids/slurmctld"
  stop_pid_file "$dir/pids/munged"
  exit 0
  ;;
start) ;;
*) die "unknown action '$action' (start, stop or env)" ;;
esac

for program in munged mungekey slurmctld slurmd sbatch scontrol scancel; do
  command -v "$program" >/dev/null || die "cannot start the cluster: '$program' is not installed (bash tools/setup.sh installs munge, slurmctld, slurmd and slurm-client)"
done
[[ ! -e $dir ]] || die "$dir exists already"
# The longest socket path below is $dir/spool/slurmd/<node>_<job>.<step> style; keep 40 bytes
# of room under the 108-byte limit.
((${#dir} <= 60)) || die "cannot start the cluster: '$dir' is ${#dir} bytes long; Unix socket paths below it would exceed 108 bytes (use a folder of at most 60 bytes)"
mkdir -p "$dir"/{munge,log,pids,spool/ctld,spool/slurmd} || die "cannot create $dir"
dir=$(cd "$dir" && pwd)
# munged refuses a socket folder that others cannot traverse.
chmod 711 "$dir" "$dir/munge"
mungekey --create --keyfile="$dir/munge/munge.key" >/dev/null 2>&1 ||
  die "cannot start the cluster: mungekey could not create a key"

# With NoCtldInAddrAny and NoInAddrAny each daemon binds to the address this machine's name
# resolves to, not to every address: 127.0.0.1 on some machines, 127.0.1.1 on an installed
# Debian (its /etc/hosts). The daemons are told that same address, which must be loopback.
host=$(hostname)
addr=$(getent ahostsv4 "$host" | awk 'NR == 1 { print $1 }')
[[ $addr == 127.* ]] || die "cannot start the cluster: this machine's name '$host' resolves to '${addr:-nothing}', not a loopback address (127.x.x.x); the test cluster listens on loopback only"

# Two free TCP ports on that address (bound then released: a small race with other programs).
read -r ctld_port slurmd_port < <(/usr/bin/python3 - "$addr" <<'EOF'
import socket, sys
s = [socket.socket() for _ in range(2)]
for x in s: x.bind((sys.argv[1], 0))
print(*[x.getsockname()[1] for x in s])
EOF
)
[[ -n ${slurmd_port:-} ]] || die "cannot start the cluster: no free port on $addr"

node=tn$ctld_port
# The node must describe this machine as slurmd sees it, or it registers as invalid.
hw=$(slurmd -C | head -n 1 | sed -e 's/^NodeName=[^ ]* //' -e 's/ *UpTime=.*//')
[[ $hw == *CPUs=* ]] || die "cannot start the cluster: 'slurmd -C' printed no hardware line"
user=$(id -un)

cat >"$dir/slurm.conf" <<EOF
ClusterName=tactile$ctld_port
SlurmctldHost=$host($addr)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/sock
StateSaveLocation=$dir/spool/ctld
SlurmdSpoolDir=$dir/spool/slurmd
SlurmctldPidFile=$dir/pids/slurmctld.conf
SlurmdPidFile=$dir/pids/slurmd.conf
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
ReturnToService=2
MpiDefault=none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=2
MinJobAge=600
MaxArraySize=1001
NodeName=$node NodeAddr=$addr NodeHostname=$host $hw State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF

# Daemons get no terminal: a test's output pipes would otherwise stay open until they stop.
munged --foreground --socket="$dir/munge/sock" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
  --seed-file="$dir/munge/seed" --force </dev/null >>"$dir/log/munged.out.log" 2>&1 &
echo $! >"$dir/pids/munged"
for i in $(seq 50); do
  [[ -S $dir/munge/sock ]] && break
  sleep 0.1
done
[[ -S $dir/munge/sock ]] || {
  show_logs
  bash "$0" stop "$dir"
  die "cannot start the cluster: munged made no socket in 5 s"
}

export SLURM_CONF=$dir/slurm.conf
slurmctld -D -f "$dir/slurm.conf" -i </dev/null >>"$dir/log/slurmctld.out.log" 2>&1 &
echo $! >"$dir/pids/slurmctld"
slurmd -D -N "$node" -f "$dir/slurm.conf" </dev/null >>"$dir/log/slurmd.out.log" 2>&1 &
echo $! >"$dir/pids/slurmd"

# Ready when the node is idle (about 1 s; 30 s allowed on a busy machine).
for i in $(seq 300); do
  state=$(timeout 5 sinfo -h -n "$node" -o %t 2>/dev/null)
  [[ $state == idle ]] && exit 0
  for d in munged slurmctld slurmd; do
    kill -0 "$(cat "$dir/pids/$d")" 2>/dev/null || {
      show_logs
      bash "$0" stop "$dir"
      die "cannot start the cluster: $d exited during start-up (logs above)"
    }
  done
  sleep 0.1
done
show_logs
bash "$0" stop "$dir"
die "cannot start the cluster: node $node not idle after 30 s (state '${state:-unknown}', logs above)"
