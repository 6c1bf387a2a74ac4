"""Kernel inputs: real numbers only, any representable magnitude, matching batches, empty batches.

* type: every numeric argument of ``two_view_locus``, ``three_view_points``, ``relative_pose``,
  ``elevation_misalignment`` and ``Aperture`` (and the result methods taking numbers) refuses
  booleans, complex numbers, strings, bytes, dates, datetimes, timedeltas, ``None`` and object
  arrays with a ``TypeError`` naming the argument;
* magnitude: huge and tiny configurations (1e±100 .. 1e±200, and powers of two up to 2**±600)
  give the scaled result of the same configuration at metre scale -- bit for bit for powers of
  two (scaling by 2**k is exact in binary floating point), to rounding of the scaled inputs
  otherwise; where a returned quantity cannot be represented (the two-view ``C``, m^2, beyond
  1e±150 m) the input is refused naming the argument and the range;
* batch shapes that do not broadcast are refused naming the arguments; ``relative_pose``
  returns both outputs in the broadcast batch shape;
* every public field, property and method of the result types works on batch shapes (0,) and
  (2, 0);
* an Aperture given radian values for a sidescan warns; the shipped sonars do not.
"""

from __future__ import annotations

import dataclasses
import datetime
import decimal
import inspect
import re
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from reference_locus import feature_seeded_configs
from sss_locus import (Aperture, LocusStatus, elevation_misalignment, relative_pose,
                       three_view_points, two_view_locus)
from sss_locus.geometry.locus import LocusResult
from sss_locus.geometry.misalignment import ElevationMisalignment
from sss_locus.geometry.three_view_points import ThreeViewResult, ThreeViewStatus as TVS

WIDE = Aperture(130.0, 20.0, 150.0)  # wide enough that most seeded loci are several arcs long
R0 = Rotation.from_euler("zyx", [30.0, -20.0, 10.0], degrees=True).as_matrix()
T0 = np.array([3.0, -40.0, 5.0])


def _names(name):
    """A regex matching ``name`` as a whole word."""
    return rf"(?<![A-Za-z_0-9]){re.escape(name)}(?![A-Za-z_0-9])"


# --- real numbers only ------------------------------------------------------------------------

BAD_KINDS = ["bool", "complex", "str", "bytes", "datetime64", "timedelta64", "date", "datetime",
             "timedelta", "object", "decimal", "none"]


def _bad_like(good, kind):
    """A value of the same shape as ``good`` (array of reals) but of the wrong kind."""
    good = np.asarray(good, dtype=float)
    py = {"date": datetime.date(2024, 5, 1), "datetime": datetime.datetime(2024, 5, 1, 12),
          "timedelta": datetime.timedelta(seconds=50), "decimal": decimal.Decimal("50.0"),
          "none": None}
    if kind in py:
        if good.ndim == 0:
            return py[kind]
        out = np.empty(good.shape, dtype=object)
        out[...] = py[kind]
        return out.tolist()  # a nested Python list, as a user would type it
    return {
        "bool": lambda: good != 0.0,  # np.eye(3) as booleans is still "the identity"
        "complex": lambda: good + 0j,  # zero imaginary part: silently dropped before
        "str": lambda: good.astype(str),  # "50.0" converts to 50.0 if one lets numpy parse it
        "bytes": lambda: good.astype(bytes),
        "datetime64": lambda: np.full(good.shape, np.datetime64("2024-05-01T12:00")),
        "timedelta64": lambda: good.astype("timedelta64[s]"),
        "object": lambda: good.astype(object),
    }[kind]()


TWO_VIEW = dict(R=R0, t=T0, r1=50.0, r2=60.0, aperture1=WIDE, aperture2=WIDE)
THREE_VIEW = dict(R12=R0, t12=T0, R13=R0.T, t13=-T0, r1=50.0, r2=60.0, r3=55.0,
                  aperture1=WIDE, aperture2=WIDE, aperture3=WIDE)
POSE = dict(rotation_a=R0, origin_a=T0, rotation_b=R0.T, origin_b=-T0)
MISALIGN = dict(R=R0, t=T0)
APERTURE = dict(azimuth_deg=130.0, elevation_deg=0.27, max_range=150.0, min_range=1.0)

CASES = ([(two_view_locus, TWO_VIEW, a) for a in ("R", "t", "r1", "r2")]
         + [(three_view_points, THREE_VIEW, a) for a in ("R12", "t12", "R13", "t13", "r1", "r2", "r3")]
         + [(relative_pose, POSE, a) for a in POSE]
         + [(elevation_misalignment, MISALIGN, a) for a in MISALIGN]
         + [(Aperture, APERTURE, a) for a in APERTURE])


