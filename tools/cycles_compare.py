#!/usr/bin/env python3
"""A glTF scene rendered by trs-render and by Blender's Cycles, as a user who opens the file in
Blender sees it: the mean over the lit pixels of the two, per channel, and their ratio.

Blender (Debian's `blender`, 3.4) imports the file with its glTF importer in its default
"Standard" lighting mode, the units trs-render converts punctual lights to (docs/renderer.md,
"Punctual lights"); Cycles then renders it on the CPU with the file's camera, the same image
size, the same path depth (Cycles' bounces are trs-render's --max-depth less one), no world
light, no clamping, no light threshold, punctual lights as points (radius and sun angle 0) and
Blender's "Standard" view, written as linear EXR. `--diffuse` makes every material Lambertian
in both: trs-render's --diffuse-materials, and in Cycles each imported Principled BSDF replaced
by a Diffuse BSDF of its base colour beside its emission, under the importer's coverage and
normal map: the node that drives the Principled BSDF's Alpha mixes the two with a Transparent
BSDF (as the Principled BSDF itself does in Cycles), and its Normal Map node feeds the Diffuse
BSDF's Normal. What is compared is then the lighting, not the two renderers' BSDFs (Cycles'
Principled diffuse brightens at grazing angles, and trs-render's darkens under its dielectric
specular layer). The lit pixels are those where no camera sample of trs-render's render sees an
emitter (its --emitter-mask is 0): where one does, both show the emitter itself.

Coverage (glTF's alphaMode) reaches Cycles through the shader alone: Cycles blends by the
Alpha input and ignores the material's blend mode, which only Eevee reads. BLEND is therefore
rendered as the file means it. For MASK, Blender 3.4's importer leaves the cut to that blend
mode ("Alpha Clip" at alphaCutoff), so Cycles would blend a masked texture's fractional alpha:
the script cuts it in the shader instead, Alpha = 1 - (alpha < cutoff), glTF's rule, in front
of whatever the importer wired into the Alpha input. Transparent hits count as Cycles'
transparent bounces (up to 64), apart from the path depth. Normal maps reach Cycles through
the importer's Normal Map node, with MikkTSpace tangents of the map's UV set (the file's TANGENT
is not read). Cycles bends a shading normal whose mirror direction of the view would fall below
the surface back towards the viewer, so steep normal maps seen at grazing angles (the far
flanks of scenes/materials/normal-wall's cobbles) differ from a renderer that shades them as
mapped.

  tools/cycles_compare.py SCENE.gltf --render build/bin/trs-render --out DIR [--diffuse]
      [--width 320 --height 180 --spp 256 --cycles-spp 256 --max-depth 3] [--csv FILE]

Writes DIR/trs.exr, DIR/cycles.exr and DIR/trs-mask.exr; prints a Markdown table and the
ratio of the two means (luminance); exits 0 whatever the ratio (--tolerance makes it a check:
status 1 beyond it). Needs Debian's python3 with python3-numpy and python3-openimageio.
"""
import argparse
import csv
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

REC709_Y = np.array([0.2126, 0.7152, 0.0722])

