"""Calling overhead of the Python module (issue 36's target: a 64x64 1-spp render from Python within
5 % of the same render from the CLI, minus process start-up).

The CLI's time without start-up is measured as the difference of two runs that differ only in
their pass count: `pathlab render --spp N1` and `--spp N2` load the same scene and write the same
image, so (t(N2) - t(N1)) / (N2 - N1) is the time of one 64x64 pass. From Python, one
`Renderer(...).render(spp=1)` call per pass: a fresh renderer and a single pass each time, so every
per-call cost (the renderer, the GIL, the thread that runs the pass, the array) is in it.

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_overhead.py build/app/pathlab
"""
import statistics
import subprocess
import sys
import time

import pathlab

EXECUTABLE = sys.argv[1] if len(sys.argv) > 1 else "build/app/pathlab"
SCENE = "assets/cornell-box.gltf"
OPTIONS = dict(width=64, height=64, threads=2)
N1, N2, ROUNDS, CALLS = 50, 1050, 5, 1000


def cli_seconds(spp):
    start = time.perf_counter()
    subprocess.run([EXECUTABLE, "render", SCENE, "--width", "64", "--height", "64", "--threads", "2",
                    "--spp", str(spp), "-o", "/tmp/python_overhead.pfm", "--force"],
                   check=True, capture_output=True)
    return time.perf_counter() - start


def python_seconds(scene, settings):
    start = time.perf_counter()
    for _ in range(CALLS):
        pathlab.Renderer(scene, settings).render(spp=1)
    return (time.perf_counter() - start) / CALLS


scene = pathlab.load(SCENE)
settings = pathlab.Settings(**OPTIONS)
cli, py = [], []
for _ in range(ROUNDS):  # interleaved: the machine's load falls on both
    cli.append((cli_seconds(N2) - cli_seconds(N1)) / (N2 - N1))
    py.append(python_seconds(scene, settings))
c, p = statistics.median(cli), statistics.median(py)
print(f"64x64, 1 spp, cornell-box, 2 threads, medians of {ROUNDS} rounds")
print(f"  CLI, one pass (start-up removed): {c * 1e3:.3f} ms   ({', '.join(f'{v * 1e3:.3f}' for v in cli)})")
print(f"  Python, Renderer(...).render(spp=1): {p * 1e3:.3f} ms   ({', '.join(f'{v * 1e3:.3f}' for v in py)})")
print(f"  Python / CLI: {p / c:.3f}")
