"""uniform against trs at equal samples per pixel: relMSE against a converged reference, over the
pixels where no emitter is seen directly, for several seeds; plotted to variance.png.

    python3 examples/python/variance.py [scene.gltf] [--quick]
"""
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import trs_render

args = [a for a in sys.argv[1:] if a != "--quick"]
scene = args[0] if args else Path(__file__).resolve().parents[2] / "scenes/neon-sign/neon-sign.gltf"
quick = "--quick" in sys.argv  # a smoke run: a small image, few samples
size = dict(width=120, height=68) if quick else dict(width=320, height=180)
spps, seeds, reference_spp = ([1, 4], [1, 2], 32) if quick else ([1, 4, 16, 64], [1, 2, 3], 2048)

reference, _ = trs_render.render(scene, strategy="ris", spp=reference_spp, seed=1000, **size)
lit = trs_render.emitter_mask(scene, **size) == 0  # the emitters themselves: noise of any strategy


def relmse(image):
    """(x - r)^2 / (r^2 + guard), averaged over the lit pixels' channels (trs-imgdiff's relMSE)."""
    return float(((image - reference) ** 2 / (reference ** 2 + trs_render.RELMSE_GUARD))[lit].mean())


for strategy in ["uniform", "trs"]:
    errors = [[relmse(trs_render.render(scene, strategy=strategy, spp=spp, seed=seed, **size)[0])
               for seed in seeds] for spp in spps]
    mean = np.mean(errors, axis=1)
    plt.loglog(spps, mean, "o-", label=strategy)
    print(strategy, " ".join(f"{spp} spp: {e:.4g}" for spp, e in zip(spps, mean)))
plt.xlabel("samples per pixel")
plt.ylabel(f"relMSE over the lit pixels (mean of {len(seeds)} seeds)")
plt.legend()
plt.title(Path(scene).stem)
plt.savefig("variance.png", dpi=120)
print("wrote variance.png")
