"""examples/dask_batch.py on a local cluster of 2 worker processes writes the frames `sonarsim batch` writes."""
import json
import os
import subprocess
import sys

import pytest

from conftest import write_small_scene


def frame_files(d):
    return sorted(p.name for p in (d / "frames").iterdir() if ".tmp-" not in p.name)


def test_dask_frames_equal_a_single_process_batch(sonarsim_exe, source_dir, scratch):
    pytest.importorskip("distributed")
    scene = write_small_scene(scratch)
    traj = scratch / "t.csv"
    rows = ["t,x,y,z,roll_deg,pitch_deg,yaw_deg"]
    rows += [f"{0.1 * k:g},{0.2 + 0.05 * k:g},2.3,0.9,0,30,{-40 + 2 * k}" for k in range(6)]
    traj.write_text("\n".join(rows) + "\n")

    single, dist = scratch / "single", scratch / "dask"
    subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), "--trajectory", str(traj), "--out", str(single)],
                   check=True, stdout=subprocess.DEVNULL)
    env = dict(os.environ)
    r = subprocess.run([sys.executable, str(source_dir / "examples/dask_batch.py"), "--scene", str(scene),
                        "--trajectory", str(traj), "--out", str(dist), "--workers", "2", "--chunk", "2"],
                       env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "index.csv lists 6 of 6 frames" in r.stdout

    names = frame_files(single)
    assert len(names) == 6 * 4
    assert frame_files(dist) == names
    for name in names:
        a, b = (single / "frames" / name).read_bytes(), (dist / "frames" / name).read_bytes()
        if name.endswith(".json"):  # equal apart from the measured timings
            ja, jb = json.loads(a), json.loads(b)
            ja.pop("time_ms"), jb.pop("time_ms")
            assert ja == jb, name
        else:
            assert a == b, name
    import numpy as np

    assert np.isfinite(np.load(dist / "frames" / "000003.npy")).sum() > 100  # frames that show something
    lines = (dist / "index.csv").read_text().splitlines()
    assert len(lines) == 7
    assert [l.split(",")[0] for l in lines[1:]] == [str(k) for k in range(6)]


def test_dask_example_bad_trajectory_is_one_line_exit_2(source_dir, scratch):
    traj = scratch / "bad.csv"
    traj.write_text("t,x,y,z,roll_deg,pitch_deg,yaw_deg\n0,1,2,x,0,0,0\n")
    r = subprocess.run([sys.executable, str(source_dir / "examples/dask_batch.py"), "--trajectory", str(traj),
                        "--out", str(scratch / "o")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert r.stderr.strip() == f"dask_batch: error: {traj}:2: z: \"x\" is not a finite number"
