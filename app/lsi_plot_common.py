"""What the plot scripts app/lsi_plot.py, app/lsi_sweep_plot.py and app/lsi_calibration_plot.py
share: their error, the text of an HDF5 attribute, and for the scripts that plot several files
into one folder (lsi_plot.py, lsi_sweep_plot.py) the opening of a file and the command line.

Not a script of its own; imported from the folder of the scripts, which puts it on the path.
"""

import argparse
import math
import os
import sys

import h5py


class PlotError(Exception):
    """A file that cannot be plotted: the message names it and says why."""


def as_str(value):
    """An HDF5 attribute as text: bytes decoded as UTF-8, a NumPy scalar or 0-d array unwrapped."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if hasattr(value, "item"):  # numpy scalar / 0-d array
        return as_str(value.item())
    return str(value)


def open_hdf5(path):
    """The file open for reading; PlotError if it is missing or not HDF5."""
    if not os.path.isfile(path):
        raise PlotError(f"{path}: no such file")
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise PlotError(f"{path}: cannot open as HDF5 ({e})") from e


def check_positive(parser, option, value):
    """Ends with a usage error (exit 2) unless `value` is None or a finite number > 0."""
    if value is not None and not (math.isfinite(value) and value > 0):
        parser.error(f"{option} {value}: must be a number > 0")


def plot_files_main(argv, prog, plot_file, description, files, files_metavar, files_help,
                    max_displacement_help):
    """The command line `prog FILE.h5 [FILE.h5 ...] --out-dir DIR [--max-displacement X]`.

    Plots every file with plot_file(path, out_dir, max_displacement), which returns the PNGs
    written, and prints their paths. A file that fails (PlotError, or one that cannot be read)
    is reported on standard error as `prog: error: ...` and the others are still plotted.
    Returns the exit code: 1 if any file failed, else 0; bad usage exits with 2.
    """
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument(files, nargs="+", metavar=files_metavar, help=files_help)
    parser.add_argument("--out-dir", required=True, metavar="DIR",
                        help="directory for the PNG files (created if missing)")
    parser.add_argument("--max-displacement", type=float, metavar="X",
                        help=max_displacement_help)
    args = parser.parse_args(argv)
    check_positive(parser, "--max-displacement", args.max_displacement)

    failed = False
    for path in getattr(args, files):
        try:
            for out in plot_file(path, args.out_dir, args.max_displacement):
                print(out)
        except PlotError as e:
            print(f"{prog}: error: {e}", file=sys.stderr)
            failed = True
        except (OSError, KeyError, ValueError) as e:
            print(f"{prog}: error: {path}: cannot read ({e})", file=sys.stderr)
            failed = True
    return 1 if failed else 0
