#!/usr/bin/env python3
"""The unit costs of `auto`'s pilot, measured: what a light sample of each strategy, a
light-sampler try and an evaluation of `restir`'s target cost, in rays.

`auto` weighs each strategy's noise against its work per pass, counted rather than timed so
that its choice is the same on every run (tracer/src/strategy_choice.cpp): rays traced, light
samples weighed and the light sampler's tries, each at a unit cost in rays. A light sample costs
each strategy differently: `power` draws a point on a triangle and reads its textures there,
`trs` and `ris` pick a point light whose radiance its record carries, and `ris` evaluates each
candidate's contribution. This tool renders each scene with the three and fits

  tracing ms a pass = a_scene (rays + b_strategy light samples)
  sampler ms a pass = c tries                    (trs and ris: drawing and writing the lights)

a_scene, what a ray costs in that scene, per scene, and b_strategy over all the scenes together
(least squares on the relative error). It renders `restir` too, and fits its reuse's costs over
all the scenes together (linear least squares on the relative error), with a_scene and b_ris as
fitted:

  restir's ms a pass = a_scene (rays + b_ris (light samples + its reservoirs' candidates)
                                + e reservoirs + d target evaluations)

a reservoir being a camera ray's first surface, shaded and kept: one a path. The unit costs are
b_strategy, the median over the scenes of c / a_scene, e and d. Prints a Markdown table and the unit costs; writes what it measured as CSV.

  tools/pilot_costs.py --render build/bin/trs-render scenes/real/*/ scenes/neon-sign --csv costs.csv
  tools/pilot_costs.py --rows costs.csv      # the same fit again, without rendering
  tools/pilot_costs.py --rows costs.csv --light-sample-costs 1.53,1.15,0.56   # the rest at auto's
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
REUSE = "restir"  # weighed by the pilot on blocks, its reuse's work beside ris's


def measure(render, scene, settings, strategy, args, work):
    s = render_stats("pilot_costs", render, scene, settings, ["--strategy", strategy, "--threads", str(args.threads)],
                     args, work)
    passes = max(s["passes"], 1)
    acceptance = s["acceptance_rate"] or 0.0
    return {"tracing_ms": s["tracing_ms_per_pass"],
            "sampler_ms": (s["sampler_ms_per_pass"] or 0.0) + (s["light_records_ms_per_pass"] or 0.0),
            "rays": s["rays"] / passes,
            "light_samples": s["light_samples"] / passes,
            "tries": (s["lights_per_pass"] or 0.0) / acceptance if acceptance > 0 else 0.0,
            # restir's reuse: its time, the camera rays of its reservoirs (a path's each), their
            # candidates and its target evaluations
            "reuse_ms": s["reuse_ms_per_pass"] or 0.0,
            "camera_rays": s["paths"] / passes,
            "reuse_candidates": s["reuse_candidates"] / passes,
            "targets": s["reuse_target_evaluations"] / passes}


def passes(scenes):
    """Each scene's tracing time, rays and light samples a pass, a row a scene."""
    return tuple(np.array([[r[key] for r in rows] for rows in scenes]) for key in ("tracing_ms", "rays", "light_samples"))


def ray_ms_given(scenes, light_sample_cost):
    """Each scene's ms a ray, at the light samples' costs given (least squares on the errors
    relative to each time)."""
    t, rays, samples = passes(scenes)
    x = rays + np.asarray(light_sample_cost) * samples
    return (x / t).sum(axis=1) / (x * x / t**2).sum(axis=1)


def fit(scenes, steps=100):
    """Each scene's ms a ray, and each strategy's light sample in rays, from `scenes`: a list of
    each scene's rows, one a strategy in STRATEGIES' order. Gauss-Newton steps on the errors
    relative to each time, so that every scene counts alike; the model is bilinear, and they
    converge where alternating between the two sets of unknowns crawls."""
    t, rays, samples = passes(scenes)
    count, strategies = t.shape
    b = np.full(strategies, 0.15)
    a = ray_ms_given(scenes, b)
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


