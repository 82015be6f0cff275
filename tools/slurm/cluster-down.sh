#!/usr/bin/env bash
# Stops the private cluster that tools/slurm/cluster-up.sh started in DIR and removes DIR; with
# --keep, DIR (logs, state) stays. Jobs still queued or running are cancelled first (up to 15 s for
# them to end), then slurmd, slurmctld and munged are stopped, then any job step daemon
# (slurmstepd) of this cluster that outlived slurmd.
#
#   tools/slurm/cluster-down.sh [--keep] DIR
#
# Each daemon is found by the PID file in DIR (read before signalling it: a daemon deletes its
# file as it exits) and signalled only if that process is still the daemon; SIGTERM, then SIGKILL
# after 10 s. Safe to run twice, or on a half-started cluster.
set -euo pipefail
die() { echo "cluster-down: $*" >&2; exit 1; }

keep=0
dir=
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=1; shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) [ -z "$dir" ] || die "one folder only (got '$dir' and '$1')"; dir=$1; shift ;;
  esac
done
[ -n "$dir" ] || die "usage: cluster-down.sh [--keep] DIR"
[ -d "$dir" ] || { echo "cluster-down: no folder $dir: nothing to stop" >&2; exit 0; }
dir=$(cd "$dir" && pwd)
[ -f "$dir/slurm.conf" ] || [ -z "$(ls -A "$dir")" ] ||
  die "$dir has no slurm.conf: not a folder of cluster-up.sh, left alone"

# running PID: the process exists and is not a zombie (one that exited, not yet reaped by init).
running() { [ -r "/proc/$1/stat" ] && [ "$(awk '{ print $3 }' "/proc/$1/stat" 2>/dev/null)" != Z ]; }

# stop NAME PIDFILE: SIGTERM to the daemon of PIDFILE if its command is NAME, SIGKILL after 10 s.
status=0
stop() {
  local name=$1 file=$2 pid
  [ -s "$file" ] || return 0
  pid=$(tr -dc 0-9 < "$file")
  [ -n "$pid" ] && [ -r "/proc/$pid/comm" ] || return 0
  [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for _ in $(seq 100); do
    running "$pid" || return 0
    sleep 0.1
  done
  echo "cluster-down: $name (pid $pid) ignored SIGTERM for 10 s; SIGKILL" >&2
  kill -KILL "$pid" 2>/dev/null || true
  status=1
}
# Cancel the cluster's jobs while the controller still runs, and wait for them to end.
if [ -s "$dir/slurmctld.pid" ] && command -v scancel >/dev/null; then
  export SLURM_CONF=$dir/slurm.conf
  jobs=$(timeout 10 squeue -h -o %F 2>/dev/null | sort -u | tr '\n' ' ' || true)
  if [ -n "${jobs// /}" ]; then
    echo "cluster-down: cancelling jobs $jobs" >&2
    # shellcheck disable=SC2086  # a list of job ids
    timeout 10 scancel $jobs 2>/dev/null || true
    for _ in $(seq 75); do
      [ -z "$(timeout 10 squeue -h -o %i 2>/dev/null || true)" ] && break
      sleep 0.2
    done
  fi
fi
stop slurmd "$dir/slurmd.pid"
stop slurmctld "$dir/slurmctld.pid"
stop munged "$dir/munge/munged.pid"
# Job step daemons of this cluster (their working folder is DIR/log) that outlived slurmd.
for p in /proc/[0-9]*; do
  [ "$(cat "$p/comm" 2>/dev/null)" = slurmstepd ] || continue
  case "$(readlink "$p/cwd" 2>/dev/null)" in
    "$dir"/*) echo "cluster-down: killing the leftover step daemon ${p#/proc/}" >&2
              kill -KILL "${p#/proc/}" 2>/dev/null || true; status=1 ;;
  esac
done

if [ "$keep" -eq 1 ]; then
  echo "cluster-down: daemons stopped; kept $dir" >&2
else
  rm -rf "$dir"
  echo "cluster-down: daemons stopped; removed $dir" >&2
fi
exit "$status"