# Runs inside Blender: imports the glTF and renders it with Cycles as the module docstring says.
BLENDER_SCRIPT = r"""
import sys
import numpy
numpy.bool = bool  # Blender 3.4's glTF importer calls numpy.bool, gone from Debian's numpy
import bpy

scene_file, out, width, height, spp, bounces, diffuse = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=scene_file, convert_lighting_mode="SPEC")
scene = bpy.context.scene


def input_into(source, target, tree):
    # `target` takes what drives `source`: its link, else its value.
    if source.is_linked:
        tree.links.new(source.links[0].from_socket, target)
    else:
        target.default_value = source.default_value


def nodes_of(material):
    # The importer's Principled BSDF and Material Output, or None where it made other nodes.
    if not material.use_nodes:
        return None, None
    tree = material.node_tree
    principled = next((n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"), None)
    return (principled, output) if principled and output else (None, None)


def cut_mask(material):
    # glTF's MASK in the shader: the importer's alpha, cut at the material's alphaCutoff (its
    # Eevee alpha_threshold) as glTF cuts it, opaque where alpha >= cutoff.
    principled, _ = nodes_of(material)
    if principled is None or getattr(material, "blend_method", None) != "CLIP":
        return
    tree = material.node_tree
    below = tree.nodes.new("ShaderNodeMath")
    below.operation = "LESS_THAN"
    input_into(principled.inputs["Alpha"], below.inputs[0], tree)
    below.inputs[1].default_value = material.alpha_threshold
    kept = tree.nodes.new("ShaderNodeMath")
    kept.operation = "SUBTRACT"
    kept.inputs[0].default_value = 1.0
    tree.links.new(below.outputs[0], kept.inputs[1])
    tree.links.new(kept.outputs[0], principled.inputs["Alpha"])


def diffuse_surface(material):
    # The importer's Principled BSDF replaced by a Lambertian Diffuse BSDF of its base colour and
    # normal, plus its emission, the two covered by its alpha as the Principled BSDF covers them.
    principled, output = nodes_of(material)
    if principled is None:
        return
    tree = material.node_tree
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    input_into(principled.inputs["Base Color"], diffuse.inputs["Color"], tree)
    if principled.inputs["Normal"].is_linked:  # the Normal Map node; unlinked: the shading normal
        input_into(principled.inputs["Normal"], diffuse.inputs["Normal"], tree)
    emission = tree.nodes.new("ShaderNodeEmission")
    input_into(principled.inputs["Emission"], emission.inputs["Color"], tree)
    input_into(principled.inputs["Emission Strength"], emission.inputs["Strength"], tree)
    both = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(diffuse.outputs["BSDF"], both.inputs[0])
    tree.links.new(emission.outputs["Emission"], both.inputs[1])
    surface = both.outputs["Shader"]
    alpha = principled.inputs["Alpha"]
    if alpha.is_linked or alpha.default_value < 1.0:
        covered = tree.nodes.new("ShaderNodeMixShader")
        input_into(alpha, covered.inputs["Fac"], tree)
        transparent = tree.nodes.new("ShaderNodeBsdfTransparent")
        tree.links.new(transparent.outputs["BSDF"], covered.inputs[1])
        tree.links.new(surface, covered.inputs[2])
        surface = covered.outputs["Shader"]
    tree.links.new(surface, output.inputs["Surface"])


for material in bpy.data.materials:
    cut_mask(material)
    if diffuse == "1":
        diffuse_surface(material)
cameras = [o for o in scene.objects if o.type == "CAMERA"]
if not cameras:
    sys.exit("cycles_compare: the file has no camera")
scene.camera = cameras[0]
for light in bpy.data.lights:
    light.shadow_soft_size = 0.0
    if light.type == "SUN":
        light.angle = 0.0
world = bpy.data.worlds.new("black")
world.color = (0.0, 0.0, 0.0)
scene.world = world
render = scene.render
render.engine = "CYCLES"
render.resolution_x, render.resolution_y, render.resolution_percentage = int(width), int(height), 100
render.filter_size = 0.01  # a box of one pixel, as trs-render's jittered camera samples
render.image_settings.file_format = "OPEN_EXR"
render.image_settings.color_depth = "32"
render.image_settings.color_mode = "RGB"
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
cycles = scene.cycles
cycles.device = "CPU"
cycles.samples = int(spp)
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.max_bounces = int(bounces)
for prop in ("diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces"):
    setattr(cycles, prop, int(bounces))
cycles.transparent_max_bounces = 64
cycles.sample_clamp_direct = 0.0
cycles.sample_clamp_indirect = 0.0
cycles.light_sampling_threshold = 0.0
cycles.blur_glossy = 0.0
render.filepath = out
bpy.ops.render.render(write_still=True)
"""


