#!/usr/bin/env bash
# A sharded ingest on a real multi-node scheduler: brings up a Slurm cluster of three nodes on
# this machine (munge with a key of its own, a generated slurm.conf, slurmctld and one slurmd per
# node, each with its own name, port, spool and log; all started and stopped by their PIDs) and
# runs three farms on it, each checked byte for byte against one unsharded run:
#   1. plan -> `matforge ingest --shard I/N` as a job array spread over the nodes -> merge
#      (a job that depends on the array: afterok);
#   2. a node lost mid-run: once a shard has begun writing, its node's slurmd and the shard are
#      killed (SIGKILL); Slurm marks the node down and requeues the task (--requeue), another node
#      runs it, the merge follows; no temporary, journal or lock is left in the output folder;
#   3. a shard that fails on its own (a set's map made unreadable): the shard exits 1, the merge
#      job never runs, `matforge merge` refuses naming that shard; the map restored, that shard
#      alone is resubmitted and the merge completes.
# The cluster is shut down at the end, also on failure or interrupt.
#
# Usage: scripts/cluster-demo.sh [INPUT] [SHARDS]   (default: sample_materials, 3 shards)
# Environment: NODES (default 3), FAULTS=0 runs farm 1 only (so does one node), KEEP=1 keeps the scratch folder,
# MATFORGE_CLUSTER_DIR names it (a folder that does not exist yet; default: a fresh mktemp
# folder), MATFORGE_BIN the binary.
# Needs root (munged and slurmd run as root here) and builds matforge when missing. The input is
# copied into the scratch folder (farm 3 damages a file of the copy, never of INPUT).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source_input=$(realpath "${1:-$root/sample_materials}")
shards=${2:-3}
nodes=${NODES:-3}
t0=$SECONDS
say() { echo "cluster-demo: $*" >&2; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

if ((EUID != 0)); then
    say "needs root (munged, slurmctld and slurmd run as root on this cluster)"
    exit 2
fi
for p in slurm-wlm munge; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        say "installing slurm-wlm munge"
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
        break
    fi
done
matforge=${MATFORGE_BIN:-$root/build/tools/matforge/matforge}
[[ -x $matforge ]] || "$root/scripts/bootstrap.sh" "$root/build" >/dev/null

# The scratch folder is removed at the end: a named one must not exist yet (a folder of the
# user's, with files in it, is never taken as scratch).
if [[ -n ${MATFORGE_CLUSTER_DIR:-} && -e $MATFORGE_CLUSTER_DIR ]]; then
    say "MATFORGE_CLUSTER_DIR=$MATFORGE_CLUSTER_DIR exists; name a folder that does not (it is removed at the end unless KEEP=1)"
    exit 2
fi
work=${MATFORGE_CLUSTER_DIR:-$(mktemp -d /tmp/matforge-cluster.XXXXXX)}
mkdir -p "$work"/{munge,slurm/state,slurm/spool,slurm/log}
chmod 700 "$work/munge"
names=()
for ((n = 1; n <= nodes; n++)); do names+=("mf-n$n"); done
daemon_pids() {
    local pf
    for pf in "$work"/slurm/slurmd-*.pid "$work/slurm/slurmctld.pid" "$work/munge/munged.pid"; do
        [[ -s $pf ]] && cat "$pf"
    done
    return 0
}
cleanup() {
    local rc=$?
    export SLURM_CONF=$work/slurm/slurm.conf
    scancel --quiet --full --signal=KILL --user=root 2>/dev/null || true
    for p in $(daemon_pids); do kill "$p" 2>/dev/null || true; done
    sleep 1
    for p in $(daemon_pids); do kill -9 "$p" 2>/dev/null || true; done
    [[ ${KEEP:-0} == 1 ]] || rm -rf "$work"
    exit "$rc"
}
trap cleanup EXIT INT TERM
trap 'say "failed (exit $?) at line $LINENO: $BASH_COMMAND"' ERR

# The input, copied: farm 3 damages one of its files.
input=$work/input/$(basename "$source_input")
mkdir -p "$work/input"
cp -r "$source_input" "$input"

# munge: a key of our own and a socket in the scratch folder, so the machine's own munge (if
# any) is untouched.
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket=$work/munge/munge.socket
munged --force --socket="$socket" --key-file="$work/munge/munge.key" --pid-file="$work/munge/munged.pid" \
    --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed"
for _ in $(seq 50); do [[ -S $socket ]] && break; sleep 0.1; done
munge -S "$socket" -n | unmunge -S "$socket" >/dev/null || { say "munge does not work"; exit 1; }

# Addresses are given, never looked up: a fresh container's /etc/hosts often does not resolve
# its own host name, and slurmd then exits at once without a word. Every node is this machine
# (NodeHostname), told apart by name and port (slurmd -N). The CPUs are shared out among the
# nodes (at least one each), and the configured count is believed (config_overrides), not the
# machine's. A lost node is noticed within SlurmdTimeout, and a requeued task may start again
# once its credential expires (cred_expire, 120 s by default: 10 s here).
host=$(hostname -s)
cpus=$(($(nproc) / nodes))
((cpus >= 1)) || cpus=1
# Ports no one listens on (another cluster on this machine, say): one for slurmctld, one a node.
listening() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
free_ports() {
    local p
    for ((p = $1; p < $1 + $2; p++)); do ! listening "$p" || return 1; done
}
for _ in $(seq 50); do
    port0=$((17818 + RANDOM % 1000)) ctld_port=$((16817 + RANDOM % 1000))
    free_ports "$port0" "$nodes" && free_ports "$ctld_port" 1 && break
done
conf=$work/slurm/slurm.conf
{
    cat <<EOF
ClusterName=matforge
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$socket,cred_expire=10
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
SlurmdParameters=config_overrides
SlurmdTimeout=5
MessageTimeout=2
ReturnToService=2
MinJobAge=3600
MpiDefault=none
SlurmctldPort=$ctld_port
StateSaveLocation=$work/slurm/state
SlurmdSpoolDir=$work/slurm/spool/%n
SlurmctldPidFile=$work/slurm/slurmctld.pid
SlurmdPidFile=$work/slurm/slurmd-%n.pid
SlurmctldLogFile=$work/slurm/log/slurmctld.log
SlurmdLogFile=$work/slurm/log/slurmd-%n.log
EOF
    for ((n = 0; n < nodes; n++)); do
        echo "NodeName=${names[n]} NodeAddr=127.0.0.1 NodeHostname=$host Port=$((port0 + n)) CPUs=$cpus State=UNKNOWN"
    done
    echo "PartitionName=main Nodes=$(IFS=,; echo "${names[*]}") Default=YES MaxTime=INFINITE State=UP"
} >"$conf"
export SLURM_CONF=$conf
slurmctld -f "$conf"
start_node() {
    mkdir -p "$work/slurm/spool/$1"
    slurmd -f "$conf" -N "$1"
}
for n in "${names[@]}"; do start_node "$n"; done
idle_nodes() { sinfo -h -N -t idle -o %N 2>/dev/null | sort -u | wc -l; }
for _ in $(seq 150); do (($(idle_nodes) == nodes)) && break; sleep 0.2; done
if (($(idle_nodes) != nodes)); then
    say "the nodes did not come up: $(sinfo -h -N -o '%N %T' | tr '\n' ' ')"
    cat "$work"/slurm/log/*.log >&2
    exit 1
fi
say "cluster up in $((SECONDS - t0)) s: $nodes node$( ((nodes == 1)) || echo s) ($(sinfo -h -N -o '%N' | sort -u | paste -sd ' ')), $cpus CPU(s) each"

# A field of a job's record: `job_field JOBID Field` (the first task's, for an array).
job_field() { scontrol -o show job "$1" 2>/dev/null | head -1 | tr ' ' '\n' | sed -n "s/^$2=//p"; }
# Waits until none of the given jobs (comma-separated ids) is pending or running.
wait_jobs() {
    for _ in $(seq 3000); do
        [[ -z $(squeue -h -j "$1" 2>/dev/null) ]] && return 0
        sleep 0.2
    done
    say "jobs $1 did not finish in 10 minutes"
    return 1
}
# One line per task of the array: "shard K: STATE on NODE (restarts R)".
tasks_of() {
    scontrol -o show job "$1" | tr ' ' '\n' | awk -F= '
        $1 == "ArrayTaskId" { k = $2 } $1 == "JobState" { s = $2 } $1 == "Restarts" { r = $2 }
        $1 == "NodeList" { print "shard " k ": " s " on " $2 " (restarts " r ")" }' | sort
}
# Submits the array (extra sbatch options in $1, shard ids in $2) writing into $3 with the
# ingest options $4, and a merge that runs when every task succeeded; prints "ARRAY MERGE".
submit() {
    local opts=$1 ids=$2 out=$3 ingest_opts=$4 array merge
    # shellcheck disable=SC2086
    array=$(sbatch --parsable $opts --array="$ids" --cpus-per-task=1 --open-mode=append \
        --output="$work/slurm/log/$(basename "$out")-shard-%a.log" \
        --wrap="echo \"shard \$SLURM_ARRAY_TASK_ID on \$SLURMD_NODENAME, restart \${SLURM_RESTART_COUNT:-0}\"
exec '$matforge' ingest '$input' -o '$out' $ingest_opts --jobs 1 -q --shard \$SLURM_ARRAY_TASK_ID/$shards")
    merge=$(sbatch --parsable --kill-on-invalid-dep=yes --dependency=afterok:"$array" \
        --output="$work/slurm/log/$(basename "$out")-merge.log" \
        --wrap="exec '$matforge' merge '$out'/manifest.shard-*-of-$shards.json -o '$out/manifest.json'")
    echo "$array $merge"
}
all_shards=0-$((shards - 1))

# The same input in one process: what every farm's merge must equal, byte for byte.
# --no-cache: computed from the sources, not restored from what the shards stored.
t=$(now)
"$matforge" ingest "$input" -o "$work/single" -q --no-cache
single_s=$(since "$t")
same_as_single() {
    local out=$1 what=$2
    if ! cmp -s "$out/manifest.json" "$work/single/manifest.json"; then
        say "$what: the merged manifest differs from the single run's"
        diff "$out/manifest.json" "$work/single/manifest.json" | head -20 >&2
        exit 1
    fi
    if ! diff -r -q -x 'manifest*.json' "$out" "$work/single" >/dev/null; then
        say "$what: the outputs differ from the single run's"
        diff -r -q -x 'manifest*.json' "$out" "$work/single" >&2
        exit 1
    fi
}
merged_or_die() {
    local out=$1 what=$2
    if [[ ! -s $out/manifest.json ]]; then
        say "$what: the merge did not run"
        tail -n 20 "$work"/slurm/log/*.log >&2
        exit 1
    fi
}
materials=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' \
    "$work/single/manifest.json")

# ---- 1. The farm: the array spread over the nodes, then the merge.
t=$(now)
read -r array merge < <(submit "" "$all_shards" "$work/out" "--cache '$work/cache'")
say "farm 1: array job $array ($shards shards) and merge job $merge (afterok)"
wait_jobs "$array,$merge"
farm_s=$(since "$t")
merged_or_die "$work/out" "farm 1"
same_as_single "$work/out" "farm 1"
tasks_of "$array" | sed 's/^/cluster-demo:   /' >&2
used=$(tasks_of "$array" | awk '{ print $5 }' | sort -u | wc -l)
say "farm 1 PASS: $shards shards on $used of $nodes nodes in $farm_s s (one process: $single_s s); $materials materials, merged manifest and outputs byte-identical to one process"

# A lost node's task needs another node to run on.
if [[ ${FAULTS:-1} == 0 ]] || ((nodes < 2)); then
    say "PASS in $((SECONDS - t0)) s"
    exit 0
fi

# ---- 2. A node lost mid-run. --no-cache: each shard computes (restored from the cache, it would
# be done before it could be stopped). The first shard seen writing (its journal is there from
# the start of its writes to its manifest) loses its node: slurmd and the shard, SIGKILL.
# A shard can finish between being seen writing and being stopped (a small shard writes for a
# fraction of a second): its job then completes on the lost node, nothing is requeued, and the
# farm is run again, up to three times.
for attempt in 1 2 3; do
    out=$work/out-lost-$attempt
    t=$(now)
    read -r array merge < <(submit "--requeue" "$all_shards" "$out" "--no-cache")
    say "farm 2: array job $array (--requeue) and merge job $merge; a node will be lost while its shard writes"
    # The first shard whose journal appears is frozen at once (its process found by its command
    # line: the job's shell execs matforge), then named: job and node, from squeue.
    victim="" node="" task="" shard_pids=()
    for _ in $(seq 60000); do
        for ((k = 0; k < shards; k++)); do
            [[ -e $out/.manifest.shard-$k-of-$shards.json.journal ]] || continue
            mapfile -t shard_pids < <(pgrep -f -- " --shard $k/$shards\$")
            ((${#shard_pids[@]})) && kill -STOP "${shard_pids[@]}" 2>/dev/null || true  # frozen mid-write
            task=$k
            break 2
        done
        sleep 0.001
    done
    [[ -n $task ]] || { say "farm 2: no shard was seen writing"; exit 1; }
    read -r victim node < <(squeue -h -j "$array" -t R -o '%A %K %N' 2>/dev/null | awk -v k="$task" '$2 == k { print $1, $3 }') || true
    if [[ -z $victim || ${#shard_pids[@]} == 0 ]] && ((attempt < 3)); then
        say "farm 2: shard $task finished before it was stopped (attempt $attempt); again"
        wait_jobs "$array,$merge"
        continue
    fi
    [[ -n $victim ]] || { say "farm 2: shard $task was seen writing but is not running"; exit 1; }
    temps=$(find "$out" -name "*.matforge-tmp-*" | wc -l)
    kill -9 "$(cat "$work/slurm/slurmd-$node.pid")"
    lost_at=$(now)
    for p in $(pgrep -f "slurmstepd: \[$victim\." || true) "${shard_pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
    say "farm 2: killed node $node (its slurmd) and shard $task (job $victim, pids ${shard_pids[*]:-none}) while it wrote: its journal and $temps temporaries in the output folder"
    for _ in $(seq 600); do
        [[ $(sinfo -h -n "$node" -o %T) == down* ]] && break
        sleep 0.1
    done
    say "farm 2: Slurm marked $node $(sinfo -h -n "$node" -o %T) after $(since "$lost_at") s"
    wait_jobs "$array,$merge"
    merged_or_die "$out" "farm 2"
    same_as_single "$out" "farm 2"
    restarts=$(job_field "$victim" Restarts)
    rerun_on=$(job_field "$victim" NodeList)
    if [[ $restarts == 0 && $(job_field "$victim" JobState) == COMPLETED && $attempt -lt 3 ]]; then
        say "farm 2: shard $task finished before it was stopped (attempt $attempt); again"
        start_node "$node"
        for _ in $(seq 100); do [[ $(sinfo -h -n "$node" -o %T) == idle ]] && break; sleep 0.2; done
        continue
    fi
    if [[ $restarts != 1 || $rerun_on == "$node" ]]; then
        say "farm 2: shard $task was not requeued onto another node (restarts $restarts, node $rerun_on)"
        exit 1
    fi
    break
done
left=$(find "$out" \( -name "*.matforge-tmp-*" -o -name "*.journal" -o -name "*.lock" \) -printf '%P\n')
[[ -z $left ]] || { say "farm 2: left in the output folder: $left"; exit 1; }
tasks_of "$array" | sed 's/^/cluster-demo:   /' >&2
say "requeue: shard $task (job $victim) lost with $node, requeued by Slurm, ran again on $rerun_on"
start_node "$node"  # ReturnToService=2: the node is back once its slurmd registers
for _ in $(seq 100); do [[ $(sinfo -h -n "$node" -o %T) == idle ]] && break; sleep 0.2; done
say "farm 2 PASS in $(since "$t") s: merged manifest and outputs byte-identical to one process; no temporary, journal or lock left; $node back: $(sinfo -h -n "$node" -o %T)"

# ---- 3. A shard that fails on its own: a map of one set of the copy made unreadable.
out=$work/out-failed
"$matforge" plan "$input" --shards "$shards" -o "$work/plan.json" >/dev/null
# The last set of the plan, and the first map the single run read of it.
read -r bad_shard bad_set bad_file < <(python3 -c 'import json, os, sys
s = json.load(open(sys.argv[1]))["sets"][-1]
m = next(m for m in json.load(open(sys.argv[2]))["materials"] if m["name"] == s["name"])
first = sorted(m["inputs"].values(), key=lambda i: i["file"])[0]["file"]
print(s["shard"], s["name"], os.path.join(os.path.dirname(sys.argv[2]), m["source"], first))' \
    "$work/plan.json" "$work/single/manifest.json")
cp -p "$bad_file" "$work/kept-image"
# Its first bytes overwritten, its size kept: the split, which follows sizes, stays the one the
# other shards ran in (a fix that changes a size moves sets between shards: merge then asks for
# every shard again, which the cache makes cheap; docs/cluster.md).
printf 'not an image' | dd of="$bad_file" conv=notrunc status=none
read -r array merge < <(submit "" "$all_shards" "$out" "--cache '$work/cache'")
say "farm 3: array job $array and merge job $merge; $(basename "$bad_file") of set $bad_set (shard $bad_shard) is unreadable"
wait_jobs "$array,$merge"
state=$(scontrol -o show job "${array}_$bad_shard" | tr ' ' '\n' | sed -n 's/^JobState=//p')
[[ $state == FAILED ]] || { say "farm 3: shard $bad_shard ended $state, not FAILED"; exit 1; }
[[ ! -e $out/manifest.json ]] || { say "farm 3: the merge job ran although a shard failed"; exit 1; }
rc=0
refusal=$("$matforge" merge "$out"/manifest.shard-*-of-"$shards".json -o "$out/manifest.json" 2>&1) || rc=$?
if ((rc != 1)) || [[ $refusal != *"shard $bad_shard of $shards"* || -e $out/manifest.json ]]; then
    say "farm 3: merge did not refuse naming shard $bad_shard (exit $rc): $refusal"
    exit 1
fi
say "farm 3: shard $bad_shard FAILED, the merge job was not run, matforge merge refused (exit 1):"
echo "$refusal" | sed 's/^/cluster-demo:   /' >&2
cp -p "$work/kept-image" "$bad_file"
read -r array merge < <(submit "" "$bad_shard" "$out" "--cache '$work/cache'")
wait_jobs "$array,$merge"
merged_or_die "$out" "farm 3"
same_as_single "$out" "farm 3"
say "farm 3 PASS: the image restored, shard $bad_shard alone resubmitted (job $array) and merged; byte-identical to one process"
say "PASS: $nodes nodes, 3 farms in $((SECONDS - t0)) s"
