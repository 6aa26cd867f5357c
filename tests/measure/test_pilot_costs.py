"""tools/pilot_costs.py's fit, on passes made up from known unit costs. What decides `auto`'s
choice is how a pass of one strategy compares with a pass of another: rays and light samples
come in nearly fixed proportion within a scene, so the costs' level is only as well known as
the scenes differ in that proportion, but their ratios are well known. Exact passes must give
the costs back; passes off by 2% must give a pass's cost over `trs`'s to 2%. The scenes differ
in how many light samples a ray comes with, as real ones do. Run by ctest with the tools'
directory."""

import argparse
import sys
import unittest
from pathlib import Path

import numpy as np

pilot_costs = None  # imported from the tools' directory given on the command line


def made_up(ray_ms, light_sample_cost, noise, seed=3):
    """Rows of scenes whose tracing time is ray_ms (rays + cost x light samples), each time
    multiplied by a factor within 1 +- noise (seeded)."""
    rng = np.random.default_rng(seed)
    scenes = []
    for a in ray_ms:
        rays = rng.uniform(2e5, 6e5)
        samples_per_ray = rng.uniform(0.2, 0.6)
        rows = []
        for strategy, b in zip(pilot_costs.STRATEGIES, light_sample_cost):
            samples = rays * samples_per_ray * (4.0 if strategy == "ris" else 1.0)
            r = rays * rng.uniform(0.98, 1.02)
            t = a * (r + b * samples) * (1.0 + noise * rng.uniform(-1.0, 1.0))
            rows.append({"tracing_ms": t, "rays": r, "light_samples": samples})
        scenes.append(rows)
    return scenes


def over_trs(costs, samples_per_ray=0.45):
    """A pass's cost of each strategy over `trs`'s, at samples_per_ray light samples a ray."""
    per_ray = [1.0 + c * samples_per_ray * (4.0 if s == "ris" else 1.0) for s, c in zip(pilot_costs.STRATEGIES, costs)]
    return np.array(per_ray) / per_ray[pilot_costs.STRATEGIES.index("trs")]


class Fit(unittest.TestCase):
    ray_ms = [1.8e-4, 2.6e-4, 3.9e-4, 2.2e-4, 5.9e-4, 3.0e-4, 2.4e-4, 3.6e-4]
    costs = [0.68, 0.36, 0.28]

    def test_exact_passes_give_the_costs_back(self):
        for costs in (self.costs, [0.3, 0.3, 0.3]):
            a, b = pilot_costs.fit(made_up(self.ray_ms, costs, 0.0))
            np.testing.assert_allclose(b, costs, rtol=1e-6)
            np.testing.assert_allclose(a, self.ray_ms, rtol=1e-6)

    def test_passes_off_by_two_percent_give_how_the_strategies_compare(self):
        for seed in (3, 4, 5):
            a, b = pilot_costs.fit(made_up(self.ray_ms, self.costs, 0.02, seed))
            np.testing.assert_allclose(over_trs(b), over_trs(self.costs), rtol=0.02)


class ReuseCosts(unittest.TestCase):
    def test_reuse_made_up_from_known_costs_gives_its_costs_back(self):
        ris, e, d = 0.56, 1.5, 0.6
        rng = np.random.default_rng(7)
        rows, ray_ms = [], []
        for a in (2e-4, 3e-4, 4e-4, 2.5e-4):
            r = {"rays": rng.uniform(2e5, 6e5), "light_samples": rng.uniform(4e5, 8e5), "camera_rays": 57600.0,
                 "reuse_candidates": 4 * 50000.0, "targets": 57600.0 * rng.uniform(2.0, 15.0)}
            whole = a * (r["rays"] + ris * (r["light_samples"] + r["reuse_candidates"]) + e * r["camera_rays"] +
                         d * r["targets"])
            r["reuse_ms"] = 0.4 * whole
            r["tracing_ms"] = whole - r["reuse_ms"]
            rows.append(r)
            ray_ms.append(a)
        np.testing.assert_allclose(pilot_costs.reuse_costs(rows, ray_ms, ris), (e, d), rtol=1e-9)
        # Scenes whose reuse evaluated nothing say nothing of the costs.
        self.assertIsNone(pilot_costs.reuse_costs([{**r, "targets": 0.0} for r in rows], ray_ms, ris))


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("--tools", type=Path, required=True)
    args, rest = p.parse_known_args()
    sys.path.insert(0, str(args.tools))
    import pilot_costs as module
    pilot_costs = module
    unittest.main(argv=[sys.argv[0], *rest])
