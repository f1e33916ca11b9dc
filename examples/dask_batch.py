#!/usr/bin/env python3
"""Render a trajectory across a Dask cluster through the sonarsim Python module.

Writes the same dataset layout as `sonarsim batch` (DIR/scene.json, DIR/trajectory.csv, DIR/frames/NNNNNN.*,
DIR/index.csv): the frames are split into chunks, each chunk is one task that renders its frames with one
Simulator (the geometry built once per task), and the index is rebuilt once at the end.

    PYTHONPATH=build/python /usr/bin/python3 examples/dask_batch.py --scene S --trajectory T.csv --out DIR \\
        --workers 4 [--scheduler tcp://host:8786] [--resume] [--ground-truth]

(or --circle / --line instead of --trajectory, as `sonarsim batch` takes them).

Without --scheduler it starts a distributed.LocalCluster with --workers worker processes (one thread each:
a render already uses every core of its worker through TBB). The workers must see DIR (a shared file system
on a real cluster) and import sonarsim (the same PYTHONPATH).
"""
import argparse
import sys
import time


def render_chunk(out, frames, resume, ground_truth):
    import sonarsim  # in the worker process

    return sonarsim.render_frames(out, frames, resume=resume, ground_truth=ground_truth)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", help="scene file (default: the built-in scene)")
    p.add_argument("--trajectory", default="", help="CSV: t,x,y,z,roll_deg,pitch_deg,yaw_deg")
    p.add_argument("--circle", default="", help="cx,cy,cz,radius_m,height_m,frames (as sonarsim batch)")
    p.add_argument("--line", default="", help="x0,y0,z0,x1,y1,z1,frames (as sonarsim batch)")
    p.add_argument("--rate", type=float, default=10.0, help="frames per second of --circle and --line")
    p.add_argument("--out", required=True, help="dataset directory")
    p.add_argument("--workers", type=int, default=2, help="worker processes of the local cluster")
    p.add_argument("--scheduler", help="address of a running Dask scheduler instead of a local cluster")
    p.add_argument("--chunk", type=int, default=0, help="frames per task (default: about 4 tasks per worker)")
    p.add_argument("--resume", action="store_true", help="skip frames that are already complete")
    p.add_argument("--ground-truth", action="store_true",
                   help="also write each frame's NNNNNN_gt_<name>.npy, as sonarsim batch --ground-truth")
    a = p.parse_args(argv)

    import sonarsim
    from distributed import Client, LocalCluster, as_completed

    try:
        n = sonarsim.prepare_dataset(a.out, a.scene, trajectory=a.trajectory, circle=a.circle, line=a.line,
                                     rate_hz=a.rate)
    except ValueError as e:  # bad input: one line, exit status 2, as the command line tool
        print(f"dask_batch: error: {e}", file=sys.stderr)
        return 2
    cluster = None
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        workers = max(1, len(client.scheduler_info()["workers"]))
        chunk = a.chunk or max(1, -(-n // (4 * workers)))
        chunks = [list(range(i, min(n, i + chunk))) for i in range(0, n, chunk)]
        t0 = time.monotonic()
        futures = [client.submit(render_chunk, a.out, c, a.resume, a.ground_truth, pure=False) for c in chunks]
        done = rendered = 0
        for f in as_completed(futures):
            rendered += f.result()
            done += 1
            if sys.stderr.isatty():
                rate = rendered / max(time.monotonic() - t0, 1e-9)
                print(f"\r\033[K{done}/{len(chunks)} tasks, {rendered} frames, {rate:.2f} frames/s",
                      end="", file=sys.stderr, flush=True)
        if sys.stderr.isatty():
            print("\r\033[K", end="", file=sys.stderr)
        listed = sonarsim.write_index(a.out)
        dt = time.monotonic() - t0
        print(f"rendered {rendered} frames on {workers} workers in {dt:.1f} s ({rendered / max(dt, 1e-9):.2f} "
              f"frames/s) into {a.out}; index.csv lists {listed} of {n} frames")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
