#!/usr/bin/env python3
"""Render one sonar image of a scene with the installed `sonarsim` module and save it.

    python3 examples/python_render.py [--scene FILE] [--out DIR] [--set KEY=VALUE ...]

Writes DIR/level_db.npy (L_EN in dB, range bins x beams) and DIR/elevation_deg.npy (the ground truth's
elevation per pixel), and prints the image's size, its echoing fraction and its strongest echo. Works from any
directory once `pip install .` has installed the module (see docs/datasets.md, "Python").
"""
import argparse
import json
import pathlib
import sys

import numpy as np
import sonarsim


def parse_set(items):
    """KEY=VALUE strings -> {key: value}, each value read as JSON when it parses (numbers, lists), else a string."""
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"--set {item}: expected KEY=VALUE")
        try:
            out[key] = json.loads(value)
        except json.JSONDecodeError:
            out[key] = value
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", help="scene file (default: the built-in scene)")
    ap.add_argument("--out", default="sonarsim_example", help="output directory")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a parameter, as `sonarsim --set`")
    args = ap.parse_args()

    try:
        frame = sonarsim.render(args.scene, set=parse_set(args.set), ground_truth=True)
    except sonarsim.InputError as e:  # bad input: one line naming the file and key, exit status 2
        print(f"error: {e}", file=sys.stderr)
        sys.exit(2)
    level = np.asarray(frame.level_db)
    echo = np.isfinite(level)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    np.save(out / "level_db.npy", level)
    np.save(out / "elevation_deg.npy", frame.ground_truth["elevation_deg"])
    bins, beams = level.shape
    strongest = float(level[echo].max()) if echo.any() else float("-inf")
    print(f"{bins} range bins x {beams} beams, {echo.mean():.1%} echoing, strongest {strongest:.1f} dB")
    print(f"wrote {out / 'level_db.npy'} and {out / 'elevation_deg.npy'}")


if __name__ == "__main__":
    main()
