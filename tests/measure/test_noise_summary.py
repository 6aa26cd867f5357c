"""tools/noise_summary.py, on studies' results.csv made up here: the ratio of the baseline's
relMSE to each strategy's, seed by seed and the median over seeds, or the ratio of the means
over seeds (the expected relMSE's, which a single firefly can move); the metric named; a clear
error for a results.csv without that metric's column. Run by ctest with the tools' directory."""

import argparse
import csv
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = None  # set from the command line
COLUMNS = ["strategy", "spp", "time", "seed", "relmse", "relmse_lit", "relmse_lit_trimmed"]


def write_study(folder, rows):
    folder.mkdir(parents=True)
    with open(folder / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=sorted({k for r in rows for k in r}, key=COLUMNS.index))
        writer.writeheader()
        writer.writerows(rows)


def rows(strategy, values, column="relmse_lit"):
    """A time-6 row per seed, `values` its metric; trimmed, a firefly's value (above 1) is gone."""
    return [{"strategy": strategy, "spp": "", "time": "6", "seed": str(seed + 1), "relmse": 1.0, column: v,
             "relmse_lit_trimmed": min(v, 1.0) / 2} for seed, v in enumerate(values)]


class NoiseSummary(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)
        # auto's seeds 1 and 2 two and four times as noisy as ris's, seed 3 with a firefly in
        # ris's: the median says ris leads (auto 2x its relMSE), the means that auto does.
        write_study(self.dir / "scene", rows("auto", [1.0, 2.0, 1.0]) + rows("ris", [0.5, 0.5, 36.5]))

    def tearDown(self):
        self.tmp.cleanup()

    def summary(self, *options, study="scene"):
        return subprocess.run([sys.executable, TOOLS / "noise_summary.py", self.dir / study, "--baseline", "auto",
                               "--csv", self.dir / "out.csv", *options], capture_output=True, text=True)

    def ratio(self, *options):
        done = self.summary(*options)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(self.dir / "out.csv", newline="") as f:
            (row,) = [r for r in csv.DictReader(f) if r["strategy"] == "ris"]
        return float(row["ratio"]), done.stdout

    def test_the_median_of_the_seeds_ratios(self):
        ratio, printed = self.ratio()
        self.assertAlmostEqual(ratio, 2.0)
        self.assertIn("lit pixels, median over seeds", printed)

    def test_the_ratio_of_the_means(self):
        ratio, printed = self.ratio("--over-seeds", "mean")
        self.assertAlmostEqual(ratio, (4.0 / 3.0) / 12.5)
        self.assertIn("ratio of the means over seeds", printed)

    def test_the_metric_named(self):
        ratio, printed = self.ratio("--metric", "relmse_lit_trimmed", "--over-seeds", "mean")
        self.assertAlmostEqual(ratio, 0.5 / (1.0 / 3.0))  # auto's 0.5 each, ris's 0.25, 0.25, 0.5
        self.assertIn("lit pixels, trimmed", printed)

    def test_a_study_without_the_metric_names_its_file(self):
        write_study(self.dir / "old", [{k: v for k, v in r.items() if k != "relmse_lit_trimmed"}
                                       for r in rows("auto", [1.0]) + rows("ris", [1.0])])
        done = self.summary("--metric", "relmse_lit_trimmed", study="old")
        self.assertNotEqual(done.returncode, 0)
        self.assertIn(str(self.dir / "old" / "results.csv"), done.stderr)
        self.assertIn("relmse_lit_trimmed", done.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tools", required=True, type=Path, help="the tools' directory")
    args, rest = parser.parse_known_args()
    TOOLS = args.tools
    unittest.main(argv=[sys.argv[0], *rest])
