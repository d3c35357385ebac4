"""The Intel Research Lab log (MOTE_DATA_DIR/intel): reading it, tracking on it from Python bit for
bit as the C++ replay loop does, and mote.replay against the `mote replay` tool."""

import json
import os
import subprocess

import numpy as np
import pytest

import mote
from conftest import read_tum

PARTICLES = 2000
SIGMA_XY, SIGMA_THETA = 0.1, 0.0873  # ReplayOptions' initial cloud (replay_run.hpp)


def test_open_log_yields_every_frame(intel):
    frames = list(mote.open_log(intel["log"]))
    assert len(frames) == 910
    stamps = np.array([f[0] for f in frames])
    assert np.isfinite(stamps).all() and stamps[-1] - stamps[0] > 2000.0  # 45 min recording
    stamp, odom, scan = frames[0]
    assert isinstance(odom, mote.Pose2) and isinstance(scan, mote.LaserScan)
    assert len(scan) == 180 and scan.stamp == stamp
    assert scan.range_max == pytest.approx(81.83)  # the SICK no-return code, inferred
    reader = mote.open_log(intel["log"], laser_max_range=50.0)
    assert next(iter(reader))[2].range_max == 50.0
    assert reader.stats["records_read"] >= 1


def python_loop(intel, start):
    """examples/01's loop in Python: initialize on the first frame, update on every frame."""
    config = mote.LocalizerConfig(min_particles=PARTICLES, max_particles=PARTICLES, seed=42)
    grid = mote.load_map(intel["map"])
    loc = mote.Localizer(grid, config)
    trajectory = []
    for k, (stamp, odom, scan) in enumerate(mote.open_log(intel["log"])):
        if k == 0:
            loc.initialize(start, np.diag([SIGMA_XY * SIGMA_XY, SIGMA_XY * SIGMA_XY,
                                           SIGMA_THETA * SIGMA_THETA]))
        loc.update(odom, scan)
        if loc.last_update.ran:
            m = loc.estimate.refined.pose  # what the replay reports
            trajectory.append((stamp, m.x, m.y, m.theta))
    return np.array(trajectory), loc


def test_python_loop_is_bit_identical_to_replay_and_tracks(intel):
    ref = read_tum(intel["reference"])
    start = tuple(float(v) for v in ref[0, 1:])
    mine, loc = python_loop(intel, start)
    report = mote.replay(map=intel["map"], log=intel["log"], reference=intel["reference"],
                         particles=PARTICLES, init_pose=start)
    assert mine.shape == report["trajectory"].shape and len(mine) > 800
    np.testing.assert_array_equal(mine, report["trajectory"])
    # Tracking: position error against the reference at matching stamps.
    idx = np.searchsorted(ref[:, 0], mine[:, 0]).clip(1, len(ref) - 1)
    idx -= (mine[:, 0] - ref[idx - 1, 0]) < (ref[idx, 0] - mine[:, 0])
    close = np.abs(ref[idx, 0] - mine[:, 0]) < 0.05
    err = np.hypot(mine[close, 1] - ref[idx[close], 1], mine[close, 2] - ref[idx[close], 2])
    assert close.sum() > 800
    rmse = float(np.sqrt(np.mean(err ** 2)))
    assert rmse < 0.15, rmse
    assert report["ate_rmse_m"] < 0.15
    assert np.max(err) < 0.6
    assert loc.particles.x.shape == (PARTICLES,)


def test_replay_matches_the_cli(intel, tmp_path):
    cli = os.environ.get("MOTE_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("MOTE_CLI (the mote tool, set by ctest) not available")
    subprocess.run([cli, "replay", "--map", intel["map"], "--log", intel["log"],
                    "--reference", intel["reference"], "--particles", str(PARTICLES),
                    "--threads", "1", "--out", str(tmp_path / "cli"), "--quiet"], check=True)
    expected = json.loads((tmp_path / "cli" / "report.json").read_text())
    report = mote.replay(map=intel["map"], log=intel["log"], reference=intel["reference"],
                         particles=PARTICLES, threads=2, out=str(tmp_path / "py"))
    for key in ("ate_rmse_m", "heading_rmse_deg", "updates", "scans", "particles_mean",
                "outcomes", "max_error_m"):
        assert report[key] == expected[key], key
    for name in ("report.json", "trajectory.tum", "updates.csv", "map.png"):
        assert (tmp_path / "py" / name).stat().st_size > 0
    written = json.loads((tmp_path / "py" / "report.json").read_text())
    assert written["ate_rmse_m"] == report["ate_rmse_m"]
    assert (tmp_path / "py" / "trajectory.tum").read_text() == \
        (tmp_path / "cli" / "trajectory.tum").read_text()


def test_replay_config_path_and_errors(intel, tmp_path):
    f = tmp_path / "c.yaml"
    f.write_text("max_beams: 30\n")
    r = mote.replay(map=intel["map"], log=intel["log"], config=str(f), particles=500)
    assert r["beams"] == 30 and "ate_rmse_m" not in r  # no reference, no accuracy
    with pytest.raises(mote.InputError, match="missing.tum"):
        mote.replay(map=intel["map"], log=intel["log"], reference=str(tmp_path / "missing.tum"))
