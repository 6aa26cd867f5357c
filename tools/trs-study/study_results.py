"""The measured rows as the pictures and the summary group them: one per render (a sequence's
frames averaged), into series and budgets."""


def by_setting(rows):
    """One row per render (strategy, budget, seed, light count): a sequence's frames averaged,
    with its worst frame; a still's row as it is."""
    import numpy as np
    settings = {}
    for r in rows:
        settings.setdefault((r["strategy"], r["spp"], r["time"], r["seed"], r["lights"]), []).append(r)
    out = []
    for runs in settings.values():
        worst = max(runs, key=lambda r: r["relmse_lit"])
        row = dict(runs[0], worst_relmse_lit=worst["relmse_lit"], worst_frame=worst["frame"], frame_count=len(runs))
        for column in ["seconds", "relmse", "relmse_lit", "rmse", "mean_ratio", "relmse_lit_32", "mean_ratio_lit",
                       "relmse_trimmed", "relmse_lit_trimmed"]:
            row[column] = float(np.mean([r[column] for r in runs]))
        out.append(row)
    return out


def animated(rows):
    return any(r["frame_count"] > 1 for r in rows)


def series_name(rows):
    """A row's curve: its strategy, and its light count where the study sweeps them."""
    swept = len({r["lights"] for r in rows}) > 1
    return lambda r: f"{r['strategy']}, {r['lights']:g} lights" if swept else r["strategy"]


def groups(rows, kind):
    """{series: {budget: [rows]}} for kind "spp" or "time"."""
    name, out = series_name(rows), {}
    for r in rows:
        if r[kind] != "":
            out.setdefault(name(r), {}).setdefault(r[kind], []).append(r)
    return out
