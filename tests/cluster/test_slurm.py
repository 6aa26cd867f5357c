"""Against a real Slurm, the one-node cluster tests/cluster/with_slurm.sh starts around this file
(ctest label `cluster`): an animation through trs-render --submit slurm --wait equals a render of
the same frames here, bit for bit; a task cancelled before it ran leaves its frames, which a
second submission renders without redoing the others; a task cancelled while it renders, with
--save-partial, leaves the passes done as a partial frame, which the next submission renders
whole; trs_render.submit() returns the job id; and a two-strategy study through trs-study
--submit slurm measures what the same study here does, times and machines aside.

Environment: SLURM_CONF (with_slurm.sh), TRS_RENDER and TRS_STUDY (the programs), TRS_SCENES (the
scenes folder), PYTHONPATH with the trs_render module."""

import csv
import json
import os
import subprocess
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest

RENDER = os.environ["TRS_RENDER"]
STUDY = os.environ["TRS_STUDY"]
SCENES = Path(os.environ["TRS_SCENES"])
VIDEO_WALL = SCENES / "video-wall" / "video-wall.gltf"
TINY = ["--width", "32", "--height", "18", "--spp", "2", "--max-depth", "2", "--threads", "1", "--quiet"]


def pixels(path):
    image = oiio.ImageInput.open(str(path))
    values = image.read_image("float")
    image.close()
    return values


def render_here(out, frames):
    subprocess.run([RENDER, VIDEO_WALL, "--frames", frames, "--out", out, *TINY], check=True, capture_output=True)


def submit(out, frames, *more):
    """trs-render --submit slurm: its exit status, standard output (the job id) and error."""
    result = subprocess.run([RENDER, VIDEO_WALL, "--frames", frames, "--out", out, *TINY, "--submit", "slurm", *more],
                            capture_output=True, text=True)
    return result.returncode, result.stdout.strip(), result.stderr


def wait_until_gone(job, seconds=180):
    """Waits until Slurm lists nothing more of `job` (done, failed or cancelled)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        listed = subprocess.run(["squeue", "-h", "-j", job], capture_output=True, text=True)
        if listed.returncode != 0 or not listed.stdout.strip():
            return
        time.sleep(1)
    pytest.fail(f"Slurm job {job} still listed after {seconds} s")


def wait_until_running(job, seconds=120):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        listed = subprocess.run(["squeue", "-h", "-j", job, "-o", "%T"], capture_output=True, text=True)
        if listed.stdout.strip() == "RUNNING":
            return
        time.sleep(0.2)
    pytest.fail(f"Slurm job {job} not running after {seconds} s")


def expect_frames_as_here(tmp_path, submitted, frames):
    render_here(tmp_path / "here" / "f.%04d.exr", f"{frames[0]}:{frames[-1]}")
    for f in frames:
        assert np.array_equal(pixels(submitted / f"f.{f:04d}.exr"), pixels(tmp_path / "here" / f"f.{f:04d}.exr")), f


def test_an_animation_through_slurm_equals_a_render_here(tmp_path):
    (tmp_path / "here").mkdir()
    status, job, err = submit(tmp_path / "slurm" / "f.%04d.exr", "0:3", "--chunk", "2", "--wait")
    assert status == 0, err
    assert job.isdigit(), job
    assert f"Slurm job {job}: frames 0:3 in 2 tasks" in err
    expect_frames_as_here(tmp_path, tmp_path / "slurm", range(4))


def test_a_cancelled_task_is_rendered_by_the_next_submission_alone(tmp_path):
    (tmp_path / "here").mkdir()
    out = tmp_path / "slurm"
    # Held, so that the task is cancelled before it runs; then the others run.
    status, job, err = submit(out / "f.%04d.exr", "0:3", "--sbatch=--hold")
    assert status == 0, err
    subprocess.run(["scancel", f"{job}_2"], check=True)
    subprocess.run(["scontrol", "release", job], check=True)
    wait_until_gone(job)
    assert not (out / "f.0002.exr").exists()
    written = {f: (out / f"f.{f:04d}.exr").stat().st_mtime_ns for f in (0, 1, 3)}
    status, again, err = submit(out / "f.%04d.exr", "0:3", "--wait")
    assert status == 0, err
    assert again != job
    assert {f: (out / f"f.{f:04d}.exr").stat().st_mtime_ns for f in (0, 1, 3)} == written
    expect_frames_as_here(tmp_path, out, range(4))


def test_a_task_cancelled_while_it_renders_keeps_its_passes_and_is_rendered_again(tmp_path):
    out = tmp_path / "slurm"
    stats_pattern = ["--stats", out / "f.%04d.json"]
    # Far more passes than the seconds before scancel allow: the frame is under way when the
    # task gets Slurm's SIGTERM, and saves what it has before KillWait's SIGKILL.
    status, job, err = submit(out / "f.%04d.exr", "0:0", *stats_pattern, "--spp", "10000000", "--save-partial")
    assert status == 0, err
    wait_until_running(job)
    time.sleep(4)  # the set-up, then passes of milliseconds each
    subprocess.run(["scancel", job], check=True)
    wait_until_gone(job)
    log = (out / f"trs-render-{job}_0.log").read_text()
    assert "interrupted; saved " in log and " spp of frame 0 as " in log, log
    assert not (out / "f.0000.exr").exists()
    assert np.isfinite(pixels(out / "f.0000.partial.exr")).all()
    stats = json.loads((out / "f.0000.partial.json").read_text())
    assert stats["interrupted"] is True and stats["passes"] >= 1, stats

    status, again, err = submit(out / "f.%04d.exr", "0:0", *stats_pattern, "--wait")
    assert status == 0, err
    stats = json.loads((out / "f.0000.json").read_text())
    assert stats["interrupted"] is False and stats["passes"] == 2, stats
    assert sorted(p.name for p in out.glob("f.*")) == ["f.0000.exr", "f.0000.json"]


def test_python_submit_returns_the_job_id(tmp_path):
    import trs_render
    job = trs_render.submit(VIDEO_WALL, frames="1:2", out=tmp_path / "py" / "f.%04d.exr", wait=True, program=RENDER,
                            width=32, height=18, spp=2, max_depth=2, threads=1, quiet=True)
    assert job.isdigit(), job
    (tmp_path / "here").mkdir()
    expect_frames_as_here(tmp_path, tmp_path / "py", range(1, 3))


def study(out, *more):
    command = ["/usr/bin/python3", STUDY, SCENES / "neon-sign" / "neon-sign.gltf", "--out", out, "--render", RENDER,
               "--strategies", "uniform,trs", "--spp", "2", "--seeds", "1", "--reference-spp", "8",
               "--width", "32", "--height", "18", "--max-depth", "2", "--quiet", *more]
    result = subprocess.run(command, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    with open(Path(out) / "results.csv") as f:
        return [{k: v for k, v in row.items() if k not in ("seconds", "node", "cpu")} for row in csv.DictReader(f)]


def test_a_study_through_slurm_measures_what_one_here_does(tmp_path):
    here = study(tmp_path / "here")
    there = study(tmp_path / "slurm", "--submit", "slurm", "--wait")
    assert sorted(there, key=lambda r: r["image"]) == sorted(here, key=lambda r: r["image"])
    summary = (tmp_path / "slurm" / "summary.md").read_text()
    assert "Rendered on 1 node" in summary
    assert "failed" not in summary
