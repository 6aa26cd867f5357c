"""The study's renders measured against their frame's reference (trs_measure's relMSE, over the
whole image, the lit pixels and lit blocks, and trimmed of its largest pixel errors) into the rows
of results.csv."""

import csv
import json
import sys

import study_plan
import trs_measure

CSV_COLUMNS = ["strategy", "spp", "time", "seed", "seconds", "passes", "relmse", "relmse_lit", "rmse",
               "mean_ratio", "image", "lights", "relmse_lit_32", "mean_ratio_lit", "frame", "node", "cpu",
               "relmse_trimmed", "relmse_lit_trimmed"]
BLOCK = 32  # pixels on a side of the blocks relmse_lit_32 averages over


def read_exr(path):
    """An image's RGB (trs_measure.read_exr), or the study stops with the reason."""
    try:
        return trs_measure.read_exr(path)
    except OSError as e:
        raise SystemExit(f"trs-study: error: {e}")


def block_means(image):
    """Means over BLOCK x BLOCK pixels (the last partial row and column of blocks left out)."""
    h, w = image.shape[0] // BLOCK * BLOCK, image.shape[1] // BLOCK * BLOCK
    return image[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, image.shape[2]).mean(axis=(1, 3))


def measure(image, reference, lit):
    """relMSE per pixel, and over the means of lit blocks: there an error that pixels share (one
    frame's light set, say) stays while independent noise averages out."""
    import numpy as np
    lit_blocks = block_means(lit[:, :, None].astype(float))[:, :, 0] == 1.0
    return {"relmse": trs_measure.relmse(image, reference),
            "relmse_lit": trs_measure.relmse(image, reference, lit),
            "rmse": float(np.sqrt(((image - reference) ** 2).mean())),
            "mean_ratio": mean_ratio(image, reference),
            "relmse_lit_32": trs_measure.relmse(block_means(image), block_means(reference), lit_blocks),
            "mean_ratio_lit": mean_ratio(image[lit], reference[lit]),
            "relmse_trimmed": trs_measure.trimmed_relmse(image, reference),
            "relmse_lit_trimmed": trs_measure.trimmed_relmse(image, reference, lit)}


def mean_ratio(image, reference):
    """The image's mean over the reference's: 1 for an unbiased render, up to noise."""
    return float(image.mean() / reference.mean()) if reference.mean() > 0 else float("nan")


def read_references(directory):
    """{frame: (reference, lit pixels)}: the study's reference and emitter mask, or each
    animation frame's (frame None for a still)."""
    names = {None: ("reference.exr", "emitter-mask.exr")} if (directory / "reference.exr").exists() else {}
    for path in directory.glob("reference.*.exr"):
        number = path.name.split(".")[1]
        if number.isdigit() and len(path.name.split(".")) == 3:
            names[int(number)] = (path.name, f"emitter-mask.{number}.exr")
    if not names:
        raise SystemExit(f"trs-study: error: {directory / 'reference.exr'}: no reference")
    references = {}
    for frame, (reference_name, mask_name) in names.items():
        reference = read_exr(directory / reference_name)
        if not (directory / mask_name).exists():
            raise SystemExit(f"trs-study: error: {directory / mask_name}: no emitter mask for {reference_name}")
        mask = read_exr(directory / mask_name)
        if mask.shape != reference.shape:
            raise SystemExit(f"trs-study: error: {directory / mask_name}: not the reference's size")
        references[frame] = (reference, trs_measure.lit_pixels(mask))
    return references


def passes(stats):
    """The passes a render's stats count; earlier versions of trs-render call them "frames"."""
    return stats["passes"] if "passes" in stats else stats["frames"]


def measure_renders(directory, references):
    """A row per render of the study in `directory` (per frame, for a sequence), measured against
    its frame's reference (read_references); an interrupted render is left out, with a warning."""
    rows = []
    for stats_file in sorted((directory / "images").glob("*.json")):
        stats = json.loads(stats_file.read_text())
        if stats.get("interrupted", False):
            sys.stderr.write(f"trs-study: warning: {stats_file}: an interrupted render, left out\n")
            continue
        settings, frame = stats["settings"], stats.get("frame")
        if frame not in references:
            raise SystemExit(f"trs-study: error: {stats_file}: no reference for "
                             f"{'a still' if frame is None else f'frame {frame}'} in {directory}")
        reference, lit = references[frame]
        image = read_exr(stats_file.with_suffix(".exr"))
        if image.shape != reference.shape:
            raise SystemExit(f"trs-study: error: {stats_file.with_suffix('.exr')}: not the reference's size")
        named = study_plan.IMAGE_NAME.match(stats_file.stem if frame is None else stats_file.stem.rsplit(".", 1)[0])
        row = {"strategy": named["strategy"] if named else settings["strategy"], "spp": "" if settings["time"] is not None else settings["spp"],
               "time": settings["time"] if settings["time"] is not None else "", "seed": settings["seed"],
               "seconds": stats["wall_seconds"], "passes": passes(stats),
               "image": str(stats_file.with_suffix(".exr").relative_to(directory)), "lights": settings["lights"],
               "frame": "" if frame is None else frame}
        row.update(measure(image, reference, lit))
        row.update(stats.get("host", {"node": "", "cpu": ""}))
        rows.append(row)
    if not rows:
        raise SystemExit(f"trs-study: error: {directory / 'images'}: no renders to measure")
    return rows


def write_results(directory, rows):
    """results.csv: the rows, in CSV_COLUMNS."""
    with open(directory / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=CSV_COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
