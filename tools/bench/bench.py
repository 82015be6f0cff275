#!/usr/bin/python3
"""vkpath's benchmark suite: run time against error (docs/performance.md "The benchmark suite").

For each scene (cornell-book3, cornell-classic, cornell-lights (25 lights of very different power),
spheres-book1, env-sky (environment-lit) and a generated dense-mesh scene) it
  1. makes or reuses a cached reference (references.py) and states its spp and noise floor;
  2. warms Mesa's shader cache for every pipeline it will time, then measures the time to first
     pixel with a fresh, empty cache (cold) and again with the same cache (warm);
  3. renders one time-limited run per sampler with --reference/--error-log (rows at 1, 2, 4, ... spp):
     the time-versus-error curve, the samples/s and rays/s, and the time to reach each relMSE threshold;
     the default sampler's run has --denoise, so its log also gives the denoised image's curve and
     times (measured only: the denoised image is biased, its error is not extrapolated);
  4. compares LP_NUM_THREADS=1 with 2, and --variant auto with --variant full (steady samples/s);
  5. where the Embree reference is built (tests/bench/embree_reference, embree.py), runs it and
     vkpath for the same time at the same size and thread count: "ratio to Embree" = vkpath's
     rays/s over Embree's, and their images' means must agree within noise (scenes it does not
     support are listed with its reason); with --embree-pairs N, N pairs alternating which runs
     first, and the median ratio with its distribution-free 95 % interval (target: at least 0.75,
     met when the interval's lower end is; reported, never failed);
  6. the denoiser (issue 17): renders of exactly 16 and 64 spp with --denoise: the raw and denoised
     relMSE, their ratio (target: at most 0.1), and the denoiser's seconds over the time of 4 spp
     (target: at most 1); the targets are reported as met or not, never failed;
  7. where Blender is installed and the scene has a Cycles twin (cycles.py: cornell-classic), the time
     to Cycles' error (issue 18): Cycles renders CYCLES_SPP spp, timed by its own render call; vkpath
     renders until its MSE against the same Cycles reference is as low; the ratio of the times
     (target: at most 0.4) is reported, never failed; with --cycles-pairs N, N pairs alternating
     which renders first, and the median ratio with its interval (met when the interval's upper end
     is at most 0.4);
and writes OUT/<scene>.csv, OUT/summary.md, OUT/summary.json and OUT/relmse_vs_time.png.

Usage: bench.py [--quick] --vkpath BUILD/vkpath [--embree BUILD/tests/bench/embree_reference | --no-embree]
                [--out DIR] [--cache DIR] [--scenes a,b] [--refresh-references] [--ref-budget S]
                [--curve-seconds S] [--embree-seconds S] [--embree-pairs N] [--cycles-pairs N] [--parts curves,scaling,settings,embree,denoise,cycles]
Exit status: 0 when every check passed, 1 when one failed (listed in summary.md), 77 when
python3-matplotlib or python3-numpy is missing (CTest reports the test as skipped).
"""
import argparse
import datetime
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import time

try:
    import numpy  # also for pfm.py and metrics.py
    import matplotlib  # noqa: F401
except ImportError as e:
    print("bench: %s: install python3-numpy and python3-matplotlib (tools/deps.sh --bench)" % e, file=sys.stderr)
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles  # noqa: E402
import embree  # noqa: E402
import metrics  # noqa: E402
import pfm  # noqa: E402
import references  # noqa: E402
import report  # noqa: E402
import vkrun  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
THRESHOLDS = (1e-2, 1e-3)
LIMITED_FRACTION = 0.2  # a point whose reference floor is above 20 % of its error is reference-limited
BIG_SPP = 1 << 24       # runs are limited by --time

