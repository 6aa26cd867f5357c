#!/usr/bin/env bash
# A one-node Slurm cluster of this machine, all of it inside one folder, for the tests that submit
# jobs (label `cluster`; tests/cluster/with_slurm.sh starts one around a command and stops it).
#
#   tools/slurm-local.sh start DIR   makes DIR (or uses it): a MUNGE key of its own, slurm.conf
#                                    naming this host as the only node (all its CPUs, a little less
#                                    than its memory) in one default partition, state, spool, pid
#                                    files, sockets and logs, all under DIR. Starts munged,
#                                    slurmctld and slurmd (root, Debian 12's munge and slurm-wlm:
#                                    tools/setup-debian.sh --cluster), waits until the node is idle
#                                    and prints the line a caller must run (also in DIR/env.sh;
#                                    eval "$(tools/slurm-local.sh start DIR)" runs it):
#                                      export SLURM_CONF=DIR/slurm.conf
#                                    A start that fails prints the daemons' logs' tails and stops
#                                    what it started. Needs root.
#   tools/slurm-local.sh stop DIR    cancels the cluster's jobs, stops the three daemons (SIGTERM,
#                                    SIGKILL after a while) and any process of theirs left behind:
#                                    job steps, and processes of jobs whose step is gone. Does
#                                    nothing where nothing runs: after a stop, after a failed start,
#                                    on a DIR that never was one. Leaves DIR, logs included.
#
# DIR must not be writable by others, and others must be able to enter it (munged's checks, as on
# each folder above it): start sets it so (go-w, go+x).
# Nothing is written outside DIR: munged gets its key, socket, pid, seed and log files there on its
# command line; slurm.conf points Slurm's authentication at that socket (AuthInfo) and every path
# of Slurm's into DIR. The ports are two free ones picked at random in 20000-29999, so that two
# clusters, or a system one, do not clash. The jobs run as whoever submits them (root here), with
# no cgroups (proctrack/linuxproc, task/none) and no accounting: sacct has nothing to show, but
# scontrol show job does for MinJobAge (10 minutes) after a job ends.
set -euo pipefail

readonly wait_idle_s=60     # start: how long the node may take to come up idle
readonly wait_exit_s=15     # stop: how long a daemon or job may take after SIGTERM
# Set in the environment of the daemons only (never in env.sh): it marks them, so that stop finds
# them even without a pid file.
readonly marker=SLURM_LOCAL_DIR

die() {
  echo "slurm-local: $*" >&2
  exit 1
}

usage() {
  echo "usage: tools/slurm-local.sh start|stop DIR" >&2
  exit 2
}

