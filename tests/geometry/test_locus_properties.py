"""Invariants of the two-view locus, checked with hypothesis.

* view swap: ``(R^T, -R^T t, r2, r1, aperture2, aperture1)`` describes the same physical
  situation seen from the other sensor: same length, same arc count;
* scaling law (the paper, Sec. IV-B): scaling r1, r2, t and the apertures' ranges by k scales
  the length by k and keeps the arc count;
* a feature built inside both apertures lies on one of the returned arcs, and every point
  ``points()`` returns lies on both spheres and inside both apertures;
* structural sanity of every result (arcs ordered, disjoint, summing to the length, NaN only
  as padding, never NaN in length / n_arcs);
* the brute-force reference again, on hypothesis-chosen configurations.

Configurations are built from hypothesis-drawn numbers (rotation quaternion, feature angles as
fractions of the half apertures, ranges, translations), never from the kernel.

Conditioning and the two tiers
------------------------------
Where the circle touches an aperture boundary tangentially (or crosses it at a grazing angle
gamma), a boundary angle is the arccos of a number within a few ulps of +-1: ANY
double-precision implementation (the kernel, the reference, the kernel in the swapped view)
places it only to about eps * (r / radius) / gamma, at worst sqrt(eps) ~ 1e-8 rad, and may
report or drop a sliver arc or gap of up to ~1e-7 rad. Hypothesis seeks exactly such
alignments (R = I, translations along axes, features exactly on an aperture edge). So:

* strict tier (rtol 1e-9, identical arc count and status): "generic" configurations -- the
  drawn rotation is composed with a fixed, irrational-looking small rotation and seeded
  features stay 1e-3 of a half angle inside the aperture edges, so hypothesis still explores
  every parameter but cannot line boundaries up exactly; and the circle's radius is at least
  1e-2 of the larger range (nearly tangent spheres carry a relative error eps (r/radius)^2);
* loose tier (all configurations, boundary-seeking): lengths agree to 1e-9 relative plus at
  most 2 * MAX_ARCS slivers of 1e-6 rad (times max(r1, r2) / radius for small circles): no
  real arc may appear or vanish.

Exact alignments whose right answer is known (elevation 180 deg, circles through a sensor's
pole, tangent spheres) are tested deterministically in test_locus_degenerate.py.
"""

from __future__ import annotations

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import assume, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from reference_locus import (  # noqa: E402
    APERTURE_FAMILIES,
    ApertureSpec,
    reference_locus,
    spherical_to_cartesian,
)
from sss_locus import MAX_ARCS, Aperture, LocusStatus, two_view_locus  # noqa: E402

RTOL = 1e-9
TWO_PI = 2.0 * np.pi
FAMILY_NAMES = sorted(APERTURE_FAMILIES)

GENERIC_MARGIN = 1e-3
GENERIC_TWIST = Rotation.from_rotvec([1.234567e-3, -2.718281e-3, 1.414213e-3]).as_matrix()
GENERIC_SHIFT = np.array([0.577215, -0.301029, 0.693147])  # metres, added to random t
STRICT_MIN_RADIUS_FRACTION = 1e-2
# Loose tier only (exact alignments drawn by hypothesis). Where the circle grazes an aperture
# bound, the bound's angle on the circle is delta = arccos(-D / M) with -D / M within rounding of
# +-1, so a relative input perturbation e (e.g. the rounding of k * t) moves it by about
# sqrt(2 e * r / M); with e ~ 1e-16 and r / M up to ~1e3 that is ~1e-5 rad. Observed: 2.05e-5 rad
# for the configuration in test_grazing_bound_scaling_is_ill_conditioned_not_wrong.
SLIVER_RAD = 5e-5


@st.composite
def rotations(draw):
    """A rotation matrix from a drawn (non-degenerate) quaternion."""
    q = np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4)))
    assume(np.linalg.norm(q) > 0.1)
    return Rotation.from_quat(q / np.linalg.norm(q)).as_matrix()


def _feature(draw, aperture, margin):
    """A point inside ``aperture`` (tuple form); angles as fractions of the half angles."""
    az, el, rmax, rmin = aperture
    lim = 1.0 - margin
    ft = draw(st.floats(-lim, lim))
    fp = draw(st.floats(-lim, lim))
    fr = draw(st.floats(0.0, 1.0))
    lowest = max(rmin, 0.05 * rmax)
    r = lowest + fr * (rmax - lowest)
    return spherical_to_cartesian(r, ft * np.deg2rad(az) / 2, fp * np.deg2rad(el) / 2), r


