"""mote.sweep on a LocalCluster of 2 worker processes: the table holds the figures of separate
mote.replay runs, and a failing task surfaces as mote.InputError naming its log."""

import math
import re
import subprocess
import sys

import distributed
import pytest

import mote

PARTICLES = 300  # few particles and short slices of the Intel log keep a task well under 1 s
SCANS = 120


def intel_slice(intel, tmp_path, first_scan, name):
    """The Intel log's PARAM lines and its ODOM/FLASER lines from scan first_scan on, SCANS
    scans; the full reference stays valid (replay matches it by stamp)."""
    lines = open(intel["log"]).read().splitlines()
    head = [line for line in lines if not line.startswith(("ODOM", "FLASER"))]
    body, scans = [], 0
    for line in lines:
        if line.startswith("FLASER"):
            scans += 1
        if first_scan < scans <= first_scan + SCANS and line.startswith(("ODOM", "FLASER")):
            body.append(line)
    path = tmp_path / f"{name}.clf"
    path.write_text("\n".join(head + body) + "\n")
    return str(path)


@pytest.fixture(scope="module")
def logs(intel, tmp_path_factory):
    d = tmp_path_factory.mktemp("sweep")
    return {name: {"map": intel["map"], "log": intel_slice(intel, d, first, name),
                   "reference": intel["reference"]}
            for name, first in (("start", 0), ("middle", 400))}


@pytest.fixture(scope="module")
def configs(tmp_path_factory):
    yaml = tmp_path_factory.mktemp("configs") / "tight.yaml"
    yaml.write_text("alpha1: 0.05\nalpha3: 0.05\n")
    return {"tight": str(yaml), "beam": mote.LocalizerConfig(laser_model_type=mote.LaserModel.BEAM)}


FIGURES = ("ate_rmse_m", "heading_rmse_deg", "particles", "updates")  # update_ms is a time


def test_sweep_gives_the_figures_of_separate_replays(logs, configs):
    rows = mote.sweep(logs, configs, particles=PARTICLES, seed=7, n_workers=2)
    assert [(r.log, r.config) for r in rows] == [
        ("start", "tight"), ("start", "beam"), ("middle", "tight"), ("middle", "beam")]
    for row in rows:
        report = mote.replay(config=configs[row.config], particles=PARTICLES, seed=7, threads=1,
                             **logs[row.log])
        assert row.seed == 7 and row.error is None
        assert row.updates == report["updates"] and row.updates > SCANS // 2
        assert row.ate_rmse_m == report["ate_rmse_m"] and row.ate_rmse_m < 1.0
        assert row.heading_rmse_deg == report["heading_rmse_deg"]
        assert row.particles == report["particles_mean"] == PARTICLES
        assert row.update_ms > 0.0 and math.isfinite(row.update_ms)
    # The configs really differ: the beam model does not track like the likelihood field.
    assert rows[0].ate_rmse_m != rows[1].ate_rmse_m


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as c:
        yield c


def test_a_failing_task_names_its_log(logs, cluster, tmp_path):
    missing = tmp_path / "nope.clf"
    bad = {"good": logs["start"], "broken": dict(logs["start"], log=str(missing))}
    named = r"log 'broken', config 'defaults', seed 42: .*" + re.escape(str(missing))
    with pytest.raises(mote.InputError, match=named):
        mote.sweep(bad, [None], client=cluster.scheduler_address, particles=PARTICLES)
    with distributed.Client(cluster) as client:
        good, broken = mote.sweep(bad, [None], client=client, particles=PARTICLES, errors="keep")
    assert good.error is None and good.ate_rmse_m is not None
    assert broken.updates == 0 and broken.ate_rmse_m is None
    assert "log 'broken'" in broken.error and str(missing) in broken.error
    with pytest.raises(mote.ConfigError, match=r"log 'good', config 'empty', seed 42: .*min_part"):
        mote.sweep({"good": logs["start"]}, {"empty": {"min_particles": 0}},
                   client=cluster.scheduler_address)


def test_names_and_bad_entries(intel):
    log = {"map": intel["map"], "log": intel["log"]}
    with pytest.raises(ValueError, match="two configs named 'max_particles=900'"):
        mote.sweep([log], [{"max_particles": 900}, mote.LocalizerConfig(max_particles=900)])
    with pytest.raises(ValueError, match="needs 'map' and 'log'.*unknown: out"):
        mote.sweep([dict(log, out="x")], [None])
    with pytest.raises(TypeError, match="no_such_field"):
        mote.sweep([log], [{"no_such_field": 1}])
    with pytest.raises(ValueError, match="errors must be"):
        mote.sweep([log], [None], errors="ignore")


def test_import_mote_does_not_import_dask():
    code = "import sys, mote; print(sorted(m for m in ('dask', 'distributed') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]" and callable(mote.sweep)
