"""The sonarsim Python module against `sonarsim render`'s files."""
import json
import subprocess
import threading
import time

import numpy as np
import pytest

import sonarsim
from conftest import SMALL, small_scene_dict


def read_npy(path):
    return np.load(path)


def test_level_db_equals_render_npy(sonarsim_exe, scratch):
    sets = [f"--set={k}={v}" for k, v in SMALL.items()]
    subprocess.run([sonarsim_exe, "render", *sets, "--out", str(scratch / "img")], check=True,
                   stdout=subprocess.DEVNULL)
    frame = sonarsim.render(set=SMALL)
    level = frame.level_db
    assert level.dtype == np.float32
    assert level.shape == (96, 48)
    expected = read_npy(scratch / "img.npy")
    assert np.array_equal(level, expected)  # -inf where nothing echoes, in both
    assert np.isfinite(level).sum() > 100
    meta = json.loads((scratch / "img.json").read_text())
    assert frame.metadata["range_bin_edges_m"] == meta["range_bin_edges_m"]
    assert frame.metadata["sonar"] == meta["sonar"]
    sector = frame.sector
    assert sector.dtype == np.uint8 and sector.ndim == 3 and sector.shape[2] == 3
    assert sector.max() > 0
    assert frame.ground_truth == {}  # only when asked for


def test_ground_truth_arrays_match_the_render_files(scratch):
    """render(ground_truth=True) gives the arrays render --ground-truth writes, with the image's shape."""
    frame = sonarsim.render(small_scene_dict(), ground_truth=True)
    gt = frame.ground_truth
    assert sorted(gt) == sorted(["elevation_deg", "elevation_min_deg", "elevation_max_deg", "point_m", "range_m",
                                 "object_id", "incidence_deg", "surfaces", "bounces"])
    level = frame.level_db
    assert gt["point_m"].shape == level.shape + (3,)
    assert gt["object_id"].dtype == np.int32
    echo = np.isfinite(level)
    assert np.array_equal(gt["object_id"] >= 0, echo)  # something echoes exactly where the image has a level
    assert np.all(np.isnan(gt["elevation_deg"][~echo]))
    assert np.all(gt["elevation_min_deg"][echo] <= gt["elevation_deg"][echo] + 1e-4)
    assert set(np.unique(gt["object_id"])) <= {-1, 0, 1}  # nothing, the floor, the prism


def test_arrays_share_the_frame_memory_and_outlive_it():
    sim = sonarsim.Simulator(small_scene_dict())
    frame = sim.render()
    a = frame.level_db
    b = frame.level_db
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]  # no copy
    assert not a.flags.writeable
    del frame
    sim.set_pose([0.3, 2.4, 0.9, 0, 30, -40])
    other = sim.render().level_db
    assert np.isfinite(a).sum() > 100 and np.isfinite(other).sum() > 100
    assert not np.array_equal(a, other)  # the first frame's memory is still alive and its own
    assert a.shape == (96, 48)


def test_set_and_pose_change_the_image():
    sim = sonarsim.Simulator(small_scene_dict())
    sim.set("sonar.beams", 64)
    assert sim.render().level_db.shape == (96, 64)
    sim.set("display.lo_db", 70)
    assert sim.scene["display"]["lo_db"] == 70
    sim.set_pose([0.34, 2.42, 0.90, 0, 29.79, -38.96])
    assert sim.scene["sonar"]["orientation_deg"] == [0, 29.79, -38.96]


def test_scene_file_path(source_dir):
    sim = sonarsim.Simulator(str(source_dir / "assets/scenes/fig9_pose2.json"))
    assert sim.scene["sonar"]["beams"] == 128


def test_bad_input_raises_value_error_with_the_one_line_message(source_dir):
    sim = sonarsim.Simulator()
    with pytest.raises(ValueError, match=r"^set: sonar.beams: value 0 is out of range; allowed: an integer in \[1, 4096\]$"):
        sim.set("sonar.beams", 0)
    with pytest.raises(ValueError, match="unknown key"):
        sim.set("sonar.bems", 12)
    with pytest.raises(ValueError, match="<dict>: sonra: unknown key"):
        sonarsim.Simulator({"sonra": {}})
    with pytest.raises(ValueError, match="scene file not found"):
        sonarsim.Simulator("no_such_scene.json")
    with pytest.raises(ValueError, match="expected"):
        sim.set_pose([1, 2, 3])
    assert sim.scene["sonar"]["beams"] == 128  # unchanged by the failed calls


