"""The benchmark's outputs: one CSV per scene (the time-versus-error curves), summary.md, summary.json and
relmse_vs_time.png."""
import csv
import json
import math
import os

import metrics

CURVE_COLUMNS = ["scene", "sampler", "setting", "spp", "seconds", "rmse", "relmse", "relmse_minus_floor",
                 "rmse_minus_floor", "ref_limited", "mean_r", "mean_g", "mean_b", "rmse_denoised", "relmse_denoised",
                 "denoise_seconds", "ref_limited_denoised"]
BIAS_SENTENCE = ("The denoised image is biased (its error does not go to zero as spp grows); the raw image is "
                 "unbiased.")


def denoised_cells(r):
    """The denoised columns of a curve row: empty where the run did not denoise."""
    if "relmse_denoised" not in r:
        return ["", "", "", ""]
    return ["%.9g" % r["rmse_denoised"], "%.9g" % r["relmse_denoised"], "%.6f" % r["denoise_seconds"],
            int(r["ref_limited_denoised"])]


def write_curves_csv(path, scene, curves, ref):
    """curves: {sampler: [row dicts of the error log, with "ref_limited" (and "ref_limited_denoised"
    where the log has the denoised columns)]}."""
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CURVE_COLUMNS)
        for sampler, rows in curves.items():
            for r in rows:
                w.writerow([scene, sampler, "auto", r["spp"], "%.6f" % r["seconds"], "%.9g" % r["rmse"],
                            "%.9g" % r["relmse"], "%.9g" % (r["relmse"] - ref["floor_relmse"]),
                            "%.9g" % math.sqrt(max(r["rmse"] ** 2 - ref["floor_mse"], 0.0)),
                            int(r["ref_limited"]), "%.9g" % r["mean_r"], "%.9g" % r["mean_g"], "%.9g" % r["mean_b"]]
                           + denoised_cells(r))
    os.replace(tmp, path)


def fmt_s(x):
    return "—" if x is None else ("%.3g s" % x if x < 100 else "%.0f s" % x)


def fmt_rate(x):
    if x is None:
        return "—"
    for unit, div in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if x >= div:
            return "%.3g %s" % (x / div, unit)
    return "%.3g" % x


def fmt_cross(c):
    """A threshold crossing {"seconds", "how"} as text."""
    if c is None:
        return "—"
    if c.get("seconds") is None:
        return "n/a (%s)" % c["how"]
    if c["how"] == "measured":
        return fmt_s(c["seconds"])
    return "≈ " + fmt_s(c["seconds"]) + " (extrap.)"


