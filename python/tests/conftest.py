"""Shared fixtures: the bundled floor plan (always there) and the Intel data set (skipped with a
message when MOTE_DATA_DIR does not hold it, as the C++ tests do)."""

import os
import pathlib

import numpy as np
import pytest

import mote

ROOT = pathlib.Path(__file__).resolve().parents[2]
FLOORPLAN = ROOT / "sim" / "data" / "floorplan.yaml"
DATA_DIR = pathlib.Path(os.environ.get("MOTE_DATA_DIR", ROOT.parent / "shared" / "data"))
INTEL = DATA_DIR / "intel"


def read_tum(path):
    """(stamp, x, y, theta) rows of a TUM file (yaw from the quaternion's z and w)."""
    rows = []
    for line in pathlib.Path(path).read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        t, x, y, _z, qx, qy, qz, qw = map(float, line.split())
        yaw = np.arctan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
        rows.append((t, x, y, yaw))
    return np.array(rows)


@pytest.fixture(scope="session")
def floorplan():
    return mote.load_map(str(FLOORPLAN))


@pytest.fixture(scope="session")
def intel():
    """Paths of the Intel map, log and reference; skips when the data set is absent."""
    paths = {"map": INTEL / "intel.yaml", "log": INTEL / "intel.clf", "reference": INTEL / "intel.gt.tum"}
    missing = [str(p) for p in paths.values() if not p.exists()]
    if missing:
        pytest.skip(f"Intel data set absent (MOTE_DATA_DIR={DATA_DIR}): {', '.join(missing)}")
    return {k: str(v) for k, v in paths.items()}


def ring_scan(n=60, r=2.0):
    """A 360-degree scan of n beams, all reading r metres."""
    inc = 2.0 * np.pi / n
    return mote.LaserScan(np.full(n, r, dtype=np.float32), angle_min=-np.pi, angle_increment=inc,
                          range_min=0.1, range_max=30.0)


@pytest.fixture
def localizer(floorplan):
    """A Localizer on the floor plan, 2000 particles around a free cell, one update run."""
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(min_particles=2000, max_particles=2000))
    i, j = np.argwhere(floorplan.cells.T == 0)[len(np.argwhere(floorplan.cells.T == 0)) // 2]
    x, y = floorplan.cell_center(int(i), int(j))
    loc.initialize((x, y, 0.0), np.diag([0.1, 0.1, 0.05]))
    loc.update((0.0, 0.0, 0.0), ring_scan())
    return loc
