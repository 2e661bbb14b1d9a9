"""pathlab.inspect against `pathlab inspect --json`, and Renderer.technique_maps against what the
maps must satisfy (the shares of every technique add up to one; the dominant technique is the one
with the largest share)."""
import json

import numpy as np
import pytest

import pathlab
from conftest import run_cli, scene_path


@pytest.mark.parametrize("integrator", ["bpt", "vcm"])
def test_inspect_equals_the_command_lines_json(tmp_path, integrator):
    scene = scene_path("cornell-spheres.gltf")
    out = tmp_path / "sample.json"
    done = run_cli("inspect", scene, "--pixel", "20,27", "--sample", "3", "--width", "40", "--height", "40",
                   "--max-length", "5", "--integrator", integrator, "--json", str(out), "--force")
    assert done.returncode == 0, done.stderr
    expected = json.loads(out.read_text())
    got = pathlab.inspect(pathlab.load(scene),
                          pathlab.Settings(width=40, height=40, max_length=5, integrator=integrator),
                          pixel=(20, 27), sample=3)
    assert got == expected


def test_inspect_refuses_what_the_command_line_refuses(box):
    with pytest.raises(pathlab.Error) as e:
        pathlab.inspect(box, pathlab.Settings(width=8, height=8), pixel=(8, 0))
    assert "pixel (8, 0) is outside the 8 x 8 image" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.inspect(box, pathlab.Settings(integrator="pt"), pixel=(0, 0))
    assert "bidirectional" in str(e.value)


def test_technique_maps_shares_add_up_and_the_dominant_technique_wins(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=24, height=24, max_length=3, technique_maps=3))
    image = r.render(spp=4)
    maps = r.technique_maps()
    keys = maps["techniques"]
    # The index order: each length's connections by s, then its merges.
    assert keys[:6] == [(0, 2), (1, 1), (0, 3), (1, 2), (2, 1), ("M", 2, 2)]
    shares = np.stack([maps["share"][k] for k in maps["share"]])
    lit = shares[0] >= 0  # -1 where the image is black
    assert lit.sum() > 0.5 * lit.size
    np.testing.assert_allclose(shares[:, lit].sum(axis=0), 1.0, atol=1e-4)
    dominant, winner = maps["dominant"][None], maps["dominant_share"][None]
    assert dominant.dtype == np.int32 and dominant.shape == image.shape[:2]
    won = dominant >= 0
    best = shares.max(axis=0)
    np.testing.assert_allclose(winner[won], best[won], atol=1e-5)
    for y, x in zip(*np.nonzero(won)):
        assert maps["share"][keys[dominant[y, x]]][y, x] == pytest.approx(best[y, x], abs=1e-5)
    # The part of its length's image a technique cannot sample is a fraction (-1 where black).
    for fraction in maps["cannot_sample"].values():
        assert ((fraction == -1) | ((fraction >= 0) & (fraction <= 1))).all()


def test_technique_maps_need_the_settings():
    r = pathlab.Renderer(pathlab.load(scene_path("cornell-box.gltf")), pathlab.Settings(width=8, height=8))
    with pytest.raises(pathlab.Error) as e:
        r.technique_maps()
    assert "technique_maps=L" in str(e.value)


@pytest.mark.parametrize("integrator", ["bpt", "vcm"])
def test_check_equals_the_command_lines_json(tmp_path, integrator):
    scene = scene_path("cornell-spheres.gltf")
    out = tmp_path / "check.json"
    done = run_cli("check", scene, "--spp", "24", "--width", "24", "--height", "24", "--max-length", "3",
                   "--integrator", integrator, "--radius-levels", "2", "--json", str(out), "--force")
    assert done.returncode in (0, 1), done.stderr
    got = pathlab.check(pathlab.load(scene), pathlab.Settings(width=24, height=24, max_length=3, integrator=integrator),
                        spp=24, radius_levels=2)
    # The check sums its passes per render thread and adds the threads' sums in whichever order the
    # threads ran (TechniqueCheck::finishPass), so two runs may differ in a float's last bits (seen:
    # a merge fit's standard error, 0.0639056334970808 against 0.06390563349708078): numbers are
    # equal to 1e-9, everything else exactly.
    assert same_to_rounding(got, json.loads(out.read_text()))
    assert "agrees" in got and any(row["status"] == "agrees" for row in got["techniques"])


