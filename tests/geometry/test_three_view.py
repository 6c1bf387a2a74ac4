"""The three-view kernel (sss_locus.geometry.three_view_points) against independent references.

* recovery: a feature built inside all three apertures is among the valid candidates, to 1e-9
  of the range;
* two-view agreement: on random configurations, the points of the two-view locus of views 1–2
  (the kernel's arcs, walked densely) that also lie on sphere 3 and inside aperture 3 are found
  by sign changes + bisection, and must be exactly the valid candidates; every valid candidate
  lies on both two-view loci (1–2 and 1–3);
* invariants: view 2 <-> 3 swap, the scaling law, rigid motion of sensor 1's frame;
* degenerate geometry (parallel, coincident planes, coincident origins, tangent line, no
  point) and bad input.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus import Aperture, two_view_locus
from sss_locus import relative_pose
from sss_locus.geometry.three_view_points import ThreeViewStatus, three_view_points

AUV = Aperture(130.0, 0.27, 150.0)
BOAT = Aperture(50.0, 0.5, 150.0)


def _inside(rng, n, ap, margin=0.95):
    """Points strictly inside ``ap`` (frame of that sensor)."""
    th = rng.uniform(-1, 1, n) * min(ap.half_azimuth_rad, math.pi) * margin
    ph = rng.uniform(-1, 1, n) * ap.half_elevation_rad * margin
    r = rng.uniform(0.05, 1.0, n) * ap.max_range * margin
    return r[:, None] * np.stack([np.cos(th) * np.cos(ph), np.sin(th) * np.cos(ph), np.sin(ph)], 1)


def _apply(R, p):
    return np.einsum("...ij,...j->...i", R, p)


def _configs(rng, n, aps):
    """Random rotations; translations chosen so that one feature is inside all three apertures."""
    p1, p2, p3 = (_inside(rng, n, a) for a in aps)
    R12 = Rotation.random(n, random_state=rng).as_matrix()
    R13 = Rotation.random(n, random_state=rng).as_matrix()
    t12, t13 = p2 - _apply(R12, p1), p3 - _apply(R13, p1)
    r = [np.linalg.norm(p, axis=1) for p in (p1, p2, p3)]
    return dict(R12=R12, t12=t12, R13=R13, t13=t13, r1=r[0], r2=r[1], r3=r[2]), p1


def _run(cfg, aps):
    return three_view_points(cfg["R12"], cfg["t12"], cfg["R13"], cfg["t13"], cfg["r1"], cfg["r2"],
                             cfg["r3"], *aps)


@pytest.mark.parametrize("aps", [(AUV, BOAT, AUV), (BOAT, BOAT, BOAT),
                                 (Aperture(130.0, 20.0, 150.0),) * 3,
                                 (Aperture(360.0, 180.0, 1e3),) * 3])
def test_feature_inside_all_apertures_is_recovered(aps):
    rng = np.random.default_rng(61)
    n = 4000
    cfg, p1 = _configs(rng, n, aps)
    res = _run(cfg, aps)
    err = np.linalg.norm(res.candidates - p1[:, None, :], axis=-1)
    best = np.argmin(err, axis=1)
    rows = np.arange(n)
    assert np.all(err[rows, best] <= 1e-9 * cfg["r1"])
    assert np.all(res.valid[rows, best])
    assert np.all(res.n_valid >= 1)
    assert np.all(np.isin(res.status, [ThreeViewStatus.TWO_POINTS, ThreeViewStatus.ONE_POINT]))
    # the resolved point is the feature
    ok = res.resolved
    if aps[0].azimuth_deg == 360.0:  # whole spheres visible: the mirror candidate always survives
        assert np.all(res.n_valid[res.status == ThreeViewStatus.TWO_POINTS] == 2)
    else:
        assert ok.any()
    np.testing.assert_allclose(res.point[ok], p1[ok], atol=1e-9 * cfg["r1"].max())
    # both candidates are on all three spheres
    both = res.status == ThreeViewStatus.TWO_POINTS
    for R, t, r in ((np.eye(3), np.zeros(3), cfg["r1"]), (cfg["R12"], cfg["t12"], cfg["r2"]),
                    (cfg["R13"], cfg["t13"], cfg["r3"])):
        q = np.einsum("...ij,...kj->...ki", R, res.candidates) + np.asarray(t)[..., None, :]
        np.testing.assert_allclose(np.linalg.norm(q, axis=-1)[both], np.repeat(r[both, None], 2, 1),
                                   rtol=1e-9)


def _roots_on_arcs(loc, i, R13, t13, r3, ap3, n_per_arc=3000):
    """Points of the two-view arcs of configuration ``i`` on sphere 3 and inside aperture 3:
    sign changes of |R13 p + t13| - r3 along each arc, refined by bisection in alpha."""
    found = []
    for k in range(int(loc.n_arcs[i])):
        a0, a1 = loc.arc_start[i, k], loc.arc_end[i, k]
        alpha = np.linspace(a0, a1, n_per_arc)

        def p_of(a):
            a = np.atleast_1d(a)
            return (loc.center[i] + loc.radius[i] * (np.cos(a)[:, None] * loc.basis1[i]
                                                     + np.sin(a)[:, None] * loc.basis2[i]))

        def f_of(a):
            return np.linalg.norm(p_of(a) @ R13.T + t13, axis=1) - r3

        f = f_of(alpha)
        # two roots closer than the grid step hide between samples: add each interior extremum
        # of f (ternary search between its neighbours) to the grid
        ext = np.nonzero((f[1:-1] - f[:-2]) * (f[2:] - f[1:-1]) <= 0)[0] + 1
        extra = []
        for j in ext:
            lo, hi = alpha[j - 1], alpha[j + 1]
            sgn = 1.0 if f[j] < f[j - 1] else -1.0  # minimise sgn * f
            for _ in range(100):
                m1, m2 = lo + (hi - lo) / 3, hi - (hi - lo) / 3
                if sgn * f_of(m1)[0] < sgn * f_of(m2)[0]:
                    hi = m2
                else:
                    lo = m1
            extra.append(0.5 * (lo + hi))
        if extra:
            alpha = np.sort(np.concatenate([alpha, extra]))
            f = f_of(alpha)
        for j in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]:
            lo, hi, flo = alpha[j], alpha[j + 1], f[j]
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                fm = f_of(mid)[0]
                if np.sign(fm) == np.sign(flo):
                    lo, flo = mid, fm
                else:
                    hi = mid
            p = p_of(0.5 * (lo + hi))[0]
            if ap3.contains(R13 @ p + t13):
                found.append(p)
    return found


def _on_arcs(loc, i, p, tol):
    """``p`` is on the circle of ``loc[i]`` (distance < tol) at an angle inside one of its arcs."""
    d = p - loc.center[i]
    off_plane = abs(d @ loc.normal[i])
    radial = abs(math.hypot(d @ loc.basis1[i], d @ loc.basis2[i]) - loc.radius[i])
    a = math.atan2(d @ loc.basis2[i], d @ loc.basis1[i])
    inside = any(((a - loc.arc_start[i, k]) % (2 * math.pi)) <= loc.arc_end[i, k] - loc.arc_start[i, k] + 1e-9
                 for k in range(int(loc.n_arcs[i])))
    return off_plane < tol and radial < tol and inside


@pytest.mark.parametrize("aps", [(Aperture(130.0, 40.0, 150.0), Aperture(90.0, 60.0, 150.0),
                                  Aperture(130.0, 30.0, 150.0)),
                                 (AUV, BOAT, AUV),
                                 (Aperture(360.0, 180.0, 1e3),) * 3])
def test_agrees_with_intersecting_two_view_arcs(aps):
    rng = np.random.default_rng(62)
    n = 60
    cfg, _ = _configs(rng, n, aps)
    # half of them: independent third range, so some configurations have no point at all
    cfg["r3"][: n // 2] *= rng.uniform(0.8, 1.2, n // 2)
    res = _run(cfg, aps)
    l12 = two_view_locus(cfg["R12"], cfg["t12"], cfg["r1"], cfg["r2"], aps[0], aps[1])
    l13 = two_view_locus(cfg["R13"], cfg["t13"], cfg["r1"], cfg["r3"], aps[0], aps[2])
    counts = []
    for i in range(n):
        ref = _roots_on_arcs(l12, i, cfg["R13"][i], cfg["t13"][i], cfg["r3"][i], aps[2])
        got = res.candidates[i][res.valid[i]]
        assert len(ref) == res.n_valid[i], (i, len(ref), res.n_valid[i], res.status[i])
        for p in ref:
            assert np.min(np.linalg.norm(got - p, axis=1)) < 1e-8 * cfg["r1"][i]
        for p in got:  # a valid candidate lies on both two-view loci
            assert _on_arcs(l12, i, p, 1e-8 * cfg["r1"][i])
            assert _on_arcs(l13, i, p, 1e-8 * cfg["r1"][i])
        counts.append(len(ref))
    assert 0 in counts and max(counts) >= 1


def test_view_swap_swaps_the_candidates():
    rng = np.random.default_rng(63)
    aps = (Aperture(130.0, 20.0, 150.0),) * 3
    cfg, _ = _configs(rng, 500, aps)
    a = _run(cfg, aps)
    b = three_view_points(cfg["R13"], cfg["t13"], cfg["R12"], cfg["t12"], cfg["r1"], cfg["r3"],
                          cfg["r2"], *aps)
    np.testing.assert_allclose(b.candidates[:, ::-1], a.candidates, atol=1e-9 * cfg["r1"].max())
    assert np.array_equal(b.n_valid, a.n_valid)
    np.testing.assert_allclose(b.plane_angle_deg, a.plane_angle_deg, atol=1e-9)


def test_scaling_law_and_rigid_motion():
    rng = np.random.default_rng(64)
    aps = (Aperture(130.0, 20.0, 1e9),) * 3  # no range limit: scale-free apertures
    cfg, _ = _configs(rng, 300, (Aperture(130.0, 20.0, 150.0),) * 3)
    a = _run(cfg, aps)
    k = 3.7
    b = three_view_points(cfg["R12"], k * cfg["t12"], cfg["R13"], k * cfg["t13"], k * cfg["r1"],
                          k * cfg["r2"], k * cfg["r3"], *aps)
    np.testing.assert_allclose(b.candidates, k * a.candidates, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(b.half_separation, k * a.half_separation, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(b.line_distance_ratio, a.line_distance_ratio, rtol=1e-9)
    # re-express frame 1 by a rotation Q (p1' = Q p1): candidates rotate, apertures ignored
    full = (Aperture(360.0, 180.0, 1e9),) * 3
    Q = Rotation.from_euler("xyz", [10.0, -40.0, 75.0], degrees=True).as_matrix()
    c = three_view_points(cfg["R12"], cfg["t12"], cfg["R13"], cfg["t13"], cfg["r1"], cfg["r2"],
                          cfg["r3"], *full)
    d = three_view_points(cfg["R12"] @ Q.T, cfg["t12"], cfg["R13"] @ Q.T, cfg["t13"], cfg["r1"],
                          cfg["r2"], cfg["r3"], *full)
    np.testing.assert_allclose(d.candidates, c.candidates @ Q.T, atol=1e-9 * cfg["r1"].max())


def test_relative_pose_matches_world_construction():
    rng = np.random.default_rng(65)
    Ra, Rb = Rotation.random(2, random_state=rng).as_matrix()
    oa, ob, f = rng.normal(size=(3, 3)) * 10
    R, t = relative_pose(Ra, oa, Rb, ob)
    pa, pb = Ra.T @ (f - oa), Rb.T @ (f - ob)
    np.testing.assert_allclose(R @ pa + t, pb, atol=1e-12)


# ----------------------------------------------------------------------- degenerate geometry

FULL = (Aperture(360.0, 180.0, 1e3),) * 3
I3 = np.eye(3)


def _ranges(p, *ts):
    return [float(np.linalg.norm(p))] + [float(np.linalg.norm(p + t)) for t in ts]


def test_collinear_origins_coincident_planes_and_parallel_planes():
    p = np.array([30.0, 10.0, -20.0])
    t12, t13 = np.array([5.0, 0.0, 0.0]), np.array([12.0, 0.0, 0.0])  # origins on one line
    r1, r2, r3 = _ranges(p, t12, t13)
    res = three_view_points(I3, t12, I3, t13, r1, r2, r3, *FULL)
    assert res.status == ThreeViewStatus.COINCIDENT_PLANES
    assert res.n_valid == 0 and not res.valid.any() and np.all(res.candidates == 0)
    assert res.plane_angle_deg == 0.0 and np.isinf(res.line_distance_ratio)
    # the same geometry, third range inconsistent: two distinct parallel planes
    res = three_view_points(I3, t12, I3, t13, r1, r2, r3 + 1.0, *FULL)
    assert res.status == ThreeViewStatus.PARALLEL_PLANES and res.n_valid == 0
    # anti-parallel normals (sensor 3 on the other side of sensor 1) coincide as well
    t13 = np.array([-12.0, 0.0, 0.0])
    res = three_view_points(I3, t12, I3, t13, *_ranges(p, t12, t13), *FULL)
    assert res.status == ThreeViewStatus.COINCIDENT_PLANES


def test_sensor_2_and_3_at_one_place():
    p = np.array([30.0, 10.0, -20.0])
    t = np.array([4.0, -7.0, 2.0])
    r1, r2, _ = _ranges(p, t, t)
    assert three_view_points(I3, t, I3, t, r1, r2, r2, *FULL).status == ThreeViewStatus.COINCIDENT_PLANES
    assert three_view_points(I3, t, I3, t, r1, r2, r2 + 0.5, *FULL).status == ThreeViewStatus.PARALLEL_PLANES


def test_coincident_origins():
    res = three_view_points(I3, np.zeros(3), I3, [1.0, 2.0, 3.0], 10.0, 10.0, 11.0, *FULL)
    assert res.status == ThreeViewStatus.COINCIDENT_ORIGINS
    assert res.n_valid == 0 and np.all(np.isfinite(res.candidates))


def test_tangent_line_gives_one_point_and_missing_line_none():
    p = np.array([20.0, 0.0, 0.0])  # line along z through p: d = z, perpendicular to p
    t12, t13 = np.array([0.0, 8.0, 0.0]), np.array([-6.0, 3.0, 0.0])  # both normals in the xy plane
    r1, r2, r3 = _ranges(p, t12, t13)
    res = three_view_points(I3, t12, I3, t13, r1, r2, r3, *FULL)
    assert res.status == ThreeViewStatus.ONE_POINT
    assert res.n_valid == 1 and res.valid[0] and not res.valid[1]
    np.testing.assert_allclose(res.point, p, atol=1e-9)
    assert res.line_distance_ratio == pytest.approx(1.0, abs=1e-12)
    # a small sphere 1 (r1 = 1 m) does not reach the line of these far planes
    res = three_view_points(I3, t12, I3, t13, 1.0, r2, r3, *FULL)
    assert res.status == ThreeViewStatus.NO_POINT and res.n_valid == 0
    assert res.line_distance_ratio > 1.0


def test_out_of_aperture_candidates_are_invalid_not_nan():
    rng = np.random.default_rng(66)
    cfg, _ = _configs(rng, 200, FULL)
    res = _run(cfg, (Aperture(10.0, 1.0, 5.0),) * 3)
    assert res.n_valid.sum() < 20
    assert np.all(np.isfinite(res.candidates)) and np.all(np.isfinite(res.half_separation))


def test_batch_broadcasting():
    p = np.array([30.0, 10.0, -20.0])
    t12, t13 = np.array([0.0, 8.0, 1.0]), np.array([-6.0, 3.0, 2.0])
    r1, r2, r3 = _ranges(p, t12, t13)
    res = three_view_points(Rotation.identity(), t12, I3, np.stack([t13, t13]), r1, r2,
                            np.array([[r3, r3 + 1], [r3, r3]]), *FULL)
    assert res.candidates.shape == (2, 2, 2, 3) and res.status.shape == (2, 2)


# ----------------------------------------------------------------------- bad input


@pytest.mark.parametrize("kwargs, name", [
    (dict(R12=np.ones((3, 3))), "R12"),
    (dict(R13=-np.eye(3)), "R13"),
    (dict(t12=[1.0, 2.0]), "t12"),
    (dict(t13=[np.nan, 0.0, 0.0]), "t13"),
    (dict(r1=0.0), "r1"),
    (dict(r2=-3.0), "r2"),
    (dict(r3=np.inf), "r3"),
    (dict(r3="far"), "r3"),
    (dict(aperture3=(130.0, 0.27, 150.0)), "aperture3"),
    (dict(r1=np.ones(3), r2=np.ones(4)), "broadcast"),
])
def test_bad_input_names_the_argument(kwargs, name):
    args = dict(R12=I3, t12=[1.0, 0.0, 0.0], R13=I3, t13=[0.0, 1.0, 0.0], r1=10.0, r2=10.0, r3=10.0,
                aperture1=AUV, aperture2=AUV, aperture3=AUV)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        three_view_points(**args)
