#!/usr/bin/env python3
"""A glTF scene rendered by trs-render and by Blender's Cycles, as a user who opens the file in
Blender sees it, its materials as the glTF specification defines them where Blender's importer
reads them otherwise: the mean over the lit pixels of the two, per channel, and their ratio.

Blender (Debian's `blender`, 3.4) imports the file with its glTF importer in its default
"Standard" lighting mode, the units trs-render converts punctual lights to (docs/renderer.md,
"Punctual lights"); Cycles then renders it on the CPU with the file's camera, the same image
size, the same path depth (Cycles' bounces are trs-render's --max-depth less one), no world
light, no clamping, no light threshold, punctual lights as points (radius and sun angle 0) and
Blender's "Standard" view, written as linear EXR (tools/cycles_scene.py runs inside Blender).
`--diffuse` makes every material Lambertian in both: trs-render's --diffuse-materials, and in
Cycles each imported Principled BSDF replaced by a Diffuse BSDF of its base colour beside its
transmission (below) and its emission, under the importer's coverage and normal map: the node
that drives the Principled BSDF's Alpha mixes the two with a Transparent BSDF (as the Principled
BSDF itself does in Cycles), and its Normal Map node feeds the Diffuse BSDF's Normal. What is
compared is then the lighting, not the two renderers' BSDFs (Cycles' Principled diffuse
brightens at grazing angles, and trs-render's darkens under its dielectric specular layer). The
lit pixels are those where no camera sample of trs-render's render sees an emitter (its
--emitter-mask is 0, also through a smooth pane): where one does, both show the emitter itself.

Coverage (glTF's alphaMode) reaches Cycles through the shader alone: Cycles blends by the
Alpha input and ignores the material's blend mode, which only Eevee reads. BLEND is therefore
rendered as the file means it. For MASK, Blender 3.4's importer leaves the cut to that blend
mode ("Alpha Clip" at alphaCutoff), so Cycles would blend a masked texture's fractional alpha:
the script cuts it in the shader instead, Alpha = 1 - (alpha < cutoff), glTF's rule, in front
of whatever the importer wired into the Alpha input. Transparent hits count as Cycles'
transparent bounces (up to 64), apart from the path depth. A material that is not doubleSided
emits from its front face alone, as in trs-render: the importer turns doubleSided into Backface
Culling, which only Eevee reads, and Cycles emits from both faces, so the script multiplies the
emission by 1 - Backfacing (a light panel 2 cm before a wall would otherwise light the wall behind
it, and the room round its edges: 3% of the lit-pixel mean in scenes/materials/coated-panel).
Where the importer multiplies a texture by a colour factor that is not grey (emissiveFactor,
sheenColorFactor) it links its Mix node's float output, which is 0, so that such an emitter
renders black: the script links the node's colour output. Normal maps reach Cycles through
the importer's Normal Map node, with MikkTSpace tangents of the map's UV set (the file's TANGENT
is not read). Cycles bends a shading normal whose mirror direction of the view would fall below
the surface back towards the viewer, so steep normal maps seen at grazing angles (the far
flanks of scenes/materials/normal-wall's cobbles) differ from a renderer that shades them as
mapped.

The material extensions. Blender 3.4's importer (io_scene_gltf2 3.4.50) reads each into the
Principled BSDF (version 1, Disney's) or beside it; the script keeps what it reads as glTF
means it and sets the rest (tools/cycles_scene.py), as far as Cycles 3.4 can render it:
- KHR_materials_transmission: the importer sets the Principled BSDF's Transmission (factor
  times the texture's red). Cycles' transmission refracts at the IOR, on every surface: it has
  no thin-walled surface. A thin pane (no KHR_materials_volume) rendered so bends the light at
  one interface, as a lens would, magnifies what lies behind it (the floor-lamp scene, shade
  and all, comes out 1.5 times as bright in Cycles as glTF means), totally reflects light
  inside a lamp shade, and stops Cycles' shadow rays. That is what a Blender user who opens the
  file sees, but not the file; the comparison renders the file: the Principled BSDF keeps the
  non-transmissive share (Transmission 0), mixed by transmission x (1 - metallic) with a pane of
  glTF's thin dielectric, Schlick's Fresnel F of the layer's f0 and f90 at N.V (a Layer Weight
  node) between a white GGX Glossy BSDF (the reflection) and, where roughness^2 < 1e-3
  (trs-render's smooth pane), a Transparent BSDF of the base colour: light straight through,
  which Cycles' shadow rays cross carrying its colour, as trs-render's cross a smooth thin pane.
  Where rougher, glTF's transmission is the GGX lobe mirrored through the surface, which Cycles
  3.4 has no BSDF for: a Translucent BSDF (Lambertian transmission) of the base colour, the
  closest one that does not bend light. `--transmission importer` renders the importer's
  refraction instead.
- KHR_materials_volume: where thicknessFactor > 0 the importer keeps the refraction (right for
  a volume's boundary) and adds a Volume Absorption node of colour attenuationColor and density
  1 / attenuationDistance, which Cycles reads as an absorption coefficient (1 - colour) x
  density: a transmittance exp(-(1 - c) d / D) where glTF's is c^(d / D). The script sets the
  density to the largest of -ln(c) / D over the channels and the colour so that each channel's
  coefficient is -ln(c) / D.
- KHR_materials_ior and _specular: the importer sets the IOR, which in the Principled BSDF
  drives only the refraction's Fresnel; the reflection's F0 is Specular (0.08 x Specular), which
  it converts from the IOR only when KHR_materials_specular is present, from the luminance of
  specularColorFactor, without specularFactor (kept in a node group that renders nothing) and
  divided by 1 - transmission (infinite at 1), and tints only towards the base colour. The script
  sets Specular to 0 and adds a GGX Glossy BSDF of the layer's Fresnel, mix(f0, f90, (1 - N.V)^5)
  per channel with f0 = min(f0(ior) x specularColor, 1) x specularFactor and f90 =
  specularFactor, times 1 - metallic: coloured, and dimmed at grazing by specularFactor, as
  glTF's layer is. With specular textures the importer's baked Specular image is kept, times
  specularFactor.
- KHR_materials_clearcoat: the importer sets Clearcoat, Clearcoat Roughness and Clearcoat Normal;
  Cycles' coat is Disney's, a GTR1 lobe weighted 0.25 x clearcoat, over a base it does not dim,
  emission included. The script sets Clearcoat to 0 and mixes, by clearcoat x Schlick(0.04, 1,
  N.V) at the coat's normal, the rest (emission included) with a white GGX Glossy BSDF of the
  coat's roughness and normal: glTF's coat, which dims what lies under it, emission too.
- KHR_materials_sheen: the importer adds a Velvet BSDF (Ashikhmin's, sigma = sheenRoughness) of
  the sheen colour to the Principled BSDF, which it leaves undimmed; glTF's sheen is Charlie's,
  over a base scaled by 1 - max(sheenColor) E(N.V), E its directional albedo. The script scales
  the Velvet BSDF's colour, per N.V (a Float Curve), to Charlie's albedo at sheenRoughnessFactor
  (the factor: a roughness texture is not tabulated) and dims the rest by 1 - max(sheenColor)
  E(N.V); the lobe's shape stays the Velvet's.
What cannot be matched: a rough thin surface's lobe (Translucent, not the mirrored GGX); the
Principled BSDF's own diffuse and specular, which it adds without sharing energy where glTF and
trs-render share it (the base difference in every comparison of materials as authored); the
Velvet's lobe shape; Cycles' exact Fresnel at refracting surfaces against glTF's Schlick.
With --diffuse, the transmission stays beside the Diffuse BSDF, mixed by its factor or texture
and tinted by the base colour, without Fresnel (trs-render's --diffuse-materials drops the
specular layer): a Transparent BSDF where smooth and thin, a Translucent one where rough and
thin, a GGX Refraction BSDF at the IOR at a volume's boundary (whose absorption stays); there
trs-render still reflects totally beyond the critical angle, which Cycles' Refraction BSDF does
not.

  tools/cycles_compare.py SCENE.gltf --render build/bin/trs-render --out DIR [--diffuse]
      [--transmission gltf|importer]
      [--width 320 --height 180 --spp 256 --cycles-spp 256 --max-depth 3] [--csv FILE]

Writes DIR/trs.exr, DIR/cycles.exr and DIR/trs-mask.exr; prints a Markdown table and the
ratio of the two means (luminance); exits 0 whatever the ratio (--tolerance makes it a check:
status 1 beyond it). Needs Debian's python3 with python3-numpy and python3-openimageio.
"""
import argparse
import csv
import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