@pytest.mark.parametrize("kind", BAD_KINDS)
@pytest.mark.parametrize("func, good, arg", CASES,
                         ids=[f"{f.__name__}-{a}" for f, _, a in CASES])
def test_numeric_arguments_accept_real_numbers_only(func, good, arg, kind):
    kwargs = dict(good)
    kwargs[arg] = _bad_like(good[arg], kind)
    with pytest.raises(TypeError, match=_names(arg)) as info:
        func(**kwargs)
    assert isinstance(info.value, ValueError)  # callers catching ValueError still catch it


INTS = {two_view_locus: dict(r1=np.uint16(50), r2=60), three_view_points: dict(r1=50, r3=np.int8(55)),
        relative_pose: dict(origin_a=[3, -40, 5]), elevation_misalignment: dict(t=np.array([3, -40, 5])),
        Aperture: dict(azimuth_deg=130, max_range=np.uint64(150), min_range=np.int32(1))}


@pytest.mark.parametrize("func, good", [(two_view_locus, TWO_VIEW), (three_view_points, THREE_VIEW),
                                        (relative_pose, POSE), (elevation_misalignment, MISALIGN),
                                        (Aperture, APERTURE)])
def test_real_numbers_of_every_numeric_type_are_accepted(func, good):
    """Python and NumPy ints (signed, unsigned) and floats (16 to 128 bits), lists and arrays."""
    def rotation(k):
        return k.startswith(("R", "rot"))

    variants = [
        lambda k, v: np.asarray(v).tolist(),
        lambda k, v: np.asarray(v, np.longdouble),
        lambda k, v: v if rotation(k) else np.asarray(v, np.float32),
        lambda k, v: v if rotation(k) else np.asarray(v, np.float16),
    ]
    for convert in variants:
        kwargs = {k: v if isinstance(v, Aperture) else convert(k, v) for k, v in good.items()}
        if func is Aperture:  # fields are scalars: NumPy scalars, not 0-d arrays
            kwargs = {k: np.asarray(v)[()] for k, v in kwargs.items()}
        func(**kwargs)
    func(**{**good, **INTS[func]})


def test_aperture_argument_is_a_type_error():
    with pytest.raises(TypeError, match=_names("aperture2")):
        two_view_locus(R0, T0, 50.0, 60.0, WIDE, (130.0, 20.0, 150.0))
    with pytest.raises(TypeError, match=_names("aperture3")):
        three_view_points(R0, T0, R0, T0, 50.0, 60.0, 55.0, WIDE, WIDE, "wide")


@pytest.mark.parametrize("kind", ["bool", "complex", "str", "object", "datetime64"])
def test_result_methods_accept_real_numbers_only(kind):
    res = two_view_locus(**TWO_VIEW)
    with pytest.raises(TypeError, match=_names("alpha")):
        res.point_at(_bad_like(np.zeros(3), kind))
    with pytest.raises(TypeError, match=_names("p1")):
        res.angle_of(_bad_like(np.ones(3), kind))
    with pytest.raises(TypeError, match=_names("points")):
        WIDE.contains(_bad_like(np.ones(3), kind))
    with pytest.raises(TypeError, match=_names("r")):
        WIDE.range_ok(_bad_like(np.ones(2), kind))


def test_result_method_choices():
    res = two_view_locus(**TWO_VIEW)
    for bad in (True, 1.5, 3, "1"):
        with pytest.raises(ValueError, match=_names("frame")):
            res.points(frame=bad)
        with pytest.raises(ValueError, match=_names("frame")):
            res.point_at(0.0, frame=bad)
    for bad in (True, 2.0, 1, "64"):
        with pytest.raises(ValueError, match=_names("n_per_arc")):
            res.points(n_per_arc=bad)
    with pytest.raises(ValueError, match=_names("alpha")):
        res.point_at(np.inf)
    assert np.isnan(res.point_at(np.nan)).all()  # NaN alpha = no point (the arcs' padding)


# --- magnitudes -------------------------------------------------------------------------------


