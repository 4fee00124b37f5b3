#!/usr/bin/env python3
"""Writes scenes/caustic-ring.json: a mirrored ring (open cylinder of triangles) on a diffuse
floor under a low point light, the classic cardioid caustic scene."""
import json, math, os

SEGMENTS, RADIUS, HEIGHT = 256, 1.0, 0.35
verts, tris = [], []
for i in range(SEGMENTS):
    a = 2 * math.pi * i / SEGMENTS
    x, z = RADIUS * math.cos(a), RADIUS * math.sin(a)
    verts += [[round(x, 6), 0.0, round(z, 6)], [round(x, 6), HEIGHT, round(z, 6)]]
for i in range(SEGMENTS):
    j = (i + 1) % SEGMENTS
    b0, t0, b1, t1 = 2 * i, 2 * i + 1, 2 * j, 2 * j + 1
    tris += [[b0, t0, t1], [b0, t1, b1]]

scene = {
    "camera": {"position": [0.6, 4.2, 2.2], "look_at": [0.35, 0, 0], "up": [0, 1, 0], "fov": 40},
    "render": {"width": 512, "height": 512, "spp": 16},
    "integrator": {"type": "photon", "photons": 200000, "caustic_photons": 400000, "caustic_k": 60},
    "materials": {
        "white": {"type": "diffuse", "albedo": [0.75, 0.75, 0.75]},
        "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
    },
    "objects": [
        {"name": "floor", "type": "quad", "origin": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0],
         "material": "white"},
        {"name": "ring", "type": "mesh", "vertices": verts, "indices": tris, "material": "mirror"},
    ],
    "lights": [
        {"name": "low lamp", "type": "point", "position": [-6, 1.6, 0], "intensity": [60, 60, 60]},
    ],
}
out = os.path.join(os.path.dirname(__file__), "..", "scenes", "caustic-ring.json")
with open(out, "w") as f:
    json.dump(scene, f, separators=(",", ":"))
    f.write("\n")
