#!/usr/bin/env python3
"""Velocity profile of a granular layer on a slope against Bagnold's, for the mu(I) friction.

Usage: ci/granular_slope_profile.py SCENE.json RESULT.h5

SCENE is an `mpm_case` scene of one Mohr-Coulomb layer with `inertial_friction` on a no-slip
base under rotated gravity (scenes/verification/granular-slope.json); RESULT its `lsi run --out`
file with particle snapshots. In the last snapshot, the points within two layer thicknesses of
the layer's mean x (away from both ends) are binned by height, and their mean velocity is
compared with the steady solution of the mu(I) rheology for a layer of thickness h down a slope
theta (GDR MiDi 2004; Jop, Forterre & Pouliquen 2006):

    tan(theta) = mu(I_theta)  =>  I_theta = I0 (tan(theta) - mu_s) / (mu_2 - tan(theta))
    u(z) = (2/3) I_theta sqrt(phi g cos(theta)) (h^1.5 - (h - z)^1.5) / d

with phi = rho / rho_s the solid fraction, mu = sin of the scene's Mohr-Coulomb angles
(docs/theory/mpm.md, "Rate-dependent friction"). Prints the profile, the surface velocity's error and
the stress ratio tau / sigma_yy per bin (tan(theta) in a steady uniform layer).
"""
import json
import math
import sys

import h5py
import numpy as np


def main(scene_path, result_path):
    scene = json.load(open(scene_path))
    case = scene["mpm_case"]
    gx, gy = case["gravity_m_s2"]
    g = math.hypot(gx, gy)
    theta = math.atan2(gx, -gy)
    (material,) = case["materials"].values()
    mi = material["inertial_friction"]
    mu_s = math.sin(math.radians(material["friction_angle_deg"]))
    mu_2 = math.sin(math.radians(mi["limit_friction_angle_deg"]))
    i0, d = mi["reference_inertial_number"], 1e-3 * mi["grain_diameter_mm"]
    phi = material["density_kg_m3"] / mi["grain_density_kg_m3"]
    base = case["walls"]["bottom"]["position_m"]
    (body,) = case["bodies"]
    ys = [p[1] for p in body["polygon_m"]]
    h0 = max(ys) - min(ys)
    dx = scene["methods"]["mpm"]["cell_size_m"]
    tan = math.tan(theta)
    if not mu_s < tan < mu_2:
        sys.exit(f"tan(theta) = {tan:.4f} outside (mu_s, mu_2) = ({mu_s:.4f}, {mu_2:.4f}): no steady flow")
    i_theta = i0 * (tan - mu_s) / (mu_2 - tan)

    with h5py.File(result_path, "r") as f:
        snaps = f["/mpm/snapshots"]
        last = snaps[sorted(snaps.keys())[-1]]
        t = float(last.attrs["time"])
        x = last["position"][:, 0]
        y = last["position"][:, 1] - base
        u = last["velocity"][:, 0]
        s = last["stress"][:]
    window = np.abs(x - x.mean()) < 2 * h0
    h = y[window].max() + dx / 4   # the top row of points lies dx/4 below the surface
    bins = max(4, int(round(h0 / dx)))
    idx = np.clip((y[window] / h * bins).astype(int), 0, bins - 1)

    def bagnold(z):
        return 2.0 / 3.0 * i_theta * math.sqrt(phi * g * math.cos(theta)) * (h**1.5 - (h - z) ** 1.5) / d

    print(f"t = {t:.3f} s, theta = {math.degrees(theta):.2f} deg, I_theta = {i_theta:.4f}, "
          f"h = {h * 1e3:.3f} mm ({h / h0:.4f} h0), {bins} bins, {window.sum()} points")
    print("  z/h     u (m/s)   Bagnold   error    tau/sigma_yy")
    surface = None
    for b in range(bins):
        sel = idx == b
        z = (b + 0.5) / bins * h
        ub = u[window][sel].mean()
        sb = s[window][sel].mean(axis=0)
        ratio = sb[2] / -sb[1]
        print(f"  {z / h:.3f}   {ub:.4f}    {bagnold(z):.4f}    {100 * (ub / bagnold(z) - 1):+6.1f} %   {ratio:.4f}")
        surface = (ub, bagnold(z))
    print(f"surface bin: {surface[0]:.4f} m/s against {surface[1]:.4f} "
          f"({100 * (surface[0] / surface[1] - 1):+.1f} %); tan(theta) = {tan:.4f}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
