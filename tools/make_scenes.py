#!/usr/bin/env python3
"""Writes the glTF 2.0 scenes that trs-render ships, each lit by emissive textures.

Python standard library only and deterministic, so the committed files can be regenerated
byte for byte:
    python3 tools/make_scenes.py scenes             # every scene
    python3 tools/make_scenes.py scenes mosaic      # only the scenes named

Each scene is a folder <name>/ holding <name>.gltf, its one buffer <name>.bin, its emission
textures (8-bit sRGB RGB PNG) and render.toml, the renderer's default settings. Units are metres
and +y is up. Meshes are written in world space (their nodes carry no transform); only the camera
node has one.
"""
import json
import math
import random
import struct
import sys
from pathlib import Path

# One PNG writer and one sRGB curve for every generated scene: the demo scene's. Importing it
# must not leave a __pycache__ folder in the source tree.
sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_demo_scene import srgb_encode, write_png  # noqa: E402

GENERATOR = "tools/make_scenes.py"
FLOAT, UNSIGNED_INT = 5126, 5125  # glTF component types
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
NEAREST, CLAMP_TO_EDGE = 9728, 33071
TRIANGLES = 4
WIDTH, HEIGHT = 480, 270  # every scene's default image size


# --- vectors as tuples --------------------------------------------------------------------------

def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def mul(a, k):
    return tuple(x * k for x in a)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    return mul(a, 1.0 / math.sqrt(dot(a, a)))


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def rotate_y(v, angle):
    c, s = math.cos(angle), math.sin(angle)
    return (c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2])


def axis(k, length=1.0):
    """The k-th coordinate axis (0: x, 1: y, 2: z), scaled."""
    return tuple(length if i == k else 0.0 for i in range(3))


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3 - 2 * t)


def f32(x):
    """x as the buffer stores it, so that accessor min/max can match the bytes exactly."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def short_f32(x):
    """The shortest decimal that reads back as float32 x: readable bounds that still match."""
    x = f32(x)
    for digits in range(1, 10):
        candidate = float(f"{x:.{digits}g}")
        if f32(candidate) == x:
            return candidate
    return x


# --- triangle meshes ----------------------------------------------------------------------------

class Mesh:
    """One glTF primitive's worth of triangles: positions, unit normals, UVs, indices."""

    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def add_grid(self, point, normal, cols, rows, uv=(0.0, 0.0, 1.0, 1.0)):
        """A patch of cols x rows quads of point(s, t), s and t in [0, 1], with UV (s, t) mapped
        onto the rectangle uv = (u0, v0, u1, v1) of the texture (all of it by default).

        The normals decide which side is the front: each triangle is wound counter-clockwise as
        seen from the side its normals point to (glTF's front face), whatever the parametrization.
        Triangles that collapse (at a sphere's poles, a disk's centre) are left out.
        """
        base = len(self.positions)
        for j in range(rows + 1):
            for i in range(cols + 1):
                s, t = i / cols, j / rows
                self.positions.append(point(s, t))
                self.normals.append(normalize(normal(s, t)))
                self.uvs.append((uv[0] + s * (uv[2] - uv[0]), uv[1] + t * (uv[3] - uv[1])))
        for j in range(rows):
            for i in range(cols):
                a = base + j * (cols + 1) + i
                b, c, d = a + 1, a + cols + 1, a + cols + 2
                self._add_triangle(a, c, d)
                self._add_triangle(a, d, b)

    def _add_triangle(self, a, b, c):
        p = self.positions
        face = cross(sub(p[b], p[a]), sub(p[c], p[a]))
        if dot(face, face) < 1e-16:
            return  # degenerate: no area to shade or sample
        if dot(face, add(add(self.normals[a], self.normals[b]), self.normals[c])) < 0:
            b, c = c, b  # wind it counter-clockwise around its normals
        self.indices += [a, b, c]

    def add_quad(self, corner, edge_s, edge_t, normal, cols=1, rows=1, uv=(0.0, 0.0, 1.0, 1.0)):
        """A flat parallelogram corner + s edge_s + t edge_t facing `normal`; UV (u0, v0) at
        `corner`, which is the image's top-left as seen from the front when edge_s points right
        and edge_t down."""
        self.add_grid(lambda s, t: add(add(corner, mul(edge_s, s)), mul(edge_t, t)),
                      lambda s, t: normal, cols, rows, uv)

    def extend(self, other):
        """Appends another mesh's triangles."""
        base = len(self.positions)
        self.positions += other.positions
        self.normals += other.normals
        self.uvs += other.uvs
        self.indices += [base + i for i in other.indices]


def room(x0, x1, height, z0, z1):
    """Floor, ceiling, back wall (at z0) and side walls facing inwards; open at z1, behind the
    camera, so that every view from inside meets a surface."""
    mesh = Mesh()
    width, depth = axis(0, x1 - x0), axis(2, z1 - z0)
    down = axis(1, -height)
    mesh.add_quad((x0, 0, z0), width, depth, (0, 1, 0))
    mesh.add_quad((x0, height, z0), width, depth, (0, -1, 0))
    mesh.add_quad((x0, height, z0), width, down, (0, 0, 1))
    mesh.add_quad((x0, height, z1), mul(depth, -1), down, (1, 0, 0))
    mesh.add_quad((x1, height, z0), depth, down, (-1, 0, 0))
    return mesh


def box(center, size, yaw=0.0):
    """A box of `size` standing at `center`, turned by `yaw` about +y; flat-shaded, 12 triangles."""
    mesh = Mesh()
    for k in range(3):
        u, v = [axis(i, size[i]) for i in range(3) if i != k]
        for sign in (-1, 1):
            n = axis(k, sign)
            corner = add(mul(n, size[k] / 2), mul(add(u, v), -0.5))  # relative to the centre
            mesh.add_quad(add(center, rotate_y(corner, yaw)), rotate_y(u, yaw), rotate_y(v, yaw),
                          rotate_y(n, yaw))
    return mesh


def sphere_direction(s, t):
    """The unit direction of UV (s, t) on sphere(): s around +y from +z, t from the north pole."""
    theta, phi = math.pi * t, 2 * math.pi * s
    return (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))


def sphere(center, radius, cols=12, rows=8):
    """A UV sphere, smooth-shaded, low-poly by default; UV (s, t) as sphere_direction()."""
    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(center, mul(sphere_direction(s, t), radius)), sphere_direction,
                  cols, rows)
    return mesh


def cylinder(base, radius, height, segments=16):
    """An upright closed cylinder: smooth side, flat caps."""
    def ring(s):
        return (math.sin(2 * math.pi * s), 0.0, math.cos(2 * math.pi * s))

    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(base, add(mul(ring(s), radius), (0, height * (1 - t), 0))),
                  lambda s, t: ring(s), segments, 1)
    for y, n in ((height, (0, 1, 0)), (0.0, (0, -1, 0))):  # t runs from the centre to the rim
        mesh.add_grid(lambda s, t, y=y: add(base, add(mul(ring(s), radius * t), (0, y, 0))),
                      lambda s, t, n=n: n, segments, 1)
    return mesh


# --- textures -----------------------------------------------------------------------------------

