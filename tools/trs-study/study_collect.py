"""--collect: the study's renders measured into results.csv, its pictures drawn and summary.md
written."""

import shlex
from pathlib import Path

import study_measure
import study_plan
import study_plots
import study_results
import study_summary


def collect(directory):
    """Measures the study's renders into results.csv, draws its pictures and writes summary.md;
    returns the names of the pictures drawn."""
    directory = Path(directory)
    references = study_measure.read_references(directory)
    rows = study_measure.measure_renders(directory, references)
    study_measure.write_results(directory, rows)
    settings = study_results.by_setting(rows)
    pictures = [study_plots.plot_convergence(directory, settings)]
    if len({r["lights"] for r in rows}) > 1:
        pictures.append(study_plots.plot_lights(directory, settings))
    first = min(references, key=lambda f: -1 if f is None else f)
    reference, lit = references[first]
    first_rows = [r for r in rows if r["frame"] == ("" if first is None else first)]
    pictures.append(study_plots.plot_crops(directory, first_rows, reference, lit))
    pictures = [name for name in pictures if name is not None]
    study_summary.write_summary(directory, settings, rows, lit, pictures, failed_renders(directory))
    return pictures


def failed_renders(directory):
    """The commands of the study's plan (RENDERS, where submitted) that left outputs unwritten."""
    plan_file = Path(directory) / study_plan.RENDERS
    if not plan_file.is_file():
        return []
    jobs = [shlex.split(line) for line in plan_file.read_text().splitlines() if line]
    return [shlex.join(job) for job in jobs if not study_plan.finished(job)]
