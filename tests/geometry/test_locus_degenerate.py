"""Degenerate geometry: every case has a defined, documented result, never NaN or a crash.

Expected values are worked out by hand from the geometry (stated next to each case), not taken
from the kernel's output.
"""

from __future__ import annotations

import zlib

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from reference_locus import (
    APERTURE_FAMILIES,
    ApertureSpec,
    near_degenerate_configs,
    reference_locus,
    spherical_to_cartesian,
)
from sss_locus import MAX_ARCS, Aperture, LocusStatus, two_view_locus

EDGETECH = Aperture(130.0, 0.27, 150.0)
OMNISCAN = Aperture(50.0, 0.5, 150.0)
EVERYTHING = Aperture(360.0, 180.0, 150.0)
RZ_PI = np.diag([-1.0, -1.0, 1.0])  # rotation by pi about z: the sensors face each other
TWO_PI = 2.0 * np.pi


def _finite_outputs(res):
    assert np.all(np.isfinite(res.length)), "length must never be NaN/inf"
    assert np.all(np.isfinite(res.radius))
    assert np.all((res.n_arcs >= 0) & (res.n_arcs <= MAX_ARCS))
    assert np.all(res.length >= 0)


# --- coincident origins -----------------------------------------------------------------------


@pytest.mark.parametrize("r1, r2", [(50.0, 50.0), (50.0, 70.0)])
@pytest.mark.parametrize("seed", [0, 1])
def test_coincident_origins(r1, r2, seed):
    """t = 0: the plane is undefined (equal ranges: the whole sphere; unequal: nothing)."""
    R = Rotation.random(random_state=seed).as_matrix()
    res = two_view_locus(R, np.zeros(3), r1, r2, EVERYTHING, EVERYTHING)
    _finite_outputs(res)
    assert res.status == LocusStatus.COINCIDENT_ORIGINS
    assert res.length == 0.0 and res.n_arcs == 0
    assert np.isnan(res.arc_start).all() and np.isnan(res.arc_end).all()


def test_nearly_coincident_origins_within_documented_threshold():
    """A baseline of 1e-13 (r1 + r2) is below the documented COINCIDENT_RTOL = 1e-12."""
    res = two_view_locus(np.eye(3), [1e-13 * 100.0, 0.0, 0.0], 50.0, 50.0, EDGETECH, EDGETECH)
    assert res.status == LocusStatus.COINCIDENT_ORIGINS
    assert res.length == 0.0


# --- spheres that do not meet -----------------------------------------------------------------


@pytest.mark.parametrize(
    "r1, r2, d",
    [
        (10.0, 20.0, 40.0),  # apart: d > r1 + r2
        (10.0, 50.0, 30.0),  # sphere 1 inside sphere 2: d < r2 - r1
        (50.0, 10.0, 30.0),  # sphere 2 inside sphere 1
    ],
)
def test_spheres_do_not_meet(r1, r2, d):
    s = np.array([0.0, d, 0.0])  # sensor 2's origin in frame 1
    res = two_view_locus(np.eye(3), -s, r1, r2, EVERYTHING, EVERYTHING)
    _finite_outputs(res)
    assert res.status == LocusStatus.NO_INTERSECTION
    assert not res.exists
    assert res.length == 0.0 and res.n_arcs == 0


# --- tangent spheres --------------------------------------------------------------------------


def test_external_tangency_point_inside_both():
    """r1 = 4, r2 = 6, sensors 10 m apart facing each other: they touch at p1 = (4, 0, 0),
    which is on both boresights (p2 = (6, 0, 0)). Documented: TANGENT, length 0, one
    zero-length arc [0, 0]."""
    R = RZ_PI
    t = -R @ np.array([10.0, 0.0, 0.0])
    res = two_view_locus(R, t, 4.0, 6.0, EDGETECH, EDGETECH)
    _finite_outputs(res)
    assert res.status == LocusStatus.TANGENT
    assert res.exists
    assert res.length == 0.0
    np.testing.assert_allclose(res.center, [4.0, 0.0, 0.0], atol=1e-12)
    assert res.n_arcs == 1
    assert res.arc_start[0] == res.arc_end[0] == 0.0


def test_external_tangency_point_outside_sensor_2():
    """Same spheres, but sensor 2 looks away (R = I): the point is behind it. Empty."""
    res = two_view_locus(np.eye(3), [-10.0, 0.0, 0.0], 4.0, 6.0, EDGETECH, EDGETECH)
    assert res.status == LocusStatus.TANGENT
    assert res.length == 0.0 and res.n_arcs == 0