# name, scene file (None: generated), full size, quick size
SCENES = [
    ("cornell-book3", "scenes/cornell-book3.json", (256, 256), (64, 64)),
    ("cornell-classic", "scenes/cornell-classic.json", (256, 256), (64, 64)),
    ("cornell-lights", "scenes/cornell-lights.json", (256, 256), (64, 64)),
    ("spheres-book1", "scenes/spheres-book1.json", (320, 180), (96, 54)),
    ("env-sky", "scenes/env-sky.json", (320, 180), (96, 54)),
    ("final-scene-book2", "scenes/next-week/final-scene.json", (200, 200), (64, 64)),
    ("dense-mesh", None, (256, 256), (64, 64)),
]
MODES = {
    # curve: seconds of rendering per sampler; scaling: per thread/variant run; ref_budget: seconds
    # for one scene's reference; mesh: the dense-mesh grid (2 * nu * (nv - 1) triangles).
    "full": dict(curve=60.0, scaling=20.0, settings=20.0, ref_budget=2700.0, pilot_spp=16, mesh=(1024, 512),
                 load_timeout=900, cycles_ref_spp=8192),
    "quick": dict(curve=6.0, scaling=3.0, settings=3.0, ref_budget=150.0, pilot_spp=16, mesh=(128, 64),
                  load_timeout=120, cycles_ref_spp=2048),
}
PARTS = ("curves", "scaling", "settings", "embree", "denoise", "cycles")
CYCLES_SPP = 256  # issue 18: the error of Cycles at 256 spp, against a Cycles reference (cfg cycles_ref_spp)
DENOISE_SPP = (16, 64)   # the denoise part's renders
DENOISE_TARGET = 0.1     # issue 17: the denoised relMSE at most a tenth of the raw image's at the same spp ...
DENOISE_TIME_SPP = 4     # ... and the denoiser's own time at most that of 4 spp at the same size
EMBREE_Z_MAX = 5.0  # the Embree image's region means must agree with vkpath's within this many standard errors
# Equal-time comparisons of one setting against the default (same sampler, same --time): what each
# knob buys. name -> extra vkpath arguments.
SETTINGS = [
    ("default", []),
    ("uniform light pick", ["--light-pick", "uniform"]),
    ("area light sampling", ["--light-sampling", "area"]),
    ("solid-angle light sampling", ["--light-sampling", "solid-angle"]),
    ("solid-angle-min 0.05", ["--solid-angle-min", "0.05"]),
    ("solid-angle-min 0.1", ["--solid-angle-min", "0.1"]),
    ("solid-angle-min 0.5", ["--solid-angle-min", "0.5"]),
    ("solid-angle-min 1", ["--solid-angle-min", "1"]),
    ("solid-angle-min 3", ["--solid-angle-min", "3"]),
    ("random sequence", ["--sequence", "random"]),
    ("linear tile order", ["--tile-order", "linear"]),
    ("workgroup 4x4", ["--workgroup", "4x4"]),
    ("workgroup 16x8", ["--workgroup", "16x8"]),
    ("workgroup 16x16", ["--workgroup", "16x16"]),
    ("adaptive 0.02", ["--adaptive", "0.02"]),
    ("adaptive 0.05", ["--adaptive", "0.05"]),
    ("rr-depth 1", ["--rr-depth", "1"]),
    ("rr-depth 2", ["--rr-depth", "2"]),
    ("rr-depth 5", ["--rr-depth", "5"]),
    ("rr-depth 8", ["--rr-depth", "8"]),
    ("no roulette", ["--rr-depth", "1024"]),
    ("1 sample/dispatch", ["--samples-per-dispatch", "1"]),
    ("2 samples/dispatch", ["--samples-per-dispatch", "2"]),
    ("4 samples/dispatch", ["--samples-per-dispatch", "4"]),
    ("8 samples/dispatch", ["--samples-per-dispatch", "8"]),
    ("16 samples/dispatch", ["--samples-per-dispatch", "16"]),
    ("spatial splits", ["--spatial-splits"]),  # the BVH build (docs/performance.md "Spatial splits")
]


def log(msg):
    print(msg, flush=True)


def load_average():
    try:
        return open("/proc/loadavg").read().split()[0]
    except OSError:
        return "?"


def cpu_model():
    """The CPU as the machine names it (/proc/cpuinfo's first "model name"; a virtual machine may name
    only the family), with its widest vector extension: ratios to Embree have moved between days,
    and a different host is one possible cause (docs/performance.md "Ratio to Embree")."""
    try:
        text = open("/proc/cpuinfo").read()
    except OSError:
        return "?"
    name = next((line.split(":", 1)[1].strip() for line in text.splitlines() if line.startswith("model name")), "?")
    flags = next((line.split(":", 1)[1].split() for line in text.splitlines() if line.startswith("flags")), [])
    widest = "avx512f" if "avx512f" in flags else "avx2" if "avx2" in flags else "sse"
    return "%s (%s)" % (name, widest)


def git_describe():
    try:
        head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return head + ("+changes" if dirty else "") if head else "?"
    except OSError:
        return "?"


def scene_file(name, path, cfg, size, cache):
    if path is not None:
        return ROOT / path
    nu, nv = cfg["mesh"]
    out = pathlib.Path(cache) / "scenes" / ("dense-mesh-glb-%dx%d-%dx%d.json" % (nu, nv, size[0], size[1]))
    if not out.exists() or not out.with_name(out.stem + "-blob.glb").exists():
        out.parent.mkdir(parents=True, exist_ok=True)
        subprocess.run([sys.executable, str(ROOT / "tools/bench/gen_dense_mesh.py"), str(out), "--nu", str(nu),
                        "--nv", str(nv), "--width", str(size[0]), "--height", str(size[1])], check=True)
    return out


def crossings(rows, floor_rel, t_start):
    """Threshold -> {"seconds", "how"} from reliable rows (measured or extrapolated ~1/t)."""
    good = [(r["seconds"], r["relmse"]) for r in rows if not r["ref_limited"]]
    out = {}
    for thr in THRESHOLDS:
        # A threshold below 5x the floor cannot be measured (its points are reference-limited), only
        # extrapolated from the reliable points.
        t = metrics.interpolate_crossing(good, thr) if floor_rel <= LIMITED_FRACTION * thr else None
        if t is not None:
            out[str(thr)] = {"seconds": t, "how": "measured"}
        elif good:
            t_last, e_last = good[-1]
            out[str(thr)] = {"seconds": metrics.extrapolate_crossing(t_last, e_last - floor_rel, t_start, thr),
                             "how": "extrapolated"}
        else:
            out[str(thr)] = {"seconds": None, "how": "no reliable point"}
    return out


def denoised_crossings(rows, floor_rel):
    """Threshold -> {"seconds", "how"} of the denoised image (error-log rows with the denoised columns
    and "ref_limited_denoised"): measured crossings only, at seconds + denoise_seconds (when the
    denoised image is ready). The denoised image is biased, its error need not fall ~1/t: a threshold
    that no reliable point reaches is "not reached", never extrapolated."""
    good = [(r["seconds"] + r["denoise_seconds"], r["relmse_denoised"]) for r in rows
            if not r["ref_limited_denoised"]]
    out = {}
    for thr in THRESHOLDS:
        if floor_rel > LIMITED_FRACTION * thr:
            out[str(thr)] = {"seconds": None, "how": "reference-limited"}
            continue
        t = metrics.interpolate_crossing(good, thr)
        out[str(thr)] = {"seconds": t, "how": "measured"} if t is not None else {"seconds": None, "how": "not reached"}
    return out


