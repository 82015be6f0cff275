"""Reference images for the benchmark: vkpath's own high-spp renders, made once and cached.

A reference is the average R = (A + B) / 2 of two renders A and B with the same spp and different
seeds; their difference estimates R's own noise (metrics.noise_floor), which every error measured
against R contains. The harness refuses a reference whose relMSE floor is above `max_floor` (10 % of
the largest relMSE threshold by default): it renders a bigger one if the time budget allows, else it
stops with the spp it would need.

Cache: CACHE/<key>/{ref.pfm, half-a.pfm, half-b.pfm, meta.json}, key = sha256 of the scene file's
content, vkpath's version, the image size and the sampler. meta.json states spp and the floor.
"""
import datetime
import hashlib
import json
import math
import os
import shutil

import numpy as np

import metrics
import pfm

SEEDS = (1000003, 2000029)  # the halves; benchmark runs use the scenes' own seeds (0)


class ReferenceRefused(RuntimeError):
    pass


def file_sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def reference_key(scene_sha, version, width, height, sampler):
    text = json.dumps({"scene_sha256": scene_sha, "vkpath": version, "width": width, "height": height,
                       "sampler": sampler}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _render_halves(vk, scene, workdir, width, height, sampler, spp_half, env):
    """Renders the two halves; returns (A, B, seconds, steady samples/s)."""
    images, seconds, rates = [], 0.0, []
    for tag, seed in zip("ab", SEEDS):
        out = os.path.join(workdir, "half-%s.pfm" % tag)
        st = vk.render(scene, workdir, "half-%s" % tag,
                       ["--width", width, "--height", height, "--sampler", sampler, "--spp", spp_half, "--seed", seed,
                        "-o", out], env)
        if st["spp"] != spp_half or st["nonfinite_samples"] != 0:
            raise ReferenceRefused("half %s: %d spp of %d, %d non-finite samples" %
                                   (tag, st["spp"], spp_half, st["nonfinite_samples"]))
        images.append(pfm.read_pfm(out))
        seconds += st["seconds_total"]
        rates.append(st["samples_per_second_steady"] or st["samples_per_second"])
    return images[0], images[1], seconds, min(rates)


def ensure_reference(vk, scene, name, width, height, sampler, cache_dir, max_floor, budget_seconds, pilot_spp,
                     log, env, refresh=False):
    """The reference of `scene` at width x height: a dict (meta.json) with "path" added. Raises
    ReferenceRefused if no reference with a relMSE floor <= max_floor fits in budget_seconds."""
    key = reference_key(file_sha256(scene), vk.version, width, height, sampler)
    d = os.path.join(cache_dir, "%s-%s" % (name, key))
    meta_path = os.path.join(d, "meta.json")
    ref_path = os.path.join(d, "ref.pfm")
    if os.path.exists(meta_path) and os.path.exists(ref_path) and not refresh:
        with open(meta_path) as f:
            meta = json.load(f)
        if meta["floor_relmse"] <= max_floor:
            log("  reference: cached %s (%d spp, relMSE floor %.3g)" % (d, meta["spp"], meta["floor_relmse"]))
            return dict(meta, path=ref_path, cached=True)
        log("  reference: cached floor %.3g > %.3g: making a bigger one" % (meta["floor_relmse"], max_floor))
    os.makedirs(d, exist_ok=True)
    pixels = width * height
    kept = _kept_halves(d, width, height, sampler)
    if kept is not None:
        # Halves of an earlier attempt that was refused (or made under another --max-floor): used
        # again, as they are if their floor now passes, else as the pilot of a bigger attempt.
        a, b, half_spp, secs, rate = kept
        spp_total, (floor_mse, floor_rel) = 2 * half_spp, metrics.noise_floor(a, b)
        log("  reference: kept halves of %d spp each, floor %.3g" % (half_spp, floor_rel))
        if floor_rel <= max_floor:
            return _write_reference(d, scene, vk, width, height, sampler, a, b, spp_total, floor_mse, floor_rel,
                                    max_floor, secs, log)
    else:
        # A pilot (two small halves) measures the noise per spp and the rate.
        a, b, secs, rate = _render_halves(vk, scene, os.path.join(d, "pilot"), width, height, sampler, pilot_spp, env)
        spp_total, floor_rel = 2 * pilot_spp, metrics.noise_floor(a, b)[1]
    spent = secs
    for attempt in range(3):  # the pilot underestimates scenes with rare bright paths (caustics)
        need = metrics.needed_total_spp(floor_rel, spp_total, 0.5 * max_floor)  # a margin of 2
        half = max(pilot_spp, int(math.ceil(need / 2 / 64.0)) * 64)
        estimate = 2 * half * pixels / max(rate, 1.0)
        log("  reference: floor %.3g at %d spp -> %d spp per half, ~%.0f s (budget %.0f s)" %
            (floor_rel, spp_total, half, estimate, budget_seconds))
        if spent + estimate > budget_seconds:
            raise ReferenceRefused("%s: a reference with relMSE floor <= %.3g needs ~%d spp (~%.0f s at %.3g "
                                   "samples/s), over the budget of %.0f s (--ref-budget)" %
                                   (name, max_floor, 2 * half, estimate, rate, budget_seconds))
        a, b, secs, rate = _render_halves(vk, scene, d, width, height, sampler, half, env)
        spent += secs
        spp_total = 2 * half
        floor_mse, floor_rel = metrics.noise_floor(a, b)
        if floor_rel <= max_floor:
            break
        log("  reference: floor %.3g > %.3g after %d spp" % (floor_rel, max_floor, spp_total))
    else:
        raise ReferenceRefused("%s: reference floor %.3g > %.3g after %d spp: refused" %
                               (name, floor_rel, max_floor, spp_total))
    return _write_reference(d, scene, vk, width, height, sampler, a, b, spp_total, floor_mse, floor_rel, max_floor,
                            spent, log)


def _kept_halves(d, width, height, sampler):
    """(A, B, spp per half, seconds, samples/s) of half-a/half-b left in d by an earlier attempt, if
    both exist, match the size, sampler and seeds, and have the same spp; else None."""
    try:
        stats = []
        for tag, seed in zip("ab", SEEDS):
            with open(os.path.join(d, "half-%s.json" % tag)) as f:
                st = json.load(f)
            if (st["width"], st["height"], st["sampler"], st["seed"]) != (width, height, sampler, seed):
                return None
            stats.append(st)
        if stats[0]["spp"] != stats[1]["spp"] or any(st["nonfinite_samples"] for st in stats):
            return None
        a, b = (pfm.read_pfm(os.path.join(d, "half-%s.pfm" % tag)) for tag in "ab")
    except (OSError, ValueError, KeyError):
        return None
    rate = min(st["samples_per_second_steady"] or st["samples_per_second"] for st in stats)
    return a, b, stats[0]["spp"], sum(st["seconds_total"] for st in stats), rate


def _write_reference(d, scene, vk, width, height, sampler, a, b, spp_total, floor_mse, floor_rel, max_floor, spent, log):
    ref_path = os.path.join(d, "ref.pfm")
    meta_path = os.path.join(d, "meta.json")
    pfm.write_pfm(ref_path, 0.5 * (a.astype(np.float64) + b.astype(np.float64)))
    shutil.rmtree(os.path.join(d, "pilot"), ignore_errors=True)
    meta = {
        "scene": os.path.basename(str(scene)), "scene_sha256": file_sha256(scene), "vkpath_version": vk.version,
        "width": width, "height": height, "sampler": sampler, "spp": spp_total, "spp_per_half": spp_total // 2,
        "seeds": list(SEEDS), "floor_mse": floor_mse, "floor_rmse": math.sqrt(floor_mse), "floor_relmse": floor_rel,
        "max_floor_relmse": max_floor, "seconds": spent,
        "created": datetime.datetime.now().isoformat(timespec="seconds"),
    }
    with open(meta_path + ".tmp", "w") as f:
        json.dump(meta, f, indent=1)
    os.replace(meta_path + ".tmp", meta_path)
    log("  reference: made %s (%d spp, relMSE floor %.3g, %.0f s)" % (d, spp_total, floor_rel, spent))
    return dict(meta, path=ref_path, cached=False)
