#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the study tests: munged,
# slurmctld and slurmd started as root from a configuration written into
# DIR (no cgroups: proctrack/linuxproc, task/none; no accounting), and
# stopped again by their pids.
#
#   bash scripts/slurm_cluster.sh start DIR   # prints SLURM_CONF=DIR/slurm.conf
#   bash scripts/slurm_cluster.sh stop DIR
#
# Needs Debian's slurmctld, slurmd, slurm-client and munge (`make setup`
# installs them) and root (the daemons run as root). Ports are taken from
# the free range above 26000 so that two clusters (two test runs) do not
# meet. Works with CI=true and no stdin.
set -euo pipefail

cmd="${1:?usage: slurm_cluster.sh start|stop DIR}"
DIR="$(mkdir -p "${2:?usage: slurm_cluster.sh start|stop DIR}" && cd "$2" && pwd -P)"
die() { printf 'slurm_cluster: ERROR: %s\n' "$*" >&2; exit 1; }

stop_pidfile() {
    local f="$1"
    [[ -s "$f" ]] || return 0
    local pid
    pid="$(cat "$f")"
    if kill -0 "$pid" 2>/dev/null; then
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
    fi
    rm -f "$f"
}

case "$cmd" in
stop)
    stop_pidfile "$DIR/slurmd.pid"
    stop_pidfile "$DIR/slurmctld.pid"
    stop_pidfile "$DIR/munge/munged.pid"
    exit 0
    ;;
start) ;;
*) die "unknown command $cmd (start or stop)" ;;
esac

[[ $(id -u) -eq 0 ]] || die "the one-node cluster runs its daemons as root; run as root"
for b in munged slurmctld slurmd sbatch squeue scontrol; do
    command -v "$b" >/dev/null 2>&1 || die "$b not found: run \`make setup\` (Debian slurmctld slurmd slurm-client munge)"
done

mkdir -p "$DIR/state" "$DIR/spool" "$DIR/munge"
chmod 700 "$DIR/munge"
# munged with its own socket, key copy and pid file inside DIR.
KEY=/etc/munge/munge.key
[[ -r "$KEY" ]] || die "no munge key at $KEY (Debian's munge package creates it)"
install -m 600 "$KEY" "$DIR/munge/munge.key"
SOCKET="$DIR/munge/munge.socket"
munged --force --key-file="$DIR/munge/munge.key" --socket="$SOCKET" \
    --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/munge/munged.log" \
    --seed-file="$DIR/munge/munged.seed" \
    || die "munged did not start (see $DIR/munge/munged.log)"

# Two free ports next to each other.
port=""
for p in $(seq 26000 2 26998); do
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null \
        && ! (exec 3<>"/dev/tcp/127.0.0.1/$((p + 1))") 2>/dev/null; then
        port=$p
        break
    fi
done
[[ -n "$port" ]] || die "no two free ports in 26000-26999"

HOST="$(hostname -s)"
CPUS="$(nproc)"
# Memory the node offers: what the machine has less 1 GB, in MB.
MEM_MB=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
cat >"$DIR/slurm.conf" <<EOF
ClusterName=study$port
SlurmctldHost=$HOST
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCKET
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
ReturnToService=2
MinJobAge=3600
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
NodeName=$HOST CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$DIR/slurm.conf"
slurmctld -f "$SLURM_CONF" -i || die "slurmctld did not start (see $DIR/slurmctld.log)"
slurmd -f "$SLURM_CONF" || die "slurmd did not start (see $DIR/slurmd.log)"
# Ready when the node is idle.
for _ in $(seq 100); do
    state="$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)"
    [[ "$state" == idle* ]] && { echo "SLURM_CONF=$SLURM_CONF"; exit 0; }
    sleep 0.2
done
die "the node did not become idle in 20 s (state '${state:-none}'; see $DIR/slurmctld.log and $DIR/slurmd.log)"