def mark_limited(rows, floor_rel):
    """Marks each error-log row reference-limited ("ref_limited", and "ref_limited_denoised" where the
    row has a denoised error) when the reference's floor is above LIMITED_FRACTION of its error."""
    for r in rows:
        r["ref_limited"] = floor_rel > LIMITED_FRACTION * r["relmse"]
        if "relmse_denoised" in r:
            r["ref_limited_denoised"] = floor_rel > LIMITED_FRACTION * r["relmse_denoised"]
    return rows


def denoise_result(spp, row, floor_rel, seconds_4spp):
    """The denoise part's numbers at `spp` from the error log's last row (with the denoised columns):
    raw and denoised relMSE, their ratio against DENOISE_TARGET, and the denoiser's seconds over
    `seconds_4spp` (the time of DENOISE_TIME_SPP spp at the same size). Targets are reported, not
    enforced."""
    raw, den, secs = row["relmse"], row["relmse_denoised"], row["denoise_seconds"]
    ratio = den / raw if raw > 0 else None
    time_ratio = secs / seconds_4spp if seconds_4spp else None
    return {"spp": spp, "relmse": raw, "relmse_denoised": den, "ratio": ratio,
            "target_met": ratio is not None and ratio <= DENOISE_TARGET,
            "ref_limited": floor_rel > LIMITED_FRACTION * raw,
            "ref_limited_denoised": floor_rel > LIMITED_FRACTION * den,
            "denoise_seconds": secs, "time_ratio": time_ratio,
            "time_target_met": time_ratio is not None and time_ratio <= 1.0}


def bench_denoise(vk, scene, runs, wh, ref, env, name, failures):
    """The denoiser at DENOISE_SPP spp (default sampler, --denoise, no --time) against the reference,
    and one DENOISE_TIME_SPP-spp render without it for the time of those samples (steady rate: the
    first batch's JIT left out). Failures only for broken runs: a missing denoised column or image,
    a non-finite denoised image or error; the targets are measured and reported."""
    base = vk.render(scene, runs, "denoise-time", wh + ["--spp", DENOISE_TIME_SPP, "-o", "denoise-time.pfm"], env)
    seconds_4spp = DENOISE_TIME_SPP * base["pixels"] / steady(base)
    out = {"time_spp": DENOISE_TIME_SPP, "seconds_4spp": seconds_4spp, "seconds_4spp_render": base["seconds_render"],
           "target": DENOISE_TARGET, "runs": []}
    for spp in DENOISE_SPP:
        tag = "denoise-%d" % spp
        logf = os.path.join(runs, tag + ".csv")
        st = vk.render(scene, runs, tag, wh + ["--spp", spp, "--denoise", "--reference", ref["path"],
                                              "--error-log", logf, "-o", tag + ".pfm"], env)
        for bad in ("nonfinite_samples", "loop_guard_paths"):
            if st[bad]:
                failures.append("%s/denoise %d spp: %d %s" % (name, spp, st[bad], bad))
        rows = vkrun.read_error_log(logf)
        if not vkrun.has_denoised(rows) or rows[-1]["spp"] != spp:
            failures.append("%s/denoise %d spp: the error log has no denoised row at %d spp" % (name, spp, spp))
            continue
        image_path = os.path.join(runs, tag + ".denoised.pfm")
        if not os.path.exists(image_path):
            failures.append("%s/denoise %d spp: --denoise wrote no %s" % (name, spp, image_path))
            continue
        r = denoise_result(spp, rows[-1], ref["floor_relmse"], seconds_4spp)
        if not numpy.isfinite(pfm.read_pfm(image_path)).all() or not math.isfinite(r["relmse_denoised"]):
            failures.append("%s/denoise %d spp: non-finite denoised image (relMSE %s)" %
                            (name, spp, r["relmse_denoised"]))
        r["samples_per_second"] = steady(st)
        out["runs"].append(r)
        log("  denoised %d spp: relMSE %.3g raw, %.3g denoised (ratio %s), denoiser %.3g s = %.2fx the time of "
            "%d spp" % (spp, r["relmse"], r["relmse_denoised"], "%.3f" % r["ratio"] if r["ratio"] is not None else "—",
            r["denoise_seconds"], r["time_ratio"] or 0.0, DENOISE_TIME_SPP))
    return out


def steady(st):
    return st["samples_per_second_steady"] or st["samples_per_second"]


