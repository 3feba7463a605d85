#!/usr/bin/python3
"""Plot the misfit maps of an `lsi calibrate --out FILE.h5` file.

    lsi_calibration_plot.py CALIBRATION.h5 [--out-dir DIR]

Writes DIR/<stem>_maps.png (DIR defaults to the file's directory): one heat map per case of the
analytical model's misfit over (lambda, tau) (log colour scale, /cases/<name>/misfit_map with its
axes /cases/<name>/lambda and /cases/<name>/tau), with
  * the best fit (white cross) and its profile ranges (dashed box),
  * the group's mean (white circle), when the file has /groups/<fixed|free>,
  * the paper's calibrated point (red star: 0.72/0.17 fixed, 0.41/0.25 free),
  * the contour where the misfit is 10 % (the file's profile_tolerance) above its minimum.
Prints the path of the PNG. Exits 1 if the file is missing or has no /cases, 2 on bad usage.

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


class PlotError(Exception):
    pass


def _as_str(value):
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if hasattr(value, "item"):
        return _as_str(value.item())
    return str(value)


def _attr(obj, name, default=float("nan")):
    v = obj.attrs.get(name)
    if v is None:
        return default
    try:
        return float(v)
    except (TypeError, ValueError):
        return _as_str(v)


def plot_file(path, out_dir):
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise PlotError(f"{path}: cannot open: {e}")
    with f:
        if "cases" not in f or len(f["cases"]) == 0:
            raise PlotError(f"{path}: no /cases group (not an `lsi calibrate --out` file?)")
        objective = _as_str(f.attrs.get("objective", "misfit"))
        tol = _attr(f, "profile_tolerance", 0.1)
        groups = {}
        for name in f.get("groups", {}):
            g = f["groups"][name]
            groups[name] = (_attr(g, "lambda_mean"), _attr(g, "tau_mean"))
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
            best = min(_attr(c, "misfit"), np.nanmin(m))
            if np.nanmax(m) > (1 + tol) * best > max(0.0, np.nanmin(m)):   # the level is on the map
                ax.contour(lam, tau, m.T, levels=[(1 + tol) * best], colors="white",
                           linewidths=0.8, linestyles="dotted")
            lb, tb = _attr(c, "lambda"), _attr(c, "tau")
            ax.plot([lb], [tb], "wx", ms=9, mew=2, label=f"best {lb:.3f}/{tb:.3f}")
            l0, l1 = _attr(c, "lambda_range_low"), _attr(c, "lambda_range_high")
            t0, t1 = _attr(c, "tau_range_low"), _attr(c, "tau_range_high")
            if all(math.isfinite(v) for v in (l0, l1, t0, t1)):
                ax.plot([l0, l1, l1, l0, l0], [t0, t0, t1, t1, t0], "w--", lw=0.8)
            group = _as_str(c.attrs.get("group", ""))
            if group in groups and all(math.isfinite(v) for v in groups[group]):
                gl, gt = groups[group]
                ax.plot([gl], [gt], "o", mfc="none", mec="white", ms=8, mew=1.5,
                        label=f"{group} mean {gl:.3f}/{gt:.3f}")
            pl, pt = _attr(c, "paper_lambda"), _attr(c, "paper_tau")
            ax.plot([pl], [pt], "r*", ms=12, label=f"paper {pl:.2f}/{pt:.2f}")
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
            ax.set_xlabel("lambda = s1,max / L1,0")
            ax.set_ylabel("tau = T1 / T2")
            ax.set_title(f"{_as_str(c.attrs.get('name', key))} ({group})")
            ax.legend(loc="upper right", fontsize=7, framealpha=0.6)
        fig.tight_layout()
        stem = os.path.splitext(os.path.basename(path))[0]
        out = os.path.join(out_dir, f"{stem}_maps.png")
        os.makedirs(out_dir, exist_ok=True)
        fig.savefig(out, dpi=110)
        plt.close(fig)
        return out


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot the misfit maps of `lsi calibrate --out`.")
    parser.add_argument("calibration", metavar="CALIBRATION.h5")
    parser.add_argument("--out-dir", metavar="DIR", help="default: the file's directory")
    args = parser.parse_args(argv)
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.calibration))
    try:
        print(plot_file(args.calibration, out_dir))
    except PlotError as e:
        print(f"lsi_calibration_plot.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
