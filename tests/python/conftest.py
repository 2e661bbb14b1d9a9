"""Shared set-up of the Python module's tests: the module from the build tree (ctest sets
PYTHONPATH), the pathlab executable and the bundled scenes, and a PFM reader."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("PATHLAB_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXECUTABLE = os.environ.get("PATHLAB_EXECUTABLE", str(SOURCE / "build" / "app" / "pathlab"))


def scene_path(name):
    return str(SOURCE / "assets" / name)


def read_pfm(path):
    """A colour PFM as float32 (height, width, 3), top row first (PFM stores rows bottom-up)."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float32)


def run_cli(*args):
    """Runs `pathlab ARGS...`; returns the completed process (check it yourself)."""
    return subprocess.run([EXECUTABLE, *args], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="session")
def box():
    import pathlab

    return pathlab.load(scene_path("cornell-box.gltf"))
