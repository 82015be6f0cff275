#!/usr/bin/python3
"""Unit tests of the benchmark harness's arithmetic (no vkpath run): PFM round trip, metrics, the
reference noise-floor estimate, threshold crossings, the sampler list of `vkpath --help`, the
comparison of the Embree reference's image with vkpath's and the "Ratio to Embree" table.
Run: /usr/bin/python3 tools/bench/test_bench.py (CTest: bench_harness, label bench)."""
import os
import sys
import tempfile
import unittest

try:
    import numpy as np
except ImportError as e:
    print("test_bench: %s: install python3-numpy" % e, file=sys.stderr)
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import embree  # noqa: E402
import metrics  # noqa: E402
import pfm  # noqa: E402
import report  # noqa: E402
import vkrun  # noqa: E402


class PfmTest(unittest.TestCase):
    def test_round_trip_keeps_orientation(self):
        img = np.arange(2 * 3 * 3, dtype=np.float32).reshape(2, 3, 3)  # row 0 = top
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "x.pfm")
            pfm.write_pfm(p, img)
            data = open(p, "rb").read()
            self.assertTrue(data.startswith(b"PF\n3 2\n-1.0\n"))
            # The file's first row is the image's bottom row (PFM order).
            first = np.frombuffer(data[len(b"PF\n3 2\n-1.0\n"):], "<f4", count=9)
            np.testing.assert_array_equal(first, img[1].ravel())
            np.testing.assert_array_equal(pfm.read_pfm(p), img)


class MetricsTest(unittest.TestCase):
    def test_known_values(self):
        x = np.zeros((1, 2, 3))
        y = np.zeros((1, 2, 3))
        x[0, 0, 0] = 1.0            # against y = 0: squared error 1, relative 1 / 0.01
        x[0, 1, 2], y[0, 1, 2] = 2.0, 4.0  # squared error 4, relative 4 / 16.01
        self.assertAlmostEqual(metrics.mse(x, y), 5.0 / 6.0)
        self.assertAlmostEqual(metrics.relmse(x, y), (100.0 + 4.0 / 16.01) / 6.0)

    def test_noise_floor_matches_the_true_error_of_the_average(self):
        # Two halves = truth + independent Gaussian noise (sigma 0.1): the average's MSE is
        # sigma^2 / 2 = 0.005. With 3 * 200 * 200 values the estimate's relative standard error is
        # ~sqrt(2 / 120000) = 0.4 %; the 3 % tolerance is > 7 standard errors (false failure < 1e-12).
        rng = np.random.default_rng(12345)
        truth = rng.uniform(0.0, 2.0, (200, 200, 3))
        a = truth + rng.normal(0.0, 0.1, truth.shape)
        b = truth + rng.normal(0.0, 0.1, truth.shape)
        floor_mse, floor_rel = metrics.noise_floor(a, b)
        self.assertAlmostEqual(floor_mse, 0.005, delta=0.03 * 0.005)
        self.assertAlmostEqual(floor_mse, metrics.mse(0.5 * (a + b), truth), delta=0.03 * 0.005)
        # relMSE: the same with the reference's denominator (close to the truth's here).
        true_rel = metrics.relmse(0.5 * (a + b), truth)
        self.assertAlmostEqual(floor_rel, true_rel, delta=0.05 * true_rel)

    def test_crossing_interpolates_in_log_log(self):
        pts = [(1.0, 1e-1), (10.0, 1e-2 * 0.5), (100.0, 1e-4)]
        # Between (1, 0.1) and (10, 0.005): log-linear in both axes.
        t = metrics.interpolate_crossing(pts, 1e-2)
        f = (np.log(1e-2) - np.log(1e-1)) / (np.log(5e-3) - np.log(1e-1))
        self.assertAlmostEqual(t, float(np.exp(f * np.log(10.0))))
        self.assertEqual(metrics.interpolate_crossing(pts, 1.0), 1.0)  # already below at the first point
        self.assertIsNone(metrics.interpolate_crossing(pts, 1e-5))

    def test_extrapolation_is_one_over_t(self):
        self.assertAlmostEqual(metrics.extrapolate_crossing(11.0, 1e-2, 1.0, 1e-3), 101.0)
        self.assertIsNone(metrics.extrapolate_crossing(1.0, 1e-2, 1.0, 1e-3))
        self.assertIsNone(metrics.extrapolate_crossing(5.0, -1.0, 1.0, 1e-3))

    def test_needed_spp(self):
        self.assertEqual(metrics.needed_total_spp(1e-2, 64, 1e-3), 640)


