#!/usr/bin/env bash
# Renders the same scenes with two builds of `firmament` and checks that every pixel is identical.
#
#   scripts/compare_builds.sh OLD_FIRMAMENT NEW_FIRMAMENT [OUT_DIR]
#
# What is rendered: every scene under scenes/ at its own size, every scene file under eval/scenarios/
# (the benchmark and calibration scenes; not the index files) at its own size, and a three-frame
# reprojected sequence of scenes/cumulus.json (the temporal history). A scenario whose terrain is a raster
# relative to its file (eval/scenarios/terrain/dem_luxembourg.json: terra/elev.tif) reads it from the
# test rasters scripts/fetch_test_dems.sh puts under build/test-data/dem (fetched first if missing;
# FIRMAMENT_DEM_DIR overrides the folder), as `bench terrain --dem-dir` does. Each build gets an empty cache folder of its own
# (FIRMAMENT_CACHE_DIR), so neither reads the other's atmosphere tables or noise textures.
# The pixels are compared with NEW_FIRMAMENT's `compare` (its "identical" field: every float equal);
# the EXR headers differ anyway (timings). Exit code 0: all identical; 1: some differ; 2: bad usage.
# Use it before and after a change that must not move a pixel (a refactor):
#   git worktree add /tmp/before <commit> && cmake -S /tmp/before -B /tmp/before/build -G Ninja && ...
#   scripts/compare_builds.sh /tmp/before/build/samples/firmament build/samples/firmament
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: scripts/compare_builds.sh OLD_FIRMAMENT NEW_FIRMAMENT [OUT_DIR]" >&2
  exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
out=${3:-out/compare_builds}
for exe in "$old" "$new"; do
  [ -x "$exe" ] || { echo "not an executable: $exe" >&2; exit 2; }
done
rm -rf "$out"
mkdir -p "$out/old" "$out/new" "$out/cache_old" "$out/cache_new"

# name|scene|extra render options
cases=()
for s in scenes/*.json; do cases+=("$(basename "$s" .json)|$s|"); done
if [ -d eval/scenarios ]; then
  while IFS= read -r s; do
    rel=${s#eval/scenarios/}
    cases+=("scenario_$(echo "${rel%.json}" | tr '/' '_')|$s|")
  done < <(find eval/scenarios -name '*.json' ! -name index.json | sort)
fi
cases+=("cumulus_sequence|scenes/cumulus.json|--frames 3 --yaw-rate 0.5")

# A relative "terrain"/"file" missing beside its scene is read from the test rasters (--dem-dir's convention).
dem_dir=${FIRMAMENT_DEM_DIR:-build/test-data/dem}
if grep -lq '"kind": "gdal"' scenes/*.json eval/scenarios/terrain/*.json 2>/dev/null; then
  scripts/fetch_test_dems.sh "$dem_dir" || { echo "compare_builds: cannot fetch the test rasters into $dem_dir" >&2; exit 2; }
  dem_dir=$(realpath "$dem_dir")
  for i in "${!cases[@]}"; do
    IFS='|' read -r name scene extra <<<"${cases[$i]}"
    file=$(sed -n 's/.*"kind": "gdal", "file": "\([^"/][^"]*\)".*/\1/p' "$scene")
    [ -n "$file" ] && [ ! -f "$(dirname "$scene")/$file" ] && cases[$i]="$name|$scene|$extra --set /terrain/file=$dem_dir/$file"
  done
fi

failed=0
compared=0
printf '%-44s %s\n' case result
for c in "${cases[@]}"; do
  IFS='|' read -r name scene extra <<<"$c"
  for side in old new; do
    exe=$old
    [ $side = new ] && exe=$new
    # shellcheck disable=SC2086
    if ! FIRMAMENT_CACHE_DIR="$out/cache_$side" FIRMAMENT_PROGRESS=0 \
        "$exe" --quiet render "$scene" -o "$out/$side/$name.exr" $extra >"$out/$side/$name.log" 2>&1; then
      echo "$name: the $side build failed (see $out/$side/$name.log)" >&2
      failed=1
      continue 2
    fi
  done
  # A sequence writes NAME_0000.exr ...; a still NAME.exr.
  for f in "$out/old/$name".exr "$out/old/$name"_[0-9][0-9][0-9][0-9].exr; do
    [ -f "$f" ] || continue
    g="$out/new/$(basename "$f")"
    j="$out/$(basename "$f" .exr).compare.json"
    compared=$((compared + 1))
    if [ ! -f "$g" ]; then
      printf '%-44s %s\n' "$(basename "$f" .exr)" "MISSING in the new build"
      failed=1
    elif "$new" --quiet compare "$g" "$f" --json "$j" >/dev/null 2>&1 && grep -q '"identical": true' "$j"; then
      printf '%-44s %s\n' "$(basename "$f" .exr)" identical
    else
      printf '%-44s %s\n' "$(basename "$f" .exr)" "DIFFERENT ($j)"
      failed=1
    fi
  done
done
echo "$compared images compared; $([ $failed = 0 ] && echo 'all identical' || echo 'some differ')"
exit $failed