class Texture:
    """An image given by pixel(x, y) -> linear RGB in [0, 1], x right and y down; kept and written
    as 8-bit sRGB. With `frames` (Textures) it plays them, frame k written to `frames_pattern % k`
    (a path relative to the scene's folder), and this image is their poster."""

    def __init__(self, name, width, height, pixel, frames=None, frames_pattern=None):
        self.name, self.width, self.height = name, width, height
        self.rows = [[encode(pixel(x, y)) for x in range(width)] for y in range(height)]
        self.frames, self.frames_pattern = frames or [], frames_pattern

    def nonzero_fraction(self):
        """Texels with any non-zero channel: where a light sampler can land."""
        lit = sum(1 for row in self.rows for px in row if px != (0, 0, 0))
        return lit / (self.width * self.height)

    def write(self, folder):
        write_png(folder / self.name, self.width, self.height, self.rows)
        for k, frame in enumerate(self.frames):
            path = folder / (self.frames_pattern % k)
            path.parent.mkdir(parents=True, exist_ok=True)
            write_png(path, frame.width, frame.height, frame.rows)


def encode(rgb):
    return tuple(round(255 * srgb_encode(c)) for c in rgb)


# --- glTF ---------------------------------------------------------------------------------------

class Gltf:
    """Accumulates one glTF document, its single binary buffer and its textures."""

    def __init__(self, name):
        self.name = name
        self.blob = bytearray()
        self.textures = []
        self.facing_away = set()
        self.doc = {
            "asset": {"version": "2.0", "generator": GENERATOR},
            "extensionsUsed": ["KHR_materials_emissive_strength"],
            "scene": 0, "scenes": [{"name": name, "nodes": []}], "nodes": [], "cameras": [],
            "meshes": [], "materials": [], "textures": [], "images": [], "samplers": [],
            "accessors": [], "bufferViews": [], "buffers": [],
        }

    def _append(self, key, item):
        self.doc[key].append(item)
        return len(self.doc[key]) - 1

    def _node(self, node):
        self.doc["scenes"][0]["nodes"].append(self._append("nodes", node))

    def _view(self, data, target):
        """A buffer view of `data`, started on a 4-byte boundary as float and uint32 need."""
        self.blob += b"\0" * (-len(self.blob) % 4)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target is not None:  # vertex and index data; an animation's is neither
            view["target"] = target
        self.blob += data
        return self._append("bufferViews", view)

    def _vectors(self, values, bounds=False):
        """A float VEC2 or VEC3 accessor; POSITION (bounds=True) must state its min and max."""
        flat = [c for v in values for c in v]
        data = struct.pack(f"<{len(flat)}f", *flat)
        accessor = {"bufferView": self._view(data, ARRAY_BUFFER), "componentType": FLOAT,
                    "count": len(values), "type": f"VEC{len(values[0])}"}
        if bounds:
            accessor["min"] = [short_f32(min(v[k] for v in values)) for k in range(3)]
            accessor["max"] = [short_f32(max(v[k] for v in values)) for k in range(3)]
        return self._append("accessors", accessor)

    def _scalars(self, values, bounds=False):
        """A float SCALAR accessor; an animation's input (bounds=True) must state its min and max."""
        data = struct.pack(f"<{len(values)}f", *values)
        accessor = {"bufferView": self._view(data, None), "componentType": FLOAT, "count": len(values),
                    "type": "SCALAR"}
        if bounds:
            accessor["min"], accessor["max"] = [short_f32(min(values))], [short_f32(max(values))]
        return self._append("accessors", accessor)

    def animate_emissive_strength(self, material, times, values, interpolation="STEP"):
        """Keys the material's KHR_materials_emissive_strength over time (KHR_animation_pointer)."""
        if "KHR_animation_pointer" not in self.doc["extensionsUsed"]:
            self.doc["extensionsUsed"].append("KHR_animation_pointer")
        pointer = f"/materials/{material}/extensions/KHR_materials_emissive_strength/emissiveStrength"
        self.doc.setdefault("animations", []).append({
            "name": self.doc["materials"][material]["name"],
            "channels": [{"sampler": 0, "target": {
                "path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": pointer}}}}],
            "samplers": [{"input": self._scalars(times, bounds=True), "output": self._scalars(values),
                          "interpolation": interpolation}]})

    def _indices(self, values):
        data = struct.pack(f"<{len(values)}I", *values)
        return self._append("accessors", {
            "bufferView": self._view(data, ELEMENT_ARRAY_BUFFER), "componentType": UNSIGNED_INT,
            "count": len(values), "type": "SCALAR"})

    def material(self, name, base_color, metallic=0.0, roughness=0.9, double_sided=False):
        return self._append("materials", {
            "name": name,
            "pbrMetallicRoughness": {"baseColorFactor": list(base_color) + [1.0],
                                     "metallicFactor": metallic, "roughnessFactor": roughness},
            "doubleSided": double_sided})

    def _texture(self, texture):
        """The glTF texture of `texture`, added with its image the first time it is used."""
        if not self.doc["samplers"]:  # texel for texel, as the light sampler reads the map
            self.doc["samplers"].append({"magFilter": NEAREST, "minFilter": NEAREST,
                                         "wrapS": CLAMP_TO_EDGE, "wrapT": CLAMP_TO_EDGE})
        if texture not in self.textures:
            self.textures.append(texture)
            image = {"uri": texture.name}
            if texture.frames:  # the renderer plays the sequence; other viewers show the poster
                image["extras"] = {"frames": texture.frames_pattern}
            image = self._append("images", image)
            self._append("textures", {"sampler": 0, "source": image})
        return self.textures.index(texture)

    def emissive_material(self, name, texture, strength, double_sided=False):
        """Black and rough, emitting `texture` times `strength` (the radiance of a white texel),
        from both faces if `double_sided`."""
        texture_index = self._texture(texture)
        index = self.material(name, (0.02, 0.02, 0.02), 0.0, 0.9, double_sided)
        self.doc["materials"][index].update({
            "emissiveTexture": {"index": texture_index},
            "emissiveFactor": [1.0, 1.0, 1.0],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}})
        return index

    def mesh(self, name, mesh, material, facing_away=False):
        """A mesh node with one triangle primitive; an emitter `facing_away` from the camera on
        purpose is exempt from check()'s test that the camera sees its front."""
        if facing_away:
            self.facing_away.add(name)
        primitive = {
            "attributes": {"POSITION": self._vectors(mesh.positions, bounds=True),
                           "NORMAL": self._vectors(mesh.normals),
                           "TEXCOORD_0": self._vectors(mesh.uvs)},
            "indices": self._indices(mesh.indices), "material": material, "mode": TRIANGLES}
        self._node({"name": name, "mesh": self._append("meshes", {"name": name,
                                                                  "primitives": [primitive]})})

    def camera(self, eye, target, yfov):
        """A perspective camera at `eye` looking at `target`, +y up. glTF cameras look down
        their local -z with +y up, so the node's rotation takes those axes there."""
        forward = normalize(sub(target, eye))
        right = normalize(cross(forward, (0, 1, 0)))
        up = cross(right, forward)
        rotation = quaternion(right, up, mul(forward, -1))
        self.doc["cameras"].append({"name": "camera", "type": "perspective", "perspective": {
            "yfov": yfov, "aspectRatio": round(WIDTH / HEIGHT, 6), "znear": 0.05}})
        self._node({"name": "camera", "camera": 0, "translation": list(eye),
                    "rotation": [round(q, 7) for q in rotation]})

    def write(self, folder):
        self.doc["buffers"].append({"uri": self.name + ".bin", "byteLength": len(self.blob)})
        check(self.doc, bytes(self.blob), self.facing_away)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / (self.name + ".gltf")).write_text(json.dumps(self.doc, indent=1) + "\n")
        (folder / (self.name + ".bin")).write_bytes(bytes(self.blob))
        for texture in self.textures:
            texture.write(folder)


