#!/usr/bin/python3
"""Stages public glTF 2.0 assets made by others as trs-render scenes under scenes/real/.

Each asset is read from a git snapshot of its public repository (a bare git directory, read at
the commit recorded below), so the output depends only on those commits:

    /usr/bin/python3 tools/make_real_scenes.py --mirrors MIRRORS scenes/real [NAME ...]

`--mirrors DIR` holds one bare repository per source, named as in SOURCES (`owner+name/repo`,
or `owner+name/repo/.git`). Debian's python3 with python3-numpy and python3-openimageio. The
glTF accessor reader and the rotations come from the package tools/scenes_gen/.

What it does to each asset (scenes/real/README.md lists it per asset):
- .glb files become .gltf + .bin + image files; the asset's geometry is copied into
  `<name>.bin` (only the accessors the kept meshes use, bytes unchanged), the room's into
  `room.bin`.
- Emission textures are kept byte for byte at their native size. The other textures the
  renderer reads (base colour, metallic-roughness, and those of the material extensions in
  MATERIAL_EXTENSIONS: transmission, volume, IOR, specular, clearcoat, sheen) are downscaled to
  at most NON_EMISSIVE_MAX texels a side and stored as JPEG, or as PNG with their alpha where
  that alpha is read (a base colour whose alphaMode is MASK or BLEND, KHR_materials_specular's
  specularTexture, KHR_materials_sheen's sheenRoughnessTexture); their texCoord and
  KHR_texture_transform are kept. Normal, occlusion and clearcoat-normal textures are dropped
  (the corpus measures light sampling: it keeps what lights the scene and what the light
  passes through or reflects from, small), as are other material extensions, TANGENT
  attributes, animations and the asset's own cameras where a staging camera replaces them.
  alphaMode and the base colour's alpha are kept (trs-render reads MASK and BLEND as coverage),
  but where an asset bakes that alpha into its emission map. extensionsRequired is kept only for
  the extensions in REQUIRABLE. A gzipped .glb is read unzipped.
- A lone object is scaled to a set size, turned about the vertical, set on a grey plinth in a
  closed grey room (Lambertian, base colour 0.5), and seen by a new perspective camera. Whole
  scenes keep their own geometry and get a camera.
- KHR_materials_emissive_strength is set where the asset's emission alone would light the room
  too dimly for an 8-bit preview at exposure 0 (the value is recorded per asset).
"""

import argparse
import gzip
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

# The package lives beside this script; importing it must not leave a __pycache__ folder in the
# source tree.
sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))
from scenes_gen.gltf import (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, TRIANGLES,  # noqa: E402
                             UNSIGNED_INT, read_accessor)
from scenes_gen.vec import look_at, quaternion  # noqa: E402

NON_EMISSIVE_MAX = 1024
JPEG_QUALITY = 88

# Material extensions kept on every asset, with the textures each one names: True where the
# extension reads the texture's alpha channel (the image then keeps its alpha), False where it
# reads colour or data channels only, None for a texture dropped as normal maps are.
MATERIAL_EXTENSIONS = {
    "KHR_materials_emissive_strength": {},
    "KHR_materials_ior": {},
    "KHR_materials_transmission": {"transmissionTexture": False},
    "KHR_materials_volume": {"thicknessTexture": False},
    "KHR_materials_specular": {"specularTexture": True, "specularColorTexture": False},
    "KHR_materials_clearcoat": {"clearcoatTexture": False, "clearcoatRoughnessTexture": False,
                                "clearcoatNormalTexture": None},
    "KHR_materials_sheen": {"sheenColorTexture": False, "sheenRoughnessTexture": True},
}

# Extensions a staged file may still require, where its source did; other requirements are
# dropped (and the asset's changes say so).
REQUIRABLE = {"KHR_materials_emissive_strength", "KHR_texture_transform", "KHR_materials_ior",
              "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume",
              "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_lights_punctual"}

SOURCES = {
    "khronos-2023": {
        "mirror": "DRx3D+glTF-Sample-Assets-OLD",
        "repo": "DRx3D/glTF-Sample-Assets-OLD",
        "commit": "02d48689ce60c8799207f180ae324997e974c956",
        "note": "a copy of KhronosGroup/glTF-Sample-Assets as of May 2023",
    },
    "gkjohnson": {
        "mirror": "gkjohnson+3d-demo-data",
        "repo": "gkjohnson/3d-demo-data",
        "commit": "a79b5400ba8ed5bdeffebc10ce5adeecda7c3ebc",
        "note": "models collected from Sketchfab for three.js demos, each with its source and licence",
    },
    "pmndrs-postprocessing": {
        "mirror": "pmndrs+postprocessing",
        "repo": "pmndrs/postprocessing",
        "commit": "71a02f5120f9137fc6abe5c79d23b3d3dd17e68f",
        "note": "the postprocessing library's manual site (gh-pages branch), with the models its demos use",
    },
    "babylon": {
        "mirror": "BabylonJS+MeshesLibrary",
        "repo": "BabylonJS/MeshesLibrary",
        "commit": "1e0c5cdbdfec7b632b9aa1f498f7016b0d210779",
        "note": "Babylon.js meshes library; files not otherwise marked are CC BY 4.0 (its README)",
    },
    "playcanvas": {
        "mirror": "playcanvas+engine",
        "repo": "playcanvas/engine",
        "commit": "0aaef5e432c4797ed23c1f966e2cc43232ec0613",
        "note": "the PlayCanvas engine; its examples' models, each beside a .txt of its title, "
                "author, source and licence",
    },
    "needle-samples": {
        "mirror": "needle-tools+needle-engine-samples",
        "repo": "needle-tools/needle-engine-samples",
        "commit": "a623e96180099bc7a1c494ec17157843540c68b7",
        "note": "Needle Engine's sample scenes; MIT, (c) 2022-2023 Needle Tools GmbH (package/License.md, "
                "the repository's licence file), where an asset's folder names no other licence",
    },
}

