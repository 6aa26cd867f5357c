#!/usr/bin/env python3
"""What it costs each light strategy to get ready for a new frame's emission.

Renders frames of an animated scene with trs-render (--frames, one sample a pixel: the render
itself is not what is measured), and averages over every frame but the first, where everything
is built, the stats' emission_update_ms (decode, upload, counting, strategy) and the light
sampler's milliseconds per sample pass. Prints a Markdown table and writes a CSV.

  tools/animation_cost.py --render build/bin/trs-render --scene scenes/video-wall/video-wall.gltf \\
      --frames 0:12 --backends cpu vulkan --csv animation-cost.csv

--large-clip measures a generated scene instead, the size of a production LED volume: a curved
screen of about 100,000 triangles playing a 2048 x 2048 clip (written to a temporary folder;
Debian's python3 with numpy and OpenImageIO).
"""
import argparse
import csv
import json
import math
import shlex
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.dont_write_bytecode = True  # importing the scene builders leaves no __pycache__ in the tree
sys.path[:0] = [str(Path(__file__).resolve().parent), str(Path(__file__).resolve().parent / "common")]
from scenes_gen.gltf import Gltf  # noqa: E402
from scenes_gen.mesh import Mesh, room, sphere  # noqa: E402
import trs_options  # noqa: E402

PARTS = ["decode", "upload", "counting", "strategy"]


LARGE_SIZE, LARGE_GRID = 2048, 224  # texels on a side; quads on a side (2 x 224^2 = 100,352 triangles)


class LargeClip:
    """A LARGE_SIZE^2 clip, frame k at clip/screen.%04d.png: on a grainy near-black ground, bright discs
    circle, a bar sweeps across and a fine checker scrolls (texel-scale detail). Stands in for a
    scenes_gen Texture (name, frames, frames_pattern, write)."""

    name, frames_pattern = "screen.png", "clip/screen.%04d.png"

    def __init__(self, count):
        self.frames = list(range(count))

    @staticmethod
    def frame(k):
        import numpy as np
        y, x = np.mgrid[0:LARGE_SIZE, 0:LARGE_SIZE] / LARGE_SIZE
        # A faint grain, as filmed footage has: every texel lit, and a PNG that is no easier to decode than a film's.
        rgb = np.random.default_rng(k).uniform(0.002, 0.02, (LARGE_SIZE, LARGE_SIZE, 1)).repeat(3, axis=2)
        for i, colour in enumerate([(1.0, 0.3, 0.1), (0.2, 0.6, 1.0), (0.9, 0.9, 0.3)]):
            angle = 2 * math.pi * (k / 24 + i / 3)
            cx, cy = 0.5 + 0.3 * math.cos(angle), 0.5 + 0.3 * math.sin(angle)
            rgb[(x - cx) ** 2 + (y - cy) ** 2 < 0.08 ** 2] = colour
        rgb[np.abs(x - (k / 24) % 1.0) < 0.02] = (1.0, 1.0, 1.0)
        checker = ((np.floor(x * 512 + k * 3) + np.floor(y * 512)) % 2 == 0) & (np.abs(y - 0.85) < 0.05)
        rgb[checker] = (0.1, 1.0, 0.4)
        return np.round(255 * np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)).astype(np.uint8)

    def write(self, folder):
        import OpenImageIO as oiio
        for k, path in [(0, folder / self.name)] + [(k, folder / (self.frames_pattern % k)) for k in self.frames]:
            path.parent.mkdir(parents=True, exist_ok=True)
            out = oiio.ImageOutput.create(str(path))
            out.open(str(path), oiio.ImageSpec(LARGE_SIZE, LARGE_SIZE, 3, oiio.UINT8))
            out.write_image(self.frame(k))
            out.close()