@st.composite
def seeded_configs(draw, generic=False):
    """(family, R, t, r1, r2, p1) with the feature p1 inside both apertures."""
    family = draw(st.sampled_from(FAMILY_NAMES))
    a1, a2 = APERTURE_FAMILIES[family]
    margin = GENERIC_MARGIN if generic else 0.0
    p1, r1 = _feature(draw, a1, margin)
    p2, r2 = _feature(draw, a2, margin)
    R = draw(rotations())
    if generic:
        R = R @ GENERIC_TWIST
    t = p2 - R @ p1
    return family, R, t, float(r1), float(r2), p1


@st.composite
def random_configs(draw, generic=False):
    """(family, R, t, r1, r2, None): unconstrained pose and ranges."""
    family = draw(st.sampled_from(FAMILY_NAMES))
    a1, a2 = APERTURE_FAMILIES[family]
    R = draw(rotations())
    t = np.array(draw(st.lists(st.floats(-300.0, 300.0), min_size=3, max_size=3)))
    if generic:
        R = R @ GENERIC_TWIST
        t = t + GENERIC_SHIFT
    r1 = draw(st.floats(0.01, 1.1)) * a1[2]
    r2 = draw(st.floats(0.01, 1.1)) * a2[2]
    return family, R, t, r1, r2, None


def any_configs(generic):
    return st.one_of(seeded_configs(generic=generic), random_configs(generic=generic))


def _apertures(family, scale=1.0):
    a1, a2 = APERTURE_FAMILIES[family]
    return tuple(Aperture(a[0], a[1], a[2] * scale, a[3] * scale) for a in (a1, a2))


def _cfg_repr(R, t, r1, r2):
    """Exact (round-trippable) text of a configuration, for failure messages."""
    return f"R={np.asarray(R).tolist()!r}, t={np.asarray(t).tolist()!r}, r1={r1!r}, r2={r2!r}"


def _shortest_feature(res):
    """Shortest arc or gap (rad) of a scalar result; inf for no arcs / the full circle."""
    n = int(res.n_arcs)
    if n == 0:
        return np.inf
    s, e = res.arc_start[:n], res.arc_end[:n]
    widths = e - s
    if n == 1 and widths[0] >= TWO_PI * (1 - 1e-15):
        return np.inf
    gaps = np.append(s[1:] - e[:-1], s[0] + TWO_PI - e[-1])
    return float(min(widths.min(), gaps.min()))


def _small_circle(res, r1, r2):
    return int(res.status) == LocusStatus.CIRCLE and float(res.radius) < (
        STRICT_MIN_RADIUS_FRACTION * max(r1, r2)
    )


def check_structure(res):
    """Invariants every scalar LocusResult must satisfy."""
    length, n = float(res.length), int(res.n_arcs)
    assert np.isfinite(length) and length >= 0.0
    assert 0 <= n <= MAX_ARCS
    start, end = np.asarray(res.arc_start), np.asarray(res.arc_end)
    assert start.shape == end.shape == (MAX_ARCS,)
    assert np.isnan(start[n:]).all() and np.isnan(end[n:]).all()
    assert np.isfinite(start[:n]).all() and np.isfinite(end[:n]).all()
    if n == 0:
        assert length == 0.0
        return
    s, e = start[:n], end[:n]
    assert ((s >= -np.pi) & (s < np.pi)).all()
    if res.status == LocusStatus.TANGENT:
        assert length == 0.0
        return
    assert res.status == LocusStatus.CIRCLE
    assert (e > s).all() and (e <= s + TWO_PI).all()
    assert (np.diff(s) > 0).all(), "arcs must be ordered by start"
    assert (s[1:] >= e[:-1]).all() and (e[-1] <= s[0] + TWO_PI), "arcs must be disjoint"
    assert length <= TWO_PI * float(res.radius) * (1 + 1e-12)
    assert float(res.radius) * np.sum(e - s) == pytest.approx(length, rel=1e-12)


@given(any_configs(generic=False))
def test_structure(cfg):
    family, R, t, r1, r2, _ = cfg
    check_structure(two_view_locus(R, t, r1, r2, *_apertures(family)))


# --- view swap --------------------------------------------------------------------------------


def _swap(cfg):
    family, R, t, r1, r2, _ = cfg
    ap1, ap2 = _apertures(family)
    return two_view_locus(R, t, r1, r2, ap1, ap2), two_view_locus(R.T, -R.T @ t, r2, r1, ap2, ap1)