# Per asset: where it comes from, who made it, its licence, and how it is staged.
#   kind: "object" (staged in a grey room) or "scene" (kept whole, a camera added)
#   size: the object's largest extent after scaling (m); yaw: degrees about +Y
#   strength: KHR_materials_emissive_strength applied to every emissive material (None: keep)
#   drop_nodes: node names whose meshes are left out
#   missing: per image absent from the snapshot, the factors that replace it (set on the object
#     that held the texture: pbrMetallicRoughness, or the material extension)
#   camera: eye and target, relative to the object's base centre (objects) or absolute (scenes)
ASSETS = {
    "damaged-helmet": {
        "source": "khronos-2023",
        "path": "Models/DamagedHelmet/glTF/DamagedHelmet.gltf",
        "title": "Battle Damaged Sci-fi Helmet - PBR (DamagedHelmet)",
        "author": "theblueturtle_ (Sketchfab); glTF conversion by the glTF sample-model contributors",
        "licence": "CC BY 4.0",
        "kind": "object",
        "size": 0.5,
        "yaw": 0.0,
        "strength": 600.0,
        "camera": {"eye": [0.55, 0.45, 1.15], "target": [0.0, 0.15, 0.0], "yfov": 55.0},
    },
    "lantern": {
        "source": "khronos-2023",
        "path": "Models/Lantern/glTF/Lantern.gltf",
        "title": "Lantern",
        "author": "Microsoft",
        "licence": "CC0 1.0",
        "kind": "object",
        "size": 1.9,
        "yaw": -30.0,
        "plinth": 0.0,
        "strength": 80.0,
        # Lantern_baseColor.png (over 4 MiB) is absent from the snapshot: a wood-brown factor.
        "missing": {"Lantern_baseColor.png": {"baseColorFactor": [0.22, 0.16, 0.11, 1.0]}},
        "camera": {"eye": [0.6, 1.1, 2.2], "target": [0.0, 1.05, 0.0], "yfov": 60.0},
    },
    "boombox": {
        "source": "khronos-2023",
        "path": "Models/BoomBox/glTF/BoomBox.gltf",
        "title": "BoomBox",
        "author": "Microsoft",
        "licence": "CC0 1.0",
        "kind": "object",
        "size": 0.6,
        "yaw": 0.0,
        "strength": 500.0,
        # BoomBox_occlusionRoughnessMetallic.png (over 4 MiB) is absent from the snapshot.
        "missing": {"BoomBox_occlusionRoughnessMetallic.png": {"metallicFactor": 0.0, "roughnessFactor": 0.5}},
        "camera": {"eye": [0.6, 0.5, 1.6], "target": [0.0, 0.15, 0.0], "yfov": 55.0},
    },
    "toy-car": {
        "source": "khronos-2023",
        "path": "Models/ToyCar/glTF/ToyCar.gltf",
        "title": "ToyCar",
        "author": "Guido Odendahl (car model); Eric Chadwick (materials, scene composition)",
        "licence": "CC0 1.0",
        "kind": "object",
        "size": 0.9,
        "yaw": 0.0,
        "strength": 4000.0,
        "camera": {"eye": [0.9, 0.7, 1.5], "target": [0.0, 0.1, 0.0], "yfov": 55.0},
    },
    "energy-ball": {
        "source": "babylon",
        "path": "TrailMeshSpell/pinkEnergyBall.glb",
        "title": "pinkEnergyBall (TrailMeshSpell demo)",
        "author": "Patrick Ryan (Babylon.js team)",
        "licence": "CC BY 4.0",
        "kind": "object",
        "size": 0.45,
        "yaw": 0.0,
        "lift": 0.15,
        "strength": 36.0,
        # The two alpha-blended outer shells (energylayer1, energylayer2) are left out: the core alone.
        "drop_nodes": ["energylayer1", "energylayer2"],
        "camera": {"eye": [0.7, 0.6, 1.7], "target": [0.0, 0.2, 0.0], "yfov": 55.0},
    },
    "spell-disk": {
        "source": "babylon",
        "path": "TrailMeshSpell/spellDisk.glb",
        "title": "spellDisk (TrailMeshSpell demo)",
        "author": "Patrick Ryan (Babylon.js team)",
        "licence": "CC BY 4.0",
        "kind": "object",
        "size": 1.6,
        "yaw": 0.0,
        "plinth": 0.0,
        "lift": 0.6,
        "strength": 16.0,
        # The runes are cut out by the base colour's alpha (BLEND); the disk is staged opaque,
        # its emission map multiplied by that alpha (and its base colour too, as read).
        "emission_times_base_alpha": True,
        "camera": {"eye": [1.2, 1.7, 1.7], "target": [0.0, 0.35, 0.0], "yfov": 60.0},
    },
    "space-exploration": {
        "source": "gkjohnson",
        "path": "models/lowpoly-space/space_exploration.glb",
        "title": "Space exploration [WLP series #8]",
        "author": "drei.lu (https://sketchfab.com/drei.lu)",
        "licence": "CC BY 4.0",
        "kind": "scene",
        "strength": 100000.0,
        "camera": {"eye_dir": [0.55, 0.6, 1.0], "distance": 1.35, "yfov": 50.0, "target_height": 0.5},
    },
    "terrarium-bots": {
        "source": "gkjohnson",
        "path": "models/terrarium-robots/scene.gltf",
        "title": "Terrarium Bots (@nerdscribbles)",
        "author": "nyancube (https://sketchfab.com/N01506)",
        "licence": "CC BY 4.0",
        "kind": "scene",
        "strength": 500.0,
        "missing": {
            "textures/BOT1_metallicRoughness.png": {"metallicFactor": 0.0, "roughnessFactor": 0.6},
            "textures/BOT2_metallicRoughness.png": {"metallicFactor": 0.0, "roughnessFactor": 0.6},
        },
        "camera": {"eye_dir": [0.35, 0.25, 1.0], "distance": 1.2, "yfov": 50.0, "target_height": 0.25},
    },
    "spaceship-corridor": {
        "source": "pmndrs-postprocessing",
        # The .glb beside it is the same file (same blob once unzipped) but over the snapshot's 4 MiB.
        "path": "manual/models/spaceship-corridor/spaceship-corridor.glb.gz",
        "title": "Spaceship Corridor",
        "author": "the_table (https://sketchfab.com/the_table)",
        "licence": "CC BY 4.0",
        "kind": "scene",
        "strength": 150.0,
        # Inside, looking down the corridor: its walls, floor and ceiling fill the frame.
        "camera": {"eye": [0.0, 1.55, -6.6], "target": [0.0, 1.35, 0.0], "yfov": 60.0},
    },
    "love-neon": {
        "source": "playcanvas",
        "path": "examples/assets/models/love.glb",
        "title": "Love neon sign 02",
        "author": "daysena (https://sketchfab.com/daysena)",
        "licence": "CC BY 4.0",
        "kind": "object",
        "size": 1.0,
        "yaw": -90.0,
        "strength": 200.0,
        "camera": {"eye": [0.45, 0.35, 1.5], "target": [0.0, 0.12, 0.0], "yfov": 55.0},
    },
    "glass-house": {
        "source": "needle-samples",
        "path": "package/Runtime/Lightmaps/Assets/Objects/House/house.glb",
        "title": "House (Needle Engine lightmaps sample)",
        "author": "Needle Tools GmbH",
        "licence": "MIT",
        "kind": "scene",
        "strength": 40.0,
        "camera": {"eye": [4.8, 1.7, -0.7], "target": [-1.0, 1.3, -0.2], "yfov": 60.0},
    },
}