def read_rgb(path):
    image = oiio.ImageBuf(str(path))
    pixels = image.get_pixels(oiio.FLOAT)
    if pixels is None or pixels.size == 0:
        sys.exit(f"cycles_compare: cannot read {path}: {image.geterror()}")
    return np.asarray(pixels)[..., :3].astype(np.float64)


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"cycles_compare: {shlex.join(map(str, command))} failed:\n{result.stdout[-2000:]}{result.stderr}")


COMPARISON_OPTIONS = ("render", "blender", "diffuse", "width", "height", "spp", "cycles_spp", "max_depth")


def add_comparison_options(parser):
    """The programs and the settings of a comparison, COMPARISON_OPTIONS (--out apart)."""
    parser.add_argument("--render", default="build/bin/trs-render", help="trs-render")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--diffuse", action="store_true", help="Lambertian materials in both renderers")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--spp", type=int, default=256, help="trs-render's samples per pixel")
    parser.add_argument("--cycles-spp", type=int, default=256)
    parser.add_argument("--max-depth", type=int, default=3)


def comparison_arguments(args):
    """COMPARISON_OPTIONS of parsed `args` as this script's command line takes them."""
    words = []
    for name in COMPARISON_OPTIONS:
        value, flag = getattr(args, name), "--" + name.replace("_", "-")
        words += ([flag] if value else []) if isinstance(value, bool) else [flag, str(value)]
    return words


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", type=Path)
    parser.add_argument("--out", type=Path, required=True, help="folder for the images")
    add_comparison_options(parser)
    parser.add_argument("--csv", type=Path, help="append a row per scene")
    parser.add_argument("--tolerance", type=float, help="exit 1 where the ratio is further than this from 1")
    args = parser.parse_args()

    args.out.mkdir(parents=True, exist_ok=True)
    trs, mask, cycles = args.out / "trs.exr", args.out / "trs-mask.exr", args.out / "cycles.exr"
    run([args.render, args.scene, "--out", trs, "--emitter-mask", mask, "--spp", str(args.spp), "--width",
         str(args.width), "--height", str(args.height), "--max-depth", str(args.max_depth), "--quiet",
         *(["--diffuse-materials"] if args.diffuse else [])])
    with tempfile.NamedTemporaryFile("w", suffix=".py") as script:
        script.write(BLENDER_SCRIPT)
        script.flush()
        run([args.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script.name, "--", str(args.scene.resolve()),
             str(cycles.resolve()), str(args.width), str(args.height), str(args.cycles_spp), str(args.max_depth - 1),
             "1" if args.diffuse else "0"])

    ours, theirs, seen = read_rgb(trs), read_rgb(cycles), read_rgb(mask)[..., 0]
    lit = seen == 0.0
    if not lit.any():
        sys.exit("cycles_compare: no lit pixel: every pixel sees an emitter")
    ours_mean, theirs_mean = ours[lit].mean(axis=0), theirs[lit].mean(axis=0)
    ratio = float(ours_mean @ REC709_Y) / float(theirs_mean @ REC709_Y)
    print("| scene | lit pixels | trs-render mean (RGB) | Cycles mean (RGB) | trs-render over Cycles |")
    print("|---|---|---|---|---|")
    fmt = lambda m: ", ".join(f"{v:.4g}" for v in m)  # noqa: E731
    print(f"| {args.scene} | {int(lit.sum())} | {fmt(ours_mean)} | {fmt(theirs_mean)} | {ratio:.3f} |")
    if args.csv:
        new = not args.csv.exists()
        with args.csv.open("a", newline="") as f:
            writer = csv.writer(f)
            if new:
                writer.writerow(["scene", "diffuse", "lit_pixels", "trs_mean_y", "cycles_mean_y", "ratio"])
            writer.writerow([args.scene, args.diffuse, int(lit.sum()), float(ours_mean @ REC709_Y),
                             float(theirs_mean @ REC709_Y), ratio])
    if args.tolerance is not None and abs(ratio - 1.0) > args.tolerance:
        sys.exit(f"cycles_compare: {args.scene}: trs-render's mean is {ratio:.3f} times Cycles', beyond {args.tolerance}")


if __name__ == "__main__":
    main()
