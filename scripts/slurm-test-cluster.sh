#!/usr/bin/env bash
# A private single-node Slurm cluster in a folder, for the engine's Slurm test
# and for trying `imapsim ... --executor slurm` on one machine
# (docs/cluster.md). Debian 12 packages munge, slurmctld, slurmd and
# slurm-client (scripts/install-deps.sh); no systemd, no /etc changes: its
# own munge key and socket, its own ports, state and logs under DIR.
#
#   scripts/slurm-test-cluster.sh start DIR   starts munged, slurmctld, slurmd; waits
#                                             for the node; prints the SLURM_CONF line
#   scripts/slurm-test-cluster.sh stop DIR    cancels every job, waits for an empty
#                                             queue, shuts the daemons down
#   ... start DIR --owner PID                 also stops the cluster by itself when
#                                             process PID ends (a test killed by its
#                                             time limit leaves no daemon behind)
#
# Then: export SLURM_CONF=DIR/slurm.conf (every Slurm command and imapsim use it).
# Run as root (the daemons run as the user who starts them; slurmd needs root).
set -euo pipefail

cmd="${1:-}"
dir="${2:-}"
owner=""
if [ "${3:-}" = "--owner" ]; then
  owner="${4:-}"
  case "$owner" in ''|*[!0-9]*) echo "$0: --owner needs a process id" >&2; exit 2 ;; esac
fi
if [ -z "$cmd" ] || [ -z "$dir" ]; then
  echo "usage: $0 start|stop DIR [--owner PID]" >&2
  exit 2
fi

die() {
  echo "slurm-test-cluster: $*" >&2
  exit 1
}

dump_logs() {
  for f in "$dir"/log/*.log "$dir"/log/*.out; do
    [ -f "$f" ] || continue
    echo "---- $f (last lines)" >&2
    tail -n 15 "$f" >&2
  done
}

start() {
  for p in munged mungekey slurmctld slurmd sinfo squeue scontrol; do
    command -v "$p" >/dev/null || die "$p not found: install munge, slurmctld, slurmd, slurm-client (scripts/install-deps.sh)"
  done
  [ -e "$dir/slurm.conf" ] && die "$dir already holds a cluster (stop it first, or use a new folder)"
  mkdir -p "$dir"
  dir="$(cd "$dir" && pwd)"
  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  # munge refuses a socket folder that others may write to: 0755.
  mkdir -p -m 0755 "$dir/munge"
  chmod 0755 "$dir" "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key" --bits=1024 >/dev/null 2>&1 ||
    die "mungekey could not create a key in $dir/munge"
  chmod 0600 "$dir/munge/munge.key"

  local user node host ports ctld_port node_port nodeline
  user="$(id -un)"
  node="imapnode"
  host="$(hostname)"
  ports="$(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1",0))
print(" ".join(str(x.getsockname()[1]) for x in s))')"
  ctld_port="${ports% *}"
  node_port="${ports#* }"
  # The node line from the hardware slurmd sees, under our node name.
  nodeline="$(slurmd -C | head -n 1 | sed -e "s/^NodeName=[^ ]*/NodeName=$node/")"
  [ -n "$nodeline" ] || die "slurmd -C printed no node line"

  cat > "$dir/slurm.conf" <<CONF
# Private single-node test cluster made by scripts/slurm-test-cluster.sh.
ClusterName=imaptest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
MpiDefault=none
# No accounting database: final states come from the jobcomp log and squeue
# (finished jobs stay listed for MinJobAge seconds).
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
MinJobAge=600
KillWait=5
InactiveLimit=0
ReturnToService=2
$nodeline NodeAddr=127.0.0.1 NodeHostname=$host State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"

  # Background daemons in their own sessions, so that a Ctrl-C of the
  # caller's terminal does not reach them.
  setsid munged --foreground --force --socket="$dir/munge/munge.socket" \
    --key-file="$dir/munge/munge.key" --pid-file="$dir/munge/munged.pid" \
    --seed-file="$dir/munge/munged.seed" --log-file="$dir/log/munged.log" \
    </dev/null >"$dir/log/munged.out" 2>&1 &
  echo $! > "$dir/munged.pid"
  local i
  for i in $(seq 1 100); do
    [ -S "$dir/munge/munge.socket" ] && break
    sleep 0.05
  done
  [ -S "$dir/munge/munge.socket" ] || { dump_logs; die "munged did not create its socket"; }

  setsid slurmctld -D -f "$dir/slurm.conf" </dev/null >"$dir/log/slurmctld.out" 2>&1 &
  echo $! > "$dir/slurmctld.daemon.pid"
  setsid slurmd -D -N "$node" -f "$dir/slurm.conf" </dev/null >"$dir/log/slurmd.out" 2>&1 &
  echo $! > "$dir/slurmd.daemon.pid"

  local state=""
  for i in $(seq 1 300); do
    state="$(sinfo --noheader --nodes="$node" --format=%T 2>/dev/null || true)"
    case "$state" in idle*|mixed*|allocated*) break ;; esac
    sleep 0.1
  done
  case "$state" in
    idle*|mixed*|allocated*) ;;
    *) dump_logs; stop_daemons; die "the node did not come up within 30 s (state '${state:-none}')" ;;
  esac
  if [ -n "$owner" ]; then
    # The watchdog: once the owner is gone, stop the cluster (a no-op if the
    # owner already did). Detached, its output in the cluster's log folder.
    setsid bash -c 'while kill -0 "$1" 2>/dev/null && [ -f "$3/slurm.conf" ]; do sleep 1; done
                    [ -f "$3/slurmd.daemon.pid" ] && bash "$2" stop "$3"' \
      watchdog "$owner" "$(cd "$(dirname "$0")" && pwd)/$(basename "$0")" "$dir" \
      </dev/null >"$dir/log/watchdog.out" 2>&1 &
    echo $! > "$dir/watchdog.pid"
  fi
  echo "slurm-test-cluster: up in $dir (controller port $ctld_port, node $node on port $node_port)"
  echo "export SLURM_CONF=$dir/slurm.conf"
}