def write_large_clip(folder, count):
    """A room lit only by a curved screen of 2 x LARGE_GRID^2 triangles playing a LargeClip of
    `count` frames; returns the glTF's path."""
    gltf = Gltf("large-clip")
    gltf.mesh("room", room(-6.0, 6.0, 5.0, -4.0, 8.0), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("ball", sphere((0.0, 0.8, 2.0), 0.8), gltf.material("white plastic", (0.8,) * 3, 0.0, 0.3))

    def point(s, t):  # a quarter cylinder of radius 5 m behind the stage, 4 m high, facing +z
        angle = (s - 0.5) * math.pi / 2
        return (5.0 * math.sin(angle), 4.5 - 4.0 * t, 1.1 - 5.0 * math.cos(angle))

    screen = Mesh()
    screen.add_grid(point, lambda s, t: (-math.sin((s - 0.5) * math.pi / 2), 0.0, math.cos((s - 0.5) * math.pi / 2)),
                    LARGE_GRID, LARGE_GRID)
    gltf.mesh("LED volume", screen, gltf.emissive_material("LED volume", LargeClip(count), 6.0))
    gltf.camera((0.0, 1.7, 6.5), (0.0, 1.8, -2.0), 0.9)
    gltf.write(folder)
    return folder / "large-clip.gltf"


def measure(args, backend, strategy, work):
    run = [args.render, args.scene, "--frames", trs_options.frames_argument(args.frames), "--strategy", strategy,
           "--backend", backend, "--spp", "1", "--width", str(args.width), "--height", str(args.height), "--quiet",
           "--out", str(work / "o.%04d.exr"), "--stats", str(work / "s.%04d.json")]
    if args.refine is not None:
        run += ["--refine", args.refine]
    done = subprocess.run(run, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"animation_cost: {shlex.join(run)} failed:\n{done.stderr}")
    stats = [json.loads((work / f"s.{f:04d}.json").read_text()) for f in args.frames[1:]]
    row = {"backend": backend, "strategy": strategy, "refine": args.refine or "default", "frames": len(stats)}
    for part in PARTS:
        row[part + "_ms"] = statistics.mean(s["emission_update_ms"][part] for s in stats)
    row["ready_ms"] = sum(row[p + "_ms"] for p in PARTS)
    row["sampler_ms_per_pass"] = statistics.mean(s["sampler_ms_per_pass"] or 0.0 for s in stats)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--render", required=True, help="the trs-render executable")
    scene = parser.add_mutually_exclusive_group(required=True)
    scene.add_argument("--scene", help="an animated glTF scene")
    scene.add_argument("--large-clip", action="store_true",
                       help=f"a generated curved screen of {2 * LARGE_GRID ** 2:,} triangles playing a "
                            f"{LARGE_SIZE} x {LARGE_SIZE} clip")
    parser.add_argument("--frames", type=trs_options.frame_range, default="0:12",
                        help="A:B, the first only builds (default 0:12)")
    parser.add_argument("--backends", nargs="+", default=["cpu"], choices=["cpu", "vulkan"])
    parser.add_argument("--strategies", nargs="+", default=trs_options.STRATEGIES, choices=trs_options.STRATEGIES)
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=90)
    parser.add_argument("--refine", help="trs-render's --refine (the light sampler's subdivision; 0: off)")
    parser.add_argument("--csv", help="write the table as CSV")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        if args.large_clip:
            args.scene = str(write_large_clip(Path(tmp) / "large-clip", args.frames.stop))
        for backend in args.backends:
            for strategy in args.strategies:
                work = Path(tmp) / f"{backend}-{strategy}"
                work.mkdir()
                rows.append(measure(args, backend, strategy, work))
    print("| backend | strategy | decode ms | upload ms | counting ms | strategy ms | ready ms | light sampler ms a pass |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['backend']} | `{r['strategy']}` | {r['decode_ms']:.2f} | {r['upload_ms']:.2f} | "
              f"{r['counting_ms']:.2f} | {r['strategy_ms']:.2f} | {r['ready_ms']:.2f} | {r['sampler_ms_per_pass']:.2f} |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
