#!/usr/bin/python3
"""Plot lsi result files: `lsi run` / `lsi compare` results and `lsi sweep` / `lsi merge` files.

    lsi_plot.py RESULT.h5 [RESULT.h5 ...] --out-dir DIR [--max-displacement X]

What is drawn depends on what the file holds (DIR/<stem> is the file's name without .h5):

Impact results (groups with force, landslide kinetic energy or barrier displacement histories):
  DIR/<stem>.png         stacked panels, every method group of the file on the same axes
                         (legend = method name), the scene's name as the title:
                           1. impact force normal to the barrier face F(t)   (kN/m)
                           2. landslide kinetic energy                       (kJ/m)
                           3. barrier displacement                           (m)
                         Force and energy share a time axis that ends soon after the last impact
                         (a closed form's barrier may slide on long after it); the displacement has
                         its own. A displacement that would squash the others (more than ten times
                         the next largest and the tolerable one) runs off the top of the panel,
                         with a marker where it leaves and a note below the panels; where the
                         displacements differ by more than ten times, a fourth panel shows them all
                         on a log scale. A run cut short (/<method> attribute end_state: unstable,
                         barrier_left_domain, end_time_landslide_moving, end_time_barrier_sliding)
                         ends in a cross and a dotted line at its end time, with the reason in a
                         note; a closed form whose barrier never stops is noted.
                         --max-displacement X draws the design's tolerable displacement on the
                         displacement panels.
  DIR/<stem>-face.png    where the MPM reported the face's pressure in height bands
                         (methods.mpm.face_band_m): the normal stress on the upstream face against
                         the height above the base at the time of the peak force, with the
                         resultant's height marked.

MPM verification scenes (`mpm_case`: /mpm with energies, wall forces and the front, no impact):
  DIR/<stem>.png         stacked panels of what the file has: the energies (kinetic, elastic,
                         potential change, the dissipations), the energy residual, the walls'
                         reactions, the material's front x.
Either kind, where the MPM reported wall pressure bands (methods.mpm.wall_band_m):
  DIR/<stem>-walls.png   one panel per wall: the normal stress of its bands against the height
                         (left, right walls) or x (bottom, top) at the time of that wall's largest
                         band pressure.

Sweep files (root attribute kind = "lsi sweep"): app/lsi_sweep_plot.py draws them, one
DIR/<stem>-<method>-<output>.png per output column (see there).

Panels a file has no data for are left out (never drawn blank). Prints the path of every PNG
written. Exits with 1 if any file is missing, unreadable or has nothing to plot (the other files
are still plotted), 2 on bad usage.

Uses Debian's /usr/bin/python3 (python3-matplotlib, python3-h5py).
"""

import json
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import h5py  # noqa: E402

sys.dont_write_bytecode = True   # nothing written into the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lsi_sweep_plot  # noqa: E402
from lsi_plot_common import PlotError, as_str, open_hdf5, plot_files_main  # noqa: E402

# (dataset, axis label, scale factor from SI)
PANELS = [
    ("force", "force normal to face (kN/m)", 1e-3),
    ("landslide_kinetic_energy", "landslide kinetic energy (kJ/m)", 1e-3),
    ("barrier_displacement", "barrier displacement (m)", 1.0),
]

# A displacement curve is drawn off scale when its largest value is this many times the
# panel's scale (the next largest curve's, or the tolerable displacement); displacements whose
# largest values differ by more than this get a log-scale panel too.
OFF_SCALE_RATIO = 10.0
# The force and energy panels end at this many times the last impact's end, when the histories
# run on much longer (a closed form's barrier still sliding).
IMPACT_WINDOW_FACTOR = 1.5

# How a cut-short MPM run ended (the /<method> attribute end_state), for the notes.
TRUNCATED = {
    "barrier_left_domain": "the barrier left the modelled domain at t = {t} s, still sliding "
                           "(>= {d} m; final displacement not known)",
    "end_time_barrier_sliding": "the run reached its end time t = {t} s with the barrier still "
                                "sliding (>= {d} m; final displacement not known)",
    "end_time_landslide_moving": "the run reached its end time t = {t} s with the landslide "
                                 "still moving",
    "unstable": "stopped unstable at t = {t} s",
}