def reuse_costs(reuse_rows, ray_ms, ris_sample_cost):
    """restir's reservoir and target evaluation, in rays (e, d), from each scene's `restir` row
    and cost a ray: what its pass takes beyond its rays and light samples at their costs, fitted
    to its reservoirs and evaluations, each scene's error relative to its pass. None where no
    scene evaluated a target."""
    equations, rhs = [], []
    for r, a in zip(reuse_rows, ray_ms):
        if r is None or not r["targets"] > 0:
            continue
        whole = (r["tracing_ms"] + r["reuse_ms"]) / a  # the pass, in rays
        rest = whole - r["rays"] - ris_sample_cost * (r["light_samples"] + r["reuse_candidates"])
        equations.append([r["camera_rays"] / whole, r["targets"] / whole])
        rhs.append(rest / whole)
    if not equations:
        return None
    return tuple(np.linalg.lstsq(np.array(equations), np.array(rhs), rcond=None)[0])


def measured(args):
    """Each scene's name and its rows (one a strategy), rendered."""
    names, scenes = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for folder in args.scenes:
            scene, settings = scene_files(folder)
            rows = []
            for strategy in [*STRATEGIES, REUSE]:
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
    missing = [name for name, rows in scenes.items() if not set(STRATEGIES) <= set(rows)]
    if missing:
        sys.exit(f"pilot_costs: {path}: {', '.join(missing)} lack a row of each of {', '.join(STRATEGIES)}")
    # A restir row is optional: CSVs written before it was measured lack it.
    return list(scenes), [[rows[s] for s in STRATEGIES if s in rows] + ([rows[REUSE]] if REUSE in rows else [])
                          for rows in scenes.values()]


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
    p.add_argument("--light-sample-costs", type=lambda text: [float(c) for c in text.split(",")],
                   help="the light samples' costs, in STRATEGIES' order (1.53,1.15,0.56), to fit the rest at: "
                        "the reuse's costs at those auto uses, whose level the passes know only roughly")
    args = p.parse_args()
    if bool(args.scenes) == bool(args.rows):
        p.error("give scenes to render, or --rows")

    names, rows_read = read_rows(args.rows) if args.rows else measured(args)
    scenes = [rows[:len(STRATEGIES)] for rows in rows_read]
    reuse_rows = [rows[len(STRATEGIES)] if len(rows) > len(STRATEGIES) else None for rows in rows_read]
    if args.light_sample_costs:
        if len(args.light_sample_costs) != len(STRATEGIES):
            p.error(f"--light-sample-costs takes {len(STRATEGIES)} costs, one for each of {', '.join(STRATEGIES)}")
        light_sample_cost = np.array(args.light_sample_costs)
        ray_ms = ray_ms_given(scenes, light_sample_cost)
    else:
        ray_ms, light_sample_cost = fit(scenes)
    ris_cost = light_sample_cost[STRATEGIES.index("ris")]
    reuse = reuse_costs(reuse_rows, ray_ms, ris_cost)
    tries = [sampler_try_cost(rows, a) for rows, a in zip(scenes, ray_ms)]
    print("\n| scene | ns a ray | sampler try (rays) | " + " | ".join(f"{s} ms a pass (fit)" for s in [*STRATEGIES, REUSE]) + " |")
    print("|---|---|---|" + "---|" * (len(STRATEGIES) + 1))
    for name, rows, a, c, r in zip(names, scenes, ray_ms, tries, reuse_rows):
        cells = [f"{r['tracing_ms']:.1f} ({a * (r['rays'] + b * r['light_samples']):.1f})"
                 for r, b in zip(rows, light_sample_cost)]
        if r is not None and reuse is not None:
            e, d = reuse
            fitted = a * (r["rays"] + ris_cost * (r["light_samples"] + r["reuse_candidates"]) + e * r["camera_rays"] +
                          d * r["targets"])
            cells.append(f"{r['tracing_ms'] + r['reuse_ms']:.1f} ({fitted:.1f})")
        else:
            cells.append("")
        print(f"| {name} | {1e6 * a:.0f} | {c:.3f} | " + " | ".join(cells) + " |")
    print(f"\nsampler try: {statistics.median(tries):.3f} rays (the median over the scenes)")
    if reuse is not None:
        print(f"{REUSE}'s reservoir: {reuse[0]:.3f} rays; its target evaluation: {reuse[1]:.3f} rays")
    for strategy, b in zip(STRATEGIES, light_sample_cost):
        print(f"light sample of {strategy}: {b:.3f} rays")
    if args.csv:  # what was measured, to fit again
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=["scene", "strategy", *rows_read[0][0]])
            writer.writeheader()
            for name, rows in zip(names, rows_read):
                writer.writerows({"scene": name, "strategy": s, **r} for s, r in zip([*STRATEGIES, REUSE], rows))

if __name__ == "__main__":
    main()
