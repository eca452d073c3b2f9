#!/usr/bin/env bash
# Starts a single-node Slurm on this machine for tests and trials: munged, slurmctld and slurmd on
# localhost, every file (config, munge key and socket, state, logs, pids) under DIR. Needs root (slurmd
# runs jobs as their users) and the Debian packages slurm-wlm and munge. Writes DIR/env.sh: source it to
# point sbatch/squeue at this cluster (SLURM_CONF). Stop it with stop_local_slurm.sh DIR.
#   scripts/slurm/start_local_slurm.sh DIR [TIMEOUT_S]
set -euo pipefail
dir=${1:?usage: $0 DIR [TIMEOUT_S]}
timeout=${2:-60}
fail() { echo "start_local_slurm: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "needs root (slurmd starts jobs as their users); run as root or use a real cluster"
for p in munged slurmctld slurmd sbatch sinfo; do
  command -v "$p" >/dev/null || PATH="$PATH:/usr/sbin:/sbin" command -v "$p" >/dev/null ||
    fail "$p not found: apt-get install slurm-wlm munge"
done
export PATH="$PATH:/usr/sbin:/sbin"
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [ -f "$dir/env.sh" ]; then "$(dirname "$0")/stop_local_slurm.sh" "$dir" >/dev/null 2>&1 || true; fi
rm -rf "$dir"/{munge,state,spool,log,run}
mkdir -p "$dir"/{munge,state,spool,log,run}
chmod 700 "$dir/munge"

# A free TCP port from the kernel (bind to 0), for slurmctld and slurmd each.
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
ctld_port=$(free_port)
slurmd_port=$(free_port)
while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done

# munge: a fresh key and its own socket, so a system munged (if any) is left alone.
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munge.seed" --force ||
  fail "munged did not start: see $dir/log/munged.log"

host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
cat >"$dir/slurm.conf" <<CONF
ClusterName=firmament-local
SlurmctldHost=${host}(127.0.0.1)
SlurmctldPort=${ctld_port}
SlurmdPort=${slurmd_port}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=${dir}/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=${dir}/state
SlurmdSpoolDir=${dir}/spool/slurmd-%n
SlurmctldPidFile=${dir}/run/slurmctld.pid
SlurmdPidFile=${dir}/run/slurmd.pid
SlurmctldLogFile=${dir}/log/slurmctld.log
SlurmdLogFile=${dir}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=30
NodeName=${host} NodeAddr=127.0.0.1 CPUs=${cpus} RealMemory=${mem} State=UNKNOWN
PartitionName=local Nodes=${host} Default=YES MaxTime=INFINITE State=UP
CONF
echo "export SLURM_CONF=${dir}/slurm.conf" >"$dir/env.sh"
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start: see $dir/log/slurmctld.log"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start: see $dir/log/slurmd.log"

# Wait until the node takes jobs.
end=$((SECONDS + timeout))
until sinfo -h -N -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; do
  if [ $SECONDS -ge $end ]; then
    echo "start_local_slurm: the node is not idle after ${timeout} s (sinfo: $(sinfo -h -N -o '%T %E' 2>&1)); logs:" >&2
    tail -n 5 "$dir"/log/*.log >&2 || true
    "$(dirname "$0")/stop_local_slurm.sh" "$dir" >/dev/null 2>&1 || true
    exit 1
  fi
  sleep 0.5
done
echo "start_local_slurm: node ${host} idle (${cpus} CPUs; slurmctld port ${ctld_port}); source ${dir}/env.sh"
