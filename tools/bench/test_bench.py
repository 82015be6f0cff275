#!/usr/bin/python3
"""Unit tests of the benchmark harness's arithmetic (no vkpath run): PFM round trip, metrics, the
reference noise-floor estimate, threshold crossings, the sampler list of `vkpath --help`, the
comparison of the Embree reference's image with vkpath's and the "Ratio to Embree" table, error logs
with and without the denoised columns, the denoised image's crossings and the "Denoiser" tables.
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
try:
    import bench  # noqa: E402  (exits 77 without python3-matplotlib)
except SystemExit:
    bench = None
import cycles  # noqa: E402
import embree  # noqa: E402
import metrics  # noqa: E402
import pfm  # noqa: E402
import report  # noqa: E402
import room_direct  # noqa: E402
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


class RoomDirectTest(unittest.TestCase):
    """tools/bench/room_direct.py: its closed form and its pixel classification."""

    def test_polygon_irradiance_limits(self):
        # Under the light's centre, far below, the light is a small source: E = A / d^2 (per unit
        # radiance, to (size / d)^2); 1e-3 below its centre it fills the hemisphere: E -> pi.
        x = np.array([[278.0, 554.0 - 50000.0, 279.5]])
        n = np.array([[0.0, 1.0, 0.0]])
        self.assertAlmostEqual(room_direct.polygon_irradiance(x, n)[0] / (130 * 105 / 50000.0 ** 2), 1.0, places=5)
        x = np.array([[278.0, 554.0 - 1e-3, 279.5]])
        self.assertAlmostEqual(room_direct.polygon_irradiance(x, n)[0], np.pi, places=4)

    def test_pixels_on_one_surface_and_mixed_pixels(self):
        pure, expected = room_direct.closed_form(16)
        self.assertEqual(expected.shape, (16, 16, 3))
        for k in range(len(room_direct.SURFACES)):
            self.assertGreater((pure == k).sum(), 0, room_direct.SURFACES[k][0])
        self.assertGreater((pure == -1).sum(), 0)  # edges, the light, the black border
        ceiling = [i for i, s in enumerate(room_direct.SURFACES) if s[0] == "ceiling"][0]
        self.assertEqual(expected[pure == ceiling].max(), 0.0)  # it sees the light's back
        self.assertGreater(expected[pure == 0].min(), 0.0)


class MetricsTest(unittest.TestCase):
    def test_known_values(self):
        x = np.zeros((1, 2, 3))
        y = np.zeros((1, 2, 3))
        x[0, 0, 0] = 1.0            # against y = 0: squared error 1, relative 1 / 0.01
        x[0, 1, 2], y[0, 1, 2] = 2.0, 4.0  # squared error 4, relative 4 / 16.01
        self.assertAlmostEqual(metrics.mse(x, y), 5.0 / 6.0)
        self.assertAlmostEqual(metrics.relmse(x, y), (100.0 + 4.0 / 16.01) / 6.0)

    def test_median_interval_ranks(self):
        # Sign-test ranks (tables of the binomial distribution with p = 1/2): 15 values at 95 %: the
        # 4th smallest and largest, P(B(15) <= 3) = 576 / 32768, coverage 1 - 2 x that = 0.96484.
        m, lo, hi, cov = metrics.median_interval([15 - i for i in range(15)])  # any order
        self.assertEqual((m, lo, hi), (8.0, 4.0, 12.0))
        self.assertAlmostEqual(cov, 1.0 - 2.0 * 576.0 / 32768.0)
        self.assertEqual(metrics.median_interval([1, 2, 3, 4, 5, 6])[:3], (3.5, 1.0, 6.0))  # 6: the extremes, 0.969
        self.assertEqual(metrics.median_interval([3, 1, 2, 5, 4]), (3.0, None, None, None))  # 5 values: no 95 % interval
        self.assertEqual(metrics.median_interval([2.0])[0], 2.0)
        with self.assertRaises(ValueError):
            metrics.median_interval([])

    def test_median_interval_covers_the_median(self):
        # 4000 draws of 15 values from a skewed distribution (lognormal, median 1): the interval
        # must hold the median in 96.5 % of them, 3860 expected, standard deviation sqrt(4000 x
        # 0.965 x 0.035) = 11.6; the bounds 3790 and 3930 are 6 standard deviations away (false
        # failure about 2e-9), while a wrong rank, the 3rd or the 5th, would cover 99.3 % (3970)
        # or 88.2 % (3526).
        rng = np.random.default_rng(2026)
        covered = 0
        for _ in range(4000):
            _, lo, hi, _ = metrics.median_interval(rng.lognormal(0.0, 0.5, 15))
            covered += lo <= 1.0 <= hi
        self.assertGreater(covered, 3790)
        self.assertLess(covered, 3930)

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
        self.assertIn("| cornell-classic | 64x64 | 2 | 5 M | 10 M | **0.50x** | 1 | no interval (1 pair) | 4.570 / 4.560 "
                      "| 400 / 900 | 0.7 |", text)
        self.assertIn("| env-sky | 96x54 | | | refused: an environment map: not supported |", text)

    def test_pairs_and_the_targets_verdict(self):
        base = {"threads": 2, "vkpath_rays_per_second": 8e6, "embree_rays_per_second": 1e7, "ratio": 0.8,
                "vkpath_rays_per_sample": 4.57, "embree_rays_per_sample": 4.56, "vkpath_spp": 400, "embree_spp": 900,
                "max_abs_z": 0.7, "pairs": 15}
        met = dict(base, ratio_interval=[0.76, 0.83])
        lines = []
        report.write_embree_md(lines, [{"name": "cornell-classic", "size": "64x64", "embree": met}], "mis")
        self.assertIn("| **0.80x** | 15 (0.76-0.83x) | met |", "\n".join(lines))
        self.assertEqual(report.embree_verdict(dict(base, ratio_interval=[0.70, 0.74])), "not met")
        self.assertEqual(report.embree_verdict(dict(base, ratio_interval=[0.70, 0.80])),
                         "undecided (the interval contains 0.75x)")
        self.assertEqual(report.embree_verdict(dict(base, pairs=3)), "no interval (3 pairs)")
        self.assertEqual(report.embree_verdict(dict(base, ratio_interval=[0.75, 0.80])), "met")  # at the target counts


class CyclesTest(unittest.TestCase):
    def test_time_to_cycles_error_is_interpolated_in_log_log(self):
        # vkpath's MSE halves with each doubling of time (error ~ 1/t): Cycles' MSE 0.002 is reached at
        # 5 s from the rows at 4 s (0.0025) and 8 s (0.00125); Cycles took 10 s, so the ratio is 0.5.
        pts = [(2.0, 0.005), (4.0, 0.0025), (8.0, 0.00125)]
        r = cycles.result(0.002, 10.0, pts, 1e-5)
        self.assertAlmostEqual(r["vkpath_seconds"], 5.0)
        self.assertAlmostEqual(r["ratio"], 0.5)
        self.assertFalse(r["target_met"])
        self.assertAlmostEqual(r["cycles_rmse"], 0.002 ** 0.5)
        self.assertEqual(r["vkpath_final_mse"], 0.00125)
        self.assertTrue(cycles.result(0.002, 20.0, pts, 1e-5)["target_met"])  # 5 s / 20 s = 0.25
        # Never as low: not reached, no ratio, target not met (a bias between the renderers shows so).
        r = cycles.result(0.001, 10.0, pts, 1e-5)
        self.assertIsNone(r["vkpath_seconds"])
        self.assertIsNone(r["ratio"])
        self.assertFalse(r["target_met"])

    def test_report(self):
        ok = {"name": "cornell-classic", "size": "256x256", "cycles": dict(
            cycles.result(0.002, 10.0, [(2.0, 0.005), (4.0, 0.0025), (8.0, 0.00125)], 1.5e-5), blender="Blender 3.4.1",
            threads=2, size="256x256", cycles_spp=256, reference_spp=8192, vkpath_spp=900,
            vkpath_samples_per_second=1e6, vkpath_mean_rel_diff=0.002, cycles_mean_rel_diff=0.0004)}
        missing = {"name": "cornell-classic", "size": "64x64", "cycles": {"refused": "blender is not installed"}}
        lines = []
        report.write_cycles_md(lines, [ok, missing], "mis")
        text = "\n".join(lines)
        self.assertIn("## Time to Cycles' error", text)
        self.assertIn("| cornell-classic | 256x256 | 2 | 256 | 0.002 | 10.00 | 5.00 | **0.50x** | 1 | not met | 8192 "
                      "(1.5e-05) | 0.20% / 0.04% | Blender 3.4.1 |", text)
        self.assertIn("| cornell-classic | 64x64 | | | | | | not measured: blender is not installed |", text)

    def test_pairs_combine_to_a_median_interval_and_verdict(self):
        pts = [(2.0, 0.005), (4.0, 0.0025), (8.0, 0.00125)]  # Cycles' MSE 0.002 reached at 5 s

        def pairs(*cycles_seconds):
            return [cycles.result(0.002, s, pts, 1e-5) for s in cycles_seconds]

        # Seven pairs, ratios 5/s: 0.25 ... 0.357; the interval of 7 values at 95 %: the extremes.
        met = cycles.combine(pairs(20.0, 18.0, 16.0, 15.0, 14.0, 19.0, 17.0))
        self.assertEqual(met["pairs"], 7)
        self.assertAlmostEqual(met["ratio"], 5.0 / 17.0)
        self.assertAlmostEqual(met["ratio_interval"][0], 0.25)
        self.assertAlmostEqual(met["ratio_interval"][1], 5.0 / 14.0)
        self.assertAlmostEqual(met["cycles_seconds"], 17.0)
        self.assertAlmostEqual(met["vkpath_seconds"], 5.0)
        self.assertEqual((met["verdict"], met["target_met"]), ("met", True))
        # An interval around 0.4 (5/13.5 = 0.37 ... 5/11 = 0.45): undecided; wholly above: not met.
        self.assertEqual(cycles.combine(pairs(13.5, 13.0, 12.5, 12.0, 11.5, 11.0, 12.2))["verdict"],
                         "undecided (the interval contains 0.4x)")
        self.assertEqual(cycles.combine(pairs(10.0, 11.0, 12.0, 10.5, 11.5, 9.0, 8.0))["verdict"], "not met")
        # Too few pairs for an interval; a pair that never reached Cycles' error.
        self.assertEqual(cycles.combine(pairs(20.0, 18.0, 16.0))["verdict"], "no interval (3 pairs)")
        missed = cycles.combine(pairs(20.0, 18.0) + [cycles.result(0.001, 20.0, pts, 1e-5)])
        self.assertIsNone(missed["ratio"])
        self.assertFalse(missed["target_met"])
        self.assertEqual(missed["verdict"], "not met (Cycles' error not reached in 1 of 3 pairs)")
        with self.assertRaises(ValueError):
            cycles.combine([])
        # The report shows the pairs, the interval and the verdict.
        row = dict(met, blender="Blender 3.4.1", threads=2, size="256x256", cycles_spp=256, reference_spp=8192,
                   vkpath_spp=900, vkpath_samples_per_second=1e6, vkpath_mean_rel_diff=0.002,
                   cycles_mean_rel_diff=0.0004)
        lines = []
        report.write_cycles_md(lines, [{"name": "cornell-classic", "size": "256x256", "cycles": row}], "mis")
        self.assertIn("| 17.00 | 5.00 | **0.29x** | 7 (0.25-0.36x) | met |", "\n".join(lines))


RAW_LOG = """spp,seconds,rmse,relmse,mean_r,mean_g,mean_b
1,4.959290,0.568653892,0.264086336,0.168121367,0.147849276,0.135076589
2,4.966834,0.262297039,0.144674988,0.170822742,0.151613332,0.138137519
"""
DENOISED_LOG = """spp,seconds,rmse,relmse,mean_r,mean_g,mean_b,rmse_denoised,relmse_denoised,denoise_seconds
1,4.959290,0.568653892,0.264086336,0.168121367,0.147849276,0.135076589,0.568653892,0.264086339,0.007141
2,4.966834,0.262297039,0.144674988,0.170822742,0.151613332,0.138137519,0.259448097,0.0191623866,0.005604
"""


class ErrorLogTest(unittest.TestCase):
    def read(self, text):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "log.csv")
            with open(p, "w") as f:
                f.write(text)
            return vkrun.read_error_log(p)

    def test_without_denoised_columns(self):
        rows = self.read(RAW_LOG)
        self.assertEqual([r["spp"] for r in rows], [1, 2])
        self.assertIsInstance(rows[1]["spp"], int)
        self.assertAlmostEqual(rows[1]["relmse"], 0.144674988)
        self.assertNotIn("relmse_denoised", rows[0])
        self.assertFalse(vkrun.has_denoised(rows))

    def test_with_denoised_columns(self):
        rows = self.read(DENOISED_LOG)
        self.assertTrue(vkrun.has_denoised(rows))
        self.assertAlmostEqual(rows[1]["relmse_denoised"], 0.0191623866)
        self.assertAlmostEqual(rows[1]["rmse_denoised"], 0.259448097)
        self.assertAlmostEqual(rows[0]["denoise_seconds"], 0.007141)
        self.assertAlmostEqual(rows[1]["relmse"], 0.144674988)  # the raw columns are unchanged

    def test_missing_columns_are_an_error(self):
        with self.assertRaises(vkrun.VkpathError):  # only some of the denoised columns
            self.read(DENOISED_LOG.replace(",denoise_seconds\n", "\n").replace(",0.007141\n", "\n")
                      .replace(",0.005604\n", "\n"))
        with self.assertRaises(vkrun.VkpathError):  # no relmse
            self.read("spp,seconds,rmse\n1,1.0,0.5\n")


def denoised_row(spp, seconds, relmse, relmse_denoised, denoise_seconds=0.01):
    return {"spp": spp, "seconds": seconds, "relmse": relmse, "relmse_denoised": relmse_denoised,
            "denoise_seconds": denoise_seconds}


@unittest.skipIf(bench is None, "bench.py needs python3-matplotlib")
class DenoisedCrossingsTest(unittest.TestCase):
    def test_measured_crossing_at_ready_time(self):
        # Crosses 1e-2 between the 2nd and 3rd points, interpolated in log-log at seconds + denoise_seconds.
        rows = bench.mark_limited([denoised_row(1, 1.0, 0.5, 0.1), denoised_row(2, 2.0, 0.25, 0.02, 0.5),
                                   denoised_row(4, 4.0, 0.12, 0.005, 0.5)], 1e-6)
        c = bench.denoised_crossings(rows, 1e-6)
        self.assertEqual(c["0.01"]["how"], "measured")
        self.assertAlmostEqual(c["0.01"]["seconds"], metrics.interpolate_crossing([(2.5, 0.02), (4.5, 0.005)], 1e-2))
        self.assertGreater(c["0.01"]["seconds"], 2.5)

    def test_no_extrapolation(self):
        # A biased curve that flattens at 5e-3: 1e-3 is "not reached", though a ~1/t extrapolation of the
        # last point would give a time (the raw crossings() does extrapolate).
        rows = bench.mark_limited([denoised_row(1, 1.0, 0.5, 0.02), denoised_row(2, 2.0, 0.25, 0.006),
                                   denoised_row(4, 4.0, 0.12, 0.005)], 1e-6)
        c = bench.denoised_crossings(rows, 1e-6)
        self.assertEqual(c["0.001"], {"seconds": None, "how": "not reached"})
        self.assertEqual(bench.crossings(rows, 1e-6, 0.5)["0.001"]["how"], "extrapolated")

    def test_reference_limited(self):
        # Floor 1e-3: a denoised point at 3e-3 is reference-limited (1e-3 > 0.2 * 3e-3) and not used;
        # the 1e-3 threshold is below 5x the floor: it cannot be measured at all.
        rows = bench.mark_limited([denoised_row(1, 1.0, 0.5, 0.02), denoised_row(2, 2.0, 0.25, 0.003)], 1e-3)
        self.assertEqual([r["ref_limited_denoised"] for r in rows], [False, True])
        self.assertEqual([r["ref_limited"] for r in rows], [False, False])
        c = bench.denoised_crossings(rows, 1e-3)
        self.assertEqual(c["0.01"], {"seconds": None, "how": "not reached"})
        self.assertEqual(c["0.001"]["how"], "reference-limited")

    def test_mark_limited_without_denoised_columns(self):
        rows = bench.mark_limited([{"spp": 1, "seconds": 1.0, "relmse": 1e-3}], 1e-3)
        self.assertTrue(rows[0]["ref_limited"])
        self.assertNotIn("ref_limited_denoised", rows[0])


@unittest.skipIf(bench is None, "bench.py needs python3-matplotlib")
class DenoiseReportTest(unittest.TestCase):
    def scene(self):
        row16 = bench.denoise_result(16, denoised_row(16, 5.0, 0.016, 0.0012, 0.0055), 1e-5, 0.011)
        row64 = bench.denoise_result(64, denoised_row(64, 5.1, 0.004, 0.0008, 0.022), 2e-4, 0.011)
        return {"name": "cornell-classic", "size": "64x64", "reference": {"floor_relmse": 2e-4},
                "samplers": {"mis": {"crossings": {"0.01": {"seconds": 5.2, "how": "measured"},
                                                   "0.001": {"seconds": 40.0, "how": "extrapolated"}},
                                     "crossings_denoised": {"0.01": {"seconds": 5.01, "how": "measured"},
                                                            "0.001": {"seconds": None, "how": "not reached"}}}},
                "denoise": {"time_spp": 4, "seconds_4spp": 0.011, "seconds_4spp_render": 0.02, "target": 0.1,
                            "runs": [row16, row64]}}

    def test_result(self):
        r16, r64 = self.scene()["denoise"]["runs"]
        self.assertAlmostEqual(r16["ratio"], 0.075)
        self.assertTrue(r16["target_met"])
        self.assertAlmostEqual(r16["time_ratio"], 0.5)
        self.assertTrue(r16["time_target_met"])
        self.assertAlmostEqual(r64["ratio"], 0.2)
        self.assertFalse(r64["target_met"])
        self.assertFalse(r64["time_target_met"])
        self.assertTrue(r64["ref_limited_denoised"])   # 2e-4 > 0.2 * 8e-4
        self.assertFalse(r64["ref_limited"])

    def test_tables(self):
        lines = []
        report.write_denoise_md(lines, [self.scene(), {"name": "env-sky", "size": "96x54", "samplers": {}}],
                                [1e-2, 1e-3], "mis")
        text = "\n".join(lines)
        self.assertIn("## Denoiser", text)
        self.assertIn("The denoised image is biased (its error does not go to zero as spp grows); the raw image is "
                      "unbiased.", text)
        self.assertIn("| scene | sampler | t(relMSE ≤ 0.01) raw | denoised | t(relMSE ≤ 0.001) raw | denoised |", text)
        self.assertIn("| cornell-classic | mis | 5.2 s | 5.01 s | ≈ 40 s (extrap.) | n/a (not reached) |", text)
        self.assertIn("| scene | size | spp | raw relMSE | denoised relMSE | denoised / raw | floor out | ≤ 0.1 | denoise s "
                      "| 4-spp s | denoise / 4 spp |", text)
        self.assertIn("| cornell-classic | 64x64 | 16 | 0.016 | 0.0012 | 0.075 | 0.063 | met | 0.0055 | 0.011 | 0.50 (met) |",
                      text)
        self.assertIn("| cornell-classic | 64x64 | 64 | 0.004 | 0.0008* | 0.200 | 0.158 | not met | 0.022 | 0.011 "
                      "| 2.00 (not met) |", text)
        self.assertNotIn("env-sky", text)  # no denoised numbers: no row


class FloorCorrectedRatioTest(unittest.TestCase):
    def test_floor_out(self):
        self.assertAlmostEqual(report.floor_corrected_ratio(0.0102, 0.0012, 2e-4), 0.1)
        self.assertAlmostEqual(report.floor_corrected_ratio(0.01, 0.001, 0.0), 0.1)
        self.assertIsNone(report.floor_corrected_ratio(0.01, 0.0012, 1e-3))  # within 1.25x the floor
        self.assertIsNone(report.floor_corrected_ratio(1e-3, 2e-3, 1e-3))    # raw at the floor
        self.assertIsNone(report.floor_corrected_ratio(0.01, 0.001, None))


class CurvesCsvTest(unittest.TestCase):
    def test_denoised_columns(self):
        raw = {"spp": 1, "seconds": 1.0, "rmse": 0.5, "relmse": 0.25, "mean_r": 0.1, "mean_g": 0.2, "mean_b": 0.3,
               "ref_limited": False}
        den = dict(raw, rmse_denoised=0.1, relmse_denoised=0.02, denoise_seconds=0.005, ref_limited_denoised=True)
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "c.csv")
            report.write_curves_csv(p, "s", {"bsdf": [raw], "mis": [den]}, {"floor_relmse": 0.0, "floor_mse": 0.0})
            with open(p) as f:
                lines = f.read().splitlines()
        self.assertTrue(lines[0].endswith(",rmse_denoised,relmse_denoised,denoise_seconds,ref_limited_denoised"))
        self.assertTrue(lines[1].endswith(",0.3,,,,"))
        self.assertTrue(lines[2].endswith(",0.3,0.1,0.02,0.005000,1"))


if __name__ == "__main__":
    unittest.main()
