#!/usr/bin/python3
"""Plot the misfit maps and the closed forms' errors of an `lsi calibrate --out FILE.h5` file.

    lsi_calibration_plot.py CALIBRATION.h5 [--out-dir DIR] [--tolerance R]

Writes (DIR defaults to the file's directory; <stem> is the file's name without .h5)
  DIR/<stem>_maps.png    one heat map per case of the analytical model's misfit over (lambda, tau)
                         (log colour scale, /cases/<name>/misfit_map with its axes
                         /cases/<name>/lambda and /cases/<name>/tau), with
                           * the best fit (white cross) and its profile ranges (dashed box),
                           * the group's mean (white circle), when the file has
                             /groups/<fixed|free>,
                           * the paper's calibrated point (red star: 0.72/0.17 fixed, 0.41/0.25
                             free),
                           * the contour where the misfit is the file's profile_tolerance (10 %)
                             above its minimum (dotted);
                         each named in the legend;
  DIR/<stem>_errors.png  when the file has /comparison: the relative errors against the MPM of the
                         peak force, the impact duration and the final displacement, one panel each,
                         a bar per case and closed form with its coefficients (default, the group's
                         calibrated ones, the case's own fit); zero marked, and with --tolerance R
                         the band of +-R (e.g. 0.2 for 20 %); errors beyond +-300 % are drawn to the
                         edge with their value written.
A case's fitted scalars are read from /cases/<name>/scalars/<name> (0-d datasets) where the file
has them, else from the case group's attributes. Prints the path of every PNG. Exits 1 if the file
is missing or has no /cases, 2 on bad usage.

Uses Debian's /usr/bin/python3 (python3-matplotlib, python3-h5py), like app/lsi_plot.py.
"""

import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
import numpy as np  # noqa: E402
import h5py  # noqa: E402

sys.dont_write_bytecode = True   # nothing written into the source tree
from lsi_plot_common import PlotError, as_str, check_positive  # noqa: E402


def _attr(obj, name, default=float("nan")):
    v = obj.attrs.get(name)
    if v is None:
        return default
    try:
        return float(v)
    except (TypeError, ValueError):
        return as_str(v)


def _value(obj, name, default=float("nan")):
    """A scalar of a case or group: the 0-d dataset scalars/<name> or <name>, else the attribute."""
    s = obj.get("scalars")
    for holder in ((s,) if isinstance(s, h5py.Group) else ()) + (obj,):
        d = holder.get(name)
        if isinstance(d, h5py.Dataset) and d.shape == ():
            v = d[()]
            try:
                return float(v)
            except (TypeError, ValueError):
                return as_str(v)
    return _attr(obj, name, default)


ERRORS = [("peak_force_rel_error", "peak force"),
          ("impact_duration_rel_error", "impact duration"),
          ("final_displacement_rel_error", "final displacement")]
ERROR_LIMIT = 3.0   # bars beyond +-300 % end at the edge, their value written


