"""Shared fixtures: the sonarsim executable, the source tree and a scratch directory per test."""
import json
import os
import pathlib
import shutil

import pytest


SOURCE = pathlib.Path(os.environ.get("SONARSIM_SOURCE", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture
def sonarsim_exe():
    # The tree's build/ by default, so that pytest runs from any directory.
    return os.environ.get("SONARSIM_EXE", str(SOURCE / "build" / "sonarsim"))


@pytest.fixture
def source_dir():
    return SOURCE


@pytest.fixture
def scratch(request):
    root = pathlib.Path(os.environ.get("SONARSIM_TEST_OUT", "/tmp/sonarsim_pytest"))
    d = root / request.node.name
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    return d


# The built-in scene made small and fast: the same keys as --set on the command line.
SMALL = {"sonar.beams": 48, "sonar.range_bins": 96, "sampling.scheme": "spread", "sampling.elevation_rays": 41}


def small_scene_dict():
    """The small scene as a scene-file dict: the built-in scene's floor and prism (paper Fig. 9)."""
    return {"sonar": {"beams": 48, "range_bins": 96}, "sampling": {"scheme": "spread", "elevation_rays": 41},
            "seafloor": {"height_m": 0}, "objects": [{"box": [0.07, 0.12, 0.22], "position": [1.5, 1.5, 0.11]}]}


def write_small_scene(directory, sonar=None, sampling=None, name="scene.json"):
    """The small scene with SONAR and SAMPLING keys replaced, written to DIRECTORY/NAME; returns its path."""
    scene = small_scene_dict()
    scene["sonar"].update(sonar or {})
    scene["sampling"].update(sampling or {})
    path = directory / name
    path.write_text(json.dumps(scene))
    return path
