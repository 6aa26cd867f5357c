"""Shell commands handed to Slurm: one job array a command per task, or one job, through
`sbatch` as the shell finds it (trs-study --submit slurm; trs-render --submit has its own, in C++).

Each array task runs its command from a batch script whose `case` picks it by
$SLURM_ARRAY_TASK_ID; the script is read by sbatch at submission and removed after it."""
import os
import shlex
import subprocess
import tempfile
from pathlib import Path


class SubmitError(RuntimeError):
    """sbatch refused the job, or could not be run."""


def batch_script(commands, name, log_pattern, directives=()):
    """The batch script of an array of `commands` (lists of words), or of one job for one command."""
    lines = ["#!/bin/sh", f"#SBATCH --job-name={name}", f"#SBATCH --output={log_pattern}"]
    lines += [f"#SBATCH {d}" for d in directives]
    if len(commands) == 1 and "%a" not in str(log_pattern):
        return "\n".join(lines + [f"exec {shlex.join(commands[0])}", ""])
    lines += [f"#SBATCH --array=0-{len(commands) - 1}", 'case "$SLURM_ARRAY_TASK_ID" in']
    lines += [f"  {i}) exec {shlex.join(c)} ;;" for i, c in enumerate(commands)]
    lines += ["esac", f'echo "{name}: no task $SLURM_ARRAY_TASK_ID in this job array" >&2', "exit 1", ""]
    return "\n".join(lines)


def submit(commands, name, log_pattern, directives=(), sbatch_args="", dependency=None, wait=False):
    """Submits `commands` (an array, or one job for one command whose log pattern has no %a);
    returns the job id. `directives` are sbatch options for this job alone (`--exclusive`),
    `sbatch_args` the user's, as the shell splits them; `dependency` is sbatch's
    (`afterok:12,afterany:13`). With `wait`, returns once the job has ended, and raises
    SubmitError if it failed."""
    Path(log_pattern).parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", suffix=".sh", prefix=f".{name}-", dir=Path(log_pattern).parent,
                                     delete=False) as script:
        script.write(batch_script(commands, name, log_pattern, directives))
    try:
        words = ["sbatch", "--parsable"] + (["--wait"] if wait else [])
        words += [f"--dependency={dependency}"] if dependency else []
        command = shlex.join(words) + " " + sbatch_args + " " + shlex.quote(script.name)
        result = subprocess.run(command, shell=True, capture_output=True, text=True)
    finally:
        os.unlink(script.name)
    job = result.stdout.strip().split(";")[0]
    if not job:
        raise SubmitError(f"sbatch submitted nothing (status {result.returncode}): {result.stderr.strip()}")
    if wait and result.returncode != 0:
        raise SubmitError(f"Slurm job {job} failed (sbatch status {result.returncode}); logs: {log_pattern}")
    return job
