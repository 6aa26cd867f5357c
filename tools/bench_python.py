#!/usr/bin/python3
"""What Python adds to a frame: lightsampler.Sampler.generate() timed by wall clock from Python,
against the C++ frame's own time (Frame.total_ms, the library's stopwatch around generate()), for
the same frames. Prints a table and writes CSV.

    PYTHONPATH=build/python tools/bench_python.py [--count 1e7] [--repeats 9] [--csv FILE]
"""
import argparse
import csv
import os
import statistics
import sys
import tempfile
import time

import numpy as np
import lightsampler as ls


def grid(cells):
    """A unit square of 2 x cells^2 triangles, its UVs the square itself."""
    t = np.linspace(0.0, 1.0, cells + 1, dtype=np.float32)
    u, v = np.meshgrid(t, t)
    positions = np.stack([u.ravel(), v.ravel(), np.zeros(u.size, np.float32)], axis=1)
    uvs = np.ascontiguousarray(positions[:, :2])
    k = np.arange(cells * (cells + 1)).reshape(cells, cells + 1)[:, :cells].ravel().astype(np.uint32)
    indices = np.concatenate([np.stack([k, k + 1, k + cells + 1], 1), np.stack([k + 1, k + cells + 2, k + cells + 1], 1)])
    return positions, uvs, np.ascontiguousarray(indices)


def density(size=2048):
    """Smooth, with a sparse pattern on it: both the rejection loop and the counting have work."""
    y, x = np.mgrid[0:size, 0:size] / size
    return (1.0 + np.sin(20 * x) * np.cos(13 * y) + (np.sin(300 * x * y) > 0.9) * 4.0).astype(np.float32)


def measure(sampler, count, repeats, warmup):
    """Medians of the C++ frame time and of the Python call's, and the last frame's sample count."""
    python_ms, cpp_ms = [], []
    for i in range(warmup + repeats):
        start = time.perf_counter()
        frame = sampler.generate(seed=i, target_count=count)
        elapsed = 1000.0 * (time.perf_counter() - start)
        if i >= warmup:
            python_ms.append(elapsed)
            cpp_ms.append(frame.total_ms)
        samples = len(frame)
        del frame  # back to the sampler, as a loop that keeps one frame at a time does
    return statistics.median(cpp_ms), statistics.median(python_ms), samples


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=float, default=1e7, help="target samples per frame")
    parser.add_argument("--repeats", type=int, default=9, help="timed frames per case (median)")
    parser.add_argument("--warmup", type=int, default=2, help="untimed frames before them")
    parser.add_argument("--meshes", default="1,300", help="grid sizes: cells per side (2 x cells^2 triangles)")
    parser.add_argument("--backends", default="cpu" + (",vulkan" if ls.has_vulkan_backend() and ls.vulkan_devices() else ""))
    parser.add_argument("--csv", help="write the results as CSV to FILE")
    args = parser.parse_args()

    texels = density()
    rows = []
    print(f"{'backend':8} {'triangles':>10} {'samples':>10} {'C++ ms':>9} {'Python ms':>10} {'ratio':>6}")
    for backend in args.backends.split(","):
        for cells in map(int, args.meshes.split(",")):
            positions, uvs, indices = grid(cells)
            sampler = ls.Sampler(positions, uvs, indices, [texels], backend=backend)
            cpp, python, samples = measure(sampler, args.count, args.repeats, args.warmup)
            row = dict(backend=backend, device=sampler.device, triangles=len(indices), samples=samples,
                       cpp_ms=round(cpp, 3), python_ms=round(python, 3), ratio=round(python / cpp, 4))
            rows.append(row)
            print(f"{backend:8} {len(indices):>10} {samples:>10} {cpp:>9.2f} {python:>10.2f} {python / cpp:>6.3f}")
    if args.csv:
        directory = os.path.dirname(os.path.abspath(args.csv))
        with tempfile.NamedTemporaryFile("w", dir=directory, delete=False, newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
        os.replace(f.name, args.csv)
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    sys.exit(main())
