"""`sonarsim batch` from the command line: bad input, a real kill then --resume, ARIS and MCAP output."""
import os
import signal
import subprocess
import time

import numpy as np

from conftest import write_small_scene


def write_scene(d, beams=48, rays=41):
    # As an ARIS file holds it: 48 beams at 1200 kHz (ARIS 1200 HF), samples from 1 m (SampleStartDelay >= 930 us),
    # 256 bins (SamplePeriod 21 us, at least 128 samples per beam).
    return write_small_scene(d, sonar={"beams": beams, "frequency_khz": 1200, "range_min_m": 1.0, "range_bins": 256},
                             sampling={"elevation_rays": rays})


def test_bad_trajectory_is_one_line_naming_file_line_and_column(sonarsim_exe, scratch):
    t = scratch / "t.csv"
    t.write_text("t,x,y,z,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n0.1,0,0,0,0,oops,0\n")
    r = subprocess.run([sonarsim_exe, "batch", "--trajectory", str(t), "--out", str(scratch / "o")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr == f"sonarsim: error: {t}:3: pitch_deg: \"oops\" is not a finite number\n"
    assert not (scratch / "o").exists()


def test_aris_needs_an_aris_beam_count(sonarsim_exe, scratch):
    scene = write_scene(scratch, beams=50)
    r = subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), "--line", "0.3,2.4,0.9,0.4,2.4,0.9,2",
                        "--out", str(scratch / "o"), "--aris", str(scratch / "x.aris")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "sonar.beams: an ARIS file holds 48, 64, 96 or 128 beams, got 50" in r.stderr
    assert len(r.stderr.splitlines()) == 1
    assert not (scratch / "o").exists()


def test_aris_is_never_faster_than_its_mode(sonarsim_exe, scratch):
    # 48 beams at 1200 kHz out to 25 m: ARIS 1200 HF, 3 pings of CyclePeriod 33926 us, 101.8 ms a frame.
    scene = write_small_scene(scratch, sonar={"beams": 48, "frequency_khz": 1200, "range_min_m": 1.0,
                                              "range_max_m": 25.0, "range_bins": 1000})
    args = [sonarsim_exe, "batch", "--scene", str(scene), "--line", "0.3,2.4,0.9,0.4,2.4,0.9,2",
            "--out", str(scratch / "o"), "--aris", str(scratch / "x.aris")]
    r = subprocess.run(args + ["--rate", "10"], capture_output=True, text=True)
    assert r.returncode == 2
    assert len(r.stderr.splitlines()) == 1
    assert r.stderr.startswith("sonarsim: error: --rate: frame 1 comes 100 ms after the one before")
    fastest = float(r.stderr.split("the fastest it allows is ")[1].split()[0])
    assert 9.5 < fastest < 10  # 1 / (3 CyclePeriods), CyclePeriod = 1 m start delay + 24 m window + 360 us
    assert not (scratch / "o").exists() and not (scratch / "x.aris").exists()


def test_aris_needs_a_frequency_of_the_beams_mode(sonarsim_exe, scratch):
    scene = write_scene(scratch, beams=64)  # ARIS 3000 LF: 1800 kHz, not the scene's 1200
    r = subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), "--line", "0.3,2.4,0.9,0.4,2.4,0.9,2",
                        "--out", str(scratch / "o"), "--aris", str(scratch / "x.aris")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr == (f"sonarsim: error: {scene}: sonar.frequency_khz: 1200 kHz is no ARIS mode of 64 beams: "
                        "they are the ARIS 3000 LF mode at 1800 kHz (allowed within 25 %); set "
                        "sonar.frequency_khz=1800 or sonar.device=aris3000-lf\n")
    assert not (scratch / "o").exists()
    assert not (scratch / "x.aris").exists()


