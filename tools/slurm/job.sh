#!/usr/bin/env bash
# One job of tools/slurm/render.sh. sbatch runs a copy of this file on a node, so it knows only its
# arguments (absolute paths, on a file system every node shares):
#
#   job.sh shard VKPATH SCENE SPP SHARDS WORK [vkpath render options...]
#       element $SLURM_ARRAY_TASK_ID = i of the job array: renders samples
#       [i*SPP/SHARDS, (i+1)*SPP/SHARDS) into the partial file WORK/shard-i.exr
#   job.sh merge VKPATH WORK SHARDS EXPOSURE OUT...
#       merges WORK/shard-0.exr ... WORK/shard-(SHARDS-1).exr into every OUT (PNG: at EXPOSURE)
#
# lavapipe renders with LP_NUM_THREADS threads: as many as the CPUs Slurm gave the job.
set -euo pipefail
die() { echo "job: $*" >&2; exit 1; }
export LP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}
mode=${1:-}
shift || true
case "$mode" in
  shard)
    [ $# -ge 5 ] || die "usage: job.sh shard VKPATH SCENE SPP SHARDS WORK [options...]"
    vkpath=$1 scene=$2 spp=$3 shards=$4 work=$5
    shift 5
    i=${SLURM_ARRAY_TASK_ID:?job.sh shard runs as an element of a job array}
    a=$((i * spp / shards))
    b=$(((i + 1) * spp / shards))
    echo "shard $i of $shards: samples $a:$b of $spp on $(hostname) (job ${SLURM_JOB_ID:-?}, LP_NUM_THREADS=$LP_NUM_THREADS)"
    exec "$vkpath" render "$scene" "$@" --sample-range "$a:$b" --partial "$work/shard-$i.exr" --quiet
    ;;
  merge)
    [ $# -ge 5 ] || die "usage: job.sh merge VKPATH WORK SHARDS EXPOSURE OUT..."
    vkpath=$1 work=$2 shards=$3 exposure=$4
    shift 4
    parts=()
    for ((i = 0; i < shards; i++)); do parts+=("$work/shard-$i.exr"); done
    outputs=()
    for out in "$@"; do outputs+=(-o "$out"); done
    echo "merge of $shards shards on $(hostname) (job ${SLURM_JOB_ID:-?}) into $*"
    exec "$vkpath" merge "${parts[@]}" "${outputs[@]}" --exposure "$exposure" --quiet
    ;;
  *) die "usage: job.sh shard|merge ... (a job of tools/slurm/render.sh)" ;;
esac
