#!/usr/bin/env python3
"""trs-render against Blender's Cycles on the material scenes (scenes/materials): one
tools/cycles_compare.py run per scene, summed up as a Markdown table and side-by-side previews.

  tools/material_gallery.py --render build/bin/trs-render --out DIR [--courtyard]
      [--diffuse | --both] [--transmission gltf|importer]
      [--width 320 --height 180 --spp 256 --cycles-spp 256 --max-depth 3] [--exposure STOPS]
      [SCENE.gltf ...]

Renders every scenes/materials/<name>/<name>.gltf (or the files named), and scenes/courtyard
with --courtyard, into DIR/<name>/ (trs.exr, cycles.exr, trs-mask.exr, as cycles_compare.py
writes them) and writes DIR/<name>.png: trs-render on the left, Cycles on the right, sRGB, at
--exposure; and DIR/gallery.png, those previews one under the other. With --diffuse the
materials are Lambertian in both (cycles_compare.py); with --both each scene is rendered as
authored and then diffuse, into DIR/<name>-diffuse/, DIR/<name>-diffuse.png and
DIR/gallery-diffuse.png besides. Prints a Markdown table: per scene and mode the lit pixels
(where no camera sample of trs-render sees an emitter), the two renders' mean luminance over
them, their ratio, and the relMSE of trs-render's image against Cycles' over them
(tools/common/trs_measure.py: both renders' noise counts in it, so it falls with the sample
counts towards the difference of the two renderers). A scene that fails to render is reported
in the table and makes the exit status 1; the others still run. Needs Debian's python3 with
python3-numpy and python3-openimageio.
"""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

TOOLS = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # importing the tools beside this one leaves no __pycache__
sys.path[:0] = [str(TOOLS), str(TOOLS / "common")]
import trs_measure  # noqa: E402
from cycles_compare import REC709_Y, add_comparison_options, comparison_arguments  # noqa: E402

MATERIALS = TOOLS.parent / "scenes" / "materials"
COURTYARD = TOOLS.parent / "scenes" / "courtyard" / "courtyard.gltf"
GAP = 4  # black pixels between the two halves of a preview


def scene_files(args):
    """The glTF files to compare: those named, else each scenes/materials/<name>/<name>.gltf;
    and the courtyard if asked for."""
    files = list(args.scenes) or sorted(p / f"{p.name}.gltf" for p in MATERIALS.iterdir()
                                         if (p / f"{p.name}.gltf").is_file())
    files += [COURTYARD] if args.courtyard else []
    return list(dict.fromkeys(f.resolve() for f in files))  # each once, in order


def compare(scene, folder, args, diffuse):
    """Runs tools/cycles_compare.py on `scene` into `folder`, as authored or `diffuse`; None, or
    why it failed."""
    arguments = [word for word in comparison_arguments(args) if word != "--diffuse"]
    command = [sys.executable, str(TOOLS / "cycles_compare.py"), str(scene), "--out", str(folder),
               *arguments, *(["--diffuse"] if diffuse else [])]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return (result.stderr.strip() or result.stdout.strip()).splitlines()[-1]
    return None


def measure(folder):
    """(lit pixels, trs-render's mean luminance, Cycles', relMSE) over the lit pixels."""
    ours = trs_measure.read_exr(folder / "trs.exr")
    theirs = trs_measure.read_exr(folder / "cycles.exr")
    lit = trs_measure.lit_pixels(trs_measure.read_exr(folder / "trs-mask.exr"))
    if not lit.any():
        return 0, float("nan"), float("nan"), float("nan")
    return (int(lit.sum()), float(ours[lit].mean(axis=0) @ REC709_Y), float(theirs[lit].mean(axis=0) @ REC709_Y),
            trs_measure.relmse(ours, theirs, lit))


def srgb(linear, exposure):
    """Linear RGB to 8-bit sRGB at `exposure` stops, clipped as a display would."""
    x = np.clip(linear * 2.0 ** exposure, 0.0, 1.0)
    return np.round(255 * np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)).astype(np.uint8)


def preview(folder, exposure):
    """trs-render | Cycles, side by side with a black gap, as 8-bit sRGB."""
    ours = trs_measure.read_exr(folder / "trs.exr")
    theirs = trs_measure.read_exr(folder / "cycles.exr")
    gap = np.zeros((ours.shape[0], GAP, 3))
    return srgb(np.concatenate([ours, gap, theirs], axis=1), exposure)


def write_png(pixels, path):
    """8-bit RGB pixels as a PNG."""
    out = oiio.ImageOutput.create(str(path))
    if out is None:
        sys.exit(f"material_gallery: cannot write {path}: {oiio.geterror()}")
    out.open(str(path), oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, oiio.UINT8))
    out.write_image(pixels)
    out.close()


def gallery(previews):
    """Previews one under the other with a black gap, padded to the widest."""
    width = max(p.shape[1] for p in previews)
    rows = []
    for p in previews:
        rows += [np.pad(p, ((0, 0), (0, width - p.shape[1]), (0, 0))), np.zeros((GAP, width, 3), np.uint8)]
    return np.concatenate(rows[:-1], axis=0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenes", nargs="*", type=Path, help="glTF files (default: every scene of scenes/materials)")
    parser.add_argument("--out", type=Path, required=True, help="folder for the renders and previews")
    parser.add_argument("--courtyard", action="store_true", help="add scenes/courtyard")
    add_comparison_options(parser)
    parser.add_argument("--both", action="store_true", help="as authored, then --diffuse")
    parser.add_argument("--exposure", type=float, default=0.0, help="the previews' exposure, in stops")
    args = parser.parse_args()

    modes = [False, True] if args.both else [args.diffuse]
    rows, failed, previews = [], False, {mode: [] for mode in modes}
    for scene in scene_files(args):
        for diffuse in modes:
            name = scene.stem + ("-diffuse" if diffuse and args.both else "")
            label = f"{scene.stem} | {'diffuse' if diffuse else 'as authored'}"
            folder = args.out / name
            print(f"material_gallery: {name} ...", file=sys.stderr)
            error = compare(scene, folder, args, diffuse)
            if error:
                failed = True
                rows.append(f"| {label} | failed: {error} | | | | |")
                continue
            lit, ours, theirs, error = measure(folder)
            pixels = preview(folder, args.exposure)
            write_png(pixels, args.out / f"{name}.png")
            previews[diffuse].append(pixels)
            rows.append(f"| {label} | {lit} | {ours:.4g} | {theirs:.4g} | {ours / theirs:.3f} | {error:.3g} |")
    for diffuse, pictures in previews.items():
        if pictures:
            write_png(gallery(pictures), args.out / ("gallery-diffuse.png" if diffuse and args.both else "gallery.png"))
    print("| scene | materials | lit pixels | trs-render mean | Cycles mean | trs-render over Cycles | relMSE |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