REC709_Y = np.array([0.2126, 0.7152, 0.0722])

TOOLS = Path(__file__).resolve().parent
BLENDER_SCRIPT = TOOLS / "cycles_scene.py"  # runs inside Blender: import, materials, render


def read_rgb(path):
    image = oiio.ImageBuf(str(path))
    pixels = image.get_pixels(oiio.FLOAT)
    if pixels is None or pixels.size == 0:
        sys.exit(f"cycles_compare: cannot read {path}: {image.geterror()}")
    return np.asarray(pixels)[..., :3].astype(np.float64)


def run(command):
    """Runs `command`, exiting with its output if it fails; returns its standard output."""
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"cycles_compare: {shlex.join(map(str, command))} failed:\n{result.stdout[-2000:]}{result.stderr}")
    return result.stdout


COMPARISON_OPTIONS = ("render", "blender", "diffuse", "transmission", "width", "height", "spp", "cycles_spp",
                      "max_depth")


def add_comparison_options(parser):
    """The programs and the settings of a comparison, COMPARISON_OPTIONS (--out apart)."""
    parser.add_argument("--render", default="build/bin/trs-render", help="trs-render")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--diffuse", action="store_true", help="Lambertian materials in both renderers")
    parser.add_argument("--transmission", choices=("gltf", "importer"), default="gltf",
                        help="Cycles' thin transmissive surfaces: unbent, as glTF defines them (default), or "
                             "refracting, as Blender's importer leaves them")
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


