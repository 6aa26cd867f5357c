"""trs-study's command line: its options, checked, and the strategies to study as their specs."""

import argparse
import re
from pathlib import Path

import slurm
import study_plan
import trs_options

DEFAULT_STRATEGIES = ",".join(trs_options.STRATEGIES)


def number_list(kind):
    def parse(text):
        try:
            values = [kind(v) for v in text.split(",") if v]
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a comma-separated list of numbers: {text}")
        if not values or any(v <= 0 for v in values):
            raise argparse.ArgumentTypeError(f"needs positive values: {text}")
        return values
    return parse


def frame_pattern(path):
    """Whether a file name holds exactly one printf integer conversion (ref.%04d.exr)."""
    return len(re.findall(r"%0?[0-9]*d", Path(path).name)) == 1 and Path(path).name.count("%") == 1


def parse_arguments(argv, doc):
    """trs-study's arguments, checked; `doc`, the program's docstring, is its help."""
    p = argparse.ArgumentParser(prog="trs-study", description=doc.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=doc.split("\n\n", 1)[1])
    p.add_argument("scene", nargs="?", help="glTF scene (not needed with --collect)")
    p.add_argument("--out", type=Path, help="output directory")
    p.add_argument("--strategies", default=DEFAULT_STRATEGIES,
                   help="strategies, comma-separated; a strategy with trs-render options of its own is "
                        "STRATEGY+OPTION=VALUE..., e.g. ris+candidates-from=power, and is named so in "
                        "the results")
    p.add_argument("--plugin", type=lambda path: Path(path).resolve(), action="append", default=[],
                   help="a shared library of light strategies for every render (trs-render --plugin): its "
                        "strategies may then be named in --strategies; repeatable")
    p.add_argument("--spp", type=number_list(int), default=[4, 16, 64], help="sample counts, e.g. 4,16,64")
    p.add_argument("--time", type=number_list(float), default=[], help="time budgets in seconds, e.g. 2,8")
    p.add_argument("--seeds", type=int, default=3, help="seeds per setting")
    reference = p.add_mutually_exclusive_group()
    reference.add_argument("--reference", type=Path,
                           help="a converged reference (OpenEXR) to use; with --frames, a frame pattern "
                                "(ref.%%04d.exr)")
    reference.add_argument("--reference-spp", type=int, default=1024, help="spp of the reference to render")
    p.add_argument("--reference-strategy", default="trs", help="strategy of the reference render")
    p.add_argument("--width", type=int)
    p.add_argument("--height", type=int)
    p.add_argument("--max-depth", type=int)
    p.add_argument("--lights", type=number_list(float), default=[],
                   help="point lights per pass; several (e.g. 1e3,1e4,1e5) sweep them")
    p.add_argument("--frames", type=trs_options.frame_range, metavar="A:B",
                   help="animation frames A to B: every render covers them, each frame is measured against "
                        "its own reference")
    p.add_argument("--render", default=None, help="trs-render executable (default: beside trs-study, else on PATH)")
    p.add_argument("--plan", action="store_true", help="print the render commands, one per line, and stop")
    p.add_argument("--collect", type=Path, metavar="DIR", help="measure the images in DIR and write the results")
    p.add_argument("--submit", choices=["slurm"],
                   help="hand the renders and the collection to Slurm as job arrays and a job after them; "
                        "print the job ids and return")
    p.add_argument("--sbatch", default="",
                   help="--submit: options for sbatch ('--partition=render --time=30'), split into words by the "
                        "shell's quotes and backslashes; nothing is expanded or run, so $, ` and unquoted "
                        "; | & < > ( ) are refused")
    p.add_argument("--wait", action="store_true", help="--submit: return once the collection has ended")
    p.add_argument("--resume", action="store_true",
                   help="skip the renders whose outputs are all there (an interrupted or extended study)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    args = p.parse_args(argv)
    if args.collect is None and (args.scene is None or args.out is None):
        p.error("SCENE and --out are needed, unless --collect DIR")
    if args.seeds < 1:
        p.error("--seeds must be at least 1")
    if (args.sbatch or args.wait) and not args.submit:
        p.error("--sbatch and --wait belong to --submit")
    if args.submit and args.plan:
        p.error("--plan and --submit are two ways to run the renders: give one")
    if args.plan or args.submit:
        refuse_control_characters(p, args)
    try:
        args.sbatch_words = slurm.shell_words(args.sbatch)
    except slurm.ShellWordsError as e:
        p.error(f"--sbatch: {e}")
    if args.frames is not None and args.reference is not None and not frame_pattern(args.reference):
        p.error(f"--reference: with --frames, it names each frame's reference: {args.reference} needs one "
                "integer conversion in its file name (ref.%04d.exr)")
    args.strategies = [s for s in args.strategies.split(",") if s]
    for spec in args.strategies:
        try:
            study_plan.strategy_flags(spec)
        except ValueError as e:
            p.error(f"--strategies: {e}")
    return args


def refuse_control_characters(parser, args):
    """--plan and --submit write the renders as commands that sh reads a line at a time: an
    argument that holds a control character is refused, named with it (--sbatch has rules of
    its own)."""
    for name, value in vars(args).items():
        problem = isinstance(value, (str, Path)) and name != "sbatch" and slurm.control_character(str(value))
        if problem:
            option = "SCENE" if name == "scene" else "--" + name.replace("_", "-")
            parser.error(f"{option}: {slurm.printable(value)} holds {problem}, which a command for a shell or a "
                         "scheduler cannot hold safely")