require_commands() {
  local missing=() c
  for c in munged mungekey slurmctld slurmd sinfo squeue scancel scontrol; do
    command -v "$c" > /dev/null || missing+=("$c")
  done
  [ ${#missing[@]} -eq 0 ] ||
    die "not installed: ${missing[*]} (tools/setup-debian.sh --cluster installs slurm-wlm and munge)"
}

# The TCP ports in use here, any state, IPv4 and IPv6, one a line (decimal).
ports_in_use() {
  local file
  for file in /proc/net/tcp /proc/net/tcp6; do
    [ -r "$file" ] || continue
    while read -r _ local _; do
      echo $((16#${local##*:}))
    done < <(tail -n +2 "$file")
  done
}

# Two consecutive free ports, PORT and PORT+1; prints PORT.
free_port_pair() {
  local used port
  used=" $(ports_in_use | sort -un | tr '\n' ' ') "
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 9999))
    if [[ $used != *" $port "* && $used != *" $((port + 1)) "* ]]; then
      echo "$port"
      return 0
    fi
  done
  return 1
}

# The pid in pid file FILE if that process is alive and runs NAME, else nothing.
live_pid() {
  local file=$1 name=$2 pid
  [ -s "$file" ] || return 0
  pid=$(tr -dc 0-9 < "$file")
  [ -n "$pid" ] && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] && echo "$pid"
  return 0
}

# The pids of this cluster's processes, but this one and its ancestors: those whose environment
# holds the marker (munged, slurmctld, slurmd, started by start), and those whose environment names
# DIR/slurm.conf and that are job steps (slurmstepd) or job processes (SLURM_JOB_ID; Slurm sets
# both in a job's environment, also with --export=NONE). With ONLY, those whose name is ONLY.
cluster_pids() {
  local only=${1:-} self=" " p pid env
  p=$$
  while [ "$p" -gt 1 ]; do
    self+="$p "
    p=$(awk '{print $4}' "/proc/$p/stat" 2>/dev/null || echo 1)
  done
  for p in /proc/[0-9]*; do
    pid=${p#/proc/}
    [[ $self == *" $pid "* ]] && continue
    [ -z "$only" ] || [ "$(cat "$p/comm" 2>/dev/null)" = "$only" ] || continue
    env=$(tr '\0' '\n' 2>/dev/null < "$p/environ") || continue
    if grep -qxF "$marker=$dir" <<< "$env" ||
      { grep -qxF "SLURM_CONF=$dir/slurm.conf" <<< "$env" &&
        { [ "$(cat "$p/comm" 2>/dev/null)" = slurmstepd ] || grep -q '^SLURM_JOB_ID=' <<< "$env"; }; }; then
      echo "$pid"
    fi
  done
  return 0
}

# Waits up to wait_exit_s for the pids to exit; true when they all have.
wait_gone() {
  local deadline=$((SECONDS + wait_exit_s)) pid alive
  while :; do
    alive=()
    for pid in "$@"; do
      [ -e "/proc/$pid" ] && [ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)" != Z ] &&
        alive+=("$pid")
    done
    [ ${#alive[@]} -eq 0 ] && return 0
    [ $SECONDS -ge $deadline ] && return 1
    sleep 0.2
  done
}

# SIGTERM, then SIGKILL to those still alive after wait_exit_s. WHAT names them in messages.
terminate() {
  local what=$1
  shift
  [ $# -eq 0 ] && return 0
  kill -TERM "$@" 2>/dev/null || true
  if ! wait_gone "$@"; then
    echo "slurm-local: $what did not exit in $wait_exit_s s of SIGTERM; SIGKILL" >&2
    kill -KILL "$@" 2>/dev/null || true
    wait_gone "$@" || echo "slurm-local: $what still alive after SIGKILL: $*" >&2
  fi
}

write_munge_key() {
  rm -f "$dir/munge/munge.key"
  mungekey --create --keyfile="$dir/munge/munge.key" ||
    die "mungekey could not write $dir/munge/munge.key"
  chmod 0400 "$dir/munge/munge.key"
}

start_munged() {
  env "$marker=$dir" munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" ||
    fail "munged did not start"
  # A credential made and decoded through the socket: the daemon is up and has the key.
  munge --socket="$dir/munge/munge.socket" --no-input |
    unmunge --socket="$dir/munge/munge.socket" > /dev/null ||
    fail "munged does not answer on $dir/munge/munge.socket"
}

write_slurm_conf() {
  local host cpus memory_mb port
  host=$(hostname -s)
  cpus=$(nproc)
  # 95 % of the memory, so that slurmd never finds less than it was told and drains the node.
  memory_mb=$(awk '/^MemTotal:/ {printf "%d", $2 / 1024 * 0.95}' /proc/meminfo)
  port=$(free_port_pair) || fail "no two free TCP ports found in 20000-29999"
  : > "$dir/plugstack.conf"  # no SPANK plugins, rather than the system's list
  cat > "$dir/slurm.conf" << EOF
# A one-node cluster of $host, written by tools/slurm-local.sh start; stop it with
# tools/slurm-local.sh stop $dir
ClusterName=local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# A requeued job waits cred_expire seconds before it may run again (120 by default; 5 at least).
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$dir/plugstack.conf
MailProg=/bin/true
# No cgroups: processes are tracked by their parents, tasks are not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
# Cores are what jobs ask for (--cpus-per-task, --exclusive); memory is not.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# No accounting: sacct has nothing; scontrol show job keeps a finished job for MinJobAge seconds.
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MinJobAge=600
# Jobs start within a second of cores coming free (by default up to 3 s later), within 2 s of
# becoming eligible (a requeued one, cred_expire after the requeue: by default at the next full
# pass, up to 60 s later). A job whose dependency can never be met is cancelled rather than left
# pending, so that sbatch --wait on it returns.
SchedulerParameters=batch_sched_delay=0,bf_interval=1,sched_interval=2
DependencyParameters=kill_invalid_depend
# A node that was down comes back as soon as its slurmd registers.
ReturnToService=2
# SIGKILL a cancelled job's processes 5 s after SIGTERM (30 by default).
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

start_slurm() {
  env "$marker=$dir" SLURM_CONF="$dir/slurm.conf" slurmctld -f "$dir/slurm.conf" ||
    fail "slurmctld did not start"
  env "$marker=$dir" SLURM_CONF="$dir/slurm.conf" slurmd -f "$dir/slurm.conf" ||
    fail "slurmd did not start"
}

wait_idle() {
  local begin=$SECONDS state=""
  while [ $((SECONDS - begin)) -lt $wait_idle_s ]; do
    state=$(SLURM_CONF="$dir/slurm.conf" sinfo --noheader --Node --format=%t 2>/dev/null || true)
    [ "$state" = idle ] && return 0
    # set so when slurmd finds fewer CPUs or less memory than slurm.conf names
    [ "$state" = inval ] && fail "the node is invalid: $(node_reason)"
    # slurmctld writes its pid file once it has forked into the background
    [ -n "$(live_pid "$dir/slurmctld.pid" slurmctld)" ] || [ $((SECONDS - begin)) -lt 3 ] ||
      fail "slurmctld exited"
    sleep 0.2
  done
  fail "the node is not idle after $wait_idle_s s (sinfo: '${state:-no answer}'; $(node_reason))"
}

# Why slurmctld holds the node down, drained or invalid.
node_reason() {
  local reason
  reason=$(SLURM_CONF="$dir/slurm.conf" sinfo --noheader --Node --format=%E 2>/dev/null || true)
  echo "reason: ${reason:-none given}"
}

# A failed start: everything stopped, then the logs' tails (as they were) and the message.
fail() {
  local log tails=""
  for log in munged slurmctld slurmd; do
    if [ -s "$dir/log/$log.log" ]; then
      tails+="--- $dir/log/$log.log (last lines)"$'\n'"$(tail -n 15 "$dir/log/$log.log")"$'\n'
    fi
  done
  stop > /dev/null 2>&1 || true
  printf '%s' "$tails" >&2
  echo "slurm-local: start $dir: $*" >&2
  exit 1
}

start() {
  local daemon pidfile
  require_commands
  [ "$(id -u)" -eq 0 ] || die "start needs root: the daemons run as root and the jobs as you"
  mkdir -p "$dir" || die "cannot make $dir"
  dir=$(cd "$dir" && pwd -P)
  # munged's socket path must fit a sockaddr_un (108 bytes); slurm.conf takes no quoting.
  [ ${#dir} -le 80 ] || die "DIR is too long for munged's socket path (${#dir} > 80): $dir"
  [[ $dir != *[[:space:][:cntrl:]\#,=\(\)]* ]] ||
    die "DIR holds a character slurm.conf cannot take (space, control character, #, comma, =, parenthesis): $dir"
  for daemon in munged slurmctld slurmd; do
    pidfile="$dir/$daemon.pid"
    [ $daemon = munged ] && pidfile="$dir/munge/munged.pid"
    [ -z "$(live_pid "$pidfile" $daemon)" ] ||
      die "$daemon already runs for $dir; tools/slurm-local.sh stop $dir first"
  done
  # From here on, whatever ends the start early stops what it started.
  trap 'exit 130' INT
  trap 'exit 143' TERM
  trap '[ $? -eq 0 ] || stop > /dev/null 2>&1' EXIT
  # munged refuses a socket in a folder that others may write to or may not enter; the job scripts
  # in the spool are executed.
  umask 022
  chmod go-w,go+x "$dir"
  mkdir -p "$dir/munge" "$dir/log" "$dir/state" "$dir/spool"
  chmod 0711 "$dir/munge"  # munged: others must reach the socket, not list the key
  write_munge_key
  start_munged
  write_slurm_conf
  start_slurm
  wait_idle
  # Quoted: the caller runs the line (eval, or sourcing env.sh), and DIR may hold $ ` ; ' or ".
  printf 'export SLURM_CONF=%q\n' "$dir/slurm.conf" > "$dir/env.sh"
  trap - EXIT INT TERM
  cat "$dir/env.sh"
}

stop() {
  local jobs
  [ -d "$dir" ] || return 0
  dir=$(cd "$dir" && pwd -P)
  # The jobs first, while slurmctld and munged can cancel them: their steps end their processes.
  if [ -n "$(live_pid "$dir/slurmctld.pid" slurmctld)" ]; then
    jobs=$(SLURM_CONF="$dir/slurm.conf" timeout 10 squeue --noheader --format=%F 2>/dev/null |
      sort -u | tr '\n' ' ' || true)
    if [ -n "${jobs// /}" ]; then
      # shellcheck disable=SC2086  # job ids
      SLURM_CONF="$dir/slurm.conf" timeout 10 scancel $jobs 2>/dev/null || true
      # shellcheck disable=SC2046  # pids
      wait_gone $(cluster_pids slurmstepd) || true
    fi
  fi
  # shellcheck disable=SC2046  # pids
  terminate slurmd $(live_pid "$dir/slurmd.pid" slurmd)
  # shellcheck disable=SC2046
  terminate slurmctld $(live_pid "$dir/slurmctld.pid" slurmctld)
  # shellcheck disable=SC2046
  terminate munged $(live_pid "$dir/munge/munged.pid" munged)
  # What is left: daemons without a pid file (a start that failed half-way), job steps, and
  # processes of jobs whose step is gone.
  # shellcheck disable=SC2046
  terminate "processes left by the cluster" $(cluster_pids)
  rm -f "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"
}

[ $# -eq 2 ] || usage
dir=$2
case "$1" in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
