"""`pip install .` into a fresh virtual environment with Debian's packages only and no index, then the example
script run from another directory: the module imports from the environment, not from build/python."""
import os
import pathlib
import subprocess
import sys

import numpy as np


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert r.returncode == 0, f"{cmd} failed ({r.returncode}):\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


def test_pip_install_into_a_venv_and_run_the_example(source_dir, scratch):
    venv = scratch / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)])
    py = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["SONARSIM_PIP_BUILD_DIR"] = str(scratch / "cmake")  # a fresh CMake build, as a user's would be
    run([str(py), "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q", str(source_dir)], env=env)

    elsewhere = scratch / "elsewhere"
    elsewhere.mkdir()
    where = run([str(py), "-c", "import sonarsim; print(sonarsim.__file__)"], cwd=elsewhere, env=env).stdout
    assert pathlib.Path(where.strip()).is_relative_to(venv), where

    out = elsewhere / "example_out"
    r = run([str(py), str(source_dir / "examples" / "python_render.py"), "--out", str(out),
             "--set", "sonar.beams=48", "--set", "sonar.range_bins=96", "--set", "sampling.scheme=spread"],
            cwd=elsewhere, env=env)
    level = np.load(out / "level_db.npy")
    elevation = np.load(out / "elevation_deg.npy")
    assert level.shape == (96, 48) and elevation.shape == (96, 48)
    echo = np.isfinite(level)
    assert 0.02 < echo.mean() < 0.9, echo.mean()  # the built-in scene's floor and prism, not an empty image
    assert f"{echo.mean():.1%} echoing" in r.stdout
    # Every echoing pixel has a ground-truth elevation inside the sonar's vertical field of view.
    assert np.all(np.abs(elevation[echo]) <= 7.0 + 1e-3)

    # Bad input reaches Python as one clear error naming the key.
    bad = subprocess.run([str(py), str(source_dir / "examples" / "python_render.py"), "--out", str(out),
                          "--set", "sonar.beams=-3"], cwd=elsewhere, env=env, capture_output=True, text=True)
    assert bad.returncode == 2 and "sonar.beams" in bad.stderr and "Traceback" not in bad.stderr, bad.stderr
