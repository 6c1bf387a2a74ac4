"""Seafloor models of the reconstruction chapter against independent references."""

import math

import numpy as np
import pytest

from sss_locus.experiments.datamodel.terrain import (TERRAIN_FILE, flat_terrain, load_terrain_config, mound_terrain,
                                                     place_features, random_terrain, slope_terrain, step_terrain,
                                                     terrain_from_config)


def test_analytic_heights():
    assert np.all(flat_terrain().height_m([1.0, -5.0], 3.0) == 0)
    s = slope_terrain(10.0, 90.0)  # rises toward +y
    assert s.height_m(123.0, 10.0) == pytest.approx(10 * math.tan(math.radians(10)))
    assert s.height_m(50.0, 0.0) == pytest.approx(0.0, abs=1e-12)
    m = mound_terrain(3.0, 15.0, 10.0, -4.0)
    assert m.height_m(10.0, -4.0) == pytest.approx(3.0)
    assert m.height_m(25.0, -4.0) == pytest.approx(3.0 * math.exp(-0.5))
    t = step_terrain(2.0, 20.0, 0.0)  # trench along x
    assert list(t.height_m(0.0, [0.0, 9.9, 10.1, -30.0])) == [-2.0, -2.0, 0.0, 0.0]


def test_random_field_statistics_and_seed():
    a = random_terrain(1.5, 20.0, 400.0, 2.0, seed=3)
    b = random_terrain(1.5, 20.0, 400.0, 2.0, seed=3)
    x0, y0, dx, h = a.grid
    assert np.array_equal(h, b.grid[3])
    assert not np.array_equal(h, random_terrain(1.5, 20.0, 400.0, 2.0, seed=4).grid[3])
    assert math.sqrt(np.mean(h * h)) == pytest.approx(1.5, rel=1e-12)
    assert abs(h.mean()) < 1e-12
    # the empirical correlation at lag ell is exp(-1) (Gaussian covariance), within sampling error
    lag = int(round(20.0 / dx))
    rho = np.mean(h[:, :-lag] * h[:, lag:]) / np.mean(h * h)
    assert rho == pytest.approx(math.exp(-1), abs=0.08)
    rho2 = np.mean(h[:, :-2 * lag] * h[:, 2 * lag:]) / np.mean(h * h)
    assert abs(rho2) < 0.1  # exp(-4) = 0.018
    # bilinear interpolation reproduces grid nodes exactly and is linear between them
    assert a.height_m(x0 + 7 * dx, y0 + 11 * dx) == pytest.approx(h[11, 7], abs=1e-12)
    mid = a.height_m(x0 + 7.5 * dx, y0 + 11 * dx)
    assert mid == pytest.approx(0.5 * (h[11, 7] + h[11, 8]), abs=1e-12)
    assert np.all(random_terrain(0.0, 20.0, 100.0, 2.0, seed=1).height_m([0, 10], 5) == 0)


def test_features_on_the_seafloor():
    t = mound_terrain(3.0, 15.0)
    f = place_features(t, 500, 200.0, seed=2)
    assert f.shape == (500, 3)
    assert np.all(np.abs(f[:, :2]) <= 100.0)
    assert np.array_equal(f[:, 2], t.height_m(f[:, 0], f[:, 1]))


@pytest.mark.parametrize("call, match", [
    (lambda: slope_terrain(80.0), "slope_deg"),
    (lambda: mound_terrain(3.0, 0.0), "sigma_m"),
    (lambda: random_terrain(1.0, 10.0, 100.0, 6.0, 1), "grid_spacing_m"),
    (lambda: random_terrain(1.0, 10.0, 100.0, 1.0, -1), "seed"),
    (lambda: random_terrain(float("nan"), 10.0, 100.0, 1.0, 1), "rms_relief_m"),
    (lambda: random_terrain(1.0, 10.0, 1e5, 1.0, 1), "4096"),
    (lambda: random_terrain(1.0, 10.0, 100.0, 1.0, 1).height_m(1e4, 0.0), "outside"),
    (lambda: place_features(flat_terrain(), -1, 10.0, 0), "n must"),
    (lambda: terrain_from_config("hills", load_terrain_config()), "kind must"),
])
def test_bad_input_is_named(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_config_is_sourced(tmp_path):
    cfg = load_terrain_config()
    assert set(cfg) == {"slope", "mound", "step", "random", "survey", "provenance"}
    assert all(note.startswith(("source:", "assumption:")) for note in cfg["provenance"].values())
    t = terrain_from_config("random", cfg, extent_m=300.0, seed=1, rms_relief_m=2.0)
    assert math.sqrt(np.mean(t.grid[3] ** 2)) == pytest.approx(2.0)
    bad = TERRAIN_FILE.read_text().replace('slope_deg = { value = 3.0, assumption',
                                           'slope_deg = { value = 3.0, nonsense')
    path = tmp_path / "t.toml"
    path.write_text(bad)
    with pytest.raises(ValueError, match="terrain.slope.slope_deg"):
        load_terrain_config(path)
