#!/usr/bin/env bash
# A one-node Slurm cluster on 127.0.0.1 for tests/slurm.rs: no systemd, no cgroups, no
# accounting. Installs Debian's slurm-wlm and munge when missing (as root).
#
#   bash .ci/slurm.sh start DIR   config, keys, logs and state in DIR; prints SLURM_CONF
#   bash .ci/slurm.sh stop DIR    stops the daemons started in DIR
#   . .ci/slurm.sh                (sourced, as .ci/run does) starts one in a temporary
#                                 folder, exports SLURM_CONF and stops it when the shell exits
#
# SLURM_TEST_PORTS="CTLD SLURMD" picks the ports (default 6817 6818).
# What the cluster needs, as measured: munged runs as the munge user, its socket folder
# owned by it and the key mode 0600; SlurmUser=root, proctrack/linuxproc, task/none,
# CR_CPU (tasks share the node), the controller and node pinned to 127.0.0.1, and
# cred_expire=10 so a requeued task starts again after 10 s rather than 120.

slurm_install() {
  local need=()
  for p in slurm-wlm munge; do
    dpkg -s "$p" >/dev/null 2>&1 || need+=("$p")
  done
  [ ${#need[@]} -eq 0 ] && return 0
  if [ "$(id -u)" != 0 ]; then
    echo "slurm.sh: ${need[*]} missing and not root: cannot install" >&2
    return 1
  fi
  apt-get update -qq >/dev/null &&
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
}

slurm_start() {
  local dir=$1 ports=(${SLURM_TEST_PORTS:-6817 6818})
  [ "$(id -u)" = 0 ] || { echo "slurm.sh: the daemons need root" >&2; return 1; }
  slurm_install || { echo "slurm.sh: cannot install slurm-wlm and munge" >&2; return 1; }
  mkdir -p "$dir" && dir=$(cd "$dir" && pwd) || return 1
  chmod 0755 "$dir"
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chown munge:munge "$dir/munge" && chmod 0700 "$dir/munge"
  # The key: 1 KiB of random bytes, owned by munge, mode 0600.
  head -c 1024 /dev/urandom >"$dir/munge/munge.key"
  chown munge:munge "$dir/munge/munge.key" && chmod 0600 "$dir/munge/munge.key"
  runuser -u munge -- munged --force \
    --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" || { echo "slurm.sh: munged did not start" >&2; return 1; }

  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  # The node's memory as slurmd sees it (jobs asking for --mem are refused beyond it).
  mem=$(slurmd -C 2>/dev/null | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -n 1)
  cat >"$dir/slurm.conf" <<EOF
ClusterName=seasynth-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
KillWait=5
MpiDefault=none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=${mem:-1000} State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
EOF
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -f "$SLURM_CONF" -i || { echo "slurm.sh: slurmctld did not start" >&2; return 1; }
  slurmd -f "$SLURM_CONF" || { echo "slurm.sh: slurmd did not start" >&2; return 1; }
  local i
  for i in $(seq 100); do
    if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
      echo "$SLURM_CONF"
      return 0
    fi
    sleep 0.1
  done
  echo "slurm.sh: the node did not come up; see $dir/log" >&2
  return 1
}

slurm_stop() {
  local dir=$1 f pid
  for f in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    [ -n "$pid" ] && kill "$pid" 2>/dev/null
  done
  # Give the daemons up to 5 s to exit.
  for f in $(seq 50); do
    pgrep -F "$dir/slurmctld.pid" >/dev/null 2>&1 || pgrep -F "$dir/slurmd.pid" >/dev/null 2>&1 || break
    sleep 0.1
  done
  return 0
}

if [[ "${BASH_SOURCE[0]}" != "$0" ]]; then
  # Sourced: a cluster for this shell, stopped when it exits.
  SEASYNTH_SLURM_DIR=$(mktemp -d /tmp/seasynth-slurm.XXXXXX)
  if (set +e; slurm_start "$SEASYNTH_SLURM_DIR" >/dev/null); then
    export SLURM_CONF=$SEASYNTH_SLURM_DIR/slurm.conf
    trap 'slurm_stop "$SEASYNTH_SLURM_DIR"; rm -rf "$SEASYNTH_SLURM_DIR"' EXIT
    echo "Slurm: a one-node cluster on 127.0.0.1 ($SLURM_CONF)"
  else
    slurm_stop "$SEASYNTH_SLURM_DIR"
    echo "Slurm: no cluster (see above); tests/slurm.rs will skip"
  fi
else
  case "${1:-}" in
  start) slurm_start "${2:?usage: slurm.sh start DIR}" ;;
  stop) slurm_stop "${2:?usage: slurm.sh stop DIR}" ;;
  install) slurm_install ;;
  *)
    echo "usage: slurm.sh start DIR | stop DIR | install" >&2
    exit 2
    ;;
  esac
fi
