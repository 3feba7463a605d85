"""Evaluates the closed forms (or any study's methods) of lsi on given points in one `lsi sweep`
call: the points go to a CSV file, a study of design "points" is written from a template study,
and the per-sample table comes back from `lsi sweep --table-csv`, in the order of the points.

The template is a study file (docs/reference/scene_schema.md, "Study files") or the same as a
dict: its scene, methods, outputs and thresholds are used; the design becomes "points" and the
drawn design's keys (samples, seed, correlation) are dropped; listed inputs keep only their paths,
so that lsi checks the points' columns against them. Used by tools/dakota_driver.py and
tools/openturns_wrapper.py; standard library only.
"""
import json
import os
import shutil
import subprocess
import tempfile


class LsiError(RuntimeError):
    """lsi refused the points or failed: `code` is its exit code (2: invalid input), the message
    its one-line reason."""

    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


def find_lsi(lsi=None):
    """The lsi executable: `lsi`, else $LSI_EXE, else `lsi` on the PATH."""
    exe = lsi or os.environ.get("LSI_EXE") or shutil.which("lsi")
    if not exe:
        raise LsiError("no lsi executable: pass its path or set LSI_EXE", 1)
    return exe


def points_study(template, points_file):
    """The study (a dict) of design "points" that evaluates `points_file` with the template's
    scene and methods."""
    if isinstance(template, (str, os.PathLike)):
        base = os.path.dirname(os.path.abspath(template))
        with open(template, encoding="utf-8") as f:
            study = json.load(f)
    else:
        base = os.getcwd()
        study = json.loads(json.dumps(template))
    scene = study.get("scene")
    if isinstance(scene, str) and not os.path.isabs(scene):
        study["scene"] = os.path.normpath(os.path.join(base, scene))
    for key in ("samples", "seed", "correlation"):
        study.pop(key, None)
    if "inputs" in study:
        study["inputs"] = [{"path": i["path"]} for i in study["inputs"] if "path" in i]
    study.setdefault("name", "points")
    study["design"] = "points"
    study["points"] = {"file": os.path.abspath(points_file)}
    return study


def write_points(path, columns, rows):
    """A points file: the header names the columns, each row a point; every value in its
    shortest form that reads back to the same double."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(",".join(columns) + "\n")
        for row in rows:
            if len(row) != len(columns):
                raise ValueError(f"a point of {len(row)} values for {len(columns)} columns")
            f.write(",".join(repr(float(v)) for v in row) + "\n")


class Table:
    """The per-sample table of `lsi sweep --table-csv`: `columns` (index, the inputs, the
    outputs "<method>/<output>", status) and `rows` of floats, in the order of the points."""

    def __init__(self, columns, rows):
        self.columns = columns
        self.rows = rows

    def column(self, name):
        k = self.columns.index(name)
        return [r[k] for r in self.rows]

    def values(self, names):
        """The listed columns of every row (a list of rows)."""
        ks = [self.columns.index(n) for n in names]
        return [[r[k] for k in ks] for r in self.rows]


def read_table(path):
    with open(path, encoding="utf-8") as f:
        columns = f.readline().rstrip("\n").split(",")
        rows = [[float(v) for v in line.rstrip("\n").split(",")] for line in f if line.strip()]
    return Table(columns, rows)


def evaluate(template, columns, rows, lsi=None, work_dir=None, keep=False):
    """Runs the points `rows` (a list of rows of numbers, the columns named by `columns`, JSON
    pointers into the scene such as /landslide/velocity_m_s) through one `lsi sweep` and returns
    its Table. Raises LsiError with lsi's message when lsi refuses a point (a value out of its
    range, an unknown column) or fails. The files go to a temporary folder under `work_dir`
    (default: the system's), removed afterwards unless `keep`."""
    if hasattr(rows, "tolist"):
        rows = rows.tolist()
    exe = find_lsi(lsi)
    work = tempfile.mkdtemp(prefix="lsi-points-", dir=work_dir)
    try:
        points = os.path.join(work, "points.csv")
        write_points(points, columns, rows)
        study = os.path.join(work, "study.json")
        with open(study, "w", encoding="utf-8") as f:
            json.dump(points_study(template, points), f, indent=1)
        table = os.path.join(work, "table.csv")
        run = subprocess.run(
            [exe, "--progress", "none", "sweep", study, "--out", os.path.join(work, "sweep.h5"),
             "--table-csv", table, "--format", "json"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
        if run.returncode != 0:
            lines = (run.stderr or run.stdout).strip().splitlines()
            raise LsiError(lines[-1] if lines else f"lsi: exit code {run.returncode}",
                           run.returncode)
        result = read_table(table)
        if len(result.rows) != len(rows):
            raise LsiError(f"lsi returned {len(result.rows)} rows for {len(rows)} points "
                           "(a stop rule in the template study?)", 1)
        return result
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)
