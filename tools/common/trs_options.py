"""trs-render's options as the Python tools write them: its strategies and its animation frame
ranges (--frames A:B, which tools/trs-render/options.cpp reads)."""

import argparse
import re

# The strategies a study compares: every one trs-render has but auto, which renders as one of
# them. tests/python/test_trs_render.py checks them against trs_render.STRATEGIES.
STRATEGIES = ["uniform", "power", "tree", "texel", "tree-texel", "trs", "ris", "restir"]


def frame_range(text):
    """--frames A:B as trs-render takes it, frames A to B inclusive (0 <= A <= B), as a range.
    An argparse type: any other text raises ArgumentTypeError."""
    match = re.fullmatch(r"([0-9]+):([0-9]+)", text)
    if not match or int(match[1]) > int(match[2]):
        raise argparse.ArgumentTypeError(f"takes A:B, frames 0 <= A <= B ({text})")
    return range(int(match[1]), int(match[2]) + 1)


def frames_argument(frames):
    """A range of frames as --frames takes it: A:B."""
    return f"{frames.start}:{frames.stop - 1}"
