#!/usr/bin/env bash
# Packs a Release build for a GPU machine that has a Vulkan driver but none of the build dependencies
# (no apt, no network): firmament, bench_sky_frame, the test binaries, the shared libraries they load
# beyond the C and C++ runtimes, the Vulkan loader, the validation layer and ../shared/data.
#   scripts/gpu_bundle.sh OUT.tar.xz        (after scripts/run.sh build)
# On the GPU machine, in a checkout of the same commit: scripts/gpu_check.sh OUT.tar.xz RESULTS_DIR.
# docs/gpu.md "Checking on a real GPU" says what the check runs and what it measured.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(realpath -m "${1:?usage: scripts/gpu_bundle.sh OUT.tar.xz}")
build=${BUILD_DIR:-build}
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT

binaries=("$build/samples/firmament" "$build/eval/micro/bench_sky_frame" "$build"/tests/test_*)
for b in "${binaries[@]}"; do
  [ -x "$b" ] || { echo "gpu_bundle: $b is missing; run scripts/run.sh build first" >&2; exit 2; }
  mkdir -p "$stage/$(dirname "$b")"
  cp "$b" "$stage/$b"
done

# Every library the binaries and the layer load, except the C/C++ runtime (the target's own, newer
# ones are compatible) and the loader's own Vulkan drivers (the GPU's driver comes with the machine).
layer=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
mkdir -p "$stage/gpu-lib" "$stage/gpu-layers"
ldd "${binaries[@]}" "$layer" | awk '/=> \//{print $3}' | sort -u |
  grep -Ev '/(libc|libm|libgcc_s|libstdc\+\+|ld-linux[^/]*)\.so' |
  while read -r lib; do cp -L "$lib" "$stage/gpu-lib/"; done
cp -L "$layer" "$stage/gpu-lib/"
cp /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json "$stage/gpu-layers/"
cp -r ../shared/data "$stage/shared-data"
echo "$PWD" >"$stage/gpu-source-dir.txt"  # FIRMAMENT_SOURCE_DIR of the test binaries

tar -C "$stage" -cJf "$out" .
echo "gpu_bundle: $out ($(du -h "$out" | cut -f1))"