def bench_embree(vk, em, scene, runs, wh, seconds, startup, env, name, failures, pairs=1):
    """The Embree reference and vkpath (default sampler), the same size, thread count and render time,
    one after the other, `pairs` times (alternating which goes first, so that neither always gets the
    machine's first minute): their rays/s, the ratio, rays per sample, and the agreement of their
    image means (embree.compare_means, every pair); {"refused": reason} for a scene the reference
    does not support. With several pairs the ratio is the median of the pairs' ratios, with its
    distribution-free 95 % interval (metrics.median_interval) from 6 pairs on: on a machine whose
    speed drifts by tens of per cent within minutes, one pair says little."""
    def run_embree():
        return em.render(scene, runs, "embree", wh + ["--spp", BIG_SPP, "--time", "%.3f" % seconds, "-o", "embree.pfm",
                                                     "--variance", "embree-var.pfm"], env)

    def run_vkpath():
        return vk.render(scene, runs, "embree-pair-vkpath", wh + ["--spp", BIG_SPP, "--time", "%.3f" % (seconds + startup),
                                                                 "-o", "embree-pair-vkpath.pfm"], env)

    results = []
    worst_z = 0.0
    for i in range(pairs):
        embree_first = i % 2 == 0
        try:
            if embree_first:
                e = run_embree()
                v = run_vkpath()
            else:
                v = run_vkpath()
                e = run_embree()
        except embree.EmbreeRefused as ex:  # on the first pair, before vkpath runs
            log("  Embree reference: %s" % ex)
            reason = str(ex)
            if reason.startswith(str(scene) + ": "):
                reason = reason[len(str(scene)) + 2:]
            return {"refused": reason.replace("|", "/")}
        rows = embree.compare_means(pfm.read_pfm(os.path.join(runs, "embree-pair-vkpath.pfm")), v["spp"],
                                    pfm.read_pfm(os.path.join(runs, "embree.pfm")),
                                    pfm.read_pfm(os.path.join(runs, "embree-var.pfm")), e["spp"])
        worst = max(rows, key=lambda r: abs(r[4]))
        if not abs(worst[4]) <= EMBREE_Z_MAX:
            failures.append("%s: Embree and vkpath images differ: %s %s mean: Embree %.6g, vkpath %.6g (z %.1f)" %
                            (name, worst[0], worst[1], worst[3], worst[2], worst[4]))
        worst_z = max(worst_z, abs(worst[4]))
        vk_rate = v["rays_per_second_steady"] or v["rays_per_second"]
        results.append((e, v, vk_rate))
        if pairs > 1:
            log("  pair %d of %d (%s first): vkpath %.3g, Embree %.3g rays/s: %.3fx" %
                (i + 1, pairs, "embree" if embree_first else "vkpath", vk_rate, e["rays_per_second"],
                 vk_rate / e["rays_per_second"]))
    e, v, _ = results[0]  # versions, threads, spp and rays per sample: the first pair's
    ratios = [r / ee["rays_per_second"] for ee, _, r in results]
    median, lo, hi, coverage = metrics.median_interval(ratios)
    out = {"embree_version": e["embree_version"], "threads": e["threads"],
           "vkpath_lp_num_threads": (v.get("environment") or {}).get("LP_NUM_THREADS"),
           "seconds": seconds, "pairs": pairs,
           "embree_rays_per_second": float(numpy.median([ee["rays_per_second"] for ee, _, _ in results])),
           "vkpath_rays_per_second": float(numpy.median([r for _, _, r in results])),
           "ratio": median, "ratios": ratios, "ratio_interval": [lo, hi] if lo is not None else None,
           "ratio_interval_coverage": coverage,
           "embree_spp": e["spp"], "vkpath_spp": v["spp"],
           "embree_rays_per_sample": e["rays"] / e["samples"], "vkpath_rays_per_sample": v["rays"] / v["samples"],
           "max_abs_z": worst_z}
    interval = (", median of %d pairs, %.0f %% interval %.3f-%.3fx" % (pairs, 100 * coverage, lo, hi) if lo is not None
                else ", median of %d pairs" % pairs if pairs > 1 else "")
    log("  ratio to Embree: %.2fx%s (vkpath %.3g, Embree %.3g rays/s, %d threads; means agree within %.1f standard "
        "errors)" % (out["ratio"], interval, out["vkpath_rays_per_second"], out["embree_rays_per_second"], e["threads"],
                     worst_z))
    return out


