#!/usr/bin/env bash
# `lsi-mpi` end to end (docs/guide/mpi.md): a 20000-sample study on 2 MPI ranks gives the file an
# unsharded `lsi sweep` writes (wall times aside); `--resume` reaches every rank; a bad study exits
# 2 with one line; a failure on one rank stops the job with exit 2 on every rank.
# Usage: mpi_sweep_test.sh MPIEXEC LSI LSI_MPI SOURCE_DIR WORK_DIR
set -euo pipefail
mpiexec="$1" lsi="$2" lsi_mpi="$3" src="$4" work="$5"
python=/usr/bin/python3   # Debian's, with python3-h5py (ci/setup.sh)
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# 2 ranks of 1 thread each on the 2-core machine; -q: no mpirun banner when a rank exits non-zero.
# --oversubscribe: a machine with fewer than 2 cores (slots) would refuse -np 2 otherwise.
mpi=("$mpiexec" -q --oversubscribe -np 2 -x OMP_NUM_THREADS=1 -x OMP_WAIT_POLICY=passive
     -x OMP_PROC_BIND=false)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
export OMP_NUM_THREADS=2 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }
# Under the sanitizers (ci/sanitize.sh): Open MPI keeps allocations of its own and of its plugins
# until exit, which ci/sanitize/lsan.supp suppresses by library name; that needs whole stacks (the
# fast unwinder stops at the first Open MPI frame, compiled without frame pointers).
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"; fi

# The study: scenes/studies/L1-B1-monte-carlo.json with 20000 samples in chunks of 2048 (10
# chunks: shard 0 has 10240 samples, shard 1 has 9760) and the scene by absolute path.
"$python" - "$src" <<'EOF'
import json, sys
src = sys.argv[1]
s = json.load(open(f"{src}/scenes/studies/L1-B1-monte-carlo.json"))
s.update(name="L1-B1-mpi-test", scene=f"{src}/scenes/former-reference/L1-B1.json", samples=20000,
         chunk_samples=2048)
json.dump(s, open("study.json", "w"), indent=2)
s["samples"] = -5
json.dump(s, open("bad.json", "w"), indent=2)
EOF

# Compares two result files: every /samples and /failures dataset but wall_time (NaN = NaN) with
# its attributes, and the /statistics JSON.
compare() {
  "$python" - "$1" "$2" <<'EOF'
import json, sys
import h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
def datasets(f):
    out = {}
    for group in ("samples", "failures"):
        if group in f:
            f[group].visititems(lambda n, o: out.__setitem__(f"/{group}/{n}", o)
                                if isinstance(o, h5py.Dataset) else None)
    return out
da, db = datasets(a), datasets(b)
assert da.keys() == db.keys(), f"datasets differ: {sorted(da)} vs {sorted(db)}"
compared = 0
for name in sorted(da):
    if name.endswith("/wall_time"):
        continue
    x, y = da[name][()], db[name][()]
    assert x.shape == y.shape, f"{name}: shape {x.shape} vs {y.shape}"
    same = np.array_equal(x, y, equal_nan=True) if x.dtype.kind == "f" else np.array_equal(x, y)
    assert same, f"{name}: values differ"
    xa, ya = da[name].attrs, db[name].attrs  # values may be arrays (the inputs' units)
    assert xa.keys() == ya.keys() and all(
        np.array_equal(np.asarray(xa[k]), np.asarray(ya[k])) for k in xa), f"{name}: attributes differ"
    compared += 1
sa, sb = (json.loads(f["statistics"].attrs["json"]) for f in (a, b))
assert sa == sb, "statistics differ"
assert a["samples/index"].shape[0] == 20000
for key in ("fingerprint", "complete", "planned_samples", "shard"):
    assert a.attrs[key] == b.attrs[key], f"attribute {key}: {a.attrs[key]} vs {b.attrs[key]}"
print(f"same: {compared} datasets and the statistics")
EOF
}

# 1. The MPI run and the single run agree; the shard files are gone.
"${mpi[@]}" "$lsi_mpi" study.json --out mpi.h5 > mpi.log 2>&1 || { cat mpi.log; fail "lsi-mpi"; }
cat mpi.log
grep -q '^complete: 20000 samples in mpi.h5 (20000 run now on 2 ranks' mpi.log || fail "summary line"
grep -q 'P(empirical/peak_force > 300000)' mpi.log || fail "statistics table"
ls mpi.h5.rank* > /dev/null 2>&1 && fail "shard files left: $(ls mpi.h5.rank*)"
"$lsi" sweep study.json --out single.h5 > single.log 2>&1 || { cat single.log; fail "lsi sweep"; }
compare mpi.h5 single.h5

# 2. --resume reaches every rank: with shard 1 already done (as a killed job could leave it), only
# shard 0's 10240 samples are run, and the result is the same file.
"$lsi" sweep study.json --shard 1/2 --out resumed.h5.rank1-of-2.h5 > /dev/null
"${mpi[@]}" "$lsi_mpi" study.json --out resumed.h5 --resume > resumed.log 2>&1 ||
  { cat resumed.log; fail "lsi-mpi --resume"; }
grep -q '^complete: 20000 samples in resumed.h5 (10240 run now on 2 ranks' resumed.log ||
  { cat resumed.log; fail "resume: expected 10240 samples run now"; }
compare resumed.h5 single.h5

# 3. A bad study: exit 2 and one line (the same error on both ranks is printed once).
set +e
"${mpi[@]}" "$lsi_mpi" bad.json --out bad.h5 > bad.log 2>&1
code=$?
set -e
cat bad.log
[ "$code" -eq 2 ] || fail "bad study: exit $code, expected 2"
[ "$(wc -l < bad.log)" -eq 1 ] || fail "bad study: expected one line"
grep -q '^lsi-mpi: error: bad.json: samples = -5' bad.log || fail "bad study: message"

# 4. A failure on one rank only (a parts directory left without --resume): exit 2, the rank named.
mkdir -p one.h5.rank1-of-2.h5.parts
set +e
"${mpi[@]}" "$lsi_mpi" study.json --out one.h5 > one.log 2>&1
code=$?
set -e
cat one.log
[ "$code" -eq 2 ] || fail "one rank failing: exit $code, expected 2"
grep -q '^lsi-mpi: rank 1: error: one.h5.rank1-of-2.h5.parts: an earlier run' one.log ||
  fail "one rank failing: message"
[ -f one.h5 ] && fail "one rank failing: merged anyway"
echo "PASS"