class SamplerListTest(unittest.TestCase):
    def test_parse_help(self):
        text = "render options:\n  --sampler S             bsdf | light | mixture (the book's) | mis (default)\n"
        self.assertEqual(vkrun.parse_samplers(text), (["bsdf", "light", "mixture", "mis"], "mis"))
        text = "  --sampler S             bsdf | light | mixture (default: mixture, the book's)\n"
        self.assertEqual(vkrun.parse_samplers(text), (["bsdf", "light", "mixture"], "mixture"))
        with self.assertRaises(vkrun.VkpathError):
            vkrun.parse_samplers("no such line")


class EmbreeCompareTest(unittest.TestCase):
    """embree.compare_means: z-scores of region means (the Embree reference against vkpath)."""

    def setUp(self):
        # A left/right asymmetric image (a red left half), Embree's variance of each pixel mean 1e-4.
        self.img = np.full((8, 8, 3), 0.5)
        self.img[:, :4, 0] = 0.9
        self.var = np.full((8, 8, 3), 1e-4)

    def test_identical_images_agree(self):
        rows = embree.compare_means(self.img, 100, self.img, self.var, 100)
        self.assertEqual(len(rows), 15)  # 5 regions x 3 channels
        self.assertTrue(all(r[4] == 0.0 for r in rows))

    def test_known_z(self):
        # Whole image: standard error sqrt(64 * 1e-4) / 64 = 1.25e-3 for Embree, times sqrt(1 + 100 / 400)
        # with vkpath's error included; an offset of 0.01 is z = 0.01 / (1.25e-3 * sqrt(1.25)).
        rows = embree.compare_means(self.img + 0.01, 400, self.img, self.var, 100)
        z = dict(((r[0], r[1]), r[4]) for r in rows)
        self.assertAlmostEqual(z[("image", "R")], 0.01 / (1.25e-3 * np.sqrt(1.25)), places=6)
        # A half has 32 pixels: its standard error is sqrt(2) times the whole image's.
        self.assertAlmostEqual(z[("left", "G")], z[("image", "G")] / np.sqrt(2.0), places=6)

    def test_mirrored_image_fails(self):
        rows = embree.compare_means(self.img[:, ::-1], 100, self.img, self.var, 100)
        z = dict(((r[0], r[1]), r[4]) for r in rows)
        self.assertEqual(z[("image", "R")], 0.0)  # the whole image's mean cannot see a mirror ...
        self.assertLess(z[("left", "R")], -100.0)  # ... its halves do
        self.assertGreater(z[("right", "R")], 100.0)

    def test_size_mismatch(self):
        with self.assertRaises(ValueError):
            embree.compare_means(self.img[:4], 100, self.img, self.var, 100)


class EmbreeReportTest(unittest.TestCase):
    def test_ratio_and_refused_rows(self):
        ok = {"name": "cornell-classic", "size": "64x64", "embree": {
            "threads": 2, "vkpath_rays_per_second": 5e6, "embree_rays_per_second": 1e7, "ratio": 0.5,
            "vkpath_rays_per_sample": 4.57, "embree_rays_per_sample": 4.56, "vkpath_spp": 400, "embree_spp": 900,
            "max_abs_z": 0.7}}
        refused = {"name": "env-sky", "size": "96x54", "embree": {"refused": "an environment map: not supported"}}
        lines = []
        report.write_embree_md(lines, [ok, refused], "mis")
        text = "\n".join(lines)
        self.assertIn("## Ratio to Embree", text)
        self.assertIn("| cornell-classic | 64x64 | 2 | 5 M | 10 M | **0.50x** | 4.570 / 4.560 | 400 / 900 | 0.7 |", text)
        self.assertIn("| env-sky | 96x54 | | | refused: an environment map: not supported |", text)


if __name__ == "__main__":
    unittest.main()