kill_pidfile() {  # file: the pid of a process this script started
  local f="$1" pid i
  [ -f "$f" ] || return 0
  pid="$(cat "$f")"
  if kill -0 "$pid" 2>/dev/null; then
    kill "$pid" 2>/dev/null || true
    for i in $(seq 1 100); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.05
    done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$f"
}

stop_daemons() {
  export SLURM_CONF="$dir/slurm.conf"
  scontrol shutdown >/dev/null 2>&1 || true
  kill_pidfile "$dir/slurmd.daemon.pid"
  kill_pidfile "$dir/slurmctld.daemon.pid"
  kill_pidfile "$dir/munged.pid"
}

stop() {
  [ -f "$dir/slurm.conf" ] || die "$dir holds no test cluster"
  dir="$(cd "$dir" && pwd)"
  export SLURM_CONF="$dir/slurm.conf"
  # Running tasks survive a controller shutdown: cancel them and wait for an
  # empty queue first.
  local jobs i
  jobs="$(squeue --noheader --format=%A 2>/dev/null || true)"
  if [ -n "$jobs" ]; then
    # shellcheck disable=SC2086
    scancel $jobs >/dev/null 2>&1 || true
    for i in $(seq 1 300); do
      [ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING,CONFIGURING --format=%A 2>/dev/null || true)" ] && break
      sleep 0.1
    done
  fi
  stop_daemons
  # The watchdog, unless it is the one stopping (then this script is it, or
  # its child).
  if [ -f "$dir/watchdog.pid" ]; then
    local w
    w="$(cat "$dir/watchdog.pid")"
    [ "$w" != "$$" ] && [ "$w" != "${PPID:-}" ] && kill_pidfile "$dir/watchdog.pid"
  fi
  rm -f "$dir/watchdog.pid"
  echo "slurm-test-cluster: stopped ($dir)"
}

case "$cmd" in
  start) start ;;
  stop) stop ;;
  *) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
esac