# The verification panels' curves: (dataset of /mpm, legend); the potential energy is drawn as
# its change since the start.
ENERGIES = [
    ("kinetic_energy", "kinetic"),
    ("elastic_energy", "elastic"),
    ("potential_energy", "potential - initial"),
    ("plastic_dissipation", "plastic dissipation"),
    ("boundary_dissipation", "boundary dissipation"),
    ("kinetic_energy_liquid", "liquid kinetic"),
    ("liquid_energy", "liquid stored"),
    ("drag_dissipation", "drag dissipation"),
    ("viscous_dissipation", "viscous dissipation"),
    ("transfer_dissipation", "transfer dissipation"),
]
RESIDUALS = [("energy_residual", "energy residual"),
             ("energy_residual_unexplained", "residual, transfer loss booked")]
WALL_FORCES = [("wall_force_x", "x"), ("wall_force_y", "y")]
FRONT = [("front_x", "front")]
# Wall pressure bands and their extent along the wall (from the dataset's description).
WALL_BAND = re.compile(r"^wall_pressure_(left|right|bottom|top)_band_(\d+)$")
BAND_EXTENT = re.compile(r"between [xy] = ([-+0-9.eE]+) and ([-+0-9.eE]+) m")


def scene_name(f, fallback):
    raw = f.attrs.get("scene")
    if raw is None:
        return fallback
    try:
        scene = json.loads(as_str(raw))
    except (ValueError, TypeError):
        return fallback
    if isinstance(scene, dict) and scene.get("name"):
        return str(scene["name"])
    return fallback


def scene_of(f):
    try:
        scene = json.loads(as_str(f.attrs.get("scene", "{}")))
    except (ValueError, TypeError):
        return {}
    return scene if isinstance(scene, dict) else {}


def scalar(group, name):
    """A method's scalar: the 0-d dataset scalars/<name>, else the group attribute (files of
    earlier versions); None where the method does not give it."""
    s = group.get("scalars")
    if isinstance(s, h5py.Group) and name in s:
        try:
            return float(s[name][()])
        except (TypeError, ValueError):
            return None
    if name in group.attrs:
        try:
            return float(group.attrs[name])
        except (TypeError, ValueError):
            return None
    return None


def history(group, dataset, path, name):
    """(t, y) of a dataset sampled at the group's time, or None."""
    if "time" not in group or dataset not in group:
        return None
    t = np.asarray(group["time"][()], dtype=float)
    y = np.asarray(group[dataset][()], dtype=float)
    if t.ndim != 1 or y.shape != t.shape:
        print(f"warning: {path}: /{name}/{dataset} does not match /{name}/time; skipped",
              file=sys.stderr)
        return None
    if t.size == 0:
        return None
    return t, y


def fmt(v):
    return f"{v:.0f}" if abs(v) >= 1000 else f"{v:.3g}"


def plot_face_bands(f, title, out):
    """The face's pressure bands of the mpm group at the peak force, or None without bands."""
    if "mpm" not in f or not isinstance(f["mpm"], h5py.Group):
        return None
    g = f["mpm"]
    names = sorted(n for n in g if n.startswith("face_pressure_band_"))
    scene = scene_of(f)
    try:
        band = float(scene["methods"]["mpm"]["face_band_m"])
        height = float(scene["barrier"]["height_m"])
    except (KeyError, TypeError, ValueError):
        return None
    if not names or "force" not in g or band <= 0:
        return None
    force = g["force"][()]
    if force.size == 0:
        return None
    peak = int(force.argmax())
    z, p = [], []
    for k, name in enumerate(names):
        z0, z1 = k * band, min((k + 1) * band, height)
        value = g[name][()][peak] * 1e-3
        z += [z0, z1]
        p += [value, value]
    fig, ax = plt.subplots(figsize=(5, 6), dpi=120)
    ax.plot(p, z, color="C2")
    ax.fill_betweenx(z, 0, p, color="C2", alpha=0.3)
    if "face_resultant_height" in g:
        zr = float(g["face_resultant_height"][()][peak])
        ax.axhline(zr, color="k", linestyle="--", linewidth=1, label=f"resultant at {zr:.2f} m")
        ax.legend(loc="best", fontsize="small")
    t = float(g["time"][()][peak]) if "time" in g else float("nan")
    ax.set_xlabel("normal stress on the upstream face (kPa)")
    ax.set_ylabel("height above the base (m)")
    ax.set_ylim(0, height)
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{title}: MPM at the peak force, t = {t:.3g} s", fontsize="medium")
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return out


