#!/usr/bin/env python3
"""Writes scenes/smoke.vol, the density grid of scenes/smoke.json: a plume of smoke rising from
the floor, made of blobs along a wavering column and thinning as it rises, in Mitsuba's binary
.vol format (version 3, float32, one channel, its box [-1, 1] x [0, 3] x [-1, 1]).

Usage: python3 scripts/make_smoke_vol.py [OUTPUT]   (default scenes/smoke.vol)
Pure Python (no numpy); the output is the same on every run."""
import math
import struct
import sys

NX, NY, NZ = 32, 48, 32
BOX = (-1.0, 0.0, -1.0, 1.0, 3.0, 1.0)


def density(x, y, z):
    # The column's centre wavers with height; its radius grows and its density falls as it rises.
    cx = 0.25 * math.sin(2.1 * y) + 0.1 * math.sin(5.3 * y + 1.0)
    cz = 0.2 * math.cos(1.7 * y + 0.5)
    radius = 0.25 + 0.18 * y
    r2 = ((x - cx) ** 2 + (z - cz) ** 2) / (radius * radius)
    d = math.exp(-2.0 * r2) * math.exp(-0.45 * y)
    # Billows: a few periodic bumps, so that the plume is not smooth.
    d *= 0.65 + 0.35 * math.sin(7.0 * y + 3.0 * x) * math.cos(6.0 * z - 2.0 * y)
    # Fade out at the box's faces.
    edge = min(1.0 - abs(x), 1.0 - abs(z), y / 0.3, (3.0 - y) / 0.5)
    return max(0.0, d * min(1.0, max(0.0, edge * 4.0)))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/smoke.vol"
    values = []
    for k in range(NZ):
        z = BOX[2] + (BOX[5] - BOX[2]) * k / (NZ - 1)
        for j in range(NY):
            y = BOX[1] + (BOX[4] - BOX[1]) * j / (NY - 1)
            for i in range(NX):
                x = BOX[0] + (BOX[3] - BOX[0]) * i / (NX - 1)
                values.append(density(x, y, z))
    with open(out, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<5i", 1, NX, NY, NZ, 1))
        f.write(struct.pack("<6f", *BOX))
        f.write(struct.pack("<%df" % len(values), *values))


if __name__ == "__main__":
    main()
