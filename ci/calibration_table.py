#!/usr/bin/python3
"""Mean absolute relative error of the closed forms against the MPM, per barrier group, from the
/comparison of `lsi calibrate --out` files (docs/calibration.md, "Closed forms against the MPM").

usage: /usr/bin/python3 ci/calibration_table.py /tmp/ref/calibration_nrms.h5 /tmp/ref/calibration_pd.h5

Prints one row per file, group, method and coefficients: the mean of |relative error| over the
group's cases for the peak force and the impact duration (an undefined error, "-" in the
command's table, is left out and counted), and the range of the run times.
"""
import sys

import h5py
import numpy as np


def text(a):
    """HDF5 variable-length strings as a numpy array of str."""
    return np.array([x.decode() if isinstance(x, bytes) else x for x in a])


def mean_abs(e):
    """Mean |relative error| in %, with the number of undefined (NaN) ones left out."""
    undefined = int(np.isnan(e).sum())
    return f"{100 * np.nanmean(np.abs(e)):.0f} %" + (f" ({undefined} undefined)" if undefined else "")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip())
    print("file | group | method | coefficients | n | peak force | impact duration | run time")
    for path in sys.argv[1:]:
        with h5py.File(path, "r") as f:
            c = f["comparison"]   # parallel 1-D datasets, one entry per case, method and coefficients
            case, method, coef = text(c["case"][:]), text(c["method"][:]), text(c["coefficients"][:])
            peak, dur = c["peak_force_rel_error"][:], c["impact_duration_rel_error"][:]
            run = c["run_time_s"][:]
            for group in ("free", "fixed"):
                in_group = np.isin(case, text(f["groups"][group]["cases"][:]))
                for m in ("empirical", "analytical", "mpm"):
                    for k in dict.fromkeys(coef[in_group & (method == m)]):   # the command's order
                        rows = in_group & (method == m) & (coef == k)
                        t = run[rows]
                        if m == "mpm":   # the reference itself: no error, solver seconds
                            errors, span = "- | -", f"{t.min():.3g}-{t.max():.3g} s"
                        else:            # closed forms: microseconds per evaluation
                            errors = f"{mean_abs(peak[rows])} | {mean_abs(dur[rows])}"
                            span = f"{1e6 * t.min():.0f}-{1e6 * t.max():.0f} us"
                        print(f"{path} | {group} | {m} | {k} | {rows.sum()} | {errors} | {span}")


if __name__ == "__main__":
    main()
