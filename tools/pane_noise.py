#!/usr/bin/env python3
"""How much a smooth thin pane before an emitter adds to the noise, in trs-render and in Blender's
Cycles, at equal time.

From scenes/materials/glass-panes (the frosted box taken out) two variants are written: `pane`,
the emissive texture behind its smooth, thin, pale green pane (transmission 1, roughness 0), and
`no-pane`, the pane taken out and the emission scaled by what the pane lets through at normal
incidence: its base colour times 1 - 0.04. Each variant gets a converged reference of its own in
each renderer; renders of equal samples per pixel with several seeds are measured against it:
relMSE (tools/common/trs_measure.py, trs-imgdiff's) over the pixels where no camera sample of
either trs-render reference sees an emitter (the masks' union, so that both variants are measured
on the same pixels), and the renders' times (trs-render's wall time, set-up included; Cycles'
render time as Blender reports it, without Blender's start). relMSE falls as 1 / time for an
unbiased renderer, so relMSE times time is relMSE at equal time: the pane's over the no-pane's
is the table's last column. (Time-limited renders of a few seconds would compare the same, but
Cycles' time limit stops at 18 to 33 samples for the same 2 s on a shared machine.) trs-render
runs the default strategy and `trs`; Cycles runs the pane as glTF defines it
(tools/cycles_scene.py: a Transparent BSDF, which Cycles' shadow rays cross) and as Blender's
importer leaves it (refracting: no shadow ray crosses it), each against its own reference.

  tools/pane_noise.py --out DIR [--render build/bin/trs-render] [--blender blender]
      [--width 160 --height 90 --max-depth 3] [--spp 32] [--seeds 4]
      [--reference-spp 2048] [--cycles-reference-spp 2048] [--no-cycles]

Prints a Markdown table: per renderer and setting the mean relMSE over the seeds and the median
time of a render, each variant, and the pane's relMSE at equal time over the no-pane's. Needs
Debian's python3 with python3-numpy and python3-openimageio (and Blender for Cycles).
"""
import argparse
import json
import statistics
import sys
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # importing the tools beside this one leaves no __pycache__
sys.path[:0] = [str(TOOLS), str(TOOLS / "common")]
import gltf_variant  # noqa: E402
import trs_measure  # noqa: E402
from cycles_compare import render_cycles, run  # noqa: E402

SCENE = TOOLS.parent / "scenes" / "materials" / "glass-panes" / "glass-panes.gltf"
FROSTED = ("frosted light", "frosted sides", "frosted pane")
PANE, LIGHT = "clear pane", "clear light"
FRESNEL_NORMAL = 0.04  # the pane's reflectance at normal incidence (ior 1.5)


def write_variants(folder):
    """pane.gltf and no-pane.gltf in `folder`; returns {name: path}."""
    pane = gltf_variant.without_nodes(gltf_variant.read(SCENE), FROSTED)
    no_pane = gltf_variant.without_nodes(gltf_variant.read(SCENE), FROSTED + (PANE,))
    materials = {m["name"]: m for m in no_pane["materials"]}
    glass = materials["clear glass"]["pbrMetallicRoughness"]["baseColorFactor"]
    light = materials[LIGHT]
    light["emissiveFactor"] = [e * g * (1 - FRESNEL_NORMAL) for e, g in zip(light["emissiveFactor"], glass)]
    return {"pane": gltf_variant.write(pane, SCENE, folder, "pane"),
            "no-pane": gltf_variant.write(no_pane, SCENE, folder, "no-pane")}


