#!/usr/bin/env python3
"""Writes scenes/textures/sky.pfm and converts it to sky.hdr (Radiance RGBE, via oiiotool): a
small latitude-longitude sky for scenes/material-spheres.json. A blue gradient above the
horizon, a grey ground below, and a sun of 2.5 degrees radius at 35 degrees elevation.
Directions map to pixels as in Mitsuba 3 (and Caustica's envmap): u = atan2(x, -z) / 2 pi,
v = acos(y) / pi, y up."""
import math
import os
import struct
import subprocess

W, H = 512, 256
SUN_ELEVATION, SUN_AZIMUTH, SUN_RADIUS = math.radians(35), math.radians(-60), math.radians(2.5)
SUN_RADIANCE = (900.0, 820.0, 700.0)


def direction(u, v):
    phi, theta = 2 * math.pi * u, math.pi * v
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = os.path.join(here, "..", "scenes", "textures")
    os.makedirs(out_dir, exist_ok=True)
    sun = direction(SUN_AZIMUTH / (2 * math.pi) % 1.0, (math.pi / 2 - SUN_ELEVATION) / math.pi)
    rows = []
    for y in range(H):
        row = []
        for x in range(W):
            d = direction((x + 0.5) / W, (y + 0.5) / H)
            if d[1] >= 0:
                t = d[1] ** 0.5
                c = (0.9 - 0.6 * t, 1.0 - 0.45 * t, 1.1 - 0.1 * t)  # white haze to blue
            else:
                c = (0.25, 0.23, 0.2)
            cos_sun = sum(a * b for a, b in zip(d, sun))
            if cos_sun > math.cos(SUN_RADIUS):
                c = SUN_RADIANCE
            row.append(c)
        rows.append(row)
    pfm = os.path.join(out_dir, "sky.pfm")
    with open(pfm, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (W, H))
        for row in reversed(rows):  # PFM stores the bottom row first
            for c in row:
                f.write(struct.pack("<3f", *c))
    subprocess.run(["oiiotool", pfm, "-o", os.path.join(out_dir, "sky.hdr")], check=True)
    os.remove(pfm)


if __name__ == "__main__":
    main()
