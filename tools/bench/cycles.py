"""Time to Cycles' error from the benchmark harness (issue 18; docs/performance.md "Time to Cycles'
error"): Debian's Blender renders the Cycles twin of a suite scene (tools/blender/cornell_cycles.py,
timed by its own render call) at a fixed spp; vkpath renders the scene until its error against the
same Cycles reference is as low; the ratio is vkpath's time from process start over Cycles' render
time."""
import hashlib
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np

import metrics
import pfm

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "tools" / "blender" / "cornell_cycles.py"
# Suite scene -> its Cycles twin: the same geometry, light, camera and Lambertian albedos, as
# Blender's glTF exporter wrote them (scenes/blender-cornell-classic/README.md).
TWINS = {"cornell-classic": ROOT / "scenes" / "blender-cornell-classic" / "cornell-rtiow.gltf"}
TARGET = 0.4  # issue 18: vkpath's time at most 0.4x Cycles' to the same error
REFERENCE_SEEDS = (1, 2)  # the reference's two halves; the timed Cycles run uses another seed
RUN_SEED = 3


class CyclesError(RuntimeError):
    pass


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        h.update(f.read())
    return h.hexdigest()


class Cycles:
    """Debian's Blender running tools/blender/cornell_cycles.py. `log` hears what is run."""

    def __init__(self, blender="blender", log=print):
        self.blender = shutil.which(blender)
        if not self.blender:
            raise CyclesError("blender is not installed (tools/deps.sh --reference): no time to Cycles' error")
        out = subprocess.run([self.blender, "--version"], capture_output=True, text=True, timeout=60).stdout
        self.version = (out.splitlines() or ["?"])[0].strip()
        self.log = log

    def render(self, gltf, out_pfm, size, spp, seed, threads, timeout=3600):
        """Renders gltf's Cornell twin at size x size, spp samples per pixel; returns (image, Cycles'
        render seconds). Raises CyclesError when Blender fails or writes nothing."""
        os.makedirs(os.path.dirname(out_pfm), exist_ok=True)
        cmd = [self.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(SCRIPT), "--",
               str(gltf), out_pfm, str(size), str(spp), str(seed), str(threads)]
        self.log("  %-14s cycles %dx%d, %d spp, seed %d, %d threads" % (os.path.basename(out_pfm), size, size, spp,
                                                                         seed, threads))
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        stats = os.path.splitext(out_pfm)[0] + ".json"
        if p.returncode != 0 or not os.path.exists(out_pfm) or not os.path.exists(stats):
            tail = (p.stdout + p.stderr).strip().splitlines()[-3:]
            raise CyclesError("Blender failed (exit %d): %s" % (p.returncode, " / ".join(tail)))
        with open(stats) as f:
            seconds = json.load(f)["seconds_render"]
        return pfm.read_pfm(out_pfm), seconds


def reference(cy, name, gltf, size, spp, threads, cache, log):
    """The Cycles reference of `name` at size x size: the average of two renders of spp / 2 with
    REFERENCE_SEEDS, cached under `cache` by scene, script, Blender version, size and spp. Returns
    {"path", "image", "spp", "floor_mse", "cached"}: floor_mse is the reference's own expected MSE
    (metrics.noise_floor), which adds alike to every error measured against it."""
    key = hashlib.sha256(("%s %s %s %d %d" % (sha256(gltf), sha256(SCRIPT), cy.version, size, spp)).encode()).hexdigest()
    folder = os.path.join(cache, "cycles-%s-%s" % (name, key[:16]))
    meta_path = os.path.join(folder, "meta.json")
    if os.path.exists(meta_path):
        with open(meta_path) as f:
            meta = json.load(f)
        meta.update(image=pfm.read_pfm(meta["path"]), cached=True)
        log("  Cycles reference: cached, %d spp, MSE floor %.3g" % (meta["spp"], meta["floor_mse"]))
        return meta
    halves = [cy.render(gltf, os.path.join(folder, "half-%d.pfm" % seed), size, spp // 2, seed, threads)[0]
              for seed in REFERENCE_SEEDS]
    image = 0.5 * (halves[0] + halves[1])
    floor_mse, _ = metrics.noise_floor(halves[0], halves[1])
    path = os.path.join(folder, "ref.pfm")
    pfm.write_pfm(path, image)
    meta = {"path": path, "spp": 2 * (spp // 2), "floor_mse": floor_mse, "blender": cy.version, "size": size}
    with open(meta_path + ".tmp", "w") as f:
        json.dump(meta, f, indent=1)
    os.replace(meta_path + ".tmp", meta_path)
    log("  Cycles reference: made, %d spp, MSE floor %.3g" % (meta["spp"], floor_mse))
    meta.update(image=image, cached=False)
    return meta


def result(cycles_mse, cycles_seconds, vkpath_points, floor_mse):
    """The comparison from Cycles' MSE and render time and vkpath's error-log points [(seconds from
    process start, MSE), ...] against the same reference: vkpath's time to Cycles' MSE (measured,
    interpolated in log-log between its rows; None when its last row is still above it) and the ratio
    of the times against TARGET. Both errors include the reference's floor_mse alike."""
    t = metrics.interpolate_crossing(vkpath_points, cycles_mse)
    ratio = t / cycles_seconds if t is not None and cycles_seconds > 0 else None
    return {"cycles_mse": cycles_mse, "cycles_rmse": float(np.sqrt(cycles_mse)), "cycles_seconds": cycles_seconds,
            "vkpath_seconds": t, "ratio": ratio, "target": TARGET, "target_met": ratio is not None and ratio <= TARGET,
            "floor_mse": floor_mse, "vkpath_final_mse": vkpath_points[-1][1] if vkpath_points else None}


def combine(pairs):
    """Several runs of the comparison (`result`'s dicts, one per pair of a Cycles and a vkpath render
    in alternating order) as one: the median of the pairs' ratios and its distribution-free interval
    (metrics.median_interval, from 6 pairs on), the medians of both renderers' times, and the
    verdict on TARGET: "met" when the interval lies at or below it, "not met" when above, else
    "undecided"; without an interval "no interval". A pair whose vkpath never reached Cycles' error
    has no ratio: the verdict is then "not met" and the median is left out (None). The other fields
    are the first pair's."""
    if not pairs:
        raise ValueError("combine: no pairs")
    out = dict(pairs[0])
    ratios = [p["ratio"] for p in pairs]
    out.update(pairs=len(pairs), ratios=ratios,
               cycles_seconds=float(np.median([p["cycles_seconds"] for p in pairs])))
    if any(r is None for r in ratios):
        out.update(ratio=None, vkpath_seconds=None, ratio_interval=None, ratio_interval_coverage=None,
                   target_met=False, verdict="not met (Cycles' error not reached in %d of %d pairs)" % (
                       sum(r is None for r in ratios), len(ratios)))
        return out
    median, lo, hi, coverage = metrics.median_interval(ratios)
    interval = [lo, hi] if lo is not None else None
    verdict = metrics.interval_verdict(interval, len(pairs), TARGET, at_least=False)
    out.update(ratio=median, vkpath_seconds=float(np.median([p["vkpath_seconds"] for p in pairs])),
               ratio_interval=interval, ratio_interval_coverage=coverage, verdict=verdict,
               target_met={"met": True, "not met": False}.get(verdict))
    return out
