"""The Embree reference from the benchmark harness (docs/performance.md "The Embree reference"):
running tests/bench/embree_reference (a CPU path tracer on Debian's Embree 3 with next-event
estimation, as vkpath's `mis`) and comparing its image with vkpath's within noise."""
import json
import os
import subprocess

import numpy as np

from vkrun import environment_with


class EmbreeError(RuntimeError):
    pass


class EmbreeRefused(EmbreeError):
    """The reference does not support the scene (exit status 1): its one-line reason."""


class EmbreeReference:
    """One embree_reference binary. `log` (a callable taking a line) hears what is run."""

    def __init__(self, binary, log=print):
        self.binary = os.path.abspath(binary)
        if not os.access(self.binary, os.X_OK):
            raise EmbreeError("no embree_reference binary at %s (tools/deps.sh --bench, then cmake --build "
                              "--preset release --target embree_reference)" % self.binary)
        self.log = log

    def render(self, scene, workdir, name, args, env=None, timeout=None):
        """Runs `embree_reference SCENE ARGS --quiet --stats-json WORKDIR/NAME.json` and returns the stats (a
        dict). `env` entries are added to the environment (None values remove a variable). Raises
        EmbreeRefused (exit 1: a scene it does not support, or bad arguments) or EmbreeError."""
        os.makedirs(workdir, exist_ok=True)
        stats_path = os.path.join(workdir, name + ".json")
        cmd = [self.binary, str(scene)] + [str(a) for a in args] + ["--quiet", "--stats-json", stats_path]
        full_env = environment_with(env)
        self.log("  %-14s embree_reference %s" % (name, " ".join(str(a) for a in args)))
        p = subprocess.run(cmd, capture_output=True, text=True, env=full_env, cwd=workdir, timeout=timeout)
        last = (p.stderr.strip().splitlines()[-1:] or ["(no message)"])[0]
        if p.returncode == 1:
            raise EmbreeRefused(last.replace("embree_reference: ", "", 1))
        if p.returncode != 0:
            raise EmbreeError("embree_reference exited with %d: %s" % (p.returncode, last))
        with open(stats_path) as f:
            return json.load(f)


def regions(height, width):
    """The image regions whose means are compared: the whole image and its four halves (left,
    right, top, bottom: a mirrored or flipped image fails), as (name, numpy index)."""
    return [("image", np.s_[:, :]), ("left", np.s_[:, : width // 2]), ("right", np.s_[:, width // 2:]),
            ("top", np.s_[: height // 2, :]), ("bottom", np.s_[height // 2:, :])]


def compare_means(vk_image, vk_spp, em_image, em_variance, em_spp):
    """Per region (regions()) and channel: (region, channel, vkpath mean, Embree mean, z), z = the
    difference of the means over its standard error. Embree's error comes from its per-pixel
    variance of the mean (em_variance, embree_reference --variance); vkpath's is taken as Embree's
    scaled by sqrt(em_spp / vk_spp): the same estimator with independent random numbers, which
    overstates vkpath's error (its Sobol' points and solid-angle light samples have less variance), so
    |z| errs small."""
    vk = np.asarray(vk_image, dtype=np.float64)
    em = np.asarray(em_image, dtype=np.float64)
    var = np.asarray(em_variance, dtype=np.float64)
    if vk.shape != em.shape or em.shape != var.shape:
        raise ValueError("image sizes differ: vkpath %s, Embree %s, variance %s" % (vk.shape, em.shape, var.shape))
    out = []
    for name, sl in regions(*vk.shape[:2]):
        n = vk[sl].shape[0] * vk[sl].shape[1]
        se_em = np.sqrt(var[sl].sum(axis=(0, 1))) / n
        se = se_em * np.sqrt(1.0 + em_spp / float(vk_spp))
        mv, me = vk[sl].mean(axis=(0, 1)), em[sl].mean(axis=(0, 1))
        for c in range(3):
            z = (mv[c] - me[c]) / se[c] if se[c] > 0 else (0.0 if mv[c] == me[c] else float("inf"))
            out.append((name, "RGB"[c], float(mv[c]), float(me[c]), float(z)))
    return out
