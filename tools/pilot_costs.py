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
(least squares on the relative error). The unit costs are b_strategy and
the median over the scenes of c / a_scene. Prints a Markdown table and the unit costs; writes what it measured as CSV.

  tools/pilot_costs.py --render build/bin/trs-render scenes/real/*/ scenes/neon-sign --csv costs.csv
  tools/pilot_costs.py --rows costs.csv      # the same fit again, without rendering
"""
import argparse
import csv
import statistics
import sys
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


def fit(scenes, steps=100):
    """Each scene's ms a ray, and each strategy's light sample in rays, from `scenes`: a list of
    each scene's rows, one a strategy in STRATEGIES' order. Gauss-Newton steps on the errors
    relative to each time, so that every scene counts alike; the model is bilinear, and they
    converge where alternating between the two sets of unknowns crawls."""
    t = np.array([[r["tracing_ms"] for r in rows] for rows in scenes])
    rays = np.array([[r["rays"] for r in rows] for rows in scenes])
    samples = np.array([[r["light_samples"] for r in rows] for rows in scenes])
    count, strategies = t.shape
    b = np.full(strategies, 0.15)
    x = rays + b * samples
    a = (x / t).sum(axis=1) / (x * x / t**2).sum(axis=1)
    for _ in range(steps):
        x = rays + b * samples
        error = (t - a[:, None] * x) / t
        jacobian = np.zeros((count, strategies, count + strategies))
        for i in range(count):
            jacobian[i, :, i] = x[i] / t[i]
            jacobian[i, range(strategies), count + np.arange(strategies)] = a[i] * samples[i] / t[i]
        step = np.linalg.lstsq(jacobian.reshape(count * strategies, -1), error.ravel(), rcond=None)[0]
        a, b = a + step[:count], b + step[count:]
        if np.abs(step[count:]).max() < 1e-12 * max(1.0, np.abs(b).max()):
            break
    return a, b


def sampler_try_cost(rows, ray_ms):
    """A try of the light sampler, in rays, from a scene's rows of the strategies that draw."""
    drawn = [r for r in rows if r["tries"] > 0]
    return sum(r["sampler_ms"] for r in drawn) / sum(r["tries"] for r in drawn) / ray_ms


def measured(args):
    """Each scene's name and its rows (one a strategy), rendered."""
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
    return names, scenes


def read_rows(path):
    """Each scene's name and its rows, from a CSV this tool wrote."""
    scenes = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            name, strategy = row.pop("scene"), row.pop("strategy")
            scenes.setdefault(name, {})[strategy] = {k: float(v) for k, v in row.items()}
    missing = [name for name, rows in scenes.items() if set(rows) != set(STRATEGIES)]
    if missing:
        sys.exit(f"pilot_costs: {path}: {', '.join(missing)} lack a row of each of {', '.join(STRATEGIES)}")
    return list(scenes), [[rows[s] for s in STRATEGIES] for rows in scenes.values()]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes", nargs="*", help="scene folders (scenes/neon-sign) or glTF files")
    p.add_argument("--render", default="build/bin/trs-render")
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=180)
    p.add_argument("--max-depth", type=int, default=3)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--repeats", type=int, default=3, help="runs of each strategy; the median of each figure")
    p.add_argument("--csv", type=Path, help="where to write what was measured")
    p.add_argument("--rows", type=Path, help="fit what an earlier --csv holds instead of rendering")
    args = p.parse_args()
    if bool(args.scenes) == bool(args.rows):
        p.error("give scenes to render, or --rows")

    names, scenes = read_rows(args.rows) if args.rows else measured(args)
    ray_ms, light_sample_cost = fit(scenes)
    tries = [sampler_try_cost(rows, a) for rows, a in zip(scenes, ray_ms)]
    print("\n| scene | ns a ray | sampler try (rays) | " + " | ".join(f"{s} ms a pass (fit)" for s in STRATEGIES) + " |")
    print("|---|---|---|" + "---|" * len(STRATEGIES))
    for name, rows, a, c in zip(names, scenes, ray_ms, tries):
        cells = [f"{r['tracing_ms']:.1f} ({a * (r['rays'] + b * r['light_samples']):.1f})"
                 for r, b in zip(rows, light_sample_cost)]
        print(f"| {name} | {1e6 * a:.0f} | {c:.3f} | " + " | ".join(cells) + " |")
    print(f"\nsampler try: {statistics.median(tries):.3f} rays (the median over the scenes)")
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