def write_summary_md(path, run):
    """run: the dict that summary.json holds (see bench.py)."""
    L = []
    m = run["machine"]
    L.append("# vkpath benchmark (%s)" % run["mode"])
    L.append("")
    L.append("%s, vkpath %s (git %s), device %s, driver %s, %d CPUs (%s); load average %s before, %s after; "
             "%.0f s in all." % (run["date"], run["vkpath_version"], run["git"], m["device"], m["driver"], m["cpus"],
                                 m.get("cpu", "?"), m["load_before"], m["load_after"], run["seconds"]))
    L.append("")
    L.append("Thresholds are relMSE against the reference; times are wall seconds since process start "
             "(set-up, scene load, BVH, shader JIT with a warm Mesa cache, error rows: everything). "
             "A curve point is *reference-limited* when the reference's own noise floor is more than 20 % "
             "of it; such points are not used, and a threshold not reached by a reliable point is "
             "extrapolated with error ~ 1/t (marked).")
    L.append("")
    L.append("## Scenes")
    L.append("")
    L.append("| scene | size | primitives | load s | reference (spp, floor relMSE / RMSE) | first pixel cold | "
             "first pixel warm | 1 → 2 threads | auto / full variant |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for s in run["scenes"]:
        if s.get("skipped"):
            L.append("| %s | %s | %s | — | skipped: %s | | | | |" % (s["name"], s.get("size", ""), s.get("primitives", ""),
                                                                   s["skipped"]))
            continue
        r, sc = s["reference"], s.get("scaling")
        ref_text = ("%d spp%s, %.2g / %.2g" % (r["spp"], " (cached)" if r["cached"] else "", r["floor_relmse"],
                                               r["floor_rmse"]) if r else "— (not needed by these parts)")
        if sc is None:
            L.append("| %s | %s | %s | %.2f | %s | %s (JIT %s) | %s (JIT %s) | — | — |" % (
                s["name"], s["size"], s["primitives"], s["load_seconds"], ref_text, fmt_s(s["ttfp"]["cold"]),
                fmt_s(s["ttfp"]["cold_jit"]), fmt_s(s["ttfp"]["warm"]), fmt_s(s["ttfp"]["warm_jit"])))
            continue
        L.append("| %s | %s | %s | %.2f | %s | %s (JIT %s) | %s (JIT %s) | %.2fx | %.2fx (JIT %s vs %s) |" % (
            s["name"], s["size"], s["primitives"], s["load_seconds"], ref_text, fmt_s(s["ttfp"]["cold"]),
            fmt_s(s["ttfp"]["cold_jit"]), fmt_s(s["ttfp"]["warm"]), fmt_s(s["ttfp"]["warm_jit"]), sc["threads_ratio"],
            sc["variant_ratio"],
            fmt_s(sc["auto_first_batch"]), fmt_s(sc["full_first_batch"])))
    L.append("")
    L.append("## Samplers")
    L.append("")
    thr = run["thresholds"]
    L.append("| scene | sampler | samples/s | rays/s | spp in %s | relMSE | RMSE | %s |" % (
        "the run", " | ".join("t(relMSE ≤ %g)" % t for t in thr)))
    L.append("|---|---|---|---|---|---|---|" + "---|" * len(thr))
    for s in run["scenes"]:
        if s.get("skipped"):
            continue
        for name, c in s["samplers"].items():
            L.append("| %s | %s | %s | %s | %d in %.0f s | %.3g | %.3g | %s |" % (
                s["name"], name, fmt_rate(c["samples_per_second"]), fmt_rate(c["rays_per_second"]), c["spp"],
                c["seconds"], c["relmse"], c["rmse"], " | ".join(fmt_cross(c["crossings"][str(t)]) for t in thr)))
    L.append("")
    L.append("samples/s and rays/s: steady rates of the curve runs (first batch, with the JIT, left out), "
             "2 threads. Scaling columns: steady samples/s with LP_NUM_THREADS=2 over LP_NUM_THREADS=1, and "
             "`--variant auto` over `--variant full` (both 2 threads, default sampler %s)." % run["default_sampler"])
    L.append("")
    if any(s.get("denoise") or denoised_sampler(s) for s in run["scenes"] if not s.get("skipped")):
        write_denoise_md(L, [s for s in run["scenes"] if not s.get("skipped")], thr, run["default_sampler"])
    embree_rows = [s for s in run["scenes"] if s.get("embree")]
    if embree_rows:
        write_embree_md(L, embree_rows, run["default_sampler"])
    cycles_rows = [s for s in run["scenes"] if s.get("cycles")]
    if cycles_rows:
        write_cycles_md(L, cycles_rows, run["default_sampler"])
    if any(s.get("settings") for s in run["scenes"]):
        L.append("## Settings at equal time")
        L.append("")
        L.append("Default sampler (%s), 2 threads, the same --time for every run; relMSE ratio = the setting's "
                 "final relMSE over the default's (below 1: the setting helps). *: reference-limited." %
                 run["default_sampler"])
        L.append("")
        L.append("| scene | setting | spp (mean) | samples/s | rays/s | relMSE | RMSE | relMSE ratio |")
        L.append("|---|---|---|---|---|---|---|---|")
        for s in run["scenes"]:
            for label, v in (s.get("settings") or {}).items():
                mean = v.get("mean_spp")
                L.append("| %s | %s | %d%s | %s | %s | %.3g%s | %.3g | %s |" % (
                    s["name"], label, v["spp"], " (%.0f)" % mean if mean is not None and abs(mean - v["spp"]) > 0.5 else "",
                    fmt_rate(v["samples_per_second"]), fmt_rate(v["rays_per_second"]), v["relmse"],
                    "*" if v["ref_limited"] else "", v["rmse"],
                    "%.2f" % v["relmse_ratio"] if v["relmse_ratio"] is not None else "—"))
        L.append("")
    o = run["error_log_overhead"]
    L.append("Error-log rows: %d rows cost %.1f ms each on average (image read-back + error + CSV row; %.2f %% of "
             "the curve runs' wall time)." % (o["rows"], 1e3 * o["seconds_per_row"], 100 * o["fraction"]))
    if run.get("failures"):
        L.append("")
        L.append("## Checks that failed")
        L.append("")
        L.extend("- " + f for f in run["failures"])
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(L) + "\n")
    os.replace(path + ".tmp", path)


def denoised_sampler(scene):
    """(name, numbers) of the scene's sampler whose curve run denoised, or None."""
    return next(((n, c) for n, c in (scene.get("samplers") or {}).items() if "crossings_denoised" in c), None)


