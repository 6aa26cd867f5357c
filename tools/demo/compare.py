#!/usr/bin/python3
"""The demo's picture: two renders of a scene at equal time and its reference, side by side, each
labelled with its strategy, samples per pixel, time and relMSE over the lit pixels (trs-imgdiff's
figures), shown through the renderer's own display transform (trs_render.preview).

    compare.py OUT_DIR REFERENCE.exr NAME STRATEGY STRATEGY   (reads OUT_DIR/NAME-STRATEGY.{exr,json}
                                                               and -noise.json; writes OUT_DIR/compare.png)
"""
import json
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import trs_render

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))
sys.dont_write_bytecode = True
from trs_measure import read_exr  # noqa: E402


def main(out, reference, name, *strategies):
    out = Path(out)
    panels = []
    for strategy in strategies:
        stats = json.loads((out / f"{name}-{strategy}.json").read_text())
        relmse = json.loads((out / f"{name}-{strategy}-noise.json").read_text())["overall"]["relmse"]
        label = f"{strategy}: {stats['passes']} spp in {stats['wall_seconds']:.1f} s, relMSE {relmse:.3g} over the lit pixels"
        panels.append((read_exr(out / f"{name}-{strategy}.exr"), label, relmse, stats))
    panels.append((read_exr(reference), "reference", None, None))

    height, width = panels[0][0].shape[:2]
    figure, axes = plt.subplots(1, len(panels), figsize=(len(panels) * width / 100, height / 100 + 0.35), dpi=100)
    for axis, (image, label, _, _) in zip(axes, panels):
        axis.imshow(trs_render.preview(image))
        axis.set_title(label, fontsize=9)
        axis.axis("off")
    figure.subplots_adjust(left=0.005, right=0.995, bottom=0.005, top=0.9, wspace=0.02)
    figure.savefig(out / "compare.png")

    (first, _, noise_a, a), (second, _, noise_b, b) = panels[0], panels[1]
    print(f"At equal time ({a['wall_seconds']:.1f} s and {b['wall_seconds']:.1f} s: {a['passes']} and "
          f"{b['passes']} spp), against the reference over the lit pixels, {strategies[1]} is "
          f"{noise_a / noise_b:.1f}x less noisy than {strategies[0]} (relMSE {noise_a:.3g} and {noise_b:.3g}).")
    print(f"Wrote {out / 'compare.png'}")


if __name__ == "__main__":
    if len(sys.argv) != 6:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
