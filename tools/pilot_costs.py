#!/usr/bin/env python3
"""The unit costs of `auto`'s pilot, measured: what a light sample of each strategy and a
light-sampler try cost, in rays.

`auto` weighs each strategy's noise against its work per pass, counted rather than timed so
that its choice is the same on every run (tracer/src/strategy_choice.cpp): rays traced, light
samples weighed and the light sampler's tries, each at a unit cost in rays. A light sample costs
each strategy differently: `power` draws a point on a triangle and reads its textures there,
`trs` and `ris` pick a point light whose radiance its record carries, and `ris` evaluates each
candidate's contribution. This tool renders each scene with the three and fits

  tracing ms a pass = a_scene (rays + b_strategy light samples)
  sampler ms a pass = c tries                    (trs and ris: drawing and writing the lights)

a_scene, what a ray costs in that scene, per scene, and b_strategy over all the scenes together
(least squares on the relative error, by alternating the two). The unit costs are b_strategy and
the median over the scenes of c / a_scene. Prints a Markdown table and the unit costs; writes what it measured as CSV.

  tools/pilot_costs.py --render build/bin/trs-render scenes/real/*/ scenes/neon-sign --csv costs.csv
"""
import argparse
import csv
import statistics
import tempfile
from pathlib import Path

import numpy as np

from setup_cost import render_stats, scene_files

STRATEGIES = ["power", "trs", "ris"]


def measure(render, scene, settings, strategy, args, work):
    s = render_stats("pilot_costs", render, scene, settings, ["--strategy", strategy, "--threads", str(args.threads)],
                     args, work)
    passes = max(s["passes"], 1)
    acceptance = s["acceptance_rate"] or 0.0
    return {"tracing_ms": s["tracing_ms_per_pass"],
            "sampler_ms": (s["sampler_ms_per_pass"] or 0.0) + (s["light_records_ms_per_pass"] or 0.0),
            "rays": s["rays"] / passes,
            "light_samples": s["light_samples"] / passes,
            "tries": (s["lights_per_pass"] or 0.0) / acceptance if acceptance > 0 else 0.0}


def fit(scenes, sweeps=200):
    """Each scene's ms a ray, and each strategy's light sample in rays, from `scenes`: a list of
    each scene's rows, one a strategy in STRATEGIES' order."""
    t = np.array([[r["tracing_ms"] for r in rows] for rows in scenes])
    rays = np.array([[r["rays"] for r in rows] for rows in scenes])
    samples = np.array([[r["light_samples"] for r in rows] for rows in scenes])
    w = 1.0 / t**2  # each row's error relative to its time, so that every scene counts alike
    b = np.full(len(STRATEGIES), 0.15)
    for _ in range(sweeps):
        x = rays + b * samples
        a = (w * t * x).sum(axis=1) / (w * x * x).sum(axis=1)
        y = a[:, None] * samples
        b = (w * (t - a[:, None] * rays) * y).sum(axis=0) / (w * y * y).sum(axis=0)
    return a, b


def sampler_try_cost(rows, ray_ms):
    """A try of the light sampler, in rays, from a scene's rows of the strategies that draw."""
    drawn = [r for r in rows if r["tries"] > 0]
    return sum(r["sampler_ms"] for r in drawn) / sum(r["tries"] for r in drawn) / ray_ms


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes", nargs="+", help="scene folders (scenes/neon-sign) or glTF files")
    p.add_argument("--render", default="build/bin/trs-render")
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=180)
    p.add_argument("--max-depth", type=int, default=3)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--repeats", type=int, default=3, help="runs of each strategy; the median of each figure")
    p.add_argument("--csv", type=Path)
    args = p.parse_args()

    names, scenes = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for folder in args.scenes:
            scene, settings = scene_files(folder)
            rows = []
            for strategy in STRATEGIES:
                runs = [measure(args.render, scene, settings, strategy, args, Path(tmp)) for _ in range(args.repeats)]
                rows.append({key: statistics.median(r[key] for r in runs) for key in runs[0]})
            names.append(str(scene.parent))
            scenes.append(rows)
            print(f"{names[-1]}: measured", flush=True)
    ray_ms, light_sample_cost = fit(scenes)
    tries = [sampler_try_cost(rows, a) for rows, a in zip(scenes, ray_ms)]
    print("\n| scene | ns a ray | sampler try (rays) | " + " | ".join(f"{s} ms a pass (fit)" for s in STRATEGIES) + " |")
    print("|---|---|---|" + "---|" * len(STRATEGIES))
    for name, rows, a, c in zip(names, scenes, ray_ms, tries):
        cells = [f"{r['tracing_ms']:.1f} ({a * (r['rays'] + b * r['light_samples']):.1f})"
                 for r, b in zip(rows, light_sample_cost)]
        print(f"| {name} | {1e6 * a:.0f} | {c:.4f} | " + " | ".join(cells) + " |")
    print(f"\nsampler try: {statistics.median(tries):.4f} rays (the median over the scenes)")
    for strategy, b in zip(STRATEGIES, light_sample_cost):
        print(f"light sample of {strategy}: {b:.3f} rays")
    if args.csv:  # what was measured, to fit again
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=["scene", "strategy", *scenes[0][0]])
            writer.writeheader()
            for name, rows in zip(names, scenes):
                writer.writerows({"scene": name, "strategy": s, **r} for s, r in zip(STRATEGIES, rows))


if __name__ == "__main__":
    main()
