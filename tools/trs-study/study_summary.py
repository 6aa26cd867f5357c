"""summary.md: the study's tables of relMSE, ratios to uniform, means over the lit pixels, worst
frames and light counts, the machines the renders ran on, and its pictures."""

from study_measure import BLOCK
from study_results import animated, groups, series_name

# What each picture shows, as summary.md describes it.
PICTURES = {"convergence.png": "relMSE at equal samples and at equal time",
            "lights.png": "relMSE against lights per pass",
            "crops.png": "crops of the reference and each strategy, with their relative error"}


def seed_ratios(base_runs, runs):
    """uniform's relMSE over the strategy's, seed by seed (the seeds both have)."""
    base = {r["seed"]: r["relmse_lit"] for r in base_runs}
    return [base[r["seed"]] / r["relmse_lit"] for r in runs if r["seed"] in base and r["relmse_lit"] > 0]


def table_head(title, prose, columns):
    """A section of summary.md up to its table's first row: its heading, its prose, the table's head."""
    return [f"## {title}", "", *prose, "", "| " + " | ".join(columns) + " |", "|---" * len(columns) + "|"]


def lights_table(rows):
    """Per strategy, budget and light count: the median relMSE per lit pixel and over lit blocks,
    and the passes rendered."""
    import numpy as np
    lines = table_head("Lights per pass",
                       [f"Medians over seeds: relMSE per lit pixel, over the means of lit {BLOCK} x {BLOCK} blocks (an",
                        "error the pixels share stays there), and the passes rendered."],
                       ["strategy", "budget", "lights", "relMSE per pixel", "relMSE, blocks", "passes"])
    cells = {}
    for r in rows:
        budget = f"{r['spp']} spp" if r["spp"] != "" else f"{r['time']:g} s"
        cells.setdefault((r["strategy"], r["spp"] == "", r["spp"] or r["time"], budget, r["lights"]), []).append(r)
    for (strategy, _, _, budget, lights), runs in sorted(cells.items()):
        median = lambda column: float(np.median([r[column] for r in runs]))
        lines.append(f"| {strategy} | {budget} | {lights:g} | {median('relmse_lit'):.4g} | {median('relmse_lit_32'):.3g} | "
                     f"{median('passes'):g} |")
    return lines + [""]


def bias_table(rows, name):
    """Each strategy's mean over the lit pixels against the reference's, over all its renders:
    an unbiased strategy's lie around 1, closer the more samples."""
    import numpy as np
    lines = table_head("Mean over the lit pixels",
                       ["Each render's mean over the lit pixels over the reference's: the mean over all renders",
                        "of the strategy, and the lowest and highest render."],
                       ["strategy", "renders", "mean", "lowest", "highest"])
    series = {}
    for r in rows:
        series.setdefault(name(r), []).append(r["mean_ratio_lit"])
    for label, ratios in sorted(series.items()):
        lines.append(f"| {label} | {len(ratios)} | {np.mean(ratios):.4f} | {min(ratios):.4f} | {max(ratios):.4f} |")
    return lines + [""]


def worst_frame_table(rows, name):
    """A sequence's frames: per strategy and budget, the mean relMSE over the frames, the frame
    worst in most seeds, and the worst frame's relMSE (medians over seeds)."""
    import numpy as np
    lines = table_head("Worst frame",
                       ["Per strategy and budget, medians over seeds: the relMSE over the lit pixels averaged over the",
                        "frames, the frame that is worst in most seeds, and the worst frame's relMSE."],
                       ["strategy", "budget", "mean over frames", "worst frame", "its relMSE", "worst / mean"])
    cells = {}
    for r in rows:
        key = (name(r), r["spp"] == "", r["spp"] or r["time"], f"{r['spp']} spp" if r["spp"] != "" else f"{r['time']:g} s")
        cells.setdefault(key, []).append(r)
    for (label, _, _, budget), runs in sorted(cells.items()):
        frames = [r["worst_frame"] for r in runs]
        frame = max(sorted(set(frames)), key=frames.count)
        mean, worst = np.median([r["relmse_lit"] for r in runs]), np.median([r["worst_relmse_lit"] for r in runs])
        lines.append(f"| {label} | {budget} | {mean:.4g} | {frame} | {worst:.4g} | {worst / mean:.2f} |")
    return lines + [""]


