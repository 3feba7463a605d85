#!/usr/bin/python3
"""CI regression sweep: runs every study in ci/regression/ with `lsi sweep` and compares each
sample's inputs, status and outputs with the golden values in ci/regression/golden.json, within
the tolerances (and their reasons) in ci/regression/tolerances.json.

  ci/regression.py --lsi build/app/lsi [--work DIR]          compare (exit 1 on a difference)
  ci/regression.py --lsi build/app/lsi --update-golden       rewrite golden.json deliberately

Uses Debian's python3-h5py (installed by ci/setup.sh).
"""
import argparse
import fnmatch
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
REGRESSION = os.path.join(HERE, "regression")
GOLDEN = os.path.join(REGRESSION, "golden.json")
TOLERANCES = os.path.join(REGRESSION, "tolerances.json")


def studies():
    return sorted(f for f in os.listdir(REGRESSION)
                  if f.endswith(".json") and f not in ("golden.json", "tolerances.json"))


def number(x):
    """JSON-safe float: non-finite values as strings."""
    x = float(x)
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return x


def value(x):
    return float(x)   # also parses the strings "nan", "inf", "-inf" written by number()


def run_study(lsi, study, work):
    out = os.path.join(work, os.path.splitext(study)[0] + ".h5")
    for leftover in (out,):
        if os.path.exists(leftover):
            os.remove(leftover)
    subprocess.run([lsi, "sweep", os.path.join(REGRESSION, study), "--out", out, "--format", "json"],
                   check=True, stdout=subprocess.DEVNULL)
    with h5py.File(out, "r") as f:
        s = f["samples"]
        columns = json.loads(s.attrs["output_columns"])
        paths = json.loads(s["inputs"].attrs["paths"])
        result = {
            "index": [int(i) for i in s["index"][:]],
            "status": [int(i) for i in s["status"][:]],
            "inputs": {p: [number(v) for v in s["inputs"][:, k]] for k, p in enumerate(paths)},
            "outputs": {c: [number(v) for v in s[c][:]] for c in columns},
            "failures": [r.decode() if isinstance(r, bytes) else r for r in f["failures/reason"][:]],
        }
    return result


def tolerance_for(column, tol):
    for t in tol["columns"]:
        if fnmatch.fnmatch(column, t["match"]):
            return t
    raise SystemExit(f"regression: no tolerance for column {column} in {TOLERANCES}")


def close(a, b, t):
    a, b = value(a), value(b)
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= t["relative"] * abs(b) + t["absolute"]


def compare(name, got, gold, tol, problems):
    if got["index"] != gold["index"]:
        problems.append(f"{name}: sample indices differ ({len(got['index'])} vs {len(gold['index'])})")
        return
    if got["status"] != gold["status"]:
        diff = [i for i, (a, b) in enumerate(zip(got["status"], gold["status"])) if a != b]
        problems.append(f"{name}: status differs at samples {diff[:10]}")
    for path, values in gold["inputs"].items():
        for i, (a, b) in enumerate(zip(got["inputs"].get(path, []), values)):
            if not close(a, b, tol["inputs"]):
                problems.append(f"{name}: input {path} of sample {i}: {a} vs golden {b}")
                break
    for column, values in gold["outputs"].items():
        if column not in got["outputs"]:
            problems.append(f"{name}: column {column} missing")
            continue
        t = tolerance_for(column, tol)
        worst = None
        for i, (a, b) in enumerate(zip(got["outputs"][column], values)):
            if not close(a, b, t):
                worst = worst or (i, a, b)
        if worst:
            i, a, b = worst
            problems.append(f"{name}: {column} of sample {i}: {a} vs golden {b} "
                            f"(tolerance {t['relative']} relative + {t['absolute']}: {t['reason']})")
    if got["failures"] != gold["failures"]:
        problems.append(f"{name}: failure reasons differ")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lsi", required=True, help="the lsi executable")
    ap.add_argument("--work", help="directory for the result files (default: a temporary one)")
    ap.add_argument("--update-golden", action="store_true", help="rewrite ci/regression/golden.json")
    args = ap.parse_args()
    tol = json.load(open(TOLERANCES))
    work = args.work or tempfile.mkdtemp(prefix="lsi_regression_")
    os.makedirs(work, exist_ok=True)
    results = {s: run_study(args.lsi, s, work) for s in studies()}
    if args.update_golden:
        version = subprocess.run([args.lsi, "--version"], capture_output=True, text=True).stdout.strip()
        tmp = GOLDEN + ".tmp"
        with open(tmp, "w") as f:
            json.dump({"written_by": version, "studies": results}, f, indent=1)
            f.write("\n")
        os.replace(tmp, GOLDEN)
        print(f"regression: wrote {GOLDEN} ({len(results)} studies)")
        return 0
    gold = json.load(open(GOLDEN))["studies"]
    problems = []
    for s in sorted(set(gold) | set(results)):
        if s not in gold:
            problems.append(f"{s}: no golden values (run with --update-golden deliberately)")
        elif s not in results:
            problems.append(f"{s}: golden values but no study file")
        else:
            compare(s, results[s], gold[s], tol, problems)
    for p in problems:
        print("regression: " + p)
    n = sum(len(r["index"]) for r in results.values())
    print(f"regression: {len(results)} studies, {n} samples: " + ("FAILED" if problems else "all within tolerance"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