@given(any_configs(generic=True))
def test_view_swap_strict(cfg):
    family, R, t, r1, r2, _ = cfg
    res, swapped = _swap(cfg)
    assume(not (_small_circle(res, r1, r2) or _small_circle(swapped, r1, r2)))
    where = _cfg_repr(R, t, r1, r2) + f", family={family!r}"
    assert int(res.status) == int(swapped.status), where
    assert float(swapped.radius) == pytest.approx(float(res.radius), rel=1e-12, abs=1e-12 * (r1 + r2))
    assert int(res.n_arcs) == int(swapped.n_arcs), where
    assert float(swapped.length) == pytest.approx(float(res.length), rel=RTOL, abs=1e-12), where


def _loose_close(a, b, radius, r_max):
    """Loose tier: 1e-9 relative plus 2 * MAX_ARCS slivers.

    A sliver is SLIVER_RAD wide, widened by r_max / radius for small circles, whose
    coefficients carry the larger relative error.
    """
    sliver = SLIVER_RAD * max(1.0, r_max / max(radius, 1e-300))
    return abs(a - b) <= RTOL * max(a, b) + 2 * MAX_ARCS * sliver * radius + 1e-12 * r_max


@given(any_configs(generic=False))
def test_view_swap_loose(cfg):
    family, R, t, r1, r2, _ = cfg
    res, swapped = _swap(cfg)
    radius = max(float(res.radius), float(swapped.radius))
    assert _loose_close(float(res.length), float(swapped.length), radius, max(r1, r2)), (
        _cfg_repr(R, t, r1, r2) + f", family={family!r}: {float(res.length)!r} vs "
        f"{float(swapped.length)!r}"
    )


# --- scaling law ------------------------------------------------------------------------------


def _scaled(cfg, k):
    family, R, t, r1, r2, _ = cfg
    res = two_view_locus(R, t, r1, r2, *_apertures(family))
    scaled = two_view_locus(R, k * t, k * r1, k * r2, *_apertures(family, scale=k))
    return res, scaled


@given(any_configs(generic=True), st.floats(1e-3, 1e3))
def test_scaling_law_strict(cfg, k):
    family, R, t, r1, r2, _ = cfg
    res, scaled = _scaled(cfg, k)
    assume(not _small_circle(res, r1, r2))
    where = _cfg_repr(R, t, r1, r2) + f", k={k!r}, family={family!r}"
    assert int(res.status) == int(scaled.status), where
    assert int(res.n_arcs) == int(scaled.n_arcs), where
    assert float(scaled.length) == pytest.approx(k * float(res.length), rel=RTOL, abs=1e-12 * k), where


@given(any_configs(generic=False), st.floats(1e-3, 1e3))
def test_scaling_law_loose(cfg, k):
    family, R, t, r1, r2, _ = cfg
    res, scaled = _scaled(cfg, k)
    radius = max(float(res.radius), float(scaled.radius) / k)
    assert _loose_close(float(res.length), float(scaled.length) / k, radius, max(r1, r2)), (
        _cfg_repr(R, t, r1, r2) + f", k={k!r}, family={family!r}: {float(res.length)!r} vs "
        f"{float(scaled.length) / k!r}"
    )


# --- the feature and the returned points ------------------------------------------------------


def _angles_ok(p, aperture, tol=1e-9):
    """Membership with a small tolerance for points exactly on a boundary.

    On a sensor's z axis the azimuth is undefined: such points pass the azimuth test.
    """
    r = np.linalg.norm(p, axis=-1)
    theta = np.arctan2(p[..., 1], p[..., 0])
    phi = np.arcsin(np.clip(p[..., 2] / r, -1, 1))
    on_axis = np.hypot(p[..., 0], p[..., 1]) <= tol * r
    return (
        ((np.abs(theta) <= aperture.half_azimuth_rad + tol) | on_axis)
        & (np.abs(phi) <= aperture.half_elevation_rad + tol)
        & (r >= aperture.min_range * (1 - tol))
        & (r <= aperture.max_range * (1 + tol))
    )


@given(seeded_configs(generic=True))
def test_feature_lies_on_a_returned_arc(cfg):
    family, R, t, r1, r2, p1 = cfg
    # coincident origins (p2 = R p1 exactly) have a documented empty locus: not this test
    assume(np.linalg.norm(t) > 1e-9 * (r1 + r2))
    ap1, ap2 = _apertures(family)
    res = two_view_locus(R, t, r1, r2, ap1, ap2)
    where = _cfg_repr(R, t, r1, r2) + f", family={family!r}"
    assert res.status == LocusStatus.CIRCLE, where
    assert res.n_arcs >= 1 and res.length > 0, where
    # the feature is on the circle ...
    d = p1 - res.center
    assert abs(d @ res.normal) <= 1e-9 * r1
    assert np.linalg.norm(d) == pytest.approx(float(res.radius), rel=1e-9, abs=1e-9 * r1)
    # ... and its circle angle is inside one of the returned arcs (modulo 2 pi)
    alpha = np.arctan2(d @ res.basis2, d @ res.basis1)
    n = int(res.n_arcs)
    s, e = res.arc_start[:n], res.arc_end[:n]
    offset = np.mod(alpha - s, TWO_PI)
    tol = 1e-9 * r1 / float(res.radius)
    hit = (offset <= (e - s) + tol) | (offset >= TWO_PI - tol)
    assert hit.any(), f"{where}: feature angle {alpha} not in arcs {list(zip(s, e))}"


