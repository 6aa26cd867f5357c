"""trs-study end to end on a tiny study of the neon-sign scene: its plan, its CSV, and each
image's relMSE against an independent computation (trs-imgdiff's, in C++), with and without the
emitter mask. Run by ctest with the paths of the tools."""

import argparse
import csv
import json
import shlex
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = None  # set from the command line
STRATEGIES = ["uniform", "power", "trs"]


def study(*args):
    return subprocess.run([sys.executable, TOOLS.study, *map(str, args)], capture_output=True, text=True)


class Study(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name) / "study"
        cls.args = [TOOLS.scene, "--out", cls.out, "--render", TOOLS.render, "--spp", "2,4", "--time", "0.3",
                    "--seeds", "2", "--reference-spp", "32", "--width", "48", "--height", "27", "--lights", "10000",
                    "--quiet"]
        cls.result = study(*cls.args)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def rows(self):
        with open(self.out / "results.csv") as f:
            return list(csv.DictReader(f))

    def test_runs_and_writes_every_output(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        for name in ["reference.exr", "emitter-mask.exr", "results.csv", "summary.md"]:
            self.assertTrue((self.out / name).is_file(), name)
        for name in ["convergence.png", "crops.png"]:
            self.assertEqual((self.out / name).read_bytes()[:8], b"\x89PNG\r\n\x1a\n", name)
        self.assertIn("lit pixels", (self.out / "summary.md").read_text())

    def test_one_row_per_image_with_the_named_columns(self):
        rows = self.rows()
        self.assertEqual(len(rows), len(STRATEGIES) * 3 * 2)  # (2 spp + 1 time) x 2 seeds
        self.assertEqual(list(rows[0].keys())[:11], ["strategy", "spp", "time", "seed", "seconds", "frames",
                                                      "relmse", "relmse_lit", "rmse", "mean_ratio", "image"])
        for r in rows:
            self.assertTrue((self.out / r["image"]).is_file(), r["image"])
            if r["time"]:
                self.assertEqual(r["spp"], "")
                self.assertGreaterEqual(float(r["seconds"]), 0.3)
            else:
                self.assertEqual(r["frames"], r["spp"])

    def test_relmse_agrees_with_an_independent_computation(self):
        for r in self.rows():
            image = self.out / r["image"]
            for mask, column in [([], "relmse"), (["--mask", self.out / "emitter-mask.exr"], "relmse_lit")]:
                figures = Path(self.tmp.name) / "imgdiff.json"
                done = subprocess.run([TOOLS.imgdiff, image, self.out / "reference.exr", *mask, "--json", figures],
                                      capture_output=True, text=True)
                self.assertEqual(done.returncode, 0, done.stderr)
                expected = json.loads(figures.read_text())["overall"]["relmse"]
                self.assertAlmostEqual(float(r[column]) / expected, 1.0, places=5, msg=f"{r['image']} {column}")

    def test_plan_prints_one_render_per_line_and_collect_measures_them(self):
        planned = study(*self.args, "--plan")
        self.assertEqual(planned.returncode, 0, planned.stderr)
        lines = planned.stdout.splitlines()
        self.assertEqual(len(lines), 1 + len(STRATEGIES) * 3 * 2)  # the reference, then the images
        for line in lines:
            self.assertEqual(shlex.split(line)[0], str(TOOLS.render))
        before = (self.out / "results.csv").read_text()
        collected = study("--collect", self.out)
        self.assertEqual(collected.returncode, 0, collected.stderr)
        self.assertEqual((self.out / "results.csv").read_text(), before)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    for name in ["study", "render", "imgdiff", "scene"]:
        parser.add_argument("--" + name, required=True)
    TOOLS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0], *rest])
