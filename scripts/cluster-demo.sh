#!/usr/bin/env bash
# A sharded ingest on a real scheduler: brings up a single-node Slurm cluster on this machine
# (munge key, a generated slurm.conf with one node and all its CPUs, slurmctld and slurmd started
# and stopped by their PIDs), submits `matforge ingest --shard I/N` as a job array and a merge job
# that depends on it (afterok), waits, checks the merged manifest and every output against one
# unsharded run byte for byte, and shuts the cluster down (also on failure or interrupt).
#
# Usage: scripts/cluster-demo.sh [INPUT] [SHARDS]   (default: sample_materials, 3 shards)
# Needs root (munged and slurmd run as root here) and builds matforge when missing. Writes
# everything under $MATFORGE_CLUSTER_DIR (default: a fresh mktemp folder, removed at the end
# unless KEEP=1).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
input=$(realpath "${1:-$root/sample_materials}")
shards=${2:-3}
t0=$SECONDS
say() { echo "cluster-demo: $*" >&2; }

if ((EUID != 0)); then
    say "needs root (munged, slurmctld and slurmd run as root on this one-node cluster)"
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

work=${MATFORGE_CLUSTER_DIR:-$(mktemp -d /tmp/matforge-cluster.XXXXXX)}
mkdir -p "$work"/{munge,slurm/state,slurm/spool,slurm/log,out,single}
chmod 700 "$work/munge"
pids=()
cleanup() {
    local rc=$?
    for pf in "$work/slurm/slurmd.pid" "$work/slurm/slurmctld.pid" "$work/munge/munged.pid"; do
        [[ -s $pf ]] && kill "$(cat "$pf")" 2>/dev/null || true
    done
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    sleep 1
    [[ ${KEEP:-0} == 1 ]] || rm -rf "$work"
    exit "$rc"
}
trap cleanup EXIT INT TERM

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
# its own host name, and slurmd then exits at once without a word.
host=$(hostname -s)
conf=$work/slurm/slurm.conf
cat >"$conf" <<EOF
ClusterName=matforge
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
ReturnToService=2
MpiDefault=none
SlurmctldPort=$((16817 + RANDOM % 1000))
SlurmdPort=$((17818 + RANDOM % 1000))
StateSaveLocation=$work/slurm/state
SlurmdSpoolDir=$work/slurm/spool
SlurmctldPidFile=$work/slurm/slurmctld.pid
SlurmdPidFile=$work/slurm/slurmd.pid
SlurmctldLogFile=$work/slurm/log/slurmctld.log
SlurmdLogFile=$work/slurm/log/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$conf
slurmctld -f "$conf"
slurmd -f "$conf"
for _ in $(seq 100); do sinfo -h -o %T 2>/dev/null | grep -qE "^idle" && break; sleep 0.2; done
sinfo -h -o %T | grep -qE "^idle" || { say "the node did not come up"; cat "$work"/slurm/log/*.log >&2; exit 1; }
say "cluster up in $((SECONDS - t0)) s: $(sinfo -h -o '%n %c CPUs %T')"

# The job array (one task per shard) and the merge, which runs only if every shard succeeded.
out=$work/out
array=$(sbatch --parsable --array=0-$((shards - 1)) --cpus-per-task=1 --output="$work/slurm/log/shard-%a.log" \
    --wrap="exec '$matforge' ingest '$input' -o '$out' --cache '$work/cache' --jobs 1 -q --shard \$SLURM_ARRAY_TASK_ID/$shards")
merge=$(sbatch --parsable --dependency=afterok:"$array" --output="$work/slurm/log/merge.log" \
    --wrap="exec '$matforge' merge '$out'/manifest.shard-*-of-$shards.json -o '$out/manifest.json'")
say "submitted array job $array ($shards shards) and merge job $merge (afterok)"
for _ in $(seq 1800); do
    [[ -z $(squeue -h -j "$array,$merge" 2>/dev/null) ]] && break
    sleep 0.2
done
state=$(sacct -n -X -j "$merge" -o State 2>/dev/null | tr -d ' ' || true)
if [[ ! -s $out/manifest.json ]]; then
    say "the merge did not run (state: ${state:-unknown})"
    cat "$work"/slurm/log/*.log >&2
    exit 1
fi

# The same input in one process: the merged manifest and every output must be the same bytes.
# --no-cache: computed from the sources, not restored from what the shards stored.
"$matforge" ingest "$input" -o "$work/single" -q --no-cache
if ! cmp -s "$out/manifest.json" "$work/single/manifest.json"; then
    say "the merged manifest differs from the single run's"
    diff "$out/manifest.json" "$work/single/manifest.json" | head -20 >&2
    exit 1
fi
if ! diff -r -q -x 'manifest*.json' "$out" "$work/single" >/dev/null; then
    say "outputs differ from the single run's"
    diff -r -q -x 'manifest*.json' "$out" "$work/single" >&2
    exit 1
fi
n=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$out/manifest.json")
say "PASS: $shards shards on Slurm, $n materials; merged manifest and outputs byte-identical to one process; $((SECONDS - t0)) s"
