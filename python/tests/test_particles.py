"""Localizer.particles: zero-copy read-only views that keep the Localizer alive and refuse to be
read once an update() may have moved the particles; copy() keeps them."""

import gc

import numpy as np
import pytest

import mote
from conftest import ring_scan

COLUMNS = ("x", "y", "theta", "log_weight")


def address(a):
    return a.__array_interface__["data"][0]


def test_views_are_zero_copy_and_read_only(localizer):
    p = localizer.particles
    assert len(p) == 2000 and p.is_view and p.valid
    for name in COLUMNS:
        a = getattr(p, name)
        b = getattr(localizer.particles, name)
        assert a.dtype == np.float32 and a.shape == (2000,)
        assert not a.flags.owndata and not a.flags.writeable
        assert a.base is p  # the Particles object, which holds the Localizer
        assert np.shares_memory(a, b) and address(a) == address(b)  # both view the C++ column
        with pytest.raises(ValueError):
            a[0] = 1.0
    # log_weight is the normalized log-weight: the weights sum to 1.
    assert np.exp(p.log_weight.astype(np.float64)).sum() == pytest.approx(1.0, rel=1e-4)


def test_views_match_the_estimate(localizer):
    p = localizer.particles
    w = np.exp(p.log_weight.astype(np.float64))
    mean = localizer.estimate.overall.mean
    assert np.sum(w * p.x) / w.sum() == pytest.approx(mean.x, abs=1e-4)
    assert np.sum(w * p.y) / w.sum() == pytest.approx(mean.y, abs=1e-4)


def test_stale_view_raises_after_update(localizer):
    p = localizer.particles
    p.x  # fresh: fine
    localizer.update((0.5, 0.0, 0.0), ring_scan())
    assert localizer.last_update.ran
    assert not p.valid
    for name in COLUMNS:
        with pytest.raises(mote.Error, match="stale particle view"):
            getattr(p, name)
    assert localizer.particles.valid
    localizer.particles.x  # a new view reads


def test_stale_after_initialize(localizer):
    p = localizer.particles
    localizer.initialize_global()
    with pytest.raises(mote.Error, match="stale"):
        p.theta


def test_copy_survives_updates(localizer):
    p = localizer.particles
    before = {name: np.array(getattr(p, name)) for name in COLUMNS}
    c = p.copy()
    assert not c.is_view and c.valid and len(c) == len(p)
    for _ in range(3):
        localizer.update((localizer.last_update.step * 0.5 + 0.5, 0.0, 0.0), ring_scan())
    for name in COLUMNS:
        a = getattr(c, name)
        assert a.flags.owndata
        assert not np.shares_memory(a, getattr(localizer.particles, name))
        np.testing.assert_array_equal(a, before[name])


def test_views_keep_the_localizer_alive(floorplan):
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(min_particles=500, max_particles=500))
    loc.initialize_global()
    x = loc.particles.x
    saved = np.array(x)
    del loc
    gc.collect()
    np.testing.assert_array_equal(x, saved)  # still the live column: the Localizer lives on
    assert x.base.valid


def test_particle_view_at_one_million_is_free(floorplan):
    n = 1_000_000
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(min_particles=n, max_particles=n,
                                                         global_particles_per_bin=0.0))
    loc.initialize_global()
    p = loc.particles
    assert len(p) == n
    a, b = p.x, loc.particles.x
    assert address(a) == address(b)  # no copy: both point at the same 4 MB column
