#!/usr/bin/env bash
# Runs the sharded reference render on a one-node Slurm cluster started on this machine, and
# checks it against a single render: the array job (reference-array.sbatch), the merge after it
# (reference-merge.sbatch), then the same frame rendered whole; the merged EXR must equal it byte
# for byte. Writes the job logs, each shard's, the merge's and the single render's time, both
# images' sha256 and the machine to the results folder; the images stay in the work folder.
#
#   scripts/slurm/local-cluster.sh                                   # bistro 320x180, 256 spp, 4 shards
#   scripts/slurm/local-cluster.sh --scene living-room --width 160 --height 90 --spp 16 --shards 3 \
#       --results /tmp/r --work /tmp/w
#
# Options override the environment: SCENE (bistro), WIDTH (320), HEIGHT (180), SPP (256),
# SHARDS (4), RESULTS_DIR (bench/results/slurm-reference), WORK_DIR (a new folder under /tmp,
# kept; its out/ and logs/ are emptied first), HMBLUR (build/hmblur), CPUS_PER_TASK (nproc: one
# shard at a time, so that each shard's time compares with the single render's), SLURM_WAIT_S
# (3600: the jobs' deadline), SLURMCTLD_PORT and SLURMD_PORT (16817, 16818: clear of a system
# cluster's defaults).
#
# Needs root: slurmd runs jobs as their user. Installs Debian's slurm-wlm and munge when they
# are missing. The cluster's configuration, keys, state and logs live in a folder of its own
# under /tmp (munged wants a socket path every user can reach), never in /etc; every daemon
# started here is stopped when the script exits, however it exits, and their logs are copied to
# the work folder's cluster-logs/.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

SCENE=${SCENE:-bistro}
WIDTH=${WIDTH:-320}
HEIGHT=${HEIGHT:-180}
SPP=${SPP:-256}
SHARDS=${SHARDS:-4}
RESULTS_DIR=${RESULTS_DIR:-$repo/bench/results/slurm-reference}
WORK_DIR=${WORK_DIR:-}
HMBLUR=${HMBLUR:-$repo/build/hmblur}
CPUS_PER_TASK=${CPUS_PER_TASK:-$(nproc)}
SLURM_WAIT_S=${SLURM_WAIT_S:-3600}
SLURMCTLD_PORT=${SLURMCTLD_PORT:-16817}
SLURMD_PORT=${SLURMD_PORT:-16818}

die() {
  echo "local-cluster: $*" >&2
  exit 1
}

while (($# > 0)); do
  case $1 in
    --scene) SCENE=${2:?--scene needs a value}; shift 2 ;;
    --width) WIDTH=${2:?--width needs a value}; shift 2 ;;
    --height) HEIGHT=${2:?--height needs a value}; shift 2 ;;
    --spp) SPP=${2:?--spp needs a value}; shift 2 ;;
    --shards) SHARDS=${2:?--shards needs a value}; shift 2 ;;
    --results) RESULTS_DIR=${2:?--results needs a folder}; shift 2 ;;
    --work) WORK_DIR=${2:?--work needs a folder}; shift 2 ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
for n in WIDTH HEIGHT SPP SHARDS CPUS_PER_TASK SLURM_WAIT_S; do
  [[ ${!n} =~ ^[1-9][0-9]*$ ]] || die "$n must be a positive integer, not '${!n}'"
done

((EUID == 0)) || die "run as root: slurmd starts jobs as their user"
export PATH=$PATH:/usr/sbin:/sbin
# The Vulkan loader looks for a runtime folder; sbatch passes this on to the jobs.
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}

missing=0
for c in sbatch squeue scontrol sinfo scancel slurmctld slurmd munged munge; do
  command -v "$c" > /dev/null || missing=1
done
if ((missing)); then
  echo "local-cluster: installing slurm-wlm and munge"
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y slurm-wlm munge
fi

[[ -x $HMBLUR ]] || die "no hmblur at $HMBLUR (build it, or set HMBLUR)"
HMBLUR=$(readlink -f "$HMBLUR")  # the jobs run in other folders
if [[ -z $WORK_DIR ]]; then
  WORK_DIR=$(mktemp -d "${TMPDIR:-/tmp}/hmb-slurm-work.XXXXXX")