def test_internal_tangency():
    """r1 = 16, r2 = 6, sensor 2 at (10, 0, 0): sphere 2 touches sphere 1 from inside at
    p1 = (16, 0, 0) = p2 + (10, 0, 0)."""
    res = two_view_locus(np.eye(3), [-10.0, 0.0, 0.0], 16.0, 6.0, EDGETECH, EDGETECH)
    _finite_outputs(res)
    assert res.status == LocusStatus.TANGENT
    assert res.length == 0.0
    np.testing.assert_allclose(res.center, [16.0, 0.0, 0.0], atol=1e-12)


def test_tangency_status_is_symmetric_under_view_swap():
    """Near-tangent spheres must get the same status from both sensors' points of view.

    r1 = 1, r2 = 100, centres 99 (1 + 1e-12) apart: the spheres meet in a circle of radius
    about 1.4e-5 m (radius^2 = 1 - a^2 with a = -1 + 100e-12, i.e. sqrt(2e-10)). Whichever way the kernel classifies it
    (circle or tangent point), the swapped view describes the same two spheres.
    """
    d = 99.0 * (1.0 + 1e-12)
    t = np.array([-d, 0.0, 0.0])
    res = two_view_locus(np.eye(3), t, 1.0, 100.0, EVERYTHING, EVERYTHING)
    swapped = two_view_locus(np.eye(3), -t, 100.0, 1.0, EVERYTHING, EVERYTHING)
    assert int(res.status) == int(swapped.status)
    assert float(res.length) == pytest.approx(float(swapped.length), rel=1e-6, abs=1e-12)


# --- a circle wholly inside both apertures ----------------------------------------------------


def test_circle_wholly_inside_both_apertures():
    """Sensors 10 m apart facing each other, r1 = r2 = 10: the circle is x1 = 5, radius
    sqrt(75); every point is at azimuth <= atan2(sqrt(75), 5) = 60 deg and elevation <= 60 deg
    from both sensors. Apertures of 130 deg x 130 deg see all of it: one arc, 2 pi radius."""
    ap = Aperture(130.0, 130.0, 150.0)
    t = -RZ_PI @ np.array([10.0, 0.0, 0.0])
    res = two_view_locus(RZ_PI, t, 10.0, 10.0, ap, ap)
    assert res.status == LocusStatus.CIRCLE
    assert res.radius == pytest.approx(np.sqrt(75.0), rel=1e-14)
    assert res.n_arcs == 1
    assert res.length == pytest.approx(TWO_PI * np.sqrt(75.0), rel=1e-14)
    assert res.arc_end[0] - res.arc_start[0] == pytest.approx(TWO_PI, rel=1e-15)


def test_unbounded_apertures_see_every_circle_whole():
    """Azimuth 360 and elevation 180 impose no angular condition: every circle is one full arc."""
    rng = np.random.default_rng(3)
    R = Rotation.random(2000, random_state=rng).as_matrix()
    r1 = rng.uniform(1.0, 150.0, 2000)
    r2 = rng.uniform(1.0, 150.0, 2000)
    s = rng.normal(size=(2000, 3))
    s *= (rng.uniform(np.abs(r1 - r2), r1 + r2) / np.linalg.norm(s, axis=1))[:, None]
    t = -np.einsum("nij,nj->ni", R, s)  # sensor 2's origin at s in frame 1: t = -R s
    res = two_view_locus(R, t, r1, r2, EVERYTHING, EVERYTHING)
    assert (res.status == LocusStatus.CIRCLE).all()
    assert (res.n_arcs == 1).all()
    np.testing.assert_allclose(res.length, TWO_PI * res.radius, rtol=1e-14)


