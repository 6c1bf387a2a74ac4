"""Extra half-spaces ``n . p1 <= d`` (sea surface, seafloor) against the brute-force reference.

What is compared
    The kernel's exact crop by the apertures AND ``K`` random half-spaces (``K`` in 1..3) against
    ``tests/reference_locus.py``, which walks the circle densely and tests ``n . p1 <= d`` on
    each frame-1 point (no ``A cos + B sin + D`` form). Half-space planes are drawn through
    random points near each circle (computed by the reference's own two-sphere construction),
    or through points near the feature, so most of them cut it; random normals, sea-surface planes of random attitudes, zero
    normals and planes parallel to the circle are included. Lengths must agree to a relative
    1e-9 and arc counts exactly, with the exclusion rule of ``test_locus_reference.py`` (only
    configurations whose KERNEL result has an arc or gap shorter than 10 walk steps are
    skipped, and they must stay rare).

Invariants (no reference needed)
    K = 0 is bit-identical to no half-spaces; a half-space containing the whole circle changes
    nothing (to rounding); a half-space and its complement split the length exactly, and
    together leave nothing; a zero normal is vacuous for ``d >= 0`` and empty for ``d < 0``;
    tangent planes; swapping the views (with the half-spaces carried into frame 2) gives the
    same length.
"""

from __future__ import annotations

import numpy as np
import pytest

from reference_locus import (APERTURE_FAMILIES, ApertureSpec, circle_from_spheres,
                             feature_seeded_configs, reference_locus)
from sss_locus import (Aperture, max_depth_half_space, sea_surface_half_space, two_view_locus)
from test_locus_reference import EXCLUDE_BELOW_STEPS, REFERENCE_STEPS, RTOL, kernel_shortest_feature

TWO_PI = 2.0 * np.pi
FAMILIES = ["omniscan-omniscan", "edgetech-edgetech", "wide-azimuth", "fragmenting", "min-range"]
N_PER_FAMILY = 72


def _configs(family, n, seed):
    a1, a2 = APERTURE_FAMILIES[family]
    rng = np.random.default_rng([20261123, seed])
    c = feature_seeded_configs(rng, n, a1, a2)
    return c, (Aperture(*a1), Aperture(*a2)), (ApertureSpec(*a1), ApertureSpec(*a2)), rng


def _random_half_spaces(rng, c, K):
    """(n, K, 3) normals and (n, K) offsets, mostly planes through points near each circle."""
    n = len(c["r1"])
    normals = rng.normal(size=(n, K, 3))
    offsets = np.empty((n, K))
    kind = rng.integers(0, 6, size=(n, K))
    for i in range(n):
        _, center, radius, e1, e2 = circle_from_spheres(c["R"][i], c["t"][i], c["r1"][i], c["r2"][i])
        normal = np.cross(e1, e2)
        for k in range(K):
            if kind[i, k] == 4:  # a zero normal, either sign of offset
                normals[i, k] = 0.0
                offsets[i, k] = rng.choice([-1.0, 1.0]) * rng.uniform(0.1, 10.0)
                continue
            if kind[i, k] == 5:  # parallel to the circle's plane: all or nothing
                normals[i, k] = rng.choice([-1.0, 1.0]) * normal * rng.uniform(0.5, 2.0)
            if kind[i, k] < 2:  # through a point near the feature (short loci of narrow beams)
                through = c["p1"][i] + rng.normal(size=3) * 0.005 * c["r1"][i]
            else:  # through a point near the circle
                a = rng.uniform(0, TWO_PI)
                through = center + radius * rng.uniform(-1.3, 1.3) * (np.cos(a) * e1 + np.sin(a) * e2)
                through += rng.normal(size=3) * 0.05 * radius
            offsets[i, k] = normals[i, k] @ through
    return normals, offsets


@pytest.fixture(scope="module", params=FAMILIES)
def comparison(request):
    family = request.param
    c, (k1, k2), (s1, s2), rng = _configs(family, N_PER_FAMILY, FAMILIES.index(family))
    K = 1 + np.arange(N_PER_FAMILY) % 3
    res = {}
    for k in (1, 2, 3):
        rows = np.nonzero(K == k)[0]
        sub = {key: v[rows] for key, v in c.items()}
        normals, offsets = _random_half_spaces(rng, sub, k)
        kernel = two_view_locus(sub["R"], sub["t"], sub["r1"], sub["r2"], k1, k2,
                                half_space_normals=normals, half_space_offsets=offsets)
        excluded = kernel_shortest_feature(kernel) < EXCLUDE_BELOW_STEPS * TWO_PI / REFERENCE_STEPS
        for j, i in enumerate(rows):
            if excluded[j]:
                res[i] = None
                continue
            ref = reference_locus(sub["R"][j], sub["t"][j], sub["r1"][j], sub["r2"][j], s1, s2,
                                  n_steps=REFERENCE_STEPS, half_spaces=list(zip(normals[j], offsets[j])))
            res[i] = (kernel.length[j], kernel.n_arcs[j], ref.length, ref.n_arcs, normals[j], offsets[j])
    return family, res