def impact_window(curves):
    """The end of the force and energy panels' time axis: shortly after the last impact ends,
    or None to show every history whole."""
    ends, impact_ends = [], []
    for t, y in curves:
        ends.append(t[-1])
        finite = np.isfinite(y)
        if not finite.any():
            continue
        peak = np.max(np.abs(y[finite]))
        if peak <= 0:
            continue
        loaded = np.nonzero(finite & (np.abs(y) > 0.01 * peak))[0]
        impact_ends.append(t[loaded[-1]] if loaded.size else t[-1])
    if not ends or not impact_ends:
        return None
    end = min(max(ends), IMPACT_WINDOW_FACTOR * max(impact_ends))
    return end if end < 0.8 * max(ends) else None


def truncation(name, group):
    """(end time, note) of a run cut short, or None."""
    state = as_str(group.attrs.get("end_state", ""))
    if state not in TRUNCATED:
        return None
    t_end = scalar(group, "end_time")
    if t_end is None and "time" in group and group["time"].size:
        t_end = float(group["time"][-1])
    d = scalar(group, "displacement_at_end")
    if d is None and "barrier_displacement" in group and group["barrier_displacement"].size:
        d = float(group["barrier_displacement"][-1])
    note = TRUNCATED[state].format(t=fmt(t_end) if t_end is not None else "?",
                                   d=fmt(d) if d is not None else "?")
    return t_end, f"{name}: {note}"


def off_scale_curves(curves, tolerance):
    """The curves whose displacement would squash the others: from the largest down, each that
    is more than OFF_SCALE_RATIO times the next largest (and times the tolerable displacement)."""
    peaks = sorted(((float(np.max(np.abs(y[np.isfinite(y)]))) if np.isfinite(y).any() else 0.0,
                    name) for name, (t, y) in curves.items()), reverse=True)
    off = set()
    for (peak, name), (below, _) in zip(peaks, peaks[1:]):
        scale = max(below, tolerance or 0.0)
        if scale <= 0 or peak <= OFF_SCALE_RATIO * scale:
            break
        off.add(name)
    return off


def wide_range(curves, tolerance):
    """Whether the displacements span more than OFF_SCALE_RATIO (a log-scale panel shows them)."""
    peaks = [float(np.max(np.abs(y[np.isfinite(y)]))) for t, y in curves.values()
             if np.isfinite(y).any()]
    peaks = [p for p in peaks + [tolerance or 0.0] if p > 0]
    return len(peaks) >= 2 and max(peaks) > OFF_SCALE_RATIO * min(peaks)


