#!/usr/bin/env python3
"""Writes the media set-up benchmark of issue 37 (docs/benchmarks.md): assets/fog.gltf with N small
opaque quads (the floor's mesh scaled to 1 %) on a grid inside its fog volume, each a node of its own.
   tests/media/make_fog_crowd.py N OUT.gltf"""
import json, pathlib, sys

n, out = int(sys.argv[1]), pathlib.Path(sys.argv[2])
src = pathlib.Path(__file__).resolve().parents[2] / "assets" / "fog.gltf"
g = json.loads(src.read_text())
# fog.gltf embeds its buffers as data URIs, so the copy stands alone anywhere.
side = round(n ** (1 / 3)) + 1
nodes = g["scenes"][0]["nodes"]
count = 0
for i in range(side):
    for j in range(side):
        for k in range(side):
            if count == n:
                break
            # Inside the fog box (centre (0, 1.25, 0), half extents 1.49, 1.245, 1.49), off its walls.
            t = [-1.3 + 2.6 * i / (side - 1), 0.1 + 2.2 * j / (side - 1), -1.3 + 2.6 * k / (side - 1)]
            g["nodes"].append({"name": f"speck{count}", "mesh": 0, "scale": [0.01, 0.01, 0.01], "translation": t})
            nodes.append(len(g["nodes"]) - 1)
            count += 1
out.write_text(json.dumps(g))
