#!/usr/bin/env python3
"""Writes bench/scenes/cornell-recessed.json: a Cornell box whose small light sits at the top of a
shaft above a square hole in the ceiling (issue 25's benchmark set). The light sees the floor and
the lower walls through the hole; most of the ceiling and the upper walls see only indirect light,
which is where final gathering and path tracing differ most."""
import json
import os

H = 0.2      # half the hole's width
SHAFT = 0.3  # the shaft's height above the ceiling


def quad(name, origin, e1, e2, material):
    # The front side (an emitter's) is along cross(e1, e2).
    return {"type": "quad", "name": name, "origin": origin, "edge1": e1, "edge2": e2, "material": material}


def main():
    top = 2.0 + SHAFT
    objects = [
        quad("floor", [-1, 0, -1], [0, 0, 2], [2, 0, 0], "white"),
        quad("back-wall", [-1, 0, -1], [2, 0, 0], [0, 2, 0], "white"),
        quad("left-wall", [-1, 0, -1], [0, 0, 2], [0, 2, 0], "red"),
        quad("right-wall", [1, 0, -1], [0, 2, 0], [0, 0, 2], "green"),
        # The ceiling around the hole, facing down.
        quad("ceiling-front", [-1, 2, H], [2, 0, 0], [0, 0, 1 - H], "white"),
        quad("ceiling-back", [-1, 2, -1], [2, 0, 0], [0, 0, 1 - H], "white"),
        quad("ceiling-left", [-1, 2, -H], [1 - H, 0, 0], [0, 0, 2 * H], "white"),
        quad("ceiling-right", [H, 2, -H], [1 - H, 0, 0], [0, 0, 2 * H], "white"),
        # The shaft's walls.
        quad("shaft-back", [-H, 2, -H], [2 * H, 0, 0], [0, SHAFT, 0], "white"),
        quad("shaft-front", [-H, 2, H], [0, SHAFT, 0], [2 * H, 0, 0], "white"),
        quad("shaft-left", [-H, 2, -H], [0, SHAFT, 0], [0, 0, 2 * H], "white"),
        quad("shaft-right", [H, 2, -H], [0, 0, 2 * H], [0, SHAFT, 0], "white"),
        # The light closes the shaft's top, facing down.
        quad("light", [-H, top, -H], [2 * H, 0, 0], [0, 0, 2 * H], "light"),
        {"type": "sphere", "name": "left-sphere", "center": [-0.45, 0.35, -0.35], "radius": 0.35, "material": "white"},
        {"type": "sphere", "name": "right-sphere", "center": [0.45, 0.3, 0.2], "radius": 0.3, "material": "white"},
    ]
    scene = {
        "camera": {"position": [0, 1, 3.6], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 39},
        "render": {"width": 512, "height": 512, "spp": 64},
        "integrator": {"type": "photon"},
        "materials": {
            "white": {"type": "diffuse", "albedo": [0.73, 0.71, 0.68]},
            "red": {"type": "diffuse", "albedo": [0.63, 0.065, 0.05]},
            "green": {"type": "diffuse", "albedo": [0.14, 0.45, 0.09]},
            "light": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [60, 48, 32]},
        },
        "objects": objects,
    }
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cornell-recessed.json")
    with open(out, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
