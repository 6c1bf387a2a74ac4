"""elevation_misalignment against an independent world-frame construction.

Each sensor i has a world position P_i and orientation Q_i (world-from-sensor rotation), so a
world point w is p_i = Q_i^T (w - P_i) in sensor i's frame; hence p2 = R p1 + t with
R = Q2^T Q1 and t = Q2^T (P1 - P2). The paper's psi_i is the elevation, in sensor i's frame,
of the line through both origins; here it is computed from the world positions with
atan2(z, hypot(x, y)) (the kernel may use arcsin; the two agree away from +-90 deg).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus import elevation_misalignment


def _elevation_deg(v):
    return np.degrees(np.arctan2(v[..., 2], np.hypot(v[..., 0], v[..., 1])))


def _world_case(rng, n):
    Q1 = Rotation.random(n, random_state=rng).as_matrix()
    Q2 = Rotation.random(n, random_state=rng).as_matrix()
    P1 = rng.uniform(-100, 100, (n, 3))
    P2 = rng.uniform(-100, 100, (n, 3))
    R = np.einsum("nji,njk->nik", Q2, Q1)  # Q2^T Q1
    t = np.einsum("nji,nj->ni", Q2, P1 - P2)  # Q2^T (P1 - P2)
    psi1 = _elevation_deg(np.einsum("nji,nj->ni", Q1, P2 - P1))  # 2 seen from 1
    psi2 = _elevation_deg(np.einsum("nji,nj->ni", Q2, P1 - P2))  # 1 seen from 2
    return R, t, psi1, psi2


def test_against_world_frame_construction():
    rng = np.random.default_rng(42)
    R, t, psi1, psi2 = _world_case(rng, 5000)
    res = elevation_misalignment(R, t)
    assert res.defined.all()
    # arcsin loses accuracy only very near +-90 deg (1e-8 rad there); 1e-6 deg covers it
    np.testing.assert_allclose(res.psi1_deg, psi1, rtol=0, atol=1e-6)
    np.testing.assert_allclose(res.psi2_deg, psi2, rtol=0, atol=1e-6)
    np.testing.assert_allclose(res.misalignment_deg, np.maximum(np.abs(psi1), np.abs(psi2)), atol=1e-6)
    away = np.maximum(np.abs(psi1), np.abs(psi2)) < 80.0
    np.testing.assert_allclose(res.psi1_deg[away], psi1[away], rtol=0, atol=1e-10)
    assert (res.misalignment_deg >= 0).all() and (res.misalignment_deg <= 90).all()


def test_swap_views_swaps_psi():
    rng = np.random.default_rng(7)
    R, t, _, _ = _world_case(rng, 1000)
    a = elevation_misalignment(R, t)
    b = elevation_misalignment(np.transpose(R, (0, 2, 1)), -np.einsum("nji,nj->ni", R, t))
    np.testing.assert_allclose(b.psi1_deg, a.psi2_deg, atol=1e-10)
    np.testing.assert_allclose(b.psi2_deg, a.psi1_deg, atol=1e-10)
    np.testing.assert_allclose(b.misalignment_deg, a.misalignment_deg, atol=1e-10)


def test_scale_invariant():
    rng = np.random.default_rng(8)
    R, t, _, _ = _world_case(rng, 200)
    a = elevation_misalignment(R, t)
    b = elevation_misalignment(R, 1e3 * t)
    np.testing.assert_allclose(b.misalignment_deg, a.misalignment_deg, atol=1e-10)


def _pose(P1, Q1, P2, Q2):
    Q1, Q2 = np.asarray(Q1, float), np.asarray(Q2, float)
    return Q2.T @ Q1, Q2.T @ (np.asarray(P1, float) - np.asarray(P2, float))


def test_hand_worked_cases():
    I = np.eye(3)
    # level sensors side by side at one height: the baseline is horizontal for both
    r = elevation_misalignment(*_pose([0, 0, 0], I, [0, 10, 0], I))
    assert (r.psi1_deg, r.psi2_deg, r.misalignment_deg) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    # sensor 2 straight above sensor 1 (both level): +90 from 1, -90 from 2
    r = elevation_misalignment(*_pose([0, 0, 0], I, [0, 0, 10], I))
    assert (r.psi1_deg, r.psi2_deg, r.misalignment_deg) == pytest.approx((90.0, -90.0, 90.0), abs=1e-9)
    # sensor 1 pitched nose-up by 20 deg, sensor 2 level, 10 m ahead along world x:
    # from sensor 1 the (horizontal) baseline lies 20 deg below its xy plane; from 2 it is level
    nose_up = Rotation.from_euler("y", -20.0, degrees=True).as_matrix()
    assert (nose_up @ [1, 0, 0])[2] > 0  # boresight points up
    r = elevation_misalignment(*_pose([0, 0, 0], nose_up, [10, 0, 0], I))
    assert r.psi1_deg == pytest.approx(-20.0, abs=1e-12)
    assert r.psi2_deg == pytest.approx(0.0, abs=1e-12)
    assert r.misalignment_deg == pytest.approx(20.0, abs=1e-12)
    # sensor 2 3 m above and 4 m beside sensor 1, both level: atan(3/4) = 36.87 deg
    r = elevation_misalignment(*_pose([0, 0, 0], I, [0, 4, 3], I))
    assert r.psi1_deg == pytest.approx(np.degrees(np.arctan2(3, 4)), abs=1e-12)
    assert r.psi2_deg == pytest.approx(-np.degrees(np.arctan2(3, 4)), abs=1e-12)


def test_coincident_origins_are_undefined_not_an_error():
    r = elevation_misalignment(Rotation.random(random_state=3).as_matrix(), np.zeros(3))
    assert not r.defined
    assert np.isnan(r.psi1_deg) and np.isnan(r.psi2_deg) and np.isnan(r.misalignment_deg)


def test_broadcasting():
    rng = np.random.default_rng(9)
    R = Rotation.random(4, random_state=rng).as_matrix()[:, None]  # (4, 1, 3, 3)
    t = rng.normal(size=(1, 6, 3))
    r = elevation_misalignment(R, t)
    assert r.misalignment_deg.shape == (4, 6) and r.defined.shape == (4, 6)
    one = elevation_misalignment(R[2, 0], t[0, 5])
    assert one.misalignment_deg == r.misalignment_deg[2, 5]
    rot = elevation_misalignment(Rotation.from_matrix(R[2, 0]), t[0, 5])  # scipy Rotation
    assert rot.misalignment_deg == pytest.approx(float(one.misalignment_deg), abs=1e-12)