def bench_cycles(vk, cy, name, scene, size, cfg, args, runs, env, startup, failures):
    """The time to Cycles' error (cycles.py): Cycles' CYCLES_SPP-spp render and its render time, then
    vkpath (default sampler, same thread count) with --reference set to the same Cycles reference
    until at least 3x Cycles' time; vkpath's time to Cycles' MSE from its error log (seconds from
    process start). With --cycles-pairs N, N such pairs, alternating which renderer goes first (a
    vkpath-first pair's budget is the previous Cycles time's), combined by cycles.combine: the
    median ratio, its interval and the verdict. Cycles' and vkpath's image means against the
    reference's are reported too (the first pair's; a bias between the renderers would show there
    and hold vkpath's error above Cycles')."""
    W, H = size
    if W != H:
        raise cycles.CyclesError("the Cornell twin renders square images only, not %dx%d" % (W, H))
    threads = os.cpu_count() or 1
    ref = cycles.reference(cy, name, cycles.TWINS[name], W, cfg["cycles_ref_spp"], threads, args.cache, log)
    ref_mean = ref["image"].reshape(-1, 3).mean(axis=0)
    logf = os.path.join(runs, "cycles-pair-vkpath.csv")
    pairs = args.cycles_pairs
    last = {}

    def run_cycles():
        image, seconds = cy.render(cycles.TWINS[name], os.path.join(runs, "cycles-run.pfm"), W, CYCLES_SPP,
                                   cycles.RUN_SEED, threads)
        last.update(image=image, seconds=seconds, mse=metrics.mse(image, ref["image"]))

    def run_vkpath():
        budget = 3.0 * last["seconds"] + startup + 2.0
        st = vk.render(scene, runs, "cycles-pair-vkpath", ["--width", W, "--height", H, "--spp", BIG_SPP, "--time",
                                                           "%.3f" % budget, "--reference", ref["path"], "--error-log",
                                                           logf, "-o", "cycles-pair-vkpath.pfm"],
                       dict(env, LP_NUM_THREADS=threads))
        for bad in ("nonfinite_samples", "loop_guard_paths"):
            if st[bad]:
                failures.append("%s/cycles pair: %d %s" % (name, st[bad], bad))
        return st, vkrun.read_error_log(logf)

    results = []
    for i in range(pairs):
        cycles_first = i % 2 == 0  # the first pair runs Cycles first: vkpath's budget needs its time
        if cycles_first:
            run_cycles()
            st, rows = run_vkpath()
        else:
            st, rows = run_vkpath()
            run_cycles()
        out = cycles.result(last["mse"], last["seconds"], [(r["seconds"], r["rmse"] ** 2) for r in rows],
                            ref["floor_mse"])
        vk_mean = numpy.array([rows[-1]["mean_r"], rows[-1]["mean_g"], rows[-1]["mean_b"]])
        out.update(blender=cy.version, threads=threads, size="%dx%d" % (W, H), cycles_spp=CYCLES_SPP,
                   reference_spp=ref["spp"], vkpath_spp=st["spp"], vkpath_samples_per_second=steady(st),
                   vkpath_mean_rel_diff=float(numpy.max(numpy.abs(vk_mean / ref_mean - 1.0))),
                   cycles_mean_rel_diff=float(numpy.max(numpy.abs(last["image"].reshape(-1, 3).mean(axis=0) /
                                                                   ref_mean - 1.0))))
        results.append(out)
        log("  %stime to Cycles' error (MSE %.3g at %d spp in %.2f s): vkpath %s, ratio %s (target %.1f); image means "
            "within %.2f%% (vkpath) and %.2f%% (Cycles) of the reference's" % (
                "pair %d of %d (%s first): " % (i + 1, pairs, "Cycles" if cycles_first else "vkpath") if pairs > 1
                else "", last["mse"], CYCLES_SPP, last["seconds"],
                "%.2f s" % out["vkpath_seconds"] if out["vkpath_seconds"] else "not reached",
                "%.2fx" % out["ratio"] if out["ratio"] is not None else "—", cycles.TARGET,
                100 * out["vkpath_mean_rel_diff"], 100 * out["cycles_mean_rel_diff"]))
    if pairs == 1:
        return results[0]
    out = cycles.combine(results)
    iv = out["ratio_interval"]
    log("  time to Cycles' error: %s, median of %d pairs%s: %s" % (
        "%.3fx" % out["ratio"] if out["ratio"] is not None else "—", pairs,
        ", %.0f %% interval %.3f-%.3fx" % (100 * out["ratio_interval_coverage"], iv[0], iv[1]) if iv else "",
        out["verdict"]))
    return out


