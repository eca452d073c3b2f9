#!/usr/bin/env python3
"""A day through the night as one small image (docs/night.md, "A day through the night").

Renders a scene as a sequence of hourly frames with `firmament render --frames N --frame-interval 3600`
(the sun, Moon and stars follow the scene's time; the preview's exposure adapts from frame to frame as a
sequence's does), tiles the frames' PNG previews into a grid and prints each frame's sun altitude, mean
luminance and exposure. Python's standard library only (zlib): no image package needed.

  scripts/night_contact_sheet.py                       # docs/images/night-24h.png from the defaults below
  scripts/night_contact_sheet.py --firmament build/samples/firmament --scene scenes/night-full-moon.json \
      --start 2026-01-02T12:00:00Z --frames 24 --width 120 --height 68 --columns 6 --out sheet.png
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_png(path):
    """8-bit RGB or RGBA PNG (non-interlaced) -> (width, height, rows of RGB bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"{path}: only 8-bit RGB/RGBA, non-interlaced")
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        previous = line
        rows.append(bytes(line) if channels == 3 else bytes(v for j, v in enumerate(line) if j % 4 != 3))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + row for row in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--firmament", default=os.path.join(ROOT, "build", "samples", "firmament"))
    parser.add_argument("--scene", default=os.path.join(ROOT, "scenes", "night-full-moon.json"))
    parser.add_argument("--start", default="2026-01-02T12:00:00Z", help="UTC of the first frame")
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--interval", type=float, default=3600.0, help="seconds between frames")
    parser.add_argument("--width", type=int, default=120)
    parser.add_argument("--height", type=int, default=68)
    parser.add_argument("--yaw", type=float, default=180.0, help="camera yaw, deg (default south)")
    parser.add_argument("--pitch", type=float, default=20.0)
    parser.add_argument("--fov", type=float, default=90.0)
    parser.add_argument("--columns", type=int, default=6)
    parser.add_argument("--gap", type=int, default=2, help="pixels between frames")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "night-24h.png"))
    # Frames an hour apart: every cloud pixel marched (the reprojection of a 1/30 s sequence would carry
    # an hour-old cloud field into 15 of 16 pixels).
    parser.add_argument("--set", action="append", default=None, metavar="/PATH=VALUE",
                        help="scene overrides passed to render (default: /clouds/temporal_update=1)")
    args = parser.parse_args()
    if args.frames < 1 or args.columns < 1 or args.width < 8 or args.height < 8:
        print("night_contact_sheet: frames, columns >= 1 and width, height >= 8", file=sys.stderr)
        return 2

    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "frame.exr")
        command = [args.firmament, "render", args.scene, "-o", out, "--width", str(args.width), "--height",
                   str(args.height), "--frames", str(args.frames), "--frame-interval", str(args.interval),
                   "--set", f'/time/utc="{args.start}"', "--set", f"/camera/yaw_deg={args.yaw}", "--set",
                   f"/camera/pitch_deg={args.pitch}", "--set", f"/camera/fov_deg={args.fov}"]
        for override in args.set if args.set is not None else ["/clouds/temporal_update=1"]:
            command += ["--set", override]
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if result.returncode != 0:
            print(result.stdout, file=sys.stderr)
            return result.returncode
        frames = []
        for k in range(args.frames):
            base = os.path.join(folder, f"frame_{k:04d}")
            with open(base + ".json") as f:
                stats = json.load(f)
            frames.append((read_png(base + ".png"), stats))

    rows_count = (args.frames + args.columns - 1) // args.columns
    width = args.columns * args.width + (args.columns - 1) * args.gap
    height = rows_count * args.height + (rows_count - 1) * args.gap
    sheet = [bytearray(width * 3) for _ in range(height)]
    print("frame  sun altitude  mean cd/m^2  EV100")
    for k, ((w, h, rows), stats) in enumerate(frames):
        x0 = (k % args.columns) * (args.width + args.gap)
        y0 = (k // args.columns) * (args.height + args.gap)
        for y in range(min(h, args.height)):
            sheet[y0 + y][x0 * 3 : (x0 + min(w, args.width)) * 3] = rows[y][: min(w, args.width) * 3]
        print(f"{k:5d}  {90.0 - stats['sun']['zenith_deg']:+12.1f}  {stats['luminance_cd_m2']['mean']:11.4g}"
              f"  {stats['preview']['ev100']:+5.2f}")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    write_png(args.out, width, height, [bytes(r) for r in sheet])
    print(f"wrote {args.out} ({width}x{height}, {os.path.getsize(args.out)} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
