"""Bad input gives a ValueError that names the offending argument; broadcasting works."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus import Aperture, elevation_misalignment, two_view_locus

AP = Aperture(130.0, 0.27, 150.0)
R0 = Rotation.from_euler("zyx", [30.0, -20.0, 10.0], degrees=True).as_matrix()
T0 = np.array([3.0, -40.0, 5.0])


def _raises_naming(name, func, *args, **kwargs):
    """ValueError whose message names ``name`` as a word."""
    with pytest.raises(ValueError, match=rf"(?<![A-Za-z_]){re.escape(name)}(?![A-Za-z_])"):
        func(*args, **kwargs)


def _call(**overrides):
    args = dict(R=R0, t=T0, r1=50.0, r2=60.0, aperture1=AP, aperture2=AP)
    args.update(overrides)
    return two_view_locus(**args)


# --- rotations --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "R",
    [
        1.01 * np.eye(3),  # scaled
        np.array([[1.0, 1e-6, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),  # sheared beyond 1e-9
        np.zeros((3, 3)),
        np.diag([1.0, 1.0, -1.0]),  # a reflection: det -1
        -np.eye(3),  # det -1
        np.stack([np.eye(3), np.diag([1.0, -1.0, 1.0])]),  # one bad matrix in a batch
    ],
)
def test_R_not_a_rotation(R):
    _raises_naming("R", _call, R=R, t=np.zeros(3) + T0)


def test_rotation_tolerance_is_1e_9():
    """Documented: orthonormal to within 1e-9. A 1e-11 perturbation passes, 1e-7 fails."""
    _call(R=R0 + 1e-11)
    _raises_naming("R", _call, R=R0 + 1e-7)


def test_determinant_message_mentions_determinant():
    with pytest.raises(ValueError, match="determinant"):
        _call(R=np.diag([1.0, -1.0, 1.0]))


@pytest.mark.parametrize("shape", [(3,), (3, 4), (4, 4), (2, 3)])
def test_R_wrong_shape(shape):
    _raises_naming("R", _call, R=np.ones(shape))


# --- non-finite values ------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("name", ["R", "t", "r1", "r2"])
def test_non_finite_input(name, bad):
    value = {"R": R0.copy(), "t": T0.copy(), "r1": np.array([50.0, 51.0]), "r2": 60.0}[name]
    value = np.array(value, dtype=float)
    value.flat[-1] = bad
    _raises_naming(name, _call, **{name: value})


# --- ranges -----------------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [0.0, -1.0, [10.0, 0.0]])
@pytest.mark.parametrize("name", ["r1", "r2"])
def test_non_positive_range(name, bad):
    _raises_naming(name, _call, **{name: bad})


@pytest.mark.parametrize("name", ["t", "r1"])
def test_non_numeric(name):
    _raises_naming(name, _call, **{name: "fifty"})


@pytest.mark.parametrize("shape", [(2,), (4,), (3, 2)])
def test_t_wrong_shape(shape):
    _raises_naming("t", _call, t=np.ones(shape))


# --- apertures --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(azimuth_deg=0.0, elevation_deg=1.0, max_range=10.0), "azimuth_deg"),
        (dict(azimuth_deg=-10.0, elevation_deg=1.0, max_range=10.0), "azimuth_deg"),
        (dict(azimuth_deg=360.001, elevation_deg=1.0, max_range=10.0), "azimuth_deg"),
        (dict(azimuth_deg=np.nan, elevation_deg=1.0, max_range=10.0), "azimuth_deg"),
        (dict(azimuth_deg=130.0, elevation_deg=0.0, max_range=10.0), "elevation_deg"),
        (dict(azimuth_deg=130.0, elevation_deg=180.5, max_range=10.0), "elevation_deg"),
        (dict(azimuth_deg=130.0, elevation_deg=np.inf, max_range=10.0), "elevation_deg"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=0.0), "max_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=-5.0), "max_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=np.inf), "max_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=10.0, min_range=10.0), "max_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=10.0, min_range=20.0), "max_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=10.0, min_range=-1.0), "min_range"),
        (dict(azimuth_deg=130.0, elevation_deg=1.0, max_range=10.0, min_range=np.nan), "min_range"),
        (dict(azimuth_deg="wide", elevation_deg=1.0, max_range=10.0), "azimuth_deg"),
    ],
)
def test_bad_aperture(kwargs, name):
    _raises_naming(name, Aperture, **kwargs)


@pytest.mark.parametrize("az, el", [(360.0, 180.0), (1e-6, 1e-6), (250.0, 0.27)])
def test_aperture_limits_are_inclusive_or_open_as_documented(az, el):
    """(0, 360] and (0, 180]: the closed ends are accepted."""
    Aperture(az, el, 10.0)


@pytest.mark.parametrize("name", ["aperture1", "aperture2"])
def test_aperture_argument_must_be_an_aperture(name):
    _raises_naming(name, _call, **{name: (130.0, 0.27, 150.0)})


# --- shapes and broadcasting ------------------------------------------------------------------


def test_shapes_that_do_not_broadcast():
    with pytest.raises(ValueError, match="broadcast") as info:
        _call(R=np.stack([R0] * 5), t=np.tile(T0, (4, 1)))
    assert "R" in str(info.value) and "t" in str(info.value)
    with pytest.raises(ValueError, match="broadcast") as info:
        _call(t=np.tile(T0, (4, 1)), r1=np.full(3, 50.0))
    assert "r1" in str(info.value)


def test_one_R_against_many_t():
    rng = np.random.default_rng(0)
    t = T0 + rng.normal(scale=5.0, size=(10, 3))
    r2 = rng.uniform(55.0, 65.0, 10)
    res = _call(t=t, r2=r2)
    assert res.length.shape == (10,) and res.arc_start.shape[0] == 10
    for i in range(10):
        one = _call(t=t[i], r2=r2[i])
        assert one.length == res.length[i] and one.n_arcs == res.n_arcs[i]
        assert one.status == res.status[i]


def test_outer_broadcasting_and_rotation_objects():
    rots = Rotation.random(2, random_state=1)
    t = np.stack([T0, -T0, 2 * T0])[None, :, :]  # (1, 3, 3)
    res = two_view_locus(rots.as_matrix()[:, None], t, 50.0, 60.0, AP, AP)
    assert res.length.shape == (2, 3)
    assert res.center.shape == (2, 3, 3)
    for i in range(2):
        for j in range(3):
            one = two_view_locus(rots[i], t[0, j], 50.0, 60.0, AP, AP)  # a scipy Rotation
            assert one.length == res.length[i, j] and one.n_arcs == res.n_arcs[i, j]
    stacked = two_view_locus(rots, T0, 50.0, 60.0, AP, AP)  # stacked Rotation
    assert stacked.length.shape == (2,)


def test_empty_batch():
    res = _call(t=np.zeros((0, 3)))
    assert res.length.shape == (0,) and res.n_arcs.shape == (0,)


def test_points_arguments():
    res = _call()
    _raises_naming("n_per_arc", res.points, n_per_arc=1)
    _raises_naming("frame", res.points, frame=3)


# --- elevation_misalignment -------------------------------------------------------------------


def test_elevation_misalignment_bad_input():
    _raises_naming("R", elevation_misalignment, np.diag([1.0, 1.0, -1.0]), T0)
    _raises_naming("R", elevation_misalignment, 2 * np.eye(3), T0)
    _raises_naming("t", elevation_misalignment, R0, [0.0, np.nan, 1.0])
    _raises_naming("t", elevation_misalignment, R0, [0.0, 1.0])
    with pytest.raises(ValueError, match="broadcast"):
        elevation_misalignment(np.stack([R0] * 3), np.tile(T0, (2, 1)))
