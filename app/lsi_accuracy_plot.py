#!/usr/bin/python3
"""Work-precision and convergence diagrams of an accuracy study (`lsi accuracy`).

    lsi_accuracy_plot.py DIR/accuracy.json [--out-dir DIR]

Writes, for each output of the study (peak_force, impact_duration, ...):
  DIR/work_precision_<output>.png  |error| against wall time per run (log-log): one line per
                                   MPM series (its runs in order of refinement), the closed
                                   forms as single markers at their time per evaluation;
  DIR/convergence_<output>.png     |error| against the refined spacing h, per series, with the
                                   slopes of first and second order for comparison.
Errors are those of accuracy.json: relative (absolute for the energy residual), against the
reference series or the series a series compares to. Runs that did not finish, and errors that
are not finite or exactly zero (the reference's own finest run), are left out of the log axes.
Prints the path of every PNG written. Exit 1 on an unreadable report, 2 on bad usage.

Uses Debian's /usr/bin/python3 (python3-matplotlib).
"""

import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "peak_force": "peak force",
    "rise_time": "rise time T1",
    "impact_duration": "impact duration T2",
    "final_displacement": "final displacement",
    "overtopped_volume": "overtopped volume",
    "energy_residual": "energy residual (absolute)",
}


def number(v):
    if isinstance(v, (int, float)):
        return float(v)
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def usable(e):
    return math.isfinite(e) and e != 0.0


def plot_output(rep, output, out_dir):
    written = []
    fig, ax = plt.subplots(figsize=(10, 5))
    figc, axc = plt.subplots(figsize=(10, 5))
    markers = "os^vD<>ph*"
    hs = []
    for s in rep["series"]:
        if output not in s["outputs"]:
            continue
        pts = []
        for r in s["runs"]:
            e = abs(number(r["errors"].get(output, "nan")))
            if r["finished"] and usable(e):
                pts.append((r["h"], r["solver_seconds"], e))
        if not pts:
            continue
        pts.sort(key=lambda p: -p[0])  # coarse to fine
        label = s["name"] + (" (reference)" if s["reference"] else "")
        # 20 distinct colours (the default cycle repeats after 10 series), markers cycling on
        # their own: every series of the study keeps its own look.
        k = len(ax.lines)
        style = dict(marker=markers[k % len(markers)], linestyle="-", color=plt.cm.tab20(k % 20))
        ax.loglog([p[1] for p in pts], [p[2] for p in pts], label=label, **style)
        axc.loglog([p[0] for p in pts], [p[2] for p in pts], label=label, **style)
        hs += [p[0] for p in pts]
    for i, c in enumerate(rep["closed_forms"]):
        e = abs(number(c["errors"].get(output, "nan")))
        if usable(e):
            ax.loglog([c["seconds_per_evaluation"]], [e], "X", markersize=11,
                      color=("black", "dimgray", "darkgray")[i % 3],
                      label="%s (closed form)" % c["method"])
    if not ax.lines:
        plt.close(fig)
        plt.close(figc)
        return written
    if hs:
        h0, h1 = min(hs), max(hs)
        ymid = math.exp(sum(math.log(abs(y)) for line in axc.lines for y in line.get_ydata())
                        / sum(len(line.get_ydata()) for line in axc.lines))
        for order, style in ((1, ":"), (2, "--")):
            axc.loglog([h0, h1], [ymid * (h0 / h1) ** order, ymid], "k" + style, linewidth=0.8,
                       label="order %d" % order)
    unit = "absolute" if output == "energy_residual" else "relative"
    ax.set_xlabel("wall time per run (s)")
    ax.set_ylabel("|error| of %s (%s)" % (LABELS.get(output, output), unit))
    ax.set_title("Work-precision: %s" % LABELS.get(output, output))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axc.set_xlabel("spacing h (cells: cell/thickness; points: 1/sqrt(ppc); Courant number)")
    axc.set_ylabel("|error| of %s (%s)" % (LABELS.get(output, output), unit))
    axc.set_title("Convergence: %s" % LABELS.get(output, output))
    axc.grid(True, which="both", alpha=0.3)
    axc.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for f, name in ((fig, "work_precision_%s.png" % output), (figc, "convergence_%s.png" % output)):
        path = os.path.join(out_dir, name)
        f.tight_layout()
        f.savefig(path, dpi=110)
        plt.close(f)
        written.append(path)
    return written


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("report")
    ap.add_argument("--out-dir", default=None)
    a = ap.parse_args()
    out_dir = a.out_dir or os.path.dirname(os.path.abspath(a.report))
    try:
        with open(a.report) as f:
            rep = json.load(f)
        outputs = rep["study"].get("outputs") or list(LABELS)
    except (OSError, ValueError, KeyError) as e:
        print("lsi_accuracy_plot.py: cannot read %s: %s" % (a.report, e), file=sys.stderr)
        return 1
    os.makedirs(out_dir, exist_ok=True)
    for output in outputs:
        for path in plot_output(rep, output, out_dir):
            print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