def fmt_rel(x, limited):
    """A relMSE, "*" when reference-limited; "—" for None."""
    return "—" if x is None else "%.3g%s" % (x, "*" if limited else "")


def fmt_met(ok):
    return "met" if ok else "not met"


def floor_corrected_ratio(raw, denoised, floor):
    """denoised / raw relMSE with the reference's own relMSE floor taken out of both: against an
    independent reference R, E|X - R|^2 = E|X - truth|^2 + E|R - truth|^2, so each measured relMSE
    is its true value plus the floor (to first order: relMSE divides by the reference too). None
    when the denoised error does not rise clearly above the floor (< 1.25 floor): unmeasurable."""
    if floor is None or raw <= floor or denoised < 1.25 * floor:
        return None
    return (denoised - floor) / (raw - floor)


def write_denoise_md(L, scenes, thresholds, sampler):
    """The "Denoiser" section: per scene, the time to each relMSE threshold of the raw and the denoised
    image (the default sampler's curve run), and the denoise part's renders at 16 and 64 spp: raw and
    denoised relMSE, their ratio against the 0.1 target, the denoiser's seconds against the time of
    4 spp (target: at most 1). Targets are reported as met or not met."""
    L.append("## Denoiser")
    L.append("")
    L.append(BIAS_SENTENCE)
    L.append("")
    crossing_rows = [(s, denoised_sampler(s)) for s in scenes if denoised_sampler(s)]
    if crossing_rows:
        L.append("Time to relMSE, raw and denoised, from the same `--denoise` curve run of the default sampler (%s): "
                 "the denoised image is ready at the row's seconds plus the denoiser's. Denoised times are measured "
                 "crossings only (interpolated between logged points); the denoised error need not fall ~1/t, so "
                 "it is never extrapolated. `--denoise` compiles the feature images into the kernel (variant "
                 "`aov`), so this raw curve includes their cost." % sampler)
        L.append("")
        L.append("| scene | sampler | %s |" % " | ".join("t(relMSE ≤ %g) raw | denoised" % t for t in thresholds))
        L.append("|---|---|" + "---|---|" * len(thresholds))
        for s, (name, c) in crossing_rows:
            L.append("| %s | %s | %s |" % (s["name"], name, " | ".join(
                "%s | %s" % (fmt_cross(c["crossings"][str(t)]), fmt_cross(c["crossings_denoised"][str(t)]))
                for t in thresholds)))
        L.append("")
    spp_rows = [s for s in scenes if s.get("denoise")]
    if spp_rows:
        d0 = spp_rows[0]["denoise"]
        L.append("Renders of exactly N spp (%s, `--denoise`, no `--time`) against the reference. Target (issue 17): "
                 "denoised relMSE / raw relMSE ≤ %g, and the denoiser's own time ≤ the time of %d spp at the same "
                 "size (steady rate of a %d-spp render without `--denoise`: the first batch's JIT left out). "
                 "*: reference-limited (the reference's floor is over 20 %% of the error; the ratio then "
                 "overstates the denoised error). \"floor out\": the ratio with the reference's floor subtracted "
                 "from both errors (a reference's own error adds to every measured one); — where the denoised "
                 "error is under 1.25x the floor." % (sampler, d0["target"], d0["time_spp"], d0["time_spp"]))
        L.append("")
        L.append("| scene | size | spp | raw relMSE | denoised relMSE | denoised / raw | floor out | ≤ %g | denoise s "
                 "| %d-spp s | denoise / %d spp |" % (d0["target"], d0["time_spp"], d0["time_spp"]))
        L.append("|---|---|---|---|---|---|---|---|---|---|---|")
        for s in spp_rows:
            d = s["denoise"]
            floor = (s.get("reference") or {}).get("floor_relmse")
            for r in d["runs"]:
                fc = floor_corrected_ratio(r["relmse"], r["relmse_denoised"], floor)
                L.append("| %s | %s | %d | %s | %s | %s | %s | %s | %.3g | %.3g | %s (%s) |" % (
                    s["name"], s["size"], r["spp"], fmt_rel(r["relmse"], r["ref_limited"]),
                    fmt_rel(r["relmse_denoised"], r["ref_limited_denoised"]),
                    "—" if r["ratio"] is None else "%.3f" % r["ratio"], "—" if fc is None else "%.3f" % fc,
                    fmt_met(r["target_met"]),
                    r["denoise_seconds"], d["seconds_4spp"],
                    "—" if r["time_ratio"] is None else "%.2f" % r["time_ratio"], fmt_met(r["time_target_met"])))
        L.append("")


