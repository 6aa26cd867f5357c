#!/usr/bin/env python3
"""The unit costs of `auto`'s pilot, measured: what a light sample and a light-sampler try cost,
in rays.

`auto` weighs each strategy's noise against its work per pass, counted rather than timed so
that its choice is the same on every run (tracer/src/strategy_choice.cpp): rays traced, light
samples weighed (a draw and a BSDF evaluation each) and the light sampler's tries, each at a
unit cost in rays. This tool renders each scene with `power`, `trs` and `ris` (whose light
samples per ray and sampler tries differ) and fits, per scene, by least squares:

  tracing ms a pass = a rays + b light samples      (the three strategies)
  sampler ms a pass = c tries                       (trs and ris: drawing and writing the lights)

The unit costs are b / a and c / a; the median over the scenes is what the pilot takes. Prints a
Markdown table and the medians; writes a CSV.

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


def fit(rows):
    """The scene's unit costs from its strategies' rows: ms per ray, and samples and tries in rays."""
    a, b = np.linalg.lstsq(np.array([[r["rays"], r["light_samples"]] for r in rows]),
                           np.array([r["tracing_ms"] for r in rows]), rcond=None)[0]
    drawn = [r for r in rows if r["tries"] > 0]
    c = sum(r["sampler_ms"] for r in drawn) / sum(r["tries"] for r in drawn)
    return {"ray_ns": 1e6 * a, "light_sample_cost": b / a, "sampler_try_cost": c / a}


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

    fits = []
    print("| scene | ns a ray | light sample (rays) | sampler try (rays) |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for folder in args.scenes:
            scene, settings = scene_files(folder)
            rows = []
            for strategy in STRATEGIES:
                runs = [measure(args.render, scene, settings, strategy, args, Path(tmp)) for _ in range(args.repeats)]
                rows.append({key: statistics.median(r[key] for r in runs) for key in runs[0]})
            f = fit(rows)
            f["scene"] = scene.parent.name
            fits.append(f)
            print(f"| {f['scene']} | {f['ray_ns']:.0f} | {f['light_sample_cost']:.3f} | {f['sampler_try_cost']:.4f} |",
                  flush=True)
    print(f"| median | {statistics.median(f['ray_ns'] for f in fits):.0f} | "
          f"{statistics.median(f['light_sample_cost'] for f in fits):.3f} | "
          f"{statistics.median(f['sampler_try_cost'] for f in fits):.4f} |")
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=["scene", "ray_ns", "light_sample_cost", "sampler_try_cost"])
            writer.writeheader()
            writer.writerows(fits)


if __name__ == "__main__":
    main()
