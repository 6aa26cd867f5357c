#!/usr/bin/env python3
"""The noise of strategies over several scenes, from the results of trs-study runs.

For each study directory (one scene each, trs-study's --out), each strategy's lit-pixel relMSE
against a baseline's (the baseline's relMSE over the strategy's: above 1 is less noisy than the
baseline), seed against seed, the median over the seeds (--over-seeds mean: the ratio of the
means over the seeds both have); at each time budget and each sample count the studies share
(--metric relmse: over the whole image; the _trimmed metrics leave out the 0.1% of pixels of the
largest error). Prints a Markdown table per budget with a geometric-mean row, and writes them as
CSV.

  tools/noise_summary.py study/neon-sign study/lantern --baseline tree --csv noise.csv
"""
import argparse
import csv
import math
import statistics
import sys
from collections import defaultdict
from pathlib import Path


METRICS = {"relmse_lit": "lit pixels", "relmse": "whole image", "relmse_lit_trimmed": "lit pixels, trimmed",
           "relmse_trimmed": "whole image, trimmed"}


def read_study(folder, metric):
    """{(budget kind, value): {strategy: {seed: metric}}} of one study."""
    table = defaultdict(lambda: defaultdict(dict))
    path = Path(folder) / "results.csv"
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if metric not in (reader.fieldnames or []):
            sys.exit(f"noise_summary: {path}: no column {metric} (measured by an older trs-study: "
                     f"run trs-study --collect {folder})")
        for row in reader:
            budget = ("time", float(row["time"])) if row["time"] else ("spp", int(row["spp"]))
            table[budget][row["strategy"]][row["seed"]] = float(row[metric])
    return table


def ratio(baseline, other, over_seeds="median"):
    """The baseline's relMSE over the other's on the seeds both have: seed by seed, the median
    (over_seeds "median"), or the ratio of their means ("mean")."""
    seeds = sorted(set(baseline) & set(other))
    if not seeds:
        return math.nan
    if over_seeds == "mean":
        mean_other = statistics.fmean(other[s] for s in seeds)
        return statistics.fmean(baseline[s] for s in seeds) / mean_other if mean_other > 0 else math.inf
    return statistics.median(baseline[s] / other[s] if other[s] > 0 else math.inf for s in seeds)


def label(budget):
    kind, value = budget
    return f"{value:g} s" if kind == "time" else f"{value} spp"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("studies", nargs="+", type=Path, help="trs-study output directories")
    p.add_argument("--baseline", default="tree", help="the strategy every ratio is against")
    p.add_argument("--metric", default="relmse_lit", choices=list(METRICS),
                   help="over the lit pixels (trs-study's), or over the whole image, for a scene whose lit "
                        "pixels are black (a frame of empty space); _trimmed: without the 0.1%% of pixels of "
                        "the largest error, the fireflies that decide one render's relMSE")
    p.add_argument("--over-seeds", default="median", choices=["median", "mean"],
                   help="the median of the seed-by-seed ratios, or the ratio of the means over the seeds "
                        "(the expected relMSE's, where rare bright paths decide it)")
    p.add_argument("--csv", type=Path)
    args = p.parse_args()

    studies = {folder.name: read_study(folder, args.metric) for folder in args.studies}
    budgets = sorted(set.intersection(*(set(t) for t in studies.values())))
    rows = []
    for budget in budgets:
        strategies = sorted(set.intersection(*(set(t[budget]) for t in studies.values())))
        if args.baseline not in strategies:
            sys.exit(f"noise_summary: the baseline {args.baseline} is not in every study at {label(budget)}")
        others = [s for s in strategies if s != args.baseline]
        over = "median over seeds" if args.over_seeds == "median" else "ratio of the means over seeds"
        print(f"\n{label(budget)}: {args.baseline}'s relMSE over each strategy's ({METRICS[args.metric]}, {over})\n")
        print("| scene | " + " | ".join(f"`{s}`" for s in others) + " |")
        print("|---|" + "---|" * len(others))
        logs = defaultdict(list)
        for scene, table in studies.items():
            values = {s: ratio(table[budget][args.baseline], table[budget][s], args.over_seeds) for s in others}
            for s, v in values.items():
                rows.append({"scene": scene, "budget": label(budget), "strategy": s, "baseline": args.baseline,
                             "ratio": v})
                if v > 0 and math.isfinite(v):
                    logs[s].append(math.log(v))
            print(f"| {scene} | " + " | ".join(f"{values[s]:.2f}x" for s in others) + " |")
        means = {s: math.exp(statistics.fmean(logs[s])) if logs[s] else math.nan for s in others}
        print("| geometric mean | " + " | ".join(f"{means[s]:.2f}x" for s in others) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=["scene", "budget", "strategy", "baseline", "ratio"])
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
