#!/usr/bin/env python3
"""Pairs of PFM images hold the same values up to the order of floating-point additions: every
channel of every pixel within a relative tolerance (default 1e-6). Prints each pair's worst pixel;
exit 1 when any pair differs. Usage: compare_pfm.py [--tolerance T] A1.pfm B1.pfm [A2.pfm B2.pfm ...]"""
import struct
import sys


def read_pfm(path):
    with open(path, "rb") as f:
        magic = f.readline().strip()
        if magic != b"PF":
            sys.exit(f"{path}: not a colour PFM file")
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = f.read()
    endian = "<" if scale < 0 else ">"
    count = 3 * width * height
    if len(data) < 4 * count:
        sys.exit(f"{path}: truncated PFM data")
    return width, height, struct.unpack(f"{endian}{count}f", data[: 4 * count])


def compare(a_path, b_path, tolerance):
    wa, ha, a = read_pfm(a_path)
    wb, hb, b = read_pfm(b_path)
    if (wa, ha) != (wb, hb):
        print(f"{a_path} is {wa} x {ha}, {b_path} is {wb} x {hb}")
        return False
    if not any(v != 0.0 for v in a):
        print(f"{a_path}: every value is zero, nothing compared")
        return False
    worst, where, differing = 0.0, -1, 0
    for i, (x, y) in enumerate(zip(a, b)):
        scale = max(abs(x), abs(y))
        if scale == 0.0:
            continue
        relative = abs(x - y) / scale
        if relative > tolerance:
            differing += 1
        if relative > worst:
            worst, where = relative, i
    pixel = where // 3
    print(f"{a_path} vs {b_path}: {differing} of {len(a)} values beyond {tolerance:g}, worst {worst:.3g}"
          + (f" at pixel {pixel % wa},{pixel // wa}" if where >= 0 else ""))
    return differing == 0


def main():
    args = sys.argv[1:]
    tolerance = 1e-6
    if args[:1] == ["--tolerance"]:
        tolerance, args = float(args[1]), args[2:]
    if not args or len(args) % 2:
        sys.exit(__doc__)
    results = [compare(args[i], args[i + 1], tolerance) for i in range(0, len(args), 2)]
    sys.exit(0 if all(results) else 1)


main()
