#!/usr/bin/env bash
# Starts a private one-node Slurm cluster on this machine (Debian 12's slurmctld, slurmd, munge;
# tools/deps.sh --farm installs them), for tests and trying tools/slurm/render.sh without a cluster.
#
#   tools/slurm/cluster-up.sh [--cpus N] [--port P] [DIR]
#   out=$(tools/slurm/cluster-up.sh DIR) && eval "$out"   # sets SLURM_CONF (sbatch, squeue, ...)
#   tools/slurm/cluster-down.sh DIR                        # stops the daemons, removes DIR
#
# Everything lives in DIR (default: a new folder from mktemp -d; it must not exist or be empty):
# slurm.conf, the controller's state, slurmd's spool, PID files, logs, and a munged of its own
# with its own key and socket. Nothing under /etc, /run or /var is read or written, so a real
# Slurm or munge on the machine is left alone. Needs root (SlurmUser=root; munged runs as user
# munge). The node gets N CPUs (default and at most: nproc); the controller listens on port P and
# slurmd on P+1 (default: a free pair picked at random in 20000-59999). Keep DIR's path short:
# munge's socket lives in it (a socket path has at most 107 bytes).
# Prints the environment to use on stdout (`export SLURM_CONF=...`), everything else on stderr.
# On failure it stops what it started, prints the end of the daemons' logs and removes DIR.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
die() { echo "cluster-up: $*" >&2; exit 1; }

cpus=$(nproc)
port=
dir=
while [ $# -gt 0 ]; do
  case "$1" in
    --cpus) [ $# -ge 2 ] || die "--cpus needs a number"; cpus=$2; shift 2 ;;
    --port) [ $# -ge 2 ] || die "--port needs a number"; port=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) [ -z "$dir" ] || die "one folder only (got '$dir' and '$1')"; dir=$1; shift ;;
  esac
done
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || die "--cpus must be a positive integer, got '$cpus'"
[ "$cpus" -le "$(nproc)" ] || die "--cpus $cpus exceeds this machine's $(nproc) CPUs (the node would be INVAL)"
[ "$(id -u)" -eq 0 ] || die "needs root (SlurmUser=root, munged runs as user munge)"
for tool in munged slurmctld slurmd sbatch scontrol sinfo runuser; do
  command -v "$tool" >/dev/null || die "'$tool' not found: install Slurm with tools/deps.sh --farm"
done
id munge >/dev/null 2>&1 || die "no user 'munge': install Slurm with tools/deps.sh --farm"

# A port is in use when something listens on it (ss, from iproute2; without it: a connection).
port_in_use() {
  if command -v ss >/dev/null; then
    ss -Htln "( sport = :$1 )" 2>/dev/null | grep -q .
  else
    (exec 3<> "/dev/tcp/127.0.0.1/$1") 2>/dev/null
  fi
}
if [ -z "$port" ]; then
  for _ in $(seq 50); do
    p=$((20000 + (RANDOM * 32768 + RANDOM) % 40000))
    if ! port_in_use "$p" && ! port_in_use $((p + 1)); then port=$p; break; fi
  done
  [ -n "$port" ] || die "found no free pair of TCP ports in 20000-59999"
fi
if ! [[ "$port" =~ ^[1-9][0-9]*$ ]] || [ "$port" -ge 65535 ]; then die "--port must be in 1-65534, got '$port'"; fi

if [ -z "$dir" ]; then
  dir=$(mktemp -d "${TMPDIR:-/tmp}/vkpath-slurm.XXXXXX")
else
  mkdir -p "$dir"
  [ -z "$(ls -A "$dir")" ] || die "$dir is not empty (a cluster already there? tools/slurm/cluster-down.sh $dir)"
fi
dir=$(cd "$dir" && pwd)
case "$dir" in *[[:space:]]*) rmdir "$dir"; die "the folder's path must have no spaces (slurm.conf): $dir" ;; esac
[ ${#dir} -le 80 ] || { rmdir "$dir"; die "the folder's path is too long for munge's socket (${#dir} > 80 bytes): $dir"; }

# From here on a failure stops whatever started and removes the folder.
started=0
fail_cleanup() {
  local rc=$?
  if [ "$started" -eq 1 ] && [ "$rc" -ne 0 ]; then
    for log in "$dir"/log/*.log "$dir"/munge/munged.log; do
      [ -s "$log" ] && { echo "--- end of $log" >&2; tail -n 15 "$log" >&2; }
    done
    "$here/cluster-down.sh" "$dir" >&2 || true
  fi
}
trap fail_cleanup EXIT
started=1

chmod 0755 "$dir"   # munged (user munge) must reach its socket below it
mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/munge"
chown munge:munge "$dir/munge"
chmod 0755 "$dir/munge"
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chown munge:munge "$dir/munge/munge.key"
chmod 0600 "$dir/munge/munge.key"

host=$(hostname -s)
node=vkpnode
cat > "$dir/slurm.conf" <<EOF
# A private one-node cluster written by tools/slurm/cluster-up.sh; stop it with cluster-down.sh.
ClusterName=vkpathfarm
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# Finished jobs leave the controller after 5 s, and sbatch --wait then polls every 2 s (it
# lengthens its polls up to 32 s only while they stay under MinJobAge/2); jobs start at once.
MinJobAge=5
SchedulerParameters=batch_sched_delay=0
NodeName=$node NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=farm Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
: > "$dir/plugstack.conf"
export SLURM_CONF=$dir/slurm.conf

t0=$(date +%s.%N)
runuser -u munge -- munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
  --seed-file="$dir/munge/munged.seed" || die "munged did not start (log: $dir/munge/munged.log)"
slurmctld -c || die "slurmctld did not start (log: $dir/log/slurmctld.log)"
slurmd -N "$node" || die "slurmd did not start (log: $dir/log/slurmd.log)"

# Wait for the node to be idle; a node left DOWN or DRAINED (a previous state, a slow first
# registration) is resumed.
# A daemon is dead once its PID file names a process that is gone or a zombie (no file yet: it is
# still starting).
alive() {
  local pid
  [ -s "$1" ] || return 0
  pid=$(tr -dc 0-9 < "$1")
  [ -r "/proc/$pid/stat" ] && [ "$(awk '{ print $3 }' "/proc/$pid/stat" 2>/dev/null)" != Z ]
}
state=
for _ in $(seq 150); do
  alive "$dir/slurmctld.pid" || die "slurmctld exited (log: $dir/log/slurmctld.log)"
  alive "$dir/slurmd.pid" || die "slurmd exited (log: $dir/log/slurmd.log)"
  state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
  case "$state" in
    idle) break ;;
    down*|drain*) scontrol update nodename="$node" state=resume 2>/dev/null || true ;;
  esac
  sleep 0.2
done
[ "$state" = idle ] || die "node $node is '${state:-unknown}', not idle, after 30 s (logs in $dir/log)"
t1=$(date +%s.%N)
echo "cluster-up: one node ($cpus CPUs) idle after $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b-a}') s; ports $port,$((port + 1)); folder $dir" >&2
printf 'export SLURM_CONF=%q\n' "$SLURM_CONF"
