#!/usr/bin/python3
"""Writes the reference scenes as a variant of the study (used by `ci/main.sh` with options).

usage: ci/reference_variant.py OUT_DIR [--cells N] [--dry] [--smooth-base] [--paper-barrier] SCENE.json ...

Each scene is copied to OUT_DIR with methods.mpm changed as asked, everything else kept:
  --cells N       N cells through the landslide's thickness (cell_size_m = thickness_m / N), N a
                  whole number >= 4 (the MPM's limit: a cell at most a quarter of the thickness)
  --dry           the single-phase landslide with the mixture's density ("phases": "dry")
  --smooth-base   the paper's smooth base under the flow (F1 = 0: landslide.base_friction 0)
  --paper-barrier the closed forms move a free barrier as the paper does ("barrier_model":
                  "paper": the two-body model with base friction, the rigid block under the
                  empirical pulse) instead of the momentum-consistent barrier
"""
import json
import os
import sys


def fail(message):
    print("reference_variant.py: " + message, file=sys.stderr)
    sys.exit(2)


def main(argv):
    args = argv[1:]
    if not args:
        fail("usage: " + __doc__.strip().splitlines()[2].split("usage: ")[1])
    out, args = args[0], args[1:]
    cells, dry, smooth, paper, paths = None, False, False, False, []
    while args:
        a = args.pop(0)
        if a == "--cells":
            text = args.pop(0) if args else ""
            if not text.isdigit() or int(text) < 4:
                fail("--cells must be a whole number of cells through the landslide's thickness, "
                     "at least 4 (the MPM's limit: a cell at most a quarter of it); got '%s'" % text)
            cells = int(text)
        elif a == "--dry":
            dry = True
        elif a == "--smooth-base":
            smooth = True
        elif a == "--paper-barrier":
            paper = True
        elif a.startswith("--"):
            fail("unknown option '%s'" % a)
        else:
            paths.append(a)
    if not paths:
        fail("no scene given")
    os.makedirs(out, exist_ok=True)
    for path in paths:
        with open(path) as f:
            scene = json.load(f)
        if "mpm" not in scene.get("methods", {}) or "landslide" not in scene:
            fail("%s has no landslide with a methods.mpm block" % path)
        mpm = scene["methods"]["mpm"]
        if cells is not None:
            mpm["cell_size_m"] = scene["landslide"]["thickness_m"] / cells
        if dry:
            mpm["phases"] = "dry"
            for key in ("drag", "pore_pressure", "pore_pressure_output"):
                mpm.pop(key, None)
        if smooth:
            scene["landslide"]["base_friction"] = 0
        if paper:
            for method in ("empirical", "analytical"):
                if method in scene["methods"]:
                    scene["methods"][method]["barrier_model"] = "paper"
        with open(os.path.join(out, os.path.basename(path)), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