ROOM = {"width": 4.0, "depth": 4.0, "height": 2.7, "object_z": -0.6, "plinth_size": 0.6,
        "plinth_height": 0.5, "albedo": 0.5}


# ---------------------------------------------------------------------------------------------
# reading the snapshots


def mirror_dir(mirrors, source):
    base = os.path.join(mirrors, SOURCES[source]["mirror"], "repo")
    return base if os.path.isfile(os.path.join(base, "HEAD")) else os.path.join(base, ".git")


def git_show(mirrors, source, path):
    """The bytes of `path` at the source's recorded commit, or None where the blob is absent."""
    src = SOURCES[source]
    r = subprocess.run(["git", "--git-dir", mirror_dir(mirrors, source), "show",
                        src["commit"] + ":" + path], capture_output=True)
    return r.stdout if r.returncode == 0 else None


def load_asset(mirrors, spec):
    """The glTF JSON, its buffers (bytes) and images [(name, bytes or None)]."""
    raw = git_show(mirrors, spec["source"], spec["path"])
    if raw is None:
        sys.exit(f"{spec['path']}: not in the snapshot")
    path = spec["path"]
    if path.endswith(".gz"):
        raw = gzip.decompress(raw)
        path = path[:-3]
    folder = os.path.dirname(path)
    if path.endswith(".glb"):
        magic, version, length = struct.unpack("<4sII", raw[:12])
        assert magic == b"glTF" and version == 2
        jlen, jtype = struct.unpack("<II", raw[12:20])
        gltf = json.loads(raw[20:20 + jlen])
        blen, btype = struct.unpack("<II", raw[20 + jlen:28 + jlen])
        buffers = [raw[28 + jlen:28 + jlen + blen]]
    else:
        gltf = json.loads(raw)
        buffers = []
        for b in gltf["buffers"]:
            data = git_show(mirrors, spec["source"], folder + "/" + b["uri"])
            if data is None:
                sys.exit(f"{b['uri']}: not in the snapshot")
            buffers.append(data[:b["byteLength"]])
    images = []
    for i, im in enumerate(gltf.get("images", [])):
        if "uri" in im:
            images.append((im["uri"], git_show(mirrors, spec["source"], folder + "/" + im["uri"])))
        else:
            bv = gltf["bufferViews"][im["bufferView"]]
            off = bv.get("byteOffset", 0)
            data = buffers[bv["buffer"]][off:off + bv["byteLength"]]
            ext = {"image/png": "png", "image/jpeg": "jpg"}[im["mimeType"]]
            tex_names = [t["name"] for t in gltf.get("textures", []) if t.get("source") == i and t.get("name")]
            name = im.get("name") or (tex_names[0] if tex_names else
                                           os.path.splitext(os.path.basename(path))[0] + f"_image{i}")
            name = os.path.splitext(name)[0] + "." + ext
            images.append((name, data))
    return gltf, buffers, images


# ---------------------------------------------------------------------------------------------
# matrices


def quat_to_mat(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=float).reshape(4, 4).T
    m = np.eye(4)
    s = node.get("scale", [1, 1, 1])
    r = node.get("rotation", [0, 0, 0, 1])
    t = node.get("translation", [0, 0, 0])
    m[:3, :3] = quat_to_mat(r) @ np.diag(s)
    m[:3, 3] = t
    return m