def trs_render(args, scene, out, extra):
    """Renders `scene` with trs-render into `out`; returns its wall time, set-up included."""
    stats = Path(out).with_suffix(".json")
    run([args.render, scene, "--out", out, "--width", str(args.width), "--height", str(args.height),
         "--max-depth", str(args.max_depth), "--stats", stats, "--quiet", *extra])
    return json.loads(stats.read_text())["wall_seconds"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, required=True, help="folder for the variants and renders")
    parser.add_argument("--render", default="build/bin/trs-render")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=90)
    parser.add_argument("--max-depth", type=int, default=3)
    parser.add_argument("--spp", type=int, default=32, help="each measured render's samples per pixel")
    parser.add_argument("--seeds", type=int, default=4)
    parser.add_argument("--reference-spp", type=int, default=2048)
    parser.add_argument("--cycles-reference-spp", type=int, default=2048)
    parser.add_argument("--no-cycles", action="store_true")
    args = parser.parse_args()

    scenes = write_variants(args.out)
    masks = []
    for name, scene in scenes.items():
        folder = args.out / "trs" / name
        folder.mkdir(parents=True, exist_ok=True)
        if not (folder / "reference.exr").exists():
            print(f"pane_noise: trs-render reference of {name} ...", file=sys.stderr)
            trs_render(args, scene, folder / "reference.exr", ["--spp", str(args.reference_spp), "--seed", "1000",
                                                               "--strategy", "power", "--emitter-mask",
                                                               folder / "mask.exr"])
        masks.append(trs_measure.read_exr(folder / "mask.exr"))
    lit = trs_measure.lit_pixels(masks[0]) & trs_measure.lit_pixels(masks[1])

    rows = []  # (renderer, setting, {variant: (relMSE, seconds)})
    for strategy in ("auto", "trs"):
        measured = {}
        for name, scene in scenes.items():
            folder = args.out / "trs" / name
            reference = trs_measure.read_exr(folder / "reference.exr")
            errors, times = [], []
            for seed in range(1, args.seeds + 1):
                image = folder / f"{strategy}-{seed}.exr"
                times.append(trs_render(args, scene, image, ["--spp", str(args.spp), "--strategy", strategy,
                                                             "--seed", str(seed)]))
                errors.append(trs_measure.relmse(trs_measure.read_exr(image), reference, lit))
            measured[name] = (statistics.mean(errors), statistics.median(times))
        rows.append(("trs-render", f"`{strategy}`", measured))
    if not args.no_cycles:
        shared = {}  # the no-pane variant renders alike in both modes: once
        for mode in ("gltf", "importer"):
            measured = {}
            for name, scene in scenes.items():
                if name in shared:
                    measured[name] = shared[name]
                    continue
                folder = args.out / "cycles" / (name if name == "no-pane" else f"{name}-{mode}")
                folder.mkdir(parents=True, exist_ok=True)
                if not (folder / "reference.exr").exists():
                    print(f"pane_noise: Cycles reference of {folder.name} ...", file=sys.stderr)
                    render_cycles(args.blender, scene, folder / "reference.exr", args.width, args.height,
                                  args.cycles_reference_spp, args.max_depth, transmission=mode, seed=1000)
                reference = trs_measure.read_exr(folder / "reference.exr")
                errors, times = [], []
                for seed in range(1, args.seeds + 1):
                    image = folder / f"render-{seed}.exr"
                    times.append(render_cycles(args.blender, scene, image, args.width, args.height, args.spp,
                                               args.max_depth, transmission=mode, seed=seed))
                    errors.append(trs_measure.relmse(trs_measure.read_exr(image), reference, lit))
                measured[name] = (statistics.mean(errors), statistics.median(times))
                if name == "no-pane":
                    shared[name] = measured[name]
            label = "pane as glTF defines it" if mode == "gltf" else "pane as the importer leaves it (refracting)"
            rows.append(("Cycles", label, measured))

    print("| renderer | setting | relMSE, no pane | relMSE, pane | seconds, no pane | seconds, pane "
          "| pane over no pane at equal time |")
    print("|---|---|---|---|---|---|---|")
    for renderer, setting, measured in rows:
        (e0, t0), (e1, t1) = measured["no-pane"], measured["pane"]
        print(f"| {renderer} | {setting} | {e0:.4g} | {e1:.4g} | {t0:.2f} | {t1:.2f} | {e1 * t1 / (e0 * t0):.2f} |")
    print(f"({int(lit.sum())} lit pixels of {lit.size}; {args.seeds} seeds of {args.spp} spp each, "
          f"{args.width} x {args.height}, max depth {args.max_depth})")


if __name__ == "__main__":
    main()
