#!/usr/bin/env bash
# The reference render split into shards on a one-node Slurm cluster and merged equals the
# single render byte for byte (scripts/slurm/local-cluster.sh at a small size). Exits 77, which
# CTest reads as a skip, where Slurm, munge or root is missing: it installs nothing itself.
#
#   tests/slurm/slurm_cluster_test.sh [HMBLUR]     # default: $HMBLUR, else build/hmblur
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
export PATH=$PATH:/usr/sbin:/sbin

for c in sbatch squeue scontrol sinfo scancel slurmctld slurmd munged munge; do
  if ! command -v "$c" > /dev/null; then
    echo "skipped: no $c on PATH (Debian: apt-get install slurm-wlm munge)"
    exit 77
  fi
done
if ((EUID != 0)); then
  echo "skipped: starting slurmd needs root"
  exit 77
fi

hmblur=${1:-${HMBLUR:-$repo/build/hmblur}}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/hmb-slurm-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# Ports of its own, so that a cluster someone runs by hand does not collide with the test's.
if ! SLURMCTLD_PORT=${SLURMCTLD_PORT:-26817} SLURMD_PORT=${SLURMD_PORT:-26818} SLURM_WAIT_S=600 \
  HMBLUR=$hmblur "$repo/scripts/slurm/local-cluster.sh" --scene living-room --width 160 --height 90 \
  --spp 16 --shards 3 --results "$tmp/results" --work "$tmp/work"; then
  # The folder goes with the test: show what is in it.
  tail -n 40 "$tmp/results/jobs.log" "$tmp"/work/cluster-logs/*.log >&2 2> /dev/null || true
  exit 1
fi

if ! grep -q '"identical": true' "$tmp/results/timings.json"; then
  echo "slurm_cluster_test: the merged image differs from the single render" >&2
  exit 1
fi
echo "slurm_cluster_test: 3 shards merged equal the single render"
