#!/usr/bin/env python3
"""Photon mapping against path tracing at equal time, from Python (docs/python.md).

Renders a scene with `photon` and with `path` for the same number of seconds each, measures both
against a reference made of independent path-traced renders (their spread gives the reference's
own error, its floor, which the figures leave out), prints the metrics, and saves a figure: the
two images, the reference, their relative error maps, and the caustic photons in 3-D.

    PYTHONPATH=build/python python3 examples/equal_time.py --time 10
"""
import argparse
import pathlib

import numpy as np

import caustica

ROOT = pathlib.Path(__file__).resolve().parents[1]


def display(image):
    """Linear RGB to a displayable sRGB-ish array (clipped, gamma 2.2)."""
    return np.clip(image, 0, 1) ** (1 / 2.2)


def relative_error(image, reference):
    """Per-pixel relative squared error (as caustica's relmse), averaged over channels."""
    return (((image - reference) ** 2) / (reference ** 2 + 0.01)).mean(axis=2)


def run(scene_path, seconds, width, height, reference_renders=2, reference_seconds=None, seed=0):
    """The renders and metrics: a dict with the images, the reference, the metrics and the photons."""
    scene = caustica.load(scene_path, width=width, height=height)
    reference_seconds = reference_seconds or 2 * seconds
    references = [scene.render("path", time=reference_seconds, seed=1000 + i) for i in range(reference_renders)]
    result = {"reference": np.mean(references, axis=0), "images": {}, "metrics": {}}
    for integrator in ("photon", "path"):
        image = scene.render(integrator, time=seconds, seed=seed)
        result["images"][integrator] = image
        result["metrics"][integrator] = caustica.compare(image, references)
    # More caustic photons than a render pass of the pilot's choosing would trace: a picture of the map.
    result["caustic"] = scene.photons("caustic", seed=seed, caustic_photons=20000)
    return result


def figure(result, path):
    """Saves the comparison figure (matplotlib, no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(13, 8))
    reference = result["reference"]
    for i, (name, image) in enumerate(result["images"].items()):
        m = result["metrics"][name]
        ax = fig.add_subplot(2, 3, 1 + i)
        ax.imshow(display(image))
        ax.set_title(f"{name}: relMSE {m.get('relmse_floor_free', m['relmse']):.2e}")
        ax.axis("off")
        ax = fig.add_subplot(2, 3, 4 + i)
        err = ax.imshow(np.log10(relative_error(image, reference) + 1e-6), vmin=-4, vmax=0, cmap="viridis")
        ax.set_title(f"{name}: log10 relative error")
        ax.axis("off")
        fig.colorbar(err, ax=ax, fraction=0.046)
    ax = fig.add_subplot(2, 3, 3)
    ax.imshow(display(reference))
    ax.set_title("reference (mean of path renders)")
    ax.axis("off")
    ax = fig.add_subplot(2, 3, 6, projection="3d")
    photons = result["caustic"]
    if len(photons):
        pick = np.random.default_rng(0).choice(len(photons), size=min(len(photons), 4000), replace=False)
        p, flux = photons["position"][pick], photons["flux"][pick]
        colour = flux / np.maximum(flux.max(axis=1, keepdims=True), 1e-12)
        ax.scatter(p[:, 0], p[:, 2], p[:, 1], c=colour, s=1)
    ax.set_title(f"caustic photons ({len(photons)})")
    ax.set_xlabel("x")
    ax.set_ylabel("z")
    ax.set_zlabel("y")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "scenes" / "cornell-spheres.json"))
    parser.add_argument("--time", type=float, default=10.0, help="seconds per integrator")
    parser.add_argument("--width", type=int, default=192)
    parser.add_argument("--height", type=int, default=192)
    parser.add_argument("--reference-time", type=float, default=None, help="seconds per reference render (2x --time)")
    parser.add_argument("-o", "--output", default="equal_time.png")
    args = parser.parse_args()
    result = run(args.scene, args.time, args.width, args.height, reference_seconds=args.reference_time)
    for name, m in result["metrics"].items():
        print(f"{name:>7}: relMSE {m['relmse']:.4e} (without the reference's floor {m['relmse_floor_free']:.4e}), "
              f"RMSE {m['rmse']:.4e}, PSNR {m['psnr']:.2f} dB, mean {np.mean(m['mean_image']):.4f}")
    print(f"reference floor: {result['metrics']['path']['reference_floor']:.4e}; "
          f"caustic photons: {len(result['caustic'])}")
    figure(result, args.output)
    print(f"figure: {args.output}")


if __name__ == "__main__":
    main()
