#!/usr/bin/env python3
"""Writes the curve files of scenes/mitsuba/curves.xml in Mitsuba's curve file format (one control
point "x y z radius" a line, a blank line between curves): helix.txt, a wire helix of three turns
around the y axis with a tapering radius and a straight stake through it (linearcurve), and
blades.txt, seven blades of grass bending in the wind (bsplinecurve: 6 control points each).

Usage: python3 scripts/make_helix_curve.py [FOLDER]   (default scenes/mitsuba)"""
import math
import sys


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "scenes/mitsuba"
    out = folder + "/helix.txt"
    lines = []
    n = 120
    for i in range(n + 1):
        s = i / n
        a = 3 * 2 * math.pi * s
        lines.append(f"{0.45 * math.cos(a):.6f} {1.5 * s:.6f} {0.45 * math.sin(a):.6f} {0.05 - 0.03 * s:.6f}")
    lines.append("")
    lines.append("0 0 0 0.03")
    lines.append("0 1.7 0 0.015")
    with open(out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(f"{out}: a helix of {n} segments and a stake")
    blades = []
    for b in range(7):
        x0, z0 = 0.25 * math.cos(2.4 * b) * (1 + 0.3 * b) * 0.5, 0.25 * math.sin(2.4 * b) * (1 + 0.3 * b) * 0.5
        lean = 0.5 + 0.08 * b
        height = 0.9 + 0.1 * math.sin(3.1 * b)
        for k in range(6):
            s_ = (k - 1) / 4.0  # the first point below the floor: the spline starts at it
            y = height * s_
            bend = lean * max(s_, 0.0) ** 2
            r = 0.03 * (1.0 - 0.8 * min(max(s_, 0.0), 1.0))
            blades.append(f"{x0 + bend:.6f} {y:.6f} {z0 + 0.3 * bend:.6f} {r:.6f}")
        blades.append("")
    with open(folder + "/blades.txt", "w") as fh:
        fh.write("\n".join(blades))
    print(f"{folder}/blades.txt: 7 blades of 6 control points")


if __name__ == "__main__":
    main()
