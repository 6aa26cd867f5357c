"""--submit slurm: the study's renders and its collection handed to Slurm (docs/cluster.md)."""

import shlex
import sys

import slurm
import study_plan


def submit_study(args, jobs, out, program):
    """--submit slurm: the reference, the renders at equal samples and those at equal time (a whole
    node each, so that their times compare) as job arrays, then --collect as a job after them, run
    by `program` (trs-study itself)."""
    (out / study_plan.RENDERS).write_text("".join(shlex.join(job) + "\n" for job in jobs))
    logs = out / "logs"
    try:
        reference = slurm.submit(jobs[:1], "trs-study-reference", logs / "reference-%A_%a.log",
                                 sbatch_words=args.sbatch_words)
        renders = []
        for kind, chosen, options in [("spp", [j for j in jobs[1:] if "--time" not in j], []),
                                      ("time", [j for j in jobs[1:] if "--time" in j], ["--exclusive"])]:
            if chosen:
                renders.append(slurm.submit(chosen, f"trs-study-{kind}", logs / f"{kind}-%A_%a.log",
                                            options=options, sbatch_words=args.sbatch_words))
        after = f"afterok:{reference}" + (f",afterany:{':'.join(renders)}" if renders else "")
        collect_command = [sys.executable, str(program), "--collect", str(out.resolve())]
        print(f"trs-study: Slurm jobs {', '.join([reference] + renders)} render; the collection follows, "
              f"its log in {logs}", file=sys.stderr)
        collect_job = slurm.submit([collect_command], "trs-study-collect", logs / "collect-%j.log",
                                   sbatch_words=args.sbatch_words, dependency=after, wait=args.wait)
    except slurm.SubmitError as error:
        raise SystemExit(f"trs-study: error: {error}")
    print(collect_job)
    return 0
