#!/usr/bin/env python3
"""Every scene in scenes/ as one small image (README, "Scenes").

Renders each scene file with `firmament render` at its own time and camera (a small size, every cloud
pixel marched: a still), tiles the PNG previews in file-name order into a grid and prints, per tile, the
scene, its sun altitude, mean luminance, exposure and frame time. Python's standard library only (the
PNG reader and writer of night_contact_sheet.py).

  scripts/scenes_contact_sheet.py                   # docs/images/scenes.png, 4 columns of 240x135
  scripts/scenes_contact_sheet.py --width 320 --height 180 --columns 3 --out sheet.png \
      --firmament build/samples/firmament scenes/cumulus.json scenes/thunderstorm.json
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

from night_contact_sheet import read_png, write_png

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenes", nargs="*", help="scene files (default: scenes/*.json)")
    parser.add_argument("--firmament", default=os.path.join(ROOT, "build", "samples", "firmament"))
    parser.add_argument("--width", type=int, default=240)
    parser.add_argument("--height", type=int, default=135)
    parser.add_argument("--columns", type=int, default=4)
    parser.add_argument("--gap", type=int, default=2, help="pixels between tiles")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "scenes.png"))
    args = parser.parse_args()
    scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "scenes", "*.json")))
    if not scenes or args.columns < 1 or args.width < 8 or args.height < 8:
        print("scenes_contact_sheet: at least one scene; columns >= 1; width, height >= 8", file=sys.stderr)
        return 2

    tiles = []
    with tempfile.TemporaryDirectory() as folder:
        for k, scene in enumerate(scenes):
            out = os.path.join(folder, f"scene_{k:02d}.exr")
            command = [args.firmament, "render", scene, "-o", out, "--width", str(args.width), "--height",
                       str(args.height)]
            result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            if result.returncode != 0:
                print(f"{scene}:\n{result.stdout}", file=sys.stderr)
                return result.returncode
            with open(out[:-4] + ".json") as f:
                stats = json.load(f)
            tiles.append((scene, read_png(out[:-4] + ".png"), stats))

    rows_count = (len(tiles) + args.columns - 1) // args.columns
    width = args.columns * args.width + (args.columns - 1) * args.gap
    height = rows_count * args.height + (rows_count - 1) * args.gap
    sheet = [bytearray(width * 3) for _ in range(height)]
    print("tile  row col  scene                      sun altitude  mean cd/m^2  EV100  frame s")
    for k, (scene, (w, h, rows), stats) in enumerate(tiles):
        x0 = (k % args.columns) * (args.width + args.gap)
        y0 = (k // args.columns) * (args.height + args.gap)
        for y in range(min(h, args.height)):
            sheet[y0 + y][x0 * 3 : (x0 + min(w, args.width)) * 3] = rows[y][: min(w, args.width) * 3]
        print(f"{k:4d}  {k // args.columns + 1:3d} {k % args.columns + 1:3d}  {os.path.basename(scene):25s}"
              f"  {90.0 - stats['sun']['zenith_deg']:+12.1f}  {stats['luminance_cd_m2']['mean']:11.4g}"
              f"  {stats['preview']['ev100']:+5.2f}  {stats['frame_ms'] / 1000.0:7.2f}")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    write_png(args.out, width, height, [bytes(r) for r in sheet])
    print(f"wrote {args.out} ({width}x{height}, {os.path.getsize(args.out)} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
