#!/usr/bin/env python3
"""The folders of core/ include each other without cycles (issue 11: tracers take options, not
RenderSettings; metrics/ only measures): prints any cycle of the folder include graph and fails.
Also fails when core/ includes ui/, app/, OpenGL, ImGui or MPI (which only app/ uses), and when a
kernel folder (the tracers and everything below them) includes a consumer of their results (issue
30: the kernel owns the interfaces its outputs implement, e.g. core/bpt/sample_sink.h)."""
import pathlib, re, sys

core = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent / "core")
include = re.compile(r'#include\s+[<"]([^">]+)[">]')
# The kernels and what they are built from; the consumers of what they compute (films, the check,
# maps, metrics, convergence runs, render sessions). A folder not named here fails the test, so a
# new folder is placed on purpose.
KERNEL = {"image", "io", "math", "sampling", "texture", "bsdf", "camera", "lights", "media", "scene", "counters", "bpt", "pt", "merge"}
# mlt drives the bidirectional kernel (its chains) into a film, as render does: a consumer.
CONSUMERS = {"film", "check", "maps", "metrics", "converge", "render", "mlt"}
edges, bad = {}, []
for d in sorted(p.name for p in core.iterdir() if p.is_dir()):
    if d not in KERNEL | CONSUMERS:
        bad.append(f"{core / d}: a folder neither in KERNEL nor in CONSUMERS (tests/core_layering_test.py)")
for f in sorted(core.rglob("*")):
    if f.suffix not in (".h", ".cpp"):
        continue
    folder = f.relative_to(core).parts[0]
    for target in include.findall(f.read_text(errors="replace")):
        parts = target.split("/")
        if parts[0] == "core" and len(parts) > 2 and parts[1] != folder:
            edges.setdefault(folder, set()).add(parts[1])
            if folder in KERNEL and parts[1] in CONSUMERS:
                bad.append(f"{f}: a kernel folder includes a consumer, {target}")
        if parts[0] in ("ui", "app") or target.startswith(("GL", "GLFW", "imgui", "EGL", "mpi")):
            bad.append(f"{f}: includes {target}")

def cycle_from(start):
    stack, on_path = [(start, iter(sorted(edges.get(start, ()))))], [start]
    while stack:
        node, children = stack[-1]
        child = next(children, None)
        if child is None:
            stack.pop(); on_path.pop(); continue
        if child in on_path:
            return on_path[on_path.index(child):] + [child]
        if len(on_path) < len(edges) + 1:
            stack.append((child, iter(sorted(edges.get(child, ()))))); on_path.append(child)
    return None

cycles = {tuple(c) for c in (cycle_from(n) for n in edges) if c}
for c in sorted(cycles):
    print("cycle: " + " -> ".join(c))
for b in bad:
    print(b)
print(f"{len(edges)} folders, {sum(len(v) for v in edges.values())} dependencies, "
      f"{len(cycles)} cycles, {len(bad)} forbidden includes")
sys.exit(1 if cycles or bad else 0)
