#!/usr/bin/env python3
"""What each light strategy costs before and during a render: set-up by part and frame time.

Renders each scene with each configuration (a few passes with trs-render: the image is not what
is measured) and reads its stats: the set-up by part (setup_ms: loading, texture decoding, the
BVH, the emission maps, the light sampler and its subdivision, the light structure, the first
frame), the parts the light sampler samples, and the milliseconds of a frame and of its light
sampling. The median over --repeats runs of each. Prints a Markdown table per scene, and the
set-up of each configuration over that of the first (the baseline, `tree` by default); writes
a CSV.

  tools/setup_cost.py --render build/bin/trs-render scenes/real/*/ scenes/night-street \\
      --configs tree power ris ris+refine=0 auto --csv setup-cost.csv

A configuration is STRATEGY or STRATEGY+OPTION=VALUE+..., as trs-study takes them.
"""
import argparse
import csv
import json
import shlex
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

PARTS = ["loading", "texture_decoding", "bvh", "emission", "light_sampler", "subdivision", "light_structure", "pilot",
         "first_pass"]


def config_options(config):
    strategy, *options = config.split("+")
    args = ["--strategy", strategy]
    for option in options:
        key, _, value = option.partition("=")
        args += [f"--{key}", value]
    return args


def scene_files(folder):
    """A scene folder's glTF (named as the folder) and its render.toml, if any."""
    folder = Path(folder)
    if folder.suffix in (".gltf", ".glb"):
        return folder, folder.parent / "render.toml"
    return folder / f"{folder.name}.gltf", folder / "render.toml"


def render_stats(tool, render, scene, settings, options, args, work):
    """trs-render's stats of `scene` rendered with --spp, --width, --height and --max-depth of
    `args` and `options`; exits naming `tool` and the command if the render fails."""
    stats = work / "stats.json"
    command = [render, str(scene), "--out", str(work / "image.exr"), "--stats", str(stats), "--quiet",
               "--spp", str(args.spp), "--width", str(args.width), "--height", str(args.height),
               "--max-depth", str(args.max_depth), *options]
    if settings.exists():
        command[2:2] = ["--settings", str(settings)]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{tool}: {shlex.join(command)} failed:\n{result.stderr}")
    return json.loads(stats.read_text())


def measure(render, scene, settings, config, args, work):
    s = render_stats("setup_cost", render, scene, settings, config_options(config), args, work)
    row = {f"{part}_ms": s["setup_ms"][part] for part in PARTS}
    row["setup_ms"] = sum(s["setup_ms"][part] for part in PARTS if part != "first_pass")
    row["parts"] = s["light_sampler_parts"]
    row["pass_ms"] = 1000.0 * s["render_seconds"] / max(s["passes"], 1)
    row["sampler_ms"] = s["sampler_ms_per_pass"]
    row["used"] = (s["strategy_choice"] or {}).get("used", s["settings"]["strategy"])
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes", nargs="+", help="scene folders (scenes/neon-sign) or glTF files")
    p.add_argument("--render", default="build/bin/trs-render")
    p.add_argument("--configs", nargs="+", default=["tree", "power", "ris", "ris+refine=0", "auto"],
                   help="the first is the baseline of the set-up ratio")
    p.add_argument("--spp", type=int, default=8)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=180)
    p.add_argument("--max-depth", type=int, default=3)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--csv", type=Path)
    args = p.parse_args()

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for folder in args.scenes:
            scene, settings = scene_files(folder)
            print(f"\n{scene.parent.name}\n")
            print("| configuration | used | set-up ms | x baseline | largest part | parts | pass ms | light sampler ms |")
            print("|---|---|---|---|---|---|---|---|")
            baseline = None
            for config in args.configs:
                runs = [measure(args.render, scene, settings, config, args, Path(tmp)) for _ in range(args.repeats)]
                row = {key: statistics.median(r[key] for r in runs) if key != "used" else runs[0][key] for key in runs[0]}
                row.update(scene=scene.parent.name, config=config)
                rows.append(row)
                baseline = baseline or row["setup_ms"]
                largest = max(PARTS[:-1], key=lambda part: row[f"{part}_ms"])
                print(f"| {config} | {row['used']} | {row['setup_ms']:.0f} | {row['setup_ms'] / baseline:.2f} | "
                      f"{largest} {row[largest + '_ms']:.0f} | {row['parts']:.0f} | {row['pass_ms']:.1f} | "
                      f"{row['sampler_ms']:.2f} |", flush=True)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=["scene", "config", "used", "setup_ms", *(f"{p}_ms" for p in PARTS),
                                                   "parts", "pass_ms", "sampler_ms"])
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
