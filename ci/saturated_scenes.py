#!/usr/bin/python3
"""Writes the reference scenes with a saturated MPM landslide (used by `ci/main.sh --saturated`).

usage: ci/saturated_scenes.py OUT_DIR CELLS SCENE.json ...

Each scene is copied to OUT_DIR with methods.mpm switched to the two-phase landslide
("phases": "saturated", "drag": "semi-implicit") at CELLS cells through the landslide's
thickness (cell_size_m = thickness_m / CELLS); everything else is kept as shipped. CELLS must be
a whole number >= 4 (the MPM's limit: a cell at most a quarter of the thickness).
"""
import json
import os
import sys


def main(argv):
    if len(argv) < 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out, cells_text, paths = argv[1], argv[2], argv[3:]
    if not cells_text.isdigit() or int(cells_text) < 4:
        print("saturated_scenes.py: CELLS must be a whole number of cells through the landslide's "
              "thickness, at least 4 (the MPM's limit: a cell at most a quarter of it); got '%s'"
              % cells_text, file=sys.stderr)
        return 2
    cells = int(cells_text)
    os.makedirs(out, exist_ok=True)
    for path in paths:
        with open(path) as f:
            scene = json.load(f)
        if "mpm" not in scene.get("methods", {}) or "landslide" not in scene:
            print("saturated_scenes.py: %s has no landslide with a methods.mpm block" % path,
                  file=sys.stderr)
            return 2
        mpm = scene["methods"]["mpm"]
        mpm["cell_size_m"] = scene["landslide"]["thickness_m"] / cells
        mpm["phases"] = "saturated"
        mpm["drag"] = "semi-implicit"
        with open(os.path.join(out, os.path.basename(path)), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
