#!/usr/bin/env bash
# Stops what start_local_slurm.sh DIR started (slurmd, slurmctld, munged: by the pids in DIR/run).
#   scripts/slurm/stop_local_slurm.sh DIR
set -uo pipefail
dir=${1:?usage: $0 DIR}
for name in slurmd slurmctld munged; do
  pidfile="$dir/run/$name.pid"
  [ -f "$pidfile" ] || continue
  pid=$(cat "$pidfile")
  if kill "$pid" 2>/dev/null; then
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$pidfile"
done
echo "stop_local_slurm: stopped the local Slurm in $dir"