def machines_section(frame_rows, failed):
    """Where the renders ran, a warning where their CPU models differ (equal-time comparisons then
    compare machines too), and the renders that failed."""
    lines = []
    cpus = sorted({r["cpu"] for r in frame_rows if r["cpu"]})
    nodes = sorted({r["node"] for r in frame_rows if r["node"]})
    if nodes:
        lines += [f"Rendered on {len(nodes)} node{'s' if len(nodes) > 1 else ''} ({', '.join(nodes)}), "
                  f"CPU: {'; '.join(cpus)}.", ""]
    if len(cpus) > 1:
        lines += [f"**Warning:** the renders ran on {len(cpus)} CPU models: renders at equal time compare "
                  "the machines as well as the strategies.", ""]
    if failed:
        lines += [f"**{len(failed)} render{'s' if len(failed) > 1 else ''} failed** (outputs missing; see their "
                  "logs), left out of the tables:", ""] + [f"- `{command}`" for command in failed] + [""]
    return lines


def write_summary(directory, rows, frame_rows, lit, pictures, failed=()):
    """summary.md from the renders (rows, a sequence's frames averaged) and each frame's
    (frame_rows: the mean over the lit pixels is each render's, frame by frame), showing the
    pictures drawn (names in PICTURES); `failed`: the commands of renders that wrote nothing."""
    import numpy as np
    sequence = animated(rows)
    frames = sorted({r["frame"] for r in frame_rows})
    measured = (["relMSE of each frame against that frame's own reference, over its lit pixels: those where no",
                 f"camera sample sees an emitter ({int(lit.sum())} of {lit.size} in frame {frames[0]}), averaged over "
                 f"frames {frames[0]} to {frames[-1]}."] if sequence else
                ["relMSE against the reference, over the lit pixels: those where no camera sample sees an",
                 f"emitter ({int(lit.sum())} of {lit.size})."])
    lines = ["# Noise study", ""] + measured + [
             "Medians over seeds; the ratio is uniform's relMSE over the strategy's (above 1: less noisy",
             "than uniform), seed by seed: the median, and in brackets the lowest and highest seed.", ""]
    lines += machines_section(frame_rows, failed)
    for picture in pictures:
        lines += [f"![{PICTURES[picture]}]({picture})", ""]
    name, deviations = series_name(rows), []
    lights_of = {name(r): r["lights"] for r in rows}
    base_name = lambda label: name({"strategy": "uniform", "lights": lights_of[label]})  # same light count
    for kind, title in [("spp", "Equal samples per pixel"), ("time", "Equal time (seconds)")]:
        table = groups(rows, kind)
        if not table:
            continue
        labels = sorted(table)
        budgets = sorted({b for s in table.values() for b in s})
        lines += [f"## {title}", "", "| " + kind + " | " + " | ".join(f"{s} relMSE | {s} ratio" for s in labels) + " |",
                  "|---" * (1 + 2 * len(labels)) + "|"]
        for b in budgets:
            cells = []
            for label in labels:
                runs = table[label].get(b, [])
                base = table.get(base_name(label), {}).get(b, [])
                cells.append(f"{np.median([r['relmse_lit'] for r in runs]):.4g}" if runs else "–")
                ratios = seed_ratios(base, runs) if label != base_name(label) else []
                if ratios:
                    median = float(np.median(ratios))
                    if median > 0:  # zero where both are exact: lit pixels all black, say
                        deviations += [abs(x / median - 1) for x in ratios]
                    cells.append(f"{median:.3g}x ({min(ratios):.3g}–{max(ratios):.3g})")
                else:
                    cells.append("–")
            lines.append(f"| {b:g} | " + " | ".join(cells) + " |")
        lines.append("")
    if deviations:
        lines += [f"Seed to seed, every ratio lies within ±{100 * max(deviations):.0f} % of its median.", ""]
    if sequence:
        lines += worst_frame_table(rows, name)
    lines += bias_table(frame_rows, name)
    if len({r["lights"] for r in rows}) > 1:
        lines += lights_table(rows)
    (directory / "summary.md").write_text("\n".join(lines))