def mesh_instances(gltf):
    """(world matrix, mesh) for every mesh node instance of the default scene."""
    def visit(n, parent):
        node = gltf["nodes"][n]
        m = parent @ node_matrix(node)
        if "mesh" in node:
            yield m, gltf["meshes"][node["mesh"]]
        for c in node.get("children", []):
            yield from visit(c, m)

    for n in gltf["scenes"][gltf.get("scene", 0)]["nodes"]:
        yield from visit(n, np.eye(4))


def world_corners(gltf):
    """The corners of every kept primitive's POSITION bounds, in world space (N x 3)."""
    pts = []
    for m, mesh in mesh_instances(gltf):
        for p in mesh["primitives"]:
            a = gltf["accessors"][p["attributes"]["POSITION"]]
            lo, hi = a["min"], a["max"]
            for i in range(8):
                c = [hi[k] if (i >> k) & 1 else lo[k] for k in range(3)]
                pts.append((m @ np.array(c + [1.0]))[:3])
    return np.array(pts)


def rotation(q):
    """A node's rotation as the staged file writes it."""
    return [round(float(v), 9) for v in q]


# ---------------------------------------------------------------------------------------------
# images


def read_pixels(data, unassociated=False):
    """Decodes image bytes with OpenImageIO (through a temporary file: ImageBuf reads files).
    OpenImageIO multiplies colour by alpha as it reads; `unassociated` keeps the colour as stored."""
    with tempfile.NamedTemporaryFile(suffix=".img", delete=False) as f:
        f.write(data)
        name = f.name
    try:
        config = oiio.ImageSpec()
        if unassociated:
            config.attribute("oiio:UnassociatedAlpha", 1)
        buf = oiio.ImageBuf(name, 0, 0, config)
        px = buf.get_pixels(oiio.UINT8)
        if px is None or buf.has_error:
            raise RuntimeError(buf.geterror())
        return np.array(px).reshape(buf.spec().height, buf.spec().width, buf.spec().nchannels)
    finally:
        os.unlink(name)


def write_pixels(path, px, quality=None, unassociated=False):
    """Writes 8-bit pixels; `unassociated`: colour and alpha as given (else OpenImageIO divides
    colour by alpha as it writes a PNG with alpha)."""
    h, w, c = px.shape
    spec = oiio.ImageSpec(w, h, c, oiio.UINT8)
    if quality is not None:
        spec.attribute("Compression", f"jpeg:{quality}")
    if unassociated:
        spec.attribute("oiio:UnassociatedAlpha", 1)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(0, w, 0, h), np.ascontiguousarray(px))
    if not buf.write(path):
        raise RuntimeError(buf.geterror())


def downscaled(px, largest):
    h, w, _ = px.shape
    if max(h, w) <= largest:
        return px
    s = largest / max(h, w)
    nw, nh = max(1, round(w * s)), max(1, round(h * s))
    spec = oiio.ImageSpec(w, h, px.shape[2], oiio.UINT8)
    src = oiio.ImageBuf(spec)
    src.set_pixels(oiio.ROI(0, w, 0, h), np.ascontiguousarray(px))
    dst = oiio.ImageBufAlgo.resize(src, roi=oiio.ROI(0, nw, 0, nh, 0, 1, 0, px.shape[2]))
    return np.array(dst.get_pixels(oiio.UINT8)).reshape(nh, nw, px.shape[2])


# ---------------------------------------------------------------------------------------------
# staging


def texture_slots(m):
    """The texture references a material keeps besides its emission map: (owner, key, alpha),
    where owner[key] is the textureInfo, owner holds the factors that scale it, and alpha says
    whether the image's alpha channel is read (a base colour's is, under MASK or BLEND)."""
    pbr = m.get("pbrMetallicRoughness", {})
    slots = [(pbr, "baseColorTexture", m.get("alphaMode", "OPAQUE") != "OPAQUE"),
             (pbr, "metallicRoughnessTexture", False)]
    for name, textures in MATERIAL_EXTENSIONS.items():
        ext = m.get("extensions", {}).get(name)
        if ext is not None:
            slots += [(ext, key, alpha) for key, alpha in textures.items() if alpha is not None]
    return [(owner, key, alpha) for owner, key, alpha in slots if key in owner]


def texture_infos(m):
    """Every textureInfo a material keeps, its emission map's included."""
    infos = [owner[key] for owner, key, _ in texture_slots(m)]
    if "emissiveTexture" in m:
        infos.append(m["emissiveTexture"])
    return infos


def uv_set(info):
    """The TEXCOORD set a textureInfo reads (KHR_texture_transform's texCoord overrides)."""
    transform = info.get("extensions", {}).get("KHR_texture_transform", {})
    return transform.get("texCoord", info.get("texCoord", 0))


def prune(gltf, spec):
    """Leaves out dropped meshes, cameras, animations and what the renderer ignores."""
    node_names = set(spec.get("drop_nodes", []))
    for node in gltf["nodes"]:
        if "mesh" in node and node.get("name") in node_names:
            del node["mesh"]
        if "camera" in node and spec["kind"] == "object":
            del node["camera"]
    # Still geometry only: animations go, and skinned meshes keep their bind pose.
    gltf.pop("animations", None)
    gltf.pop("skins", None)
    for node in gltf["nodes"]:
        node.pop("skin", None)
    if spec["kind"] == "object":
        gltf.pop("cameras", None)
    # Meshes still in use, renumbered.
    used = sorted({n["mesh"] for n in gltf["nodes"] if "mesh" in n})
    remap = {old: new for new, old in enumerate(used)}
    gltf["meshes"] = [gltf["meshes"][i] for i in used]
    for n in gltf["nodes"]:
        if "mesh" in n:
            n["mesh"] = remap[n["mesh"]]
    # Materials still in use, renumbered.
    used_m = sorted({p["material"] for m in gltf["meshes"] for p in m["primitives"] if "material" in p})
    mremap = {old: new for new, old in enumerate(used_m)}
    gltf["materials"] = [gltf["materials"][i] for i in used_m]
    for mesh in gltf["meshes"]:
        for p in mesh["primitives"]:
            if "material" in p:
                p["material"] = mremap[p["material"]]
    for mesh in gltf["meshes"]:
        for p in mesh["primitives"]:
            assert p.get("mode", 4) == 4
            p.pop("targets", None)
            keep = {"POSITION", "NORMAL", "TEXCOORD_0"}
            if "material" in p:  # and TEXCOORD_1 where a kept texture reads it
                infos = texture_infos(gltf["materials"][p["material"]])
                keep |= {f"TEXCOORD_{uv_set(info)}" for info in infos}
            p["attributes"] = {k: v for k, v in p["attributes"].items() if k in keep}


