"""tools/seed_variance.py, on a study made up here with known answers: two strategies whose
seeds' renders differ from their mean by +-0.1 and +-0.2 in every pixel and channel, the second
also off the reference by 0.3 everywhere (as where the reference misses light). Their variances'
ratio must be 4 exactly, whatever the offset, where their relMSE against the reference says
otherwise; a firefly in one render of the first raises its whole-image variance and is gone
from the trimmed one and from the lit pixels, where the emitter mask covers it. Run by ctest
with the tools' directory and trs_measure's."""

import argparse
import csv
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = None  # set from the command line
SIZE = 40  # 1,600 pixels: the trimmed share (0.1%) leaves out one


def write_exr(path, pixels):
    import OpenImageIO as oiio
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, oiio.FLOAT)
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), spec)
    out.write_image(pixels.astype("float32"))
    out.close()


class SeedVariance(unittest.TestCase):
    def setUp(self):
        import numpy as np
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name) / "scene"
        (self.dir / "images").mkdir(parents=True)
        reference = np.linspace(0.2, 2.0, SIZE * SIZE * 3).reshape(SIZE, SIZE, 3)
        write_exr(self.dir / "reference.exr", reference)
        mask = np.zeros((SIZE, SIZE, 3))
        mask[0, 0] = 1.0  # an emitter seen at the firefly's pixel
        write_exr(self.dir / "emitter-mask.exr", mask)
        rows = []
        for strategy, spread, offset in [("a", 0.1, 0.0), ("b", 0.2, 0.3)]:
            for seed in range(1, 5):
                image = reference + offset + spread * (1.0 if seed % 2 else -1.0)
                if strategy == "a" and seed == 1:
                    image[0, 0] += 50.0
                name = f"images/{strategy}-seed{seed}.exr"
                write_exr(self.dir / name, image)
                rows.append({"strategy": strategy, "spp": "", "time": "6", "seed": seed, "image": name})
        with open(self.dir / "results.csv", "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)

    def tearDown(self):
        self.tmp.cleanup()

    def measured(self):
        done = subprocess.run([sys.executable, TOOLS / "seed_variance.py", self.dir, "--baseline", "a",
                               "--csv", self.dir / "out.csv"], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(self.dir / "out.csv", newline="") as f:
            return {r["strategy"]: r for r in csv.DictReader(f)}

    def test_the_variance_leaves_the_reference_out(self):
        b = self.measured()["b"]
        self.assertAlmostEqual(float(b["ratio_trimmed"]), 4.0, places=6)
        self.assertAlmostEqual(float(b["ratio_lit"]), 4.0, places=6)
        self.assertAlmostEqual(float(b["ratio_lit_trimmed"]), 4.0, places=6)

    def test_a_firefly_is_in_the_whole_image_alone(self):
        a = self.measured()["a"]
        self.assertGreater(float(a["variance"]), 2.0 * float(a["variance_trimmed"]))
        self.assertAlmostEqual(float(a["variance_trimmed"]), float(a["variance_lit"]), places=9)

    def test_a_folder_without_results_is_named(self):
        done = subprocess.run([sys.executable, TOOLS / "seed_variance.py", self.dir / "images", "--baseline", "a"],
                              capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn(str(self.dir / "images" / "results.csv"), done.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tools", required=True, type=Path, help="the tools' directory")
    args, rest = parser.parse_known_args()
    TOOLS = args.tools
    unittest.main(argv=[sys.argv[0], *rest])
