#!/usr/bin/env python3
"""Writes three scenes of issue 25's benchmark set, built from their published descriptions:

env-preview.json  a material preview lit only by an environment map (our sky.hdr): a glossy
                  copper sphere on a diffuse sphere-shaped base, on a checkerboard floor, as in
                  Mitsuba's matpreview (whose mesh and museum map we may not ship).
glass-env.json    a glass sphere and a glass slab on a diffuse floor under the same sky: the
                  caustics come from the environment, the indirect light from the floor.
veach-mis.json    Veach's multiple-importance-sampling scene (thesis, fig. 9.2): four metal
                  plates of increasing roughness reflecting four spherical lights of equal power
                  and radii 0.03 to 0.9 of a plate's depth, in front of a diffuse wall and floor.

Run from anywhere: python3 bench/scenes/make_bench_scenes.py
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SKY = "../../scenes/textures/sky.hdr"


def write(name, scene):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


def floor_quad(size, material, y=0.0):
    return {"type": "quad", "origin": [-size, y, -size], "edge1": [0, 0, 2 * size], "edge2": [2 * size, 0, 0],
            "material": material}


def checker_floor():
    return {"type": "diffuse", "reflectance": {"type": "checkerboard", "color0": [0.2, 0.2, 0.2],
                                               "color1": [0.4, 0.4, 0.4], "to_uv": {"scale": 16}}}


def env_preview():
    return {
        "camera": {"position": [0, 2.2, -6.0], "look_at": [0, 0.9, 0], "up": [0, 1, 0], "fov": 30},
        "render": {"width": 320, "height": 240, "spp": 64},
        "integrator": {"type": "photon"},
        "materials": {
            "floor": checker_floor(),
            "base": {"type": "diffuse", "reflectance": [0.18, 0.18, 0.18]},
            "copper": {"type": "roughconductor", "material": "Cu", "distribution": "ggx", "alpha": 0.12},
        },
        "objects": [
            floor_quad(8, "floor"),
            {"name": "base", "type": "sphere", "center": [0, 0.35, 0], "radius": 0.35, "material": "base"},
            {"name": "object", "type": "sphere", "center": [0, 1.25, 0], "radius": 0.6, "material": "copper"},
        ],
        "lights": [{"name": "sky", "type": "envmap", "filename": SKY, "scale": 1.0}],
    }


def glass_env():
    return {
        "camera": {"position": [0, 3.0, -6.5], "look_at": [0, 0.6, 0], "up": [0, 1, 0], "fov": 32},
        "render": {"width": 320, "height": 240, "spp": 64},
        "integrator": {"type": "photon"},
        "materials": {
            "floor": {"type": "diffuse", "reflectance": [0.6, 0.6, 0.6]},
            "glass": {"type": "dielectric", "int_ior": 1.5},
        },
        "objects": [
            floor_quad(8, "floor"),
            {"name": "ball", "type": "sphere", "center": [-0.8, 0.8, 0], "radius": 0.8, "material": "glass"},
            {"name": "ball2", "type": "sphere", "center": [1.1, 0.45, -0.6], "radius": 0.45, "material": "glass"},
        ],
        "lights": [{"name": "sky", "type": "envmap", "filename": SKY, "scale": 1.0}],
    }


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def veach_mis():
    camera = [0.0, 2.0, 15.0]
    lights_at = [[-3.75, 5.0, 0.0], [-1.25, 5.0, 0.0], [1.25, 5.0, 0.0], [3.75, 5.0, 0.0]]
    radii = [0.03, 0.1, 0.3, 0.9]
    colours = [[1.0, 0.35, 0.25], [0.9, 0.8, 0.3], [0.3, 0.9, 0.4], [0.3, 0.5, 1.0]]
    alphas = [0.005, 0.02, 0.05, 0.1]  # the plates, smooth to rough, far to near
    materials = {
        "wall": {"type": "diffuse", "reflectance": [0.4, 0.4, 0.4]},
    }
    objects = [
        floor_quad(20, "wall", y=-2.5),
        {"type": "quad", "origin": [-20, -2.5, -4], "edge1": [40, 0, 0], "edge2": [0, 30, 0], "material": "wall"},
    ]
    # Equal power: radiance times area the same for every light (0.9's radiance is 100/(4 pi)...).
    for i, (p, r, c) in enumerate(zip(lights_at, radii, colours)):
        radiance = 0.9 * 0.9 * 6.0 / (r * r)
        materials[f"light{i}"] = {"type": "diffuse", "reflectance": [0, 0, 0], "emission": [radiance * x for x in c]}
        objects.append({"name": f"light{i}", "type": "sphere", "center": p, "radius": r, "material": f"light{i}"})
    # Each plate faces the bisector of the directions to the camera and to the lights' row.
    target = [0.0, 5.0, 0.0]
    for i, a in enumerate(alphas):
        centre = [0.0, -1.6 + 0.95 * i, 3.2 - 1.05 * i]
        to_cam = normalize([camera[k] - centre[k] for k in range(3)])
        to_light = normalize([target[k] - centre[k] for k in range(3)])
        n = normalize([to_cam[k] + to_light[k] for k in range(3)])
        # Edges: x across (width 8), and along n x X (depth 0.9).
        depth_dir = normalize([0.0, -n[2], n[1]])  # X cross n, perpendicular to both
        w, d = 8.0, 0.9
        origin = [centre[0] - w / 2, centre[1] - d / 2 * depth_dir[1], centre[2] - d / 2 * depth_dir[2]]
        e1 = [w, 0.0, 0.0]
        e2 = [0.0, d * depth_dir[1], d * depth_dir[2]]
        materials[f"plate{i}"] = {"type": "roughconductor", "material": "Al", "distribution": "ggx", "alpha": a}
        objects.append({"name": f"plate{i}", "type": "quad", "origin": origin, "edge1": e2, "edge2": e1,
                        "material": f"plate{i}"})
    return {
        "camera": {"position": camera, "look_at": [0, 0.2, 0.6], "up": [0, 1, 0], "fov": 38},
        "render": {"width": 384, "height": 256, "spp": 64},
        "integrator": {"type": "photon"},
        "materials": materials,
        "objects": objects,
    }


write("env-preview.json", env_preview())
write("glass-env.json", glass_env())
write("veach-mis.json", veach_mis())
