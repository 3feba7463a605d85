#!/usr/bin/env bash
# Where the threads of host work run (tests/app/thread_binding.cpp) under an OpenMP binding, with
# and without lsi's restart for its wait defaults: with OMP_PROC_BIND=spread on 2 threads each
# thread has its own CPU (a restart that kept the first thread's binding put every thread on one
# CPU, and threads started with std::thread shared the first thread's); without a binding every
# thread keeps every CPU the test may use. Skipped (77) with fewer than 2 CPUs.
# Usage: thread_binding_test.sh THREAD_BINDING_EXE
set -euo pipefail
exe=$1
# The CPUs this test may run on, as a list "0 1 ..." (Cpus_allowed_list: "0-3,6").
mine=""
IFS=, read -ra ranges <<<"$(sed -n 's/^Cpus_allowed_list:[[:space:]]*//p' /proc/self/status)"
for r in "${ranges[@]}"; do
  for ((c = ${r%-*}; c <= ${r#*-}; ++c)); do mine+="${mine:+ }$c"; done
done
cpus=$(wc -w <<<"$mine")
if [ "$cpus" -lt 2 ]; then
  echo "skipped: $cpus CPU(s) for this test, the bindings need 2"
  exit 77
fi
status=0
# The harness in an environment of no OpenMP settings but ENV...: prints its lines.
clean=(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u OMP_PLACES -u OMP_PROC_BIND -u OMP_DYNAMIC
  -u OMP_THREAD_LIMIT -u OMP_MAX_ACTIVE_LEVELS -u OMP_NESTED -u GOMP_CPU_AFFINITY -u KMP_AFFINITY
  -u OMP_NUM_THREADS)
run() { "${clean[@]}" OMP_NUM_THREADS=2 "$@" "$exe"; }
for wait in restart passive; do
  extra=()
  [ "$wait" = passive ] && extra=(OMP_WAIT_POLICY=passive)
  out=$(run "${extra[@]}" OMP_PROC_BIND=spread)
  a=$(sed -n 's/^0: *//p' <<<"$out")
  b=$(sed -n 's/^1: *//p' <<<"$out")
  if [ -z "$a" ] || [ -z "$b" ] || [ "$a" = "$b" ] || [[ "$a" == *" "* ]] || [[ "$b" == *" "* ]]; then
    echo "FAIL ($wait, OMP_PROC_BIND=spread): threads 0 and 1 should each have one CPU of" \
      "their own, have '$a' and '$b'" >&2
    status=1
  else
    echo "ok ($wait, OMP_PROC_BIND=spread): thread 0 on CPU $a, thread 1 on CPU $b"
  fi
  out=$(run "${extra[@]}" OMP_PROC_BIND=false)
  while IFS= read -r line; do
    got=${line#*: }
    if [ "$got" != "$mine" ]; then
      echo "FAIL ($wait, OMP_PROC_BIND=false): thread ${line%%:*} may run on '$got'," \
        "the test on '$mine'" >&2
      status=1
    fi
  done <<<"$out"
  [ "$status" -eq 0 ] && echo "ok ($wait, OMP_PROC_BIND=false): every thread on CPUs $mine"
done
# Places of one CPU and no OMP_NUM_THREADS: the restarted runtime keeps the thread count of the
# CPUs the program was started with (one thread a CPU), not one of the places' CPU.
first=${mine%% *}
lines=$("${clean[@]}" OMP_PROC_BIND=true "OMP_PLACES={$first}" "$exe" | wc -l)
if [ "$lines" -ne "$cpus" ]; then
  echo "FAIL (restart, OMP_PLACES={$first}): $lines thread(s), the test's $cpus CPUs give $cpus" >&2
  status=1
else
  echo "ok (restart, OMP_PLACES={$first}): $lines threads"
fi
exit "$status"