@pytest.mark.parametrize("pole_z", [+1.0, -1.0], ids=["zenith", "nadir"])
@pytest.mark.parametrize("which", [1, 2])
def test_circle_through_a_sensor_pole_with_unbounded_apertures(pole_z, which):
    """A circle through sensor ``which``'s zenith/nadir (its z axis) with azimuth 360 and
    elevation 180 is still seen whole: elevation 180 imposes no condition, the pole included.

    Each configuration puts the feature exactly on that sensor's z axis.
    """
    rng = np.random.default_rng(5 + which)
    n = 300
    R = Rotation.random(n, random_state=rng).as_matrix()
    r1 = rng.uniform(5.0, 150.0, n)
    r2 = rng.uniform(5.0, 150.0, n)
    if which == 1:
        p1 = np.zeros((n, 3))
        p1[:, 2] = pole_z * r1
        p2 = spherical_to_cartesian(r2, rng.uniform(-np.pi, np.pi, n), rng.uniform(-1.4, 1.4, n))
    else:
        p2 = np.zeros((n, 3))
        p2[:, 2] = pole_z * r2
        p1 = spherical_to_cartesian(r1, rng.uniform(-np.pi, np.pi, n), rng.uniform(-1.4, 1.4, n))
    t = p2 - np.einsum("nij,nj->ni", R, p1)
    res = two_view_locus(R, t, r1, r2, EVERYTHING, EVERYTHING)
    circle = res.status == LocusStatus.CIRCLE
    assert circle.mean() > 0.99
    bad = circle & ((res.n_arcs != 1) | ~np.isclose(res.length, TWO_PI * res.radius, rtol=1e-12))
    i = np.argmax(bad)
    assert not bad.any(), (
        f"{bad.sum()} of {circle.sum()} circles through the pole are not seen whole, e.g. "
        f"R={R[i].tolist()}, t={t[i].tolist()}, r1={r1[i]!r}, r2={r2[i]!r}: length "
        f"{res.length[i]!r} vs 2 pi radius {TWO_PI * res.radius[i]!r}, n_arcs {res.n_arcs[i]}"
    )


def test_pole_of_elevation_180_sensor_does_not_split_an_arc():
    """Hand-checked: R = I, t = (-22.5, 0, 22.5), r1 = r2 = 22.5. The plane is z = x - 22.5;
    the circle passes through p1 = (22.5, 0, 0), which is sensor 2's zenith
    (p2 = (0, 0, 22.5)). Sensor 2 (azimuth 360, elevation 180) excludes nothing; sensor 1
    (250 deg x 30 deg) keeps one arc |z| <= 22.5 sin(15 deg) around p1, where x > 0 so the
    azimuth wedge does not bind: one arc, length 2 rho acos(1 - h / 11.25) with
    h = 22.5 sin(15 deg) and rho = 22.5 / sqrt(2) (derivation in the comments below)."""
    ap1, ap2 = Aperture(250.0, 30.0, 450.0), Aperture(360.0, 180.0, 450.0)
    R, t = np.eye(3), np.array([-22.5, 0.0, 22.5])
    res = two_view_locus(R, t, 22.5, 22.5, ap1, ap2)
    ref = reference_locus(R, t, 22.5, 22.5, ApertureSpec(250, 30, 450), ApertureSpec(360, 180, 450))
    # closed form: centre (11.25, 0, -11.25), radius 22.5/sqrt(2); z(a) = -11.25 + 11.25 cos(a)
    # with a measured from p1; |z| <= h  <=>  cos(a) >= 1 - h / 11.25.
    h = 22.5 * np.sin(np.deg2rad(15.0))
    rho = 22.5 / np.sqrt(2.0)
    want = 2.0 * rho * np.arccos(1.0 - h / 11.25)
    assert ref.n_arcs == 1 and ref.length == pytest.approx(want, rel=1e-12)
    assert res.n_arcs == 1
    assert res.length == pytest.approx(want, rel=1e-12)


# --- ranges outside the aperture --------------------------------------------------------------


@pytest.mark.parametrize(
    "r1, r2, ap1, ap2, out",
    [
        (160.0, 100.0, EDGETECH, EDGETECH, True),  # r1 > max_range
        (100.0, 151.0, EDGETECH, OMNISCAN, True),  # r2 > max_range
        (10.0, 100.0, Aperture(130.0, 0.27, 150.0, 20.0), EDGETECH, True),  # r1 < min_range
        (100.0, 4.0, EDGETECH, Aperture(50.0, 0.5, 120.0, 5.0), True),  # r2 < min_range
        (150.0, 100.0, EDGETECH, EDGETECH, False),  # r1 == max_range: inside (closed interval)
        (20.0, 100.0, Aperture(130.0, 0.27, 150.0, 20.0), EDGETECH, False),  # r1 == min_range
    ],
)
def test_range_outside_aperture(r1, r2, ap1, ap2, out):
    """Choose a pose so that the spheres meet in a circle: sensor 2 at distance max(r1, r2),
    strictly between |r1 - r2| and r1 + r2."""
    s = np.array([0.0, 0.0, max(r1, r2)])
    res = two_view_locus(np.eye(3), -s, r1, r2, ap1, ap2)
    _finite_outputs(res)
    assert res.exists
    if out:
        assert res.status == LocusStatus.OUT_OF_RANGE
        assert res.length == 0.0 and res.n_arcs == 0
        assert np.isnan(res.arc_start).all()
    else:
        assert res.status == LocusStatus.CIRCLE