def compact_geometry(gltf, buffers):
    """Copies the bufferViews the kept accessors use into one new buffer; renumbers."""
    used_acc = []
    for mesh in gltf["meshes"]:
        for p in mesh["primitives"]:
            used_acc += list(p["attributes"].values())
            if "indices" in p:
                used_acc.append(p["indices"])
    used_acc = sorted(set(used_acc))
    acc_map = {old: new for new, old in enumerate(used_acc)}
    out = bytearray()
    views, view_map = [], {}
    accessors = []
    for old in used_acc:
        a = dict(gltf["accessors"][old])
        assert "sparse" not in a and "bufferView" in a
        bv_old = a["bufferView"]
        if bv_old not in view_map:
            bv = gltf["bufferViews"][bv_old]
            off = bv.get("byteOffset", 0)
            while len(out) % 4:
                out.append(0)
            new_bv = {"buffer": 0, "byteOffset": len(out), "byteLength": bv["byteLength"]}
            for k in ("byteStride", "target"):
                if k in bv:
                    new_bv[k] = bv[k]
            out += buffers[bv["buffer"]][off:off + bv["byteLength"]]
            view_map[bv_old] = len(views)
            views.append(new_bv)
        a["bufferView"] = view_map[bv_old]
        accessors.append(a)
    for mesh in gltf["meshes"]:
        for p in mesh["primitives"]:
            p["attributes"] = {k: acc_map[v] for k, v in p["attributes"].items()}
            if "indices" in p:
                p["indices"] = acc_map[p["indices"]]
    gltf["accessors"] = accessors
    gltf["bufferViews"] = views
    return bytes(out)


