#!/bin/bash
# The sweep on a real Slurm cluster: one node on this machine, from Debian 12's slurm-wlm and
# munge, started as root under a private configuration in a temporary directory (its own munge
# key and socket, its own slurm.conf, ports, state, spool and logs; no systemd). It submits the
# job array `penumbra sweep --emit slurm` writes for PLAN, runs the same plan locally meanwhile,
# merges both and requires identical error figures and every view's truth traced once across
# the shards. Every daemon it started is stopped on exit, however it exits.
#
#   tests/cluster/slurm_test.sh PENUMBRA PLAN [SHARDS]     (make slurm-test)
#
# KEEP=1 keeps the temporary directory (logs, results) for a look afterwards.
set -euo pipefail

PENUMBRA=$(realpath "$1")
PLAN=$(realpath "$2")
SHARDS=${3:-3}
for tool in munged slurmctld slurmd sbatch squeue sinfo scancel; do
    command -v "$tool" >/dev/null || { echo "slurm-test: $tool missing (make deps installs slurm-wlm and munge)"; exit 1; }
done
[ "$(id -u)" = 0 ] || { echo "slurm-test: needs root (slurmd runs jobs as their user)"; exit 1; }

WORK=$(mktemp -d /tmp/penumbra-slurm.XXXXXX)
chmod 755 "$WORK"
PIDS=()
JOB=""
cleanup() {
    local rc=$?
    [ -n "$JOB" ] && scancel "$JOB" 2>/dev/null || true
    # Daemons in the reverse order of their start, each by the pid it was started with.
    for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do
        kill "${PIDS[i]}" 2>/dev/null || true
    done
    for pid in "${PIDS[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
    done
    if [ $rc != 0 ]; then
        echo "slurm-test: FAILED; the daemons' logs:"
        tail -n 30 "$WORK"/log/*.log 2>/dev/null || true
    fi
    [ "${KEEP:-0}" = 1 ] && echo "slurm-test: kept $WORK" || rm -rf "$WORK"
    exit $rc
}
trap cleanup EXIT INT TERM

mkdir -p "$WORK"/{munge,state,spool,log}
chmod 700 "$WORK/munge"
# munge: a private key and socket (munged refuses a world-writable parent without --force).
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
SOCKET="$WORK/munge/munge.socket"
munged --foreground --force --key-file="$WORK/munge/munge.key" --socket="$SOCKET" \
    --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/log/munged.log" \
    --seed-file="$WORK/munge/munged.seed" >"$WORK/log/munged.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do [ -S "$SOCKET" ] && break; sleep 0.1; done
[ -S "$SOCKET" ] || { echo "slurm-test: munged did not start"; exit 1; }

# Ports of our own, so that another cluster on this machine does not answer.
free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
NODE=$(hostname -s)
export SLURM_CONF="$WORK/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=penumbra-test
SlurmctldHost=$NODE
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCKET
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=$NODE CPUs=$(nproc) State=UNKNOWN
PartitionName=penumbra Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -D -c -f "$SLURM_CONF" >"$WORK/log/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" >"$WORK/log/slurmd.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 120); do
    state=$(sinfo -h -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.5
done
[ "$state" = idle ] || { echo "slurm-test: the node is '$state', not idle"; exit 1; }
echo "slurm-test: one-node cluster up ($NODE, $(nproc) CPUs)"

START=$(date +%s)
SHARDED="$WORK/sharded"
"$PENUMBRA" sweep "$PLAN" -o "$SHARDED" --emit slurm --gpus 0 --task-count "$SHARDS" \
    --penumbra "$PENUMBRA" \
    > "$WORK/job.sh"
JOB=$(sbatch --parsable "$WORK/job.sh")
echo "slurm-test: submitted job array $JOB ($SHARDS tasks)"
# The same plan locally meanwhile, for the figures to compare with.
"$PENUMBRA" sweep "$PLAN" -o "$WORK/local" > "$WORK/local.out" 2> "$WORK/local.err"
for _ in $(seq 1200); do
    [ -z "$(squeue -h -j "$JOB" 2>/dev/null)" ] && break
    sleep 0.5
done
[ -z "$(squeue -h -j "$JOB" 2>/dev/null)" ] || { echo "slurm-test: the array did not finish"; exit 1; }
JOB_DONE=$JOB
JOB=""
echo "slurm-test: the array and the local run done in $(($(date +%s) - START)) s"

logs=("$SHARDED"/slurm-"$JOB_DONE"_*.log)
[ ${#logs[@]} = "$SHARDS" ] || { echo "slurm-test: ${#logs[@]} task logs, not $SHARDS"; exit 1; }
cat "${logs[@]}" | grep '^sweep: ' || true
if grep -L '^sweep: .* 0 failed' "${logs[@]}" | grep -q .; then
    echo "slurm-test: a shard failed"; cat "${logs[@]}"; exit 1
fi
traced=$(cat "${logs[@]}" | sed -n 's/.*truths: \([0-9]*\) traced.*/\1/p' | awk '{ n += $1 } END { print n }')
views=$(python3 -c 'import json,sys; print(len({t["view"] for t in json.load(open(sys.argv[1]))["tasks"]}))' "$SHARDED/sweep.json")

"$PENUMBRA" merge "$SHARDED" -o "$WORK/merged-sharded" > /dev/null
"$PENUMBRA" merge "$WORK/local" -o "$WORK/merged-local" > /dev/null
python3 - "$WORK/merged-sharded/merge.json" "$WORK/merged-local/merge.json" "$SHARDS" <<'PY'
import json, sys
def figures(path):  # everything but the costs, which are timings
    merged = json.load(open(path))
    for group in merged["groups"]:
        for setting in group["settings"]:
            setting.pop("cost")
    return merged
sharded, local = figures(sys.argv[1]), figures(sys.argv[2])
assert sharded["tasks"] > 0 and not sharded["failed"] and sharded["missing"] == 0, sharded
if sharded != local:
    sys.exit("slurm-test: the sharded figures differ from the local run's")
print("slurm-test: merge.json of %d tasks from %s shards = the local run's" %
      (sharded["tasks"], sys.argv[3]))
PY
[ "$traced" = "$views" ] || { echo "slurm-test: $traced truths traced for $views views"; exit 1; }
echo "slurm-test: every view's truth traced once across the shards ($views views)"
echo "slurm-test: passed"
