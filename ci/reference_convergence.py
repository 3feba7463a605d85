#!/usr/bin/python3
"""Convergence study of the reference study's MPM outputs: every scene of scenes/reference/ at
several cell sizes (cells through the landslide's thickness, Courant 0.5) and, at the base
resolution, a smaller Courant number. For every case and output it records the value at the base
resolution, the changes to the finer runs and their spread (the larger change), and whether the
output converged; writes them to ci/reference_convergence.json, which `lsi compare
--convergence` reads to print and store the error bars (ci/main.sh does), and the tables of
docs/vv/reference_convergence.md.

  ci/reference_convergence.py                       the study as documented (about 20 min on 2 cores)
  ci/reference_convergence.py --tables-only         rewrite the outputs from the runs already made

Runs are kept in --work (one HDF5 file per run, beside the scene it ran) and reused when the scene
is the same: a killed study resumes where it stopped.
"""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import subprocess
import sys

import h5py

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The outputs, their units and scale in the tables, and the absolute floor below which a change
# counts as converged whatever the value (a relative test is meaningless near zero): each with
# its reason.
OUTPUTS = [
    # name, label, unit, scale, floor (in the output's SI unit), reason for the floor
    ("peak_force", "peak force", "kN/m", 1e-3, 5e3,
     "5 kN/m: 3 % of the smallest reference peak"),
    ("peak_force_windowed", "peak force, window", "kN/m", 1e-3, 5e3, "as the peak force"),
    ("impulse", "impulse", "kN s/m", 1e-3, 10e3,
     "10 kN s/m: 3 % of the smallest reference impulse"),
    ("impact_duration", "impact duration", "s", 1.0, 0.1,
     "0.1 s: a few output intervals, where the 10 % threshold is crossed"),
    ("final_displacement", "final displacement", "m", 1.0, 0.05,
     "5 cm: below what a barrier design distinguishes"),
    ("overtopped_volume_m2", "overtopped volume", "m^2", 1.0, 0.5,
     "0.5 m^2: about 1 % of the landslides"),
    ("retained_volume_m2", "retained volume", "m^2", 1.0, 0.5, "as the overtopped volume"),
    ("face_pore_pressure_max_pa", "face pore pressure", "kPa", 1e-3, 10e3,
     "10 kPa: a quarter of the hydrostatic pressure at the base of the thinnest flow"),
]
RELATIVE = 0.10   # converged: spread <= 10 % of the value (or the floor)
WINDOWS = [0.0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3]   # s; 0: the raw peak (one output interval)


def run_name(scene, cells, courant):
    return "%s-n%d-c%g" % (scene["name"], cells, courant)


def variant(scene, cells, courant):
    s = json.loads(json.dumps(scene))
    mpm = dict(s["methods"]["mpm"])
    mpm["cell_size_m"] = scene["landslide"]["thickness_m"] / cells
    mpm["courant"] = courant
    s["methods"] = {"mpm": mpm}
    s["name"] = run_name(scene, cells, courant)
    return s


def run_one(lsi, work, s, threads):
    """Runs one variant unless its result exists for the same scene; returns the HDF5 path."""
    stem = os.path.join(work, s["name"])
    h5, js = stem + ".h5", stem + ".json"
    if os.path.exists(h5) and os.path.exists(js):
        try:
            with open(js) as f:
                if json.load(f) == s:
                    return h5
        except (OSError, ValueError):
            pass
    tmp = js + ".tmp"
    with open(tmp, "w") as f:
        json.dump(s, f, indent=1)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    r = subprocess.run([lsi, "run", tmp, "--methods", "mpm", "--out", h5, "--format", "json"],
                       capture_output=True, text=True, env=env)
    if r.returncode not in (0, 3):
        sys.exit("%s failed (exit %d):\n%s%s" % (s["name"], r.returncode, r.stdout, r.stderr))
    os.replace(tmp, js)   # the scene beside its result only once the result is complete
    return h5


