#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs what is missing, builds, then
#   scripts/run.sh render [SCENE] [firmament render options...]   renders (default: scenes/default.json) into out/
#   scripts/run.sh test                                           runs the whole test suite (CTest)
#   scripts/run.sh build                                          only installs and builds
# Environment: BUILD_DIR (default build), FIRMAMENT_SKIP_INSTALL=1 to never call apt-get.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${BUILD_DIR:-build}
action=${1:-build}
[ $# -gt 0 ] && shift

# Debian 12 packages the project needs (docs/dependencies.md says why each).
packages=(cmake ninja-build g++ pkg-config libglm-dev nlohmann-json3-dev libopenexr-dev libpng-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools liberfa-dev
  libgeographiclib-dev libopenvdb-dev libboost-dev libgdal-dev libgtest-dev xplanet clang-format
  ffmpeg slurm-wlm munge libglfw3-dev libimgui-dev xvfb)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "${FIRMAMENT_SKIP_INSTALL:-0}" = 1 ]; then
    echo "missing packages: ${missing[*]}" >&2
    echo "install them with: sudo apt-get install -y ${missing[*]}" >&2
    exit 2
  elif [ "$(id -u)" = 0 ]; then
    echo "installing: ${missing[*]}" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
    sudo apt-get update -qq
    sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "missing packages: ${missing[*]}" >&2
    echo "install them with: sudo apt-get install -y ${missing[*]}" >&2
    exit 2
  fi
fi

jobs=$(nproc)
# configure_and_build DIR [cmake options...]; BUILD_TARGET limits what is built (default: all)
configure_and_build() {
  local dir=$1
  shift
  if [ ! -f "$dir/build.ninja" ]; then
    cmake -S . -B "$dir" -G Ninja "$@" >/dev/null
  fi
  cmake --build "$dir" -j "$jobs" ${BUILD_TARGET:+--target "$BUILD_TARGET"}
}

case "$action" in
  build)
    configure_and_build "$build" -DCMAKE_BUILD_TYPE=Release
    ;;
  render)
    BUILD_TARGET=firmament configure_and_build "$build" -DCMAKE_BUILD_TYPE=Release
    scene=scenes/default.json
    if [ $# -gt 0 ] && [[ "$1" != -* ]]; then scene=$1; shift; fi
    mkdir -p out
    name=$(basename "$scene" .json)
    "$build/samples/firmament" render "$scene" -o "out/$name.exr" "$@"
    ;;
  test)
    # The suite runs once, built optimised with AddressSanitizer + UndefinedBehaviorSanitizer
    # (RelWithDebInfo), so every test also checks memory and undefined behaviour.
    # FIRMAMENT_SKIP_SANITIZERS=1 runs it on the plain Release build instead.
    if [ "${FIRMAMENT_SKIP_SANITIZERS:-0}" = 1 ]; then
      configure_and_build "$build" -DCMAKE_BUILD_TYPE=Release
      ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"
    else
      tests=${build}-sanitize
      # -g1 (line tables only): sanitizer reports keep file:line, and the build (CI: 2 cores, 30 min)
      # spends less time writing and linking full debug information.
      configure_and_build "$tests" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFIRMAMENT_SANITIZE=ON \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
      LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0 \
      UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        ctest --test-dir "$tests" --output-on-failure -j "$jobs" "$@"
    fi
    ;;
  *)
    echo "usage: scripts/run.sh build|render [SCENE] [options]|test [ctest options]" >&2
    exit 2
    ;;
esac
