"""Maps, configs, scans and exceptions."""

import pathlib
import re

import numpy as np
import pytest

import mote
from conftest import FLOORPLAN, ROOT, ring_scan


def test_map_fields_and_read_only_cells(floorplan):
    g = floorplan
    assert g.width > 0 and g.height > 0 and g.resolution > 0
    cells = g.cells
    assert cells.shape == (g.height, g.width) and cells.dtype == np.uint8
    assert not cells.flags.owndata and not cells.flags.writeable
    assert np.shares_memory(cells, g.cells)
    assert set(np.unique(cells)) <= {0, 1, 2}
    assert int((cells == 0).sum()) == g.free_cell_count
    # world <-> cell round trip at a cell centre
    x, y = g.cell_center(3, 5)
    assert g.world_to_cell(x, y) == (3, 5)
    assert g.contains(3, 5) and not g.contains(-1, 0)
    assert g.origin.x == pytest.approx(x - 3.5 * g.resolution)


def header_fields():
    """Every field of struct LocalizerConfig, read from the C++ header."""
    text = (ROOT / "engine/include/mote/engine/localizer_config.hpp").read_text()
    body = text[text.index("struct LocalizerConfig {"):text.index("void validate() const;")]
    return re.findall(r"^\s+[\w:]+ (\w+) = ", body, flags=re.M)


def test_config_has_every_cpp_field():
    fields = header_fields()
    assert len(fields) > 35
    assert sorted(mote.LocalizerConfig.fields) == sorted(fields)
    c = mote.LocalizerConfig()
    for name in fields:
        assert hasattr(c, name)


def test_config_keywords():
    c = mote.LocalizerConfig(max_particles=1234, alpha1=0.05, laser_model_type=mote.LaserModel.BEAM)
    assert c.max_particles == 1234 and c.alpha1 == 0.05 and c.laser_model_type == mote.LaserModel.BEAM
    assert c.min_particles == 500  # the rest keep mote's defaults
    with pytest.raises(TypeError, match="no_such_field"):
        mote.LocalizerConfig(no_such_field=1)
    assert mote.nav2_defaults().max_particles == 2000
    assert c.replace(seed=7).seed == 7 and c.seed == 42


def test_a_misspelled_keyword_says_what_it_meant(tmp_path):
    # As the tool does for a flag or a config key: the nearest name, not a list of signatures.
    with pytest.raises(TypeError, match=r"no field 'max_particle' \(did you mean 'max_particles'\?\)"):
        mote.LocalizerConfig(max_particle=1000)
    with pytest.raises(TypeError, match=r"no field 'sede' \(did you mean 'seed'\?\)"):
        mote.LocalizerConfig().replace(sede=1)
    with pytest.raises(TypeError, match=r"^replay\(\) got an unexpected keyword argument 'particels' "
                       r"\(did you mean 'particles'\?\)$"):
        mote.replay(map=FLOORPLAN, log=tmp_path / "never-read.clf", particels=5000)
    with pytest.raises(TypeError, match=r"'lenent' \(did you mean 'lenient'\?\)"):
        mote.open_log(tmp_path / "never-read.clf", lenent=True)
    # A word far from every keyword gets no guess.
    with pytest.raises(TypeError, match=r"argument 'colour'$"):
        mote.load_map(FLOORPLAN, colour=1)
    assert mote.replay.__doc__.startswith("replay(*, map")  # the wrapper keeps the signature


def test_load_config(tmp_path):
    f = tmp_path / "c.yaml"
    f.write_text("max_particles: 3000\nalpha2: 0.1\n")
    c = mote.load_config(str(f))
    assert c.max_particles == 3000 and c.alpha2 == 0.1
    f.write_text("max_particles: 3000\nbogus_key: 1\n")
    with pytest.raises(mote.InputError, match="line 2, key 'bogus_key': unknown key"):
        mote.load_config(str(f))
    f.write_text("max_partcles: 3000\n")  # a typo: the error names the key it meant
    with pytest.raises(mote.InputError, match="did you mean 'max_particles'"):
        mote.load_config(str(f))
    f.write_text("max_particles: 3000\ndo_beamskip: true\n")  # amcl's, not implemented
    with pytest.warns(UserWarning, match="do_beamskip"):
        mote.load_config(str(f))


def test_config_yaml_round_trips(tmp_path):
    c = mote.LocalizerConfig(
        max_particles=3000, alpha2=0.1 + 0.2, odom_model_type=mote.OdomModel.ACKERMANN
    )
    text = mote.config_yaml(c)
    assert "odom_model_type: ackermann\n" in text and "seed" not in text
    f = tmp_path / "c.yaml"
    f.write_text(text)
    back = mote.load_config(str(f))
    assert back.max_particles == 3000 and back.alpha2 == 0.1 + 0.2
    assert back.odom_model_type == mote.OdomModel.ACKERMANN
    assert mote.config_yaml(mote.nav2_defaults(), mote.nav2_defaults()) == ""


def test_bad_map_path_raises_input_error_naming_the_file(tmp_path):
    missing = tmp_path / "nope.yaml"
    with pytest.raises(mote.InputError, match=re.escape(str(missing))) as info:
        mote.load_map(str(missing))
    assert isinstance(info.value, ValueError) and isinstance(info.value, mote.Error)
    assert "\n" not in str(info.value)


def test_bad_config_value(tmp_path, floorplan):
    f = tmp_path / "bad.yaml"
    f.write_text("max_particles: -5\n")
    with pytest.raises(mote.InputError, match=re.escape(str(f)) + ".*max_particles"):
        mote.load_config(str(f))
    with pytest.raises(mote.ConfigError, match="min_particles"):
        mote.Localizer(floorplan, mote.LocalizerConfig(min_particles=0))
    assert issubclass(mote.ConfigError, mote.Error) and not issubclass(mote.ConfigError, ValueError)


def test_update_before_initialize_raises(floorplan):
    loc = mote.Localizer(floorplan, mote.LocalizerConfig(min_particles=100, max_particles=100))
    with pytest.raises(mote.Error):
        loc.update((0.0, 0.0, 0.0), ring_scan())


def test_bad_log_raises_input_error(tmp_path):
    with pytest.raises(mote.InputError, match="nope.clf"):
        mote.open_log(str(tmp_path / "nope.clf"))
    with pytest.raises(mote.InputError, match="txt"):
        mote.open_log(str(tmp_path / "log.txt"))


def test_scan_and_update_stats(localizer):
    s = ring_scan(90, 1.5)
    assert len(s) == 90 and s.ranges.dtype == np.float32 and s.range_max == 30.0
    with pytest.raises(ValueError):
        mote.LaserScan(np.zeros((2, 2)), 0.0, 0.1, 0.1, 10.0)
    assert localizer.update((0.5, 0.0, 0.0), s)
    u = localizer.last_update
    assert u.outcome == mote.UpdateOutcome.UPDATED and u.ran
    assert u.beams > 0 and u.particles > 0 and 0 < u.effective_sample_size <= u.weighed
    assert 0 < u.tempering <= 1 and u.ms.total >= u.ms.sensor >= 0
    assert np.isfinite(u.log_evidence) and u.log_evidence != 0.0
    assert localizer.update((0.5, 0.0, 0.0), s) is False
    assert localizer.last_update.outcome == mote.UpdateOutcome.NOT_MOVED
    e = localizer.estimate
    assert e.covariance.shape == (3, 3) and len(e.clusters) >= 1
    assert e.best.weight <= 1.0 + 1e-9