def windowed_peak(t, f, w):
    """Largest mean of the piecewise-constant force (f[i] over (t[i-1], t[i]]) over a window w;
    w = 0: the largest sample (as model/impact_summary.cpp)."""
    if w <= 0:
        return max(f)
    J = [0.0]
    for i in range(1, len(t)):
        J.append(J[-1] + f[i] * (t[i] - t[i - 1]))

    def J_at(x):
        lo, hi = 0, len(t) - 1
        if x <= t[0]:
            return 0.0
        if x >= t[-1]:
            return J[-1]
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if t[mid] <= x:
                lo = mid
            else:
                hi = mid
        return J[lo] + f[hi] * (x - t[lo])

    w = min(w, t[-1] - t[0])
    best = -1e300
    for ti in t:
        for start in (ti, ti - w):
            start = min(max(start, t[0]), t[-1] - w)
            best = max(best, (J_at(start + w) - J_at(start)) / w)
    return best


def read_run(h5):
    with h5py.File(h5, "r") as f:
        m = f["mpm"]
        a = m.attrs
        # The scalars are 0-d datasets of /mpm/scalars; attributes of /mpm in earlier files.
        s = m["scalars"] if "scalars" in m else None

        def scalar(k):
            if s is not None:
                return float(s[k][()]) if k in s else float("nan")
            return float(a[k]) if k in a else float("nan")

        out = {k: scalar(k) for k, *_ in OUTPUTS}
        out["end_state"] = a["end_state"] if "end_state" in a else ""
        out["solver_seconds"] = scalar("solver_seconds")
        out["steps"] = int(scalar("steps"))
        out["window"] = scalar("peak_force_window")
        t, force = [float(x) for x in m["time"][:]], [float(x) for x in m["force"][:]]
        out["history"] = (t, force)
        out["windows"] = {str(w): windowed_peak(t, force, w) for w in WINDOWS}
    return out


def with_window(run, window):
    """The run's peak_force_windowed at `window` (the base run's), from its force history: the
    finer runs then measure the same thing, whatever window they ran with."""
    run = dict(run)
    if run.get("history") and finite(window):
        run["peak_force_windowed"] = windowed_peak(*run["history"], window)
    return run


def finite(x):
    return x is not None and not (isinstance(x, float) and (math.isnan(x) or math.isinf(x)))


def summarise(base, coarse, finer_cells, finer_courant, floor):
    changes = [x - base for x in (finer_cells, finer_courant) if finite(x) and finite(base)]
    if not finite(base) or len(changes) < 2:
        return {"value": base if finite(base) else None, "spread": None, "converged": False}
    spread = max(abs(c) for c in changes)
    return {
        "value": base,
        "coarser": coarse if finite(coarse) else None,
        "finer_cells": finer_cells,
        "finer_courant": finer_courant,
        "spread": spread,
        "converged": bool(spread <= max(RELATIVE * abs(base), floor)),
    }