def _seeded(n=200, seed=3):
    ap = (WIDE.azimuth_deg, WIDE.elevation_deg, WIDE.max_range, WIDE.min_range)
    cfg = feature_seeded_configs(np.random.default_rng(seed), n, ap, ap)
    # a few degenerate rows: tangent spheres, no intersection, coincident origins
    R = np.concatenate([cfg["R"], np.stack([np.eye(3)] * 3)])
    t = np.concatenate([cfg["t"], [[0.0, 0.0, -90.0], [0.0, 0.0, -200.0], [0.0, 0.0, 0.0]]])
    r1 = np.concatenate([cfg["r1"], [40.0, 40.0, 40.0]])
    r2 = np.concatenate([cfg["r2"], [50.0, 50.0, 40.0]])
    return R, t, r1, r2


def _two_view_at(k, R, t, r1, r2):
    ap = Aperture(WIDE.azimuth_deg, WIDE.elevation_deg, WIDE.max_range * k, WIDE.min_range * k)
    return two_view_locus(R, t * k, r1 * k, r2 * k, ap, ap)


LENGTHS = ("u", "center", "radius", "length")  # fields in metres; C is in m^2
SCALE_FREE = ("normal", "basis1", "basis2", "exists", "status", "in_range", "n_arcs",
              "arc_start", "arc_end")


def test_reference_batch_is_not_trivial():
    res = _two_view_at(1.0, *_seeded())
    status = res.status
    assert (res.length[status == LocusStatus.CIRCLE] > 0).mean() > 0.9
    assert {int(s) for s in status[-3:]} == {LocusStatus.TANGENT, LocusStatus.NO_INTERSECTION,
                                             LocusStatus.COINCIDENT_ORIGINS}


@pytest.mark.parametrize("p", [-480, -400, -200, -100, 100, 200, 400, 480])
def test_two_view_power_of_two_scale_is_exact(p):
    """Scaling every length by 2**p scales every length of the result by exactly 2**p."""
    cfg = _seeded()
    ref, big = _two_view_at(1.0, *cfg), _two_view_at(2.0 ** p, *cfg)
    for name in LENGTHS:
        np.testing.assert_array_equal(getattr(big, name), getattr(ref, name) * 2.0 ** p, err_msg=name)
    np.testing.assert_array_equal(big.C, ref.C * 4.0 ** p)
    for name in SCALE_FREE:
        np.testing.assert_array_equal(getattr(big, name), getattr(ref, name), err_msg=name)


