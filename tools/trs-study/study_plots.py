"""The study's pictures: convergence.png, lights.png and crops.png. matplotlib draws them without a
display (Agg)."""

import trs_measure
from study_measure import BLOCK, read_exr
from study_results import animated, groups, series_name


def spread(axis, points, label, **style):
    """One curve of medians over seeds, with their range shaded; points: (x, [values])."""
    import numpy as np
    x = np.array([p[0] for p in points])
    values = [np.array(p[1]) for p in points]
    line, = axis.plot(x, [np.median(v) for v in values], marker="o", label=label, **style)
    axis.fill_between(x, [v.min() for v in values], [v.max() for v in values], alpha=0.2, color=line.get_color())
    return line


def log_axes(axis, xlabel, ticks, ylabel="relMSE over lit pixels"):
    """Log-log, with the x ticks at the budgets measured; an axis without curves says so."""
    import matplotlib.ticker
    if not ticks:
        axis.text(0.5, 0.5, "no runs", ha="center", va="center", transform=axis.transAxes)
        axis.set_xticks([])
        axis.set_yticks([])
        return
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xticks(sorted(set(ticks)))
    axis.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%.3g"))
    axis.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    axis.set_xlabel(xlabel)
    axis.set_ylabel(ylabel)
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(fontsize="small")