def table_row(cells):
    """A Markdown table row; an empty cell is written "| |"."""
    return "|" + "|".join(" %s " % c if c != "" else " " for c in cells) + "|"


def write_table(L, columns, scenes, key, refused_at, refused_word, row):
    """A table with a header of `columns` and one row per scene: row(scene, scene[key]), or, where
    scene[key] has "refused", the reason at column refused_at after refused_word."""
    L.append(table_row(columns))
    L.append("|" + "---|" * len(columns))
    for s in scenes:
        part = s[key]
        if part.get("refused"):
            cells = [s["name"], s["size"]] + [""] * (len(columns) - 2)
            cells[refused_at] = "%s: %s" % (refused_word, part["refused"])
            L.append(table_row(cells))
        else:
            L.append(row(s, part))
    L.append("")


EMBREE_TARGET = 0.75  # issue 18: vkpath's rays/s at least 0.75x the Embree reference's


def embree_verdict(e):
    """Issue 18's target for a scene's "embree" result: the 95 % interval of the median ratio against
    at least EMBREE_TARGET (metrics.interval_verdict; no verdict below 6 pairs)."""
    return metrics.interval_verdict(e.get("ratio_interval"), e.get("pairs", 1), EMBREE_TARGET, at_least=True)


def pairs_cell(result):
    """The "pairs (interval)" cell of a comparison run as pairs (Embree's, Cycles'): their number and
    the median ratio's interval where there is one."""
    iv = result.get("ratio_interval")
    return "%d (%.2f-%.2fx)" % (result.get("pairs", 1), iv[0], iv[1]) if iv else "%d" % result.get("pairs", 1)


def write_embree_md(L, scenes, sampler):
    """The "Ratio to Embree" section: per scene, vkpath's and the Embree reference's rays/s in the
    same run (same size, thread count and render time, one after the other; with several pairs their
    medians) and the ratio (the median of the pairs' ratios), its interval and the target's verdict."""
    L.append("## Ratio to Embree")
    L.append("")
    L.append("The Embree reference (tests/bench/embree_reference: path tracing with next-event estimation and MIS "
             "on Embree's CPU BVH, incoherent single rays) and vkpath (%s) render the same scene at the same size "
             "with the same thread count for the same time, one after the other; ratio to Embree = vkpath's steady "
             "rays/s over Embree's. Rays are counted alike (camera, bounce and shadow rays), so rays per sample "
             "should agree; |z|: the largest difference of the two images' region means, in standard errors (the "
             "worst pair). With several pairs (`--embree-pairs N`, alternating which runs first) the rates are "
             "medians, the ratio is the median of the pairs' ratios, and the interval is its distribution-free 95 %% "
             "interval (the sign test's; from 6 pairs on). Target (issue 18): at least %.2fx, met when the interval "
             "lies at or above it." % (sampler, EMBREE_TARGET))
    L.append("")
    columns = ["scene", "size", "threads", "vkpath rays/s", "Embree rays/s", "**ratio to Embree**", "pairs (interval)",
               "target", "rays/sample vkpath / Embree", "spp vkpath / Embree", "max abs(z)"]

    write_table(L, columns, scenes, "embree", 4, "refused", lambda s, e: (
        "| %s | %s | %d | %s | %s | **%.2fx** | %s | %s | %.3f / %.3f | %d / %d | %.1f |" % (
            s["name"], s["size"], e["threads"], fmt_rate(e["vkpath_rays_per_second"]), fmt_rate(e["embree_rays_per_second"]),
            e["ratio"], pairs_cell(e), embree_verdict(e), e["vkpath_rays_per_sample"], e["embree_rays_per_sample"],
            e["vkpath_spp"], e["embree_spp"], e["max_abs_z"])))


