#!/usr/bin/env python3
"""Is the sampler's error estimate honest at the tolerances you use? Estimate against measured error.

    bench/tolerance_sweep.py SCENE.json [SCENE.json ...] [--pairs 0.01:0.1,0.03:0.3] [--set KEY=VALUE ...]
                             [--reference 2187x9] [--module build/python]

For each scene: a dense reference (placement grid, spread, ELEVATIONxAZIMUTH rays per beam, 2187 x 9 unless
--reference says otherwise), then the scene's default sampling at each tolerance pair (tolerance_rel_l1 :
tolerance_db). Per pair it prints the rays, the measured rel L1 and median |dB| against the reference, the
sampler's estimates of both (metadata `sampling_error_estimate`), and their ratios estimate / measured: an
honest estimate is at or above 1. The bench scenes `bench/run.sh` writes are in build/bench/scenes/.
bench/NOTEBOOK.md ("The estimate at loose tolerances") shows its numbers for the bench scenes.
"""
import argparse
import json
import pathlib
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
DEFAULT_PAIRS = "0.01:0.1,0.01:0.3,0.03:0.3,0.03:0.5,0.1:1,0.005:0.05"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes", nargs="+", help="scene files")
    p.add_argument("--pairs", default=DEFAULT_PAIRS, help="tolerance_rel_l1:tolerance_db, comma separated")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="a scene key for every image (JSON value), e.g. sampling.bounces=0")
    p.add_argument("--reference", default="2187x9", help="ELEVATIONxAZIMUTH rays per beam of the reference")
    p.add_argument("--module", default=str(ROOT / "build" / "python"), help="directory of the sonarsim module")
    return p.parse_args()


def fail(msg):
    print(f"tolerance_sweep: {msg}", file=sys.stderr)
    sys.exit(2)


def main():
    a = parse_args()
    try:
        pairs = [tuple(float(v) for v in t.split(":")) for t in a.pairs.split(",")]
        if any(len(t) != 2 for t in pairs):
            raise ValueError
    except ValueError:
        fail(f"--pairs: '{a.pairs}' is not a list of REL:DB pairs (e.g. 0.01:0.1,0.03:0.3)")
    try:
        ref_e, ref_a = (int(v) for v in a.reference.lower().split("x"))
    except ValueError:
        fail(f"--reference: '{a.reference}' is not ELEVATIONxAZIMUTH (e.g. 2187x9)")
    sets = []
    for kv in a.set:
        if "=" not in kv:
            fail(f"--set: '{kv}' is not KEY=VALUE")
        k, v = kv.split("=", 1)
        try:
            v = json.loads(v)
        except json.JSONDecodeError:
            pass  # a bare string
        sets.append((k, v))
    sys.path.insert(0, a.module)
    try:
        import numpy as np
        import sonarsim
    except ImportError as e:
        fail(f"{e} (build the module: cmake --build build --target sonarsim_python, or pass --module)")

    def linear(db):
        return np.where(np.isfinite(db), 10 ** (db.astype(np.float64) / 10), 0.0)

    def errors(ref_db, img_db):
        r, x = linear(ref_db), linear(img_db)
        both = np.isfinite(ref_db) & np.isfinite(img_db)
        median = float(np.median(np.abs(ref_db[both] - img_db[both]))) if both.any() else 0.0
        return float(np.abs(r - x).sum() / r.sum()), median

    print("scene | rel L1 tol | dB tol | rays | measured rel L1 | estimate | ratio | measured median dB | "
          "estimate | ratio")
    for path in a.scenes:
        try:
            sim = sonarsim.Simulator(path)
            for k, v in sets:
                sim.set(k, v)
        except sonarsim.InputError as e:
            fail(f"{path}: {e}")
        name = pathlib.Path(path).stem
        t0 = time.time()
        print(f"{name}: reference {ref_e} x {ref_a} ...", file=sys.stderr, flush=True)
        sim.set("sampling.placement", "grid")
        sim.set("sampling.elevation_rays", ref_e)
        sim.set("sampling.azimuth_rays", ref_a)
        sim.set("sampling.max_rays", 50_000_000)
        ref = np.array(sim.render().level_db)
        # Back to the scene's own sampling: a fresh simulator, so that nothing of the reference's stays.
        sim = sonarsim.Simulator(path)
        for k, v in sets:
            sim.set(k, v)
        for i, (tol_rel, tol_db) in enumerate(pairs):
            print(f"{name}: {i + 1}/{len(pairs)} ({time.time() - t0:.0f} s)", file=sys.stderr, flush=True)
            try:
                sim.set("sampling.tolerance_rel_l1", tol_rel)
                sim.set("sampling.tolerance_db", tol_db)
            except sonarsim.InputError as e:
                fail(f"--pairs: {e}")
            f = sim.render()
            img = np.array(f.level_db)
            est = f.metadata.get("sampling_error_estimate", {})
            rel, med = errors(ref, img)
            e_rel, e_med = est.get("rel_l1", float("nan")), est.get("median_abs_db", float("nan"))
            print(f"{name} | {tol_rel:g} | {tol_db:g} | {f.metadata['rays_traced']} | {100 * rel:.3f} % | "
                  f"{100 * e_rel:.3f} % | {e_rel / rel if rel > 0 else float('inf'):.2f} | {med:.4f} | "
                  f"{e_med:.4f} | {e_med / med if med > 0 else float('inf'):.2f}", flush=True)


if __name__ == "__main__":
    main()
