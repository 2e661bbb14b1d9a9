#!/usr/bin/env python3
"""Generates every glTF scene pathlab ships: the bundled scenes in assets/ and the small test
scenes (closed-form answers, loader coverage, malformed inputs) in tests/scenes/.

Run from anywhere:  python3 assets/make_scenes.py
All .gltf/.glb files it writes are generated: edit this script, never the files. The output is
deterministic (running it twice gives byte-identical files) and uses only the standard library.
Buffers and images are embedded as base64 data URIs so each .gltf is self-contained.

Conventions (see assets/README.md): metres, +y up, cameras look down their local -z; emission is
emissiveFactor (max component 1) x KHR_materials_emissive_strength; punctual light intensity is
radiant intensity in W/sr (point, spot) or irradiance in W/m^2 (directional), pathlab's reading of
KHR_lights_punctual. "Lambertian" materials are metallic 0, roughness 1, KHR_materials_specular
specularFactor 0 (no dielectric specular layer).
"""

import base64
import json
import math
import struct
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ASSETS = ROOT / "assets"
TESTS = ROOT / "tests" / "scenes"
BAD = TESTS / "bad"

FLOAT, UINT, USHORT = 5126, 5125, 5123
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
NEAREST, REPEAT = 9728, 10497

# The default scene of hierarchy.gltf, as a test must find it after flattening the node tree
# (world-space axis-aligned bounds and triangle count). Checked against the geometry below.
HIERARCHY_BOUNDS = ((-2.5, 0.0, -1.75), (2.0, 3.0, 1.25))
HIERARCHY_TRIANGLES = 48
HIERARCHY_SCENE0_TRIANGLES = 12


# ---------------------------------------------------------------------------------------------
# Small vector and float helpers

