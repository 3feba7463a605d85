#!/usr/bin/python3
"""tools/openturns_wrapper.py: an OpenTURNS sample of 1e5 points through the lsi function in one
lsi run, each value lsi's own (`lsi run` on a spread of the points) to 1e-12 relative.
Exits 77 (skipped) where Debian's python3-openturns is not installed.

  openturns_wrapper_test.py LSI SOURCE_DIR WORK_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys

from checks import check, finish  # tests/tools/checks.py, beside this script

try:
    import openturns as ot
except ImportError:
    print("openturns is not installed (Debian: python3-openturns): skipped")
    sys.exit(77)

LSI, SOURCE, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
sys.path.insert(0, os.path.join(SOURCE, "tools"))
from openturns_wrapper import lsi_function_and_runner  # noqa: E402

SCENE = os.path.join(SOURCE, "scenes", "former-reference", "L1-B1.json")
# The wrapper's values go through the batched kernel of `lsi sweep`, `lsi run` through the scalar
# methods: the same formulas, whose multiply-adds the compiler may contract differently.
REL = 1e-12
N = 100000



shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
calls = os.path.join(WORK, "lsi-calls.txt")
counting_lsi = os.path.join(WORK, "counting-lsi")
with open(counting_lsi, "w", encoding="utf-8") as f:
    f.write(f'#!/bin/sh\necho run >> "{calls}"\nexec "{LSI}" "$@"\n')
os.chmod(counting_lsi, 0o755)
study = os.path.join(WORK, "study.json")
with open(study, "w", encoding="utf-8") as f:
    json.dump({"name": "openturns", "scene": SCENE, "methods": ["empirical", "analytical"]}, f)

inputs = ["/landslide/velocity_m_s", "/barrier/base_friction", "/landslide/thickness_m"]
outputs = ["analytical/peak_force", "analytical/final_displacement", "empirical/peak_force",
           "empirical/rise_time"]
f, runner = lsi_function_and_runner(study, inputs, outputs, lsi=counting_lsi, work_dir=WORK)
ot.RandomGenerator.SetSeed(7)
X = ot.ComposedDistribution([ot.Uniform(3.0, 9.0), ot.Uniform(0.15, 0.7),
                             ot.Uniform(1.5, 2.5)]).getSample(N)
Y = f(X)
with open(calls, encoding="utf-8") as c:
    runs = len(c.readlines())
check(runs == 1 and runner.lsi_runs == 1, f"{runs} lsi runs for {N} points (expected 1)")
check(Y.getSize() == N and Y.getDimension() == len(outputs), f"Y is {Y.getSize()} x "
      f"{Y.getDimension()}")
check(all(math.isfinite(y) for row in Y for y in row), "every output is finite")

sliding = 0
for i in range(0, N, N // 20):
    x = X[i]
    run = subprocess.run([LSI, "run", SCENE, "--methods", "empirical,analytical", "--format",
                          "json"] + [a for d, p in enumerate(inputs)
                                     for a in ("--set", f"{p}={x[d]!r}")],
                         check=True, stdout=subprocess.PIPE, text=True)
    want = json.loads(run.stdout)
    for k, column in enumerate(outputs):
        method, output = column.split("/")
        w = want[method][output]
        check(abs(Y[i, k] - w) <= REL * abs(w), f"point {i}: {column} = {Y[i, k]!r}, "
              f"lsi run gives {w!r}")
    sliding += want["analytical"]["final_displacement"] > 0
check(sliding > 0, "the compared points include a sliding barrier")

# One point through _exec: the same value as in the sample.
y0 = f(X[0])
check(list(y0) == list(Y[0]), f"f(X[0]) = {list(y0)}, f(X)[0] = {list(Y[0])}")

finish()
