"""The study's renders as trs-render commands (the reference's, then every strategy's at each
budget, seed and light count), the files they write, and whether they have written them all."""

import json
import re
from pathlib import Path

import trs_options

RENDERS = "renders.txt"  # the study's render commands, one a line, for --collect to name the failed
# A study image's name: its strategy spec, budget, light count (when swept) and seed.
IMAGE_NAME = re.compile(r"^(?P<strategy>.+)-(spp|time)[0-9.e+-]+?(-lights[0-9.e+]+)?-seed[0-9]+$")


def strategy_flags(spec):
    """trs-render's options for a strategy spec: STRATEGY, or STRATEGY+OPTION=VALUE+..."""
    name, *options = spec.split("+")
    flags = ["--strategy", name]
    for option in options:
        key, equals, value = option.partition("=")
        if not key or not equals or not value:
            raise ValueError(f"{spec!r}: {option!r} is not OPTION=VALUE")
        flags += [f"--{key}", value]
    return flags


def render_executable(args):
    if args.render:
        return args.render
    beside = Path(__file__).resolve().parent / "trs-render"  # beside trs-study, as this module is
    return str(beside) if beside.exists() else "trs-render"


def common_options(args):
    options = []
    settings = Path(args.scene).parent / "render.toml"
    if settings.exists():
        options += ["--settings", str(settings)]
    for flag, value in [("--width", args.width), ("--height", args.height), ("--max-depth", args.max_depth)]:
        if value is not None:
            options += [flag, str(value)]
    for plugin in args.plugin:
        options += ["--plugin", str(plugin)]
    return options + ["--quiet"]


def lights_flags(lights):
    return ["--lights", f"{lights:g}"]


def frame_suffix(args):
    """What an output's name ends in: one file, or one per animation frame."""
    return ".%04d" if args.frames is not None else ""


def plan(args):
    """The render commands: the reference (or the emitter mask of the one given), then every
    strategy x spp x seed and strategy x time x seed, at each light count; with --frames, each
    command renders every frame."""
    render, out, frame = render_executable(args), Path(args.out), frame_suffix(args)
    common = [render, str(args.scene)] + common_options(args)
    if args.frames is not None:
        common += ["--frames", trs_options.frames_argument(args.frames)]
    jobs = []
    if args.reference is None:
        # The estimate is unbiased at any light count; a sweep's reference keeps the scene's own.
        reference_lights = lights_flags(args.lights[0]) if len(args.lights) == 1 else []
        jobs.append(common + reference_lights + ["--strategy", args.reference_strategy, "--spp", str(args.reference_spp),
                              "--seed", "1000003", "--out", str(out / f"reference{frame}.exr"),
                              "--emitter-mask", str(out / f"emitter-mask{frame}.exr")])
    else:
        # The mask of the camera's view alone: no bounces needed.
        jobs.append(common + ["--spp", "64", "--max-depth", "0", "--out", str(out / "images" / f"mask-render{frame}.exr"),
                              "--emitter-mask", str(out / f"emitter-mask{frame}.exr")])
    budgets = [("spp", str(n), ["--spp", str(n)]) for n in args.spp]
    budgets += [("time", f"{t:g}", ["--time", f"{t:g}"]) for t in args.time]
    sweep = [(f"-lights{n:g}" if len(args.lights) > 1 else "", lights_flags(n)) for n in args.lights] or [("", [])]
    # Strategies innermost: renders compared at equal time run back to back, so that a machine
    # whose speed drifts (a shared one) slows them alike.
    for seed in range(1, args.seeds + 1):
        for kind, value, flags in budgets:
            for suffix, lights in sweep:
                for strategy in args.strategies:
                    stem = out / "images" / f"{strategy}-{kind}{value}{suffix}-seed{seed}"
                    jobs.append(common + lights + strategy_flags(strategy) + ["--seed", str(seed)] + flags +
                                ["--out", f"{stem}{frame}.exr", "--stats", f"{stem}{frame}.json"])
    return jobs


def frame_file(path, frame):
    """A frame pattern's file for one frame (the pattern is in the file name only)."""
    path = Path(path)
    return path.parent / (path.name % frame)


def job_frames(job):
    """The animation frames a render command covers (None for a still)."""
    return trs_options.frame_range(job[job.index("--frames") + 1]) if "--frames" in job else None


def finished(job):
    """Whether a render command has written all its files (each frame's, for a sequence), and
    none was cut short by an interrupt."""
    frames = job_frames(job)
    for i, flag in enumerate(job):
        if flag not in ("--out", "--stats", "--emitter-mask"):
            continue
        for path in ([Path(job[i + 1])] if frames is None else [frame_file(job[i + 1], f) for f in frames]):
            if not path.exists() or (flag == "--stats" and json.loads(path.read_text()).get("interrupted", False)):
                return False
    return True


def copy_reference(args, out):
    """The reference given, into the study (each frame's, for a sequence)."""
    frames = args.frames if args.frames is not None else [None]
    for f in frames:
        source = frame_file(args.reference, f) if f is not None else args.reference
        target = out / (f"reference.{f:04d}.exr" if f is not None else "reference.exr")
        if not source.is_file():
            raise SystemExit(f"trs-study: error: {source}: no such reference")
        if source.resolve() != target.resolve():
            target.write_bytes(source.read_bytes())