def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def mul(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    return mul(a, 1.0 / math.sqrt(dot(a, a)))


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def json_float(x):
    """The shortest decimal that reads back as the same float32 (so min/max match the data)."""
    x = f32(x)
    if x == 0.0 or not math.isfinite(x):
        return 0.0
    for digits in range(1, 10):
        s = f"{x:.{digits}g}"
        if f32(float(s)) == x:
            return float(s)
    return x


def clean(value):
    if isinstance(value, float):
        return json_float(value)
    if isinstance(value, dict):
        return {k: clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    return value


def quat_axis_angle(axis, angle):
    s = math.sin(angle / 2.0)
    x, y, z = normalize(axis)
    return (x * s, y * s, z * s, math.cos(angle / 2.0))


def quat_from_basis(right, up, back):
    """Quaternion (x, y, z, w) of the rotation whose matrix has these columns."""
    m00, m01, m02 = right[0], up[0], back[0]
    m10, m11, m12 = right[1], up[1], back[1]
    m20, m21, m22 = right[2], up[2], back[2]
    trace = m00 + m11 + m22
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    return q if q[3] >= 0.0 else tuple(-c for c in q)


def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    """Node rotation for a camera (or light) at eye whose local -z points at target."""
    back = normalize(sub(eye, target))
    right = normalize(cross(up, back))
    return quat_from_basis(right, cross(back, right), back)


def emission_factor_strength(radiance):
    strength = max(radiance)
    return tuple(c / strength for c in radiance), strength


# ---------------------------------------------------------------------------------------------
# Geometry: indexed triangle lists with per-vertex normals and uvs, winding always CCW about the
# normal (glTF front face).

class Geom:
    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def vertex(self, p, n, uv=(0.0, 0.0)):
        self.positions.append(tuple(p))
        self.normals.append(tuple(n))
        self.uvs.append(tuple(uv))
        return len(self.positions) - 1

    def triangle(self, i0, i1, i2):
        """Append with CCW winding about the vertex normals; zero-area triangles are dropped."""
        p0, p1, p2 = (self.positions[i] for i in (i0, i1, i2))
        gn = cross(sub(p1, p0), sub(p2, p0))
        if dot(gn, gn) < 1e-24:
            return
        n = add(add(self.normals[i0], self.normals[i1]), self.normals[i2])
        self.indices += [i0, i1, i2] if dot(gn, n) > 0.0 else [i0, i2, i1]

    def __iadd__(self, other):
        base = len(self.positions)
        self.positions += other.positions
        self.normals += other.normals
        self.uvs += other.uvs
        self.indices += [i + base for i in other.indices]
        return self


def merged(*geoms):
    out = Geom()
    for g in geoms:
        out += g
    return out


def rect(center, normal, half_u, half_v, u_dir=None, uv_scale=1.0):
    """A rectangle facing `normal`; u_dir (default: horizontal) is the image's right, and the
    glTF uv (0,0) is the top-left corner as seen from the front."""
    n = normalize(normal)
    if u_dir is None:
        u_dir = cross((0.0, 1.0, 0.0), n) if abs(n[1]) < 0.999 else (1.0, 0.0, 0.0)
    u = normalize(u_dir)
    v = cross(n, u)
    g = Geom()
    corners = ((-1, -1, 0, 1), (1, -1, 1, 1), (1, 1, 1, 0), (-1, 1, 0, 0))
    for su, sv, tu, tv in corners:
        p = add(center, add(mul(u, su * half_u), mul(v, sv * half_v)))
        g.vertex(p, n, (tu * uv_scale, tv * uv_scale))
    g.triangle(0, 1, 2)
    g.triangle(0, 2, 3)
    return g


def box(center, half, inward=False):
    """Axis-aligned box; normals outward, or inward for a closed room seen from inside."""
    g = Geom()
    for axis in range(3):
        for sign in (-1.0, 1.0):
            c, n = list(center), [0.0, 0.0, 0.0]
            c[axis] += sign * half[axis]
            n[axis] = -sign if inward else sign
            # rect's default u is horizontal: along z for x faces, along x otherwise.
            half_u = half[2] if axis == 0 else half[0]
            half_v = half[2] if axis == 1 else half[1]
            g += rect(tuple(c), tuple(n), half_u, half_v)
    return g


def polygon(points, toward):
    """A planar-ish quad from data; faces the side of `toward` (a direction). Non-planar quads
    (the Cornell box's left wall) get one flat normal per triangle."""
    p0, p1, p2, p3 = points
    n0 = normalize(cross(sub(p1, p0), sub(p2, p0)))
    n1 = normalize(cross(sub(p2, p0), sub(p3, p0)))
    if dot(n0, toward) < 0.0:
        n0, n1 = mul(n0, -1.0), mul(n1, -1.0)
    g = Geom()
    if dot(n0, n1) > 1.0 - 1e-12:
        ids = [g.vertex(p, n0) for p in points]
        g.triangle(ids[0], ids[1], ids[2])
        g.triangle(ids[0], ids[2], ids[3])
    else:
        for tri, n in (((p0, p1, p2), n0), ((p0, p2, p3), n1)):
            ids = [g.vertex(p, n) for p in tri]
            g.triangle(*ids)
    return g


def uv_sphere(center, radius, segments=48, rings=24):
    g = Geom()
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            g.vertex(add(center, mul(n, radius)), n, (j / segments, i / rings))
    row = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b = i * row + j, (i + 1) * row + j
            g.triangle(a, b, b + 1)
            g.triangle(a, b + 1, a + 1)
    return g


def lathe(profile, center=(0.0, 0.0, 0.0), segments=48):
    """Surface of revolution about the vertical axis through `center`. `profile` is a polyline
    of (radius, height) points; each edge gets its own flat profile normal, to its right when
    walking the profile (walk a closed solid from the bottom of the axis outward, up, inward)."""
    g = Geom()
    for (r0, y0), (r1, y1) in zip(profile, profile[1:]):
        nr, ny = normalize((y1 - y0, -(r1 - r0)))
        base = len(g.positions)
        for r, y, v in ((r0, y0, 0.0), (r1, y1, 1.0)):
            for j in range(segments + 1):
                phi = 2.0 * math.pi * j / segments
                c, s = math.cos(phi), -math.sin(phi)
                g.vertex(add(center, (r * c, y, r * s)), (nr * c, ny, nr * s), (j / segments, v))
        row = segments + 1
        for j in range(segments):
            a, b = base + j, base + row + j
            g.triangle(a, b, b + 1)
            g.triangle(a, b + 1, a + 1)
    return g


def prism():
    """A flat-shaded triangular prism along z: depth 1, cross-section base 1 at y = -0.25 and
    apex at y = 0.25."""
    tri = ((-0.5, -0.25), (0.5, -0.25), (0.0, 0.25))  # CCW seen from +z
    g = Geom()
    for z, nz in ((0.5, 1.0), (-0.5, -1.0)):
        g.triangle(*(g.vertex((x, y, z), (0.0, 0.0, nz), (x + 0.5, 0.25 - y)) for x, y in tri))
    for (xa, ya), (xb, yb) in zip(tri, tri[1:] + tri[:1]):
        n = normalize((yb - ya, -(xb - xa), 0.0))
        corners = ((xa, ya, 0.5), (xb, yb, 0.5), (xb, yb, -0.5), (xa, ya, -0.5))
        ids = [g.vertex(p, n, uv) for p, uv in zip(corners, ((0, 0), (1, 0), (1, 1), (0, 1)))]
        g.triangle(ids[0], ids[1], ids[2])
        g.triangle(ids[0], ids[2], ids[3])
    return g


def unindexed(geom):
    """The same triangles as a soup: three vertices of its own for every triangle."""
    soup = Geom()
    for i in geom.indices:
        soup.vertex(geom.positions[i], geom.normals[i], geom.uvs[i])
    return soup


# ---------------------------------------------------------------------------------------------
# The glTF builder: one binary buffer, one bufferView per accessor (or one interleaved view),
# everything 4-byte aligned.

class GltfBuilder:
    def __init__(self):
        self.bin = bytearray()
        self.lists = {k: [] for k in ("scenes", "nodes", "cameras", "meshes", "materials",
                                      "textures", "images", "samplers", "accessors", "bufferViews")}
        self.lights = []
        self.used = set()
        self.required = []
        self.default_scene = 0
        self.mesh_geometry = []  # per mesh, per primitive: (positions, triangle indices)

    def _append(self, kind, item):
        self.lists[kind].append(item)
        return len(self.lists[kind]) - 1

    # -- buffers

    def add_view(self, data, target=None, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        if target:
            view["target"] = target
        self.bin += data
        return self._append("bufferViews", view)

    def add_accessor(self, view, component_type, count, type_, offset=0, lo=None, hi=None):
        acc = {"bufferView": view}
        if offset:
            acc["byteOffset"] = offset
        acc.update({"componentType": component_type, "count": count, "type": type_})
        if lo is not None:
            acc["min"], acc["max"] = list(lo), list(hi)
        return self._append("accessors", acc)

    @staticmethod
    def _bounds(points):
        """Per component over the finite values (the NaN / Inf test files hold one bad one)."""
        columns = [[f32(c) for c in column if math.isfinite(c)] for column in zip(*points)]
        return tuple(min(c) for c in columns), tuple(max(c) for c in columns)

    def _float_accessor(self, values, type_, with_bounds=False):
        width = len(values[0])
        data = struct.pack(f"<{width * len(values)}f", *(c for v in values for c in v))
        lo, hi = self._bounds(values) if with_bounds else (None, None)
        return self.add_accessor(self.add_view(data, ARRAY_BUFFER), FLOAT, len(values), type_,
                                 lo=lo, hi=hi)

    def _interleaved(self, positions, normals, uvs):
        data = b"".join(struct.pack("<8f", *p, *n, *t) for p, n, t in zip(positions, normals, uvs))
        view = self.add_view(data, ARRAY_BUFFER, stride=32)
        lo, hi = self._bounds(positions)
        count = len(positions)
        return {"POSITION": self.add_accessor(view, FLOAT, count, "VEC3", 0, lo, hi),
                "NORMAL": self.add_accessor(view, FLOAT, count, "VEC3", 12),
                "TEXCOORD_0": self.add_accessor(view, FLOAT, count, "VEC2", 24)}

    def _primitive(self, positions, normals, uvs, indices, material, index_type, interleaved):
        if interleaved:
            attributes = self._interleaved(positions, normals, uvs)
        else:
            attributes = {"POSITION": self._float_accessor(positions, "VEC3", with_bounds=True)}
            if normals:
                attributes["NORMAL"] = self._float_accessor(normals, "VEC3")
            if uvs:
                attributes["TEXCOORD_0"] = self._float_accessor(uvs, "VEC2")
        prim = {"attributes": attributes}
        if indices is not None:
            fmt = "<%dI" if index_type == UINT else "<%dH"
            view = self.add_view(struct.pack(fmt % len(indices), *indices), ELEMENT_ARRAY_BUFFER)
            prim["indices"] = self.add_accessor(view, index_type, len(indices), "SCALAR")
        if material is not None:
            prim["material"] = material
        tris = list(indices) if indices is not None else list(range(len(positions)))
        return prim, (positions, tris)

    def add_mesh(self, positions, normals=None, uvs=None, indices=None, material=None, name=None,
                 index_type=UINT, interleaved=False):
        """A mesh with one primitive; returns the mesh index (add_primitive appends more)."""
        prim, geometry = self._primitive(positions, normals, uvs, indices, material, index_type,
                                         interleaved)
        self.mesh_geometry.append([geometry])
        mesh = {"name": name} if name else {}
        mesh["primitives"] = [prim]
        return self._append("meshes", mesh)

    def add_primitive(self, mesh, positions, normals=None, uvs=None, indices=None, material=None,
                      index_type=UINT, interleaved=False):
        prim, geometry = self._primitive(positions, normals, uvs, indices, material, index_type,
                                         interleaved)
        self.mesh_geometry[mesh].append(geometry)
        self.lists["meshes"][mesh]["primitives"].append(prim)

    def add_geom(self, geom, material, name, uvs=False, **kw):
        """Texture coordinates only where a test or a texture reads them."""
        return self.add_mesh(geom.positions, geom.normals, geom.uvs if uvs else None,
                             geom.indices, material, name, **kw)

    # -- materials and textures

    def add_material(self, name, base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=1.0, *,
                     lambertian=False, glass=False, emission=None, double_sided=False,
                     base_color_texture=None, metallic_roughness_texture=None,
                     emissive_texture=None, ior=None, volume=None, scatter=None, grid=None):
        """emission is the radiance Le (any magnitude): stored as a factor with max component 1
        times KHR_materials_emissive_strength."""
        pbr = {"baseColorFactor": list(base_color) + [1.0]}
        if base_color_texture is not None:
            pbr["baseColorTexture"] = {"index": base_color_texture}
        pbr["metallicFactor"], pbr["roughnessFactor"] = metallic, roughness
        if metallic_roughness_texture is not None:
            pbr["metallicRoughnessTexture"] = {"index": metallic_roughness_texture}
        mat = {"name": name, "pbrMetallicRoughness": pbr}
        ext = {}
        if emission is not None:
            factor, strength = emission_factor_strength(emission)
            mat["emissiveFactor"] = list(factor)
            if strength != 1.0:
                ext["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        if emissive_texture is not None:
            mat["emissiveTexture"] = {"index": emissive_texture}
        if lambertian:
            ext["KHR_materials_specular"] = {"specularFactor": 0.0}
        if glass:
            ext["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
            ext["KHR_materials_ior"] = {"ior": 1.5 if ior is None else ior}
        if volume is not None:
            # (attenuationColor, attenuationDistance): a closed mesh bounding a medium.
            color, distance = volume
            ext["KHR_materials_volume"] = {"thicknessFactor": 1.0, "attenuationColor": list(color),
                                           "attenuationDistance": distance}
        if scatter is not None:
            # (multiscatterColor, scatterAnisotropy): the KHR_materials_volume_scatter draft.
            color, g = scatter
            ext["KHR_materials_volume_scatter"] = {"multiscatterColor": list(color), "scatterAnisotropy": g}
        if grid is not None:
            # (uri, densityScale): PATHLAB_materials_volume_grid, the grid named "density".
            uri, scale = grid
            ext["PATHLAB_materials_volume_grid"] = {"uri": uri, "grid": "density", "densityScale": scale}
        if ext:
            mat["extensions"] = ext
            self.used.update(ext)
        if double_sided:
            mat["doubleSided"] = True
        return self._append("materials", mat)

    def add_emitter(self, name, radiance):
        """A one-sided emitter that reflects nothing: black, no specular layer."""
        return self.add_material(name, (0.0, 0.0, 0.0), lambertian=True, emission=radiance)

    def add_texture(self, png, sampler):
        uri = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
        image = self._append("images", {"uri": uri})
        return self._append("textures", {"sampler": sampler, "source": image})

    def add_sampler(self, mag=NEAREST, min_filter=NEAREST, wrap=REPEAT):
        return self._append("samplers", {"magFilter": mag, "minFilter": min_filter,
                                         "wrapS": wrap, "wrapT": wrap})

    # -- nodes, cameras, lights, scenes

    def add_node(self, name, mesh=None, camera=None, light=None, translation=None, rotation=None,
                 scale=None, matrix=None, children=None):
        node = {"name": name}
        for key, value in (("mesh", mesh), ("camera", camera), ("children", children),
                           ("matrix", matrix), ("translation", translation),
                           ("rotation", rotation), ("scale", scale)):
            if value is not None:
                node[key] = list(value) if isinstance(value, tuple) else value
        if light is not None:
            node["extensions"] = {"KHR_lights_punctual": {"light": light}}
        return self._append("nodes", node)

    def add_camera(self, name, yfov, aspect=1.0, znear=0.01):
        return self._append("cameras", {"name": name, "type": "perspective", "perspective": {
            "aspectRatio": aspect, "yfov": yfov, "znear": znear}})

    def add_camera_node(self, eye, target, yfov, aspect=1.0, name="camera"):
        return self.add_node(name, camera=self.add_camera(name, yfov, aspect),
                             translation=eye, rotation=look_at(eye, target))

    def add_orthographic_camera_node(self, eye, target, xmag, ymag, name="camera"):
        camera = self._append("cameras", {"name": name, "type": "orthographic", "orthographic": {
            "xmag": xmag, "ymag": ymag, "znear": 0.01, "zfar": 100.0}})
        return self.add_node(name, camera=camera, translation=eye, rotation=look_at(eye, target))

    def add_light(self, name, type_, intensity, color=(1.0, 1.0, 1.0), inner=None, outer=None):
        light = {"name": name, "type": type_, "color": list(color), "intensity": intensity}
        if type_ == "spot":
            light["spot"] = {"innerConeAngle": inner, "outerConeAngle": outer}
        self.used.add("KHR_lights_punctual")
        self.lights.append(light)
        return len(self.lights) - 1

    def add_scene(self, name, nodes, default=False):
        index = self._append("scenes", {"name": name, "nodes": list(nodes)})
        if default:
            self.default_scene = index
        return index

    # -- output

    def document(self, buffer_uri=None):
        doc = {"asset": {"version": "2.0", "generator": "pathlab assets/make_scenes.py"}}
        if self.used:
            doc["extensionsUsed"] = sorted(self.used)
        if self.required:
            doc["extensionsRequired"] = list(self.required)
        doc["scene"] = self.default_scene
        for kind, items in self.lists.items():
            if items:
                doc[kind] = items
        buf = {"byteLength": len(self.bin)}
        if buffer_uri is not None:
            buf["uri"] = buffer_uri
        doc["buffers"] = [buf]
        if self.lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        return clean(doc)

    def gltf_bytes(self):
        uri = "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode("ascii")
        return (json.dumps(self.document(uri), indent=2) + "\n").encode("ascii")

    def glb_bytes(self):
        text = json.dumps(self.document(), separators=(",", ":")).encode("ascii")
        text += b" " * (-len(text) % 4)
        blob = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        chunks = (struct.pack("<II", len(text), 0x4E4F534A) + text +
                  struct.pack("<II", len(blob), 0x004E4942) + blob)
        return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def write(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    print(f"wrote {path.relative_to(ROOT)} ({len(data)} bytes)")


# ---------------------------------------------------------------------------------------------
# Node-tree walk, for the facts a loader test checks (world bounds, triangle count)

def node_matrix(node):
    """Row-major 4x4 local transform of a glTF node."""
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    x, y, z, w = node.get("rotation", (0.0, 0.0, 0.0, 1.0))
    sx, sy, sz = node.get("scale", (1.0, 1.0, 1.0))
    tx, ty, tz = node.get("translation", (0.0, 0.0, 0.0))
    rot = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
           [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
           [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[rot[r][0] * sx, rot[r][1] * sy, rot[r][2] * sz, (tx, ty, tz)[r]] for r in range(3)] \
        + [[0.0, 0.0, 0.0, 1.0]]


def matmul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def scene_facts(builder, scene):
    """(world bounds, triangle count) of one scene of a builder, flattening the node tree."""
    doc = builder.document()
    lo, hi, triangles = [math.inf] * 3, [-math.inf] * 3, 0
    stack = [(n, [[float(r == c) for c in range(4)] for r in range(4)])
             for n in doc["scenes"][scene]["nodes"]]
    while stack:
        index, parent = stack.pop()
        node = doc["nodes"][index]
        world = matmul(parent, node_matrix(node))
        if "mesh" in node:
            for positions, tris in builder.mesh_geometry[node["mesh"]]:
                triangles += len(tris) // 3
                for p in positions:
                    q = [dot(world[r][:3], p) + world[r][3] for r in range(3)]
                    lo = [min(a, b) for a, b in zip(lo, q)]
                    hi = [max(a, b) for a, b in zip(hi, q)]
        stack += [(c, world) for c in node.get("children", [])]
    return (tuple(round(v, 6) + 0.0 for v in lo), tuple(round(v, 6) + 0.0 for v in hi)), triangles


# ---------------------------------------------------------------------------------------------
# PNG writer (8-bit RGB, no filtering) for the texture test scene

def png(rows):
    """rows: list of rows of (r, g, b) bytes, row 0 at the top."""
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + \
            struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    height, width = len(rows), len(rows[0])
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


# ---------------------------------------------------------------------------------------------
# Bundled scenes

# The Cornell box as measured (http://www.graphics.cornell.edu/online/box/data.html), in mm;
# the camera looks along +z from z = -800 with the red wall on the left (x = 556).
CORNELL_WALLS = {
    "floor": [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)],
    "ceiling": [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)],
    "backWall": [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)],
    "redWall": [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)],
    "greenWall": [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)],
}
CORNELL_SHORT_BLOCK = [
    [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
    [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
    [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
    [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
    [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)],
]
CORNELL_TALL_BLOCK = [
    [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
    [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
    [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
    [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
    [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)],
]


def mm(points):
    return [tuple(c * 0.001 for c in p) for p in points]


def centroid(points):
    return mul(tuple(map(sum, zip(*points))), 1.0 / len(points))


def cornell_walls(b):
    """The measured box's materials and walls; returns the white material, the light's material and
    the wall nodes."""
    white = b.add_material("white", (0.73, 0.73, 0.73), lambertian=True)
    red = b.add_material("red", (0.63, 0.065, 0.05), lambertian=True)
    green = b.add_material("green", (0.14, 0.45, 0.091), lambertian=True)
    light = b.add_emitter("light", (17.0, 12.0, 4.0))
    inside = (0.278, 0.2744, 0.2796)
    materials = {"redWall": red, "greenWall": green}
    nodes = []
    for name, quad in CORNELL_WALLS.items():
        quad = mm(quad)
        g = polygon(quad, sub(inside, centroid(quad)))
        nodes.append(b.add_node(name, b.add_geom(g, materials.get(name, white), name)))
    return white, light, nodes


def cornell_light_and_camera(b, light, nodes):
    # 130 x 105 mm, as measured, 1 mm below the ceiling, facing down.
    quad = rect((0.278, 0.5478, 0.2795), (0.0, -1.0, 0.0), 0.065, 0.0525)
    nodes.append(b.add_node("light", b.add_geom(quad, light, "light")))
    # Measured camera: 35 mm focal length, 25 mm film -> yfov = 2 atan(12.5 / 35).
    nodes.append(b.add_camera_node((0.278, 0.273, -0.8), (0.278, 0.273, 0.0),
                                   2.0 * math.atan(12.5 / 35.0)))


def cornell_box():
    """The measured Cornell box, all Lambertian, light radiance (17, 12, 4) as in common use."""
    b = GltfBuilder()
    white, light, nodes = cornell_walls(b)
    for name, faces in (("shortBlock", CORNELL_SHORT_BLOCK), ("tallBlock", CORNELL_TALL_BLOCK)):
        faces = [mm(f) for f in faces]
        middle = centroid([p for f in faces for p in f])
        g = merged(*(polygon(f, sub(centroid(f), middle)) for f in faces))
        nodes.append(b.add_node(name, b.add_geom(g, white, name)))
    cornell_light_and_camera(b, light, nodes)
    b.add_scene("cornell-box", nodes)
    return b


def cornell_spheres():
    """SmallVCM's "mirror ball + glass ball" box in the measured Cornell box: the same walls, light
    and camera as cornell_box, the blocks replaced by a mirror sphere (left) and a glass sphere (IOR
    1.6, right) on the floor, each of radius 0.196 x the box's width and centred 2/7 of the width
    from its wall, as in SmallVCM's scene.hxx. Meshes, like SmallVCM's scene as measured in issue 31."""
    b = GltfBuilder()
    _, light, nodes = cornell_walls(b)
    mirror = b.add_material("mirror", (1.0, 1.0, 1.0), metallic=1.0, roughness=0.0)
    glass = b.add_material("glass", (1.0, 1.0, 1.0), roughness=0.0, glass=True, ior=1.6)
    width = 0.556
    radius = 0.196 * width
    for name, x, material in (("mirrorSphere", width * 5.0 / 7.0, mirror),
                              ("glassSphere", width * 2.0 / 7.0, glass)):
        sphere = uv_sphere((x, radius, 0.25), radius, segments=96, rings=48)
        nodes.append(b.add_node(name, b.add_geom(sphere, material, name)))
    cornell_light_and_camera(b, light, nodes)
    b.add_scene("cornell-spheres", nodes)
    return b

def veach_mis():
    """Veach 1997, fig. 9.2: glossy plates (top: near mirror, bottom: rough) reflecting four
    spherical lights of equal power; each plate is tilted to mirror the light row at the camera."""
    b = GltfBuilder()
    eye, target, lights_centre = (0.0, 2.0, 15.0), (0.0, -2.0, 2.5), (0.0, 0.0, 0.0)
    nodes = []
    plates = (((-2.395, -0.135), 0.03), ((-3.063, 0.923), 0.08),
              ((-3.582, 2.223), 0.2), ((-3.908, 3.574), 0.45))
    for k, ((y, z), roughness) in enumerate(plates, 1):
        c = (0.0, y, z)
        n = normalize(add(normalize(sub(eye, c)), normalize(sub(lights_centre, c))))
        mat = b.add_material(f"plate{k}", (0.7, 0.7, 0.7), metallic=1.0, roughness=roughness)
        g = rect(c, n, 4.0, 0.5, u_dir=(1.0, 0.0, 0.0))
        nodes.append(b.add_node(f"plate{k}", b.add_geom(g, mat, f"plate{k}")))
    # Equal power: mean radiance x r^2 = 1, so each sphere emits 4 pi^2 W (channel mean).
    spheres = ((-3.75, 0.03333, (1.0, 0.45, 0.35)), (-1.25, 0.1, (1.0, 0.9, 0.35)),
               (1.25, 0.3, (0.4, 1.0, 0.5)), (3.75, 0.9, (0.4, 0.6, 1.0)))
    for k, (x, r, colour) in enumerate(spheres, 1):
        strength = 1.0 / (r * r * sum(colour) / 3.0)
        mat = b.add_emitter(f"light{k}", mul(colour, strength))
        mesh = b.add_geom(uv_sphere((x, 0.0, 0.0), r), mat, f"light{k}")
        nodes.append(b.add_node(f"light{k}", mesh))
    dark = b.add_material("dark", (0.15, 0.15, 0.15), lambertian=True)
    room = merged(rect((0.0, -4.0, 7.0), (0.0, 1.0, 0.0), 10.0, 9.0),
                  rect((0.0, 1.0, -2.0), (0.0, 0.0, 1.0), 10.0, 5.0))
    nodes.append(b.add_node("floorAndWall", b.add_geom(room, dark, "floorAndWall")))
    # 40 degrees horizontally at 3:2, as in the thesis figure.
    yfov = 2.0 * math.atan(math.tan(math.radians(20.0)) / 1.5)
    nodes.append(b.add_camera_node(eye, target, yfov, aspect=1.5))
    b.add_scene("veach-mis", nodes)
    return b


def bidir_lamp():
    """A room lit by an uplighter: the spot light only reaches the ceiling, so almost everything
    the camera sees is lit indirectly -- hard for path tracing, easy for light subpaths."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.8, 0.78, 0.72), lambertian=True)
    ceiling = b.add_material("ceiling", (0.85, 0.85, 0.85), lambertian=True)
    floor = b.add_material("floor", (0.5, 0.42, 0.34), lambertian=True)
    metal = b.add_material("lampMetal", (0.25, 0.25, 0.25), metallic=1.0, roughness=0.35)
    shade = b.add_material("shade", (0.9, 0.85, 0.75), lambertian=True)
    wood = b.add_material("tableWood", (0.45, 0.28, 0.15), roughness=0.45)
    glass = b.add_material("glass", (1.0, 1.0, 1.0), roughness=0.0, glass=True)
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    # Room 4 x 3 x 4 m, x and z in [-2, 2], y in [0, 3], faces inward.
    part("floor", rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 2.0, 2.0), floor)
    part("ceiling", rect((0.0, 3.0, 0.0), (0.0, -1.0, 0.0), 2.0, 2.0), ceiling)
    part("walls", merged(*(rect((2.0 * sx, 1.5, 2.0 * sz), (-sx, 0.0, -sz), 2.0, 1.5)
                           for sx, sz in ((1, 0), (-1, 0), (0, 1), (0, -1)))), wall)

    # Floor lamp in the far corner: base, pole and a closed bowl-shaped shade open upward.
    lamp = (-1.4, 0.0, -1.4)
    part("lampBody", merged(lathe([(0.0, 0.0), (0.16, 0.0), (0.16, 0.02), (0.0, 0.02)], lamp),
                            lathe([(0.012, 0.02), (0.012, 1.5)], lamp)), metal)
    part("lampShade", lathe([(0.0, 1.5), (0.09, 1.5), (0.26, 1.78), (0.252, 1.78),
                             (0.084, 1.508), (0.0, 1.508)], lamp), shade)
    # The shade's inner rim is 49 degrees off the axis as seen from the bulb, outside the cone.
    spot = b.add_light("uplight", "spot", 15.0, (1.0, 0.85, 0.65), inner=0.55, outer=0.8)
    nodes.append(b.add_node("uplight", light=spot, translation=(lamp[0], 1.56, lamp[2]),
                            rotation=quat_axis_angle((1.0, 0.0, 0.0), math.pi / 2.0)))

    # Table 1.0 x 0.7 m, top at 0.76 m, with a glass sphere on it.
    table = (0.5, 0.0, 0.4)
    legs = [box((table[0] + sx * 0.44, 0.36, table[2] + sz * 0.29), (0.025, 0.36, 0.025))
            for sx in (-1, 1) for sz in (-1, 1)]
    part("table", merged(box((table[0], 0.74, table[2]), (0.5, 0.02, 0.35)), *legs), wood)
    part("glassSphere", uv_sphere((0.45, 0.88, 0.35), 0.12), glass)

    nodes.append(b.add_camera_node((1.85, 1.7, 1.85), (-0.4, 1.1, -0.4), 1.2))
    b.add_scene("bidir-lamp", nodes)
    return b


def caustic():
    """A glass ball focusing a small, bright area light onto a diffuse floor: the caustic is
    reachable only through a specular chain, which light subpaths find and camera paths miss."""
    b = GltfBuilder()
    floor = b.add_material("floor", (0.8, 0.8, 0.8), lambertian=True)
    dark = b.add_material("darkWall", (0.05, 0.05, 0.05), lambertian=True)
    glass = b.add_material("glass", (1.0, 1.0, 1.0), roughness=0.0, glass=True)
    light = b.add_emitter("light", (1000.0, 930.0, 850.0))
    nodes = [
        b.add_node("floor", b.add_geom(rect((0.25, 0.0, 1.0), (0.0, 1.0, 0.0), 2.75, 3.0),
                                       floor, "floor")),
        b.add_node("walls", b.add_geom(merged(
            rect((0.25, 1.5, -2.0), (0.0, 0.0, 1.0), 2.75, 1.5),
            rect((-2.5, 1.5, 1.0), (1.0, 0.0, 0.0), 3.0, 1.5)), dark, "walls")),
        b.add_node("glassSphere", b.add_geom(uv_sphere((0.0, 0.5, 0.0), 0.5), glass,
                                             "glassSphere")),
        # 0.1 x 0.1 m, above, right and behind: the caustic lands in front, left of the sphere,
        # around (-0.45, 0, 0.27), before the focus (1.4 m from the centre) so it is a bright blob.
        b.add_node("light", b.add_geom(rect((1.0, 1.6, -0.6), (0.0, -1.0, 0.0), 0.05, 0.05),
                                       light, "light")),
        b.add_camera_node((0.3, 1.3, 3.5), (-0.2, 0.3, 0.0), 0.7),
    ]
    b.add_scene("caustic", nodes)
    return b


def foggy_room(part, half, height, wall, floor, fog_boundary):
    """A room 2 half x height x 2 half m (x, z in [-half, half], y in [0, height], faces inward)
    filled with fog: its index-matched boundary box 1 cm inside the walls, 5 mm below the ceiling."""
    part("floor", rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), half, half), floor)
    part("ceiling", rect((0.0, height, 0.0), (0.0, -1.0, 0.0), half, half), wall)
    part("walls", merged(*(rect((half * sx, 0.5 * height, half * sz), (-sx, 0.0, -sz), half, 0.5 * height)
                           for sx, sz in ((1, 0), (-1, 0), (0, 1), (0, -1)))), wall)
    part("fogVolume", box((0.0, 0.5 * height, 0.0), (half - 0.01, 0.5 * height - 0.005, half - 0.01)), fog_boundary)


def fog():
    """A room filled with thin fog, lit by a spot light shining down through a glass sphere: the
    beam is visible in the fog, and the sphere focuses it into a volumetric caustic (light ->
    glass -> glass -> fog -> camera, which no technique with a short light subpath can sample).
    A block of coloured glass absorbs along its length. The camera stands inside the fog."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.6, 0.6, 0.6), lambertian=True)
    floor = b.add_material("floor", (0.45, 0.4, 0.35), lambertian=True)
    glass = b.add_material("glass", (1.0, 1.0, 1.0), roughness=0.0, glass=True)
    # Fog: sigma_t = -ln(0.82) / 1 m = 0.2 per metre, white (albedo 1), mildly forward scattering;
    # bounded by an index-matched box (ior 1, smooth, fully transmissive) just inside the walls.
    fog_boundary = b.add_material("fog", (1.0, 1.0, 1.0), roughness=0.0, glass=True, ior=1.0,
                                  volume=((0.82, 0.82, 0.82), 1.0),
                                  scatter=((1.0, 1.0, 1.0), 0.3))
    # Coloured glass: absorbs red and green over a few centimetres, blue much less.
    blue_glass = b.add_material("blueGlass", (1.0, 1.0, 1.0), roughness=0.0, glass=True,
                                volume=((0.2, 0.45, 0.9), 0.1))
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    # Room 3 x 2.5 x 3 m.
    foggy_room(part, 1.5, 2.5, wall, floor, fog_boundary)
    part("glassSphere", uv_sphere((-0.3, 1.3, -0.2), 0.3), glass)
    # Volumes nest but must not overlap: the block floats 1 cm up, inside the fog.
    part("glassBlock", box((0.3, 0.21, -0.55), (0.12, 0.2, 0.12)), blue_glass)
    # 2.2 m up, straight down onto the sphere: its cone (outer 0.2 rad) is mostly caught by it.
    spot = b.add_light("spot", "spot", 60.0, (1.0, 0.92, 0.8), inner=0.14, outer=0.2)
    nodes.append(b.add_node("spot", light=spot, translation=(-0.3, 2.3, -0.2),
                            rotation=quat_axis_angle((1.0, 0.0, 0.0), -math.pi / 2.0)))
    nodes.append(b.add_camera_node((0.9, 1.2, 1.4), (-0.25, 0.8, -0.2), 1.0))
    b.add_scene("fog", nodes)
    return b


def fog_lamp():
    """A bare bulb (a point light) hanging in a dark, foggy room (sooty walls, a black floor), a
    table beneath it, a dim panel in the ceiling's corner: what the camera sees is mostly the
    fog's single scattering of the bulb, its glow and the table's shadow, which distance sampling
    finds only where the fog happens to scatter near the bulb; equiangular sampling (issue 35)
    places the vertex where the bulb's light falls off."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.06, 0.06, 0.06), lambertian=True)
    floor = b.add_material("floor", (0.05, 0.045, 0.04), lambertian=True)
    wood = b.add_material("table", (0.3, 0.2, 0.12), lambertian=True)
    panel = b.add_material("panel", (0.0, 0.0, 0.0), lambertian=True, emission=(1.0, 0.95, 0.9))
    # Thin fog: sigma_t = -ln(0.95) / 1 m = 0.051 per metre, white, slightly forward scattering.
    fog_boundary = b.add_material("fog", (1.0, 1.0, 1.0), roughness=0.0, glass=True, ior=1.0,
                                  volume=((0.95, 0.95, 0.95), 1.0),
                                  scatter=((1.0, 1.0, 1.0), 0.2))
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    # Room 4 x 2.6 x 4 m.
    foggy_room(part, 2.0, 2.6, wall, floor, fog_boundary)
    # A table: a top 1.2 x 0.8 m, 4 cm thick, at 0.75 m, on four legs; inside the fog.
    legs = [box((sx * 0.55, 0.365, sz * 0.35), (0.03, 0.355, 0.03)) for sx in (-1, 1) for sz in (-1, 1)]
    part("table", merged(box((0.0, 0.75, 0.0), (0.6, 0.02, 0.4)), *legs), wood)
    # A dim 0.4 x 0.4 m panel 1 mm below the ceiling, in a corner (an area light in the fog).
    part("panel", rect((-1.5, 2.599, -1.5), (0.0, -1.0, 0.0), 0.2, 0.2), panel)
    # The bulb: 5 W/sr, warm, 1.5 m up above the table's edge.
    bulb = b.add_light("bulb", "point", 5.0, (1.0, 0.85, 0.65))
    nodes.append(b.add_node("bulb", light=bulb, translation=(0.3, 1.5, -0.2)))
    nodes.append(b.add_camera_node((1.5, 1.2, 1.8), (-0.2, 1.0, -0.5), 1.0))
    b.add_scene("fog-lamp", nodes)
    return b


def smoke():
    """A plume of smoke rising from the floor of a grey room (issue 35): a heterogeneous medium whose
    density is the OpenVDB grid smoke.vdb (`pathlab make-volume smoke assets/smoke.vdb`: its voxel
    centres fill the unit cube), placed by its node's transform in a 1.2 x 1.8 x 1.2 m box whose
    index-matched boundary bounds the medium. Lit by a warm ceiling panel to one side and a cool
    point light low on the other, so both the plume's lit side and its self-shadowing show."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.5, 0.5, 0.5), lambertian=True)
    floor = b.add_material("floor", (0.35, 0.33, 0.3), lambertian=True)
    panel = b.add_material("panel", (0.0, 0.0, 0.0), lambertian=True, emission=(6.0, 5.2, 4.2))
    # At density 1: sigma_t = -ln(0.05) / 0.1 m = 30 per metre, grey-white (albedo about 0.95),
    # forward scattering; the grid's densities (at most 1, mostly far less) scale it point by point.
    smoke_boundary = b.add_material("smoke", (1.0, 1.0, 1.0), roughness=0.0, glass=True, ior=1.0,
                                    volume=((0.05, 0.05, 0.05), 0.1),
                                    scatter=((0.8, 0.8, 0.8), 0.4), grid=("smoke.vdb", 1.0))
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    # Room 4 x 3 x 4 m.
    half, height = 2.0, 3.0
    part("floor", rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), half, half), floor)
    part("ceiling", rect((0.0, height, 0.0), (0.0, -1.0, 0.0), half, half), wall)
    part("walls", merged(*(rect((half * sx, 0.5 * height, half * sz), (-sx, 0.0, -sz), half, 0.5 * height)
                           for sx, sz in ((1, 0), (-1, 0), (0, 1), (0, -1)))), wall)
    part("panel", rect((-1.0, height - 0.001, 0.3), (0.0, -1.0, 0.0), 0.4, 0.4), panel)
    # The smoke's box: the unit cube, scaled and lifted 1 cm off the floor by its node.
    cube = b.add_geom(box((0.0, 0.0, 0.0), (0.5, 0.5, 0.5)), smoke_boundary, "smokeVolume")
    nodes.append(b.add_node("smokeVolume", cube, translation=(0.0, 0.91, 0.0), scale=(1.2, 1.8, 1.2)))
    rim = b.add_light("rim", "point", 3.0, (0.6, 0.75, 1.0))
    nodes.append(b.add_node("rim", light=rim, translation=(1.4, 0.5, 1.0)))  # outside the view
    nodes.append(b.add_camera_node((0.0, 1.05, 1.95), (0.0, 0.95, 0.0), 1.0))
    b.add_scene("smoke", nodes)
    return b


def grid_fog(kind):
    """A 2 m closed room (grey walls, a ceiling panel, a small block on the floor) filled with fog
    of sigma_t 1 per metre at density 1 and albedo 0.8 (issue 35's tests): kind "homogeneous" is
    that fog; "constant" the same fog as a density grid of 1 everywhere (constant.vdb, which the
    tests write with `makeProceduralVolume`); "ramp" a density rising linearly with height
    (ramp.vdb, density z + 1 in the grid's unit cube: 0.5 at the floor, 1.5 at the ceiling)."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.6, 0.6, 0.6), lambertian=True)
    panel = b.add_material("panel", (0.0, 0.0, 0.0), lambertian=True, emission=(4.0, 4.0, 4.0))
    grid = None if kind == "homogeneous" else (kind + ".vdb", 1.0)
    fog_boundary = b.add_material("fog", (1.0, 1.0, 1.0), roughness=0.0, glass=True, ior=1.0,
                                  volume=((math.exp(-1.0),) * 3, 1.0),
                                  scatter=((0.5, 0.5, 0.5), 0.3), grid=grid)
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    part("room", box((0.0, 1.0, 0.0), (1.0, 1.0, 1.0), inward=True), wall)
    part("panel", rect((0.0, 1.999, 0.0), (0.0, -1.0, 0.0), 0.3, 0.3), panel)
    part("block", box((0.3, 0.2, -0.2), (0.2, 0.19, 0.2)), wall)
    # The fog's box, 1 cm inside the walls: the unit cube (the grid's) scaled by its node, its
    # "up" the grid's z (rotated so the ramp rises with the room's y).
    cube = b.add_geom(box((0.0, 0.0, 0.0), (0.5, 0.5, 0.5)), fog_boundary, "fogVolume")
    nodes.append(b.add_node("fogVolume", cube, translation=(0.0, 1.0, 0.0), scale=(1.98, 1.98, 1.98),
                            rotation=quat_axis_angle((1.0, 0.0, 0.0), -math.pi / 2.0)))
    nodes.append(b.add_camera_node((0.0, 1.0, 0.9), (0.0, 0.8, -1.0), 1.1))
    b.add_scene("grid-fog-" + kind, nodes)
    return b


def door_ajar():
    """Veach's "door ajar" (Veach and Guibas 1997, fig. 5), in pathlab's own measurements: two
    rooms joined by a doorway whose door stands open by 3 degrees. The lamp hangs in the back
    room; the camera stands in the front room, which the lamp lights only through the gap
    between the door's free edge and the jamb. Almost every path that reaches the camera crosses
    that gap, which a light subpath passes with a small probability and a camera subpath finds
    by chance: the hard visibility Metropolis light transport (issue 33) is built for."""
    b = GltfBuilder()
    wall = b.add_material("wall", (0.7, 0.7, 0.68), lambertian=True)
    floor = b.add_material("floor", (0.45, 0.32, 0.22), lambertian=True)
    door = b.add_material("door", (0.55, 0.4, 0.3), lambertian=True)
    table = b.add_material("table", (0.35, 0.25, 0.18), lambertian=True)
    red = b.add_material("red", (0.65, 0.12, 0.1), lambertian=True)
    blue = b.add_material("blue", (0.12, 0.2, 0.6), lambertian=True)
    lamp = b.add_emitter("lamp", (1200.0, 1100.0, 900.0))
    nodes = []

    def part(name, geom, material, **kw):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name), **kw))

    # The house: x in [-2, 2], y in [0, 2.6], z in [-3, 4]; the front room z > 0, the back z < 0.
    part("floor", rect((0.0, 0.0, 0.5), (0.0, 1.0, 0.0), 2.0, 3.5), floor)
    part("walls", merged(rect((0.0, 2.6, 0.5), (0.0, -1.0, 0.0), 2.0, 3.5),
                         rect((2.0, 1.3, 0.5), (-1.0, 0.0, 0.0), 3.5, 1.3, u_dir=(0.0, 0.0, 1.0)),
                         rect((-2.0, 1.3, 0.5), (1.0, 0.0, 0.0), 3.5, 1.3, u_dir=(0.0, 0.0, 1.0)),
                         rect((0.0, 1.3, 4.0), (0.0, 0.0, -1.0), 2.0, 1.3),
                         rect((0.0, 1.3, -3.0), (0.0, 0.0, 1.0), 2.0, 1.3)), wall)
    # The dividing wall, 10 cm thick, with a doorway x in [0.2, 1.0], y in [0, 2.0].
    part("dividingWall", merged(box((-0.9, 1.3, 0.0), (1.1, 1.3, 0.05)),
                                box((1.5, 1.3, 0.0), (0.5, 1.3, 0.05)),
                                box((0.6, 2.3, 0.0), (0.4, 0.3, 0.05))), wall)
    # The door, 0.8 x 2 m and 4 cm thick, hinged at the doorway's left edge (x = 0.2, z = -0.05)
    # and turned 3 degrees into the back room: its free edge stands about 5 cm from the jamb.
    angle = math.radians(3.0)
    hinge = (0.2, 0.0, -0.05)
    centre = add(hinge, (0.4 * math.cos(angle), 1.0, -0.4 * math.sin(angle) - 0.02))
    part("door", box((0.0, 0.0, 0.0), (0.4, 0.99, 0.02)), door,
         translation=centre, rotation=quat_axis_angle((0.0, 1.0, 0.0), angle))
    # The lamp: a 0.3 x 0.3 m panel under the back room's ceiling, facing down.
    part("lamp", rect((1.2, 2.59, -2.2), (0.0, -1.0, 0.0), 0.15, 0.15), lamp)
    # A table in the front room with a block and a tall box on it.
    legs = [box((0.4 + sx * 0.5, 0.36, 1.6 + sz * 0.3), (0.03, 0.36, 0.03)) for sx in (-1, 1) for sz in (-1, 1)]
    part("table", merged(box((0.4, 0.74, 1.6), (0.58, 0.02, 0.38)), *legs), table)
    part("block", box((0.2, 0.88, 1.5), (0.12, 0.12, 0.12)), red)
    part("tower", box((0.65, 1.01, 1.75), (0.1, 0.25, 0.1)), blue)
    # The camera to the right of the doorway, looking left across it: the gap is edge-on, so the
    # lit back room is not seen through it (what the camera sees is all indirect).
    nodes.append(b.add_camera_node((1.7, 1.5, 3.8), (-0.2, 0.8, 0.4), 0.9))
    b.add_scene("door-ajar", nodes)
    return b


def isometric():
    """Blocks and a ball on a floor under a square area light, seen by an orthographic camera
    from the isometric angle (azimuth 45 degrees, elevation 35.26): parallel rays, so equal
    lengths look equal everywhere. Its importance is a delta in direction: no light subpath can
    connect to it (t = 1), so light tracing is refused and BPT combines the t >= 2 techniques."""
    b = GltfBuilder()
    floor = b.add_material("floor", (0.7, 0.7, 0.7), lambertian=True)
    red = b.add_material("red", (0.7, 0.12, 0.08), lambertian=True)
    blue = b.add_material("blue", (0.1, 0.22, 0.65), lambertian=True)
    gold = b.add_material("gold", (1.0, 0.78, 0.35), metallic=1.0, roughness=0.3)
    light = b.add_emitter("light", (18.0, 17.0, 15.0))
    nodes = []

    def part(name, geom, material):
        nodes.append(b.add_node(name, b.add_geom(geom, material, name)))

    part("floor", rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 1.5, 1.5), floor)
    part("redBlock", box((-0.55, 0.25, -0.35), (0.25, 0.25, 0.25)), red)
    part("blueTower", box((0.45, 0.45, -0.45), (0.2, 0.45, 0.2)), blue)
    part("goldBall", uv_sphere((0.15, 0.3, 0.5), 0.3), gold)
    part("light", rect((-0.3, 2.0, 0.3), (0.0, -1.0, 0.0), 0.4, 0.4), light)
    d = 5.0  # far enough that the film plane lies outside the scene
    eye = (d * math.cos(math.radians(35.264)) * math.sin(math.radians(45.0)),
           d * math.sin(math.radians(35.264)),
           d * math.cos(math.radians(35.264)) * math.cos(math.radians(45.0)))
    nodes.append(b.add_orthographic_camera_node(eye, (0.0, 0.3, 0.0), 2.0, 1.5))
    b.add_scene("isometric", nodes)
    return b


def many_lights():
    """A wall in the sun's shadow, lit from close by: a sun behind a long wall over a large floor,
    eight small lantern cubes in front of the wall's shaded face and a small point lamp near its
    foot. Chosen by
    power, the sun takes almost every next-event sample, and in the shade it is occluded: the
    lanterns' and the lamp's light is speckled. A light BVH chooses by what each light can send
    to the receiving point (--light-sampler bvh, the default for a scene of many emitters)."""
    b = GltfBuilder()
    floor = b.add_material("floor", (0.5, 0.5, 0.5), lambertian=True)
    wall = b.add_material("wall", (0.7, 0.68, 0.62), lambertian=True)
    nodes = [b.add_node("floor", b.add_geom(rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 30.0, 30.0), floor, "floor")),
             b.add_node("wall", b.add_geom(box((0.0, 1.5, -2.1), (15.0, 1.5, 0.1)), wall, "wall"))]
    colours = [(1.0, 0.55, 0.2), (1.0, 0.8, 0.45), (0.45, 0.7, 1.0), (1.0, 0.4, 0.35)]
    for i in range(8):
        x = -7.0 + 2.0 * i
        lantern = b.add_emitter(f"lantern{i}", mul(colours[i % 4], 8.0))
        g = box((x, 2.0, -1.75), (0.08, 0.08, 0.08))
        nodes.append(b.add_node(f"lantern{i}", b.add_geom(g, lantern, f"lantern{i}")))
    lamp = b.add_light("lamp", "point", 0.6, color=(1.0, 0.85, 0.6))
    nodes.append(b.add_node("lamp", light=lamp, translation=(0.6, 0.3, -1.7)))
    sun = b.add_light("sun", "directional", 3.0, color=(1.0, 0.95, 0.85))
    # Travels toward +z and down, 40 degrees above the horizon: the wall shades z < 1.3.
    nodes.append(b.add_node("sun", light=sun, rotation=look_at((0.0, 0.0, 0.0), (0.3, -0.64, 0.7))))
    nodes.append(b.add_camera_node((0.3, 1.4, 4.2), (0.0, 1.0, -2.0), 0.9, 1.5))
    b.add_scene("many-lights", nodes)
    return b


def environment_objects(eye, target, yfov, aspect):
    """No light of its own: lit by an environment (the default light, or --environment). A
    Lambertian floor (0.5), a rough gold sphere (metal, roughness 0.3), a glass sphere and a
    Lambertian box (0.7, 0.3, 0.2), all floating 5 cm above the floor: no concave edge, so every
    connection's geometry term is bounded (the uniform heuristic's variance stays finite)."""
    b = GltfBuilder()
    floor = b.add_material("floor", (0.5, 0.5, 0.5), lambertian=True)
    gold = b.add_material("gold", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3)
    glass = b.add_material("glass", (1.0, 1.0, 1.0), roughness=0.0, glass=True)
    clay = b.add_material("clay", (0.7, 0.3, 0.2), lambertian=True)
    nodes = [
        b.add_node("floor", b.add_geom(rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 2.0, 2.0), floor, "floor")),
        b.add_node("goldSphere", b.add_geom(uv_sphere((-0.55, 0.45, 0.0), 0.4), gold, "goldSphere")),
        b.add_node("glassSphere", b.add_geom(uv_sphere((0.5, 0.4, 0.35), 0.35), glass, "glassSphere")),
        b.add_node("box", b.add_geom(box((0.35, 0.3, -0.6), (0.25, 0.25, 0.25)), clay, "box")),
        b.add_camera_node(eye, target, yfov, aspect),
    ]
    b.add_scene("environment", nodes)
    return b


def sky_texel(direction):
    """Radiance of the bundled sky: a sun of radiance 1500 (2.5 degrees in radius) at
    elevation 35 deg toward -z+x, a blue gradient above the horizon, dim brown ground below."""
    x, y, z = direction
    sun = normalize((0.45, math.sin(math.radians(35.0)), -0.75))
    if dot(direction, sun) > math.cos(math.radians(2.5)):
        return (1500.0, 1350.0, 1100.0)
    if y < 0.0:
        return (0.12, 0.10, 0.08)
    t = y ** 0.5
    return (0.9 - 0.6 * t, 1.0 - 0.45 * t, 1.2 - 0.1 * t)


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(c[0] * scale), int(c[1] * scale), int(c[2] * scale), exponent + 128])


def sky_hdr(width=128, height=64):
    """An equirectangular Radiance HDR of sky_texel, pathlab's lat-long convention (environment_light.h):
    row 0 straight up, the centre column toward -z, the right half toward +x. Uncompressed RGBE
    scanlines (readers accept them)."""
    out = bytearray(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode("ascii"))
    for row in range(height):
        theta = math.pi * (row + 0.5) / height
        for col in range(width):
            phi = 2.0 * math.pi * ((col + 0.5) / width - 0.5)
            d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
            out += rgbe(sky_texel(d))
    return bytes(out)


# ---------------------------------------------------------------------------------------------
# Test scenes (closed-form answers and loader coverage; facts in assets/README.md)

def lambert_floor(b, size=100.0):
    mat = b.add_material("floor", (0.5, 0.5, 0.5), lambertian=True)
    g = rect((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), size / 2.0, size / 2.0)
    return b.add_node("floor", b.add_geom(g, mat, "floor"))


def furnace():
    """Closed cube of side 2 around the origin, faces inward, albedo 0.5 and Le = 1 everywhere:
    L = Le (1 - rho^K) / (1 - rho) with at most K bounces, 2 in the limit."""
    b = GltfBuilder()
    mat = b.add_material("furnaceWall", (0.5, 0.5, 0.5), lambertian=True, emission=(1.0, 1.0, 1.0))
    cube = box((0.0, 0.0, 0.0), (1.0, 1.0, 1.0), inward=True)
    nodes = [b.add_node("cube", b.add_geom(cube, mat, "cube")),
             b.add_node("camera", camera=b.add_camera("camera", 1.0))]
    b.add_scene("furnace", nodes)
    return b


def square_light():
    """Direct lighting under a 1 x 1 m emitter 1 m above a Lambertian floor (form factor)."""
    b = GltfBuilder()
    light = b.add_emitter("light", (1.0, 1.0, 1.0))
    emitter = rect((0.0, 1.0, 0.0), (0.0, -1.0, 0.0), 0.5, 0.5)
    nodes = [lambert_floor(b), b.add_node("light", b.add_geom(emitter, light, "light")),
             b.add_camera_node((0.0, 0.5, 0.3), (0.0, 0.0, 0.0), 0.05)]
    b.add_scene("square-light", nodes)
    return b


def punctual():
    b = GltfBuilder()
    point = b.add_light("point", "point", 10.0)
    spot = b.add_light("spot", "spot", 10.0, inner=0.3, outer=0.5)
    sun = b.add_light("directional", "directional", 1.0)
    down = quat_axis_angle((1.0, 0.0, 0.0), -math.pi / 2.0)
    nodes = [
        lambert_floor(b),
        # A point light ignores its rotation; it has one so the loader is seen to ignore it.
        b.add_node("point", light=point, translation=(0.0, 1.0, 0.0),
                   rotation=quat_axis_angle((0.0, 1.0, 0.0), math.pi / 6.0)),
        b.add_node("spot", light=spot, translation=(2.0, 1.0, 0.0), rotation=down),
        # Travels along (0, -1, -1) / sqrt(2): 45 degrees from the floor normal.
        b.add_node("directional", light=sun,
                   rotation=quat_axis_angle((1.0, 0.0, 0.0), -math.pi / 4.0)),
        b.add_node("camera", camera=b.add_camera("camera", 2.0 * math.atan(0.5)),
                   translation=(1.0, 5.0, 0.0), rotation=down),
    ]
    b.add_scene("punctual", nodes)
    return b


def trs_matrix(translation, linear=((1, 0, 0), (0, 1, 0), (0, 0, 1))):
    """Column-major glTF matrix from a 3x3 linear part (given as rows) and a translation."""
    columns = [[linear[0][c], linear[1][c], linear[2][c], 0.0] for c in range(3)]
    return [float(v) for col in columns + [list(translation) + [1.0]] for v in col]


def hierarchy():
    """Loader coverage: three-level TRS / matrix nesting, a mesh used by three nodes, an
    unindexed interleaved primitive, UNSIGNED_SHORT indices, a primitive without NORMAL, two
    scenes with the second as default."""
    b = GltfBuilder()
    grey = b.add_material("grey", (0.6, 0.6, 0.6), roughness=0.8)
    blue = b.add_material("blue", (0.2, 0.3, 0.7), roughness=0.5)
    sign = b.add_material("sign", (0.8, 0.2, 0.1), lambertian=True)
    light = b.add_emitter("light", (5.0, 5.0, 5.0))

    cube = b.add_geom(box((0.0, 0.0, 0.0), (0.5, 0.5, 0.5)), grey, "box", uvs=True,
                      index_type=USHORT)
    soup = unindexed(prism())
    wedge = b.add_mesh(soup.positions, soup.normals, soup.uvs, None, blue, "wedgeAndSign",
                       interleaved=True)
    # No NORMAL: flat, so any generated normal is (0, 0, -1) locally, (0, 0, 1) in the world.
    plate = rect((0.0, 0.5, -0.55), (0.0, 0.0, -1.0), 0.25, 0.15)
    b.add_primitive(wedge, plate.positions, None, plate.uvs, plate.indices, sign)
    lamp = b.add_geom(rect((0.0, 0.0, 0.0), (0.0, -1.0, 0.0), 0.5, 0.5), light, "light",
                      uvs=True)

    leaf = b.add_node("leaf", cube, translation=(0.0, 0.25, 0.0), scale=(0.5, 1.0, 0.5))
    rot_z90 = ((0, -1, 0), (1, 0, 0), (0, 0, 1))
    middle = b.add_node("middle", matrix=trs_matrix((1.0, 0.0, 0.0), rot_z90),
                        children=[leaf])
    wedge_node = b.add_node("wedge", wedge, translation=(-0.5, 0.0, 0.0))
    root = b.add_node("root", translation=(0.0, 0.5, 0.0), rotation=(0.0, 1.0, 0.0, 0.0),
                      scale=(2.0, 2.0, 2.0), children=[middle, wedge_node])
    twin = b.add_node("twin", cube, translation=(-1.0, 0.5, -1.25))
    half = ((0.5, 0, 0), (0, 0.5, 0), (0, 0, 0.5))
    third = b.add_node("third", cube, matrix=trs_matrix((-2.0, 0.25, 1.0), half))
    lamp_node = b.add_node("light", lamp, matrix=trs_matrix((0.0, 3.0, 0.0)))
    eye, target = (0.0, 2.5, 7.0), (0.0, 0.8, 0.0)
    camera = b.add_camera_node(eye, target, 0.8)
    b.add_scene("one box", [b.add_node("lonelyBox", cube, translation=(0.0, 0.5, 0.0)),
                            b.add_camera_node(eye, target, 0.8, name="camera0")])
    b.add_scene("three boxes", [root, twin, third, lamp_node, camera], default=True)
    return b


# 8 x 8 textures of textured.gltf, row 0 at the top (uv v = 0).
CHECKER_A, CHECKER_B, MARKER = (255, 128, 0), (0, 128, 255), (0, 255, 0)


def checker_texels():
    rows = [[CHECKER_A if (x + y) % 2 == 0 else CHECKER_B for x in range(8)] for y in range(8)]
    rows[0][0] = MARKER
    return rows


def metal_rough_texels():
    """G = roughness, B = metallic: left half rough dielectric, right half smoothish metal."""
    return [[(0, 255, 0) if x < 4 else (0, 64, 255) for x in range(8)] for _ in range(8)]


def emissive_texels():
    return [[(255, 255, 255) if y < 4 else (128, 128, 128) for _ in range(8)] for y in range(8)]


def textured():
    b = GltfBuilder()
    sampler = b.add_sampler()
    checker = b.add_texture(png(checker_texels()), sampler)
    metal_rough = b.add_texture(png(metal_rough_texels()), sampler)
    glow = b.add_texture(png(emissive_texels()), sampler)
    surface = b.add_material("checker", (1.0, 1.0, 1.0), metallic=1.0, roughness=1.0,
                             base_color_texture=checker, metallic_roughness_texture=metal_rough)
    emitter = b.add_material("glow", (0.0, 0.0, 0.0), lambertian=True, emission=(4.0, 4.0, 4.0),
                             emissive_texture=glow)
    left = rect((-0.6, 0.0, 0.0), (0.0, 0.0, 1.0), 0.5, 0.5, uv_scale=2.0)
    right = rect((0.6, 0.0, 0.0), (0.0, 0.0, 1.0), 0.5, 0.5, uv_scale=2.0)
    lamp = b.add_light("fill", "point", 2.0)
    nodes = [b.add_node("checker", b.add_geom(left, surface, "checker", uvs=True)),
             b.add_node("glow", b.add_geom(right, emitter, "glow", uvs=True)),
             b.add_node("fill", light=lamp, translation=(-0.6, 0.0, 1.5)),
             b.add_camera_node((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), 2.0 * math.atan(1.3 / 3.0))]
    b.add_scene("textured", nodes)
    return b


# ---------------------------------------------------------------------------------------------
# Malformed inputs: each a tiny scene (floor, emissive triangle, camera) with one defect

def tiny_scene(name, emissive=True, emitter_indices=(0, 1, 2), emitter_positions=None):
    b = GltfBuilder()
    nodes = [lambert_floor(b, size=2.0)]
    if emissive:
        light = b.add_emitter("light", (4.0, 4.0, 4.0))
        positions = emitter_positions or [(-0.2, 1.0, -0.2), (0.2, 1.0, -0.2), (0.0, 1.0, 0.2)]
        normals = [(0.0, -1.0, 0.0)] * len(positions)
        mesh = b.add_mesh(positions, normals, None, list(emitter_indices), light, "light")
        nodes.append(b.add_node("light", mesh))
    nodes.append(b.add_camera_node((0.0, 0.5, 2.5), (0.0, 0.3, 0.0), 0.8))
    b.add_scene(name, nodes)
    return b


def garbage(n):
    out, x = bytearray(b"\x89\x00\xfe\xff"), 12345
    while len(out) < n:
        x = (x * 1103515245 + 12345) & 0x7FFFFFFF
        out.append((x >> 16) & 0xFF)
    return bytes(out)


def bad_files():
    """name -> bytes."""
    files = {}
    text = tiny_scene("truncated").gltf_bytes()
    files["truncated.gltf"] = text[:len(text) // 2]
    files["not-json.gltf"] = garbage(256)

    b = tiny_scene("buffer-too-short")
    b.lists["accessors"][0]["count"] = 1000  # the floor's POSITION: its view holds 4 vertices
    files["buffer-too-short.gltf"] = b.gltf_bytes()

    for name, bad in (("nan-vertex.gltf", math.nan), ("inf-vertex.gltf", math.inf)):
        positions = [(-0.2, 1.0, -0.2), (0.2, bad, -0.2), (0.0, 1.0, 0.2)]
        files[name] = tiny_scene(name[:-5], emitter_positions=positions).gltf_bytes()

    # Emissive primitive: one good triangle, one with a repeated index, one with collinear
    # vertices (vertex 3 is the midpoint of 0 and 1).
    positions = [(-0.2, 1.0, -0.2), (0.2, 1.0, -0.2), (0.0, 1.0, 0.2), (0.0, 1.0, -0.2)]
    files["degenerate.gltf"] = tiny_scene("degenerate", emitter_positions=positions,
                                          emitter_indices=(0, 1, 2, 0, 0, 2, 0, 3, 1)).gltf_bytes()

    b = tiny_scene("no-emitter", emissive=False)
    files["no-emitter.gltf"] = b.gltf_bytes()

    b = tiny_scene("required-extension")
    b.used.add("KHR_draco_mesh_compression")
    b.required.append("KHR_draco_mesh_compression")
    files["required-extension.gltf"] = b.gltf_bytes()

    files["bad-index.gltf"] = tiny_scene("bad-index", emitter_indices=(0, 1, 7)).gltf_bytes()

    b = tiny_scene("missing-buffer")
    doc = b.document("missing-buffer.bin")
    files["missing-buffer.gltf"] = (json.dumps(doc, indent=2) + "\n").encode("ascii")

    glb = tiny_scene("truncated-glb").glb_bytes()
    json_length = struct.unpack_from("<I", glb, 12)[0]
    bin_start = 12 + 8 + json_length + 8
    files["truncated.glb"] = glb[:bin_start + (len(glb) - bin_start) // 2]
    return files


# ---------------------------------------------------------------------------------------------

def square_light_radiance():
    """Le rho F: F is the form factor from the floor point under the centre of the emitter
    (a differential area) to the 1 x 1 m square 1 m above, four corner rectangles of 0.5 x 0.5."""
    x = y = 0.5
    a, c = math.sqrt(1 + x * x), math.sqrt(1 + y * y)
    corner = (x / a * math.atan(y / a) + y / c * math.atan(x / c)) / (2.0 * math.pi)
    return 4.0 * corner, 0.5 * 4.0 * corner


def main():
    write(ASSETS / "cornell-box.gltf", cornell_box().gltf_bytes())
    write(ASSETS / "cornell-spheres.gltf", cornell_spheres().gltf_bytes())
    write(ASSETS / "veach-mis.gltf", veach_mis().gltf_bytes())
    write(ASSETS / "bidir-lamp.gltf", bidir_lamp().gltf_bytes())
    write(ASSETS / "caustic.gltf", caustic().gltf_bytes())
    write(ASSETS / "fog.gltf", fog().gltf_bytes())
    write(ASSETS / "fog-lamp.gltf", fog_lamp().gltf_bytes())
    write(ASSETS / "isometric.gltf", isometric().gltf_bytes())
    write(ASSETS / "door-ajar.gltf", door_ajar().gltf_bytes())
    write(ASSETS / "smoke.gltf", smoke().gltf_bytes())
    write(ASSETS / "many-lights.gltf", many_lights().gltf_bytes())
    write(ASSETS / "environment.gltf",
          environment_objects((1.2, 1.1, 2.6), (0.0, 0.3, 0.0), 0.75, 1.5).gltf_bytes())
    write(ASSETS / "sky.hdr", sky_hdr())
    # Looking down: every pixel sees the floor or an object (light tracing never sees the
    # environment directly, so the agreement test compares no background).
    write(TESTS / "environment.gltf",
          environment_objects((0.0, 2.4, 1.3), (0.0, 0.2, 0.0), 0.8, 1.0).gltf_bytes())
    write(TESTS / "furnace.gltf", furnace().gltf_bytes())
    for kind in ("homogeneous", "constant", "ramp"):
        write(TESTS / ("grid-fog-" + kind + ".gltf"), grid_fog(kind).gltf_bytes())
    write(TESTS / "square-light.gltf", square_light().gltf_bytes())
    write(TESTS / "punctual.gltf", punctual().gltf_bytes())
    h = hierarchy()
    write(TESTS / "hierarchy.gltf", h.gltf_bytes())
    write(TESTS / "textured.gltf", textured().gltf_bytes())
    write(TESTS / "cornell-box.glb", cornell_box().glb_bytes())
    for name, data in bad_files().items():
        write(BAD / name, data)

    bounds, triangles = scene_facts(h, 1)
    assert (bounds, triangles) == (HIERARCHY_BOUNDS, HIERARCHY_TRIANGLES), (bounds, triangles)
    assert scene_facts(h, 0)[1] == HIERARCHY_SCENE0_TRIANGLES
    form_factor, radiance = square_light_radiance()
    print(f"hierarchy default scene: bounds {bounds}, {triangles} triangles")
    print(f"square-light: form factor {form_factor:.9f}, floor radiance {radiance:.9f}")


if __name__ == "__main__":
    main()