def render_cycles(blender, scene, out, width, height, spp, max_depth, diffuse=False, transmission="gltf",
                  seed=0, time_limit=0.0, threads=None):
    """Renders glTF file `scene` with Cycles into EXR `out` (tools/cycles_scene.py): Cycles'
    bounces are trs-render's `max_depth` less one; with `time_limit` (seconds) it stops there,
    short of `spp`. Returns the render's time in seconds as Blender reports it (its scene's
    synchronisation and the samples, not Blender's start), or None where it reports none."""
    options = {"scene": str(Path(scene).resolve()), "out": str(Path(out).resolve()), "width": width,
               "height": height, "spp": spp, "bounces": max_depth - 1, "diffuse": diffuse,
               "transmission": transmission, "seed": seed, "time_limit": time_limit}
    if threads:
        options["threads"] = threads
    output = run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(BLENDER_SCRIPT),
                  "--", json.dumps(options)])
    times = re.findall(r"Time: (\d+):(\d+\.\d+) \(Saving", output)
    return int(times[-1][0]) * 60 + float(times[-1][1]) if times else None


def compare(scene, out, args):
    """Renders `scene` with both renderers into folder `out` (trs.exr, trs-mask.exr, cycles.exr)
    at the COMPARISON_OPTIONS of `args`; returns (lit pixels, trs-render's mean RGB over them,
    Cycles', the ratio of their luminances)."""
    out.mkdir(parents=True, exist_ok=True)
    trs, mask, cycles = out / "trs.exr", out / "trs-mask.exr", out / "cycles.exr"
    run([args.render, scene, "--out", trs, "--emitter-mask", mask, "--spp", str(args.spp), "--width",
         str(args.width), "--height", str(args.height), "--max-depth", str(args.max_depth), "--quiet",
         *(["--diffuse-materials"] if args.diffuse else [])])
    render_cycles(args.blender, scene, cycles, args.width, args.height, args.cycles_spp, args.max_depth,
                  args.diffuse, args.transmission)
    ours, theirs, seen = read_rgb(trs), read_rgb(cycles), read_rgb(mask)[..., 0]
    lit = seen == 0.0
    if not lit.any():
        sys.exit(f"cycles_compare: {scene}: no lit pixel: every pixel sees an emitter")
    ours_mean, theirs_mean = ours[lit].mean(axis=0), theirs[lit].mean(axis=0)
    return int(lit.sum()), ours_mean, theirs_mean, ratio(ours_mean, theirs_mean)


def ratio(ours, theirs):
    """The ratio of two mean RGBs' luminances; NaN where Cycles' is 0 (a scene left dark)."""
    denominator = float(theirs @ REC709_Y)
    return float(ours @ REC709_Y) / denominator if denominator > 0 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", type=Path)
    parser.add_argument("--out", type=Path, required=True, help="folder for the images")
    add_comparison_options(parser)
    parser.add_argument("--csv", type=Path, help="append a row per scene")
    parser.add_argument("--tolerance", type=float, help="exit 1 where the ratio is further than this from 1")
    args = parser.parse_args()

    lit, ours_mean, theirs_mean, mean_ratio = compare(args.scene, args.out, args)
    print("| scene | lit pixels | trs-render mean (RGB) | Cycles mean (RGB) | trs-render over Cycles |")
    print("|---|---|---|---|---|")
    fmt = lambda m: ", ".join(f"{v:.4g}" for v in m)  # noqa: E731
    print(f"| {args.scene} | {lit} | {fmt(ours_mean)} | {fmt(theirs_mean)} | {mean_ratio:.3f} |")
    if args.csv:
        new = not args.csv.exists()
        with args.csv.open("a", newline="") as f:
            writer = csv.writer(f)
            if new:
                writer.writerow(["scene", "diffuse", "lit_pixels", "trs_mean_y", "cycles_mean_y", "ratio"])
            writer.writerow([args.scene, args.diffuse, lit, float(ours_mean @ REC709_Y),
                             float(theirs_mean @ REC709_Y), mean_ratio])
    if args.tolerance is not None and not abs(mean_ratio - 1.0) <= args.tolerance:
        sys.exit(f"cycles_compare: {args.scene}: trs-render's mean is {mean_ratio:.3f} times Cycles', beyond {args.tolerance}")


if __name__ == "__main__":
    main()