def bench_scene(vk, name, scene, size, cfg, args, env, workdir, failures):
    W, H = size
    res = {"name": name, "size": "%dx%d" % (W, H)}
    try:
        info, load_s = vk.info(scene, timeout=cfg["load_timeout"])
    except subprocess.TimeoutExpired:
        raise vkrun.VkpathError("`vkpath info` did not load the scene within %d s" % cfg["load_timeout"])
    res["primitives"] = next((l.split()[1] for l in info.splitlines() if l.startswith("primitives")), "?")
    res["load_seconds"] = load_s
    log("  %s primitives, `vkpath info` in %.2f s" % (res["primitives"], load_s))
    wh = ["--width", W, "--height", H]
    # The reference is what the curves and settings measure errors against; `--parts scaling,embree`
    # (rates only) needs none.
    ref, res["reference"] = None, None
    if args.references_only or {"curves", "settings", "denoise"} & args.parts:
        ref = references.ensure_reference(vk, scene, name, W, H, vk.default_sampler, args.cache, args.max_floor,
                                          args.ref_budget or cfg["ref_budget"], cfg["pilot_spp"], log,
                                          dict(env, LP_NUM_THREADS=args.ref_threads),
                                          args.refresh_references)
        res["reference"] = {k: ref[k] for k in ("spp", "sampler", "floor_relmse", "floor_rmse", "floor_mse", "cached")}
    if args.references_only:
        return res, {}
    runs = os.path.join(workdir, name)
    # Warm the shared cache for every pipeline timed below, then cold and warm time to first pixel.
    for s in vk.samplers:
        vk.render(scene, runs, "warmup-" + s, wh + ["--sampler", s, "--spp", 1, "-o", "warmup.pfm"], env)
    vk.render(scene, runs, "warmup-full", wh + ["--variant", "full", "--spp", 1, "-o", "warmup.pfm"], env)
    if {"curves", "denoise"} & args.parts:  # the feature images' variant and the denoiser's pipelines
        vk.render(scene, runs, "warmup-denoise", wh + ["--spp", 2, "--denoise", "-o", "warmup.pfm"], env)
    cold_dir = os.path.join(runs, "cold-shader-cache")
    shutil.rmtree(cold_dir, ignore_errors=True)
    os.makedirs(cold_dir)
    cold_env = dict(env, MESA_SHADER_CACHE_DIR=cold_dir, VKPATH_CACHE_DIR=os.path.join(cold_dir, "vkpath"))
    cold = vk.render(scene, runs, "ttfp-cold", wh + ["--spp", 1, "-o", "ttfp.pfm"], cold_env)
    warm = vk.render(scene, runs, "ttfp-warm", wh + ["--spp", 1, "-o", "ttfp.pfm"], cold_env)
    res["ttfp"] = {"cold": cold["seconds_to_first_sample"], "cold_jit": cold["seconds_first_batch"],
                   "warm": warm["seconds_to_first_sample"], "warm_jit": warm["seconds_first_batch"]}
    startup = warm["seconds_to_first_sample"]
    # Curves: one run per sampler; --time counts from process start, so the start-up is added. With
    # the denoise part, one more run of the default sampler ("<sampler> --denoise") denoises at every
    # log row (not in its `seconds`): the denoised curve, beside the raw curve of the same run (its
    # kernel gathers the feature images, so its raw curve is the AOV variant's; the plain runs keep
    # the plain variant's rates).
    curve_time = (args.curve_seconds or cfg["curve"]) + startup
    curves, samplers, rows_total, ck_seconds, wall = {}, {}, 0, 0.0, 0.0
    curve_runs = [(s, s, []) for s in vk.samplers] if "curves" in args.parts else []
    if curve_runs and "denoise" in args.parts:
        curve_runs.append((vk.default_sampler + " --denoise", vk.default_sampler, ["--denoise"]))
    for label, s, denoise in curve_runs:
        tag = "curve-" + label.replace(" --", "-")
        logf = os.path.join(runs, tag + ".csv")
        st = vk.render(scene, runs, tag, wh + ["--sampler", s, "--spp", BIG_SPP, "--time", "%.3f" % curve_time,
                                               "--reference", ref["path"], "--error-log", logf,
                                               "-o", tag + ".pfm"] + denoise, env)
        rows = mark_limited(vkrun.read_error_log(logf), ref["floor_relmse"])
        curves[label] = rows
        rows_total += st["checkpoints"]
        # seconds_checkpoints includes the denoising at the rows: the error-log overhead leaves it out.
        ck_seconds += st["seconds_checkpoints"] - sum(r.get("denoise_seconds", 0.0) for r in rows)
        wall += st["seconds_total"]
        # Extrapolations start at this run's own first sample (a separate warm run's start-up can
        # come later than this run's last point on a loaded machine).
        samplers[label] = {"samples_per_second": steady(st), "rays_per_second": st["rays_per_second_steady"],
                           "spp": st["spp"], "seconds": st["seconds_total"], "relmse": rows[-1]["relmse"],
                           "rmse": rows[-1]["rmse"],
                           "crossings": crossings(rows, ref["floor_relmse"], st["seconds_to_first_sample"] or startup),
                           "variant": st["variant"]}
        if denoise and not vkrun.has_denoised(rows):
            failures.append("%s/%s: --denoise but the error log has no denoised columns" % (name, label))
        elif denoise:
            samplers[label].update(relmse_denoised=rows[-1]["relmse_denoised"],
                                   denoise_seconds=rows[-1]["denoise_seconds"],
                                   crossings_denoised=denoised_crossings(rows, ref["floor_relmse"]))
        for bad in ("nonfinite_samples", "loop_guard_paths"):
            if st[bad]:
                failures.append("%s/%s: %d %s" % (name, label, st[bad], bad))
        # An unbiased estimator's relMSE falls ~1/spp: over >= 64x the spp it must fall at least 4x.
        first, last = rows[0], rows[-1]
        if last["spp"] >= 64 * first["spp"] and not last["relmse"] < first["relmse"] / 4:
            failures.append("%s/%s: relMSE %.3g at %d spp, %.3g at %d spp: not converging" %
                            (name, label, first["relmse"], first["spp"], last["relmse"], last["spp"]))
    res["samplers"] = samplers
    res["overhead"] = {"rows": rows_total, "seconds": ck_seconds, "wall": wall}
    if "scaling" in args.parts:
        # Scaling: threads and variant, default sampler, same time each.
        t = "%.3f" % ((args.scaling_seconds or cfg["scaling"]) + startup)
        base = wh + ["--spp", BIG_SPP, "--time", t, "-o", "scaling.pfm"]
        one = vk.render(scene, runs, "threads-1", base, dict(env, LP_NUM_THREADS=1))
        two = vk.render(scene, runs, "threads-2", base, dict(env, LP_NUM_THREADS=2))
        full = vk.render(scene, runs, "variant-full", base + ["--variant", "full"], dict(env, LP_NUM_THREADS=2))
        res["scaling"] = {"threads_1": steady(one), "threads_2": steady(two),
                          "threads_ratio": steady(two) / steady(one), "full": steady(full),
                          "variant_ratio": steady(two) / steady(full), "auto_first_batch": two["seconds_first_batch"],
                          "full_first_batch": full["seconds_first_batch"]}
    if "embree" in args.parts and args.embree_ref is not None:
        res["embree"] = bench_embree(vk, args.embree_ref, scene, runs, wh, args.embree_seconds or cfg["scaling"], startup,
                                     env, name, failures, args.embree_pairs)
    if "settings" in args.parts:
        res["settings"] = bench_settings(vk, scene, runs, wh, ref, "%.3f" % ((args.settings_seconds or cfg["settings"])
                                                                           + startup), env, name, failures, args.settings)
    if "denoise" in args.parts:
        res["denoise"] = bench_denoise(vk, scene, runs, wh, ref, env, name, failures)
    if "cycles" in args.parts and name in cycles.TWINS:
        if args.cycles is None:
            res["cycles"] = {"refused": args.cycles_missing}
        else:
            res["cycles"] = bench_cycles(vk, args.cycles, name, scene, size, cfg, args, runs, env, startup, failures)
    if curves:
        report.write_curves_csv(os.path.join(args.out, name + ".csv"), name, curves, ref)
    return res, curves


