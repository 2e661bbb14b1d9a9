"""pathlab.converge against `pathlab converge`: by sample count the checkpoints and their errors are
the command line's (the images are the same bits); curves are arrays; Ctrl+C stops a run."""
import csv
import os
import signal
import threading
import time

import numpy as np
import pytest

import pathlab
from conftest import read_pfm, run_cli, scene_path


def test_curves_equal_the_command_lines_csv(tmp_path, box):
    ref = tmp_path / "ref.pfm"
    done = run_cli("render", scene_path("cornell-box.gltf"), "--width", "32", "--height", "32", "--spp", "32",
                   "--max-length", "4", "-o", str(ref), "--force")
    assert done.returncode == 0, done.stderr
    out = tmp_path / "conv"
    done = run_cli("converge", scene_path("cornell-box.gltf"), "-o", str(out), "--reference", str(ref), "--spp", "8",
                   "--max-length", "4", "--configs", "bpt;pt")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(open(out / "convergence.csv")))
    curves = pathlab.converge(box, {"bpt": pathlab.Settings(max_length=4),
                                    "pt": pathlab.Settings(max_length=4, integrator="pt")},
                              spp=8, reference=read_pfm(ref))
    assert list(curves) == ["bpt", "pt"]
    for label, curve in curves.items():
        mine = [r for r in rows if r["config"] == label]
        assert curve["spp"].tolist() == [int(r["spp"]) for r in mine]
        for key, column in [("rmse", "rmse"), ("relmse", "relmse"), ("mape", "mape"),
                            ("two_buffer_relmse", "twobuffer_relmse")]:
            np.testing.assert_allclose(curve[key], [float(r[column]) for r in mine], rtol=1e-5, err_msg=key)
        assert curve["image"].shape == (32, 32, 3)
        assert (np.diff(curve["seconds"]) > 0).all()
    # The final image is an 8-pass render's, bit for bit.
    assert np.array_equal(curves["bpt"]["image"],
                          pathlab.Renderer(box, pathlab.Settings(width=32, height=32, max_length=4)).render(spp=8))


def test_labels_masks_and_no_reference(box):
    curves = pathlab.converge(box, [pathlab.Settings(width=16, height=16, max_length=3),
                                    pathlab.Settings(width=16, height=16, max_length=3, mis="power")], spp=4)
    assert list(curves) == ["width=16 height=16 max_length=3", "width=16 height=16 max_length=3 mis=power"]
    assert "relmse" not in curves["width=16 height=16 max_length=3"]  # no reference: the two-buffer estimate only
    reference = curves["width=16 height=16 max_length=3"]["image"]
    mask = np.zeros((16, 16))
    mask[4:8, 4:8] = 1
    masked = pathlab.converge(box, pathlab.Settings(width=16, height=16, max_length=3, seed=9), spp=4,
                              reference=reference, mask=mask)
    whole = pathlab.converge(box, pathlab.Settings(width=16, height=16, max_length=3, seed=9), spp=4,
                             reference=reference)
    assert masked["width=16 height=16 max_length=3 seed=9"]["mse"][-1] != whole["width=16 height=16 max_length=3 seed=9"]["mse"][-1]


def test_bad_converge_calls(box):
    s = pathlab.Settings(width=8, height=8)
    for kwargs, message in [(dict(configs="bpt"), "configs must be"), (dict(configs=s, spp=1), "spp: 1 is outside"),
                            (dict(configs=s, reference=np.zeros((4, 4, 3))), "renders 8 x 8, the reference is 4 x 4"),
                            (dict(configs=s, clock="sun"), "clock"), (dict(configs=s, factor=1.0), "factor"),
                            (dict(configs=s, spp=2, reference=np.ones((8, 8, 3)), mask=np.zeros((8, 8))),
                             "selects no pixel"),
                            (dict(configs=s, spp=2, mask=np.ones((8, 8))), "give a reference"),
                            (dict(configs=[s, s], spp=2), "two configurations are labelled"),
                            (dict(configs=s, spp=2**40), "spp: 1099511627776 is outside")]:
        with pytest.raises(pathlab.Error) as e:
            pathlab.converge(box, **kwargs)
        assert message in str(e.value)


def test_ctrl_c_stops_a_run(box):
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        pathlab.converge(box, pathlab.Settings(width=64, height=64), time=20)
    timer.join()
    assert time.monotonic() - start < 10


def test_configs_from_any_sequence(box):
    # Items that live only while the sequence hands them out: converge keeps its own copies.
    class Fresh:
        def __len__(self):
            return 2

        def __getitem__(self, i):
            if i >= 2:
                raise IndexError(i)
            return pathlab.Settings(width=8, height=8, max_length=2 + i)

    curves = pathlab.converge(box, Fresh(), spp=2)
    assert list(curves) == ["width=8 height=8 max_length=2", "width=8 height=8 max_length=3"]
