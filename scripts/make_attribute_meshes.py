#!/usr/bin/env python3
"""Writes the meshes of scenes/mitsuba/mesh-attributes.xml, binary PLY files whose colours are
vertex or face properties, read through Mitsuba's mesh_attribute texture:

  scenes/mitsuba/meshes/ball-vertex-colours.ply  an icosphere (642 vertices) whose vertices carry
      `red green blue` as uchar, a smooth rainbow around the vertical axis (vertex_color);
  scenes/mitsuba/meshes/gem-face-colours.ply     an icosahedron subdivided once (80 faces), flat, whose
      faces carry `r g b` as uchar in six colours (face_color) and a float `shade_x` (face_shade);
  scenes/mitsuba/meshes/strip-light.ply          a 1 x 0.25 rectangle of 8 x 1 quads whose vertices
      carry float `red green blue` from warm to cool (the emitter's radiance, vertex_color).

uchar values are sRGB-encoded (Mitsuba decodes integer properties so); floats are linear."""
import colorsys
import math
import os
import struct


def icosphere(levels):
    t = (1.0 + 5 ** 0.5) / 2.0
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache, out = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                cache[key] = len(verts) - 1
            return cache[key]

        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = out
    return verts, faces


def write_ply(path, verts, vertex_props, vertex_rows, faces, face_props, face_rows):
    """vertex_props / face_props: (type, name) beyond x y z / vertex_indices; rows: values."""
    fmt = {"float": "f", "uchar": "B"}
    with open(path, "wb") as f:
        head = ["ply", "format binary_little_endian 1.0",
                "comment written by scripts/make_attribute_meshes.py",
                "element vertex %d" % len(verts), "property float x", "property float y", "property float z"]
        head += ["property %s %s" % p for p in vertex_props]
        head += ["element face %d" % len(faces), "property list uchar int vertex_indices"]
        head += ["property %s %s" % p for p in face_props]
        f.write(("\n".join(head) + "\nend_header\n").encode())
        vfmt = "<3f" + "".join(fmt[t] for t, _ in vertex_props)
        for v, row in zip(verts, vertex_rows):
            f.write(struct.pack(vfmt, *v, *row))
        ffmt = "".join(fmt[t] for t, _ in face_props)
        for face, row in zip(faces, face_rows):
            f.write(struct.pack("<B%di" % len(face), len(face), *face))
            f.write(struct.pack("<" + ffmt, *row))


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "mitsuba", "meshes")
    os.makedirs(out, exist_ok=True)

    verts, faces = icosphere(3)
    rows = []
    for x, y, z in verts:
        hue = (math.atan2(z, x) / math.pi) % 1.0  # twice round: the front half shows every hue
        r, g, b = colorsys.hsv_to_rgb(hue, 0.75 - 0.35 * abs(y), 0.9)
        rows.append([round(255 * c) for c in (r, g, b)])
    write_ply(os.path.join(out, "ball-vertex-colours.ply"), verts,
              [("uchar", "red"), ("uchar", "green"), ("uchar", "blue")], rows, faces, [], [[]] * len(faces))

    verts, faces = icosphere(1)
    palette = [(230, 60, 50), (240, 180, 40), (60, 170, 80), (40, 120, 220), (150, 70, 200), (235, 235, 235)]
    face_rows = []
    for i, (a, b, c) in enumerate(faces):
        cy = (verts[a][1] + verts[b][1] + verts[c][1]) / 3
        face_rows.append(list(palette[(i * 7) % len(palette)]) + [0.55 + 0.45 * (cy + 1) / 2])
    write_ply(os.path.join(out, "gem-face-colours.ply"), verts, [], [[]] * len(verts), faces,
              [("uchar", "r"), ("uchar", "g"), ("uchar", "b"), ("float", "shade_x")], face_rows)

    n = 8
    verts, rows, faces = [], [], []
    for i in range(n + 1):
        s = i / n
        warm, cool = (1.0, 0.55, 0.2), (0.25, 0.5, 1.0)
        colour = [warm[k] * (1 - s) + cool[k] * s for k in range(3)]
        for y in (-0.125, 0.125):
            verts.append((s - 0.5, y, 0.0))
            rows.append(colour)
    for i in range(n):
        a, b, c, d = 2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1
        faces += [(a, b, c), (a, c, d)]
    write_ply(os.path.join(out, "strip-light.ply"), verts,
              [("float", "red"), ("float", "green"), ("float", "blue")], rows, faces, [], [[]] * len(faces))


if __name__ == "__main__":
    main()