def test_render_releases_the_gil():
    sim = sonarsim.Simulator(small_scene_dict())
    sim.set("sampling.elevation_rays", 40001)  # about a second of rendering
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    t = threading.Thread(target=count)
    t.start()
    t0 = time.monotonic()
    sim.render()
    seconds = time.monotonic() - t0
    done.set()
    t.join()
    assert seconds > 0.05
    assert len(ticks) > 0.2 * seconds / 0.001  # the other thread ran throughout the render


def test_compare_closed_forms_and_files(scratch):
    """compare() on exponential speckle (contrast 1, amplitude contrast sqrt(4/pi - 1)) and on an image against
    itself with a gain; and from a rendered .npy file as `sonarsim compare` reads it."""
    rng = np.random.default_rng(1)
    speckle = (10 * np.log10(rng.exponential(size=(300, 200))) + 60).astype(np.float32)
    r = sonarsim.compare(speckle, speckle + 10)
    assert abs(r["a"]["contrast_intensity"] - 1) < 0.03
    assert abs(r["a"]["contrast_amplitude"] - np.sqrt(4 / np.pi - 1)) < 0.015
    assert r["pair"]["aligned"] and abs(r["pair"]["correlation"] - 1) < 1e-6
    assert r["pair"]["histogram_distance"] < 1e-6
    frame = sonarsim.render(None, set=SMALL)
    np.save(scratch / "a.npy", np.asarray(frame.level_db))
    r = sonarsim.compare(str(scratch / "a.npy"), np.asarray(frame.level_db))
    assert r["a"]["floor_fraction"] == r["b"]["floor_fraction"] > 0
    with pytest.raises(ValueError, match="unknown image file"):
        sonarsim.compare(str(scratch / "a.txt"), speckle)


def test_compare_reads_a_gray_fan_png(sonarsim_exe, scratch):
    """A fan PNG that render wrote reads back (geometry from its metadata) onto the .npy's grid: the same
    image against itself correlates exactly, and against the levels it shows (clipped to its display range)
    closely; a geometry given by hand must fit the image."""
    sets = [a for k, v in {**SMALL, "display.auto": "false", "display.lo_db": 60, "display.hi_db": 110}.items()
            for a in ("--set", f"{k}={v}")]
    subprocess.run([sonarsim_exe, "render", *sets, "--out", str(scratch / "fan")], check=True,
                   capture_output=True)
    png, npy = str(scratch / "fan.png"), np.load(scratch / "fan.npy")
    r = sonarsim.compare(png, png)
    assert r["a"]["bins"] == npy.shape[0] and r["a"]["beams"] == npy.shape[1]
    assert r["pair"]["aligned"] and abs(r["pair"]["correlation"] - 1) < 1e-9
    shown = np.where(npy < 60, -np.inf, np.minimum(npy, 110)).astype(np.float32)
    r = sonarsim.compare(png, shown)
    assert r["pair"]["correlation"] > 0.75  # 0.84: the fan interpolates across beams and bins (48 x 96 here)
    assert abs(r["a"]["floor_fraction"] - r["b"]["floor_fraction"]) < 0.05
    with pytest.raises(ValueError, match="outside"):
        sonarsim.compare(png, shown, fan_a="10,10,1000,32,0.5,5,60,110,48,96")


