"""1e6 samples drawn on a textured mesh and scattered over the texture they follow, in UV space,
beside the density map alone: points.png.

    python3 examples/python/points.py [--quick]
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import lightsampler as ls

# A quad of two triangles in 3D, its UVs covering a density map: rings that fade to the right.
positions = np.array([[0, 0, 0], [2, 0, 0], [0, 1, 0], [2, 1, 0.5]], np.float32)
uvs = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float32)
indices = np.array([[0, 1, 2], [1, 3, 2]], np.uint32)
y, x = np.mgrid[0:128, 0:256] / np.array([128.0, 256.0])[:, None, None]
density = ((np.sin(40 * np.hypot(x - 0.3, y - 0.5)) > 0.3) * (1.0 - x)).astype(np.float32)

sampler = ls.Sampler(positions, uvs, indices, [density])
count = 1e4 if "--quick" in sys.argv else 1e6
frame = sampler.generate(seed=1, target_count=count)
print(f"{len(frame)} samples on {sampler.device} ({sampler.backend}) in {frame.total_ms:.1f} ms, "
      f"acceptance {frame.acceptance:.2f}; passes (ms): {frame.pass_ms}")

uv = frame.uvs()
figure, (left, right) = plt.subplots(1, 2, figsize=(12, 3.4))
left.imshow(density, origin="lower", extent=(0, 1, 0, 1), cmap="magma")  # row 0 at v = 0
left.set_title("density map")
shown = uv[:: max(1, len(uv) // 200000)]
right.imshow(density, origin="lower", extent=(0, 1, 0, 1), cmap="Greys", alpha=0.25)
right.scatter(shown[:, 0], shown[:, 1], s=0.05, c="tab:blue", alpha=0.4, linewidths=0)
right.set(xlim=(0, 1), ylim=(0, 1), aspect=0.5, title=f"{len(shown)} of {len(frame)} samples, in UV")
left.set_aspect(0.5)
figure.savefig("points.png", dpi=120, bbox_inches="tight")
print("wrote points.png")