def stage_materials(gltf, images, spec, out_dir):
    """Materials as trs-render reads them; writes the images they use; returns a report."""
    missing = spec.get("missing", {})
    uri_of_texture = {}
    for t, tex in enumerate(gltf.get("textures", [])):
        uri_of_texture[t] = images[tex["source"]][0]
    for m in gltf.get("materials", []):
        m.pop("normalTexture", None)
        m.pop("occlusionTexture", None)
        ext = m.get("extensions", {})
        m["extensions"] = {k: v for k, v in ext.items() if k in MATERIAL_EXTENSIONS}
        for name, textures in MATERIAL_EXTENSIONS.items():
            for key, alpha in textures.items():
                if alpha is None:
                    m["extensions"].get(name, {}).pop(key, None)
        pbr = m.setdefault("pbrMetallicRoughness", {})
        if spec.get("emission_times_base_alpha") and "emissiveTexture" in m:
            # The base colour's alpha is baked into the emission map; the surface is opaque.
            m["_bake_alpha_from"] = pbr["baseColorTexture"]["index"]
            if m.get("alphaMode") == "BLEND":
                m["alphaMode"] = "OPAQUE"
        # A texture absent from the snapshot: its factors replace it (spec["missing"]).
        for owner, slot, _ in texture_slots(m):
            uri = uri_of_texture[owner[slot]["index"]]
            if images[gltf["textures"][owner[slot]["index"]]["source"]][1] is None:
                if uri not in missing:
                    sys.exit(f"{uri}: absent from the snapshot and no replacement given")
                del owner[slot]
                owner.update(missing[uri])
        for owner, slot, _ in texture_slots(m):
            assert uv_set(owner[slot]) in (0, 1), f"{slot} reads TEXCOORD_{uv_set(owner[slot])}"
        emits = "emissiveTexture" in m or any(v > 0 for v in m.get("emissiveFactor", [0, 0, 0]))
        if "emissiveTexture" in m:
            assert uv_set(m["emissiveTexture"]) == 0
        if emits and spec.get("strength") is not None:
            m["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": spec["strength"]}
        if not m["extensions"]:
            del m["extensions"]
    # Images written once per (image, use): emission native, the rest downscaled; textures
    # renumbered per (texture, use), so one glTF texture serving both gets two.
    img_written, new_images, report = {}, [], []
    new_textures, tex_written, new_samplers, sampler_map = [], {}, [], {}

    def texture_for(old, emissive, bake, alpha=False, stored=False):
        """`alpha`: the image keeps its alpha; `stored`: its colour is read as stored, not
        multiplied by its alpha as OpenImageIO reads it (data textures; a base colour whose alpha
        is not read is kept multiplied, as the spell disk's cut-outs are)."""
        tex = gltf["textures"][old]
        name, data = images[tex["source"]]
        px = read_pixels(data, unassociated=alpha or stored)
        h, w, c = px.shape
        alpha = alpha and c in (2, 4)  # an image without alpha reads as opaque: nothing to keep
        premultiplied = c in (2, 4) and not (alpha or stored)
        base = os.path.basename(name)
        as_is = bake is None and (emissive or max(w, h) <= NON_EMISSIVE_MAX)
        key = (tex["source"], "as-is" if as_is else "baked" if emissive else "alpha" if alpha
               else "premultiplied" if premultiplied else "small")
        if key not in img_written:
            if as_is:
                out_name = base
                with open(os.path.join(out_dir, out_name), "wb") as f:
                    f.write(data)
                report.append(f"{out_name}: {w} x {h}, kept as it is" + (" (emission)" if emissive else ""))
            elif emissive:
                alpha_px = read_pixels(images[gltf["textures"][bake]["source"]][1])
                assert alpha_px.shape[:2] == px.shape[:2] and alpha_px.shape[2] == 4
                a = alpha_px[..., 3:4].astype(np.float64) / 255.0
                baked = np.round(px[..., :3].astype(np.float64) * a).astype(np.uint8)
                out_name = os.path.splitext(base)[0] + "_alpha.png"
                write_pixels(os.path.join(out_dir, out_name), baked)
                report.append(f"{out_name}: {w} x {h}, emission multiplied by the base colour's alpha")
            else:
                colour = px if alpha else px[..., :3] if c >= 3 else px[..., :1]
                small = downscaled(colour, NON_EMISSIVE_MAX)
                stem, ext = os.path.splitext(base)[0], ".png" if alpha else ".jpg"
                out_name = stem + ext
                if out_name in {im["uri"] for im in new_images}:  # the same image at another use
                    out_name = f"{stem}_{NON_EMISSIVE_MAX}{ext}"
                if alpha:
                    write_pixels(os.path.join(out_dir, out_name), small, unassociated=True)
                else:
                    write_pixels(os.path.join(out_dir, out_name), small, JPEG_QUALITY)
                report.append(f"{out_name}: {w} x {h} -> {small.shape[1]} x {small.shape[0]} "
                              + ("PNG (alpha kept)" if alpha else "JPEG"))
            assert out_name not in {im["uri"] for im in new_images}, out_name
            img_written[key] = len(new_images)
            new_images.append({"uri": out_name})
        tkey = (old, emissive, bake, key[1])
        if tkey not in tex_written:
            t = {"source": img_written[key]}
            if "sampler" in tex:
                if tex["sampler"] not in sampler_map:
                    sampler_map[tex["sampler"]] = len(new_samplers)
                    new_samplers.append(gltf["samplers"][tex["sampler"]])
                t["sampler"] = sampler_map[tex["sampler"]]
            tex_written[tkey] = len(new_textures)
            new_textures.append(t)
        return tex_written[tkey]

    for m in gltf.get("materials", []):
        bake = m.pop("_bake_alpha_from", None)
        for owner, slot, alpha in texture_slots(m):
            owner[slot]["index"] = texture_for(owner[slot]["index"], False, None, alpha,
                                               stored=slot != "baseColorTexture")
        if "emissiveTexture" in m:
            m["emissiveTexture"]["index"] = texture_for(m["emissiveTexture"]["index"], True, bake)
    gltf["textures"] = new_textures
    gltf["images"] = new_images
    gltf["samplers"] = new_samplers
    if not new_samplers:
        gltf.pop("samplers")
    for k in ("textures", "images"):
        if not gltf[k]:
            gltf.pop(k)
    return report