def quaternion(x_axis, y_axis, z_axis):
    """The unit quaternion [x, y, z, w] of the rotation matrix with these columns."""
    m = [[x_axis[r], y_axis[r], z_axis[r]] for r in range(3)]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(1 + trace)
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4)
    else:  # w is small: divide by the largest diagonal term's instead, for stability
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0] * 4
        q[i], q[j], q[k] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
        q[3] = (m[k][j] - m[j][k]) / s
    return normalize(q)


# --- self-check ---------------------------------------------------------------------------------

def read_accessor(doc, blob, index):
    """An accessor's elements (tuples, or ints for indices), asserting it lies in its view."""
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[accessor["type"]]
    code = "I" if accessor["componentType"] == UNSIGNED_INT else "f"
    assert accessor["count"] * width * 4 <= view["byteLength"], index
    flat = struct.unpack_from(f"<{accessor['count'] * width}{code}", blob, view["byteOffset"])
    return [flat[i:i + width] for i in range(0, len(flat), width)] if width > 1 else list(flat)


def check(doc, blob, facing_away=()):
    """Asserts the document is consistent with its buffer: views and accessors lie within it,
    attribute counts agree, POSITION bounds match the bytes, indices are in range, every triangle
    is wound counter-clockwise around its normals, and the camera sees each emitter's front faces
    (but those of the meshes named in `facing_away`)."""
    assert len(blob) == doc["buffers"][0]["byteLength"] and len(blob) % 4 == 0
    for view in doc["bufferViews"]:
        assert view["byteOffset"] % 4 == 0
        assert view["byteOffset"] + view["byteLength"] <= len(blob)
    eye = next(node["translation"] for node in doc["nodes"] if "camera" in node)
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            p, n, uv = (read_accessor(doc, blob, attributes[key])
                        for key in ("POSITION", "NORMAL", "TEXCOORD_0"))
            indices = read_accessor(doc, blob, primitive["indices"])
            bounds = doc["accessors"][attributes["POSITION"]]
            assert len(p) == len(n) == len(uv) and len(indices) % 3 == 0
            assert [f32(x) for x in bounds["min"]] == [min(v[k] for v in p) for k in range(3)]
            assert [f32(x) for x in bounds["max"]] == [max(v[k] for v in p) for k in range(3)]
            assert all(0 <= i < len(p) for i in indices)
            emitter = "emissiveTexture" in doc["materials"][primitive["material"]]
            facing_camera = 0
            for t in range(0, len(indices), 3):
                a, b, c = indices[t:t + 3]
                face = cross(sub(p[b], p[a]), sub(p[c], p[a]))
                assert dot(face, add(add(n[a], n[b]), n[c])) > 0, (mesh["name"], t // 3)
                facing_camera += dot(face, sub(eye, p[a])) > 0
            assert not emitter or facing_camera > 0 or mesh["name"] in facing_away, mesh["name"]


def write_settings(folder, title, spp, max_depth=4, lights='"auto"'):
    """render.toml: `key = value` lines that trs-render's CLI11 config parser reads."""
    lines = [f"# {title}: settings for trs-render (command-line flags override these)",
             f"width = {WIDTH}", f"height = {HEIGHT}", f"spp = {spp}",
             f"max-depth = {max_depth}", f"lights = {lights}"]
    (folder / "render.toml").write_text("\n".join(lines) + "\n")


# --- scene 1: neon-sign -------------------------------------------------------------------------

def segment(ax, ay, bx, by):
    """Distance to segment a-b, and its bounding box (x0, y0, x1, y1)."""
    def distance(x, y):
        dx, dy = bx - ax, by - ay
        t = min(max(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0), 1.0)
        return math.hypot(x - ax - t * dx, y - ay - t * dy)
    return distance, (min(ax, bx), min(ay, by), max(ax, bx), max(ay, by))


def arc(cx, cy, r, start, end):
    """Distance to the circular arc from angle `start` to `end` (degrees, y down, increasing)."""
    a0, a1 = math.radians(start), math.radians(end)

    def distance(x, y):
        if (math.atan2(y - cy, x - cx) - a0) % (2 * math.pi) <= a1 - a0:
            return abs(math.hypot(x - cx, y - cy) - r)
        return min(math.hypot(x - cx - r * math.cos(a), y - cy - r * math.sin(a))
                   for a in (a0, a1))
    return distance, (cx - r, cy - r, cx + r, cy + r)


def wave(x0, x1, y0, amplitude, period):
    """Vertical distance to a sine wave of whole periods: near enough for gentle slopes."""
    def distance(x, y):
        if x < x0 or x > x1:
            return math.hypot(min(abs(x - x0), abs(x - x1)), y - y0)
        return abs(y - y0 - amplitude * math.sin(2 * math.pi * (x - x0) / period))
    return distance, (x0, y0 - amplitude, x1, y0 + amplitude)


NEON_CORE, NEON_GLOW, NEON_REACH = 2.5, 4.0, 12.0  # texels: tube radius, halo width, cut-off


def neon_strokes():
    """(shape, linear RGB) pairs: the word TRS, a ring around a bolt, an arrow, a wavy line."""
    cyan, pink, yellow = (0.1, 0.8, 1.0), (1.0, 0.1, 0.6), (1.0, 0.85, 0.1)
    green, orange = (0.2, 1.0, 0.3), (1.0, 0.45, 0.05)
    letters = [segment(80, 50, 220, 50), segment(150, 50, 150, 190),  # T
               segment(265, 50, 265, 190), segment(265, 50, 300, 50),  # R
               segment(265, 130, 300, 130), arc(300, 90, 40, -90, 90),
               segment(300, 130, 350, 190),
               arc(430, 85, 35, 90, 340), arc(430, 155, 35, -90, 160)]  # S
    bolt = [(625, 70), (660, 118), (622, 128), (658, 175)]
    arrow = [((770, 120), (960, 120)), ((960, 120), (920, 88)), ((960, 120), (920, 152))]
    return ([(shape, cyan) for shape in letters] + [(arc(640, 120, 70, 0, 360), pink)]
            + [(segment(*a, *b), yellow) for a, b in zip(bolt, bolt[1:])]
            + [(segment(*a, *b), green) for a, b in arrow]
            + [(wave(70, 950, 228, 7, 110), orange)])


def neon_pixel(strokes):
    """Bright tubes, each in a soft halo that is exactly zero beyond NEON_REACH texels: most of
    the sign is black, as a density map that rewards sampling by texel."""
    def pixel(x, y):
        x, y = x + 0.5, y + 0.5
        rgb = (0.0, 0.0, 0.0)
        for (distance, (x0, y0, x1, y1)), color in strokes:
            if x0 - NEON_REACH < x < x1 + NEON_REACH and y0 - NEON_REACH < y < y1 + NEON_REACH:
                d = distance(x, y)
                if d < NEON_REACH:
                    halo = 0.3 * math.exp(-((d - NEON_CORE) / NEON_GLOW) ** 2)
                    rgb = add(rgb, mul(color, 1.0 if d < NEON_CORE else halo))
        return rgb
    return pixel


def neon_sign():
    """The README demo: a room with a few objects, lit only by a neon sign on a wall."""
    gltf = Gltf("neon-sign")
    gltf.mesh("room", room(-3.0, 3.0, 3.2, -2.5, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("crate", box((0.6, 0.35, -1.6), (0.7, 0.7, 0.7), 0.35),
              gltf.material("crate", (0.7, 0.55, 0.4)))
    gltf.mesh("ball", sphere((1.5, 0.45, 0.4), 0.45),
              gltf.material("red plastic", (0.7, 0.08, 0.05), 0.0, 0.3))
    gltf.mesh("post", cylinder((-0.3, 0.0, -0.2), 0.25, 1.1),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("neon.png", 1024, 256, neon_pixel(neon_strokes()))
    sign = Mesh()  # 3.2 x 0.8 m, 2 cm off the right-hand wall, facing into the room (-x)
    sign.add_quad((2.98, 2.45, -1.9), axis(2, 3.2), axis(1, -0.8), (-1, 0, 0))
    gltf.mesh("neon sign", sign, gltf.emissive_material("neon", texture, 100.0))
    gltf.camera((-2.3, 1.6, 3.9), (1.2, 1.1, -1.0), 0.75)
    return gltf, "Neon sign", 16


# --- scene 2: gradient-screen -------------------------------------------------------------------

def blob(u, v, cu, cv, ru, rv):
    """A Gaussian bump centred at (cu, cv) with radii (ru, rv)."""
    return math.exp(-(((u - cu) / ru) ** 2 + ((v - cv) / rv) ** 2))


def sunset_pixel(width, height):
    """A sky from deep blue to orange over a dark sea, two soft clouds and a low sun with its
    glitter path: smooth everywhere, and no texel is zero."""
    horizon, sun_u, sun_v = 0.68, 0.55, 0.58

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        if v >= horizon:  # the sea: dim, darker towards the viewer, lit under the sun
            rgb = mix((0.35, 0.12, 0.08), (0.03, 0.04, 0.12), smoothstep(horizon, 1.0, v))
            return add(rgb, mul((0.5, 0.25, 0.075), blob(u, v, sun_u, horizon, 0.04, 0.3)))
        sky = mix((0.05, 0.08, 0.35), (0.9, 0.35, 0.1), smoothstep(0.0, horizon, v) ** 1.5)
        cloud = 0.6 * (blob(u, v, 0.25, 0.3, 0.18, 0.05) + blob(u, v, 0.75, 0.2, 0.22, 0.04))
        rgb = mix(sky, (0.35, 0.15, 0.25), min(cloud, 1.0))
        glow = blob(u, v, sun_u, sun_v, 0.12, 0.2) + 0.3 * blob(u, v, sun_u, 0.6, 0.4, 0.35)
        disc = 1.0 - smoothstep(0.06, 0.075, math.hypot((u - sun_u) * width / height, v - sun_v))
        rgb = add(rgb, add(mul((0.5, 0.275, 0.1), glow), mul((1.0, 0.85, 0.55), disc)))
        return tuple(min(c, 1.0) for c in rgb)
    return pixel


def gradient_screen():
    """A big screen showing a smooth sunset: every texel lit, low contrast, a broad emitter."""
    gltf = Gltf("gradient-screen")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -2.5, 4.5), gltf.material("plaster", (0.7,) * 3))
    black = gltf.material("black plastic", (0.03, 0.03, 0.03), 0.0, 0.4)
    gltf.mesh("bezel", box((0.0, 1.35, -1.55), (3.3, 1.9, 0.08)), black)
    gltf.mesh("stand", box((0.0, 0.2, -1.55), (1.2, 0.4, 0.5)), black)
    gltf.mesh("ball", sphere((-0.7, 0.4, 0.2), 0.4),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((0.8, 0.3, 0.6), (0.6, 0.6, 0.6), -0.4),
              gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((1.6, 0.0, -0.3), 0.2, 0.8),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("sunset.png", 512, 288, sunset_pixel(512, 288))
    screen = Mesh()  # 3.2 x 1.8 m, 1 mm in front of its bezel, facing the room (+z)
    screen.add_quad((-1.6, 2.25, -1.509), axis(0, 3.2), axis(1, -1.8), (0, 0, 1))
    gltf.mesh("screen", screen, gltf.emissive_material("screen", texture, 5.0))
    gltf.camera((2.0, 1.4, 4.0), (-0.1, 0.9, -1.0), 0.8)
    return gltf, "Gradient screen", 16


# --- scene 3: mosaic ----------------------------------------------------------------------------

def tile_color(rng, u, v):
    """A random tile at (u, v) in [0, 1]^2 of the panel: a quarter are off, intensities are
    skewed so that a few are much brighter than the rest, and hues drift from blue (top left)
    through magenta to orange (bottom right) so that the light varies at large scale too."""
    if rng.random() < 0.25:
        return (0.0, 0.0, 0.0)
    hue = 0.62 + 0.45 * (u + v) / 2 + 0.15 * (rng.random() - 0.5)
    level = rng.random() ** 3
    rgb = tuple(0.5 + 0.5 * math.cos(2 * math.pi * (hue - k / 3)) for k in range(3))
    return mul(mix(rgb, (1.0, 1.0, 1.0), 0.25), level)


def mosaic_pixel(size, seed=7):
    """8-texel cells, 30% of them split into four 4-texel tiles; the last texel row and column
    of every tile is black grout."""
    rng = random.Random(seed)
    cells = size // 8
    split = [[rng.random() < 0.3 for _ in range(cells)] for _ in range(cells)]
    tiles = {}  # (column, row, tile size) -> linear RGB; drawn in a fixed order from the seed
    for j in range(cells):
        for i in range(cells):
            if split[j][i]:
                for k in range(4):
                    tile = (2 * i + k % 2, 2 * j + k // 2, 4)
                    tiles[tile] = tile_color(rng, i / cells, j / cells)
            else:
                tiles[(i, j, 8)] = tile_color(rng, i / cells, j / cells)

    def pixel(x, y):
        tile = 4 if split[y // 8][x // 8] else 8
        if x % tile == tile - 1 or y % tile == tile - 1:
            return (0.0, 0.0, 0.0)
        return tiles[(x // tile, y // tile, tile)]
    return pixel


def mosaic():
    """A fine, high-contrast mosaic on four large triangles: 262,144 texels per triangle."""
    gltf = Gltf("mosaic")
    gltf.mesh("room", room(-2.5, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("ball", sphere((-1.0, 0.45, 0.4), 0.45),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("crate", box((0.2, 0.4, -0.8), (0.8, 0.8, 0.8), 0.5),
              gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((-0.6, 0.0, -1.6), 0.22, 1.3),
              gltf.material("gold", (1.0, 0.78, 0.35), 1.0, 0.35))
    texture = Texture("mosaic.png", 1024, 1024, mosaic_pixel(1024))
    panel = Mesh()  # 2.6 x 2.6 m, 1 cm off the left-hand wall, facing the room (+x)
    panel.add_quad((-2.49, 2.8, 1.3), axis(2, -2.6), axis(1, -2.6), (1, 0, 0), cols=2)
    gltf.mesh("mosaic panel", panel, gltf.emissive_material("mosaic", texture, 20.0))
    gltf.camera((0.9, 1.8, 4.3), (-0.7, 0.8, -1.0), 0.8)
    return gltf, "Mosaic", 16


# --- scene 4: tile-emitter ----------------------------------------------------------------------

def light_box_pixel(size, seed=11):
    """An 8 x 8 grid of rounded bright cells (LEDs behind a diffuser), warm or cool white, a
    quarter of them dimmed and some off, with black gaps between them."""
    rng = random.Random(seed)
    cells, pitch = 8, size // 8
    levels = []
    for _ in range(cells * cells):
        on, dim, warm = rng.random(), rng.random(), rng.random() < 0.5
        white = (1.0, 0.8, 0.55) if warm else (0.75, 0.85, 1.0)
        levels.append(mul(white, 0.0 if on < 0.15 else (0.35 if dim < 0.25 else 1.0)))

    def pixel(x, y):
        cx, cy = x % pitch + 0.5 - pitch / 2, y % pitch + 0.5 - pitch / 2
        half, radius = pitch * 0.36, pitch * 0.12  # a rounded square, 72% of the pitch wide
        qx, qy = max(abs(cx) - half + radius, 0.0), max(abs(cy) - half + radius, 0.0)
        inside = 1.0 - smoothstep(radius - 1.0, radius + 1.0, math.hypot(qx, qy))
        return mul(levels[(y // pitch) * cells + x // pitch], inside)
    return pixel


def light_box(centre, size, sag, cells):
    """A square panel bowed into a shallow barrel vault, lowest along its axis, facing down;
    cells x cells quads of UV-space side 1/cells."""
    def point(s, t):
        x, z = (s - 0.5) * size, (t - 0.5) * size
        return add(centre, (x, -sag * (1 - (2 * x / size) ** 2), z))

    def normal(s, t):  # downwards, tilted outwards with the slope
        return (8 * sag * (s - 0.5) / size, -1.0, 0.0)

    mesh = Mesh()
    mesh.add_grid(point, normal, cells, cells)
    return mesh


def tile_emitter():
    """A ceiling light box of 32,768 small triangles, each about 2 x 2 texels of its map."""
    gltf = Gltf("tile-emitter")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("table", box((0.0, 0.375, -0.6), (1.2, 0.75, 0.8), 0.2),
              gltf.material("wood", (0.55, 0.35, 0.2)))
    gltf.mesh("ball", sphere((-1.4, 0.35, 0.3), 0.35),
              gltf.material("red plastic", (0.7, 0.08, 0.05), 0.0, 0.3))
    gltf.mesh("post", cylinder((1.5, 0.0, 0.2), 0.2, 1.2),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("light-box.png", 256, 256, light_box_pixel(256))
    panel = light_box((0.0, 2.9, -0.6), 2.4, 0.12, 128)
    gltf.mesh("light box", panel, gltf.emissive_material("light box", texture, 10.0))
    gltf.camera((2.2, 1.5, 4.0), (-0.4, 1.1, -1.0), 0.95)
    return gltf, "Tile emitter", 16


# --- scene 5: lantern ---------------------------------------------------------------------------

def lantern_pixels(width, height, dots=90, radius=0.05, seed=5):
    """Round dots, scattered evenly over the sphere (a jittered Fibonacci lattice), on black: a
    bright core with a soft rim, each dot warm, cool or amber white and some dimmer. Returns
    pixel(x, y) over a map rasterised dot by dot (each touches only the texels near it)."""
    rng = random.Random(seed)
    texels = [[(0.0, 0.0, 0.0)] * width for _ in range(height)]
    golden = math.pi * (3 - math.sqrt(5))
    for k in range(dots):
        y = 1 - 2 * (k + 0.5 + rng.uniform(-0.3, 0.3)) / dots
        phi = golden * k + rng.uniform(-0.2, 0.2)
        r = math.sqrt(max(1 - y * y, 0.0))
        centre = (r * math.sin(phi), y, r * math.cos(phi))
        colour = mul(rng.choice([(1.0, 0.85, 0.6), (0.75, 0.85, 1.0), (1.0, 0.6, 0.25)]),
                     rng.choice([1.0, 1.0, 0.5, 0.25]))
        theta = math.acos(max(-1.0, min(1.0, centre[1])))
        t0 = max(int((theta - radius) / math.pi * height) - 1, 0)
        t1 = min(int((theta + radius) / math.pi * height) + 2, height)
        for j in range(t0, t1):
            for i in range(width):
                d = sphere_direction((i + 0.5) / width, (j + 0.5) / height)
                angle = math.acos(max(-1.0, min(1.0, dot(d, centre))))
                if angle < radius:
                    weight = 1.0 - smoothstep(0.6 * radius, radius, angle)
                    texels[j][i] = add(texels[j][i], mul(colour, weight))
    return lambda x, y: tuple(min(c, 1.0) for c in texels[y][x])


def lantern():
    """A ball lantern pierced with sparse bright dots, hanging in the middle of a room: its
    lights face every way, so from any point of the room about half of them face away."""
    gltf = Gltf("lantern")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("table", box((-0.9, 0.375, -1.2), (1.2, 0.75, 0.8), 0.3),
              gltf.material("wood", (0.55, 0.35, 0.2)))
    gltf.mesh("ball", sphere((1.3, 0.4, 0.2), 0.4),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("post", cylinder((1.2, 0.0, -1.7), 0.2, 1.4),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("lantern.png", 512, 256, lantern_pixels(512, 256))
    ball = sphere((0.0, 1.9, -0.6), 0.4, cols=48, rows=24)
    gltf.mesh("lantern", ball, gltf.emissive_material("lantern", texture, 250.0))
    gltf.camera((2.3, 1.5, 4.1), (-0.3, 1.3, -1.0), 0.9)
    return gltf, "Lantern", 16


# --- scene 6: night-street ----------------------------------------------------------------------

# A stroke font on a 2 x 4 lattice (x right, y down): each letter a few segments, as a neon sign
# bends its tubes.
STROKES = {
    "A": [(0, 4, 1, 0), (1, 0, 2, 4), (0.5, 2.5, 1.5, 2.5)], "B": [(0, 0, 0, 4), (0, 0, 1.6, 0.6), (1.6, 0.6, 0, 2), (0, 2, 2, 3), (2, 3, 0, 4)],
    "C": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4)], "D": [(0, 0, 0, 4), (0, 0, 2, 1), (2, 1, 2, 3), (2, 3, 0, 4)],
    "E": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4), (0, 2, 1.5, 2)], "F": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 2, 1.5, 2)],
    "H": [(0, 0, 0, 4), (2, 0, 2, 4), (0, 2, 2, 2)], "I": [(1, 0, 1, 4), (0.3, 0, 1.7, 0), (0.3, 4, 1.7, 4)],
    "K": [(0, 0, 0, 4), (2, 0, 0, 2), (0, 2, 2, 4)], "L": [(0, 0, 0, 4), (0, 4, 2, 4)],
    "M": [(0, 4, 0, 0), (0, 0, 1, 2), (1, 2, 2, 0), (2, 0, 2, 4)], "N": [(0, 4, 0, 0), (0, 0, 2, 4), (2, 4, 2, 0)],
    "O": [(0, 0, 2, 0), (2, 0, 2, 4), (2, 4, 0, 4), (0, 4, 0, 0)], "P": [(0, 4, 0, 0), (0, 0, 2, 0), (2, 0, 2, 2), (2, 2, 0, 2)],
    "R": [(0, 4, 0, 0), (0, 0, 2, 0), (2, 0, 2, 2), (2, 2, 0, 2), (0.8, 2, 2, 4)], "S": [(2, 0, 0, 0), (0, 0, 0, 2), (0, 2, 2, 2), (2, 2, 2, 4), (2, 4, 0, 4)],
    "T": [(0, 0, 2, 0), (1, 0, 1, 4)], "U": [(0, 0, 0, 4), (0, 4, 2, 4), (2, 4, 2, 0)],
    "V": [(0, 0, 1, 4), (1, 4, 2, 0)], "W": [(0, 0, 0.5, 4), (0.5, 4, 1, 2), (1, 2, 1.5, 4), (1.5, 4, 2, 0)],
    "Y": [(0, 0, 1, 2), (2, 0, 1, 2), (1, 2, 1, 4)], "Z": [(0, 0, 2, 0), (2, 0, 0, 4), (0, 4, 2, 4)],
    "G": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4), (2, 4, 2, 2), (2, 2, 1, 2)], "J": [(2, 0, 2, 4), (2, 4, 0, 4), (0, 4, 0, 3)],
    "X": [(0, 0, 2, 4), (2, 0, 0, 4)],
}
SIGN_WORDS = ["BAR", "HOTEL", "PIZZA", "OPEN", "CAFE", "NOODLES", "CLUB", "BOOKS", "RAMEN", "DINER",
              "JAZZ", "TATTOO", "SUSHI", "KEBAB", "RADIO", "WINE"]
NEON_COLOURS = [(0.1, 0.8, 1.0), (1.0, 0.1, 0.6), (1.0, 0.85, 0.1), (0.2, 1.0, 0.3), (1.0, 0.45, 0.05),
                (0.6, 0.3, 1.0), (1.0, 0.15, 0.1)]


class Atlas:
    """A texture painted region by region: each region a rectangle of texels with a painter of its
    own, pixel(x, y) -> linear RGB in region coordinates. uv(region) is its UV rectangle."""

    def __init__(self, name, width, height):
        self.name, self.width, self.height = name, width, height
        self.texels = [[(0.0, 0.0, 0.0)] * width for _ in range(height)]

    def paint(self, x0, y0, w, h, pixel):
        for y in range(h):
            row = self.texels[y0 + y]
            for x in range(w):
                row[x0 + x] = pixel(x, y)
        return (x0 / self.width, y0 / self.height, (x0 + w) / self.width, (y0 + h) / self.height)

    def texture(self):
        return Texture(self.name, self.width, self.height, lambda x, y: self.texels[y][x])


def word_strokes(word, width, height, colour):
    """The word centred in a width x height region, as neon_pixel's (shape, colour) pairs."""
    size = min(height * 0.62 / 4, width * 0.9 / (3 * len(word)))  # texels per lattice step
    left, top = (width - (3 * len(word) - 1) * size) / 2, (height - 4 * size) / 2
    strokes = []
    for k, letter in enumerate(word):
        x = left + 3 * k * size
        for ax, ay, bx, by in STROKES[letter]:
            strokes.append((segment(x + ax * size, top + ay * size, x + bx * size, top + by * size), colour))
    return strokes


def window_pixel(rng, width, height):
    """A lit window seen from the street: a warm or cool interior falling off from a lamp, a few
    dark silhouettes, mullions, and sometimes a half-drawn curtain."""
    warm = rng.random() < 0.7
    glow = (1.0, 0.7, 0.4) if warm else (0.6, 0.8, 1.0)
    lamp_x, lamp_y = rng.uniform(0.2, 0.8), rng.uniform(0.1, 0.4)
    panes = rng.choice([1, 2, 3])
    curtain = rng.random() < 0.4
    shapes = [(rng.uniform(0.1, 0.9), rng.uniform(0.5, 0.9), rng.uniform(0.08, 0.2)) for _ in range(rng.randint(0, 3))]

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        if min(u, v, 1 - u, 1 - v) < 0.04 or abs((u * panes) % 1.0) < 0.03 * panes:
            return (0.0, 0.0, 0.0)  # frame and mullions
        level = 0.25 + 0.75 * math.exp(-((u - lamp_x) ** 2 + (v - lamp_y) ** 2) / 0.08)
        if curtain and u < 0.35:
            level *= 0.3
        if any(math.hypot(u - cx, (v - cy) * 0.6) < r for cx, cy, r in shapes):
            level *= 0.08
        return mul(glow, level)
    return pixel


def lamp_pixel(size):
    """A street lamp's diffuser seen from below: bright in the middle, falling to zero at the rim."""
    def pixel(x, y):
        r = math.hypot((x + 0.5) / size - 0.5, (y + 0.5) / size - 0.5) * 2
        return mul((1.0, 0.82, 0.55), max(0.0, 1.0 - r * r))
    return pixel


def screen_pixel(rng, width, height, bars):
    """A video screen's frame: a dark ground with bright moving-image shapes: discs, bars and a
    band of large letters' strokes, high contrast."""
    discs = [(rng.uniform(0.1, 0.9), rng.uniform(0.15, 0.85), rng.uniform(0.04, 0.12), rng.choice(NEON_COLOURS))
             for _ in range(6)]
    stripes = [(rng.uniform(0.0, 0.8), rng.uniform(0.05, 0.2), rng.choice(NEON_COLOURS)) for _ in range(bars)]

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        rgb = mix((0.02, 0.02, 0.06), (0.05, 0.02, 0.1), v)
        for cu, cv, r, colour in discs:
            if math.hypot((u - cu) * width / height, v - cv) < r:
                rgb = colour
        for start, thickness, colour in stripes:
            if start < v < start + thickness and (u * 7) % 1.0 < 0.8:
                rgb = mul(colour, 0.8)
        return rgb
    return pixel


def facade(x, z0, z1, height, facing):
    """A street facade at x from z0 to z1 (z0 > z1), facing +x or -x, with pilasters every 5 m and
    a kerb-high plinth: shadows and edges for the signs to light."""
    mesh = Mesh()
    length = z0 - z1
    wall = Mesh()
    corner = (x, height, z1) if facing > 0 else (x, height, z0)
    edge = axis(2, length) if facing > 0 else axis(2, -length)
    wall.add_quad(corner, edge, axis(1, -height), (facing, 0, 0))
    mesh.extend(wall)
    z = z0 - 2.5
    while z > z1:
        mesh.extend(box((x + facing * 0.15, height / 2, z), (0.3, height, 0.4)))
        z -= 5.0
    return mesh


STREET_END = -86.0  # the street runs from z = 5 (behind the camera) to here


def street_emitters(rng):
    """The street's emitters, by atlas: {atlas name: [(mesh, double_sided)]}, and the atlases."""
    neon = Atlas("street-neon.png", 1024, 1024)      # 16 words of 512 x 128
    windows = Atlas("street-windows.png", 512, 512)  # 16 windows of 128 x 128
    screens = Atlas("street-screens.png", 1024, 512)  # screen, billboard, blades, lamp
    regions = {"word": [], "window": []}
    for k, word in enumerate(SIGN_WORDS):
        x0, y0 = (k % 2) * 512, (k // 2) * 128
        colour = NEON_COLOURS[k % len(NEON_COLOURS)]
        regions["word"].append(neon.paint(x0, y0, 512, 128, neon_pixel(word_strokes(word, 512, 128, colour))))
    for k in range(16):
        regions["window"].append(windows.paint((k % 4) * 128, (k // 4) * 128, 128, 128, window_pixel(rng, 128, 128)))
    screen_uv = screens.paint(0, 0, 512, 288, screen_pixel(rng, 512, 288, 3))
    billboard_uv = screens.paint(512, 0, 512, 256, screen_pixel(rng, 512, 256, 5))
    blade_uv = [screens.paint(512 + 64 * k, 256, 64, 192,
                              neon_pixel(word_strokes(w, 64, 192, NEON_COLOURS[k % 7])))
                for k, w in enumerate(["BAR", "INN", "TAXI", "POOL", "CAFE", "OPEN"][:6])]
    lamp_uv = screens.paint(0, 320, 64, 64, lamp_pixel(64))

    signs, lit_windows, lamps, blades, big = Mesh(), Mesh(), Mesh(), [], Mesh()
    word = 0
    for side in (-1, 1):
        x = side * 6.0
        for k in range(17):
            z = -5.0 * k - 0.3
            uv = regions["word"][word % 16]
            word += 1
            if (k, side) in ((3, -1), (6, 1), (12, -1)):
                # Backlit letters mounted the wrong way round: they face the wall they hang on.
                signs.add_quad((x - side * 0.25, 3.95, z - 3.5 * (side < 0)), axis(2, 3.5 * side * -1 if side < 0 else 3.5),
                               axis(1, -0.7), (side, 0, 0), uv=uv)
                continue
            front = (-side, 0, 0)
            corner = (x - side * 0.05, 3.95, z - (0 if side < 0 else 3.5))
            edge = axis(2, -3.5) if side < 0 else axis(2, 3.5)
            signs.add_quad(corner, edge, axis(1, -0.7), front, uv=uv)
            if rng.random() < 0.6:  # a lit shop window under it
                lit_windows.add_quad((x - side * 0.04, 2.6, z - (0.4 if side < 0 else 3.1)),
                                     axis(2, -2.7) if side < 0 else axis(2, 2.7), axis(1, -2.0), front,
                                     uv=regions["window"][rng.randrange(16)])
            for floor in (6.5, 9.5):  # lit flats upstairs
                if rng.random() < 0.45:
                    wz = z - rng.uniform(0.5, 3.0)
                    lit_windows.add_quad((x - side * 0.04, floor + 1.4, wz + (0 if side < 0 else -1.0)),
                                         axis(2, -1.0) if side < 0 else axis(2, 1.0), axis(1, -1.4), front,
                                         uv=regions["window"][rng.randrange(16)])
        for k in range(9):  # street lamps over the kerbs, facing down
            z = -10.0 * k - 4.0
            lamps.add_quad((x * 0.68 - 0.25, 6.0, z - 0.15), axis(0, 0.5), axis(2, 0.3), (0, -1, 0), uv=lamp_uv)
    for k in range(12):  # blade signs sticking out of the facades, along the street
        side = -1 if k % 2 else 1
        z = -7.0 * k - 2.0
        x = side * (6.0 - 0.2)
        mesh = Mesh()
        inner = (x - side * 0.7, 5.0, z)
        if k % 4 < 2:  # two-sided, seen from both ways along the street
            mesh.add_quad(inner, axis(0, side * 0.6), axis(1, -1.8), (0, 0, 1), uv=blade_uv[k % 6])
            blades.append((mesh, True))
        else:  # one-sided, facing away from the camera, down the street
            mesh.add_quad((inner[0] + side * 0.6, 5.0, z), axis(0, -side * 0.6), axis(1, -1.8), (0, 0, -1),
                          uv=blade_uv[k % 6])
            blades.append((mesh, False))
    # A large video screen on the building closing the street, and billboards high on the facades.
    big.add_quad((-6.0, 10.5, STREET_END + 0.1), axis(0, 12.0), axis(1, -6.75), (0, 0, 1), cols=8, rows=4,
                 uv=screen_uv)
    big.add_quad((5.9, 12.0, -16.0), axis(2, 6.0), axis(1, -3.0), (-1, 0, 0), cols=2, rows=2, uv=billboard_uv)
    big.add_quad((-5.9, 12.0, -64.0), axis(2, -6.0), axis(1, -3.0), (1, 0, 0), cols=2, rows=2, uv=billboard_uv)
    atlases = [neon.texture(), windows.texture(), screens.texture()]
    return {"signs": signs, "windows": lit_windows, "lamps": lamps, "blades": blades, "screens": big}, atlases


def night_street():
    """A street at night lit by 60-odd textured emitters at every distance and orientation:
    neon signs, shop windows, flats upstairs, lamps, blade signs, a billboard and a video screen."""
    rng = random.Random(21)
    gltf = Gltf("night-street")
    brick = gltf.material("brick", (0.35, 0.25, 0.2), 0.0, 0.85)
    for side in (-1, 1):
        gltf.mesh(f"facade {'left' if side < 0 else 'right'}", facade(side * 6.0, 5.0, STREET_END, 12.0, -side), brick)
    end = Mesh()
    end.add_quad((-6.0, 12.0, STREET_END), axis(0, 12.0), axis(1, -12.0), (0, 0, 1))
    gltf.mesh("end of the street", end, brick)
    road, pavement = Mesh(), Mesh()
    length = 5.0 - STREET_END
    road.add_quad((-4.0, 0.0, STREET_END), axis(0, 8.0), axis(2, length), (0, 1, 0))
    for side in (-1, 1):
        x0 = -6.0 if side < 0 else 4.0
        pavement.add_quad((x0, 0.15, STREET_END), axis(0, 2.0), axis(2, length), (0, 1, 0))
        kerb = (-4.0, 0.15, STREET_END) if side < 0 else (4.0, 0.0, STREET_END)
        pavement.add_quad(kerb, axis(1, -0.15) if side < 0 else axis(1, 0.15), axis(2, length), (-side, 0, 0))
    gltf.mesh("wet road", road, gltf.material("wet asphalt", (0.08, 0.08, 0.09), 0.0, 0.12))
    gltf.mesh("pavements", pavement, gltf.material("paving", (0.4, 0.4, 0.38), 0.0, 0.8))
    props = Mesh()
    for k in range(12):
        props.extend(cylinder((-3.8 if k % 2 else 3.8, 0.0, -6.0 * k - 1.0), 0.12, 0.9, 12))
    for side in (-1, 1):
        for k in range(9):
            props.extend(cylinder((side * 4.08, 0.15, -10.0 * k - 4.0), 0.08, 5.9, 8))
    props.extend(box((-2.2, 0.6, -12.0), (1.8, 1.2, 4.2), 0.05))  # a parked van's shape
    gltf.mesh("posts and bollards", props, gltf.material("painted steel", (0.3, 0.32, 0.35), 1.0, 0.45))
    emitters, atlases = street_emitters(rng)
    neon, windows, screens = atlases
    gltf.mesh("neon signs", emitters["signs"], gltf.emissive_material("neon", neon, 60.0))
    gltf.mesh("lit windows", emitters["windows"], gltf.emissive_material("windows", windows, 4.0))
    gltf.mesh("street lamps", emitters["lamps"], gltf.emissive_material("lamps", screens, 400.0))
    for k, (mesh, double_sided) in enumerate(emitters["blades"]):
        material = gltf.emissive_material(f"blade sign {k}", screens, 60.0, double_sided)
        gltf.mesh(f"blade sign {k}", mesh, material, facing_away=not double_sided)
    gltf.mesh("screens", emitters["screens"], gltf.emissive_material("screens", screens, 16.0))
    gltf.camera((1.2, 1.7, 4.0), (-0.6, 3.0, -30.0), 0.85)
    return gltf, "Night street", 16


# --- scene 7: video-wall ------------------------------------------------------------------------

CLIP_FRAMES, CLIP_WIDTH, CLIP_HEIGHT = 48, 320, 180  # two seconds at 24 frames per second


def clip_frame(k, banner, banner_width):
    """Frame k of the wall's clip: on a dark ground, a banner of neon words scrolling right to
    left, two bright discs on Lissajous paths and a bar sweeping down: high contrast, moving."""
    t = k / CLIP_FRAMES
    shift = int(t * banner_width)
    discs = [((0.5 + 0.4 * math.sin(2 * math.pi * (t + p)), 0.3 + 0.2 * math.sin(4 * math.pi * (t + p) + 1.0)),
              0.12, colour) for p, colour in ((0.0, (1.0, 0.3, 0.1)), (0.3, (0.2, 0.6, 1.0)))]
    bar = (t * 1.3) % 1.3 - 0.15

    def pixel(x, y):
        u, v = (x + 0.5) / CLIP_WIDTH, (y + 0.5) / CLIP_HEIGHT
        rgb = (0.002, 0.002, 0.005)  # an LED wall's black is not quite black
        if abs(v - bar) < 0.03:
            rgb = (0.6, 0.6, 0.7)
        for (cu, cv), r, colour in discs:
            if math.hypot((u - cu) * CLIP_WIDTH / CLIP_HEIGHT, v - cv) < r:
                rgb = colour
        if 0.62 <= v < 0.92:  # the banner's band
            lit = banner[int((v - 0.62) / 0.30 * len(banner))][(x + shift) % banner_width]
            rgb = add(rgb, lit)
        return tuple(min(c, 1.0) for c in rgb)
    return pixel


def video_wall():
    """An LED wall playing a two-second clip lights a room with a glossy floor, beside a small
    "on air" sign that blinks: emission that changes every frame."""
    gltf = Gltf("video-wall")
    gltf.mesh("room", room(-3.5, 3.5, 3.2, -2.5, 5.0), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("floor", box((0.0, -0.01, 1.0), (7.0, 0.02, 7.0)),
              gltf.material("polished concrete", (0.35, 0.35, 0.36), 0.0, 0.15))
    gltf.mesh("ball", sphere((-1.3, 0.45, 0.8), 0.45), gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((1.1, 0.35, 0.3), (0.7, 0.7, 0.7), 0.5), gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((0.2, 0.0, 1.6), 0.18, 1.2), gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.35))
    # The banner's words, painted once and scrolled: 3 words of neon strokes, 960 x 54 texels.
    banner_width, banner_height = 960, 54
    words = [neon_pixel(word_strokes(word, 320, banner_height, NEON_COLOURS[i]))
             for i, word in enumerate(["LIVE", "NEWS", "TRS"])]
    banner = [[words[x // 320](x % 320, y) for x in range(banner_width)] for y in range(banner_height)]
    frames = [Texture(f"frame {k}", CLIP_WIDTH, CLIP_HEIGHT, clip_frame(k, banner, banner_width))
              for k in range(CLIP_FRAMES)]
    clip = Texture("video-wall.png", CLIP_WIDTH, CLIP_HEIGHT, clip_frame(0, banner, banner_width), frames,
                   "clip/wall.%04d.png")
    wall = Mesh()  # 4.8 x 2.7 m on the back wall, 2 triangles, facing the room (+z)
    wall.add_quad((-2.4, 2.95, -2.49), axis(0, 4.8), axis(1, -2.7), (0, 0, 1))
    gltf.mesh("LED wall", wall, gltf.emissive_material("LED wall", clip, 8.0))
    sign_texture = Texture("on-air.png", 128, 32, neon_pixel(word_strokes("ONAIR", 128, 32, (1.0, 0.1, 0.1))))
    sign = Mesh()  # on the right-hand wall, facing the room (-x)
    sign.add_quad((3.49, 2.9, -1.6), axis(2, 1.2), axis(1, -0.3), (-1, 0, 0))
    on_air = gltf.emissive_material("on air", sign_texture, 40.0)
    gltf.mesh("on air sign", sign, on_air)
    gltf.animate_emissive_strength(on_air, [0.0, 0.5, 1.0, 1.5], [40.0, 0.0, 40.0, 0.0])
    gltf.camera((2.4, 1.6, 4.6), (-0.5, 1.2, -1.5), 0.85)
    return gltf, "Video wall", 16


SCENES = {"neon-sign": neon_sign, "gradient-screen": gradient_screen, "mosaic": mosaic,
          "tile-emitter": tile_emitter, "lantern": lantern, "night-street": night_street,
          "video-wall": video_wall}


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "scenes")
    for name in sys.argv[2:] or SCENES:
        gltf, title, spp = SCENES[name]()
        gltf.write(out / name)
        write_settings(out / name, title, spp)
        triangles = emitting = 0
        for m in gltf.doc["meshes"]:
            primitive = m["primitives"][0]
            count = gltf.doc["accessors"][primitive["indices"]]["count"] // 3
            triangles += count
            emitting += count if "emissiveTexture" in gltf.doc["materials"][primitive["material"]] else 0
        maps = ", ".join(f"{t.name} {t.width}x{t.height}, {100 * t.nonzero_fraction():.1f}% of "
                         "texels non-zero" for t in gltf.textures)
        print(f"{name}: {triangles} triangles, {emitting} emitting; {maps}")


if __name__ == "__main__":
    main()
