"""trs-study end to end on a tiny study of the neon-sign scene: its plan, its CSV, and each
image's relMSE against an independent computation (trs-imgdiff's, in C++), with and without the
emitter mask; its pictures' choices (bars for a single budget, crops among the lit pixels) on
made-up results; and its submission to a stand-in sbatch, which nothing given to it runs. Run
by ctest with the paths of the tools."""

import argparse
import csv
import importlib.machinery
import importlib.util
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

TOOLS = None  # set from the command line
STRATEGIES = ["uniform", "power", "tree", "texel", "tree-texel", "trs", "ris", "restir"]  # trs-study's default
SOURCE_STUDY = Path(__file__).resolve().parents[2] / "tools" / "trs-study" / "trs-study"
SUPPORT = Path(__file__).resolve().parents[1] / "support"


def study(*args, program=None, environment=None):
    return subprocess.run([sys.executable, program or TOOLS.study, *map(str, args)], capture_output=True, text=True,
                          env=environment)


def plots_module():
    """trs-study's pictures (study_plots.py, beside it), imported as trs-study imports them, for
    their functions."""
    sys.dont_write_bytecode = True  # no __pycache__ beside it
    loader = importlib.machinery.SourceFileLoader("trs_study", str(TOOLS.study))
    loader.exec_module(importlib.util.module_from_spec(importlib.util.spec_from_loader("trs_study", loader)))
    import study_plots  # found where trs-study, loaded, finds its modules
    return study_plots


