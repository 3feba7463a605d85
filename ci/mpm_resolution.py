#!/usr/bin/python3
"""Resolution study of the MPM impact (issue 4): runs reference scenes at several cell sizes
(cells through the landslide's thickness) and tabulates peak force, impact duration, final
displacement, overtopped volume, steps and solver time, so that the default resolution of
scenes/reference/ can be chosen and justified (docs/notes/mpm.md, "Reference study resolution"); also
the lowest energy residual of each run and the largest volume of points inside the barrier (the
contact's leak), and, with --set transfer_dissipation=true, the energy lost in the grid
transfers and the residual it leaves unexplained (docs/theory/mpm.md, "Energy lost in the transfers").

usage: ci/mpm_resolution.py [--cells 4 8 16] [--phases saturated] [--drag semi-implicit]
                            [--out results/mpm_resolution] SCENE.json ...
"""
import argparse
import json
import os
import subprocess
import sys

import h5py

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--cells", nargs="+", type=int, default=[4, 8, 16])
    ap.add_argument("--phases", default="saturated")
    ap.add_argument("--drag", default="semi-implicit")
    ap.add_argument("--set", nargs="*", default=[], metavar="KEY=JSON",
                    help="further methods.mpm keys, e.g. transfer='\"pic\"'")
    ap.add_argument("--lsi", default=os.path.join(root, "build", "app", "lsi"))
    ap.add_argument("--out", default=os.path.join(root, "results", "mpm_resolution"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for path in a.scenes:
        scene = json.load(open(path))
        h = scene["landslide"]["thickness_m"]
        for n in a.cells:
            s = json.loads(json.dumps(scene))
            mpm = dict(s["methods"].get("mpm", {}))
            mpm["cell_size_m"] = h / n
            mpm["phases"] = a.phases
            for kv in a.set:
                k, v = kv.split("=", 1)
                mpm[k] = json.loads(v)
            if a.phases == "saturated":
                mpm["drag"] = a.drag
            else:
                mpm.pop("drag", None)
            s["methods"] = {"mpm": mpm}
            s["name"] = "%s-n%d" % (scene["name"], n)
            f = os.path.join(a.out, s["name"] + ".json")
            json.dump(s, open(f, "w"), indent=1)
            r = subprocess.run([a.lsi, "run", f, "--format", "json", "--out",
                                os.path.join(a.out, s["name"] + ".h5")],
                               capture_output=True, text=True)
            if r.returncode not in (0, 3):
                print(r.stdout, r.stderr, file=sys.stderr)
                sys.exit(r.returncode)
            m = json.loads(r.stdout)["mpm"]
            # From the histories: the lowest energy residual (numerical losses show as < 0).
            with h5py.File(os.path.join(a.out, s["name"] + ".h5"), "r") as hf:
                m["energy_residual_min"] = float(hf["mpm/energy_residual"][:].min())
            if r.returncode == 3:
                print("%-6s %3d cells/h: %s" % (scene["name"], n, r.stderr.strip()), flush=True)
                rows.append((scene["name"], n, h / n, m))
                continue
            rows.append((scene["name"], n, h / n, m))
            print("%-6s %3d cells/h  dx %.4f m: peak %.1f kN/m, duration %.2f s, displacement "
                  "%s m, overtopped %.2f m^2 (%.2f inside the barrier), %d points, %d steps, "
                  "%.1f s, residual min %.3f, "
                  "inside the barrier at most %.3f m^2" % (
                      scene["name"], n, h / n, m["peak_force"] / 1e3, m["impact_duration"],
                      "%.3f" % m["final_displacement"] if m.get("final_displacement") is not None
                      else ">= %.3f (%s)" % (m.get("displacement_at_end", float("nan")),
                                             m.get("end_state", "cut short")),
                      m["overtopped_volume_m2"],
                      m.get("overtopped_inside_barrier_m2", 0.0), m["particles"], m["steps"],
                      m["solver_seconds"], m["energy_residual_min"],
                      m.get("barrier_interior_volume_max_m2", 0.0))
                  + (", transfer dissipation %.3f MJ/m, unexplained residual %.4f .. %.4f" % (
                      m["transfer_dissipation_j_per_m"] / 1e6, m["energy_residual_unexplained_min"],
                      m["energy_residual_unexplained_max"])
                     if "transfer_dissipation_j_per_m" in m else ""),
                  flush=True)
    with open(os.path.join(a.out, "resolution.json"), "w") as f:
        json.dump([{"scene": s, "cells_per_thickness": n, "cell_size_m": dx, "mpm": m}
                   for s, n, dx, m in rows], f, indent=1)


if __name__ == "__main__":
    main()
