#!/usr/bin/env bash
# CTest timelapse_slurm (fixture slurm_local: the local Slurm of scripts/slurm/start_local_slurm.sh in
# SLURM_DIR): a 6-frame time-lapse of 64x36 submitted as a 3-task array plus the dependent assemble job,
# waited for, and its EXR and PNG frames compared byte for byte with the single-process run's.
#   tests/timelapse/slurm_timelapse_test.sh FIRMAMENT SOURCE_DIR SLURM_DIR WORK_DIR
set -euo pipefail
firmament=$1 src=$2 slurm=$3 work=$4
# shellcheck disable=SC1091
source "$slurm/env.sh"
rm -rf "$work"
mkdir -p "$work"
args=("$src/scenes/fair-weather.json" --from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --fps 1 --speed 300
  --width 64 --height 36)
FIRMAMENT_PROGRESS=0 "$firmament" --quiet timelapse "${args[@]}" --no-video --out "$work/single"
FIRMAMENT="$firmament" timeout 300 "$src/scripts/slurm/submit_timelapse.sh" --wait 3 "$work/slurm" "${args[@]}"
failed=0
for i in 0 1 2 3 4 5; do
  for ext in exr png; do
    f=$(printf 'frame_%06d.%s' "$i" "$ext")
    if ! cmp -s "$work/single/$f" "$work/slurm/$f"; then
      echo "timelapse_slurm: $f of the Slurm run differs from the single-process run's (or is missing)" >&2
      failed=1
    fi
  done
done
[ -s "$work/slurm/timelapse.mp4" ] || { echo "timelapse_slurm: no timelapse.mp4 from the assemble job" >&2; failed=1; }
[ "$failed" = 0 ] && echo "timelapse_slurm: 6 frames from 3 array tasks equal the single-process run's byte for byte"
exit $failed
