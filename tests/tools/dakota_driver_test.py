#!/usr/bin/python3
"""tools/dakota_driver.py end to end: hand-written Dakota parameters files (standard format, one
evaluation and a batch of three) through the driver, whose results files must hold lsi's own
values (`lsi run` on each point) to 1e-12 relative, every batch in one lsi run; and the driver's
refusals (a value out of range, a gradient request).

  dakota_driver_test.py LSI SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

from checks import check, finish  # tests/tools/checks.py, beside this script

LSI, SOURCE, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
DRIVER = os.path.join(SOURCE, "tools", "dakota_driver.py")
SCENE = os.path.join(SOURCE, "scenes", "former-reference", "L1-B1.json")
# The driver's values go through the same batched kernel as `lsi sweep`, `lsi run` through the
# scalar methods: the same formulas, whose multiply-adds the compiler may contract differently.
REL = 1e-12



def lsi_run(velocity, friction):
    out = subprocess.run([LSI, "run", SCENE, "--methods", "empirical,analytical", "--format", "json",
                          "--set", f"/landslide/velocity_m_s={velocity!r}",
                          "--set", f"/barrier/base_friction={friction!r}"],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    return json.loads(out)


def close(a, b):
    return abs(a - b) <= REL * abs(b)


def parameters(sets, functions, batch):
    """A standard-format parameters file: `sets` of (label, value), `functions` (asv, label)."""
    text = ""
    for k, variables in enumerate(sets):
        text += f"{len(variables):>44} variables\n"
        for label, value in variables:
            text += f"{value:>44.15e} {label}\n"
        text += f"{len(functions):>44} functions\n"
        for i, (asv, label) in enumerate(functions):
            text += f"{asv:>44} ASV_{i + 1}:{label}\n"
        text += f"{len(variables):>44} derivative_variables\n"
        for i, (label, _) in enumerate(variables):
            text += f"{i + 1:>44} DVV_{i + 1}:{label}\n"
        text += f"{0:>44} analysis_components\n"
        text += f"{'1:' + str(k + 1) if batch else '1':>44} eval_id\n"
    return text


def write(name, text):
    path = os.path.join(WORK, name)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def driver(params, results, *options):
    return subprocess.run([sys.executable, DRIVER, "--study", STUDY, "--lsi", COUNTING_LSI,
                           *options, params, results],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def lsi_runs():
    if not os.path.exists(CALLS):
        return 0
    with open(CALLS, encoding="utf-8") as f:
        return len(f.readlines())


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
STUDY = write("study.json", json.dumps({"name": "dakota", "scene": SCENE,
                                        "methods": ["empirical", "analytical"]}))
# lsi behind a script that counts its runs.
CALLS = os.path.join(WORK, "lsi-calls.txt")
COUNTING_LSI = write("counting-lsi", f'#!/bin/sh\necho run >> "{CALLS}"\nexec "{LSI}" "$@"\n')
os.chmod(COUNTING_LSI, 0o755)

# One evaluation, the descriptors being lsi's names; an inactive response (ASV 0) gets no line.
single = write("params.in", parameters(
    [[("/landslide/velocity_m_s", 7.3), ("/barrier/base_friction", 0.27)]],
    [(1, "analytical/peak_force"), (0, "analytical/rise_time"),
     (1, "analytical/final_displacement"), (1, "empirical/peak_force")], batch=False))
r = driver(single, os.path.join(WORK, "results.out"))
check(r.returncode == 0, f"single evaluation: exit {r.returncode}: {r.stderr}")
if r.returncode == 0:
    with open(os.path.join(WORK, "results.out"), encoding="utf-8") as f:
        lines = [l.split() for l in f.read().splitlines()]
    # The values as Dakota wrote them (15 digits after the point) are the ones lsi ran.
    v, mu = float(f"{7.3:.15e}"), float(f"{0.27:.15e}")
    want = lsi_run(v, mu)
    check([l[1] for l in lines] == ["analytical/peak_force", "analytical/final_displacement",
                                    "empirical/peak_force"], f"single: labels {lines}")
    for (value, label) in lines:
        method, output = label.split("/")
        check(close(float(value), want[method][output]),
              f"single: {label} = {value}, lsi run gives {want[method][output]!r}")
    check(want["analytical"]["final_displacement"] > 0, "the point's barrier slides")
check(lsi_runs() == 1, f"single: {lsi_runs()} lsi runs")

# A batch of three evaluations in one lsi run, the descriptors mapped to lsi's names.
points = [(4.5, 0.35), (8.25, 0.2), (6.0, 0.55)]
batch = write("batch.in", parameters([[("v", p[0]), ("mu", p[1])] for p in points],
                                     [(1, "force"), (1, "slide")], batch=True))
r = driver(batch, os.path.join(WORK, "batch.out"), "--variable", "v=/landslide/velocity_m_s",
           "--variable", "mu=/barrier/base_friction", "--response", "force=analytical/peak_force",
           "--response", "slide=empirical/final_displacement")
check(r.returncode == 0, f"batch: exit {r.returncode}: {r.stderr}")
check(lsi_runs() == 2, f"batch: {lsi_runs() - 1} lsi runs for 3 evaluations (expected 1)")
if r.returncode == 0:
    with open(os.path.join(WORK, "batch.out"), encoding="utf-8") as f:
        blocks = f.read().split("#\n")
    check(blocks[0] == "" and len(blocks) == 4, f"batch: {len(blocks) - 1} blocks after '#' lines")
    for (velocity, friction), block in zip(points, blocks[1:]):
        want = lsi_run(float(f"{velocity:.15e}"), float(f"{friction:.15e}"))
        got = dict((l.split()[1], float(l.split()[0])) for l in block.splitlines())
        check(close(got["force"], want["analytical"]["peak_force"]),
              f"batch: force {got['force']!r} vs {want['analytical']['peak_force']!r}")
        check(close(got["slide"], want["empirical"]["final_displacement"]),
              f"batch: slide {got['slide']!r} vs {want['empirical']['final_displacement']!r}")

# A velocity out of range: lsi's message (file, row, column, value, range), exit 2, no results.
bad = write("bad.in", parameters([[("/landslide/velocity_m_s", 5.0)],
                                  [("/landslide/velocity_m_s", -2.0)]],
                                 [(1, "analytical/peak_force")], batch=True))
r = driver(bad, os.path.join(WORK, "bad.out"))
check(r.returncode == 2, f"bad value: exit {r.returncode}")
check("row 2 (line 3), column /landslide/velocity_m_s = -2: must be > 0" in r.stderr,
      f"bad value: message {r.stderr!r}")
check(not os.path.exists(os.path.join(WORK, "bad.out")), "bad value: a results file was written")

# Gradients are refused before lsi runs.
runs = lsi_runs()
grad = write("grad.in", parameters([[("/landslide/velocity_m_s", 5.0)]],
                                   [(3, "analytical/peak_force")], batch=False))
r = driver(grad, os.path.join(WORK, "grad.out"))
check(r.returncode == 2 and "gradients" in r.stderr, f"gradient request: {r.returncode} {r.stderr}")
check(lsi_runs() == runs, "gradient request: lsi ran")

finish()
