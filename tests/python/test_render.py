"""pathlab.Renderer against `pathlab render`: the same settings and seed give the same image, bit
for bit, and the same pyramid; counters and progress follow the passes."""
import numpy as np
import pytest

import pathlab
from conftest import read_pfm, run_cli, scene_path

# (scene, Settings keyword arguments, the same as command-line options)
CASES = [
    ("cornell-box.gltf", dict(width=48, height=40, seed=7, max_length=5),
     ["--width", "48", "--height", "40", "--seed", "7", "--max-length", "5"]),
    ("cornell-box.gltf", dict(width=40, height=40, integrator="pt"),
     ["--width", "40", "--height", "40", "--integrator", "pt"]),
    ("veach-mis.gltf", dict(width=48, mis="power", beta=3, techniques="s=0;s=1;2,2"),
     ["--width", "48", "--mis", "power", "--beta", "3", "--techniques", "s=0;s=1;2,2"]),
    ("cornell-spheres.gltf", dict(width=40, height=40, integrator="vcm", radius=0.01, radius_alpha=0.5),
     ["--width", "40", "--height", "40", "--integrator", "vcm", "--radius", "0.01", "--radius-alpha", "0.5"]),
    ("cornell-box.gltf", dict(width=32, height=32, integrator="lt", rr=False),
     ["--width", "32", "--height", "32", "--integrator", "lt", "--no-rr"]),
    ("door-ajar.gltf", dict(width=32, height=24, integrator="mlt", chains=50, bootstrap=2000, large_step=0.5),
     ["--width", "32", "--height", "24", "--integrator", "mlt", "--chains", "50", "--bootstrap", "2000",
      "--large-step", "0.5"]),
    ("cornell-box.gltf", dict(width=32, height=32, integrator="mlt", mlt_variant="pss", bootstrap=2000, sigma=0.05),
     ["--width", "32", "--height", "32", "--integrator", "mlt", "--mlt-variant", "pss", "--bootstrap", "2000",
      "--sigma", "0.05"]),
    ("cornell-box.gltf", dict(width=32, height=32, integrator="mlt", bootstrap=2000, mlt_direct=2),
     ["--width", "32", "--height", "32", "--integrator", "mlt", "--bootstrap", "2000", "--mlt-direct", "2"]),
]


@pytest.mark.parametrize("scene,kwargs,options", CASES, ids=[c[0] + ":" + " ".join(c[2][4:]) for c in CASES])
def test_image_equals_the_command_lines_bit_for_bit(tmp_path, scene, kwargs, options):
    out = tmp_path / "cli.pfm"
    done = run_cli("render", scene_path(scene), "--spp", "3", "-o", str(out), "--force", *options)
    assert done.returncode == 0, done.stderr
    r = pathlab.Renderer(pathlab.load(scene_path(scene)), pathlab.Settings(**kwargs))
    image = r.render(spp=3)
    assert image.dtype == np.float32 and image.shape == (r.height, r.width, 3)
    expected = read_pfm(out)
    assert image.shape == expected.shape
    assert np.array_equal(image, expected), f"max difference {np.abs(image - expected).max()}"


def test_variance_aware_mis_equals_the_command_line_past_its_pilot_passes(tmp_path):
    # 7 passes: the last 3 weighed with factors estimated from the passes before them.
    out = tmp_path / "va.pfm"
    scene = scene_path("cornell-box.gltf")
    done = run_cli("render", scene, "--spp", "7", "-o", str(out), "--force", "--width", "32", "--height", "32",
                   "--mis", "variance-aware")
    assert done.returncode == 0, done.stderr
    image = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=32, height=32, mis="variance-aware")).render(spp=7)
    assert np.array_equal(image, read_pfm(out))
    balance = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=32, height=32)).render(spp=7)
    assert not np.array_equal(image, balance)


def test_optimal_mis_equals_the_command_line_past_its_pilot_passes(tmp_path):
    # 9 passes: the last 5 corrected with coefficients solved after pass 4 (and 8).
    out = tmp_path / "optimal.pfm"
    scene = scene_path("cornell-box.gltf")
    done = run_cli("render", scene, "--spp", "9", "-o", str(out), "--force", "--width", "32", "--height", "32",
                   "--mis", "optimal")
    assert done.returncode == 0, done.stderr
    image = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=32, height=32, mis="optimal")).render(spp=9)
    assert np.array_equal(image, read_pfm(out))
    balance = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=32, height=32)).render(spp=9)
    assert not np.array_equal(image, balance)