@pytest.mark.parametrize("k", [1e-140, 1e-100, 1e-80, 1e80, 1e100, 1e140])
def test_two_view_decimal_scale_matches_scaled_result(k):
    """At 1e+-80 and beyond, fourth powers of lengths leave float64; the result is still the
    metre-scale one times k (up to the rounding of k * inputs, well-conditioned rows)."""
    cfg = _seeded()
    ref, big = _two_view_at(1.0, *cfg), _two_view_at(k, *cfg)
    np.testing.assert_array_equal(big.status, ref.status)
    np.testing.assert_array_equal(big.n_arcs, ref.n_arcs)
    assert not np.isnan(big.length).any()
    np.testing.assert_allclose(big.length / k, ref.length, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(big.radius / k, ref.radius, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(big.center / k, ref.center, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(big.C / k**2, ref.C, rtol=1e-8, atol=1e-8)


def test_two_view_mixed_magnitudes_in_one_batch():
    """Each configuration is rescaled on its own: a batch mixing 1e-140 m and 1e140 m."""
    R, t, r1, r2 = _seeded(n=20)
    k = np.where(np.arange(len(r1)) % 2 == 0, 2.0 ** 460, 2.0 ** -460)
    ap = Aperture(130.0, 20.0, 1e150)  # no range limit at either scale
    mixed = two_view_locus(R, t * k[:, None], r1 * k, r2 * k, ap, ap)
    ref = two_view_locus(R, t, r1, r2, ap, ap)
    np.testing.assert_array_equal(mixed.length, ref.length * k)
    np.testing.assert_array_equal(mixed.status, ref.status)


@pytest.mark.parametrize("k", [1e160, 1e200, 1e-160, 1e-200])
@pytest.mark.parametrize("arg", ["r1", "r2", "t"])
def test_two_view_refuses_lengths_whose_square_is_not_representable(k, arg):
    """C = r2^2 - r1^2 - |t|^2 (m^2) is returned: lengths beyond 1e+-150 m are refused."""
    kwargs = dict(TWO_VIEW)
    kwargs[arg] = kwargs[arg] * k
    if arg == "t" and k < 1:
        two_view_locus(**kwargs)  # a tiny baseline is fine (coincident origins, within range)
        return
    with pytest.raises(ValueError, match=_names(arg)) as info:
        two_view_locus(**kwargs)
    assert "1e+150" in str(info.value) and ("1e-150" in str(info.value) or arg == "t")


def test_two_view_bounds_are_inclusive():
    ap = Aperture(130.0, 20.0, 1e151)
    assert two_view_locus(R0, T0 * 1e148, 50.0e148, 60.0e148, ap, ap).status.shape == ()
    res = two_view_locus(np.eye(3), [0.0, 0.0, 1e150], 1e150, 1e150, ap, ap)
    assert np.isfinite(res.C) and res.status == LocusStatus.CIRCLE
    res = two_view_locus(np.eye(3), [0.0, 0.0, 1e-150], 1e-150, 1e-150, WIDE, WIDE)
    assert res.C != 0.0 and res.status == LocusStatus.CIRCLE


def _three_view_at(k, cfg, aps):
    scaled = [Aperture(a.azimuth_deg, a.elevation_deg, a.max_range * k, a.min_range * k) for a in aps]
    return three_view_points(cfg["R12"], cfg["t12"] * k, cfg["R13"], cfg["t13"] * k, cfg["r1"] * k,
                             cfg["r2"] * k, cfg["r3"] * k, *scaled)


def _three_view_configs(n=200, seed=5):
    rng = np.random.default_rng(seed)
    p1 = np.stack([rng.uniform(20, 120, n), rng.uniform(-60, 60, n), rng.uniform(-20, 5, n)], 1)
    R12, R13 = (Rotation.random(n, random_state=rng).as_matrix() for _ in range(2))
    t12, t13 = rng.normal(scale=30.0, size=(n, 3)), rng.normal(scale=30.0, size=(n, 3))
    # degenerate rows: three origins on one line (coincident planes), sensor 2 at sensor 1
    p1 = np.concatenate([p1, [[50.0, 10.0, -5.0]] * 2])
    R12, R13 = (np.concatenate([R, np.stack([np.eye(3)] * 2)]) for R in (R12, R13))
    t12 = np.concatenate([t12, [[0.0, 0.0, -10.0], [0.0, 0.0, 0.0]]])
    t13 = np.concatenate([t13, [[0.0, 0.0, -25.0], [5.0, 0.0, 0.0]]])
    def rng_(R, t):
        return np.linalg.norm(np.einsum("nij,nj->ni", R, p1) + t, axis=1)
    return dict(R12=R12, t12=t12, R13=R13, t13=t13, r1=np.linalg.norm(p1, axis=1),
                r2=rng_(R12, t12), r3=rng_(R13, t13))


THREE_APS = (Aperture(360.0, 180.0, 150.0),) * 3
THREE_LENGTHS = ("candidates", "line_point", "half_separation")
THREE_FREE = ("valid", "n_valid", "status", "line_direction", "plane_angle_deg",
              "line_distance_ratio")


@pytest.mark.parametrize("p", [-600, -300, 300, 600])
def test_three_view_power_of_two_scale_is_exact(p):
    cfg = _three_view_configs()
    ref, big = _three_view_at(1.0, cfg, THREE_APS), _three_view_at(2.0 ** p, cfg, THREE_APS)
    assert (ref.n_valid > 0).mean() > 0.8
    assert list(ref.status[-2:]) == [TVS.COINCIDENT_PLANES, TVS.COINCIDENT_ORIGINS]
    for name in THREE_LENGTHS:
        np.testing.assert_array_equal(getattr(big, name), getattr(ref, name) * 2.0 ** p, err_msg=name)
    for name in THREE_FREE:
        np.testing.assert_array_equal(getattr(big, name), getattr(ref, name), err_msg=name)


@pytest.mark.parametrize("k", [1e-200, 1e-160, 1e-100, 1e100, 1e160, 1e200])
def test_three_view_decimal_scale_matches_scaled_result(k):
    """p0 is a ratio of fifth and fourth powers of lengths: it left float64 beyond ~1e+-60."""
    cfg = _three_view_configs()
    ref, big = _three_view_at(1.0, cfg, THREE_APS), _three_view_at(k, cfg, THREE_APS)
    np.testing.assert_array_equal(big.status, ref.status)
    np.testing.assert_array_equal(big.n_valid, ref.n_valid)
    assert np.isfinite(big.candidates).all()
    np.testing.assert_allclose(big.candidates / k, ref.candidates, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(big.plane_angle_deg, ref.plane_angle_deg, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("k", [1e-200, 1e-160, 1e160, 1e200, 2.0 ** -1000, 2.0 ** 1000])
def test_elevation_misalignment_any_magnitude(k):
    rng = np.random.default_rng(7)
    R = Rotation.random(50, random_state=rng).as_matrix()
    t = rng.normal(scale=20.0, size=(50, 3))
    ref, big = elevation_misalignment(R, t), elevation_misalignment(R, t * k)
    assert big.defined.all()
    for name in ("psi1_deg", "psi2_deg", "misalignment_deg"):
        np.testing.assert_allclose(getattr(big, name), getattr(ref, name), rtol=1e-12, atol=1e-12)
    # reference: the elevation of t itself, from its own direction (no norm of t needed)
    psi2 = np.degrees(np.arctan2(t[:, 2], np.hypot(t[:, 0], t[:, 1])))
    np.testing.assert_allclose(big.psi2_deg, psi2, atol=1e-9)


@pytest.mark.parametrize("k", [1e-200, 1e200])
def test_relative_pose_and_contains_any_magnitude(k):
    Ra, Rb = Rotation.random(2, random_state=1).as_matrix()
    oa, ob = np.array([1.0, 2.0, 3.0]), np.array([-4.0, 5.0, 0.5])
    R, t = relative_pose(Ra, oa * k, Rb, ob * k)
    np.testing.assert_allclose(t / k, Rb.T @ (oa - ob), rtol=1e-12)
    ap = Aperture(130.0, 20.0, 150.0 * k, 1.0 * k)
    p = np.array([[100.0, 10.0, 3.0], [100.0, 10.0, 30.0], [0.5, 0.0, 0.0], [200.0, 0.0, 0.0]])
    np.testing.assert_array_equal(ap.contains(p * k), [True, False, False, False])


@pytest.mark.parametrize("k", [1e-200, 1e200])
def test_zero_rows_do_not_hide_tiny_or_huge_ones(k):
    """A batch with an all-zero row (coincident origins, a point at the origin) next to rows of
    extreme magnitude: each row still gets its own scale."""
    mis = elevation_misalignment(np.eye(3), np.array([[0.0, 0.0, 0.0], [3.0, 0.0, 3.0]]) * k)
    np.testing.assert_array_equal(mis.defined, [False, True])
    np.testing.assert_allclose(mis.psi2_deg[1], 45.0, rtol=1e-12)
    ap = Aperture(130.0, 20.0, 150.0 * k)
    p = np.array([[0.0, 0.0, 0.0], [100.0, 0.0, 0.0], [200.0, 0.0, 0.0]]) * k
    np.testing.assert_array_equal(ap.contains(p), [True, True, False])


def test_relative_pose_difference_overflow_is_refused():
    with pytest.raises(ValueError, match=r"origin_a - origin_b"):
        relative_pose(np.eye(3), [1e308, 0.0, 0.0], np.eye(3), [-1e308, 0.0, 0.0])


# --- batch shapes -----------------------------------------------------------------------------


def test_relative_pose_broadcasts_both_outputs():
    """Five rotations against one origin pair: R and t both have batch shape (5,)."""
    Ra = Rotation.random(5, random_state=2).as_matrix()
    oa, ob = np.array([1.0, 2.0, 3.0]), np.array([-4.0, 5.0, 0.5])
    R, t = relative_pose(Ra, oa, np.eye(3), ob)
    assert R.shape == (5, 3, 3) and t.shape == (5, 3)
    R, t = relative_pose(np.eye(3), oa + np.arange(4)[:, None], Ra[:1], ob)
    assert R.shape == (4, 3, 3) and t.shape == (4, 3)
    np.testing.assert_allclose(t, (oa - ob + np.arange(4)[:, None]) @ Ra[0], rtol=1e-14)


@pytest.mark.parametrize("kwargs, names", [
    (dict(rotation_a=np.stack([R0] * 2), origin_a=np.zeros((3, 3))), ("rotation_a", "origin_a")),
    (dict(rotation_b=np.stack([R0] * 4), origin_a=np.zeros((5, 3))), ("rotation_b", "origin_a")),
    (dict(origin_a=np.zeros((2, 3)), origin_b=np.zeros((3, 3))), ("origin_a", "origin_b")),
])
def test_relative_pose_mismatched_batches_are_refused(kwargs, names):
    with pytest.raises(ValueError, match="broadcast") as info:
        relative_pose(**{**POSE, **kwargs})
    for name in names:
        assert re.search(_names(name), str(info.value))


def test_three_view_mismatched_batches_are_refused():
    with pytest.raises(ValueError, match="broadcast") as info:
        three_view_points(**{**THREE_VIEW, "t12": np.zeros((2, 3)), "r3": np.ones(3)})
    assert re.search(_names("t12"), str(info.value)) and re.search(_names("r3"), str(info.value))


# --- empty batches ----------------------------------------------------------------------------

EMPTY_SHAPES = [(0,), (2, 0)]


def _public(obj):
    """Public fields, properties and methods of a result (class or instance)."""
    cls = obj if isinstance(obj, type) else type(obj)
    names = {n for n in dir(obj) if not n.startswith("_")}
    if issubclass(cls, tuple):
        names -= {"count", "index"}
    return names


def _check_all(obj, calls, shape):
    """Every public name of ``obj`` is exercised: fields and properties by shape, methods by call."""
    expected = set(calls)
    for name in _public(obj):
        attr = getattr(obj, name)
        if name in calls:
            out = calls[name](attr)
            assert out.shape[: len(shape)] == shape and out.size == 0, name
            expected.discard(name)
        elif callable(attr):
            raise AssertionError(f"public method {name} is not exercised on an empty batch")
        elif isinstance(attr, np.ndarray):
            assert attr.shape[: len(shape)] == shape, name
        else:
            assert attr == shape, name
    assert not expected


@pytest.mark.parametrize("shape", EMPTY_SHAPES)
def test_two_view_empty_batch(shape):
    res = two_view_locus(R0, np.zeros(shape + (3,)), 50.0, 60.0, WIDE, WIDE)
    assert isinstance(res, LocusResult)
    calls = {
        "points": lambda f: f(n_per_arc=5, frame=2),
        "point_at": lambda f: f(np.zeros(shape + (4,)), frame=2),
        "angle_of": lambda f: f(np.zeros(shape + (3,))),
    }
    _check_all(res, calls, shape)
    assert res.points().shape == shape + (8, 64, 3)
    assert res.point_at(np.zeros(shape)).shape == shape + (3,)
    assert {f.name for f in dataclasses.fields(res)} <= _public(res)


@pytest.mark.parametrize("shape", EMPTY_SHAPES)
def test_three_view_empty_batch(shape):
    res = three_view_points(R0, T0, R0, np.zeros(shape + (3,)), 50.0, 60.0, 55.0, WIDE, WIDE, WIDE)
    assert isinstance(res, ThreeViewResult)
    _check_all(res, {}, shape)
    assert res.point.shape == shape + (3,) and res.resolved.shape == shape
    assert res.candidates.shape == shape + (2, 3)


@pytest.mark.parametrize("shape", EMPTY_SHAPES)
def test_misalignment_pose_and_aperture_empty_batch(shape):
    res = elevation_misalignment(np.zeros(shape + (3, 3)) + np.eye(3), T0)
    assert isinstance(res, ElevationMisalignment)
    _check_all(res, {}, shape)
    R, t = relative_pose(R0, np.zeros(shape + (3,)), R0, T0)
    assert R.shape == shape + (3, 3) and t.shape == shape + (3,)
    assert WIDE.contains(np.zeros(shape + (3,))).shape == shape
    assert WIDE.range_ok(np.zeros(shape)).shape == shape


def test_result_classes_have_only_the_checked_public_methods():
    """A method added later must be added to the empty-batch checks above."""
    methods = {cls.__name__: {n for n in _public(cls) if inspect.isfunction(getattr(cls, n))}
               for cls in (LocusResult, ThreeViewResult)}
    assert methods == {"LocusResult": {"points", "point_at", "angle_of"}, "ThreeViewResult": set()}


# --- degrees, not radians ---------------------------------------------------------------------


@pytest.mark.parametrize("az, el", [(130.0, 0.27), (50.0, 0.5)])
def test_aperture_in_radians_warns(az, el):
    with pytest.warns(UserWarning, match="radians") as record:
        Aperture(np.radians(az), np.radians(el), 150.0)
    assert record[0].filename == __file__  # points at the caller's line


def test_shipped_sonars_and_other_apertures_do_not_warn():
    from sss_locus.experiments.datamodel.platforms import load_platforms

    sonars = {p.sonar for p in load_platforms().values()}
    assert {(s.azimuth_deg, s.elevation_deg) for s in sonars} >= {(50.0, 0.5), (130.0, 0.27)}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for s in sonars:
            s.aperture()
        for az, el in [(360.0, 180.0), (2.0, 2.0), (1e-6, 1e-6), (3.2, 0.27), (10.0, 1.0),
                       (40.0, 0.05)]:
            Aperture(az, el, 150.0)