def box_quads(lo, hi, inward):
    """Six faces of an axis-aligned box as quads (4 corners each, counter-clockwise as seen from
    the side the normal points to) with their normals."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [  # (corners seen from outside, outward normal)
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1)),
        ([(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)], (1, 0, 0)),
        ([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0)),
        ([(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)], (0, 1, 0)),
        ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0)),
    ]
    out = []
    for corners, n in faces:
        if inward:
            out.append((corners[::-1], tuple(-v for v in n)))
        else:
            out.append((corners, n))
    return out


def room_geometry(plinth_height):
    """The grey room, closed on all six sides (scenes_gen.mesh.room() leaves one open), and the
    plinth but its bottom: positions, normals and indices, each quad split from its first corner."""
    r = ROOM
    w, d, h = r["width"] / 2, r["depth"] / 2, r["height"]
    quads = box_quads((-w, 0.0, -d), (w, h, d), inward=True)
    if plinth_height > 0:
        p = r["plinth_size"] / 2
        z = r["object_z"]
        quads += [q for q in box_quads((-p, 0.0, z - p), (p, plinth_height, z + p), inward=False)
                  if q[1] != (0, -1, 0)]
    pos, nrm, idx = [], [], []
    for corners, n in quads:
        base = len(pos)
        pos += corners
        nrm += [n] * 4
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return np.array(pos, np.float32), np.array(nrm, np.float32), np.array(idx, np.uint32)


def add_room(gltf, plinth_height):
    """Appends the room as buffer 1 (room.bin), its material and node; returns its triangles."""
    pos, nrm, idx = room_geometry(plinth_height)
    uv = np.zeros((len(pos), 2), np.float32)
    blob = bytearray()
    views = []
    for arr, target in ((idx, ELEMENT_ARRAY_BUFFER), (pos, ARRAY_BUFFER), (nrm, ARRAY_BUFFER),
                        (uv, ARRAY_BUFFER)):
        views.append({"buffer": 1, "byteOffset": len(blob), "byteLength": arr.nbytes, "target": target})
        blob += arr.tobytes()
    bv0 = len(gltf["bufferViews"])
    gltf["bufferViews"] += views
    a0 = len(gltf["accessors"])
    gltf["accessors"] += [
        {"bufferView": bv0, "componentType": UNSIGNED_INT, "count": int(idx.size), "type": "SCALAR"},
        {"bufferView": bv0 + 1, "componentType": FLOAT, "count": len(pos), "type": "VEC3",
         "min": [float(v) for v in pos.min(0)], "max": [float(v) for v in pos.max(0)]},
        {"bufferView": bv0 + 2, "componentType": FLOAT, "count": len(pos), "type": "VEC3"},
        {"bufferView": bv0 + 3, "componentType": FLOAT, "count": len(pos), "type": "VEC2"},
    ]
    gltf.setdefault("materials", []).append({
        "name": "room_grey_diffuse",
        "pbrMetallicRoughness": {"baseColorFactor": [ROOM["albedo"]] * 3 + [1.0],
                                 "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    gltf["meshes"].append({"name": "room", "primitives": [{
        "attributes": {"POSITION": a0 + 1, "NORMAL": a0 + 2, "TEXCOORD_0": a0 + 3},
        "indices": a0, "material": len(gltf["materials"]) - 1, "mode": TRIANGLES}]})
    gltf["nodes"].append({"name": "room", "mesh": len(gltf["meshes"]) - 1})
    return bytes(blob), len(gltf["nodes"]) - 1, int(idx.size // 3)


def add_camera(gltf, eye, target, yfov_deg):
    gltf["cameras"] = [{"name": "staging", "type": "perspective", "perspective": {
        "yfov": round(math.radians(yfov_deg), 6), "aspectRatio": 16 / 9, "znear": 0.01, "zfar": 100.0}}]
    gltf["nodes"].append({"name": "staging_camera", "camera": 0,
                          "translation": [round(float(v), 6) for v in eye],
                          "rotation": rotation(look_at(eye, target))})
    return len(gltf["nodes"]) - 1


def count_triangles(gltf):
    """Triangles over the mesh instances of the default scene: (total, with an emission map,
    with a constant emission, transmissive)."""
    total = emit = constant = clear = 0
    for _, mesh in mesh_instances(gltf):
        for p in mesh["primitives"]:
            k = gltf["accessors"][p["indices"]]["count"] // 3 if "indices" in p else \
                gltf["accessors"][p["attributes"]["POSITION"]]["count"] // 3
            total += k
            m = gltf["materials"][p["material"]] if "material" in p else {}
            if any(v > 0 for v in m.get("emissiveFactor", [0, 0, 0])):
                if "emissiveTexture" in m:
                    emit += k
                else:
                    constant += k
            if "KHR_materials_transmission" in m.get("extensions", {}):
                clear += k
    return total, emit, constant, clear


def count_emitting(out_dir, name):
    """Triangles whose UV bounding box covers at least one non-black texel of their emission
    map (a conservative count, over the default scene's mesh instances)."""
    with open(os.path.join(out_dir, name + ".gltf")) as f:
        gltf = json.load(f)
    bins = []
    for b in gltf["buffers"]:
        with open(os.path.join(out_dir, b["uri"]), "rb") as f:
            bins.append(f.read())
    tables = {}
    lit = 0

    def table(img):
        if img not in tables:
            with open(os.path.join(out_dir, gltf["images"][img]["uri"]), "rb") as f:
                px = read_pixels(f.read())[..., :3]
            mask = (px.max(axis=2) > 0).astype(np.int64)
            tiled = np.tile(mask, (2, 2))
            sat = np.zeros((tiled.shape[0] + 1, tiled.shape[1] + 1), np.int64)
            sat[1:, 1:] = tiled.cumsum(0).cumsum(1)
            tables[img] = (sat, mask.shape[1], mask.shape[0])
        return tables[img]

    for _, mesh in mesh_instances(gltf):
        for p in mesh["primitives"]:
            m = gltf["materials"][p["material"]]
            if "emissiveTexture" not in m or not any(v > 0 for v in m.get("emissiveFactor", [0, 0, 0])):
                continue
            sat, w, h = table(gltf["textures"][m["emissiveTexture"]["index"]]["source"])
            uv = np.array(read_accessor(gltf, bins, p["attributes"]["TEXCOORD_0"]), np.float64)
            tri = np.array(read_accessor(gltf, bins, p["indices"])).reshape(-1, 3)
            t = uv[tri]  # triangles x 3 x 2
            lo = np.floor(t.min(1) * [w, h]).astype(np.int64)
            hi = np.floor(t.max(1) * [w, h]).astype(np.int64)
            shift = np.floor_divide(lo, [w, h]) * [w, h]
            lo -= shift
            hi -= shift
            full = (hi[:, 0] - lo[:, 0] >= w) | (hi[:, 1] - lo[:, 1] >= h)
            hi = np.minimum(hi, lo + [w - 1, h - 1])
            x0, y0, x1, y1 = lo[:, 0], lo[:, 1], hi[:, 0] + 1, hi[:, 1] + 1
            count = sat[y1, x1] - sat[y0, x1] - sat[y1, x0] + sat[y0, x0]
            lit += int(np.count_nonzero((count > 0) | (full & (sat[-1, -1] > 0))))
    return lit


def stage(name, spec, mirrors, out_root):
    out_dir = os.path.join(out_root, name)
    os.makedirs(out_dir, exist_ok=True)
    for f in os.listdir(out_dir):
        if f != "render.toml":
            os.unlink(os.path.join(out_dir, f))
    gltf, buffers, images = load_asset(mirrors, spec)
    src = SOURCES[spec["source"]]
    prune(gltf, spec)
    geometry = compact_geometry(gltf, buffers)
    report = stage_materials(gltf, images, spec, out_dir)
    required = gltf.pop("extensionsRequired", [])
    scene = gltf["scenes"][gltf.get("scene", 0)]
    gltf["scene"] = gltf.get("scene", 0)
    corners = world_corners(gltf)
    room_blob = None
    cam = spec["camera"]
    if spec["kind"] == "object":
        yaw = math.radians(spec.get("yaw", 0.0))
        rot = np.array([[math.cos(yaw), 0, math.sin(yaw)], [0, 1, 0], [-math.sin(yaw), 0, math.cos(yaw)]])
        extent = corners.max(0) - corners.min(0)
        scale = spec["size"] / float(extent.max())
        p = (rot @ corners.T).T * scale
        plinth = spec.get("plinth", ROOM["plinth_height"])
        base = np.array([0.0, plinth + spec.get("lift", 0.0), ROOM["object_z"]])
        offset = base - np.array([(p[:, 0].min() + p[:, 0].max()) / 2, p[:, 1].min(),
                                  (p[:, 2].min() + p[:, 2].max()) / 2])
        root = {"name": name + "_staging", "children": list(scene["nodes"]),
                "translation": [round(float(v), 6) for v in offset],
                "rotation": rotation(quaternion(*rot.T)), "scale": [round(scale, 9)] * 3}
        gltf["nodes"].append(root)
        scene["nodes"] = [len(gltf["nodes"]) - 1]
        for m in gltf.get("materials", []):  # a volume's attenuation distance is in world units
            volume = m.get("extensions", {}).get("KHR_materials_volume", {})
            if "attenuationDistance" in volume:
                volume["attenuationDistance"] = round(volume["attenuationDistance"] * scale, 9)
        room_blob, room_node, room_tris = add_room(gltf, plinth)
        scene["nodes"].append(room_node)
        anchor = base
        eye = anchor + np.array(cam["eye"])
        target = anchor + np.array(cam["target"])
        scene["nodes"].append(add_camera(gltf, eye, target, cam["yfov"]))
        placed = f"scaled by {scale:.6g} to {spec['size']} m, turned {spec.get('yaw', 0.0)} degrees"
    elif "eye" in cam:  # a camera inside the scene, placed in its own coordinates
        scene["nodes"].append(add_camera(gltf, cam["eye"], cam["target"], cam["yfov"]))
        placed = "kept at its own scale"
    else:  # a camera outside, looking at the scene's bounds
        centre = (corners.max(0) + corners.min(0)) / 2
        lo, hi = corners.min(0), corners.max(0)
        centre[1] = lo[1] + cam.get("target_height", 0.5) * (hi[1] - lo[1])
        radius = float(np.linalg.norm(corners.max(0) - corners.min(0))) / 2
        d = np.array(cam["eye_dir"], float)
        eye = centre + d / np.linalg.norm(d) * cam["distance"] * radius
        scene["nodes"].append(add_camera(gltf, eye, centre, cam["yfov"]))
        placed = "kept at its own scale"
    gltf["buffers"] = [{"uri": name + ".bin", "byteLength": len(geometry)}]
    if room_blob is not None:
        gltf["buffers"].append({"uri": "room.bin", "byteLength": len(room_blob)})
        with open(os.path.join(out_dir, "room.bin"), "wb") as f:
            f.write(room_blob)
    with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
        f.write(geometry)
    used = set()
    for m in gltf.get("materials", []):
        used |= set(m.get("extensions", {}))
        for info in texture_infos(m):
            used |= set(info.get("extensions", {}))
    if used:
        gltf["extensionsUsed"] = sorted(used)
    else:
        gltf.pop("extensionsUsed", None)
    required = sorted(set(required) & used & REQUIRABLE)
    if required:
        gltf["extensionsRequired"] = required
    gltf["asset"] = {
        "version": "2.0",
        "generator": "tools/make_real_scenes.py",
        "copyright": f"{spec['title']} by {spec['author']}, {spec['licence']}",
        "extras": {"title": spec["title"], "author": spec["author"], "license": spec["licence"],
                   "source": f"https://github.com/{src['repo']}/blob/{src['commit']}/{spec['path']}",
                   "changes": "staged for trs-render by tools/make_real_scenes.py; see scenes/real/README.md"},
    }
    total, emit, constant, clear = count_triangles(gltf)
    order = ["asset", "extensionsUsed", "extensionsRequired", "scene", "scenes", "nodes", "cameras",
             "meshes", "materials", "textures", "images", "samplers", "accessors", "bufferViews", "buffers"]
    doc = {k: gltf[k] for k in order if k in gltf}
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    with open(os.path.join(out_dir, "render.toml"), "w") as f:
        f.write(f"# {spec['title']}: settings for trs-render (command-line flags override these)\n"
                "width = 320\nheight = 180\nspp = 16\nmax-depth = 3\nlights = \"auto\"\n")
    size = sum(os.path.getsize(os.path.join(out_dir, f)) for f in os.listdir(out_dir))
    lit = count_emitting(out_dir, name)
    extra = (f", {constant} with a constant emission" if constant else "") + \
        (f", {clear} transmissive" if clear else "")
    print(f"{name}: {total} triangles, {emit} with an emission map, {lit} over non-black texels{extra}; "
          f"{placed}; {size / 1e6:.2f} MB")
    for line in report:
        print("   ", line)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", help="output folder (scenes/real)")
    ap.add_argument("names", nargs="*", help="assets to stage (all by default)")
    ap.add_argument("--mirrors", required=True,
                    help="folder of the bare git snapshots of the source repositories (owner+name/repo)")
    args = ap.parse_args()
    names = args.names or list(ASSETS)
    for n in names:
        if n not in ASSETS:
            sys.exit(f"unknown asset {n}; known: {', '.join(ASSETS)}")
        stage(n, ASSETS[n], args.mirrors, args.out)


if __name__ == "__main__":
    main()
