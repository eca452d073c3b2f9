#!/usr/bin/env bash
# Fetches the two small real elevation rasters the terrain tests read, from Debian's own packages, into
# DIR (default build/test-data/dem) unless they are there already:
#   DIR/terra/elev.tif               r-cran-terra: terra/ex/elev.tif (95 x 90, UInt16, LZW, WGS 84; Luxembourg)
#   DIR/stars/olinda_dem_utm25s.tif  r-cran-stars: stars/tif/olinda_dem_utm25s.tif (111 x 111, Float32, UTM 25S; Olinda)
# The packages are downloaded (apt-get download, no install; R is not needed) and unpacked with
# dpkg-deb -x; only the two files and the packages' copyright files are kept. CTest runs this as the
# fixture `terrain_test_data` before the terrain and CLI tests (tests/CMakeLists.txt). It needs apt's
# package lists: as root it runs `apt-get update` once if the download finds nothing.
set -euo pipefail
dir=${1:-build/test-data/dem}
terra=$dir/terra/elev.tif
stars=$dir/stars/olinda_dem_utm25s.tif
if [ -f "$terra" ] && [ -f "$stars" ]; then
  exit 0
fi
command -v apt-get >/dev/null && command -v dpkg-deb >/dev/null || {
  echo "fetch_test_dems: needs apt-get and dpkg-deb (Debian); or put $terra and $stars there by hand" >&2
  exit 1
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
download() { (cd "$tmp" && apt-get download -qq r-cran-terra r-cran-stars >/dev/null 2>&1); }
if ! download; then
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq >/dev/null 2>&1 || true
  fi
  download || {
    echo "fetch_test_dems: 'apt-get download r-cran-terra r-cran-stars' failed (no network, or no package lists:" \
         "run 'apt-get update' as root); then run: scripts/fetch_test_dems.sh $dir" >&2
    exit 1
  }
fi
for deb in "$tmp"/*.deb; do dpkg-deb -x "$deb" "$tmp/x"; done
lib=$tmp/x/usr/lib/R/site-library
mkdir -p "$dir/terra" "$dir/stars"
cp "$lib/terra/ex/elev.tif" "$terra.part" && mv "$terra.part" "$terra"
cp "$lib/stars/tif/olinda_dem_utm25s.tif" "$stars.part" && mv "$stars.part" "$stars"
cp "$tmp/x/usr/share/doc/r-cran-terra/copyright" "$dir/terra/copyright" 2>/dev/null || true
cp "$tmp/x/usr/share/doc/r-cran-stars/copyright" "$dir/stars/copyright" 2>/dev/null || true
echo "fetch_test_dems: $terra, $stars"
