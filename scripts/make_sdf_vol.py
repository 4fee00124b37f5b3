#!/usr/bin/env python3
"""Writes a signed distance grid for the `sdfgrid` shape in Mitsuba's binary .vol format
(version 3, float32, one channel; the box [0, 1]^3, which the shape does not use): a torus
(default) or a sphere, centred in the unit cube, negative inside.

Usage: python3 scripts/make_sdf_vol.py [torus|sphere] [N] [OUTPUT]
       (defaults: torus, 48 points a side, scenes/mitsuba/torus.vol)
Pure Python (no numpy); the output is the same on every run."""
import math
import struct
import sys


def torus(x, y, z):
    # Major radius 0.3 in the xz plane, minor radius 0.12.
    q = math.hypot(x, z) - 0.3
    return math.hypot(q, y) - 0.12


def sphere(x, y, z):
    return math.sqrt(x * x + y * y + z * z) - 0.35


def main():
    shape = sys.argv[1] if len(sys.argv) > 1 else "torus"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 48
    out = sys.argv[3] if len(sys.argv) > 3 else "scenes/mitsuba/torus.vol"
    f = {"torus": torus, "sphere": sphere}[shape]
    values = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                values.append(f(i / (n - 1) - 0.5, j / (n - 1) - 0.5, k / (n - 1) - 0.5))
    with open(out, "wb") as fh:
        fh.write(b"VOL" + bytes([3]))
        fh.write(struct.pack("<5i", 1, n, n, n, 1))
        fh.write(struct.pack("<6f", 0.0, 0.0, 0.0, 1.0, 1.0, 1.0))
        fh.write(struct.pack("<%df" % len(values), *values))
    print(f"{out}: {shape}, {n}^3 points")


if __name__ == "__main__":
    main()