def plot_errors(f, out, tolerance):
    """The closed forms' relative errors against the MPM per case; None without /comparison."""
    if "comparison" not in f:
        return None
    c = f["comparison"]
    if not all(k in c for k in ("case", "method", "coefficients")):
        return None
    case = [as_str(v) for v in c["case"][()]]
    method = [as_str(v) for v in c["method"][()]]
    coef = [as_str(v) for v in c["coefficients"][()]]
    rows = [i for i in range(len(case)) if method[i] != "mpm"]
    panels = [(k, label) for k, label in ERRORS if k in c]
    if not rows or not panels:
        return None
    cases = list(dict.fromkeys(case[i] for i in rows))
    kinds = list(dict.fromkeys((method[i], coef[i]) for i in rows))
    colours = {k: plt.cm.tab10(n % 10) for n, k in enumerate(kinds)}
    height = 1.0 / (len(kinds) + 1)
    rows_height = len(cases) * (0.18 * len(kinds) + 0.3)
    fig, axes = plt.subplots(1, len(panels), squeeze=False, sharey=True,
                             figsize=(5 * len(panels), 1.6 + rows_height))
    for ax, (key, label) in zip(axes[0], panels):
        err = np.asarray(c[key][()], dtype=float)
        for i in rows:
            k = kinds.index((method[i], coef[i]))
            y = cases.index(case[i]) + (k - (len(kinds) - 1) / 2) * height
            e = err[i]
            if not math.isfinite(e):
                continue
            shown = max(-ERROR_LIMIT, min(ERROR_LIMIT, e))
            ax.barh(y, 100 * shown, height=height * 0.9, color=colours[(method[i], coef[i])])
            if shown != e:
                ax.text(100 * shown, y, f" {100 * e:+.0f} % ", va="center", fontsize=6,
                        ha="right" if e > 0 else "left", color="white")
        ax.axvline(0, color="k", linewidth=0.8)
        if tolerance is not None:
            for side in (-1, 1):
                ax.axvline(100 * side * tolerance, color="red", linestyle="--", linewidth=1,
                           label=f"+-{100 * tolerance:g} %" if side > 0 else None)
        ax.set_xlabel(f"{label}: (closed form - MPM) / MPM (%)")
        ax.grid(True, axis="x", alpha=0.3)
    axes[0, 0].set_yticks(range(len(cases)))
    axes[0, 0].set_yticklabels(cases)
    axes[0, 0].invert_yaxis()
    handles = [plt.Rectangle((0, 0), 1, 1, color=colours[k]) for k in kinds]
    labels = [f"{m} ({co})" for m, co in kinds]
    if tolerance is not None:
        handles.append(plt.Line2D([], [], color="red", linestyle="--"))
        labels.append(f"tolerance +-{100 * tolerance:g} %")
    fig.legend(handles, labels, loc="upper center", ncol=min(len(labels), 4), fontsize="small")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.5 / fig.get_size_inches()[1]))
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def plot_file(path, out_dir, tolerance=None):
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise PlotError(f"{path}: cannot open: {e}")
    with f:
        if "cases" not in f or len(f["cases"]) == 0:
            raise PlotError(f"{path}: no /cases group (not an `lsi calibrate --out` file?)")
        objective = as_str(f.attrs.get("objective", "misfit"))
        tol = _value(f, "profile_tolerance", 0.1)
        groups = {}
        for name in f.get("groups", {}):
            g = f["groups"][name]
            groups[name] = (_value(g, "lambda_mean"), _value(g, "tau_mean"))
        names = list(f["cases"])
        ncol = min(3, len(names))
        nrow = int(math.ceil(len(names) / ncol))
        fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.9 * nrow), squeeze=False)
        for ax in axes.flat[len(names):]:
            ax.set_visible(False)
        for ax, key in zip(axes.flat, names):
            c = f["cases"][key]
            lam = np.asarray(c["lambda"])
            tau = np.asarray(c["tau"])
            m = np.asarray(c["misfit_map"])  # [lambda, tau]
            positive = m[np.isfinite(m) & (m > 0)]
            floor = positive.min() if positive.size else 1e-12
            shown = np.where(np.isfinite(m), np.maximum(m, floor), np.nan)
            im = ax.pcolormesh(lam, tau, shown.T, shading="nearest", cmap="viridis",
                               norm=LogNorm(vmin=floor, vmax=np.nanmax(shown)))
            fig.colorbar(im, ax=ax, label=f"{objective} misfit")
            best = np.nanmin([_value(c, "misfit"), np.nanmin(m)])
            if np.nanmax(m) > (1 + tol) * best > max(0.0, np.nanmin(m)):   # the level is on the map
                ax.contour(lam, tau, m.T, levels=[(1 + tol) * best], colors="white",
                           linewidths=0.8, linestyles="dotted")
                ax.plot([], [], "w:", lw=0.8, label=f"misfit {100 * tol:g} % above the best")
            lb, tb = _value(c, "lambda"), _value(c, "tau")
            ax.plot([lb], [tb], "wx", ms=9, mew=2, label=f"best {lb:.3f}/{tb:.3f}")
            l0, l1 = _value(c, "lambda_range_low"), _value(c, "lambda_range_high")
            t0, t1 = _value(c, "tau_range_low"), _value(c, "tau_range_high")
            if all(math.isfinite(v) for v in (l0, l1, t0, t1)):
                ax.plot([l0, l1, l1, l0, l0], [t0, t0, t1, t1, t0], "w--", lw=0.8,
                        label="profile ranges")
            group = as_str(c.attrs.get("group", ""))
            if group in groups and all(math.isfinite(v) for v in groups[group]):
                gl, gt = groups[group]
                ax.plot([gl], [gt], "o", mfc="none", mec="white", ms=8, mew=1.5,
                        label=f"{group} mean {gl:.3f}/{gt:.3f}")
            pl, pt = _value(c, "paper_lambda"), _value(c, "paper_tau")
            ax.plot([pl], [pt], "r*", ms=12, label=f"paper {pl:.2f}/{pt:.2f}")
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
            ax.set_xlabel("lambda = s1,max / L1,0")
            ax.set_ylabel("tau = T1 / T2")
            ax.set_title(f"{as_str(c.attrs.get('name', key))} ({group})")
            # grey behind the legend: its markers are white, as on the map
            ax.legend(loc="upper right", fontsize=7, framealpha=0.7, facecolor="0.45",
                      labelcolor="white")
        fig.tight_layout()
        stem = os.path.splitext(os.path.basename(path))[0]
        out = os.path.join(out_dir, f"{stem}_maps.png")
        os.makedirs(out_dir, exist_ok=True)
        fig.savefig(out, dpi=110)
        plt.close(fig)
        written = [out]
        errors = plot_errors(f, os.path.join(out_dir, f"{stem}_errors.png"), tolerance)
        if errors:
            written.append(errors)
        return written


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot the misfit maps of `lsi calibrate --out`.")
    parser.add_argument("calibration", metavar="CALIBRATION.h5")
    parser.add_argument("--out-dir", metavar="DIR", help="default: the file's directory")
    parser.add_argument("--tolerance", type=float, metavar="R",
                        help="relative error drawn as a band of +-R on the errors plot "
                             "(0.2: 20 %%)")
    args = parser.parse_args(argv)
    check_positive(parser, "--tolerance", args.tolerance)
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.calibration))
    try:
        for out in plot_file(args.calibration, out_dir, args.tolerance):
            print(out)
    except PlotError as e:
        print(f"lsi_calibration_plot.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
