#!/usr/bin/env python3
"""What a glTF file's material extension adds, in trs-render against Blender's Cycles: the file is
compared with Cycles (tools/cycles_compare.py) as it is and once more with the extensions named
taken out of every material (KHR_materials_transmission by default: the same surfaces, opaque).
The two renderers' other differences (their base BSDFs, their emitters) are in both ratios
trs-render / Cycles and largely cancel in their quotient; what is left is how differently the
two render the extension.

  tools/cycles_extension_check.py SCENE.gltf --out DIR [--extension NAME ...] [--tolerance 0.05]
      [--render build/bin/trs-render --width 160 --height 90 --spp 64 --cycles-spp 64 --max-depth 3]
      [--diffuse] [--transmission gltf|importer]

Writes DIR/with/ and DIR/without/ (cycles_compare.py's images) and DIR/without.gltf (the file
without the extensions, beside copies of its buffers and images). The means are taken over the
pixels lit in both variants (no camera sample of trs-render sees an emitter in either), so that
an emitter seen through a surface in one variant and hidden in the other counts in neither.
Prints a Markdown table and the quotient of the two ratios; with --tolerance, exits 1 where the
quotient is further than that from 1. Needs Debian's python3 with python3-numpy and
python3-openimageio, and Blender.
"""
import argparse
import sys
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # importing the tools beside this one leaves no __pycache__
sys.path[:0] = [str(TOOLS), str(TOOLS / "common")]
import gltf_variant  # noqa: E402
from cycles_compare import add_comparison_options, compare, ratio, read_rgb  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", type=Path)
    parser.add_argument("--out", type=Path, required=True, help="folder for the images")
    parser.add_argument("--extension", action="append", help="an extension to take out (repeatable; default: "
                                                              "KHR_materials_transmission)")
    add_comparison_options(parser)
    parser.set_defaults(width=160, height=90, spp=64, cycles_spp=64)
    parser.add_argument("--tolerance", type=float, help="exit 1 where the quotient is further than this from 1")
    args = parser.parse_args()
    extensions = args.extension or ["KHR_materials_transmission"]
    if args.scene.suffix != ".gltf":
        sys.exit("cycles_extension_check: a .gltf file, please (its JSON is edited)")

    without = gltf_variant.without_extensions(gltf_variant.read(args.scene), extensions)
    variants = (("with", args.scene), ("without", gltf_variant.write(without, args.scene, args.out, "without")))
    for name, scene in variants:
        print(f"cycles_extension_check: {name} {', '.join(extensions)} ...", file=sys.stderr)
        compare(scene, args.out / name, args)
    images = {name: [read_rgb(args.out / name / f) for f in ("trs.exr", "cycles.exr", "trs-mask.exr")]
              for name, _ in variants}
    lit = (images["with"][2][..., 0] == 0) & (images["without"][2][..., 0] == 0)
    if not lit.any():
        sys.exit("cycles_extension_check: no pixel is lit in both variants")
    print(f"| {args.scene.stem} | lit pixels | trs-render mean (RGB) | Cycles mean (RGB) | trs-render over Cycles |")
    print("|---|---|---|---|---|")
    fmt = lambda m: ", ".join(f"{v:.4g}" for v in m)  # noqa: E731
    ratios = []
    for name, _ in variants:
        ours, theirs = (image[lit].mean(axis=0) for image in images[name][:2])
        ratios.append(ratio(ours, theirs))
        print(f"| {name} {' '.join(extensions)} | {int(lit.sum())} | {fmt(ours)} | {fmt(theirs)} | {ratios[-1]:.4f} |")
    quotient = ratios[0] / ratios[1]  # NaN where a variant is dark in Cycles
    print(f"ratio with over ratio without: {quotient:.4f}")
    if args.tolerance is not None and not abs(quotient - 1.0) <= args.tolerance:
        sys.exit(f"cycles_extension_check: {args.scene}: {', '.join(extensions)} change trs-render over Cycles by "
                 f"{quotient:.3f}, beyond {args.tolerance}")


if __name__ == "__main__":
    main()
