# A single-node Slurm cluster on the loopback interface for tests, sourced by tests/slurm/*.sh: munged, slurmctld
# and slurmd (Debian's munge and slurm-wlm) run in the foreground as children of this shell, with every key,
# socket, state file, spool and log under one folder and ports chosen free at start. Runs as root (SlurmUser and
# SlurmdUser root) without systemd or cgroups: proctrack/linuxproc, task/none. Every wait is bounded.
#
#   slurm_cluster_start DIR   start the daemons; exports SLURM_CONF; returns non-zero when they do not come up
#   slurm_cluster_stop        cancel the cluster's jobs, stop the daemons (TERM, then KILL after 10 s)
#   wait_for SECONDS WHAT CMD...       run CMD every 0.2 s until it succeeds; fails naming WHAT on timeout
#   job_state JOBID                    the job's state (COMPLETED, CANCELLED, ...) from slurmctld
#   wait_job_end SECONDS JOBID         wait until the job has ended; prints its final state

SLURM_DAEMON_PIDS=()
SLURM_CLUSTER_DIR=""

wait_for() {
  local seconds=$1 what=$2
  shift 2
  local deadline=$((SECONDS + seconds))
  until "$@" > /dev/null 2>&1; do
    if [ "$SECONDS" -ge "$deadline" ]; then
      echo "timed out after ${seconds}s waiting for $what" >&2
      return 1
    fi
    sleep 0.2
  done
}

slurm_free_port() {
  local port
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 40000))
    # A port nothing listens on refuses the connection.
    if ! timeout 2 bash -c "exec 3<>/dev/tcp/127.0.0.1/$port" 2> /dev/null; then
      echo "$port"
      return 0
    fi
  done
  return 1
}

slurm_node_idle() { [ "$(timeout 10 sinfo -h -n kilnnode -o %T 2> /dev/null)" = idle ]; }

slurm_cluster_start() {
  local dir=$1
  SLURM_CLUSTER_DIR=$dir
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chmod 755 "$dir" "$dir/munge"  # munged requires its socket's folder to be traversable by all
  mungekey --create --keyfile="$dir/munge/munge.key" || return 1
  chmod 600 "$dir/munge/munge.key"
  local socket="$dir/munge/socket"
  munged --foreground --key-file="$dir/munge/munge.key" --socket="$socket" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed" > "$dir/log/munged.out" 2>&1 &
  SLURM_DAEMON_PIDS+=($!)
  wait_for 20 "munged" munge --socket="$socket" --no-input || return 1

  local ctld_port slurmd_port
  ctld_port=$(slurm_free_port) && slurmd_port=$(slurm_free_port) || return 1
  [ "$ctld_port" != "$slurmd_port" ] || slurmd_port=$((ctld_port + 1))
  export SLURM_CONF="$dir/slurm.conf"
  cat > "$SLURM_CONF" << EOF
ClusterName=kilntest
SlurmctldHost=$(hostname -s)(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
CommunicationParameters=NoInAddrAny
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
KillWait=5
MinJobAge=600
MailProg=/bin/true
NodeName=kilnnode NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=kiln Nodes=kilnnode Default=YES MaxTime=INFINITE State=UP
EOF
  slurmctld -D -f "$SLURM_CONF" > "$dir/log/slurmctld.out" 2>&1 &
  SLURM_DAEMON_PIDS+=($!)
  slurmd -D -N kilnnode -f "$SLURM_CONF" > "$dir/log/slurmd.out" 2>&1 &
  SLURM_DAEMON_PIDS+=($!)
  wait_for 60 "the Slurm node to come up idle" slurm_node_idle
}

slurm_cluster_stop() {
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then
    timeout 10 scancel --user="$(id -un)" > /dev/null 2>&1 || true
    wait_for 30 "the jobs to end" bash -c '[ -z "$(timeout 10 squeue -h 2>&1)" ]' || true
  fi
  local pid i
  for ((i = ${#SLURM_DAEMON_PIDS[@]} - 1; i >= 0; i--)); do
    kill -TERM "${SLURM_DAEMON_PIDS[i]}" 2> /dev/null || true
  done
  for pid in "${SLURM_DAEMON_PIDS[@]}"; do
    wait_for 10 "daemon $pid to stop" bash -c "! kill -0 $pid" || kill -KILL "$pid" 2> /dev/null || true
    wait "$pid" 2> /dev/null || true
  done
  SLURM_DAEMON_PIDS=()
}

job_state() {
  local line
  line=$(timeout 10 scontrol show job -o "$1" 2> /dev/null) || return 1
  [[ "$line" =~ JobState=([A-Z_]+) ]] || return 1
  echo "${BASH_REMATCH[1]}"
}

job_ended() {
  case "$(job_state "$1")" in
    "" | PENDING | RUNNING | CONFIGURING | COMPLETING | REQUEUED | REQUEUE_HOLD | REQUEUE_FED | RESIZING | SUSPENDED | STAGE_OUT | SIGNALING) return 1 ;;
    *) return 0 ;;
  esac
}

wait_job_end() {
  wait_for "$1" "job $2 to end" job_ended "$2" || return 1
  job_state "$2"
}
