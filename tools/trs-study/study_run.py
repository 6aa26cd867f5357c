"""The study's renders run here, one at a time: time budgets mean nothing when renders share the
processor."""

import shlex
import subprocess
import sys

import study_plan


def remaining(jobs):
    """--resume: the renders whose outputs are not all there. A sequence cut short renders only the
    frames it has not written whole."""
    return [job + (["--resume"] if study_plan.job_frames(job) is not None else []) for job in jobs
            if not study_plan.finished(job)]


def run_jobs(jobs, quiet):
    for i, job in enumerate(jobs):
        if not quiet and sys.stderr.isatty():
            done = int(40 * i / len(jobs))
            sys.stderr.write(f"\r[{'#' * done}{'.' * (40 - done)}] render {i + 1}/{len(jobs)} ")
            sys.stderr.flush()
        result = subprocess.run(job, capture_output=True, text=True)
        if result.returncode != 0:
            sys.stderr.write("\n")
            raise SystemExit(f"trs-study: error: a render failed (status {result.returncode}): "
                             f"{shlex.join(job)}\n{result.stderr}")
    if not quiet and sys.stderr.isatty():
        sys.stderr.write(f"\r[{'#' * 40}] {len(jobs)} renders done\n")
