#!/usr/bin/env bash
# Runs the test suite (validation layer on), the timing benches and a few renders on a GPU machine
# from a bundle made by scripts/gpu_bundle.sh, in a checkout of the same commit.
#   scripts/gpu_check.sh BUNDLE.tar.xz RESULTS_DIR [STEP...]
# STEPs (default: all, in this order):
#   tests       every test binary, in parallel, FIRMAMENT_VALIDATION=1 (as CTest runs them)
#   clouds1080  firmament bench clouds --timing-only --timing-size 1920x1080
#   clouds360   firmament bench clouds --timing-only (640x360, the issue's lavapipe size)
#   atmosphere  firmament bench atmosphere --quick
#   cloudsquick firmament bench clouds --quick (errors against the CPU path tracer, GPU renders)
#   renders     scenes/default, thunderstorm and overcast at 640x360 (to compare with lavapipe's)
#   timelapse1080  31 frames of the fair-weather afternoon (12:00 UTC, 720x, 30 fps) at 1920x1080 and
#               of the night (22:00 UTC); per-frame wall times in each run's frames.csv
# A step named twice runs twice (its second folder gets _2: the run-to-run spread of the timings).
# REPEATS=N sets the benches' --repeats (default 3).
# RESULTS_DIR gets one folder or log per step and summary.txt. A step that fails is reported and the
# next one runs; the exit code is the number of failed steps.
# The NVIDIA driver's Vulkan library needs libglvnd (libGLdispatch, libGLX); a bare container may
# lack it: unpack Debian's libglvnd0, libglx0, libgl1, libegl1, libgles2 and libopengl0 first.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
bundle=$(realpath "${1:?usage: scripts/gpu_check.sh BUNDLE.tar.xz RESULTS_DIR [STEP...]}")
results=$(realpath -m "${2:?usage: scripts/gpu_check.sh BUNDLE.tar.xz RESULTS_DIR [STEP...]}")
shift 2
steps=("$@")
[ ${#steps[@]} -eq 0 ] && steps=(tests clouds1080 clouds360 atmosphere cloudsquick renders timelapse1080)
mkdir -p "$results"
summary=$results/summary.txt
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }

tar -C "$root" -xJf "$bundle"
# The test binaries carry the build machine's source and build paths (FIRMAMENT_SOURCE_DIR): point
# that path at this checkout, and ../shared/data beside it at the bundle's copy.
built_source=$(cat gpu-source-dir.txt)
if [ "$built_source" != "$root" ] && [ ! -e "$built_source" ]; then
  mkdir -p "$(dirname "$built_source")" && ln -s "$root" "$built_source"
fi
mkdir -p "$(dirname "$built_source")/shared"
[ -e "$(dirname "$built_source")/shared/data" ] || cp -r shared-data "$(dirname "$built_source")/shared/data"

export LD_LIBRARY_PATH=$root/gpu-lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export VK_LAYER_PATH=$root/gpu-layers
# The NVIDIA container images keep the driver's Vulkan manifest outside the loader's search path.
for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
  /etc/vulkan/icd.d/nvidia_icd.json; do
  if [ -f "$icd" ]; then export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd; break; fi
done
export FIRMAMENT_PROGRESS=0
fm=$root/build/samples/firmament

{ nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv 2>/dev/null || true; nproc; } |
  tee -a "$summary"
failed=0
run_step() {
  local name=$1
  shift
  local start=$SECONDS
  if "$@" >"$results/$name.log" 2>&1; then
    say "step $name: ok ($((SECONDS - start)) s)"
  else
    say "step $name: FAILED, exit $? ($((SECONDS - start)) s); the end of $name.log:"
    tail -n 30 "$results/$name.log" | tee -a "$summary"
    failed=$((failed + 1))
  fi
}

run_tests() {
  local pids=() t rc=0
  mkdir -p "$results/tests"
  for t in build/tests/test_*; do
    FIRMAMENT_VALIDATION=1 "$t" --gtest_brief=1 >"$results/tests/$(basename "$t").log" 2>&1 &
    pids+=($!)
  done
  for p in "${pids[@]}"; do wait "$p" || rc=1; done
  grep -h -E '^\[  (PASSED|FAILED)|^\[  FAILED|tests? ran' "$results"/tests/*.log
  return $rc
}

repeats=${REPEATS:-3}
for step in "${steps[@]}"; do
  out=$step
  [ -e "$results/$out" ] && out=${step}_2
  case $step in
    tests) run_step tests run_tests ;;
    clouds1080) run_step "$out" "$fm" bench clouds --timing-only --timing-size 1920x1080 --repeats "$repeats" --out "$results/$out" ;;
    clouds360) run_step "$out" "$fm" bench clouds --timing-only --repeats "$repeats" --out "$results/$out" ;;
    atmosphere) run_step "$out" "$fm" bench atmosphere --quick --out "$results/$out" ;;
    cloudsquick) run_step "$out" "$fm" bench clouds --quick --out "$results/$out" ;;
    renders)
      mkdir -p "$results/renders"
      for s in default thunderstorm overcast; do
        run_step "render_$s" "$fm" render "scenes/$s.json" --width 640 --height 360 -o "$results/renders/$s.exr"
      done
      ;;
    timelapse1080)
      for t in 12 22; do
        run_step "timelapse_$t" "$fm" timelapse scenes/fair-weather.json --from "2026-06-21T$t:00:00Z" \
          --to "2026-06-21T$t:12:00Z" --fps 30 --speed 720 --width 1920 --height 1080 --no-video \
          --out "$results/timelapse_$t"
        say "timelapse_$t: median frame_wall_s of frames 1.. = $(awk -F, 'NR > 2 { print $NF }' \
          "$results/timelapse_$t/frames.csv" 2>/dev/null | sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')"
      done
      ;;
    *) say "unknown step $step (tests clouds1080 clouds360 atmosphere cloudsquick renders timelapse1080)"; failed=$((failed + 1)) ;;
  esac
done
say "failed steps: $failed"
exit "$failed"
