"""tools/common/trs_measure.py, the Python tools' measurement, against trs-imgdiff's (C++): the
relMSE guard, and EXRs written here with numpy, measured by both, relMSE over all pixels and over
the lit pixels of an emitter mask. Run by ctest with the paths of trs-imgdiff and of the module's
directory."""

import argparse
import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

TOOLS = None  # set from the command line
trs_measure = None  # imported from TOOLS.module


def write_exr(path, pixels):
    """pixels (height, width, channels) as a float OpenEXR: both readers see the same values."""
    pixels = np.ascontiguousarray(pixels, dtype=np.float32)
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], oiio.FLOAT))
    out.write_image(pixels)
    out.close()


class AgainstImgdiff(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = Path(cls.tmp.name)
        rng = np.random.default_rng(7)
        # Dark reference values (r^2 well under the 0.01 guard) beside bright ones, so that a
        # definition without the guard, or with another, disagrees.
        reference = rng.uniform(0.0, 0.05, (40, 56, 3)) * np.where(rng.uniform(size=(40, 56, 1)) < 0.5, 1.0, 100.0)
        image = reference * rng.gamma(1.0, 1.0, reference.shape) + rng.uniform(0.0, 0.02, reference.shape)
        # The values as the files hold them (float).
        cls.reference, cls.image = (np.float32(x).astype(np.float64) for x in (reference, image))
        write_exr(cls.dir / "reference.exr", cls.reference)
        write_exr(cls.dir / "image.exr", cls.image)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def imgdiff(self, *mask):
        figures = self.dir / "figures.json"
        done = subprocess.run([TOOLS.imgdiff, self.dir / "image.exr", self.dir / "reference.exr", *mask,
                               "--json", figures], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        return json.loads(figures.read_text())

    def assert_agrees(self, ours, theirs):
        self.assertLess(abs(ours / theirs - 1.0), 1e-9, f"trs_measure {ours!r}, trs-imgdiff {theirs!r}")

    def test_the_guard_is_the_one_imgdiff_prints(self):
        self.assertEqual(trs_measure.GUARD, self.imgdiff()["relmse_guard"])

    def test_read_exr_gives_the_pixels_written(self):
        np.testing.assert_array_equal(trs_measure.read_exr(self.dir / "image.exr"), self.image)

    def test_relmse_over_all_pixels(self):
        self.assert_agrees(trs_measure.relmse(self.image, self.reference), self.imgdiff()["overall"]["relmse"])

    def test_relmse_over_the_lit_pixels_of_a_mask(self):
        # The mask's first channel decides, as trs-imgdiff reads it; the others differ on purpose.
        rng = np.random.default_rng(8)
        first = np.where(rng.uniform(size=(40, 56)) < 0.3, 1.0, 0.0)
        mask = np.stack([first, 1.0 - first, rng.uniform(size=(40, 56))], axis=2)
        write_exr(self.dir / "mask.exr", mask)
        lit = trs_measure.lit_pixels(trs_measure.read_exr(self.dir / "mask.exr"))
        figures = self.imgdiff("--mask", self.dir / "mask.exr")
        self.assertEqual(int(lit.sum()), figures["pixels"])
        self.assert_agrees(trs_measure.relmse(self.image, self.reference, lit), figures["overall"]["relmse"])

    def test_a_single_channel_mask_is_read_as_grey(self):
        first = np.zeros((40, 56, 1))
        first[:, :20] = 1.0  # the emitter seen over the left columns
        write_exr(self.dir / "grey-mask.exr", first)
        lit = trs_measure.lit_pixels(trs_measure.read_exr(self.dir / "grey-mask.exr"))
        figures = self.imgdiff("--mask", self.dir / "grey-mask.exr")
        self.assertEqual(int(lit.sum()), 40 * 36)
        self.assertEqual(int(lit.sum()), figures["pixels"])
        self.assert_agrees(trs_measure.relmse(self.image, self.reference, lit), figures["overall"]["relmse"])


class Trimmed(unittest.TestCase):
    """trimmed_relmse: relMSE less the 0.1% of pixels of the largest error."""

    def setUp(self):
        rng = np.random.default_rng(11)
        self.reference = rng.uniform(0.5, 1.0, (50, 40, 3))  # 2,000 pixels: 2 left out
        self.image = self.reference * rng.normal(1.0, 0.1, self.reference.shape)

    def per_pixel(self, image):
        return trs_measure.relative_errors(image, self.reference).mean(axis=2).ravel()

    def test_without_a_share_it_is_relmse(self):
        self.assertAlmostEqual(trs_measure.trimmed_relmse(self.image, self.reference, share=0.0),
                               trs_measure.relmse(self.image, self.reference), places=12)

    def test_fireflies_are_left_out_and_nothing_else(self):
        clean = trs_measure.trimmed_relmse(self.image, self.reference)
        image = self.image.copy()
        image[3, 5] *= 1e4  # two fireflies: the share of 2,000 pixels
        image[40, 30, 1] *= 1e4
        self.assertGreater(trs_measure.relmse(image, self.reference), 100 * clean)
        errors = np.sort(self.per_pixel(self.image))
        fireflies = {np.ravel_multi_index((3, 5), (50, 40)), np.ravel_multi_index((40, 30), (50, 40))}
        kept = [e for i, e in enumerate(self.per_pixel(self.image)) if i not in fireflies]
        self.assertAlmostEqual(trs_measure.trimmed_relmse(image, self.reference), np.mean(kept), places=12)
        self.assertAlmostEqual(clean, errors[:-2].mean(), places=12)

    def test_over_the_pixels_selected(self):
        lit = np.zeros((50, 40), dtype=bool)
        lit[:25] = True  # 1,000 pixels: 1 left out
        errors = np.sort(trs_measure.relative_errors(self.image, self.reference).mean(axis=2)[lit])
        self.assertAlmostEqual(trs_measure.trimmed_relmse(self.image, self.reference, lit), errors[:-1].mean(),
                               places=12)
        self.assertTrue(np.isnan(trs_measure.trimmed_relmse(self.image, self.reference, ~np.ones_like(lit))))


class Edges(unittest.TestCase):
    def test_no_pixel_selected_gives_nan(self):
        image = np.ones((2, 3, 3))
        self.assertTrue(np.isnan(trs_measure.relmse(image, image, np.zeros((2, 3), dtype=bool))))

    def test_an_unreadable_file_raises_oserror_naming_it(self):
        with self.assertRaisesRegex(OSError, "no-such-image.exr"):
            trs_measure.read_exr("no-such-image.exr")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--imgdiff", required=True, help="the trs-imgdiff executable")
    parser.add_argument("--module", required=True, help="the directory of trs_measure.py")
    TOOLS, rest = parser.parse_known_args()
    sys.dont_write_bytecode = True  # no __pycache__ beside the module in the source tree
    sys.path.insert(0, TOOLS.module)
    import trs_measure  # noqa: E402
    unittest.main(argv=[sys.argv[0], *rest])