def fmt(x, scale, digits):
    return "-" if x is None else "%.*f" % (digits, x * scale)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="*",
                    default=sorted(glob.glob(os.path.join(root, "scenes", "reference", "L?-B?*.json"))))
    ap.add_argument("--cells", nargs="+", type=int, default=[4, 8, 16],
                    help="cells through the thickness at Courant 0.5; the base is --base-cells")
    ap.add_argument("--base-cells", type=int, default=8)
    ap.add_argument("--courant", nargs="+", type=float, default=[0.5, 0.25],
                    help="Courant numbers at the base cells; the first is the base")
    ap.add_argument("--lsi", default=os.path.join(root, "build", "app", "lsi"))
    ap.add_argument("--work", default=os.path.join(root, "results", "convergence"))
    ap.add_argument("--out", default=os.path.join(root, "ci", "reference_convergence.json"))
    ap.add_argument("--tables", default=os.path.join(root, "docs", "vv", "reference_convergence.md"))
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (one thread each)")
    ap.add_argument("--tables-only", action="store_true")
    a = ap.parse_args()
    base_c = a.courant[0]
    finest_cells = max(a.cells)
    finer_courant = min(a.courant)
    if a.base_cells not in a.cells or finest_cells <= a.base_cells or finer_courant >= base_c:
        sys.exit("--cells must contain --base-cells and a finer one; --courant a smaller one")
    os.makedirs(a.work, exist_ok=True)
    scenes = [json.load(open(p)) for p in a.scenes]
    jobs = []
    for s in scenes:
        for n in a.cells:
            jobs.append((s, n, base_c))
        for c in a.courant[1:]:
            jobs.append((s, a.base_cells, c))
    # The longest runs first, so that the pool ends together.
    jobs.sort(key=lambda j: -j[1] ** 3 / j[2])
    results = {}
    if a.tables_only:
        for s, n, c in jobs:
            results[(s["name"], n, c)] = read_run(os.path.join(a.work, run_name(s, n, c) + ".h5"))
    else:
        with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
            futures = {pool.submit(run_one, a.lsi, a.work, variant(s, n, c), 1): (s["name"], n, c)
                       for s, n, c in jobs}
            for fu in concurrent.futures.as_completed(futures):
                key = futures[fu]
                results[key] = read_run(fu.result())
                print("done %s-n%d-c%g" % key, file=sys.stderr, flush=True)
    coarse_cells = max([n for n in a.cells if n < a.base_cells], default=None)
    cases = {}
    for s in scenes:
        name = s["name"]
        b = results[(name, a.base_cells, base_c)]
        fc = with_window(results[(name, finest_cells, base_c)], b["window"])
        ft = with_window(results[(name, a.base_cells, finer_courant)], b["window"])
        co = results.get((name, coarse_cells, base_c)) if coarse_cells else None
        co = with_window(co, b["window"]) if co else None
        outs = {}
        for key, _, _, _, floor, _ in OUTPUTS:
            outs[key] = summarise(b[key], co[key] if co else None, fc[key], ft[key], floor)
        windows = {}
        for w in WINDOWS:
            k = str(w)
            windows[k] = summarise(b["windows"][k], co["windows"][k] if co else None,
                                   fc["windows"][k], ft["windows"][k], 5e3)
        cases[name] = {
            "landslide": s["landslide"],
            "barrier": s["barrier"],
            "mpm": variant(s, a.base_cells, base_c)["methods"]["mpm"],
            "end_states": {"base": b["end_state"], "finer_cells": fc["end_state"],
                           "finer_courant": ft["end_state"]},
            "solver_seconds": {"base": b["solver_seconds"], "finer_cells": fc["solver_seconds"],
                               "finer_courant": ft["solver_seconds"]},
            "window": b["window"],
            "outputs": outs,
            "peak_force_windows": windows,
        }
    doc = {
        "about": "Convergence study of the reference study's MPM outputs (ci/reference_convergence.py). "
                 "value: at the base resolution; finer_cells, finer_courant: the same case at the finest "
                 "cell and at the smaller Courant number; spread: the larger of the two changes (the error "
                 "bar of the base value); converged: spread <= max(relative x |value|, floor).",
        "command": "ci/reference_convergence.py --cells %s --base-cells %d --courant %s" % (
            " ".join(map(str, a.cells)), a.base_cells, " ".join("%g" % c for c in a.courant)),
        "base": {"cells": a.base_cells, "courant": base_c},
        "finer": {"cells": finest_cells, "courant": finer_courant},
        "relative": RELATIVE,
        "floors": {k: {"value": floor, "reason": why} for k, _, _, _, floor, why in OUTPUTS},
        "cases": cases,
    }
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(tmp, a.out)
    write_tables(a, doc, results, scenes)


