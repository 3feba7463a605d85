#!/usr/bin/python3
"""Runs test_lsi_module.py with pytest on the built module; exits 77 (skipped) where the module is
not built or pytest is not installed.

  run_pytest.py MODULE_DIR LSI SOURCE_DIR WORK_DIR     (MODULE_DIR empty: the module is not built)
"""
import glob
import os
import sys

module_dir, lsi, source, work = sys.argv[1:5]
if not module_dir or not glob.glob(os.path.join(module_dir, "lsi*.so")):
    print("the Python module lsi is not built (LSI_PYTHON, pybind11-dev, python3-dev): skipped")
    sys.exit(77)
try:
    import pytest
except ImportError:
    print("pytest is not installed (Debian: python3-pytest): skipped")
    sys.exit(77)

sys.path.insert(0, os.path.abspath(module_dir))
os.environ["LSI_EXE"] = os.path.abspath(lsi)
os.environ["LSI_SOURCE_DIR"] = os.path.abspath(source)
os.environ["LSI_WORK_DIR"] = os.path.abspath(work)
os.makedirs(work, exist_ok=True)
here = os.path.dirname(os.path.abspath(__file__))
sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "--rootdir", here,
                      os.path.join(here, "test_lsi_module.py")]))
