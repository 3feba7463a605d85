"""The checks of a test script of tests/tools: check(ok, what) counts a check and prints the ones
that fail; finish() prints the counts and exits, non-zero where any check failed."""
import sys

_failures = []
_checks = 0


def check(ok, what):
    global _checks
    _checks += 1
    if not ok:
        _failures.append(what)
        print("FAIL:", what)


def finish():
    print(f"{_checks - len(_failures)} passed, {len(_failures)} failed")
    sys.exit(1 if _failures else 0)