def test_out_of_range_feature_that_would_be_visible():
    """A feature on both boresights, but r1 just beyond max_range: OUT_OF_RANGE, length 0,
    whereas the same geometry with a larger max_range gives a non-empty locus."""
    R = RZ_PI
    t = -R @ np.array([300.0, 0.0, 0.0])  # sensors 300 m apart, facing each other
    ap_short, ap_long = Aperture(130.0, 0.27, 149.0), Aperture(130.0, 0.27, 160.0)
    res = two_view_locus(R, t, 150.0, 150.5, ap_short, ap_long)
    assert res.status == LocusStatus.OUT_OF_RANGE and res.length == 0.0
    ok = two_view_locus(R, t, 150.0, 150.5, ap_long, ap_long)
    assert ok.status == LocusStatus.CIRCLE and ok.length > 0.0


# --- near-degenerate batches: never NaN, sane, consistent with the reference --------------------


@pytest.mark.parametrize("family", sorted(APERTURE_FAMILIES))
def test_near_degenerate_batch(family):
    a1, a2 = APERTURE_FAMILIES[family]
    rng = np.random.default_rng(zlib.crc32(family.encode()))  # stable: hash() varies per run
    cfg = near_degenerate_configs(rng, 140, a1, a2)
    ap1, ap2 = Aperture(*a1), Aperture(*a2)
    res = two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], ap1, ap2)
    _finite_outputs(res)
    assert (res.length <= TWO_PI * res.radius * (1 + 1e-12)).all()
    nan_pad = np.arange(MAX_ARCS)[None, :] >= res.n_arcs[:, None]
    assert np.isnan(res.arc_start[nan_pad]).all() and np.isfinite(res.arc_start[~nan_pad]).all()

    # every element equals the unbatched call (no cross-talk between batch elements)
    for i in range(0, len(cfg["r1"]), 7):
        one = two_view_locus(cfg["R"][i], cfg["t"][i], cfg["r1"][i], cfg["r2"][i], ap1, ap2)
        assert one.status == res.status[i] and one.n_arcs == res.n_arcs[i]
        assert one.length == res.length[i]

    # against the reference, with conditioning-aware tolerances: a circle the kernel calls
    # TANGENT / NO_INTERSECTION / COINCIDENT must be tiny or absent in the reference, and
    # lengths agree to a few sqrt(eps)-slivers scaled by r / radius (see test_locus_properties).
    s1, s2 = ApertureSpec(*a1), ApertureSpec(*a2)
    r_max = np.maximum(cfg["r1"], cfg["r2"])
    for i, kind in enumerate(cfg["kind"]):
        ref = reference_locus(cfg["R"][i], cfg["t"][i], cfg["r1"][i], cfg["r2"][i], s1, s2, n_steps=2**14)
        where = f"{kind}: R={cfg['R'][i].tolist()}, t={cfg['t'][i].tolist()}, r1={cfg['r1'][i]!r}, r2={cfg['r2'][i]!r}"
        if res.status[i] == LocusStatus.CIRCLE and ref.kind in ("circle", "out_of_range"):
            radius = max(res.radius[i], ref.radius)
            sliver = 1e-6 * max(1.0, r_max[i] / radius)
            # the walk (2**14 steps) can miss arcs shorter than a step: allow 2 such per arc
            walk = 2 * MAX_ARCS * ref.step
            tol = 1e-9 * ref.length + 2 * MAX_ARCS * sliver * radius + walk * radius
            assert abs(res.length[i] - ref.length) <= tol, where
        elif res.status[i] == LocusStatus.CIRCLE:
            assert res.radius[i] <= 1e-6 * r_max[i], where  # reference: spheres just miss
        elif res.status[i] == LocusStatus.COINCIDENT_ORIGINS:
            # documented threshold: baseline below COINCIDENT_RTOL = 1e-12 of r1 + r2
            assert np.linalg.norm(cfg["t"][i]) <= 1e-12 * (cfg["r1"][i] + cfg["r2"][i]), where
            assert res.length[i] == 0.0
        elif ref.kind == "circle":
            assert ref.radius <= 1e-6 * r_max[i], where  # kernel: tangent / no intersection
            assert res.length[i] == 0.0
