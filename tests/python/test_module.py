# `import caustica`: the module against the command line it wraps, and its errors, interrupts and
# threads (docs/python.md).
import json
import math
import struct
import subprocess
import threading
import time
import _thread

import numpy as np
import pytest

import caustica


def cli(exe, *args):
    subprocess.run([exe, *map(str, args)], check=True, capture_output=True)


def test_a_dict_scene_renders_as_its_file_does(tiny):
    from_file = caustica.load(tiny).render("path", spp=4, seed=3)
    from_dict = caustica.load(json.loads(tiny.read_text())).render("path", spp=4, seed=3)
    assert from_file.dtype == np.float32 and from_file.shape == (32, 32, 3)
    assert from_file.mean() > 0.05  # a lit room, not a black image
    assert np.array_equal(from_file, from_dict)


@pytest.mark.parametrize("integrator", ["path", "photon"])
def test_render_equals_the_command_lines_pfm_bit_for_bit(tiny, exe, tmp_path, integrator):
    out = tmp_path / "cli.pfm"
    cli(exe, "render", tiny, "--integrator", integrator, "--spp", 3, "--seed", 11, "-o", out, "-q")
    ours = caustica.load(tiny).render(integrator, spp=3, seed=11)
    theirs = caustica.read_image(str(out))
    assert ours.shape == theirs.shape
    assert np.array_equal(ours, theirs)
    # The seed matters (the comparison above is not between two constant images).
    assert not np.array_equal(ours, caustica.load(tiny).render(integrator, spp=3, seed=12))


def test_settings_and_size_reach_the_render(tiny, exe, tmp_path):
    out = tmp_path / "cli.pfm"
    cli(exe, "render", tiny, "--integrator", "photon", "--photons", 3000, "--width", 20, "--height", 10,
        "--spp", 2, "-o", out, "-q")
    ours = caustica.load(tiny, width=20, height=10).render("photon", spp=2, photons=3000)
    assert ours.shape == (10, 20, 3)
    assert np.array_equal(ours, caustica.read_image(str(out)))


def read_ply(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    n = int(next(line.split()[2] for line in header.splitlines() if line.startswith("element vertex")))
    record = np.dtype([("xyz", "<f4", 3), ("n", "<f4", 3), ("rgb", "u1", 3)])
    return np.frombuffer(data[end:], dtype=record, count=n)


@pytest.mark.parametrize("which", ["global", "caustic"])
def test_photon_arrays_match_the_command_lines_point_cloud(source, exe, tmp_path, which):
    scene = source / "scenes" / "cornell-spheres.json"
    ply = tmp_path / f"{which}.ply"
    cli(exe, "photons", scene, "--map", which, "--photons", 20000, "--caustic-photons", 20000, "-o", ply, "-q")
    theirs = read_ply(ply)
    ours = caustica.load(scene).photons(which, photons=20000, caustic_photons=20000)
    assert len(ours) == len(theirs) > 1000
    assert set(ours.dtype.names) == {"position", "normal", "direction", "flux", "bounces"}
    assert np.array_equal(ours["position"], theirs["xyz"])
    assert np.array_equal(ours["normal"], theirs["n"])
    # Flux: positive, and its hue is the PLY's colour (the brightest channel scaled to 255).
    flux = ours["flux"].astype(np.float64)
    assert (flux >= 0).all() and (flux.max(axis=1) > 0).all()
    hue = np.rint(255 * flux / flux.max(axis=1, keepdims=True))
    assert np.abs(hue - theirs["rgb"]).max() <= 1
    # Photons arrive from above their surface: the incoming direction faces the normal.
    assert (np.einsum("ij,ij->i", ours["direction"], ours["normal"]) > -1e-3).all()
    if which == "caustic":
        assert (ours["bounces"] >= 1).all()  # through the glass or off the mirror first


def test_errors_name_the_file_and_the_place(tiny, tmp_path):
    scene = json.loads(tiny.read_text())
    scene["objects"][7]["radius"] = -1
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(scene))
    with pytest.raises(caustica.SceneError, match=r"bad\.json: /objects/7/radius"):
        caustica.load(bad)
    with pytest.raises(caustica.SceneError, match=r"<dict>: /objects/7/radius"):
        caustica.load(scene)
    with pytest.raises(caustica.SceneError, match=r"<dict>: .*/render/spp"):
        caustica.load({"render": {"spp": "many"}, "objects": []})
    with pytest.raises(caustica.SceneError, match="no_such_file.xml"):
        caustica.load(tmp_path / "no_such_file.xml")
    broken = tmp_path / "broken.xml"
    broken.write_text('<scene version="3.0.0">\n  <shape type="sphere">\n</scene>\n')
    with pytest.raises(caustica.SceneError, match=r"broken\.xml:3"):
        caustica.load(broken)
    assert issubclass(caustica.SceneError, ValueError)


def test_bad_render_settings_raise(tiny):
    scene = caustica.load(tiny)
    with pytest.raises(caustica.SceneError, match="photons"):
        scene.render("photon", spp=1, photons=-5)
    with pytest.raises(caustica.SceneError, match="unknown integrator"):
        scene.render("nonsense", spp=1)
    with pytest.raises(ValueError, match="spp"):
        scene.render("path", spp=0)
    with pytest.raises(caustica.SceneError, match="aovs"):
        scene.render("path", spp=1, aovs=True)


def test_aovs_come_with_the_image(tiny):
    image, aovs = caustica.load(tiny).render("photon", spp=2, aovs=True)
    assert set(aovs) == {"photons", "radius"}
    assert aovs["radius"].shape == image.shape
    assert aovs["radius"][..., 0].max() > 0  # the global estimate's radius where it gathered


