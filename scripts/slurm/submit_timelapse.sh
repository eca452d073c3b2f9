#!/usr/bin/env bash
# Submits a time-lapse to Slurm: an array of N tasks (each a block of frames) and an assemble job that
# runs once all of them succeeded (--dependency=afterok). Prints the two job ids.
#   scripts/slurm/submit_timelapse.sh [--wait] N DIR SCENE --from UTC --to UTC [timelapse options...]
# FIRMAMENT (default: firmament on PATH) names the program; extra sbatch options in SBATCH_EXTRA.
# --wait: return when the assemble job has ended, with its exit status.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
wait=""
if [ "${1:-}" = "--wait" ]; then wait="--wait"; shift; fi
if [ $# -lt 3 ]; then
  echo "usage: $0 [--wait] N DIR SCENE --from UTC --to UTC [timelapse options...]" >&2
  exit 2
fi
n=$1 dir=$2
shift 2
case "$n" in ''|*[!0-9]*|0) echo "$0: N '$n': allowed: a whole number of tasks, 1 or more" >&2; exit 2;; esac
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
export FIRMAMENT="${FIRMAMENT:-$(command -v firmament || echo firmament)}"
export TIMELAPSE_ARGS="$* --out $dir"
export TIMELAPSE_DIR="$dir"
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_EXTRA:-} --export=ALL --array=0-$((n - 1)) --chdir="$dir" "$here/timelapse.sbatch")
array=${array%%;*}
# shellcheck disable=SC2086
assemble=$(sbatch --parsable $wait ${SBATCH_EXTRA:-} --export=ALL --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
  --chdir="$dir" "$here/timelapse_assemble.sbatch")
echo "array job ${array} (${n} tasks), assemble job ${assemble%%;*}"
