"""The glTF 2.0 writer: one document, its single buffer and its textures, checked before writing;
and render.toml, the renderer's default settings."""
import json
import struct
from pathlib import Path

from .vec import add, cross, dot, f32, look_at, mul, normalize, quaternion, short_f32, sub

GENERATOR = "tools/make_scenes.py"  # the asset's "generator": the command that writes the scenes
MATERIALS_GENERATOR = "tools/make_material_scenes.py"  # the same for scenes/materials
UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT, FLOAT = 5121, 5123, 5125, 5126  # glTF component types
COMPONENT_FORMATS = {UNSIGNED_BYTE: "B", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I", FLOAT: "f"}
TYPE_WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
NEAREST, CLAMP_TO_EDGE, REPEAT, MIRRORED_REPEAT = 9728, 33071, 10497, 33648
TRIANGLES = 4
WIDTH, HEIGHT = 480, 270  # every scene's default image size


class Gltf:
    """Accumulates one glTF document, its single binary buffer and its textures."""

    def __init__(self, name, generator=GENERATOR, extensions=("KHR_materials_emissive_strength",)):
        self.name = name
        self.blob = bytearray()
        self.textures = []
        self.facing_away = set()
        self.doc = {
            "asset": {"version": "2.0", "generator": generator},
            "extensionsUsed": list(extensions),
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
        """A float VEC2, VEC3 or VEC4 accessor; POSITION (bounds=True) must state its min and max."""
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

    def use_extension(self, extension):
        """Lists `extension` in extensionsUsed (once). Never in extensionsRequired: a viewer
        without it still shows the scene, if not quite as written."""
        if extension not in self.doc["extensionsUsed"]:
            self.doc["extensionsUsed"].append(extension)

    def _sampler(self, wrap):
        """The sampler of `wrap` on both axes, texel for texel (nearest), as the light sampler
        reads an emission map; the renderer's light sampler takes one wrap mode for both axes."""
        sampler = {"magFilter": NEAREST, "minFilter": NEAREST, "wrapS": wrap, "wrapT": wrap}
        if sampler not in self.doc["samplers"]:
            self.doc["samplers"].append(sampler)
        return self.doc["samplers"].index(sampler)

    def _texture(self, texture, wrap=CLAMP_TO_EDGE):
        """The glTF texture of `texture` read with `wrap`, added with its image the first time
        either is used."""
        sampler = self._sampler(wrap)
        if texture not in self.textures:
            self.textures.append(texture)
            image = {"uri": texture.name}
            if texture.frames:  # the renderer plays the sequence; other viewers show the poster
                image["extras"] = {"frames": texture.frames_pattern}
            self._append("images", image)
        entry = {"sampler": sampler, "source": self.textures.index(texture)}
        if entry not in self.doc["textures"]:
            self._append("textures", entry)
        return self.doc["textures"].index(entry)

    def texture_info(self, texture, wrap=CLAMP_TO_EDGE, tex_coord=0, transform=None):
        """A material's textureInfo: `texture` read with `wrap` at TEXCOORD_<tex_coord>, through
        `transform` if given: KHR_texture_transform's {"offset", "rotation", "scale",
        "texCoord"}, whose texCoord overrides `tex_coord`."""
        info = {"index": self._texture(texture, wrap)}
        if tex_coord:
            info["texCoord"] = tex_coord
        if transform:
            self.use_extension("KHR_texture_transform")
            info["extensions"] = {"KHR_texture_transform": dict(transform)}
        return info

    def set_alpha(self, material, mode, alpha=1.0, texture=None, cutoff=None):
        """Coverage: alphaMode `mode` ("MASK" or "BLEND") with alpha = `alpha` (baseColorFactor's
        fourth component) times the alpha of `texture` (a baseColorTexture textureInfo, whose
        RGB also multiplies the base colour); a MASK cuts at `cutoff`, glTF's 0.5 if None."""
        entry = self.doc["materials"][material]
        entry["pbrMetallicRoughness"]["baseColorFactor"][3] = alpha
        if texture is not None:
            entry["pbrMetallicRoughness"]["baseColorTexture"] = texture
        entry["alphaMode"] = mode
        if cutoff is not None:
            entry["alphaCutoff"] = cutoff

    def set_extension(self, material, extension, properties):
        """A material extension (KHR_materials_transmission, _volume, _ior, _specular, _clearcoat,
        _sheen) with its `properties` as the file stores them: textureInfos from texture_info()."""
        self.use_extension(extension)
        self.doc["materials"][material].setdefault("extensions", {})[extension] = dict(properties)

    def set_normal_texture(self, material, texture, scale=1.0):
        """A tangent-space normal map (a normalTexture textureInfo of linear data) and its scale."""
        self.doc["materials"][material]["normalTexture"] = dict(texture, scale=scale)

    def set_emission(self, material, texture, strength, factor=(1.0, 1.0, 1.0)):
        """Emission: `factor` times the emissiveTexture textureInfo `texture` (None: the factor
        alone) times `strength` (KHR_materials_emissive_strength)."""
        self.use_extension("KHR_materials_emissive_strength")
        entry = self.doc["materials"][material]
        if texture is not None:
            entry["emissiveTexture"] = texture
        entry["emissiveFactor"] = list(factor)
        entry.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}

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
        attributes = {"POSITION": self._vectors(mesh.positions, bounds=True),
                      "NORMAL": self._vectors(mesh.normals),
                      "TEXCOORD_0": self._vectors(mesh.uvs)}
        if mesh.uvs1:
            attributes["TEXCOORD_1"] = self._vectors(mesh.uvs1)
        if mesh.tangents:
            attributes["TANGENT"] = self._vectors(mesh.tangents)
        primitive = {"attributes": attributes, "indices": self._indices(mesh.indices),
                     "material": material, "mode": TRIANGLES}
        self._node({"name": name, "mesh": self._append("meshes", {"name": name,
                                                                  "primitives": [primitive]})})

    def punctual_light(self, name, kind, intensity, color=(1.0, 1.0, 1.0), position=(0.0, 0.0, 0.0),
                       direction=(0.0, -1.0, 0.0), cones=None, required=True):
        """A KHR_lights_punctual light (candela; lux for "directional") at `position`, shining
        along `direction` (spot and directional); `cones`: a spot's (inner, outer) angles. The
        file requires the extension unless not `required`: without its lights a scene is not the
        one written, but a scene that shows another feature still shows it."""
        for key in ("extensionsUsed", "extensionsRequired")[:2 if required else 1]:
            if "KHR_lights_punctual" not in self.doc.setdefault(key, []):
                self.doc[key].append("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})["lights"]
        light = {"name": name, "type": kind, "color": list(color), "intensity": intensity}
        if cones:
            light["spot"] = {"innerConeAngle": cones[0], "outerConeAngle": cones[1]}
        lights.append(light)
        # The node's -z along `direction`.
        back = mul(normalize(direction), -1)
        right = normalize(cross((0, 1, 0) if abs(back[1]) < 0.9 else (1, 0, 0), back))
        rotation = quaternion(right, cross(back, right), back)
        self._node({"name": name, "translation": list(position), "rotation": [round(q, 7) for q in rotation],
                    "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})

    def camera(self, eye, target, yfov):
        """A perspective camera at `eye` looking at `target`, +y up."""
        self.doc["cameras"].append({"name": "camera", "type": "perspective", "perspective": {
            "yfov": yfov, "aspectRatio": round(WIDTH / HEIGHT, 6), "znear": 0.05}})
        self._node({"name": "camera", "camera": 0, "translation": list(eye),
                    "rotation": [round(q, 7) for q in look_at(eye, target)]})

    def write(self, folder):
        self.doc["buffers"].append({"uri": self.name + ".bin", "byteLength": len(self.blob)})
        check(self.doc, bytes(self.blob), self.facing_away)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / (self.name + ".gltf")).write_text(json.dumps(self.doc, indent=1) + "\n")
        (folder / (self.name + ".bin")).write_bytes(bytes(self.blob))
        for texture in self.textures:
            texture.write(folder)


def read_accessor(doc, buffers, index):
    """An accessor's elements as stored (tuples, or numbers for a SCALAR), asserting it lies in
    its view; `buffers` holds the bytes of each of the document's buffers."""
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    width = TYPE_WIDTHS[accessor["type"]]
    element = struct.Struct(f"<{width}{COMPONENT_FORMATS[accessor['componentType']]}")
    stride = view.get("byteStride", element.size)
    offset, count = accessor.get("byteOffset", 0), accessor["count"]
    assert offset + stride * (count - 1) + element.size <= view["byteLength"], index
    blob, start = buffers[view["buffer"]], view.get("byteOffset", 0) + offset
    rows = [element.unpack_from(blob, start + i * stride) for i in range(count)]
    return rows if width > 1 else [row[0] for row in rows]


def check(doc, blob, facing_away=()):
    """Asserts the document is consistent with its buffer: views and accessors lie within it,
    attribute counts agree, POSITION bounds match the bytes, indices are in range, every triangle
    is wound counter-clockwise around its normals, tangents are unit, at right angles to the
    normals and carry a handedness of +-1, and the camera sees each emitter's front faces (but
    those of the meshes named in `facing_away`)."""
    assert len(blob) == doc["buffers"][0]["byteLength"] and len(blob) % 4 == 0
    for view in doc["bufferViews"]:
        assert view["byteOffset"] % 4 == 0
        assert view["byteOffset"] + view["byteLength"] <= len(blob)
    eye = next(node["translation"] for node in doc["nodes"] if "camera" in node)
    buffers = [blob]
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            p, n, uv = (read_accessor(doc, buffers, attributes[key])
                        for key in ("POSITION", "NORMAL", "TEXCOORD_0"))
            indices = read_accessor(doc, buffers, primitive["indices"])
            bounds = doc["accessors"][attributes["POSITION"]]
            assert len(p) == len(n) == len(uv) and len(indices) % 3 == 0
            assert [f32(x) for x in bounds["min"]] == [min(v[k] for v in p) for k in range(3)]
            assert [f32(x) for x in bounds["max"]] == [max(v[k] for v in p) for k in range(3)]
            assert all(0 <= i < len(p) for i in indices)
            if "TEXCOORD_1" in attributes:
                assert len(read_accessor(doc, buffers, attributes["TEXCOORD_1"])) == len(p)
            if "TANGENT" in attributes:
                tangents = read_accessor(doc, buffers, attributes["TANGENT"])
                assert len(tangents) == len(p), mesh["name"]
                for t, normal in zip(tangents, n):
                    assert abs(dot(t[:3], t[:3]) - 1) < 1e-5 and abs(dot(t[:3], normal)) < 1e-5, mesh["name"]
                    assert t[3] in (1.0, -1.0), mesh["name"]
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


def write_scenes(table, argv, default_out, describe):
    """The generators' command line: `OUT [NAME...]` writes each scene of `table` named (every one
    without names) into OUT/<name>/ with its render.toml, and prints describe(name, gltf)."""
    out = Path(argv[0] if argv else default_out)
    for name in argv[1:] or table:
        gltf, title, spp = table[name]()
        gltf.write(out / name)
        write_settings(out / name, title, spp)
        print(describe(name, gltf))
