#!/usr/bin/env python3
"""Writes scenes/textures/bumps.pfm: a 64 x 64 single-channel height field for the bump-mapped
floor of scenes/mitsuba/principled.xml. One round bump per 16 x 16 cell, a smooth cosine cap
of height 1 and radius 7 texels, so the floor's shading shows rings of tilted normals; flat
between the bumps. PFM rows run bottom to top; images are read top-down, so they are written
in reverse."""
import math
import os
import struct

N, CELL, RADIUS = 64, 16, 7.0


def height(x, y):
    cx = (x // CELL) * CELL + CELL / 2 - 0.5
    cy = (y // CELL) * CELL + CELL / 2 - 0.5
    r = math.hypot(x - cx, y - cy)
    return 0.5 * (1.0 + math.cos(math.pi * r / RADIUS)) if r < RADIUS else 0.0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "..", "scenes", "textures", "bumps.pfm")
    with open(out, "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (N, N))
        for y in reversed(range(N)):
            f.write(struct.pack("<%df" % N, *(height(x, y) for x in range(N))))


if __name__ == "__main__":
    main()