fi
mkdir -p "$WORK_DIR" "$RESULTS_DIR"
WORK_DIR=$(cd "$WORK_DIR" && pwd)
RESULTS_DIR=$(cd "$RESULTS_DIR" && pwd)
out=$WORK_DIR/out
logs=$WORK_DIR/logs
# Parts left from another run would be resumed, not rendered, and spoil the timings.
rm -rf "$out" "$logs" "$WORK_DIR/cluster-logs" "$WORK_DIR/single.exr" "$WORK_DIR/single.json"
mkdir -p "$out" "$logs"

for port in "$SLURMCTLD_PORT" "$SLURMD_PORT"; do
  if (exec 3<> "/dev/tcp/127.0.0.1/$port") 2> /dev/null; then
    die "port $port is taken (another cluster?); set SLURMCTLD_PORT and SLURMD_PORT"
  fi
done

cluster="" munged_pid="" slurmctld_pid="" slurmd_pid="" jobs=""

stop_pid() {  # TERM, then KILL after 20 s; a zombie counts as stopped
  local - pid=$1 i
  set +e
  [[ -n $pid ]] || return 0
  kill -TERM "$pid" 2> /dev/null || { wait "$pid" 2> /dev/null; return 0; }
  for ((i = 0; i < 100; i++)); do
    case $(ps -o stat= -p "$pid" 2> /dev/null) in
      "" | Z*) wait "$pid" 2> /dev/null; return 0 ;;
    esac
    sleep 0.2
  done
  kill -KILL "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  return 0
}

stop_cluster() {
  local - i ids
  set +e
  [[ -n $cluster ]] || return 0
  # Cancelled jobs first, while slurmd can still end their steps.
  if [[ -n $jobs && -n $slurmctld_pid ]]; then
    IFS=, read -ra ids <<< "$jobs"
    scancel "${ids[@]}" 2> /dev/null
    for ((i = 0; i < 150; i++)); do
      [[ -z $(squeue -h -j "$jobs" -o %i 2> /dev/null) ]] && break
      sleep 0.2
    done
  fi
  stop_pid "$slurmd_pid"
  stop_pid "$slurmctld_pid"
  stop_pid "$munged_pid"
  slurmd_pid="" slurmctld_pid="" munged_pid="" jobs=""
  mkdir -p "$WORK_DIR/cluster-logs"
  cp "$cluster"/log/* "$cluster/slurm.conf" "$WORK_DIR/cluster-logs/" 2> /dev/null
  rm -rf "$cluster"
  cluster=""
  return 0
}

trap 'set +e; stop_cluster' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

cluster=$(mktemp -d /tmp/hmb-slurm.XXXXXX)
chmod 755 "$cluster"
mkdir -p "$cluster/munge" "$cluster/state" "$cluster/spool" "$cluster/log"
chmod 755 "$cluster/munge"
munge_socket=$cluster/munge/munge.socket

dd if=/dev/urandom of="$cluster/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$cluster/munge/munge.key"
munged -F --key-file="$cluster/munge/munge.key" --socket="$munge_socket" \
  --pid-file="$cluster/munge/munged.pid" --seed-file="$cluster/munge/munged.seed" \
  > "$cluster/log/munged.log" 2>&1 &
munged_pid=$!
for ((i = 0; ; i++)); do
  munge -n -S "$munge_socket" 2> /dev/null | unmunge -S "$munge_socket" > /dev/null 2>&1 && break
  ((i < 50)) || { cat "$cluster/log/munged.log" >&2; die "munged did not start"; }
  sleep 0.2
done

node=$(hostname -s)
memory_mb=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
# Linux process tracking and no task plugin: no cgroup, which containers often lack. CR_CPU
# lets tasks share the node by CPU count alone. kill_invalid_depend cancels the merge when a
# shard fails, instead of leaving it pending for ever.
cat > "$cluster/slurm.conf" << EOF
ClusterName=hmblocal
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$SLURMCTLD_PORT
SlurmdPort=$SLURMD_PORT
AuthType=auth/munge
AuthInfo=socket=$munge_socket
CredType=cred/munge
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
DependencyParameters=kill_invalid_depend
ReturnToService=2
MinJobAge=3600
MpiDefault=none
MailProg=/bin/true
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$cluster/log/jobcomp.txt
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$cluster/slurm.conf

slurmctld -D -f "$SLURM_CONF" > "$cluster/log/slurmctld.log" 2>&1 &
slurmctld_pid=$!
slurmd -D -f "$SLURM_CONF" -N "$node" > "$cluster/log/slurmd.log" 2>&1 &
slurmd_pid=$!
for ((i = 0; ; i++)); do
  state=$(sinfo -h -N -n "$node" -o %T 2> /dev/null || true)
  case $state in
    idle) break ;;
    drain* | down*) scontrol update nodename="$node" state=resume 2> /dev/null || true ;;
  esac
  for d in slurmctld slurmd; do
    pid_var=${d}_pid
    kill -0 "${!pid_var}" 2> /dev/null || { tail -n 20 "$cluster/log/$d.log" >&2; die "$d exited"; }
  done
  ((i < 150)) || { tail -n 20 "$cluster/log/slurmctld.log" "$cluster/log/slurmd.log" >&2; die "node $node stayed '$state'"; }
  sleep 0.2
done
echo "local-cluster: node $node is up ($(nproc) CPUs); cluster files in $cluster"

now() { date +%s.%N; }
seconds_since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }'; }

export HMBLUR SCENE WIDTH HEIGHT SPP SHARDS OUT_DIR=$out
submitted=$(now)
array=$(sbatch --parsable --array=0-$((SHARDS - 1)) --cpus-per-task="$CPUS_PER_TASK" \
  --chdir="$WORK_DIR" --output="$logs/reference-%A_%a.out" "$here/reference-array.sbatch")
array=${array%%;*}
jobs=$array
merge=$(sbatch --parsable --dependency=afterok:"$array" --cpus-per-task="$CPUS_PER_TASK" \
  --chdir="$WORK_DIR" --output="$logs/reference-merge-%j.out" "$here/reference-merge.sbatch")
merge=${merge%%;*}
jobs=$array,$merge
echo "local-cluster: array job $array ($SHARDS shards of $SCENE ${WIDTH}x$HEIGHT, $SPP spp), merge job $merge"

deadline=$(($(date +%s) + SLURM_WAIT_S))
while [[ -n $(squeue -h -j "$jobs" -o %i 2> /dev/null) ]]; do
  (($(date +%s) < deadline)) || die "jobs $jobs still queued after $SLURM_WAIT_S s"
  sleep 1
done
slurm_seconds=$(seconds_since "$submitted")

# One "shard state exit" line per array task, then the merge's; read before the daemons stop.
job_states=$(
  scontrol -o show job "$array" | sed -n 's/.*ArrayTaskId=\([0-9]*\) .*JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\).*/shard-\1 \2 \3/p' | sort -V
  scontrol -o show job "$merge" | sed -n 's/.*JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\).*/merge \1 \2/p'
)
slurm_version=$(slurmctld -V)
munge_version=$(munged --version 2>&1 | head -n 1)
jobs=""
stop_cluster

