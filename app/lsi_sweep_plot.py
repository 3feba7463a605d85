#!/usr/bin/python3
"""Plot the distributions of an `lsi sweep` / `lsi merge` result file.

    lsi_sweep_plot.py SWEEP.h5 [SWEEP.h5 ...] --out-dir DIR [--max-displacement X]

(app/lsi_plot.py hands sweep files, root attribute kind = "lsi sweep", to this script.)

For every output column /samples/<method>/<output> of the file writes
DIR/<stem>-<method>-<output>.png (DIR/<stem> is the file's name without .h5): three panels over
the ok samples (status 0, the samples the statistics describe), in the output's units (the
dataset's `units` attribute; forces in kN/m):
  1. histogram, with the mean and the stored quantiles (/statistics/<method>/<output>/quantile)
     and their confidence intervals (shaded);
  2. empirical CDF, with the stored quantiles as points and their confidence intervals as
     horizontal error bars;
     (where a long upper tail would squash them, these two end at the 99.5 % quantile: the
     titles say so and how many samples lie beyond);
  3. exceedance curve P(X > x) on a log scale, with the stored exceedance probabilities at the
     study's thresholds (exceedance_threshold, exceedance_probability) and their Wilson intervals
     as error bars (a probability of 0 as its upper bound, a downward triangle).
With --max-displacement X, the final_displacement panels also mark X and give P(final
displacement > X) from the samples with its Wilson interval at the file's confidence. Infinite
values (a barrier that never stops) count in the CDF and the exceedance curve but have no bar in
the histogram (the title says how many). A column whose ok samples have no finite value is left
out with a warning. Prints the path of every PNG written. Exits with 1 if a file is missing,
unreadable, not a sweep file or has no column to plot, 2 on bad usage.

Uses Debian's /usr/bin/python3 (python3-matplotlib, python3-h5py, python3-numpy).
"""

import json
import math
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import h5py  # noqa: E402

sys.dont_write_bytecode = True   # nothing written into the source tree
from lsi_plot_common import PlotError, as_str, open_hdf5, plot_files_main  # noqa: E402

KIND = "lsi sweep"
# Points of the CDF and exceedance curves at most (the tails are kept point by point).
CURVE_POINTS = 4000
# The histogram's quantile lines (the bars are C0; red is the tolerable displacement's).
QUANTILE_COLOURS = ["C1", "C2", "C4", "C5", "C6", "C8", "C9"]
# The histogram and the CDF end at this quantile when the samples beyond it would take more than
# TAIL_SPAN times its width (the tail is the exceedance panel's).
TAIL_QUANTILE = 0.995
TAIL_SPAN = 3.0

LABELS = {
    "peak_force": "peak force",
    "rise_time": "rise time",
    "impact_duration": "impact duration",
    "final_displacement": "final displacement",
}


def _units(dataset):
    u = dataset.attrs.get("units", "")
    return as_str(u) if np.ndim(u) == 0 else ""


def shown_units(units, values):
    """(units, scale): N/m shown as kN/m, J/m as kJ/m, Pa as kPa when the values are large."""
    prefixed = {"N/m": "kN/m", "J/m": "kJ/m", "Pa": "kPa", "N s/m": "kN s/m"}
    finite = values[np.isfinite(values)]
    if units in prefixed and finite.size and np.max(np.abs(finite)) >= 1e4:
        return prefixed[units], 1e-3
    return units, 1.0