def plot_displacement(ax, curves, colours, tolerance, off_scale, notes):
    """The displacement panel on a linear scale: the curves in off_scale run off its top, marked
    where they leave, with a note."""
    for name, (t, y) in curves.items():
        ax.plot(t, y, label=name + (" (off scale)" if name in off_scale else ""),
                color=colours[name])
    if tolerance is not None:
        ax.axhline(tolerance, color="red", linestyle="--", linewidth=1.2,
                   label=f"tolerable displacement {tolerance:g} m")
    if not off_scale:
        return
    shown = [curves[n] for n in curves if n not in off_scale]
    top = max([float(np.nanmax(y)) for _, y in shown if np.isfinite(y).any()] +
              [tolerance or 0.0])
    bottom = min([float(np.nanmin(y)) for _, y in shown if np.isfinite(y).any()] + [0.0])
    top = top if top > 0 else 1.0
    pad = 0.12 * (top - bottom)
    ax.set_ylim(bottom - 0.05 * (top - bottom), top + pad)
    right = max(float(t[-1]) for t, _ in shown)
    for name in sorted(off_scale):
        t, y = curves[name]
        above = np.nonzero(y > top + pad)[0]
        t_cross = float(t[above[0]]) if above.size else float(t[-1])
        right = max(right, t_cross)
        ax.plot([t_cross], [top + pad], marker="^", markersize=9, color=colours[name],
                clip_on=False)
        ax.annotate(f"{name}: {fmt(float(np.nanmax(y)))} m", (t_cross, top + pad),
                    textcoords="offset points", xytext=(6, -12), fontsize="small",
                    color=colours[name])
        finite = np.isfinite(y)
        notes.append(f"{name}: displacement off scale from t = {fmt(t_cross)} s, "
                     f"{fmt(float(y[finite][-1]))} m at t = {fmt(float(t[finite][-1]))} s")
    left = min(float(t[0]) for t, _ in curves.values())
    ax.set_xlim(left, left + 1.05 * (right - left) if right > left else right + 1.0)


def plot_displacement_log(ax, curves, colours, tolerance):
    """Every displacement curve on a log scale (where their sizes differ by orders)."""
    peak = 0.0
    smallest = math.inf
    for name, (t, y) in curves.items():
        positive = y[np.isfinite(y) & (y > 0)]
        if positive.size:
            peak = max(peak, float(positive.max()))
            smallest = min(smallest, float(positive.max()))
        ax.plot(t, np.where(y > 0, y, np.nan), label=name, color=colours[name])
    if tolerance is not None:
        ax.axhline(tolerance, color="red", linestyle="--", linewidth=1.2,
                   label=f"tolerable displacement {tolerance:g} m")
        smallest = min(smallest, tolerance)
        peak = max(peak, tolerance)
    ax.set_yscale("log")
    if peak > 0:
        ax.set_ylim(max(smallest / 100, peak * 1e-6), peak * 2)