def test_half_space_crop_matches_reference(comparison):
    family, res = comparison
    kept = {i: r for i, r in res.items() if r is not None}
    assert len(kept) >= 0.95 * len(res), f"{family}: {len(res) - len(kept)} excluded"
    bad = [(i, r) for i, r in kept.items()
           if r[1] != r[3] or not np.isclose(r[0], r[2], rtol=RTOL, atol=1e-12)]
    assert not bad, f"{family}: {len(bad)} of {len(kept)} differ, e.g. {bad[:2]}"


def test_comparison_exercises_cuts(comparison):
    """The planes really cut: some loci are shortened, some emptied, some split."""
    family, res = comparison
    kept = [r for r in res.values() if r is not None]
    ref_len = np.array([r[2] for r in kept])
    assert (ref_len == 0).mean() > 0.05 and (ref_len > 0).mean() > 0.15


def _base(family="fragmenting", n=400, seed=99):
    c, (k1, k2), _, rng = _configs(family, n, seed)
    args = (c["R"], c["t"], c["r1"], c["r2"], k1, k2)
    return c, args, two_view_locus(*args), rng


def test_zero_half_spaces_are_bit_identical():
    _, args, base, _ = _base()
    for normals, offsets in ((np.zeros((0, 3)), np.zeros(0)), (np.zeros((400, 0, 3)), np.zeros((400, 0)))):
        got = two_view_locus(*args, half_space_normals=normals, half_space_offsets=offsets)
        for field in ("length", "n_arcs", "status", "arc_start", "arc_end", "center", "radius"):
            np.testing.assert_array_equal(getattr(got, field), getattr(base, field), err_msg=field)


def test_half_space_containing_the_circle_changes_nothing():
    c, args, base, rng = _base()
    up = rng.normal(size=(400, 3))
    far = np.linalg.norm(up, axis=1) * (c["r1"] + 1.0)  # |p1| = r1 on the circle
    got = two_view_locus(*args, half_space_normals=up[:, None], half_space_offsets=far[:, None])
    np.testing.assert_array_equal(got.n_arcs, base.n_arcs)
    np.testing.assert_allclose(got.length, base.length, rtol=1e-12, atol=1e-12)


def test_complementary_half_spaces_split_the_length_and_together_leave_nothing():
    c, args, base, rng = _base()
    normals = rng.normal(size=(400, 1, 3))
    offsets = rng.normal(size=(400, 1)) * 0.5 * c["r1"][:, None]
    lo = two_view_locus(*args, half_space_normals=normals, half_space_offsets=offsets)
    hi = two_view_locus(*args, half_space_normals=-normals, half_space_offsets=-offsets)
    np.testing.assert_allclose(lo.length + hi.length, base.length, rtol=1e-12, atol=1e-9)
    assert ((lo.length > 0) & (hi.length > 0)).mean() > 0.2  # the planes do cut
    both = two_view_locus(*args, half_space_normals=np.concatenate([normals, -normals], 1),
                          half_space_offsets=np.concatenate([offsets, -offsets], 1))
    assert np.all(both.length == 0.0) and np.all(both.n_arcs == 0)


def test_zero_normal_is_vacuous_or_empty_by_the_sign_of_d():
    _, args, base, _ = _base(n=50)
    keep = two_view_locus(*args, half_space_normals=[[0.0, 0.0, 0.0]], half_space_offsets=[0.0])
    np.testing.assert_array_equal(keep.n_arcs, base.n_arcs)
    np.testing.assert_allclose(keep.length, base.length, rtol=1e-12)
    drop = two_view_locus(*args, half_space_normals=[[0.0, 0.0, 0.0]], half_space_offsets=[-1e-300])
    assert np.all(drop.length == 0.0) and np.all(drop.n_arcs == 0)


def test_tangent_planes():
    """A plane touching the circle: from inside it keeps everything, from outside nothing of
    positive length (to the rounding stated in :mod:`sss_locus.geometry.halfspaces`)."""
    R, t = np.diag([-1.0, -1.0, 1.0]), np.array([10.0, 0.0, 0.0])  # circle x1 = 5, radius sqrt 75
    ap = Aperture(360.0, 180.0, 150.0)
    rho = np.sqrt(75.0)
    base = two_view_locus(R, t, 10.0, 10.0, ap, ap)
    assert base.length == pytest.approx(TWO_PI * rho)
    for normal in ([0.0, 1.0, 0.0], [0.0, 0.6, 0.8], [0.3, 0.0, 1.0]):
        n = np.array(normal)
        reach = rho * np.hypot(n[1], n[2])  # max of n . (p - c) over the circle
        inside = two_view_locus(R, t, 10.0, 10.0, ap, ap, half_space_normals=[n],
                                half_space_offsets=[n[0] * 5.0 + reach])
        outside = two_view_locus(R, t, 10.0, 10.0, ap, ap, half_space_normals=[n],
                                 half_space_offsets=[n[0] * 5.0 - reach])
        assert inside.length == pytest.approx(base.length, rel=1e-7) and inside.n_arcs == 1
        assert outside.length <= 1e-7 * rho