def test_passes_accumulate_as_one_render(box):
    # 2 passes then 3 more: the image of a 5-pass render, and the array owns its pixels.
    settings = pathlab.Settings(width=24, height=24, seed=2)
    r = pathlab.Renderer(box, settings)
    first = r.render(spp=2)
    kept = first.copy()
    five = r.render(spp=3)
    assert r.spp == 5
    assert np.array_equal(first, kept)
    assert np.array_equal(five, pathlab.Renderer(box, settings).render(spp=5))
    assert not np.array_equal(first, five)


def test_pyramid_equals_the_command_lines_files(tmp_path):
    scene = scene_path("cornell-spheres.gltf")
    out = tmp_path / "p.pfm"
    done = run_cli("render", scene, "--width", "32", "--height", "32", "--spp", "2", "--integrator", "vcm",
                   "--pyramid", "3", "-o", str(out), "--force")
    assert done.returncode == 0, done.stderr
    r = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=32, height=32, integrator="vcm", pyramid=3))
    r.render(spp=2)
    pyramid = r.pyramid()
    # Every connection of lengths 1..3 and the merges M(2,2), M(2,3), M(3,2).
    assert set(pyramid) == {(0, 2), (1, 1), (0, 3), (1, 2), (2, 1), (0, 4), (1, 3), (2, 2), (3, 1),
                            ("M", 2, 2), ("M", 2, 3), ("M", 3, 2)}
    for key, (weighted, unweighted) in pyramid.items():
        tag = f"-m-s{key[1]}-t{key[2]}" if key[0] == "M" else f"-s{key[0]}-t{key[1]}"
        assert np.array_equal(weighted, read_pfm(tmp_path / f"p{tag}.pfm")), key
        assert np.array_equal(unweighted, read_pfm(tmp_path / f"p{tag}-unweighted.pfm")), key
    assert set(r.pyramid(max_length=1)) == {(0, 2), (1, 1)}


def test_counters_and_progress_follow_the_passes(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=20, height=10, max_length=4))
    seen = []
    r.render(spp=3, progress=lambda spp, seconds: seen.append((spp, seconds)))
    assert [spp for spp, _ in seen] == [1, 2, 3]
    assert all(b[1] >= a[1] > 0 for a, b in zip(seen, seen[1:]))
    c = r.counters()
    assert c["spp"] == 3 and c["camera_samples"] == 3 * 20 * 10
    assert c["rays"] > 0 and c["discarded"] == {"nan": 0, "inf": 0, "negative": 0}
    assert (1, 2) in c["techniques"] and c["techniques"][(1, 2)]["tried"] > 0
    assert "camera walks" in c["walks"]


def test_a_timed_render_renders_at_least_one_pass(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=16, height=16))
    r.render(time=0.2)
    assert r.spp >= 1 and r.seconds > 0


def test_scene_properties(box):
    centre, radius = box.bounds
    assert len(centre) == 3 and radius > 0
    assert box.lights >= 1 and box.triangle_count > 0
    assert box.camera["aspect_ratio"] == 1.0 and len(box.camera["camera_to_world"]) == 4
    # The size follows the camera's shape as on the command line: one side given, the other too.
    assert pathlab.Renderer(box, pathlab.Settings(width=30)).height == 30


def test_technique_sets():
    vcm = pathlab.Settings(integrator="vcm")
    assert str(vcm.techniques) == "all;m=all"
    assert ("M", 2, 3) in vcm.techniques and (1, 2) in vcm.techniques
    spec = pathlab.TechniqueSet("s=0;2,2")
    assert (0, 5) in spec and (1, 2) not in spec
    assert str(pathlab.Settings(techniques=spec).techniques) == str(spec)


def test_automatic_light_paths_equal_the_command_line_past_their_choices(tmp_path):
    # 10 passes of the default-lit environment scene: F leaves 1 after the 4th (and is chosen again
    # after the 8th); the module takes "auto" as the command line does.
    out = tmp_path / "auto.pfm"
    scene = scene_path("environment.gltf")
    done = run_cli("render", scene, "--spp", "10", "-o", str(out), "--force", "--width", "64", "--height", "48",
                   "--light-paths", "auto")
    assert done.returncode == 0, done.stderr
    assert "light paths auto: F = 0.0625" in done.stderr
    settings = pathlab.Settings(width=64, height=48, light_paths="auto")
    image = pathlab.Renderer(pathlab.load(scene), settings).render(spp=10)
    assert np.array_equal(image, read_pfm(out))
    fixed = pathlab.Renderer(pathlab.load(scene), pathlab.Settings(width=64, height=48)).render(spp=10)
    assert not np.array_equal(image, fixed)