def write_cycles_md(L, scenes, sampler):
    """The "Time to Cycles' error" section: per scene with a Cycles twin, Cycles' MSE at its spp and
    its own render time, vkpath's time from process start to the same MSE, and their ratio."""
    L.append("## Time to Cycles' error")
    L.append("")
    L.append("Blender's Cycles renders the scene's twin (tools/blender/cornell_cycles.py: Blender's own glTF "
             "export of the scene, Lambertian, box pixel filter, no clamping, denoising or adaptive sampling) at a "
             "fixed spp, timed by its own render call; vkpath (%s, same thread count) renders the scene with "
             "--reference set to the same Cycles reference; vkpath's time = seconds from process start when its "
             "MSE reaches Cycles' (interpolated between error-log rows). Both MSEs include the reference's own "
             "floor alike. With several pairs (`--cycles-pairs N`, alternating which renders first) the times are "
             "medians, the ratio is the median of the pairs' ratios and the interval its distribution-free 95 %% "
             "interval (from 6 pairs on). Target (issue 18): ratio at most 0.4, met with pairs when the interval "
             "lies at or below it. Mean diff.: the largest relative difference of a "
             "channel's image mean from the reference's." % sampler)
    L.append("")
    columns = ["scene", "size", "threads", "Cycles spp", "Cycles MSE", "Cycles s", "vkpath s", "**ratio**",
               "pairs (interval)", "target", "reference spp (MSE floor)", "mean diff. vkpath / Cycles", "Blender"]

    write_table(L, columns, scenes, "cycles", 7, "not measured", lambda s, c: (
        "| %s | %s | %d | %d | %.3g | %.2f | %s | **%s** | %s | %s | %d (%.2g) | %.2f%% / %.2f%% | %s |" % (
            s["name"], c["size"], c["threads"], c["cycles_spp"], c["cycles_mse"], c["cycles_seconds"],
            "%.2f" % c["vkpath_seconds"] if c["vkpath_seconds"] is not None else "not reached",
            "%.2fx" % c["ratio"] if c["ratio"] is not None else "—", pairs_cell(c),
            c.get("verdict") or fmt_met(c["target_met"]), c["reference_spp"],
            c["floor_mse"], 100 * c["vkpath_mean_rel_diff"], 100 * c["cycles_mean_rel_diff"], c["blender"])))


def write_summary_json(path, run):
    with open(path + ".tmp", "w") as f:
        json.dump(run, f, indent=1)
    os.replace(path + ".tmp", path)


def plot_denoised(ax, pts, color, sampler):
    """The denoised curve of a run that denoised (points at seconds + denoise_seconds): dashed, in the
    sampler's colour; reference-limited points hollow."""
    pts = [p for p in pts if "relmse_denoised" in p]
    good = [(p["seconds"] + p["denoise_seconds"], p["relmse_denoised"]) for p in pts if not p["ref_limited_denoised"]]
    limited = [(p["seconds"] + p["denoise_seconds"], p["relmse_denoised"]) for p in pts if p["ref_limited_denoised"]]
    label = sampler + " denoised (biased)"
    if good and limited:
        limited.insert(0, good[-1])  # the hollow part continues the solid one
    if good:
        ax.loglog(*zip(*good), "s--", color=color, ms=3, label=label)
    if limited:
        ax.loglog(*zip(*limited), "s--", color=color, ms=3, mfc="none", alpha=0.6, label=None if good else label)


def plot(path, run, curves_by_scene):
    """Log-log relMSE against seconds, one panel per scene, one line per sampler, and the denoised
    curve (dashed) of the sampler whose run denoised."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = [s for s in run["scenes"] if not s.get("skipped") and curves_by_scene.get(s["name"])]
    if not scenes:
        return
    cols = 2 if len(scenes) > 1 else 1
    rows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.4 * cols, 4.6 * rows), squeeze=False)
    for ax, s in zip(axes.flat, scenes):
        for i, (sampler, pts) in enumerate(curves_by_scene[s["name"]].items()):
            color = "C%d" % i
            good = [(p["seconds"], p["relmse"]) for p in pts if not p["ref_limited"]]
            limited = [(p["seconds"], p["relmse"]) for p in pts if p["ref_limited"]]
            if good and limited:
                limited.insert(0, good[-1])  # the dotted part continues the solid one
            if good:
                ax.loglog(*zip(*good), "o-", color=color, ms=3, label=sampler)
            if limited:
                ax.loglog(*zip(*limited), "o:", color=color, ms=3, mfc="none", alpha=0.6,
                          label=None if good else sampler)
            plot_denoised(ax, pts, color, sampler)
        ax.axhline(s["reference"]["floor_relmse"], color="k", ls="--", lw=0.8,
                   label="reference floor (%d spp)" % s["reference"]["spp"])
        for t in run["thresholds"]:
            ax.axhline(t, color="0.6", ls=":", lw=0.8)
        ax.set_title("%s %s" % (s["name"], s["size"]))
        ax.set_xlabel("seconds since process start")
        ax.set_ylabel("relMSE")
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=8)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    fig.suptitle("vkpath %s, %s (%s): relMSE against time\nhollow = reference-limited; dashed = denoised "
                 "(biased; the raw image is not)" % (run["vkpath_version"], run["machine"]["device"], run["mode"]),
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)