def test_render_pings_equals_render_files(sonarsim_exe, scratch, source_dir):
    """render_pings gives a side-scan's arrays as `sonarsim render` writes them."""
    scene = str(source_dir / "assets/scenes/sidescan_wreck.json")
    sets = {"sidescan.pings": 12, "sonar.range_bins": 300}
    subprocess.run([sonarsim_exe, "render", "--scene", scene, *[f"--set={k}={v}" for k, v in sets.items()],
                    "--out", str(scratch / "ss")], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    out = sonarsim.render_pings(scene, set=sets)
    assert out["level_db"].shape == (12, 2, 300)
    assert np.array_equal(out["level_db"], read_npy(scratch / "ss.npy"))
    assert np.array_equal(out["waterfall_db"], read_npy(scratch / "ss_waterfall.npy"))
    assert out["image"].shape == (12, 600, 3)
    assert len(out["metadata"]["pings"]) == 12
    with pytest.raises(ValueError, match="render_pings takes sonar.kind sidescan or scanning"):
        sonarsim.render_pings(None)


def test_render_pings_along_a_trajectory(sonarsim_exe, scratch, source_dir):
    """Pings heard along a survey line (render's --trajectory, --at): ping k at k dt after the line's start, from
    its pose then, the newest at the time asked; Python's arrays are render's files."""
    scene = str(source_dir / "assets/scenes/sidescan_wreck.json")
    sets = {"sidescan.pings": 20, "sonar.range_bins": 200}
    line = scratch / "line.csv"
    line.write_text("t,x,y,z,roll_deg,pitch_deg,yaw_deg\n2.0,-20,16,9,0,0,0\n12.0,0,16,9,0,0,0\n")  # 2 m/s
    subprocess.run([sonarsim_exe, "render", "--scene", scene, *[f"--set={k}={v}" for k, v in sets.items()],
                    "--trajectory", str(line), "--at", "7.3", "--out", str(scratch / "al")], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = sonarsim.render_pings(scene, set=sets, trajectory=str(line), at_s=7.3)
    assert np.array_equal(out["level_db"], read_npy(scratch / "al.npy"))
    pings = out["metadata"]["pings"]
    assert len(pings) == 20
    dt = out["metadata"]["ping_interval_s"]
    newest = pings[-1]["time_s"]
    assert newest <= 5.3 + 1e-9 < newest + dt  # seconds after the line's start
    for p in pings:  # on the line: x = -20 + 2 t
        assert p["position_m"][0] == pytest.approx(-20 + 2 * p["time_s"], abs=1e-9)
        assert p["position_m"][1] == 16
    with pytest.raises(ValueError, match="at_s: is a time on a trajectory: give trajectory= too"):
        sonarsim.render_pings(scene, set=sets, at_s=3.0)
    with pytest.raises(ValueError, match="at_s: expected a number of seconds"):
        sonarsim.render_pings(scene, set=sets, trajectory=str(line), at_s="soon")
    for bad in (float("nan"), float("inf")):
        with pytest.raises(ValueError, match="at_s: the time on the trajectory must be a finite number"):
            sonarsim.render_pings(scene, set=sets, trajectory=str(line), at_s=bad)


def test_render_pings_ground_truth_per_sample(sonarsim_exe, scratch, source_dir):
    """render_pings(ground_truth=True) gives the arrays `render --ground-truth` writes, shaped as level_db."""
    scene = str(source_dir / "assets/scenes/scan_tank.json")
    sets = {"scanning.sector_end_deg": 36, "sonar.range_bins": 200}
    subprocess.run([sonarsim_exe, "render", "--scene", scene, *[f"--set={k}={v}" for k, v in sets.items()],
                    "--ground-truth", "--out", str(scratch / "sc")], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    out = sonarsim.render_pings(scene, set=sets, ground_truth=True)
    steps = out["level_db"].shape[0]
    gt = out["ground_truth"]
    assert gt["point_m"].shape == (steps, 200, 3)
    assert gt["object_id"].shape == (steps, 200)
    for name in ("point_m", "object_id", "incidence_deg", "elevation_deg"):
        assert np.array_equal(gt[name], np.load(scratch / f"sc_gt_{name}.npy"), equal_nan=True), name
    # A sample the truth names something for has an echo (a footprint also spreads echo into bins its
    # surface does not cross at their centre range, which the truth leaves empty).
    named = gt["object_id"] >= 0
    assert named.sum() > 1000
    assert np.isfinite(out["ideal_db"][named]).all()
