"""Presets that mean what they say (`--set sonar.device=...` over a scene file), and the command line's
smaller promises: the key named when a value is out of order, the render message of the ideal sensor,
index.csv listing the ground-truth files, and a batch interrupted by Ctrl-C."""
import json
import signal
import subprocess
import time

from conftest import write_small_scene


def effect_keys(exe, name):
    """The preset's effect switches, which it sets only under sensor.model "device" (the table's rows with an
    ideal value): the keys `sonarsim devices NAME` marks with *."""
    r = subprocess.run([exe, "devices", name], capture_output=True, text=True, check=True)
    rows = [line.split() for line in r.stdout.splitlines() if line.startswith("  ")]
    return {row[0] for row in rows if row[2] == "*"}


def preset_values(source_dir, name):
    doc = json.loads((source_dir / "assets" / "devices" / f"{name}.json").read_text())
    return {k: v["value"] for k, v in doc["values"].items()}


def value_in(meta, key):
    section, name = key.split(".", 1)
    return meta[section][name]


def render(exe, scratch, scene, *sets, name="img"):
    args = [exe, "render", "--out", str(scratch / name)]
    if scene:
        args += ["--scene", str(scene)]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r, json.loads((scratch / f"{name}.json").read_text())


def scene_file(scratch, extra_sonar):
    return write_small_scene(scratch, sonar={"frequency_khz": 1200, "azimuth_fov_deg": 60, "range_max_m": 4.5,
                                             **extra_sonar})


def test_a_device_on_the_command_line_wins_over_the_scenes_sonar_keys(sonarsim_exe, scratch, source_dir):
    preset = preset_values(source_dir, "aris3000-hf")
    effects = effect_keys(sonarsim_exe, "aris3000-hf")
    assert {"sensor.tvg", "sensor.speckle", "sensor.noise"} <= effects
    assert "sensor.beamformer" not in effects
    scene = scene_file(scratch, {})
    r, meta = render(sonarsim_exe, scratch, scene, "sonar.device=aris3000-hf", "sampling.elevation_rays=41")
    assert meta["sonar"]["device"] == "aris3000-hf"
    for key, value in preset.items():
        if key not in effects:  # the ideal sensor: the preset's effect switches stay off
            assert value_in(meta, key) == value, key
    assert meta["sonar"]["frequency_khz"] == 3000  # the scene said 1200
    assert meta["sonar"]["beams"] == 128  # the scene said 48
    assert meta["device_overrides"] == []
    assert "device preset" not in r.stderr
    # The scene's other keys stay.
    assert meta["sampling"]["elevation_rays"] == 41
    assert meta["objects"][0]["box"] == [0.07, 0.12, 0.22]

    # A --set of a preset key after it wins, and is listed with both values, once on stderr (another beam
    # count needs a beam table of that count: the 128-beam table's 64-beam sibling).
    r, meta = render(sonarsim_exe, scratch, scene, "sonar.device=aris3000-hf", "sonar.beams=64",
                     "sonar.beam_table=aris3000_64", "sensor.model=device", "sampling.elevation_rays=41",
                     name="img64")
    assert meta["sonar"]["beams"] == 64
    assert meta["sensor"]["tvg"] == preset["sensor.tvg"]  # under the device sensor its effects too
    assert meta["device_overrides"] == [{"key": "sonar.beam_table", "preset": "aris3000_128",
                                         "value": "aris3000_64"},
                                        {"key": "sonar.beams", "preset": 128, "value": 64}]
    notes = [line for line in r.stderr.splitlines() if "device preset aris3000-hf" in line]
    assert len(notes) == 1
    assert "sonar.beams 64 (preset 128, from --set)" in notes[0]


def test_a_scene_naming_a_device_keeps_its_own_keys_and_lists_them(sonarsim_exe, scratch, source_dir):
    scene = scene_file(scratch, {"device": "aris3000-hf", "beams": 64, "beam_table": "uniform", "range_bins": 96})
    r, meta = render(sonarsim_exe, scratch, scene)
    assert meta["sonar"]["beams"] == 64
    assert meta["sonar"]["range_bins"] == 96
    assert meta["sonar"]["frequency_khz"] == 1200
    overrides = {o["key"]: (o["preset"], o["value"]) for o in meta["device_overrides"]}
    assert overrides == {"sonar.beams": (128, 64), "sonar.beam_table": ("aris3000_128", "uniform"),
                         "sonar.range_bins": (1024, 96),
                         "sonar.frequency_khz": (3000, 1200), "sonar.azimuth_fov_deg": (30.25, 60),
                         "sonar.range_max_m": (5.0, 4.5)}
    notes = [line for line in r.stderr.splitlines() if "device preset aris3000-hf" in line]
    assert len(notes) == 1
    assert f"sonar.beams 64 (preset 128, from {scene})" in notes[0]


def test_devices_name_shows_what_the_preset_sets(sonarsim_exe, source_dir):
    r = subprocess.run([sonarsim_exe, "devices", "gemini-720is"], capture_output=True, text=True, check=True)
    for key, value in preset_values(source_dir, "gemini-720is").items():
        assert any(line.split()[:2] == [key, json.dumps(value)] for line in r.stdout.splitlines()), key


def test_an_out_of_order_range_names_the_key_that_was_set(sonarsim_exe, scratch):
    r = subprocess.run([sonarsim_exe, "render", "--set", "sonar.range_max_m=0.2", "--out", str(scratch / "x")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr == "sonarsim: error: --set: sonar.range_max_m: range_max_m (0.2) must be above range_min_m (0.5)\n"


def test_the_ideal_render_says_what_it_wrote(sonarsim_exe, scratch):
    r, _ = render(sonarsim_exe, scratch, None, "sonar.beams=48", "sonar.range_bins=96")
    assert "through the sensor" not in r.stdout
    assert "shade 0 ms" not in r.stdout
    assert "L_EN (the ideal sensor)" in r.stdout


def test_index_lists_the_ground_truth_files(sonarsim_exe, scratch):
    out = scratch / "o"
    subprocess.run([sonarsim_exe, "batch", "--scene", str(write_small_scene(scratch, sampling={"elevation_rays": 41})), "--line",
                    "0.3,2.4,0.9,0.4,2.4,0.9,2", "--out", str(out), "--ground-truth"], check=True, capture_output=True)
    rows = (out / "index.csv").read_text().splitlines()
    files = rows[1].split(",")[rows[0].split(",").index("files")].split(";")
    on_disk = sorted(str(p.relative_to(out)) for p in (out / "frames").glob("000000*"))
    assert sorted(files) == on_disk
    assert "frames/000000_gt_object_id.npy" in files


def test_ctrl_c_says_what_it_finished_and_writes_the_index(sonarsim_exe, scratch):
    out = scratch / "o"
    args = [sonarsim_exe, "batch", "--scene", str(write_small_scene(scratch, sampling={"elevation_rays": 4001})), "--circle",
            "1.5,1.5,0,1.2,0.8,40", "--out", str(out)]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if (out / "frames").exists() and len(list((out / "frames").glob("*.json"))) >= 3:
            break
        time.sleep(0.01)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 128 + signal.SIGINT
    done = len(list((out / "frames").glob("*.npy")))
    assert 3 <= done < 40
    assert f"index.csv lists {done} of 40 frames" in stdout
    assert f"interrupted (Ctrl-C) after the frame in flight; the same command with --resume renders the {40 - done} " \
           "frames not yet complete" in stderr
    rows = (out / "index.csv").read_text().splitlines()
    assert len(rows) == 1 + done
