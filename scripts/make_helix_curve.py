#!/usr/bin/env python3
"""Writes scenes/mitsuba/helix.txt, the wire of scenes/mitsuba/curves.xml: a helix of three turns
around the y axis with a tapering radius, and a straight stake through it, in Mitsuba's curve
file format (one control point "x y z radius" a line, a blank line between curves).

Usage: python3 scripts/make_helix_curve.py [OUTPUT]   (default scenes/mitsuba/helix.txt)"""
import math
import sys


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/mitsuba/helix.txt"
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


if __name__ == "__main__":
    main()
