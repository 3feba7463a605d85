#!/usr/bin/python3
"""Compare two Google Benchmark JSON files (--benchmark_out=F --benchmark_out_format=json).

    compare_json.py [--metric M] OLD.json NEW.json
    compare_json.py merge OUT.json IN.json [IN.json ...]

For every benchmark in both files: the median over its repetitions on each side (from the
per-repetition entries; from the `median` aggregate when the file holds aggregates only), the
number of repetitions, the spread (min-max) and the ratio NEW / OLD of the medians. The metric is
the real time by default (shown in OLD's time unit; ratio < 1: NEW is faster); --metric cpu_time,
items_per_second, bytes_per_second or any user counter (e.g. solver_pups) compares that instead
(for a rate, ratio > 1: NEW is faster). Benchmarks present on one side only are listed at the end.

`merge` joins the runs of one binary (e.g. rounds alternated with another binary on a noisy
machine) into one file that this script and Google Benchmark's tools/compare.py read as
repetitions: the context of the first file, the benchmark entries of all.

Debian's /usr/bin/python3, standard library only. bench/compare_revisions.sh calls it.
"""
import argparse
import json
import signal
import statistics
import sys

TIME_UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
AGGREGATES = ("mean", "median", "stddev", "cv")


def load(path):
    with open(path) as f:
        return json.load(f)


def collect(doc, metric):
    """name -> {"values": [...], "unit": time unit or None, "from": "repetitions"|"median"}"""
    per_rep, medians, order, errors = {}, {}, [], {}
    for b in doc.get("benchmarks", []):
        name = b.get("run_name") or b.get("name")
        if name not in order:
            order.append(name)
        if b.get("error_occurred"):
            errors[name] = b.get("error_message", "error")
            continue
        if metric not in b:
            continue
        value = float(b[metric])
        unit = b.get("time_unit") if metric in ("real_time", "cpu_time") else None
        if unit:
            value *= TIME_UNITS[unit]   # seconds
        run_type = b.get("run_type", "iteration")
        if run_type == "iteration":
            per_rep.setdefault(name, {"values": [], "unit": unit})["values"].append(value)
        elif b.get("aggregate_name") == "median":
            medians[name] = {"values": [value], "unit": unit}
    out = {}
    for name in order:
        if name in per_rep:
            out[name] = dict(per_rep[name], source="repetitions")
        elif name in medians:
            out[name] = dict(medians[name], source="median aggregate")
        elif name in errors:
            out[name] = {"values": [], "unit": None, "source": "error: " + errors[name]}
    return out


def fmt(value, unit):
    if value is None:
        return "-"
    if unit:
        return "%.4g %s" % (value / TIME_UNITS[unit], unit)
    return "%.4g" % value


def compare(old_path, new_path, metric):
    old_doc, new_doc = load(old_path), load(new_path)
    old, new = collect(old_doc, metric), collect(new_doc, metric)
    for label, doc, path in (("old", old_doc, old_path), ("new", new_doc, new_path)):
        ctx = doc.get("context", {})
        print("%s: %s (git %s, %s, load %s)" % (
            label, path, ctx.get("git_revision", "?"), ctx.get("date", "?"),
            ",".join("%.2f" % x for x in ctx.get("load_avg", [])) or "?"))
    print("metric: %s; median over the repetitions (n), [min-max]; ratio = new / old%s\n" % (
        metric, " (< 1: new is faster)" if metric in ("real_time", "cpu_time") else ""))
    names = [n for n in old if n in new]
    rows = []
    for name in names:
        a, b = old[name], new[name]
        if not a["values"] or not b["values"]:
            rows.append((name, a["source"], b["source"], ""))
            continue
        unit = a["unit"] or b["unit"]
        ma, mb = statistics.median(a["values"]), statistics.median(b["values"])

        def cell(v, m):
            s = "%s (%d)" % (fmt(m, unit), len(v))
            if len(v) > 1:
                s += " [%s-%s]" % (fmt(min(v), unit).split()[0], fmt(max(v), unit).split()[0])
            return s

        ratio = mb / ma if ma != 0 else float("nan")
        rows.append((name, cell(a["values"], ma), cell(b["values"], mb), "%.3f" % ratio))
    header = ("benchmark", "old", "new", "ratio")
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(4)]
    for r in [header] + rows:
        print("%-*s  %*s  %*s  %*s" % (widths[0], r[0], widths[1], r[1], widths[2], r[2],
                                       widths[3], r[3]))
    only_old = [n for n in old if n not in new]
    only_new = [n for n in new if n not in old]
    if only_old:
        print("\nonly in old: " + ", ".join(only_old))
    if only_new:
        print("\nonly in new: " + ", ".join(only_new))
    if not names:
        print("(no benchmark in both files with metric %s)" % metric)
        return 1
    return 0


def merge(out_path, in_paths):
    docs = [load(p) for p in in_paths]
    merged = {"context": docs[0].get("context", {}), "benchmarks": []}
    merged["context"]["merged_from"] = list(in_paths)
    for d in docs:
        merged["benchmarks"].extend(d.get("benchmarks", []))
    with open(out_path, "w") as f:
        json.dump(merged, f, indent=1)
    return 0


def main(argv):
    if argv and argv[0] == "merge":
        if len(argv) < 3:
            print("usage: compare_json.py merge OUT.json IN.json [IN.json ...]", file=sys.stderr)
            return 2
        return merge(argv[1], argv[2:])
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--metric", default="real_time",
                    help="real_time (default), cpu_time, items_per_second, bytes_per_second "
                         "or a counter name")
    a = ap.parse_args(argv)
    return compare(a.old, a.new, a.metric)


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)   # `| head` ends quietly
    sys.exit(main(sys.argv[1:]))
