#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for trying and testing `medax run --backend slurm`
# (docs/cluster.md). Needs the Debian packages slurm-wlm and munge, and root (the daemons run as
# root: SlurmUser=root). No systemd: munged, slurmctld and slurmd are started directly.
#
#   scripts/slurm-local.sh start  [STATE_DIR]   writes STATE_DIR/slurm.conf, starts the daemons,
#                                               waits until the node is idle; prints the SLURM_CONF line
#   scripts/slurm-local.sh stop   [STATE_DIR]   stops them (their pid files are in STATE_DIR)
#   scripts/slurm-local.sh status [STATE_DIR]   exit 0 when all three run
#
# STATE_DIR (default /tmp/medax-slurm) holds everything: configuration, munge key and socket,
# spool, logs and pid files. Both commands are idempotent. The ports are derived from STATE_DIR
# (override with MEDAX_SLURM_PORT=N: slurmctld N, slurmd N+1), so clusters started with other
# state folders, or a system Slurm on the default 6817/6818, do not clash.
# Clients (sbatch, squeue, medax) find this cluster with: export SLURM_CONF=STATE_DIR/slurm.conf
set -euo pipefail

command_name=${1:-}
state=$(realpath -m "${2:-/tmp/medax-slurm}")
conf=$state/slurm.conf

die() { echo "slurm-local: $*" >&2; exit 1; }

port_base() {
  if [[ -n ${MEDAX_SLURM_PORT:-} ]]; then echo "$MEDAX_SLURM_PORT"; return; fi
  local sum
  sum=$(printf '%s' "$state" | cksum | cut -d' ' -f1)
  echo $((20000 + (sum % 5000) * 2))
}

alive() { [[ -f $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null; }

write_config() {
  local port node cpus memory
  port=$(port_base)
  node=$(hostname -s)
  cpus=$(nproc)
  memory=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)  # half the machine for jobs
  mkdir -p "$state"/{munge,ctld,spool,log}
  chmod 755 "$state/munge"  # munged wants its socket folder reachable, the key private
  cat >"$conf" <<EOF
# Written by scripts/slurm-local.sh: one node, root daemons, no cgroups, no accounting database.
ClusterName=medaxlocal
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$state/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
# Finished jobs stay visible to squeue/scontrol for 10 minutes (there is no sacct here).
MinJobAge=600
# SIGTERM at the time limit, SIGKILL 5 s later.
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=60
# A job without --mem gets 1 GiB per CPU (not the whole node), so tasks run side by side.
DefMemPerCPU=1024
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

start_munge() {
  local key=$state/munge/munge.key
  alive "$state/munged.pid" && return
  if [[ ! -s $key ]]; then
    if ! mungekey --create --keyfile="$key" 2>/dev/null; then
      dd if=/dev/urandom bs=1 count=1024 of="$key" status=none
    fi
  fi
  chmod 400 "$key"
  munged --force --key-file="$key" --socket="$state/munge/munge.socket" --pid-file="$state/munged.pid" \
    --log-file="$state/log/munged.log" --seed-file="$state/munge/munged.seed" \
    || die "munged did not start: $(tail -n 3 "$state/log/munged.log" 2>/dev/null)"
}

# Starts a Slurm daemon unless it runs; it forks into the background and writes its pid file.
start_daemon() {
  local name=$1 pidfile=$state/$1.pid
  alive "$pidfile" && return
  SLURM_CONF=$conf "/usr/sbin/$name" -f "$conf" ${3:-} \
    || die "$name did not start: $(tail -n 5 "$state/log/$2" 2>/dev/null)"
}

wait_idle() {
  local node
  node=$(hostname -s)
  for _ in $(seq 1 60); do
    local s
    s=$(SLURM_CONF=$conf sinfo -h -n "$node" -o %T 2>/dev/null || true)
    case $s in
      idle*|mixed*|allocated*) return 0 ;;
      down*|drain*) SLURM_CONF=$conf scontrol update NodeName="$node" State=RESUME >/dev/null 2>&1 || true ;;
    esac
    sleep 0.5
  done
  die "the node did not become idle within 30 s (state '${s:-unknown}'); last lines of $state/log/:
$(tail -n 4 "$state/log/slurmctld.log" "$state/log/slurmd.log" 2>&1)"
}

start() {
  command -v slurmctld >/dev/null && command -v munged >/dev/null \
    || die "slurmctld or munged not found: install the Debian packages slurm-wlm and munge (scripts/install-deps.sh)"
  [[ $(id -u) == 0 ]] || die "the daemons run as root (SlurmUser=root): run this as root"
  if ! { alive "$state/munged.pid" && alive "$state/slurmctld.pid" && alive "$state/slurmd.pid"; }; then
    write_config
    start_munge
    # -i: ignore (and drop) jobs of an earlier run of this cluster left in the state folder.
    start_daemon slurmctld slurmctld.log -i
    start_daemon slurmd slurmd.log
  fi
  wait_idle
  echo "export SLURM_CONF=$conf"
}

stop_one() {
  local pidfile=$state/$1.pid
  alive "$pidfile" || { rm -f "$pidfile"; return; }
  local pid
  pid=$(cat "$pidfile")
  kill "$pid"
  for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
  rm -f "$pidfile"
}

stop() {
  stop_one slurmd
  stop_one slurmctld
  stop_one munged
  # slurmstepd of jobs still running belong to this cluster's spool; they end with slurmd.
  echo "slurm-local: stopped ($state)"
}

status() {
  local ok=0
  for d in munged slurmctld slurmd; do
    if alive "$state/$d.pid"; then echo "$d: running (pid $(cat "$state/$d.pid"))"; else echo "$d: stopped"; ok=1; fi
  done
  return $ok
}

case $command_name in
  start) start ;;
  stop) stop ;;
  status) status ;;
  *) echo "usage: $0 start|stop|status [STATE_DIR]" >&2; exit 2 ;;
esac
