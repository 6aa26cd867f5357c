#!/usr/bin/env python3
"""What it costs each light strategy to get ready for a new frame's emission.

Renders frames of an animated scene with trs-render (--frames, one sample a pixel: the render
itself is not what is measured), and averages over every frame but the first, where everything
is built, the stats' emission_update_ms (decode, upload, counting, strategy) and the light
sampler's milliseconds per sample pass. Prints a Markdown table and writes a CSV.

  tools/animation_cost.py --render build/bin/trs-render --scene scenes/video-wall/video-wall.gltf \\
      --frames 0:12 --backends cpu vulkan --csv animation-cost.csv
"""
import argparse
import csv
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

STRATEGIES = ["uniform", "power", "tree", "texel", "tree-texel", "trs", "ris"]
PARTS = ["decode", "upload", "counting", "strategy"]


def measure(args, backend, strategy, work):
    first, last = (int(x) for x in args.frames.split(":"))
    run = [args.render, args.scene, "--frames", args.frames, "--strategy", strategy, "--backend", backend,
           "--spp", "1", "--width", str(args.width), "--height", str(args.height), "--quiet",
           "--out", str(work / "o.%04d.exr"), "--stats", str(work / "s.%04d.json")]
    done = subprocess.run(run, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"animation_cost: {' '.join(run)} failed:\n{done.stderr}")
    stats = [json.loads((work / f"s.{f:04d}.json").read_text()) for f in range(first + 1, last + 1)]
    row = {"backend": backend, "strategy": strategy, "frames": len(stats)}
    for part in PARTS:
        row[part + "_ms"] = statistics.mean(s["emission_update_ms"][part] for s in stats)
    row["ready_ms"] = sum(row[p + "_ms"] for p in PARTS)
    row["sampler_ms_per_frame"] = statistics.mean(s["sampler_ms_per_frame"] or 0.0 for s in stats)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--render", required=True, help="the trs-render executable")
    parser.add_argument("--scene", required=True, help="an animated glTF scene")
    parser.add_argument("--frames", default="0:12", help="A:B, the first only builds (default 0:12)")
    parser.add_argument("--backends", nargs="+", default=["cpu"], choices=["cpu", "vulkan"])
    parser.add_argument("--strategies", nargs="+", default=STRATEGIES, choices=STRATEGIES)
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=90)
    parser.add_argument("--csv", help="write the table as CSV")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for backend in args.backends:
            for strategy in args.strategies:
                work = Path(tmp) / f"{backend}-{strategy}"
                work.mkdir()
                rows.append(measure(args, backend, strategy, work))
    print("| backend | strategy | decode ms | upload ms | counting ms | strategy ms | ready ms | light sampler ms a pass |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['backend']} | `{r['strategy']}` | {r['decode_ms']:.2f} | {r['upload_ms']:.2f} | "
              f"{r['counting_ms']:.2f} | {r['strategy_ms']:.2f} | {r['ready_ms']:.2f} | {r['sampler_ms_per_frame']:.2f} |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
