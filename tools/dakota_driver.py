#!/usr/bin/env python3
"""Dakota analysis driver for lsi (a "fork" or "system" interface, with or without `batch`).

Dakota calls it with its parameters file and the results file to write:

    interface
      fork
        analysis_drivers = 'python3 tools/dakota_driver.py --study my-study.json'
        # batch             <- optional: every evaluation of a batch in ONE lsi run

    tools/dakota_driver.py --study STUDY.json [--lsi PATH] [--variable LABEL=/POINTER ...]
                           [--response LABEL=METHOD/OUTPUT ...] PARAMS RESULTS

It reads the parameters file (Dakota's standard format, not aprepro; a batch file is several
parameter sets one after the other), writes the points to one CSV file, runs `lsi sweep` once on
a study of design "points" made from STUDY.json (tools/lsi_points.py), and writes the results
file: for each active response (ASV bit 1) "value label", in the parameters file's order; in a
batch, each evaluation's results after a line "#". An evaluation whose sample lsi ran but could
not evaluate (an MPM run that failed) gets "fail" (Dakota's failure capture). Gradients and
Hessians are not provided: ask Dakota for numerical_gradients or none.

Names: a variable's descriptor is the JSON pointer of the scene value it sets
(/landslide/velocity_m_s), or is mapped to one with --variable LABEL=/POINTER; a response's
descriptor is an lsi output column "<method>/<output>" (analytical/peak_force), or is mapped with
--response LABEL=METHOD/OUTPUT. lsi checks every value as it checks a scene: a value out of its
range ends the driver with lsi's message (exit code 2) and no results file.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lsi_points  # noqa: E402

SECTIONS = ("variables", "functions", "derivative_variables", "analysis_components", "metadata")


class ParametersError(ValueError):
    pass


class Evaluation:
    """One parameter set: variables (label, value text), functions (ASV, label), its eval_id."""

    def __init__(self):
        self.variables = []
        self.functions = []
        self.eval_id = None


def split_line(line, number):
    parts = line.split(None, 1)
    if len(parts) != 2:
        raise ParametersError(f"line {number}: {line.strip()!r}: expected 'value label'")
    return parts[0], parts[1].strip()


def read_parameters(path):
    """The parameter sets of a standard-format parameters file, in order."""
    with open(path, encoding="utf-8") as f:
        lines = [(k + 1, line) for k, line in enumerate(f) if line.strip()]
    sets, current, k = [], None, 0
    while k < len(lines):
        number, line = lines[k]
        value, label = split_line(line, number)
        if label == "eval_id":
            if current is None:
                raise ParametersError(f"line {number}: eval_id before any variables")
            current.eval_id = value
            k += 1
            continue
        if label not in SECTIONS:
            raise ParametersError(f"line {number}: {line.strip()!r}: expected a count and one of "
                                  f"{', '.join(SECTIONS)}, or eval_id (is it an aprepro-format "
                                  "file? use Dakota's standard format)")
        try:
            count = int(value)
        except ValueError:
            raise ParametersError(f"line {number}: {value!r} {label}: not a count") from None
        body = lines[k + 1:k + 1 + count]
        if len(body) != count:
            raise ParametersError(f"line {number}: {count} {label}, the file ends after "
                                  f"{len(body)}")
        if label == "variables":
            current = Evaluation()
            sets.append(current)
            current.variables = [split_line(l, n) for n, l in body]
        elif current is None:
            raise ParametersError(f"line {number}: {label} before any variables")
        elif label == "functions":
            for n, l in body:
                asv, name = split_line(l, n)
                current.functions.append((int(asv), name.split(":", 1)[1] if ":" in name else name))
        k += 1 + count
    if not sets:
        raise ParametersError("no variables: not a Dakota parameters file")
    return sets


def mapping(pairs, option):
    out = {}
    for p in pairs or []:
        if "=" not in p:
            raise ParametersError(f"{option} {p!r}: expected LABEL=NAME")
        label, name = p.split("=", 1)
        out[label] = name
    return out


def points_of(sets, variables):
    """The columns (JSON pointers) and one row per parameter set."""
    labels = [label for _, label in sets[0].variables]
    for e in sets[1:]:
        if [label for _, label in e.variables] != labels:
            raise ParametersError(f"evaluation {e.eval_id}: other variables than the first "
                                  "evaluation's")
    rows = []
    for e in sets:
        row = []
        for value, label in e.variables:
            try:
                row.append(float(value))
            except ValueError:
                raise ParametersError(f"evaluation {e.eval_id}: variable {label} = {value!r}: not "
                                      "a number (lsi takes numeric variables only)") from None
        rows.append(row)
    return [variables.get(label, label) for label in labels], rows


def results_text(sets, table, responses):
    blocks = []
    status = table.column("status")
    for i, e in enumerate(sets):
        lines = []
        if status[i] != 0:
            lines.append("fail")
        else:
            for asv, label in e.functions:
                if asv & 1:
                    column = responses.get(label, label)
                    if column not in table.columns:
                        outputs = [c for c in table.columns if "/" in c and not c.startswith("/")]
                        raise ParametersError(f"response {label}: not an output of the study "
                                              f"(outputs: {', '.join(outputs)}; map it with "
                                              "--response LABEL=METHOD/OUTPUT)")
                    lines.append(f"{table.rows[i][table.columns.index(column)]!r} {label}")
        blocks.append("\n".join(lines) + "\n")
    batch = len(sets) > 1 or any(e.eval_id and ":" in e.eval_id for e in sets)
    return "".join("#\n" + b for b in blocks) if batch else blocks[0]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--study", required=True, help="template study file (scene, methods, ...)")
    ap.add_argument("--lsi", help="the lsi executable (default: $LSI_EXE, else lsi on the PATH)")
    ap.add_argument("--variable", action="append", help="LABEL=/POINTER: a variable's scene key")
    ap.add_argument("--response", action="append",
                    help="LABEL=METHOD/OUTPUT: a response's lsi output column")
    ap.add_argument("--work-dir", help="where the temporary files go (default: the system's)")
    ap.add_argument("parameters", help="Dakota's parameters file")
    ap.add_argument("results", help="the results file to write")
    a = ap.parse_args(argv)
    try:
        sets = read_parameters(a.parameters)
        for e in sets:  # refused before lsi runs
            for asv, label in e.functions:
                if asv & 6:
                    raise ParametersError(f"evaluation {e.eval_id}: {label}: ASV {asv} asks for "
                                          "gradients or Hessians, which lsi does not give (use "
                                          "numerical_gradients or no_gradients)")
        columns, rows = points_of(sets, mapping(a.variable, "--variable"))
        table = lsi_points.evaluate(a.study, columns, rows, lsi=a.lsi, work_dir=a.work_dir)
        text = results_text(sets, table, mapping(a.response, "--response"))
    except ParametersError as e:
        print(f"dakota_driver: {a.parameters}: {e}", file=sys.stderr)
        return 2
    except lsi_points.LsiError as e:
        print(f"dakota_driver: {e}", file=sys.stderr)
        return e.code or 1
    tmp = f"{a.results}.tmp.{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, a.results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