def write_tables(a, doc, results, scenes):
    base, finer = doc["base"], doc["finer"]
    L = []
    L.append("# Convergence of the reference study's MPM outputs\n")
    L.append("Generated by `%s` (do not edit: rerun it). Every case of `scenes/reference/` at "
             "%s cells through the landslide's thickness (Courant %g) and at %d cells with Courant "
             "%g. Each cell gives the value at the base resolution (%d cells, Courant %g) and, "
             "after the ±, its spread: the larger change to the finest cell (%d) or to the "
             "smaller Courant number (%g). `*`: not converged, the spread above %d %% of the value "
             "and above the output's floor (`ci/reference_convergence.json`, `floors`). "
             "Read by `lsi compare --convergence` (ci/main.sh).\n" % (
                 doc["command"], ", ".join(str(n) for n in sorted(set(x[1] for x in results))),
                 base["courant"], base["cells"], finer["courant"], base["cells"], base["courant"],
                 finer["cells"], finer["courant"], int(100 * doc["relative"])))
    heads = [(k, lab, unit, sc) for k, lab, unit, sc, _, _ in OUTPUTS]
    L.append("| case | " + " | ".join("%s [%s]" % (lab, unit) for _, lab, unit, _ in heads) + " |")
    L.append("|---|" + "---|" * len(heads))
    for s in scenes:
        c = doc["cases"][s["name"]]
        cells = []
        for k, _, unit, sc in heads:
            o = c["outputs"][k]
            d = 3 if unit in ("m", "s") else (2 if unit == "m^2" else 0)
            cell = fmt(o["value"], sc, d)
            if o["spread"] is not None:
                cell += " ± " + fmt(o["spread"], sc, d) + ("" if o["converged"] else " *")
            cells.append(cell)
        L.append("| %s | %s |" % (s["name"], " | ".join(cells)))
    L.append("")
    L.append("## The peak force against the averaging window\n")
    L.append("The largest mean normal force over a window of the given length (0: one output "
             "interval, the raw `peak_force`), at the base resolution ± its spread, and the "
             "largest relative spread over the cases: the default `peak_force_window_s` is the "
             "shortest window whose spread stays within about 5 % for every case.\n")
    ws = [str(w) for w in WINDOWS]
    L.append("| case | " + " | ".join(("raw" if float(w) == 0 else "%g s" % float(w)) for w in ws) + " |")
    L.append("|---|" + "---|" * len(ws))
    worst = {w: 0.0 for w in ws}
    for s in scenes:
        c = doc["cases"][s["name"]]["peak_force_windows"]
        cells = []
        for w in ws:
            o = c[w]
            cells.append(fmt(o["value"], 1e-3, 0) + " ± " + fmt(o["spread"], 1e-3, 0))
            if o["spread"] is not None and o["value"]:
                worst[w] = max(worst[w], o["spread"] / abs(o["value"]))
        L.append("| %s | %s |" % (s["name"], " | ".join(cells)))
    L.append("| largest spread | %s |" % " | ".join("%.1f %%" % (100 * worst[w]) for w in ws))
    L.append("")
    within = [float(w) for w in ws if float(w) > 0 and worst[w] <= 0.05]
    used = sorted(set(doc["cases"][s["name"]]["window"] for s in scenes))
    L.append("Shortest window with every spread within 5 %%: %s; the study's runs used "
             "`peak_force_window_s` = %s s (the `peak force, window` column above).\n" % (
                 ("%g s" % min(within)) if within else "none of these",
                 ", ".join("%g" % w for w in used)))
    L.append("## Run time\n")
    L.append("Solver seconds per run (one thread each, %d runs at a time), and how each run "
             "ended.\n" % a.jobs)
    L.append("| case | base | finer cells | finer Courant | end states |")
    L.append("|---|---|---|---|---|")
    for s in scenes:
        c = doc["cases"][s["name"]]
        t, e = c["solver_seconds"], c["end_states"]
        states = sorted(set(e.values()))
        L.append("| %s | %.1f | %.1f | %.1f | %s |" % (s["name"], t["base"], t["finer_cells"],
                                                       t["finer_courant"], ", ".join(states)))
    L.append("")
    tmp = a.tables + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(L))
    os.replace(tmp, a.tables)


if __name__ == "__main__":
    main()