def test_defines_reach_a_mitsuba_scene(tmp_path):
    xml = tmp_path / "s.xml"
    xml.write_text("""<scene version="3.0.0">
  <default name="res" value="8"/>
  <sensor type="perspective"><float name="fov" value="45"/>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film></sensor>
  <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
  <shape type="sphere"><point name="center" x="0" y="0" z="-10"/></shape>
</scene>""")
    assert caustica.load(xml).render("path", spp=1).shape == (8, 8, 3)
    image = caustica.load(xml, res=6).render("path", spp=1)
    assert image.shape == (6, 6, 3)
    assert np.allclose(image, 0.5)  # the constant environment seen directly
    assert caustica.load(xml, defines={"res": 4}).render("path", spp=1).shape == (4, 4, 3)


def test_loader_warnings_are_python_warnings(tmp_path):
    xml = tmp_path / "w.xml"
    xml.write_text("""<scene version="3.0.0">
  <integrator type="moment"><integrator type="path"/></integrator>
  <shape type="sphere"/>
</scene>""")
    with pytest.warns(caustica.SceneWarning, match="moment"):
        scene = caustica.load(xml)
    assert any("moment" in w for w in scene.warnings)


def long_render(scene):
    return scene.render("path", spp=1_000_000, threads=1)


def test_interrupt_main_stops_a_long_render_with_its_passes(tiny):
    scene = caustica.load(tiny)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt) as e:
        long_render(scene)
    assert time.monotonic() - start < 20
    assert isinstance(e.value, caustica.RenderInterrupted)
    assert e.value.passes >= 1 and e.value.image.shape == (32, 32, 3) and e.value.image.mean() > 0.05
    # The scene renders again afterwards.
    assert scene.render("path", spp=1).mean() > 0.05


def test_cancel_from_another_thread_stops_a_render_there(tiny):
    scene = caustica.load(tiny)
    outcome = {}

    def worker():
        try:
            long_render(scene)
        except caustica.RenderInterrupted as e:
            outcome["passes"] = e.passes

    t = threading.Thread(target=worker)
    t.start()
    time.sleep(0.5)
    scene.cancel()
    t.join(timeout=20)
    assert not t.is_alive() and outcome["passes"] >= 1


def test_a_render_releases_the_gil(tiny):
    scene = caustica.load(tiny, width=64, height=64)
    ticks = [0]
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.monotonic()
    scene.render("path", spp=64, threads=1)
    seconds = time.monotonic() - start
    done.set()
    t.join()
    # Held for the whole render, the GIL would let the counter run only between Python lines.
    assert seconds > 0.2
    assert ticks[0] > 0.2 * seconds / 0.001 * 0.5


def test_compare_matches_the_command_line(tiny, exe, tmp_path):
    a, b, c = (tmp_path / f"{n}.exr" for n in "abc")
    for path, seed in ((a, 1), (b, 2), (c, 3)):
        cli(exe, "render", tiny, "--spp", 2, "--seed", seed, "-o", path, "-q")
    out = subprocess.run([exe, "compare", a, b, c, "--json"], check=True, capture_output=True, text=True).stdout
    theirs = json.loads(out)
    image = caustica.read_image(str(a))
    ours = caustica.compare(image, [caustica.read_image(str(b)), str(c)])
    for key in ("rmse", "relmse", "mae", "psnr", "reference_floor", "relmse_floor_free"):
        assert ours[key] == pytest.approx(theirs[key], rel=1e-6), key
    same = caustica.compare(image, image)
    assert same["rmse"] == 0 and math.isinf(same["psnr"])
    with pytest.raises(caustica.SceneError, match="16x16"):
        caustica.compare(image[:16, :16], image)


def test_converge_rows_fall_with_time(tiny):
    scene = caustica.load(tiny)
    reference = [scene.render("path", spp=256, seed=s) for s in (101, 102)]
    rows = caustica.converge(scene, ["path", "photon"], 1.0, [0.25, 0.5], references=reference)
    for name in ("path", "photon"):
        mine = [r for r in rows if r["integrator"] == name]
        assert len(mine) >= 2
        assert all(x["seconds"] < y["seconds"] and x["passes"] < y["passes"] for x, y in zip(mine, mine[1:]))
        assert mine[-1]["relmse"] < mine[0]["relmse"]
        assert "relmse_floor_free" in mine[0]


def test_images_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    image = rng.random((5, 7, 3), dtype=np.float32) * 4
    for ext in ("exr", "pfm", "hdr", "png"):
        path = str(tmp_path / f"x.{ext}")
        caustica.write_image(path, image)
        back = caustica.read_image(path)
        assert back.shape == image.shape
        if ext in ("exr", "pfm"):
            assert np.array_equal(back, image)
        elif ext == "hdr":
            # RGBE: 8 bits of mantissa for the largest channel, an exponent shared by all three
            assert (np.abs(back - image) <= 0.01 * image.max(axis=2, keepdims=True)).all()
        else:  # tone-mapped 8-bit sRGB: bright pixels clip to 1
            assert back.max() <= 1 and np.allclose(back, np.minimum(image, 1), atol=0.01)
    with pytest.raises(caustica.SceneError, match="no_such.exr"):
        caustica.read_image(str(tmp_path / "no_such.exr"))
    with pytest.raises(ValueError, match=r"\(5, 7, 2\)"):
        caustica.write_image(str(tmp_path / "y.exr"), np.zeros((5, 7, 2)))