def plot_impact(f, path, stem, title, out_dir, tolerance):
    """DIR/<stem>.png of an impact result, or None when the file has no impact histories."""
    methods = [(name, obj) for name, obj in f.items() if isinstance(obj, h5py.Group)]
    data = {}
    for dataset, _, scale in PANELS:
        curves = {}
        for name, group in methods:
            h = history(group, dataset, path, name)
            if h is not None:
                curves[name] = (h[0], h[1] * scale)
        if curves:
            data[dataset] = curves
    if not data:
        return None
    colours = {name: f"C{k}" for k, (name, _) in enumerate(methods)}
    truncated = {}
    notes = []
    for name, group in methods:
        tr = truncation(name, group)
        if tr is not None:
            truncated[name] = tr[0]
            notes.append(tr[1])
        d = scalar(group, "final_displacement")
        if d is not None and math.isinf(d):
            notes.append(f"{name}: the barrier never stops (final displacement infinite)")

    panels = [(dataset, label) for dataset, label, _ in PANELS if dataset in data]
    off_scale = set()
    if "barrier_displacement" in data:
        off_scale = off_scale_curves(data["barrier_displacement"], tolerance)
        if off_scale or wide_range(data["barrier_displacement"], tolerance):
            panels.append(("barrier_displacement_log", "barrier displacement (m), log scale"))
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 3 * len(panels) + 0.6), dpi=120,
                             squeeze=False)
    axes = list(axes[:, 0])
    timed = [ax for ax, p in zip(axes, panels) if not p[0].startswith("barrier_displacement")]
    for ax in timed[1:]:
        ax.sharex(timed[0])
    window = impact_window(list(data["force"].values())) if "force" in data else None
    for ax, (dataset, label) in zip(axes, panels):
        curves = data[dataset.replace("_log", "")]
        if dataset == "barrier_displacement":
            plot_displacement(ax, curves, colours, tolerance, off_scale, notes)
        elif dataset == "barrier_displacement_log":
            plot_displacement_log(ax, curves, colours, tolerance)
        else:
            for name, (t, y) in curves.items():
                ax.plot(t, y, label=name, color=colours[name])
            if window is not None:
                ax.set_xlim(min(float(t[0]) for t, _ in curves.values()), window)
        for name, (t, y) in curves.items():
            if name in truncated:
                ax.plot([t[-1]], [y[-1]], marker="x", markersize=9, mew=2, color=colours[name],
                        clip_on=True)
                if truncated[name] is not None:
                    ax.axvline(truncated[name], color=colours[name], linestyle=":", linewidth=1.2)
        ax.set_ylabel(label)
        ax.set_xlabel("time (s)")
        ax.grid(True, which="both" if dataset.endswith("_log") else "major", alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    for ax in timed[:-1]:
        ax.set_xlabel("")
        ax.tick_params(labelbottom=False)
    fig.suptitle(title)
    if truncated:
        notes.insert(0, "x / dotted line: where a run was cut short")
    bottom = 0.0
    if notes:
        height_in = fig.get_size_inches()[1]
        bottom = min(0.4, (0.2 * len(notes) + 0.15) / height_in)
        fig.text(0.02, 0.01, "\n".join(notes), fontsize="small", va="bottom", ha="left",
                 wrap=True)
    fig.tight_layout(rect=(0, bottom, 1, 1))
    out = os.path.join(out_dir, stem + ".png")
    fig.savefig(out)
    plt.close(fig)
    return out


def kilo(units, values):
    """(units, scale): SI force, energy and stress units in kilo when the values are large."""
    finite = values[np.isfinite(values)] if values.size else values
    large = finite.size and np.max(np.abs(finite)) >= 1e4
    prefixed = {"N/m": "kN/m", "J/m": "kJ/m", "Pa": "kPa", "N": "kN"}
    if large and units in prefixed:
        return prefixed[units], 1e-3
    return units, 1.0


def plot_verification(f, path, stem, title, out_dir):
    """DIR/<stem>.png of an MPM run's energies, residual, wall forces and front, or None."""
    g = f.get("mpm")
    if not isinstance(g, h5py.Group):
        return None
    panels = []
    for entries, label in ((ENERGIES, "energy"), (RESIDUALS, "energy residual"),
                           (WALL_FORCES, "reaction of the walls"),
                           (FRONT, "front: largest x of a point")):
        curves = []
        units = None
        for dataset, legend in entries:
            h = history(g, dataset, path, "mpm")
            if h is None:
                continue
            t, y = h
            if dataset == "potential_energy":
                y = y - y[0]
            curves.append((t, y, legend))
            units = units or as_str(g[dataset].attrs.get("units", ""))
        if curves:
            panels.append((label, units, curves))
    if not panels:
        return None
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8, 2.6 * len(panels) + 0.6),
                             dpi=120, squeeze=False)
    for ax, (label, units, curves) in zip(axes[:, 0], panels):
        every = np.concatenate([y for _, y, _ in curves])
        shown_units, scale = kilo(units or "", every)
        for t, y, legend in curves:
            ax.plot(t, y * scale, label=legend)
        ax.set_ylabel(f"{label} ({shown_units})" if shown_units not in ("", "1") else label)
        ax.grid(True, alpha=0.3)
        if len(curves) > 1:
            ax.legend(loc="best", fontsize="small")
    axes[-1, 0].set_xlabel("time (s)")
    state = as_str(g.attrs.get("status", ""))
    fig.suptitle(f"{title}: MPM" + (f" ({state})" if state and state != "finished" else ""))
    fig.tight_layout()
    out = os.path.join(out_dir, stem + ".png")
    fig.savefig(out)
    plt.close(fig)
    return out