def same_to_rounding(a, b):
    if isinstance(a, float) or isinstance(b, float):
        return isinstance(a, (int, float)) and isinstance(b, (int, float)) and a == pytest.approx(b, rel=1e-9, abs=1e-12)
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same_to_rounding(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(same_to_rounding(x, y) for x, y in zip(a, b))
    return a == b


def test_check_refuses_what_check_does_not_take(box):
    with pytest.raises(pathlab.Error) as e:
        pathlab.check(box, pathlab.Settings(pyramid=2), spp=2)
    assert "pyramid" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.check(box, pathlab.Settings(integrator="vcm", radius_alpha=0.5), spp=2)
    assert "radius_alpha 0.5: check renders each radius fixed" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.check(box, pathlab.Settings(), spp=1)
    assert "spp" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.check(box, pathlab.Settings(), blocks="4")
    assert "blocks: expected an int, got str" in str(e.value)


@pytest.mark.parametrize("integrator", ["bpt", "vcm"])
def test_outliers_equal_the_command_lines_json(tmp_path, integrator):
    scene = scene_path("cornell-spheres.gltf")
    out = tmp_path / "outliers.json"
    done = run_cli("outliers", scene, "--spp", "6", "--top", "5", "--width", "32", "--height", "32",
                   "--max-length", "5", "--integrator", integrator, "--json", str(out), "--force")
    assert done.returncode == 0, done.stderr
    r = pathlab.Renderer(pathlab.load(scene),
                         pathlab.Settings(width=32, height=32, max_length=5, integrator=integrator))
    r.find_outliers(5)
    r.render(spp=6)
    got = r.outliers()
    assert len(got) == 5
    assert [o["luminance"] for o in got] == sorted((o["luminance"] for o in got), reverse=True)
    assert got == json.loads(out.read_text())["outliers"]


def test_outliers_are_refused_where_the_command_line_refuses_them(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=8, height=8, integrator="pt"))
    with pytest.raises(pathlab.Error) as e:
        r.find_outliers(3)
    assert "find_outliers" in str(e.value) and "bidirectional" in str(e.value)
    r = pathlab.Renderer(box, pathlab.Settings(width=8, height=8))
    with pytest.raises(pathlab.Error):
        r.find_outliers(-1)
    assert r.outliers() == []  # none kept without find_outliers


def test_variance_maps_are_the_variance_of_the_passes_estimates(box):
    """Each technique's map against the brute force: the sample variance, over the passes, of
    each pass's estimate, recovered from the pyramid's running means (luminance, as the maps)."""
    r = pathlab.Renderer(box, pathlab.Settings(width=16, height=16, max_length=3, variance_maps=3, seed=5))
    passes = 10
    estimates, previous = {}, {}
    for p in range(1, passes + 1):
        r.render(spp=1)
        for key, (weighted, _) in r.pyramid(max_length=3).items():
            mean = weighted.astype(np.float64)
            one = p * mean - (p - 1) * previous.get(key, 0.0)  # this pass's estimate
            previous[key] = mean
            luminance = one @ np.array([0.2126, 0.7152, 0.0722])
            estimates.setdefault(key, []).append(luminance)
    maps = r.variance_maps()
    checked = 0
    for key, v in maps["variance"].items():
        brute = np.var(np.stack(estimates[key]), axis=0, ddof=1)
        assert v.shape == brute.shape and v.dtype == np.float32
        np.testing.assert_allclose(v, brute, rtol=2e-3, atol=1e-6 * max(brute.max(), 1e-12))
        checked += brute.max() > 0
    assert checked >= 4  # most techniques of the box vary
    # 'techniques' lists merges too (index order); the box's bpt keeps none: zero variance.
    zero = np.zeros_like(maps["variance"][(0, 2)])
    variances = np.stack([maps["variance"].get(k, zero) for k in maps["techniques"]])
    dominant, share = maps["dominant"], maps["dominant_share"]
    varies = dominant >= 0
    assert varies.sum() > 0.5 * varies.size
    for y, x in zip(*np.nonzero(varies)):
        assert variances[dominant[y, x], y, x] == pytest.approx(variances[:, y, x].max(), rel=1e-5)
        assert share[y, x] == pytest.approx(variances[:, y, x].max() / variances[:, y, x].sum(), rel=1e-4)


def test_variance_maps_need_the_settings(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=8, height=8))
    with pytest.raises(pathlab.Error) as e:
        r.variance_maps()
    assert "variance_maps=L" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.Settings(integrator="pt", variance_maps=2)
    assert "variance_maps" in str(e.value) and "bidirectional" in str(e.value)
