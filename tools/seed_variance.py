#!/usr/bin/env python3
"""The noise of each strategy of a trs-study run, from its seeds' images alone: relMSE's
variance part, per pixel the variance over the seeds of the strategy's renders over
(reference^2 + GUARD), averaged over the pixels (whole image, the lit pixels where the study has
an emitter mask, and each trimmed of the 0.1% largest as trimmed_relmse is).

relMSE against the reference adds what the reference itself misses (its own noise, a firefly it
lacks); where that is most of it, strategies of very different noise come out close, and the
more passes a strategy renders the less its relMSE falls. The seeds' spread leaves the
reference's error out: the reference only scales each pixel. Each strategy needs two seeds or
more at the budget; the ratio columns are each strategy's variances over the baseline's (above
1: noisier than the baseline).

  tools/seed_variance.py study/space-exploration --baseline ris --csv variance.csv
"""
import argparse
import csv
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "common"))
import trs_measure  # noqa: E402


def budgets(folder):
    """{(budget kind, value): {strategy: [image path, ...]}} of a study's renders."""
    table = defaultdict(lambda: defaultdict(list))
    path = folder / "results.csv"
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            budget = ("time", float(row["time"])) if row["time"] else ("spp", int(row["spp"]))
            table[budget][row["strategy"]].append(folder / row["image"])
    return table


def variance_terms(images, reference):
    """Per pixel, the variance over the images over (reference^2 + GUARD), the channels' mean."""
    import numpy as np
    stack = np.stack(images)
    return (stack.var(axis=0, ddof=1) / (reference ** 2 + trs_measure.GUARD)).mean(axis=2)


def mean_and_trimmed(terms):
    return float(terms.mean()), trs_measure.trimmed_mean(terms)


def measure(folder, baseline):
    """Rows of {budget, strategy, seeds, variance..., ratio...} for a study folder."""
    reference = trs_measure.read_exr(folder / "reference.exr")
    mask = folder / "emitter-mask.exr"
    lit = trs_measure.lit_pixels(trs_measure.read_exr(mask)) if mask.exists() else None
    rows = []
    for (kind, value), strategies in sorted(budgets(folder).items()):
        measured = {}
        for strategy, paths in sorted(strategies.items()):
            if len(paths) < 2:
                continue
            terms = variance_terms([trs_measure.read_exr(p) for p in paths], reference)
            row = {"budget": f"{kind} {value:g}", "strategy": strategy, "seeds": len(paths)}
            row["variance"], row["variance_trimmed"] = mean_and_trimmed(terms.ravel())
            if lit is not None and lit.any():
                row["variance_lit"], row["variance_lit_trimmed"] = mean_and_trimmed(terms[lit])
            measured[strategy] = row
        base = measured.get(baseline)
        for row in measured.values():
            for key in [k for k in row if k.startswith("variance")]:
                row[key.replace("variance", "ratio")] = row[key] / base[key] if base and base[key] > 0 else float("nan")
            rows.append(row)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study", type=Path, help="a trs-study --out folder")
    parser.add_argument("--baseline", required=True, help="the strategy the others are compared with")
    parser.add_argument("--csv", type=Path, help="write the rows as CSV")
    args = parser.parse_args()
    if not (args.study / "results.csv").exists():
        sys.exit(f"seed_variance: {args.study / 'results.csv'}: no such file (a trs-study --out folder)")
    rows = measure(args.study, args.baseline)
    columns = ["budget", "strategy", "seeds"] + sorted({k for r in rows for k in r} - {"budget", "strategy", "seeds"},
                                                       key=lambda k: (k.startswith("ratio"), k))
    print("| " + " | ".join(columns) + " |\n|" + "---|" * len(columns))
    for r in rows:
        print("| " + " | ".join(f"{r[c]:.4g}" if isinstance(r.get(c), float) else str(r.get(c, "")) for c in columns) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=columns)
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
