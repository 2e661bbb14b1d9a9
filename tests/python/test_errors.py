"""Bad arguments raise pathlab.Error with the command line's message, naming the argument."""
import pytest

import pathlab
from conftest import scene_path

BAD_SETTINGS = [
    (dict(max_length=0), "max_length"),
    (dict(max_length="5"), "max_length: expected an int, got str"),
    (dict(max_length=True), "max_length: expected an int, got bool"),
    (dict(beta=float("nan")), "beta: nan is not a finite number"),
    (dict(integrator="sppm"), "integrator"),
    (dict(integrator="vcm", techniques="all"), "integrator vcm sets the techniques"),
    (dict(mis="max"), "mis"),
    (dict(techniques="9,9,9"), "techniques"),
    (dict(isolate="M1,2"), "isolate"),
    (dict(radius_alpha=1.5, integrator="vcm"), "radius_alpha: Value 1.5 not in range"),
    (dict(noncaustic_photons=0, integrator="vcm"), "noncaustic_photons: Value 0 not in range"),
    (dict(width=-3), "width"),
    (dict(width=10000, height=10000), "is more than"),
    (dict(technique_maps=3, integrator="pt"), "technique_maps needs the bidirectional tracer"),
    (dict(unweighted=True), "unweighted"),
    (dict(rr="no"), "rr: expected a bool, got str"),
    (dict(colour=1), "unknown argument 'colour'"),
    (dict(seed=-1), "seed: -1 is negative"),
    (dict(beta=1e999), "beta: inf is not a finite number"),
    (dict(width=2**70), "width"),
]


@pytest.mark.parametrize("kwargs,message", BAD_SETTINGS, ids=[m for _, m in BAD_SETTINGS])
def test_bad_settings_name_the_argument(kwargs, message):
    with pytest.raises(pathlab.Error, match=None) as e:
        pathlab.Settings(**kwargs)
    assert message in str(e.value)
    assert "\n" not in str(e.value)


def test_bad_files_name_the_file(tmp_path):
    with pytest.raises(pathlab.Error) as e:
        pathlab.load(str(tmp_path / "missing.gltf"))
    assert "missing.gltf" in str(e.value)
    broken = tmp_path / "broken.gltf"
    broken.write_text("{ not json")
    with pytest.raises(pathlab.Error) as e:
        pathlab.load(str(broken))
    assert "broken.gltf" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.load(scene_path("cornell-box.gltf"), light_sampler="random")
    assert "light_sampler" in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        pathlab.load(scene_path("cornell-box.gltf"), environment=(1, 2))
    assert "environment" in str(e.value)


def test_paths_and_odd_values(tmp_path, box):
    import pathlib

    assert pathlab.load(pathlib.Path(scene_path("cornell-box.gltf"))).triangle_count == box.triangle_count
    with pytest.raises(pathlab.Error) as e:
        pathlab.load(str(tmp_path / "out--seed" / "box.gltf"))
    assert "out--seed" in str(e.value)  # a path is not an option
    assert pathlab.TechniqueSet("all") != "all" and len({pathlab.TechniqueSet("all"), pathlab.TechniqueSet(), pathlab.TechniqueSet("k=1")}) == 2
    for key in [("M", "a", 2), (2**40, 1), (None, None), (1,)]:
        with pytest.raises(pathlab.Error):
            key in pathlab.TechniqueSet()
    settings = pathlab.Settings(width=8, height=8)
    for kwargs, message in [(dict(pixel=(2**40, 0)), "pixel x"), (dict(pixel=(0, 0), sample=-1), "sample: -1"),
                            (dict(pixel=(0, 0), sample=2**70), "sample"), (dict(pixel="0,0"), "pixel must be")]:
        with pytest.raises(pathlab.Error) as e:
            pathlab.inspect(box, settings, **kwargs)
        assert message in str(e.value) and "\n" not in str(e.value)


def test_warnings_of_the_command_line(box):
    with pytest.warns(UserWarning, match="no enabled technique samples paths of length 2"):
        pathlab.Renderer(box, pathlab.Settings(width=8, height=8, max_length=2, techniques="k=1"))


def test_bad_render_calls(box):
    r = pathlab.Renderer(box, pathlab.Settings(width=8, height=8))
    for kwargs, message in [(dict(spp=0), "spp: 0 is outside"), (dict(spp=2**40), "spp: 1099511627776"),
                            (dict(spp=2, time=1.0), "not both"),
                            (dict(time=-1.0), "time -1"), (dict(progress=3), "progress")]:
        with pytest.raises(pathlab.Error) as e:
            r.render(**kwargs)
        assert message in str(e.value)
    with pytest.raises(pathlab.Error) as e:
        r.pyramid()
    assert "pyramid=K" in str(e.value)