def wilson(k, n, confidence):
    """Wilson score interval of k successes in n trials."""
    if n <= 0:
        return math.nan, math.nan
    z = statistics.NormalDist().inv_cdf(0.5 + confidence / 2)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def curve_indices(n):
    """Indices of the sorted samples drawn: all of them up to CURVE_POINTS, else evenly spread
    ones and every one of the last (upper tail) on a geometric spacing."""
    if n <= CURVE_POINTS:
        return np.arange(n)
    spread = np.linspace(0, n - 1, CURVE_POINTS // 2).astype(np.int64)
    tail = n - np.unique(np.geomspace(1, n, CURVE_POINTS // 2).astype(np.int64))
    return np.unique(np.concatenate([spread, tail, [n - 1]]))


def read(g, name, default=None):
    return np.asarray(g[name][()], dtype=float) if name in g else default


def plot_column(f, stem, method, output, out_dir, tolerance, study_name, confidence):
    samples = f["samples"][method][output]
    status = np.asarray(f["samples"]["status"][()])
    values = np.asarray(samples[()], dtype=float)
    if status.shape != values.shape:
        raise PlotError(f"/samples/{method}/{output} does not match /samples/status")
    ok = values[status == 0]
    ok = ok[~np.isnan(ok)]
    finite = ok[np.isfinite(ok)]
    if finite.size == 0:
        return None
    n = ok.size
    infinite = n - finite.size
    units, scale = shown_units(_units(samples), finite)
    ok_s = np.sort(ok) * scale
    finite_s = finite * scale
    stats = f.get(f"statistics/{method}/{output}")
    if stats is not None and "error" in stats.attrs:
        stats = None
    label = f"{LABELS.get(output, output)} ({units})" if units else LABELS.get(output, output)

    fig, (ax_h, ax_c, ax_e) = plt.subplots(1, 3, figsize=(16, 5), dpi=110)
    # 1. Histogram, over the bulk of the samples when a long tail would squash it.
    bins = int(min(60, max(10, math.sqrt(finite_s.size))))
    lo_h, hi_h = float(finite_s.min()), float(finite_s.max())
    cut = float(np.quantile(finite_s, TAIL_QUANTILE))
    beyond = 0
    if hi_h - lo_h > TAIL_SPAN * (cut - lo_h) and cut > lo_h:
        hi_h = cut
        beyond = int(np.count_nonzero(finite_s > cut))
    counts, _, _ = ax_h.hist(finite_s, bins=bins, range=(lo_h, hi_h), color="C0", alpha=0.75)
    nonzero = counts[counts > 0]
    if nonzero.size and counts.max() > 20 * np.median(nonzero):
        ax_h.set_yscale("log")
    if infinite == 0:   # with infinite values the mean is infinite
        ax_h.axvline(np.mean(finite_s), color="k", linewidth=1.2,
                     label=f"mean {np.mean(finite_s):.4g}")
    levels = quantiles = q_lo = q_hi = None
    if stats is not None and "quantile" in stats and "quantile_level" in stats:
        levels = read(stats, "quantile_level")
        quantiles = read(stats, "quantile") * scale
        q_lo = read(stats, "quantile_ci_low", quantiles / scale) * scale
        q_hi = read(stats, "quantile_ci_high", quantiles / scale) * scale
        for k, (p, q, lo, hi) in enumerate(zip(levels, quantiles, q_lo, q_hi)):
            if not math.isfinite(q):
                continue
            colour = QUANTILE_COLOURS[k % len(QUANTILE_COLOURS)]
            ax_h.axvline(q, color=colour, linestyle="--", linewidth=1.1,
                         label=f"{100 * p:g} % quantile {q:.4g}")
            if math.isfinite(lo) and math.isfinite(hi) and hi > lo:
                ax_h.axvspan(lo, hi, color=colour, alpha=0.12)
    ax_h.set_xlabel(label)
    ax_h.set_ylabel("samples")
    ax_h.set_title("histogram (shaded: quantiles' intervals)" +
                   (f"\n{beyond} samples above {hi_h:.4g} not shown" if beyond else ""),
                   fontsize="medium")
    if hi_h > lo_h:
        ax_h.set_xlim(lo_h - 0.03 * (hi_h - lo_h), hi_h + 0.03 * (hi_h - lo_h))
    ax_h.grid(True, alpha=0.3)

    # 2. Empirical CDF: F(x) = (samples <= x) / n.
    idx = curve_indices(n)
    x = ok_s[idx]
    drawn = np.isfinite(x)
    ax_c.step(x[drawn], ((idx + 1) / n)[drawn], where="post", color="C0", label="samples")
    if quantiles is not None:
        usable = np.isfinite(quantiles)
        ax_c.errorbar(quantiles[usable], levels[usable],
                      xerr=[np.maximum(quantiles - q_lo, 0)[usable],
                            np.maximum(q_hi - quantiles, 0)[usable]],
                      fmt="o", color="k", capsize=4, markersize=5,
                      label=f"quantiles, {100 * confidence:g} % intervals")
    ax_c.set_xlabel(label)
    ax_c.set_ylabel(f"P({output} <= x)")
    ax_c.set_ylim(0, 1.02)
    ax_c.set_title("empirical CDF" + (f"\nup to the {100 * TAIL_QUANTILE:g} % quantile, {hi_h:.4g}"
                                      if beyond else ""), fontsize="medium")
    if beyond:   # the tail is the exceedance panel's
        ax_c.set_xlim(ax_h.get_xlim())
    ax_c.grid(True, alpha=0.3)

    # 3. Exceedance P(X > x) = (samples > x) / n, log scale down to half a sample.
    exceed = (n - 1 - idx) / n
    keep = drawn & (exceed > 0)
    if keep.any():   # the last level holds up to the largest finite sample
        last = x[drawn][-1]
        ax_e.step(np.append(x[keep], last), np.append(exceed[keep], exceed[keep][-1]),
                  where="post", color="C0", label="samples")
    floor = 0.5 / n
    if stats is not None and "exceedance_threshold" in stats:
        th = read(stats, "exceedance_threshold") * scale
        p = read(stats, "exceedance_probability")
        lo = read(stats, "exceedance_probability_ci_low", p)
        hi = read(stats, "exceedance_probability_ci_high", p)
        counts = read(stats, "exceedance_count", np.full(p.shape, np.nan))
        for t, pk, l, h, c in zip(th, p, lo, hi, counts):
            tag = f"P(> {t:.4g}{' ' + units if units else ''}) = {pk:.3g} [{l:.3g}, {h:.3g}]"
            if math.isfinite(c):
                tag += f" ({int(c)} of {n})"
            if pk > 0:
                ax_e.errorbar([t], [pk], yerr=[[pk - max(l, floor)], [h - pk]], fmt="s",
                              color="C4", capsize=5, markersize=6, label=tag)
            else:   # nothing above the threshold: only the interval's upper end says anything
                ax_e.plot([t, t], [floor, h], color="C4", linewidth=1.2)
                ax_e.plot([t], [h], marker="v", color="C4", markersize=8, linestyle="",
                          label=tag + ", upper end")
    if tolerance is not None and output == "final_displacement":
        tol = tolerance * scale
        k = int(np.count_nonzero(ok > tolerance))
        pk = k / n
        l, h = wilson(k, n, confidence)
        for ax in (ax_h, ax_c, ax_e):
            ax.axvline(tol, color="red", linestyle="--", linewidth=1.2,
                       label=f"tolerable displacement {tolerance:g} m" if ax is not ax_e else None)
        ax_e.plot([tol], [max(pk, floor)], marker="D", color="red", linestyle="",
                  label=f"P(> {tolerance:g} m) = {pk:.3g} [{l:.3g}, {h:.3g}] ({k} of {n})")
    ax_e.set_yscale("log")
    ax_e.set_ylim(floor, 1.5)
    ax_e.set_xlabel(label)
    ax_e.set_ylabel(f"P({output} > x)")
    ax_e.set_title(f"exceedance (study thresholds: {100 * confidence:g} % Wilson intervals)",
                   fontsize="medium")
    ax_e.grid(True, which="both", alpha=0.3)
    for ax in (ax_h, ax_c, ax_e):
        handles, _ = ax.get_legend_handles_labels()
        if handles:
            ax.legend(loc="best", fontsize="x-small")

    done = int(status.size)
    title = f"{study_name}: {method} {LABELS.get(output, output)}, {n} ok samples of {done}"
    not_ok = int(np.count_nonzero(status != 0))
    if not_ok:
        title += f" ({not_ok} failed or cut short)"
    if infinite:
        title += f"; {infinite} infinite (never stops), not in the histogram"
    if not bool(f.attrs.get("complete", True)):
        title += " (sweep incomplete)"
    fig.suptitle(title)
    fig.tight_layout()
    out = os.path.join(out_dir, f"{stem}-{method}-{output}.png")
    fig.savefig(out)
    plt.close(fig)
    return out


def plot_sweep(f, path, out_dir, tolerance=None):
    """Plots an open sweep file; returns the PNGs written."""
    if as_str(f.attrs.get("kind", "")) != KIND:
        raise PlotError(f"{path}: not an lsi sweep file (root attribute kind is not '{KIND}')")
    if "samples" not in f or "status" not in f["samples"]:
        raise PlotError(f"{path}: no /samples table")
    stem = os.path.splitext(os.path.basename(path))[0]
    try:
        study_name = str(json.loads(as_str(f.attrs.get("study", "{}"))).get("name", stem))
    except (ValueError, TypeError, AttributeError):
        study_name = stem
    confidence = 0.95
    if "statistics" in f and "confidence" in f["statistics"]:
        confidence = float(f["statistics"]["confidence"][()])
    columns = [(m, o) for m, g in f["samples"].items() if isinstance(g, h5py.Group)
               for o, d in g.items() if isinstance(d, h5py.Dataset)]
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for method, output in columns:
        out = plot_column(f, stem, method, output, out_dir, tolerance, study_name, confidence)
        if out is None:
            print(f"warning: {path}: /samples/{method}/{output} has no finite value among the ok "
                  "samples; not plotted", file=sys.stderr)
        else:
            written.append(out)
    if not written:
        raise PlotError(f"{path}: nothing to plot (no output column with a finite value among "
                        "the ok samples)")
    return written


def plot_file(path, out_dir, tolerance=None):
    with open_hdf5(path) as f:
        return plot_sweep(f, path, out_dir, tolerance)


def main(argv=None):
    return plot_files_main(
        argv, "lsi_sweep_plot.py", plot_file,
        description="Plot histogram, CDF and exceedance curve of every output of lsi sweep "
                    "files (one PNG per method and output).",
        files="sweeps", files_metavar="SWEEP.h5", files_help="lsi sweep result file(s)",
        max_displacement_help="the design's tolerable displacement (m): marked on the "
                              "final_displacement plots with P(final displacement > X)")


if __name__ == "__main__":
    sys.exit(main())
