"""Running the vkpath binary from the benchmark harness: one render, its --stats-json numbers and its
--error-log rows."""
import csv
import json
import os
import re
import subprocess
import time



def environment_with(env):
    """os.environ with `env`'s entries added (None values remove a variable), as a new dict."""
    full_env = dict(os.environ)
    for k, v in (env or {}).items():
        if v is None:
            full_env.pop(k, None)
        else:
            full_env[k] = str(v)
    return full_env

class VkpathError(RuntimeError):
    pass


def parse_samplers(help_text):
    """The sampler names of `vkpath --help`'s `--sampler S` line, e.g.
    "--sampler S   bsdf | light | mixture (the book's) | mis (default)" -> (["bsdf", "light",
    "mixture", "mis"], "mis"). The default is the one marked "(default" (else "mixture")."""
    for line in help_text.splitlines():
        m = re.match(r"\s*--sampler\s+\S+\s+(.*)$", line)
        if not m:
            continue
        names, default = [], None
        for part in m.group(1).split("|"):
            words = part.split()
            if not words or not re.fullmatch(r"[a-z][a-z0-9_-]*", words[0]):
                continue
            names.append(words[0])
            if "(default" in part:
                default = words[0]
        if names:
            return names, default or ("mixture" if "mixture" in names else names[0])
    raise VkpathError("cannot find the --sampler line in `vkpath --help`")


ERROR_LOG_COLUMNS = ("spp", "seconds", "rmse", "relmse", "mean_r", "mean_g", "mean_b")
# Written with --denoise: the denoised image's errors and the denoiser's seconds at that row (the
# denoised image is ready at seconds + denoise_seconds; `seconds` leaves the denoising out).
DENOISED_COLUMNS = ("rmse_denoised", "relmse_denoised", "denoise_seconds")


def read_error_log(path):
    """Rows of an --error-log CSV as dicts of floats (spp as int). The denoised columns are optional:
    present in every row or in none. Raises VkpathError when a column is missing, or only some of
    the denoised ones are there."""
    rows = []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        columns = set(reader.fieldnames or ())
        missing = [c for c in ERROR_LOG_COLUMNS if c not in columns]
        denoised = [c for c in DENOISED_COLUMNS if c in columns]
        if denoised and len(denoised) != len(DENOISED_COLUMNS):
            missing += [c for c in DENOISED_COLUMNS if c not in columns]
        if missing:
            raise VkpathError("%s: no column %s" % (path, ", ".join(missing)))
        for r in reader:
            row = {k: float(v) for k, v in r.items()}
            row["spp"] = int(row["spp"])
            rows.append(row)
    return rows


def has_denoised(rows):
    """Whether error-log rows carry the denoised columns (a log written with --denoise)."""
    return bool(rows) and all(c in rows[0] for c in DENOISED_COLUMNS)


class Vkpath:
    """One vkpath binary. Every render runs with --quiet and writes --stats-json; `log` (a callable
    taking a line) hears what is run."""

    def __init__(self, binary, log=print):
        self.binary = os.path.abspath(binary)
        if not os.access(self.binary, os.X_OK):
            raise VkpathError("no vkpath binary at %s (build it: cmake --build --preset release --target vkpath)"
                              % self.binary)
        self.log = log
        self.help = self._run_text(["--help"])
        self.version = self._run_text(["--version"]).split()[-1]
        self.samplers, self.default_sampler = parse_samplers(self.help)

    def _run_text(self, args):
        p = subprocess.run([self.binary] + args, capture_output=True, text=True)
        if p.returncode != 0:
            raise VkpathError("vkpath %s failed: %s" % (" ".join(args), p.stderr.strip()))
        return p.stdout

    def info(self, scene, timeout=None):
        """`vkpath info SCENE`: (stdout, wall seconds). Raises VkpathError on failure, TimeoutExpired
        after `timeout` seconds."""
        t0 = time.monotonic()
        p = subprocess.run([self.binary, "info", str(scene)], capture_output=True, text=True, timeout=timeout)
        if p.returncode != 0:
            raise VkpathError("vkpath info %s failed: %s" % (scene, p.stderr.strip()))
        return p.stdout, time.monotonic() - t0

    def render(self, scene, workdir, name, args, env=None, timeout=None):
        """Runs `vkpath render SCENE ARGS --quiet --stats-json WORKDIR/NAME.json` and returns the stats
        (a dict). `env` entries are added to the environment (None values remove a variable)."""
        os.makedirs(workdir, exist_ok=True)
        stats_path = os.path.join(workdir, name + ".json")
        cmd = [self.binary, "render", str(scene)] + [str(a) for a in args] + ["--quiet", "--stats-json", stats_path]
        full_env = environment_with(env)
        shown = " ".join("%s=%s" % kv for kv in (env or {}).items()
                         if kv[1] is not None and kv[0] not in ("MESA_SHADER_CACHE_DIR", "VKPATH_CACHE_DIR"))
        self.log("  %-14s %s%s" % (name, shown + " " if shown else "", " ".join(str(a) for a in args)))
        p = subprocess.run(cmd, capture_output=True, text=True, env=full_env, cwd=workdir, timeout=timeout)
        with open(os.path.join(workdir, name + ".stderr.txt"), "w") as f:
            f.write(p.stderr)
        if p.returncode != 0:
            last = p.stderr.strip().splitlines()[-1:] or ["(no message)"]
            raise VkpathError("vkpath render exited with %d: %s" % (p.returncode, last[0]))
        with open(stats_path) as f:
            return json.load(f)
