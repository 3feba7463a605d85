#!/usr/bin/python3
"""Plot lsi result files (HDF5, one group per design method).

    lsi_plot.py RESULT.h5 [RESULT.h5 ...] --out-dir DIR

For each result file writes DIR/<stem>.png: three stacked panels sharing the time axis,
  1. impact force normal to the barrier face F(t)   (kN/m)
  2. landslide kinetic energy                       (kJ/m)
  3. barrier displacement                           (m)
with every method group of the file drawn on the same axes (legend = method name) and the scene
name (root attribute `scene`, JSON) as the title. A method lacking a dataset is left out of that
panel. Where the MPM reported the face's pressure in height bands (methods.mpm.face_band_m), also
writes DIR/<stem>-face.png: the normal stress on the upstream face against the height above the
base at the time of the peak force, with the resultant's height marked. Prints the path of every PNG written. Exits with 1 if any file is missing, unreadable or
has no method groups (the other files are still plotted), 2 on bad usage.

Uses Debian's /usr/bin/python3 (python3-matplotlib, python3-h5py).
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import h5py  # noqa: E402

# (dataset, axis label, scale factor from SI)
PANELS = [
    ("force", "force normal to face (kN/m)", 1e-3),
    ("landslide_kinetic_energy", "landslide kinetic energy (kJ/m)", 1e-3),
    ("barrier_displacement", "barrier displacement (m)", 1.0),
]


class PlotError(Exception):
    pass


def _as_str(value):
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if hasattr(value, "item"):  # numpy scalar / 0-d array
        return _as_str(value.item())
    return str(value)


def scene_name(f, fallback):
    raw = f.attrs.get("scene")
    if raw is None:
        return fallback
    try:
        scene = json.loads(_as_str(raw))
    except (ValueError, TypeError):
        return fallback
    if isinstance(scene, dict) and scene.get("name"):
        return str(scene["name"])
    return fallback


def scene_of(f):
    try:
        scene = json.loads(_as_str(f.attrs.get("scene", "{}")))
    except (ValueError, TypeError):
        return {}
    return scene if isinstance(scene, dict) else {}


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


def plot_file(path, out_dir):
    if not os.path.isfile(path):
        raise PlotError(f"{path}: no such file")
    stem = os.path.splitext(os.path.basename(path))[0]
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise PlotError(f"{path}: cannot open as HDF5 ({e})") from e
    with f:
        methods = [(name, obj) for name, obj in f.items() if isinstance(obj, h5py.Group)]
        if not methods:
            raise PlotError(f"{path}: no method groups in the file")
        title = scene_name(f, stem)

        fig, axes = plt.subplots(len(PANELS), 1, sharex=True, figsize=(8, 9), dpi=120)
        for ax, (dataset, label, scale) in zip(axes, PANELS):
            drawn = 0
            for name, group in methods:
                if "time" not in group or dataset not in group:
                    continue
                t = group["time"][()]
                y = group[dataset][()]
                if t.ndim != 1 or y.shape != t.shape:
                    print(f"warning: {path}: /{name}/{dataset} does not match /{name}/time; "
                          "skipped", file=sys.stderr)
                    continue
                ax.plot(t, y * scale, label=name)
                drawn += 1
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
            if drawn:
                ax.legend(loc="best", fontsize="small")
            else:
                ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center",
                        color="grey")
        axes[-1].set_xlabel("time (s)")
        fig.suptitle(title)
        fig.tight_layout()

        os.makedirs(out_dir, exist_ok=True)
        out = os.path.join(out_dir, stem + ".png")
        fig.savefig(out)
        plt.close(fig)
        face = plot_face_bands(f, title, os.path.join(out_dir, stem + "-face.png"))
        if face:
            print(face)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Plot force, landslide kinetic energy and barrier displacement from lsi "
                    "HDF5 result files (one PNG per file).")
    parser.add_argument("results", nargs="+", metavar="RESULT.h5", help="lsi result file(s)")
    parser.add_argument("--out-dir", required=True, metavar="DIR",
                        help="directory for the PNG files (created if missing)")
    args = parser.parse_args(argv)

    failed = False
    for path in args.results:
        try:
            print(plot_file(path, args.out_dir))
        except PlotError as e:
            print(f"lsi_plot.py: error: {e}", file=sys.stderr)
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