def bench_settings(vk, scene, runs, wh, ref, seconds, env, name, failures, settings_wanted=None):
    """Equal-time runs of the default sampler, one per SETTINGS entry: final errors and rates, and each
    setting's relMSE over the default's (below 1: the setting helps at equal time)."""
    out = {}
    for label, extra in SETTINGS:
        if settings_wanted and label not in settings_wanted and label != "default":
            continue
        tag = "setting-" + "".join(ch if ch.isalnum() else "-" for ch in label)
        st = vk.render(scene, runs, tag, wh + ["--spp", BIG_SPP, "--time", seconds, "--reference", ref["path"],
                                              "-o", tag + ".pfm"] + extra, env)
        out[label] = {"args": " ".join(str(a) for a in extra), "spp": st["spp"], "mean_spp": st.get("mean_spp"),
                      "samples_per_second": steady(st), "rays_per_second": st["rays_per_second_steady"],
                      "relmse": st["error"]["relmse"], "rmse": st["error"]["rmse"],
                      "ref_limited": ref["floor_relmse"] > LIMITED_FRACTION * st["error"]["relmse"]}
        for bad in ("nonfinite_samples", "loop_guard_paths"):
            if st[bad]:
                failures.append("%s/%s: %d %s" % (name, label, st[bad], bad))
    base = out["default"]["relmse"]
    for v in out.values():
        v["relmse_ratio"] = v["relmse"] / base if base > 0 else None
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small sizes and short runs (a few minutes)")
    ap.add_argument("--vkpath", default=str(ROOT / "build/release/vkpath"), help="the vkpath binary")
    ap.add_argument("--embree", default=str(ROOT / "build/release/tests/bench/embree_reference"),
                    help="the Embree reference (tests/bench/embree_reference; default %(default)s, skipped if absent)")
    ap.add_argument("--no-embree", action="store_true", help="no Embree reference, no ratio to Embree")
    ap.add_argument("--embree-seconds", type=float,
                    help="seconds of rendering for the Embree reference and its vkpath pair (default: the scaling runs')")
    ap.add_argument("--cycles-pairs", type=int, default=1,
                    help="time to Cycles' error: N pairs of a Cycles and a vkpath render, alternating which goes "
                         "first; the median ratio, its interval from 6 pairs on, and the target's verdict")
    ap.add_argument("--embree-pairs", type=int, default=1,
                    help="Embree/vkpath pairs per scene, alternating which runs first; from 6 on the summary gives "
                         "the median ratio with its distribution-free 95 %% interval (default %(default)s)")
    ap.add_argument("--out", help="results folder (default: build/bench-results/<mode>-<date> in the repository)")
    ap.add_argument("--cache", default=str(ROOT / "build/bench-cache"),
                    help="references, generated scenes and the warm Mesa shader cache")
    ap.add_argument("--scenes", help="comma-separated subset of: " + ", ".join(s[0] for s in SCENES))
    ap.add_argument("--refresh-references", action="store_true", help="render the references again")
    ap.add_argument("--ref-threads", type=int, help="LP_NUM_THREADS for the reference renders (default: unset)")
    ap.add_argument("--references-only", action="store_true",
                    help="only make (or check) the cached references, then stop: no timing, no report")
    ap.add_argument("--ref-budget", type=float, help="seconds allowed for one scene's reference")
    ap.add_argument("--max-floor", type=float, default=0.1 * max(THRESHOLDS),
                    help="refuse a reference whose relMSE floor is above this (default %(default)g)")
    ap.add_argument("--curve-seconds", type=float, help="seconds of rendering per sampler curve")
    ap.add_argument("--mesh", help="the dense-mesh grid NUxNV (2 * NU * (NV - 1) triangles; default %s full, %s quick)"
                    % tuple("%dx%d" % MODES[m]["mesh"] for m in ("full", "quick")))
    ap.add_argument("--scaling-seconds", type=float, help="seconds of rendering per thread/variant run")
    ap.add_argument("--settings-seconds", type=float, help="seconds of rendering per equal-time setting run")
    ap.add_argument("--settings", help="comma-separated subset of the equal-time settings (default: all): " +
                    ", ".join(label for label, _ in SETTINGS[1:]))
    ap.add_argument("--parts", default=",".join(PARTS),
                    help="comma-separated subset of %s (default: all)" % ", ".join(PARTS))
    args = ap.parse_args()
    mode = "quick" if args.quick else "full"
    args.parts = set(args.parts.split(","))
    if args.settings:
        args.settings = set(x.strip() for x in args.settings.split(","))
        unknown_settings = args.settings - {label for label, _ in SETTINGS}
        if unknown_settings:
            ap.error("unknown setting(s): " + ", ".join(sorted(unknown_settings)))
    if args.parts - set(PARTS):
        ap.error("unknown part(s): " + ", ".join(sorted(args.parts - set(PARTS))))
    if args.cycles_pairs < 1:
        ap.error("--cycles-pairs wants at least 1, got %d" % args.cycles_pairs)
    if args.embree_pairs < 1:
        ap.error("--embree-pairs wants at least 1, got %d" % args.embree_pairs)
    cfg = dict(MODES[mode])
    if args.mesh:
        try:
            cfg["mesh"] = tuple(int(v) for v in args.mesh.lower().split("x"))
            assert len(cfg["mesh"]) == 2 and min(cfg["mesh"]) >= 3
        except (ValueError, AssertionError):
            ap.error("--mesh wants NUxNV with NU, NV >= 3, got %r" % args.mesh)
    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    args.out = os.path.abspath(args.out or ROOT / "build" / "bench-results" / ("%s-%s" % (mode, stamp)))
    args.cache = os.path.abspath(args.cache)
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.cache, exist_ok=True)
    wanted = set(args.scenes.split(",")) if args.scenes else None
    unknown = (wanted or set()) - {s[0] for s in SCENES}
    if unknown:
        ap.error("unknown scene(s): " + ", ".join(sorted(unknown)))

    t0 = time.monotonic()
    try:
        vk = vkrun.Vkpath(args.vkpath, log)
    except vkrun.VkpathError as e:
        print("bench: %s" % e, file=sys.stderr)
        return 1
    args.embree_ref = None
    if "embree" in args.parts and not args.no_embree:
        try:
            args.embree_ref = embree.EmbreeReference(args.embree, log)
        except embree.EmbreeError as e:
            log("bench: %s: no ratio to Embree" % e)
    args.cycles, args.cycles_missing = None, None
    if "cycles" in args.parts:
        try:
            args.cycles = cycles.Cycles(log=log)
        except cycles.CyclesError as e:
            args.cycles_missing = str(e)
            log("bench: %s" % e)
    load_before = load_average()
    log("bench: %s mode, vkpath %s, samplers %s (reference: %s), results in %s" %
        (mode, vk.version, ", ".join(vk.samplers), vk.default_sampler, args.out))
    # Every run: the warm shader caches of the cache folder (Mesa's and vkpath's kernel cache),
    # lavapipe's default thread count.
    env = {"MESA_SHADER_CACHE_DIR": os.path.join(args.cache, "mesa-shader-cache"),
           "VKPATH_CACHE_DIR": os.path.join(args.cache, "vkpath-kernel-cache"), "LP_NUM_THREADS": None}
    workdir = os.path.join(args.out, "runs")
    failures, scenes, curves_by_scene, device = [], [], {}, {"name": "?", "driver_info": "?"}
    for name, path, full_size, quick_size in SCENES:
        if wanted and name not in wanted:
            continue
        size = quick_size if args.quick else full_size
        log("bench: %s %dx%d" % (name, size[0], size[1]))
        try:
            scene = scene_file(name, path, cfg, size, args.cache)
            res, curves = bench_scene(vk, name, scene, size, cfg, args, env, workdir, failures)
            scenes.append(res)
            curves_by_scene[name] = curves
            if not args.references_only:
                with open(os.path.join(workdir, name, "ttfp-warm.json")) as f:
                    device = json.load(f)["device"]
        except (vkrun.VkpathError, embree.EmbreeError, cycles.CyclesError, references.ReferenceRefused,
                subprocess.SubprocessError, OSError) as e:
            log("bench: %s: %s" % (name, e))
            failures.append("%s: %s" % (name, e))
            scenes.append({"name": name, "size": "%dx%d" % size, "skipped": str(e).replace("|", "/")})
    if args.references_only:
        for s in scenes:
            r = s.get("reference")
            log("bench: %s: %s" % (s["name"], "%d spp, relMSE floor %.3g" % (r["spp"], r["floor_relmse"]) if r
                                   else "skipped: " + s.get("skipped", "?")))
        return 1 if failures else 0
    rows = sum(s["overhead"]["rows"] for s in scenes if "overhead" in s)
    secs = sum(s["overhead"]["seconds"] for s in scenes if "overhead" in s)
    wall = sum(s["overhead"]["wall"] for s in scenes if "overhead" in s)
    run = {
        "mode": mode, "date": datetime.datetime.now().isoformat(timespec="seconds"), "vkpath_version": vk.version,
        "git": git_describe(), "thresholds": list(THRESHOLDS), "default_sampler": vk.default_sampler,
        "command": " ".join(sys.argv),
        "machine": {"device": device["name"], "driver": device["driver_info"], "cpus": os.cpu_count(),
                    "cpu": cpu_model(),
                    "load_before": load_before, "load_after": load_average()},
        "error_log_overhead": {"rows": rows, "seconds_per_row": secs / rows if rows else 0.0,
                               "fraction": secs / wall if wall else 0.0},
        "parts": sorted(args.parts), "denoised_note": report.BIAS_SENTENCE, "scenes": scenes, "failures": failures,
        "seconds": time.monotonic() - t0,
    }
    ratios = ["%s %.2fx%s" % (s["name"], s["embree"]["ratio"], " [%.2f, %.2f]" % tuple(s["embree"]["ratio_interval"])
                              if s["embree"].get("ratio_interval") else "")
              for s in scenes if "ratio" in s.get("embree", {})]
    if ratios:
        log("bench: ratio to Embree (vkpath rays/s / Embree rays/s): " + ", ".join(ratios))
    ratios = ["%s %s" % (s["name"], "%.2fx" % s["cycles"]["ratio"] if s["cycles"].get("ratio") is not None else
                         s["cycles"].get("refused", "not reached")) for s in scenes if s.get("cycles")]
    if ratios:
        log("bench: time to Cycles' error (vkpath / Cycles): " + ", ".join(ratios))
    report.write_summary_json(os.path.join(args.out, "summary.json"), run)
    report.write_summary_md(os.path.join(args.out, "summary.md"), run)
    report.plot(os.path.join(args.out, "relmse_vs_time.png"), run, curves_by_scene)
    log("bench: wrote %s/{summary.md, summary.json, relmse_vs_time.png, <scene>.csv} in %.0f s" %
        (args.out, run["seconds"]))
    if failures:
        log("bench: %d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