def test_resume_after_a_kill_completes_the_set(sonarsim_exe, scratch):
    scene = write_scene(scratch, rays=4001)  # slow enough frames to be killed mid-run
    out = scratch / "o"
    args = [sonarsim_exe, "batch", "--scene", str(scene), "--circle", "1.5,1.5,0,1.2,0.8,40", "--out", str(out)]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if (out / "frames").exists() and len(list((out / "frames").glob("*.json"))) >= 3:
            break
        time.sleep(0.01)
    assert proc.poll() is None, "the run ended before it could be killed"
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done_before = len(list((out / "frames").glob("*.npy")))
    assert 3 <= done_before < 40
    assert not (out / "index.csv").exists()  # the killed run never got there

    r = subprocess.run(args + ["--resume", "--aris", str(scratch / "o.aris"), "--mcap", str(scratch / "o.mcap")],
                       capture_output=True, text=True, check=True)
    assert "index.csv lists 40 of 40 frames" in r.stdout
    rendered_line = next(line for line in r.stdout.splitlines() if line.startswith("rendered "))
    rendered = int(rendered_line.split()[1])
    # Begun without --aris, the dataset keeps its grid and the file resamples it, saying so.
    assert "was begun on its own range grid" in r.stdout
    assert 40 - done_before <= rendered <= 40 - done_before + 1  # at most the frame in flight again
    rows = (out / "index.csv").read_text().splitlines()
    assert len(rows) == 41
    assert [int(row.split(",")[0]) for row in rows[1:]] == list(range(40))
    for k in range(40):
        level = np.load(out / "frames" / f"{k:06d}.npy")
        assert level.shape == (256, 48)
        assert np.isfinite(level).sum() > 100
    # The ARIS file: 1024 + 40 frames of (1024 + 48 x SamplesPerBeam) bytes; the samples cover the 1-5 m
    # window at SamplePeriod 21 us (2 x 15.6 mm bins / the water's 1490 m/s), 15.6 mm each: 256.
    data = (scratch / "o.aris").read_bytes()
    samples = int.from_bytes(data[1024 + 468:1024 + 472], "little")
    assert int.from_bytes(data[1024 + 452:1024 + 456], "little") == 21
    assert samples == 256
    assert len(data) == 1024 + 40 * (1024 + 48 * samples)
    assert (scratch / "o.mcap").read_bytes()[:8] == b"\x89MCAP0\r\n"


def test_the_dataset_clock_is_fixed_unless_the_wall_clock_is_asked_for(sonarsim_exe, scratch):
    import json
    scene = write_scene(scratch)
    line = ["--line", "0.3,2.4,0.9,0.4,2.4,0.9,2"]
    subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), *line, "--out", str(scratch / "fixed")],
                   capture_output=True, text=True, check=True)
    d = json.loads((scratch / "fixed" / "dataset.json").read_text())
    assert d["start_time_s"] == 1767225600  # 2026-01-01 00:00:00 UTC
    assert d["scene_file"] == str(scene.resolve())
    assert d["program"]["name"] == "sonarsim" and d["program"]["commit"]

    before = time.time()
    subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), *line, "--out", str(scratch / "now"),
                    "--start-now"], capture_output=True, text=True, check=True)
    start = json.loads((scratch / "now" / "dataset.json").read_text())["start_time_s"]
    assert before - 1 <= start <= time.time() + 1

    r = subprocess.run([sonarsim_exe, "batch", "--scene", str(scene), *line, "--out", str(scratch / "both"),
                        "--start-now", "--set", "export.start_time_s=1700000000"], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr == ("sonarsim: error: --start-now: export.start_time_s is given too: give either the start "
                        "or --start-now\n")
    assert not (scratch / "both").exists()


def test_an_unknown_command_is_named_with_the_commands(sonarsim_exe):
    r = subprocess.run([sonarsim_exe, "frobnicate"], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.startswith('sonarsim: error: unknown command "frobnicate"; the commands are render, view, ')
    assert "batch" in r.stderr and len(r.stderr.splitlines()) == 1