failed=0
if grep -qv ' COMPLETED ' <<< "$job_states" || (($(wc -l <<< "$job_states") != SHARDS + 1)); then
  echo "local-cluster: a job did not complete:" >&2
  echo "$job_states" >&2
  failed=1
fi

single_seconds=""
if ((!failed)); then
  echo "local-cluster: rendering the frame whole"
  started=$(now)
  "$HMBLUR" --quiet render --scene "$SCENE" --method reference --width "$WIDTH" --height "$HEIGHT" \
    --spp "$SPP" --out "$WORK_DIR/single.exr" --report "$WORK_DIR/single.json" || failed=1
  single_seconds=$(seconds_since "$started")
fi

sha() { [[ -f $1 ]] && sha256sum "$1" | cut -d' ' -f1 || echo missing; }
merged_sha=$(sha "$out/merged.exr")
single_sha=$(sha "$WORK_DIR/single.exr")
identical=false
if ((!failed)) && cmp "$out/merged.exr" "$WORK_DIR/single.exr"; then
  identical=true
fi

# Results: small text only, with the work folder's path written as WORK.
anonymous() { sed "s|$WORK_DIR|WORK|g"; }
mkdir -p "$RESULTS_DIR/reports"
rm -f "$RESULTS_DIR"/reports/*.json
for f in "$out"/*.json "$WORK_DIR/single.json"; do
  [[ -f $f ]] && anonymous < "$f" > "$RESULTS_DIR/reports/$(basename "$f")"
done
shopt -s nullglob
job_logs=("$logs"/*)
if ((${#job_logs[@]} > 0)); then
  mapfile -t job_logs < <(printf '%s\n' "${job_logs[@]}" | sort -V)
fi
for f in ${job_logs[@]+"${job_logs[@]}"}; do
  echo "==> $(basename "$f") <=="
  anonymous < "$f"
done > "$RESULTS_DIR/jobs.log"
if [[ -f $WORK_DIR/cluster-logs/jobcomp.txt ]]; then
  anonymous < "$WORK_DIR/cluster-logs/jobcomp.txt" > "$RESULTS_DIR/jobcomp.txt"
fi

json_str() {
  local s=${1//\\/\\\\}
  printf '"%s"' "${s//\"/\\\"}"
}
time_of() { [[ -f $1 ]] && cat "$1" || echo null; }
shard_times=()
shard_sum=0
for ((s = 0; s < SHARDS; s++)); do
  t=$(time_of "$out/part-$s.time")
  shard_times+=("$t")
  [[ $t == null ]] || shard_sum=$(awk -v a="$shard_sum" -v b="$t" 'BEGIN { printf "%.3f", a + b }')
done
merge_seconds=$(time_of "$out/merge.time")
part_bytes=()
for ((s = 0; s < SHARDS; s++)); do
  part_bytes+=("$(stat -c %s "$out/part-$s.hmbpart" 2> /dev/null || echo null)")
done
cpu_model=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
hmblur_version=$("$HMBLUR" --version 2>&1 | head -n 1)
date_utc=$(date -u +%FT%TZ)

{
  echo "{"
  echo "  \"date\": $(json_str "$date_utc"),"
  echo "  \"scene\": $(json_str "$SCENE"), \"width\": $WIDTH, \"height\": $HEIGHT, \"spp\": $SPP, \"shards\": $SHARDS,"
  echo "  \"cpus_per_task\": $CPUS_PER_TASK,"
  printf -v joined '%s, ' "${shard_times[@]}"
  echo "  \"shard_seconds\": [${joined%, }],"
  echo "  \"shard_seconds_sum\": $shard_sum,"
  printf -v joined '%s, ' "${part_bytes[@]}"
  echo "  \"part_bytes\": [${joined%, }],"
  echo "  \"merge_seconds\": $merge_seconds,"
  echo "  \"slurm_wall_seconds\": $slurm_seconds,"
  echo "  \"single_seconds\": ${single_seconds:-null},"
  echo "  \"merged_sha256\": $(json_str "$merged_sha"),"
  echo "  \"single_sha256\": $(json_str "$single_sha"),"
  echo "  \"identical\": $identical,"
  echo "  \"hmblur_version\": $(json_str "$hmblur_version"),"
  echo "  \"slurm_version\": $(json_str "$slurm_version"),"
  echo "  \"munge_version\": $(json_str "$munge_version"),"
  echo "  \"nproc\": $(nproc),"
  echo "  \"cpu_model\": $(json_str "${cpu_model:-unknown}"),"
  echo "  \"lp_num_threads\": $(json_str "${LP_NUM_THREADS:-unset}")"
  echo "}"
} > "$RESULTS_DIR/timings.json"

{
  echo "date: $date_utc"
  echo "frame: $SCENE ${WIDTH}x$HEIGHT, $SPP spp, $SHARDS shards, $CPUS_PER_TASK CPUs per task"
  echo "hmblur: $hmblur_version"
  echo "slurm: $slurm_version; munge: $munge_version"
  echo "machine: nproc $(nproc), CPU ${cpu_model:-unknown}, LP_NUM_THREADS ${LP_NUM_THREADS:-unset}"
  echo "jobs: array $array, merge $merge"
  while read -r line; do echo "  $line"; done <<< "$job_states"
  for ((s = 0; s < SHARDS; s++)); do
    echo "shard $s: ${shard_times[s]} s, part ${part_bytes[s]} bytes"
  done
  echo "shards summed: $shard_sum s"
  echo "merge: $merge_seconds s"
  echo "slurm, submission to merge end: $slurm_seconds s"
  echo "single render: ${single_seconds:-null} s"
  echo "sha256 merged.exr: $merged_sha"
  echo "sha256 single.exr: $single_sha"
  echo "identical: $identical"
} | tee "$RESULTS_DIR/run.log"
echo "images: $out/merged.exr, $WORK_DIR/single.exr"

((!failed)) || die "failed; job logs in $RESULTS_DIR/jobs.log, daemon logs in $WORK_DIR/cluster-logs"
[[ $identical == true ]] || die "merged.exr and single.exr differ"
echo "local-cluster: merged.exr equals single.exr"