def test_view_swap_with_half_spaces_carried_to_frame_2():
    """n . p1 <= d is (R n) . p2 <= d + (R n) . t: the swapped problem has the same length."""
    c, args, _, rng = _base(family="edgetech-edgetech", n=300, seed=5)
    R, t, r1, r2, k1, k2 = args
    normals = rng.normal(size=(300, 2, 3))
    offsets = np.einsum("nkj,nj->nk", normals, c["p1"]) + rng.normal(size=(300, 2)) * 5.0
    one = two_view_locus(*args, half_space_normals=normals, half_space_offsets=offsets)
    n2 = np.einsum("nij,nkj->nki", R, normals)
    d2 = offsets + np.einsum("nkj,nj->nk", n2, t)
    Rs = np.transpose(R, (0, 2, 1))
    two = two_view_locus(Rs, -np.einsum("nij,nj->ni", Rs, t), r2, r1, k2, k1,
                         half_space_normals=n2, half_space_offsets=d2)
    scale = np.maximum(r1, r2)
    np.testing.assert_allclose(one.length, two.length, rtol=1e-9, atol=1e-9 * scale.max())
    assert (one.length > 0).mean() > 0.2


def test_sea_surface_and_seafloor_helpers_against_world_coordinates():
    """The helpers' half-spaces hold exactly where world z of the point is in the water."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(3)
    W = Rotation.random(200, random_state=rng).as_matrix()
    depth = rng.uniform(0.0, 20.0, 200)
    water = depth + rng.uniform(0.5, 50.0, 200)
    p1 = rng.normal(size=(200, 3)) * 30.0
    z = -depth + np.einsum("nij,nj->ni", W, p1)[:, 2]  # world z, surface at 0
    n, d = sea_surface_half_space(depth, W)
    assert n.shape == (200, 1, 3) and d.shape == (200, 1)
    np.testing.assert_array_equal(np.einsum("nkj,nj->nk", n, p1)[:, 0] <= d[:, 0], z <= 0.0)
    n, d = max_depth_half_space(water, depth, W)
    np.testing.assert_array_equal(np.einsum("nkj,nj->nk", n, p1)[:, 0] <= d[:, 0], z >= -water)


@pytest.mark.parametrize("kwargs, match", [
    (dict(half_space_normals=[[0.0, 0.0, 1.0]]), "given together"),
    (dict(half_space_offsets=[1.0]), "given together"),
    (dict(half_space_normals=[0.0, 0.0, 1.0], half_space_offsets=[1.0]), "half_space_normals must have shape"),
    (dict(half_space_normals=[[0.0, 0.0]], half_space_offsets=[1.0]), "half_space_normals must have shape"),
    (dict(half_space_normals=[[0.0, 0.0, 1.0]] * 2, half_space_offsets=[1.0, 2.0, 3.0]), "same number K"),
    (dict(half_space_normals=[[0.0, 0.0, np.nan]], half_space_offsets=[1.0]), "half_space_normals must be finite"),
    (dict(half_space_normals=[[0.0, 0.0, 1.0]], half_space_offsets=[np.inf]), "half_space_offsets must be finite"),
    (dict(half_space_normals=[[0.0, 0.0, 1.0]], half_space_offsets=[1e200]), "half_space_offsets components"),
    (dict(half_space_normals=[[0.0, 0.0, 1.0]], half_space_offsets=1.0), "half_space_offsets must have shape"),
    (dict(half_space_normals=np.zeros((3, 1, 3)), half_space_offsets=np.zeros((3, 1))), "do not broadcast"),
    (dict(half_space_normals=np.zeros((33, 3)), half_space_offsets=np.zeros(33)), "at most 32"),
])
def test_bad_half_spaces_are_refused_naming_the_argument(kwargs, match):
    ap = Aperture(130.0, 0.27, 150.0)
    with pytest.raises(ValueError, match=match):
        two_view_locus(np.eye(3), np.zeros((2, 3)) + [0.0, 0.0, -1.0], 50.0, 50.0, ap, ap, **kwargs)


def test_helpers_refuse_bad_depths():
    with pytest.raises(ValueError, match="depth_m must be >= 0"):
        sea_surface_half_space(-1.0, np.eye(3))
    with pytest.raises(ValueError, match="water_depth_m must be > 0"):
        max_depth_half_space(0.0, 0.0, np.eye(3))
    with pytest.raises(ValueError, match=r"depth_m must lie in \[0, water_depth_m\)"):
        max_depth_half_space(10.0, 12.0, np.eye(3))
    with pytest.raises(ValueError, match="rotation must be a rotation"):
        sea_surface_half_space(1.0, 2 * np.eye(3))