def plot_wall_bands(f, title, out):
    """The walls' pressure bands (wall_pressure_<wall>_band_<k>), each wall at the time of its
    largest band pressure; None without bands."""
    g = f.get("mpm")
    if not isinstance(g, h5py.Group) or "time" not in g:
        return None
    walls = {}
    for name in g:
        m = WALL_BAND.match(name)
        if m:
            walls.setdefault(m.group(1), []).append((int(m.group(2)), name))
    if not walls:
        return None
    t = np.asarray(g["time"][()], dtype=float)
    order = [w for w in ("left", "right", "bottom", "top") if w in walls]
    fig, axes = plt.subplots(1, len(order), figsize=(4.8 * len(order), 5), dpi=120, squeeze=False)
    for ax, wall in zip(axes[0], order):
        bands = sorted(walls[wall])
        p = np.array([np.asarray(g[name][()], dtype=float) for _, name in bands])  # [band, time]
        extents = []
        for k, name in bands:
            m = BAND_EXTENT.search(as_str(g[name].attrs.get("description", "")))
            extents.append((float(m.group(1)), float(m.group(2))) if m else (k, k + 1.0))
        finite = np.where(np.isfinite(p), p, -np.inf)
        if p.size == 0 or not np.isfinite(finite).any():
            ax.set_visible(False)
            continue
        i = int(np.unravel_index(np.argmax(finite), finite.shape)[1])
        units, scale = kilo(as_str(g[bands[0][1]].attrs.get("units", "Pa")), p[:, i])
        s, v = [], []
        for (s0, s1), value in zip(extents, p[:, i] * scale):
            s += [s0, s1]
            v += [value, value]
        along = "y" if wall in ("left", "right") else "x"
        if along == "y":
            ax.plot(v, s, color="C0")
            ax.fill_betweenx(s, 0, v, color="C0", alpha=0.3)
            ax.set_xlabel(f"normal stress on the {wall} wall ({units})")
            ax.set_ylabel("height y (m)")
        else:
            ax.plot(s, v, color="C0")
            ax.fill_between(s, 0, v, color="C0", alpha=0.3)
            ax.set_xlabel("x (m)")
            ax.set_ylabel(f"normal stress on the {wall} wall ({units})")
        ax.grid(True, alpha=0.3)
        ax.set_title(f"{wall} wall at t = {t[i]:.3g} s\n(its largest band pressure)",
                     fontsize="medium")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return out


def plot_file(path, out_dir, tolerance=None):
    """Plots one file; returns the PNGs written."""
    stem = os.path.splitext(os.path.basename(path))[0]
    with open_hdf5(path) as f:
        if as_str(f.attrs.get("kind", "")) == lsi_sweep_plot.KIND:
            return lsi_sweep_plot.plot_sweep(f, path, out_dir, tolerance)
        if not any(isinstance(obj, h5py.Group) for obj in f.values()):
            raise PlotError(f"{path}: no method groups in the file")
        title = scene_name(f, stem)
        os.makedirs(out_dir, exist_ok=True)
        written = []
        main = plot_impact(f, path, stem, title, out_dir, tolerance)
        if main is None:
            main = plot_verification(f, path, stem, title, out_dir)
        if main is None:
            raise PlotError(f"{path}: nothing to plot (no force, landslide kinetic energy or "
                            "barrier displacement history, and no MPM energies, wall forces or "
                            "front)")
        written.append(main)
        for extra in (plot_face_bands(f, title, os.path.join(out_dir, stem + "-face.png")),
                      plot_wall_bands(f, title, os.path.join(out_dir, stem + "-walls.png"))):
            if extra:
                written.append(extra)
    return written


def main(argv=None):
    return plot_files_main(
        argv, "lsi_plot.py", plot_file,
        description="Plot lsi HDF5 result files: force, landslide kinetic energy and barrier "
                    "displacement of impact results; energies, wall forces, front and wall "
                    "pressures of MPM verification scenes; distributions of sweep files.",
        files="results", files_metavar="RESULT.h5", files_help="lsi result file(s)",
        max_displacement_help="the design's tolerable barrier displacement (m): a line on the "
                              "displacement panel, and P(final displacement > X) on sweep plots")


if __name__ == "__main__":
    sys.exit(main())