@given(any_configs(generic=False))
def test_points_lie_on_both_spheres_inside_both_apertures(cfg):
    family, R, t, r1, r2, _ = cfg
    ap1, ap2 = _apertures(family)
    res = two_view_locus(R, t, r1, r2, ap1, ap2)
    pts1 = res.points(n_per_arc=17, frame=1)
    pts2 = res.points(n_per_arc=17, frame=2)
    n = int(res.n_arcs)
    assert pts1.shape == pts2.shape == (MAX_ARCS, 17, 3)
    assert np.isnan(pts1[n:]).all() and np.isfinite(pts1[:n]).all()
    p1 = pts1[:n].reshape(-1, 3)
    p2 = p1 @ R.T + t
    np.testing.assert_allclose(pts2[:n].reshape(-1, 3), p2, rtol=0, atol=1e-9 * (r1 + r2))
    np.testing.assert_allclose(np.linalg.norm(p1, axis=-1), r1, rtol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(p2, axis=-1), r2, rtol=1e-9)
    where = _cfg_repr(R, t, r1, r2) + f", family={family!r}"
    assert _angles_ok(p1, ap1).all(), where
    assert _angles_ok(p2, ap2).all(), where


# --- the reference, on hypothesis-chosen configurations ---------------------------------------


@settings(max_examples=40)
@given(any_configs(generic=True))
def test_matches_reference_on_hypothesis_configs(cfg):
    """Strict tier against the brute-force reference (2**15 walk steps).

    Same exclusion rule as test_locus_reference.py: skipped (``assume``) only when the KERNEL
    reports an arc or gap shorter than 10 reference steps.
    """
    family, R, t, r1, r2, _ = cfg
    res = two_view_locus(R, t, r1, r2, *_apertures(family))
    steps = 2**15
    assume(_shortest_feature(res) >= 10 * TWO_PI / steps)
    assume(not _small_circle(res, r1, r2))
    a1, a2 = APERTURE_FAMILIES[family]
    ref = reference_locus(R, t, r1, r2, ApertureSpec(*a1), ApertureSpec(*a2), n_steps=steps)
    where = _cfg_repr(R, t, r1, r2) + f", family={family!r}"
    assert int(res.n_arcs) == ref.n_arcs, where
    assert float(res.length) == pytest.approx(ref.length, rel=RTOL, abs=1e-12 * (r1 + r2)), where


def test_grazing_bound_scaling_is_ill_conditioned_not_wrong():
    """A configuration where scaling changes the answer beyond 1e-9, and why that is right.

    Sensors 1.8 cm apart with identical orientation and equal ranges: the circle grazes
    sensor 1's elevation bound, so rounding in k * t (relative 1e-16) opens a 2e-5 rad gap in
    the scaled copy. The kernel agrees with the independent brute-force reference on BOTH
    copies (same arc count; lengths to 1e-7 rad per arc end, the sqrt(eps) scale at which any
    double-precision method places a grazing boundary, 200 times smaller than the 2e-5 rad gap
    that the scaling opens): the sensitivity is the problem's, not the code's.
    """
    from reference_locus import reference_locus

    edgetech = Aperture(130.0, 0.27, 150.0)
    t = np.array([2.081868718395441e-05, 0.0, -0.01767144232548091])
    r1, r2, k = 7.5, 7.500000000000032, 0.28739961318557516
    scaled = Aperture(130.0, 0.27, 150.0 * k)
    for args, ap in (((t, r1, r2), edgetech), ((k * t, k * r1, k * r2), scaled)):
        res = two_view_locus(np.eye(3), *args, ap, ap)
        ref = reference_locus(np.eye(3), *args, ap, ap, n_steps=2**19)
        assert int(res.n_arcs) == ref.n_arcs
        tolerance = 2 * int(res.n_arcs) * 1e-7 * float(res.radius)
        assert abs(float(res.length) - ref.length) <= tolerance
    assert int(two_view_locus(np.eye(3), k * t, k * r1, k * r2, scaled, scaled).n_arcs) == 2
    assert int(two_view_locus(np.eye(3), t, r1, r2, edgetech, edgetech).n_arcs) == 1