def two_panels(directory, name, title, draw):
    """A figure of equal samples (left) and equal time (right); draw(axis, kind) fills a panel.
    Returns its name."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for axis, kind in zip(axes, ["spp", "time"]):
        draw(axis, kind)
        axis.set_title(f"at equal {'samples' if kind == 'spp' else 'time'}")
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(directory / name, dpi=110)
    plt.close(figure)
    return name


def bars(axis, series, unit, colours):
    """One budget: each strategy's median relMSE as a bar at that budget, the range over seeds as
    an error bar (a sequence's worst frame as a black tick). A line through a single budget would
    read as a trend where there is none."""
    import numpy as np
    labels = sorted(series)
    runs_of = [[r for runs in series[label].values() for r in runs] for label in labels]
    values = [np.array([r["relmse_lit"] for r in runs]) for runs in runs_of]
    medians = np.array([np.median(v) for v in values])
    errors = [medians - [v.min() for v in values], [v.max() for v in values] - medians]
    axis.bar(range(len(labels)), medians, yerr=errors, capsize=4, color=[colours[label] for label in labels])
    if animated([r for runs in runs_of for r in runs]):
        worst = [np.median([r["worst_relmse_lit"] for r in runs]) for runs in runs_of]
        axis.scatter(range(len(labels)), worst, marker="_", s=400, color="black", label="worst frame", zorder=3)
        axis.legend(fontsize="small")
    axis.set_xticks(range(len(labels)), labels, rotation=30, ha="right", fontsize="small")
    axis.set_yscale("log")
    budget = next(iter(series[labels[0]]))
    axis.set_xlabel(f"at {budget:g} {unit}")
    axis.set_ylabel("relMSE over lit pixels")
    axis.grid(True, axis="y", which="both", alpha=0.3)


def plot_convergence(directory, rows):
    import numpy as np

    def draw(axis, kind):
        series = groups(rows, kind)
        if len({b for budgets in series.values() for b in budgets}) == 1:
            bars(axis, series, "spp" if kind == "spp" else "s", colours)
            return
        ticks = []
        for label, budgets in sorted(series.items()):
            # x: the budget (spp), or the mean seconds actually spent (time).
            x = [b if kind == "spp" else float(np.mean([r["seconds"] for r in runs])) for b, runs in sorted(budgets.items())]
            line = spread(axis, list(zip(x, [[r["relmse_lit"] for r in runs] for _, runs in sorted(budgets.items())])),
                          label, color=colours[label])
            if sequence:
                spread(axis, list(zip(x, [[r["worst_relmse_lit"] for r in runs] for _, runs in sorted(budgets.items())])),
                       f"{label}, worst frame", linestyle="--", color=line.get_color())
            ticks += list(budgets)
        log_axes(axis, "samples per pixel" if kind == "spp" else
                 f"seconds{' a frame' if sequence else ''} (wall, set-up included)", ticks)

    sequence = animated(rows)
    # One colour per strategy in both panels, whichever budgets each has.
    colours = {label: f"C{i}" for i, label in enumerate(sorted({series_name(rows)(r) for r in rows}))}
    what = ("each frame's relMSE against its own reference over its lit pixels (no emitter seen): the mean over "
            "frames\nand the worst frame" if sequence else
            "relMSE against the reference over the lit pixels (no emitter seen)")
    return two_panels(directory, "convergence.png", f"{what}; median and range over seeds", draw)


def plot_lights(directory, rows):
    """relMSE against lights per pass, per pixel and over 32 x 32 blocks, one curve per
    strategy and budget."""
    def draw(axis, kind):
        ticks = []
        for column, scale, style in [("relmse_lit", "per pixel", "-"), ("relmse_lit_32", f"{BLOCK}² blocks", "--")]:
            curves = {}
            for r in rows:
                if r[kind] != "":
                    curves.setdefault((r["strategy"], r[kind]), {}).setdefault(r["lights"], []).append(r[column])
            for (strategy, budget), by_lights in sorted(curves.items()):
                unit = "spp" if kind == "spp" else "s"
                spread(axis, sorted(by_lights.items()), f"{strategy}, {budget:g} {unit}, {scale}", linestyle=style)
                ticks += list(by_lights)
        log_axes(axis, "point lights per pass", ticks, "relMSE, lit pixels or blocks")

    return two_panels(directory, "lights.png",
                      f"relMSE against lights per pass, per lit pixel (solid) and over lit {BLOCK} x {BLOCK} "
                      "blocks (dashed); median and range over seeds", draw)


def lit_crop(lit, reference):
    """A third of the image on a side, among the lit pixels (those the noise figures measure): of
    the windows on a grid of eighths of a window, those with at least nine tenths as many lit
    pixels as the most lit one (a crop is mostly emitter only where every window nearly is); of
    these, the one whose lit pixels hold the most of the reference's light, where the noise shows.
    The centre where nothing is lit."""
    import numpy as np
    h, w = lit.shape
    ch, cw = max(h // 3, 1), max(w // 3, 1)
    ys, xs = np.arange(0, h - ch + 1, max(ch // 8, 1)), np.arange(0, w - cw + 1, max(cw // 8, 1))

    def window_sums(values):
        """The sum of values over each window (a summed-area table)."""
        table = np.pad(values.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
        return (table[np.ix_(ys + ch, xs + cw)] - table[np.ix_(ys, xs + cw)] - table[np.ix_(ys + ch, xs)]
                + table[np.ix_(ys, xs)])

    lit_counts = window_sums(lit.astype(float))
    if lit_counts.max() == 0:
        y0, x0 = (h - ch) // 2, (w - cw) // 2
    else:
        brightness = reference.mean(axis=2)
        light = window_sums(np.where(lit, brightness / (1.0 + brightness), 0.0))
        y, x = np.unravel_index(np.where(lit_counts >= 0.9 * lit_counts.max(), light, -1.0).argmax(), light.shape)
        y0, x0 = int(ys[y]), int(xs[x])
    return (slice(y0, y0 + ch), slice(x0, x0 + cw))


def plot_crops(directory, rows, reference, lit):
    """crops.png, where the study has renders at a sample count; returns its name, or None."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    # The largest spp (and light count) of each strategy, seed 1; the crop lit_crop chooses.
    chosen = {}
    for r in rows:
        best = chosen.get(r["strategy"])
        if r["spp"] != "" and r["seed"] == 1 and (best is None or (r["spp"], r["lights"]) > (best["spp"], best["lights"])):
            chosen[r["strategy"]] = r
    if not chosen:
        return None
    crop = lit_crop(lit, reference)
    tonemap = lambda x: np.clip(x / (1 + x), 0, 1) ** (1 / 2.2)
    columns, aspect = len(chosen) + 1, (crop[0].stop - crop[0].start) / (crop[1].stop - crop[1].start)
    figure, axes = plt.subplots(2, columns, figsize=(3 * columns + 1, 6 * aspect + 1), squeeze=False,
                                layout="constrained")
    axes[0][0].imshow(tonemap(reference[crop]))
    axes[0][0].set_title("reference")
    axes[1][0].imshow(np.where(lit[crop], 0.0, 1.0), cmap="gray", vmin=0, vmax=1)
    axes[1][0].set_title("left out (emitter seen)")
    for column, (strategy, r) in enumerate(sorted(chosen.items()), start=1):
        image = read_exr(directory / r["image"])
        axes[0][column].imshow(tonemap(image[crop]))
        axes[0][column].set_title(f"{strategy}, {r['spp']} spp")
        error = trs_measure.relative_errors(image[crop], reference[crop]).mean(axis=2)
        shown = axes[1][column].imshow(np.log10(np.maximum(error, 1e-6)), cmap="inferno", vmin=-4, vmax=1)
        axes[1][column].set_title(f"relMSE {r['relmse_lit']:.3g} (lit)")
    for axis in axes.flat:
        axis.set_xticks([])
        axis.set_yticks([])
    figure.colorbar(shown, ax=axes[1].tolist(), label="log10 relative error")
    figure.savefig(directory / "crops.png", dpi=110)
    plt.close(figure)
    return "crops.png"