class Study(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name) / "study"
        cls.args = [TOOLS.scene, "--out", cls.out, "--render", TOOLS.render, "--spp", "2,4", "--time", "0.3",
                    "--seeds", "2", "--reference-spp", "32", "--width", "64", "--height", "36", "--lights", "10000",
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
        self.assertIn("## Mean over the lit pixels", (self.out / "summary.md").read_text())
        shown = re.findall(r"!\[[^]]*\]\(([^)]+)\)", (self.out / "summary.md").read_text())
        self.assertEqual(sorted(shown), sorted(p.name for p in self.out.glob("*.png")))
        self.assertEqual(sorted(shown), ["convergence.png", "crops.png"])

    def test_runs_from_the_source_tree_too(self):
        before = (self.out / "results.csv").read_text()
        collected = study("--collect", self.out, program=SOURCE_STUDY)
        self.assertEqual(collected.returncode, 0, collected.stderr)
        self.assertEqual((self.out / "results.csv").read_text(), before)

    def test_one_row_per_image_with_the_named_columns(self):
        rows = self.rows()
        self.assertEqual(len(rows), len(STRATEGIES) * 3 * 2)  # (2 spp + 1 time) x 2 seeds
        self.assertEqual(list(rows[0].keys())[:13], ["strategy", "spp", "time", "seed", "seconds", "passes",
                                                      "relmse", "relmse_lit", "rmse", "mean_ratio", "image", "lights",
                                                      "relmse_lit_32"])
        self.assertEqual(list(rows[0].keys())[-2:], ["relmse_trimmed", "relmse_lit_trimmed"])
        self.assertEqual({r["frame"] for r in rows}, {""})  # a still
        for r in rows:
            self.assertTrue((self.out / r["image"]).is_file(), r["image"])
            if r["time"]:
                self.assertEqual(r["spp"], "")
                self.assertGreaterEqual(float(r["seconds"]), 0.3)
            else:
                self.assertEqual(r["passes"], r["spp"])

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
                # Less the 0.1% of pixels of the largest error (2 of these 2,304): no more.
                trimmed = float(r[f"{column}_trimmed"])
                self.assertTrue(0.0 < trimmed <= expected * (1 + 1e-5), f"{r['image']} {column}_trimmed")

    def imgdiff_guard(self):
        """relMSE's guard, as trs-imgdiff writes it."""
        figures, reference = Path(self.tmp.name) / "guard.json", self.out / "reference.exr"
        done = subprocess.run([TOOLS.imgdiff, reference, reference, "--json", figures], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        return json.loads(figures.read_text())["relmse_guard"]

    def test_block_relmse_agrees_with_a_direct_sum_over_blocks(self):
        import numpy as np
        import OpenImageIO as oiio

        def read(path):
            return np.asarray(oiio.ImageBuf(str(path)).get_pixels(oiio.FLOAT), dtype=np.float64)[:, :, :3]

        reference, mask = read(self.out / "reference.exr"), read(self.out / "emitter-mask.exr")[:, :, 0]
        guard = self.imgdiff_guard()
        for r in self.rows():
            image, terms = read(self.out / r["image"]), []
            for y in range(0, reference.shape[0] - 31, 32):
                for x in range(0, reference.shape[1] - 31, 32):
                    if mask[y:y + 32, x:x + 32].any():
                        continue
                    a = image[y:y + 32, x:x + 32].mean(axis=(0, 1))
                    b = reference[y:y + 32, x:x + 32].mean(axis=(0, 1))
                    terms += list((a - b) ** 2 / (b ** 2 + guard))
            self.assertTrue(terms)
            self.assertAlmostEqual(float(r["relmse_lit_32"]) / np.mean(terms), 1.0, places=6, msg=r["image"])
            lit = mask == 0
            self.assertAlmostEqual(float(r["mean_ratio_lit"]), image[lit].mean() / reference[lit].mean(), places=6,
                                   msg=r["image"])

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

    def test_resume_renders_only_what_is_missing(self):
        images = self.out / "images"
        gone = images / "trs-spp2-seed2"
        for suffix in [".exr", ".json"]:
            gone.with_suffix(suffix).unlink()
        cut_short = images / "uniform-spp4-seed1.json"  # as an interrupted render leaves it
        stats = json.loads(cut_short.read_text())
        cut_short.write_text(json.dumps(dict(stats, interrupted=True)))
        collected = study("--collect", self.out)
        self.assertIn("an interrupted render, left out", collected.stderr)
        self.assertEqual(len(self.rows()), len(STRATEGIES) * 3 * 2 - 2)
        kept = {f: f.stat().st_mtime_ns for f in images.iterdir() if f.stem != cut_short.stem}
        resumed = study(*self.args, "--resume")
        self.assertEqual(resumed.returncode, 0, resumed.stderr)
        self.assertNotIn("interrupted", resumed.stderr)
        self.assertTrue(gone.with_suffix(".exr").is_file())
        self.assertFalse(json.loads(cut_short.read_text())["interrupted"])
        self.assertEqual({f: f.stat().st_mtime_ns for f in kept}, kept)
        self.assertEqual(len(self.rows()), len(STRATEGIES) * 3 * 2)

    def test_summary_gives_each_ratio_with_its_range_over_seeds(self):
        summary = (self.out / "summary.md").read_text()
        self.assertRegex(summary, r"\| 4 \| [0-9.e+-]+ \| [0-9.]+x \([0-9.]+–[0-9.]+\) \|")
        self.assertRegex(summary, r"every ratio lies within ±[0-9]+ % of its median")


class LightsSweep(unittest.TestCase):
    """--lights with several counts renders every setting at each and plots relMSE against them."""

    def test_every_light_count_is_rendered_and_plotted(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "sweep"
            done = study(TOOLS.scene, "--out", out, "--render", TOOLS.render, "--strategies", "uniform,trs",
                         "--spp", "2", "--seeds", "1", "--reference-spp", "8", "--width", "32", "--height", "18",
                         "--lights", "1e3,4e3", "--quiet")
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out / "results.csv") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(sorted((r["strategy"], float(r["lights"])) for r in rows),
                             [("trs", 1e3), ("trs", 4e3), ("uniform", 1e3), ("uniform", 4e3)])
            self.assertEqual((out / "lights.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.assertIn("trs, 4000 lights", (out / "summary.md").read_text())
            self.assertIn("](lights.png)", (out / "summary.md").read_text())


class Pictures(unittest.TestCase):
    """The pictures' choices, on made-up results: a single budget as bars, several as lines; crops
    among the lit pixels."""

    @classmethod
    def setUpClass(cls):
        cls.plots = plots_module()

    @staticmethod
    def rows(spp, time):
        """Two strategies, two seeds, a row per render as trs-study draws them."""
        rows = []
        for strategy, noise in [("uniform", 1.0), ("trs", 0.1)]:
            for seed in [1, 2]:
                budgets = [(n, "", 0.5) for n in spp] + [("", t, t * 1.01) for t in time]
                for n, t, seconds in budgets:
                    relmse = noise * seed / (n or 10 * t)
                    rows.append({"strategy": strategy, "spp": n, "time": t, "seed": seed, "lights": 1e4,
                                 "seconds": seconds, "relmse_lit": relmse, "worst_relmse_lit": relmse,
                                 "frame_count": 1})
        return rows

    def drawn(self, rows):
        """How convergence.png draws each panel: the units bars() is given, and the x of each line
        spread() draws."""
        bar_units, line_xs = [], []

        def bars(axis, series, unit, colours):
            bar_units.append(unit)
            original_bars(axis, series, unit, colours)

        def spread(axis, points, label, **style):
            line_xs.append([x for x, _ in points])
            return original_spread(axis, points, label, **style)

        original_bars, original_spread = self.plots.bars, self.plots.spread
        with tempfile.TemporaryDirectory() as tmp, mock.patch.object(self.plots, "bars", bars), \
                mock.patch.object(self.plots, "spread", spread):
            self.assertEqual(self.plots.plot_convergence(Path(tmp), rows), "convergence.png")
            self.assertEqual((Path(tmp) / "convergence.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
        return bar_units, line_xs

    def test_a_single_budget_is_drawn_as_bars(self):
        bar_units, line_xs = self.drawn(self.rows(spp=[2, 4], time=[4.0]))
        self.assertEqual(bar_units, ["s"])  # the time panel: one budget
        self.assertEqual(line_xs, [[2, 4], [2, 4]])  # the spp panel: a line per strategy
        bar_units, line_xs = self.drawn(self.rows(spp=[16], time=[2.0, 8.0]))
        self.assertEqual(bar_units, ["spp"])
        self.assertEqual(line_xs, [[2.02, 8.08], [2.02, 8.08]])  # at the seconds spent

    def test_crops_fall_among_the_lit_pixels(self):
        import numpy as np
        # An emitter over three quarters of the frame (all but the lower left quarter), seen
        # through a grid of lit gaps lit brightly by it; the lit quarter dim, but for a bright patch.
        lit = np.zeros((90, 160), dtype=bool)
        lit[45:, :80] = True
        lit[0:90:2, 0:160:2] = True
        reference = np.full((90, 160, 3), 0.02)
        reference[lit & ~np.pad(np.ones((45, 80), dtype=bool), ((45, 0), (0, 80)))] = 2.0
        reference[75:85, 50:70] = 0.5
        rows, columns = self.plots.lit_crop(lit, reference)
        self.assertEqual((rows.stop - rows.start, columns.stop - columns.start), (30, 53))
        self.assertGreaterEqual(lit[rows, columns].mean(), 0.9)
        self.assertTrue(rows.start <= 75 and rows.stop >= 85 and columns.start <= 50 and columns.stop >= 70,
                        (rows, columns))  # the bright patch, among windows as lit

    def test_nothing_lit_crops_the_centre(self):
        import numpy as np
        rows, columns = self.plots.lit_crop(np.zeros((90, 160), dtype=bool), np.ones((90, 160, 3)))
        self.assertEqual((rows, columns), (slice(30, 60), slice(53, 106)))


class StrategySpecs(unittest.TestCase):
    """A strategy with options of its own (STRATEGY+OPTION=VALUE) is rendered with them and named
    by its spec in the results."""

    def test_a_spec_passes_its_options_and_names_its_rows(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "specs"
            spec = "ris+candidates-from=power+candidates=2"
            args = [TOOLS.scene, "--out", out, "--render", TOOLS.render, "--strategies", f"uniform,{spec}",
                    "--spp", "2", "--seeds", "1", "--reference-spp", "8", "--width", "32", "--height", "18",
                    "--quiet"]
            planned = study(*args, "--plan")
            self.assertEqual(planned.returncode, 0, planned.stderr)
            self.assertIn("--strategy ris --candidates-from power --candidates 2 --seed 1",
                          planned.stdout.splitlines()[-1])
            done = study(*args)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out / "results.csv") as f:
                self.assertEqual(sorted(r["strategy"] for r in csv.DictReader(f)), [spec, "uniform"])
            stats = json.loads((out / "images" / f"{spec}-spp2-seed1.json").read_text())
            self.assertEqual(stats["settings"]["candidates_from"], "power")
            self.assertEqual(stats["settings"]["candidates"], 2)

    def test_a_malformed_spec_is_refused(self):
        refused = study(TOOLS.scene, "--out", "unused", "--strategies", "ris+candidates-from", "--plan")
        self.assertEqual(refused.returncode, 2)
        self.assertIn("is not OPTION=VALUE", refused.stderr)


class Frames(unittest.TestCase):
    """--frames: every render covers the frames, and each frame is measured against its own
    reference (the video wall's emission changes every frame)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name) / "frames"
        cls.scene = Path(TOOLS.scene).parent.parent / "video-wall" / "video-wall.gltf"
        cls.args = [cls.scene, "--out", cls.out, "--render", TOOLS.render, "--strategies", "uniform,trs",
                    "--spp", "2", "--time", "0.2", "--seeds", "2", "--reference-spp", "16", "--width", "48",
                    "--height", "27", "--frames", "3:5", "--quiet"]
        cls.result = study(*cls.args)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def rows(self):
        with open(self.out / "results.csv") as f:
            return list(csv.DictReader(f))

    def test_one_render_per_setting_covers_every_frame(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        planned = study(*self.args, "--plan")
        self.assertEqual(planned.returncode, 0, planned.stderr)
        lines = planned.stdout.splitlines()
        self.assertEqual(len(lines), 1 + 2 * 2 * 2)  # the references, then (spp, time) x 2 seeds x 2 strategies
        for line in lines:
            self.assertIn("--frames 3:5", line)
        self.assertIn("--out " + str(self.out / "reference.%04d.exr"), lines[0])
        rows = self.rows()
        self.assertEqual(sorted(int(r["frame"]) for r in rows), sorted([3, 4, 5] * 2 * 2 * 2))

    def test_each_frame_is_measured_against_its_own_reference(self):
        for r in self.rows():
            image, frame = self.out / r["image"], int(r["frame"])
            self.assertTrue(image.name.endswith(f".{frame:04d}.exr"), image.name)
            figures = Path(self.tmp.name) / "imgdiff.json"
            done = subprocess.run([TOOLS.imgdiff, image, self.out / f"reference.{frame:04d}.exr", "--mask",
                                   self.out / f"emitter-mask.{frame:04d}.exr", "--json", figures],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            expected = json.loads(figures.read_text())["overall"]["relmse"]
            self.assertAlmostEqual(float(r["relmse_lit"]) / expected, 1.0, places=5, msg=r["image"])

    def test_summary_reports_the_mean_and_the_worst_frame(self):
        import numpy as np
        summary = (self.out / "summary.md").read_text()
        self.assertIn("averaged over frames 3 to 5", summary)
        self.assertIn("## Worst frame", summary)
        self.assertEqual((self.out / "convergence.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
        rows = [r for r in self.rows() if r["strategy"] == "trs" and r["spp"] == "2"]
        by_seed = {}
        for r in rows:
            by_seed.setdefault(r["seed"], []).append(r)
        means = [np.mean([float(r["relmse_lit"]) for r in runs]) for runs in by_seed.values()]
        worsts = [max(float(r["relmse_lit"]) for r in runs) for runs in by_seed.values()]
        line = next(l for l in summary.splitlines() if l.startswith("| trs | 2 spp |"))
        cells = [c.strip() for c in line.split("|")[1:-1]]
        self.assertAlmostEqual(float(cells[2]) / np.median(means), 1.0, places=3)
        self.assertAlmostEqual(float(cells[4]) / np.median(worsts), 1.0, places=3)
        self.assertIn(int(cells[3]), [3, 4, 5])

    def test_resume_renders_only_the_missing_frames(self):
        images = self.out / "images"
        gone = [images / f"uniform-spp2-seed1.0004{suffix}" for suffix in [".exr", ".json"]]
        for path in gone:
            path.unlink()
        kept = {f: f.stat().st_mtime_ns for f in images.iterdir()}
        resumed = study(*self.args, "--resume")
        self.assertEqual(resumed.returncode, 0, resumed.stderr)
        self.assertTrue(all(path.is_file() for path in gone))
        self.assertEqual({f: f.stat().st_mtime_ns for f in kept}, kept)

    def test_a_reference_that_is_no_frame_pattern_is_refused(self):
        refused = study(self.scene, "--out", "unused", "--frames", "0:1", "--reference", "ref.exr", "--plan")
        self.assertEqual(refused.returncode, 2)
        self.assertIn("needs one integer conversion", refused.stderr)
        refused = study(self.scene, "--out", "unused", "--frames", "2:1", "--plan")
        self.assertEqual(refused.returncode, 2)
        self.assertIn("takes A:B", refused.stderr)



def slurm_module():
    """tools/common/slurm.py, as trs-study imports it from beside itself."""
    sys.dont_write_bytecode = True
    sys.path.insert(0, str(Path(TOOLS.study).parent))
    import slurm
    return slurm


class ShellWords(unittest.TestCase):
    """--sbatch's words against the table that trs-render's splitter is held to as well."""

    def test_splits_as_the_table_says(self):
        slurm = slurm_module()
        for case in json.loads((SUPPORT / "shell_words.json").read_text())["cases"]:
            with self.subTest(text=case["text"]):
                if "words" in case:
                    self.assertEqual(slurm.shell_words(case["text"]), case["words"])
                    continue
                with self.assertRaises(slurm.ShellWordsError) as refused:
                    slurm.shell_words(case["text"])
                self.assertEqual((refused.exception.character, refused.exception.position), (case["refused"], case["at"]))
                self.assertIn(f" at character {case['at']}", str(refused.exception))


# --sbatch texts that a shell would run `touch CANARY` from, and what the refusal names.
HOSTILE_SBATCH = [("--partition=x; touch {canary}", '";" at character 14 is a shell operator'),
                  ("--partition=x $(touch {canary})", '"$" at character 15 would expand in a shell'),
                  ("--partition=x `touch {canary}`", '"`" at character 15 would expand in a shell'),
                  ("--partition=x | touch {canary}", '"|" at character 15'),
                  ("--partition=x && touch {canary}", '"&" at character 15'),
                  ('--comment="$(touch {canary})"', '"$" at character 12'),
                  ("--partition=x\ntouch {canary}", "a control character (newline) at character 14"),
                  ("--comment='a", "\"'\" at character 11 opens a quote that is never closed")]


class Submit(unittest.TestCase):
    """--submit slurm through the stand-in sbatch (tests/support/slurm/sbatch), which records its
    calls: no --sbatch text and no output folder runs anything; the batch scripts, run by sh as
    Slurm runs them, make the study."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        self.record = self.root / "sbatch"
        self.record.mkdir()
        self.canary = self.root / "pwned"
        self.environment = {**os.environ, "PATH": f"{SUPPORT / 'slurm'}:{os.environ['PATH']}",
                            "SBATCH_RECORD": str(self.record)}

    def tearDown(self):
        self.tmp.cleanup()

    def submit(self, out, *more):
        return study(TOOLS.scene, "--out", out, "--render", TOOLS.render, "--strategies", "uniform", "--spp", "2",
                     "--seeds", "1", "--reference-spp", "4", "--width", "32", "--height", "18", "--quiet",
                     "--submit", "slurm", *more, environment=self.environment)

    def calls(self):
        """Each sbatch call's arguments, in order."""
        count = len(list(self.record.glob("*.args")))
        return [(self.record / f"{n}.args").read_text().split("\0")[:-1] for n in range(count)]

    def test_an_sbatch_text_a_shell_would_run_is_refused_and_runs_nothing(self):
        for text, named in HOSTILE_SBATCH:
            with self.subTest(text=text):
                refused = self.submit(self.root / "study", "--sbatch=" + text.format(canary=self.canary))
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn("trs-study: error: --sbatch: " + named, refused.stderr)
                self.assertEqual(sorted(p.name for p in self.root.iterdir()), ["sbatch"])
                self.assertEqual(self.calls(), [])

    def test_quoted_words_reach_sbatch_whole_and_the_scripts_hold_commands_alone(self):
        words = f"--comment='a b' '--comment=$(touch {self.canary})' --exclude=node[1-3]"
        submitted = self.submit(self.root / "study", "--sbatch", words)
        self.assertEqual(submitted.returncode, 0, submitted.stderr)
        self.assertEqual(submitted.stdout, "4244\n")  # the collection's job: the third call
        calls = self.calls()
        self.assertEqual(len(calls), 3)  # the reference, the renders at equal samples, the collection
        for n, args in enumerate(calls):
            self.assertEqual(args[-4:-1], ["--comment=a b", f"--comment=$(touch {self.canary})", "--exclude=node[1-3]"])
            self.assertNotIn("#SBATCH", (self.record / f"{n}.script").read_text())
        self.assertIn("--dependency=afterok:4242,afterany:4243", calls[2])
        self.assertFalse(self.canary.exists())

    def test_the_scripts_run_by_sh_make_the_study_in_any_output_folder(self):
        out = self.root / "o" / f"$(touch {self.canary})" / f"it's `touch {self.canary}` \"q\""
        submitted = self.submit(out)
        self.assertEqual(submitted.returncode, 0, submitted.stderr)
        for n in range(3):  # in the order of their dependencies
            task = subprocess.run(["sh", self.record / f"{n}.script"], capture_output=True, text=True,
                                  env={**self.environment, "SLURM_ARRAY_TASK_ID": "0"})
            self.assertEqual(task.returncode, 0, task.stderr)
        self.assertEqual(len(list(csv.DictReader((out / "results.csv").read_text().splitlines()))), 1)
        self.assertFalse(self.canary.exists())
        self.assertEqual(sorted(p.name for p in self.root.iterdir()), ["o", "sbatch"])

    def test_a_path_with_a_control_character_is_refused_naming_its_option(self):
        refused = self.submit(self.root / "a\nb")
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("trs-study: error: --out: ", refused.stderr)
        self.assertIn("holds a control character (newline) at character", refused.stderr)
        self.assertEqual(sorted(p.name for p in self.root.iterdir()), ["sbatch"])


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    for name in ["study", "render", "imgdiff", "scene"]:
        parser.add_argument("--" + name, required=True)
    TOOLS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0], *rest])
