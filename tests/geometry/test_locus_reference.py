"""The exact kernel against the independent brute-force reference (tests/reference_locus.py).

What is compared
    For every aperture family in ``reference_locus.APERTURE_FAMILIES`` (the two Table I sonars,
    a mixed pair, an azimuth wider than 180 deg and a full 360 deg fan, wide elevations where
    multi-arc loci are common, nonzero minimum ranges) the kernel's ``length`` must agree with
    the reference to a relative 1e-9 and its ``n_arcs`` must be identical, on
    ``N_SEEDED`` feature-seeded configurations (non-empty by construction) plus ``N_RANDOM``
    fully random poses (mostly empty loci, some ranges out of range) per family.

Reference resolution and the one exclusion rule
    The reference walks the circle at ``REFERENCE_STEPS`` equally spaced angles (step
    2 pi / 2**16 = 9.6e-5 rad) and bisects every in/out transition to machine precision. A
    walk can miss an arc, or a gap between two arcs, that is shorter than one step. A
    configuration is therefore excluded from the comparison ONLY when the KERNEL reports an
    arc or an inter-arc gap (cyclically, including the gap of a single arc) shorter than
    ``EXCLUDE_BELOW_STEPS`` reference steps. The excluded fraction is asserted to stay below
    ``MAX_EXCLUDED_FRACTION``: a kernel that emits spurious tiny arcs or splits arcs with
    spurious tiny gaps cannot hide behind the exclusion. Arcs the kernel MISSES are never
    excluded (the rule looks only at what the kernel reports).

Counts: 8 families x (250 seeded + 100 random) = 2,800 configurations, plus every 3- and
4-arc locus among 20,000 draws of the "fragmenting" family (about 250), plus closed-form
cases. Runtime: about 15 s of CPU on one core (the walk dominates).
"""

from __future__ import annotations

import numpy as np
import pytest

from reference_locus import (
    APERTURE_FAMILIES,
    ApertureSpec,
    circle_from_spheres,
    feature_seeded_configs,
    random_pose_configs,
    reference_locus,
)
from sss_locus import Aperture, LocusStatus, two_view_locus

REFERENCE_STEPS = 2**16
EXCLUDE_BELOW_STEPS = 10
MAX_EXCLUDED_FRACTION = 0.02
N_SEEDED = 250
N_RANDOM = 100
RTOL = 1e-9
TWO_PI = 2.0 * np.pi


def kernel_shortest_feature(result) -> np.ndarray:
    """Shortest arc or inter-arc gap (radians) the kernel reports, per configuration.

    Infinity where there are no arcs or the single arc is the full circle.
    """
    width = result.arc_start.shape[-1]  # MAX_ARCS, plus K with K extra half-spaces
    start = np.asarray(result.arc_start, dtype=float).reshape(-1, width)
    end = np.asarray(result.arc_end, dtype=float).reshape(-1, width)
    n_arcs = np.asarray(result.n_arcs).reshape(-1)
    out = np.full(n_arcs.shape, np.inf)
    for i, n in enumerate(n_arcs):
        if n == 0:
            continue
        s = start[i, :n]
        e = end[i, :n]
        order = np.argsort(s)
        s, e = s[order], e[order]
        widths = e - s
        gaps = np.append(s[1:] - e[:-1], s[0] + TWO_PI - e[-1])
        features = np.concatenate([widths, gaps])
        if n == 1 and widths[0] >= TWO_PI * (1 - 1e-15):
            continue  # the full circle: no boundary at all
        out[i] = features.min()
    return out


def _aperture_pair(family):
    a1, a2 = APERTURE_FAMILIES[family]
    return (Aperture(*a1), Aperture(*a2)), (ApertureSpec(*a1), ApertureSpec(*a2))


@pytest.fixture(scope="module", params=sorted(APERTURE_FAMILIES))
def comparison(request):
    """Kernel and reference results for one aperture family (computed once per module)."""
    family = request.param
    (k1, k2), (s1, s2) = _aperture_pair(family)
    seed = sorted(APERTURE_FAMILIES).index(family)
    rng = np.random.default_rng([20261121, seed])
    seeded = feature_seeded_configs(rng, N_SEEDED, APERTURE_FAMILIES[family][0], APERTURE_FAMILIES[family][1])
    random = random_pose_configs(rng, N_RANDOM, APERTURE_FAMILIES[family][0], APERTURE_FAMILIES[family][1])
    R = np.concatenate([seeded["R"], random["R"]])
    t = np.concatenate([seeded["t"], random["t"]])
    r1 = np.concatenate([seeded["r1"], random["r1"]])
    r2 = np.concatenate([seeded["r2"], random["r2"]])
    is_seeded = np.arange(len(r1)) < N_SEEDED

    kernel = two_view_locus(R, t, r1, r2, k1, k2)
    shortest = kernel_shortest_feature(kernel)
    excluded = shortest < EXCLUDE_BELOW_STEPS * TWO_PI / REFERENCE_STEPS

    ref_length = np.full(len(r1), np.nan)
    ref_arcs = np.full(len(r1), -1)
    for i in np.nonzero(~excluded)[0]:
        ref = reference_locus(R[i], t[i], r1[i], r2[i], s1, s2, n_steps=REFERENCE_STEPS)
        ref_length[i] = ref.length
        ref_arcs[i] = ref.n_arcs
    return {
        "family": family,
        "R": R,
        "t": t,
        "r1": r1,
        "r2": r2,
        "apertures": (k1, k2),
        "kernel": kernel,
        "excluded": excluded,
        "is_seeded": is_seeded,
        "ref_length": ref_length,
        "ref_arcs": ref_arcs,
    }


def _describe(c, idx, limit=3):
    lines = []
    for i in idx[:limit]:
        lines.append(
            f"  R={c['R'][i].tolist()!r}\n  t={c['t'][i].tolist()!r} r1={c['r1'][i]!r} "
            f"r2={c['r2'][i]!r} apertures={c['apertures']}\n"
            f"  kernel length={c['kernel'].length[i]!r} n_arcs={c['kernel'].n_arcs[i]} "
            f"status={c['kernel'].status[i]}; reference length={c['ref_length'][i]!r} "
            f"n_arcs={c['ref_arcs'][i]}"
        )
    return "\n".join(lines)


def test_excluded_fraction_is_small(comparison):
    frac = comparison["excluded"].mean()
    assert frac < MAX_EXCLUDED_FRACTION, (
        f"{comparison['family']}: {frac:.1%} of configurations have a kernel arc or gap shorter "
        f"than {EXCLUDE_BELOW_STEPS} reference steps"
    )


def _assert_agrees(c, field, reference, differs, what):
    """Compare kernel ``field`` with the reference on the non-excluded configurations."""
    keep = ~c["excluded"]
    bad = differs(np.asarray(getattr(c["kernel"], field))[keep], c[reference][keep])
    idx = np.nonzero(keep)[0][bad]
    assert not bad.any(), (
        f"{c['family']}: {bad.sum()} of {keep.sum()} {what}:\n{_describe(c, idx)}"
    )


def test_length_matches_reference(comparison):
    _assert_agrees(
        comparison, "length", "ref_length",
        lambda got, want: ~np.isclose(got, want, rtol=RTOL, atol=0.0),
        f"lengths differ from the reference by more than rtol={RTOL}",
    )


def test_arc_count_matches_reference(comparison):
    _assert_agrees(
        comparison, "n_arcs", "ref_arcs", lambda got, want: got != want,
        "arc counts differ from the reference",
    )


def test_circle_matches_two_sphere_construction(comparison):
    """Status, centre, normal and radius against the reference's two-sphere circle."""
    c = comparison
    k = c["kernel"]
    for i in range(len(c["r1"])):
        kind, center, radius, _, _ = circle_from_spheres(c["R"][i], c["t"][i], c["r1"][i], c["r2"][i])
        r_max = max(c["r1"][i], c["r2"][i])
        if kind != "circle" or radius < 1e-2 * r_max:
            continue  # degenerate / ill-conditioned circles: test_locus_degenerate.py
        assert k.exists[i] and k.status[i] in (LocusStatus.CIRCLE, LocusStatus.OUT_OF_RANGE)
        assert k.radius[i] == pytest.approx(radius, rel=1e-10)
        np.testing.assert_allclose(k.center[i], center, rtol=0, atol=1e-10 * r_max)
        s = -c["R"][i].T @ c["t"][i]
        assert abs(abs(k.normal[i] @ s) / np.linalg.norm(s) - 1.0) < 1e-12


def test_comparison_exercises_what_it_claims(comparison):
    """Feature-seeded loci are non-empty; wide-elevation families do produce multi-arc loci."""
    c = comparison
    length = np.asarray(c["kernel"].length)
    n_arcs = np.asarray(c["kernel"].n_arcs)
    seeded = c["is_seeded"]
    # By construction a feature lies inside both apertures: the reference agrees the locus
    # is non-empty for (practically) all seeded configurations.
    ref_nonempty = c["ref_length"][seeded & ~c["excluded"]] > 0
    assert ref_nonempty.mean() > 0.99
    assert (length[seeded] > 0).mean() > 0.99
    wide_elevation = min(a.elevation_deg for a in c["apertures"]) >= 30.0
    if wide_elevation:
        assert (n_arcs > 1).sum() >= 10, f"{c['family']}: only {(n_arcs > 1).sum()} multi-arc loci"
    # the random poses include empty loci and out-of-range measurements
    assert (length[~seeded] == 0).any()


def test_multi_arc_loci_occur_for_narrow_beams_too():
    """The Table I sonars also fragment sometimes (the paper's orange points, Fig. 3c)."""
    rng = np.random.default_rng(7)
    a = APERTURE_FAMILIES["edgetech-edgetech"][0]
    cfg = feature_seeded_configs(rng, 20000, a, a)
    res = two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], Aperture(*a), Aperture(*a))
    n_multi = int((np.asarray(res.n_arcs) > 1).sum())
    assert n_multi > 0
    # and the reference confirms the first few of them
    s = ApertureSpec(*a)
    for i in np.nonzero(np.asarray(res.n_arcs) > 1)[0][:5]:
        ref = reference_locus(cfg["R"][i], cfg["t"][i], cfg["r1"][i], cfg["r2"][i], s, s)
        assert ref.n_arcs == res.n_arcs[i]
        assert ref.length == pytest.approx(res.length[i], rel=RTOL)


def test_three_and_four_arc_loci_match_reference():
    """Loci with 3+ arcs are rare; draw many configurations and check every such one.

    Selecting on the kernel's own n_arcs only picks WHICH configurations to check; the
    random-family comparison above covers kernels that under-count arcs.
    """
    family = "fragmenting"
    (k1, k2), (s1, s2) = _aperture_pair(family)
    rng = np.random.default_rng(11)
    cfg = feature_seeded_configs(rng, 20000, *APERTURE_FAMILIES[family])
    res = two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], k1, k2)
    shortest = kernel_shortest_feature(res)
    pick = np.nonzero((np.asarray(res.n_arcs) >= 3))[0]
    excluded = shortest[pick] < EXCLUDE_BELOW_STEPS * TWO_PI / REFERENCE_STEPS
    assert len(pick) >= 100 and (np.asarray(res.n_arcs)[pick] >= 4).any()
    assert excluded.mean() < 0.05  # short arcs are more common among many-arc loci
    for i in pick[~excluded]:
        ref = reference_locus(cfg["R"][i], cfg["t"][i], cfg["r1"][i], cfg["r2"][i], s1, s2, n_steps=REFERENCE_STEPS)
        where = f"R={cfg['R'][i].tolist()} t={cfg['t'][i].tolist()} r1={cfg['r1'][i]} r2={cfg['r2'][i]}"
        assert res.n_arcs[i] == ref.n_arcs, where
        assert res.length[i] == pytest.approx(ref.length, rel=RTOL), where


# --- closed-form cases: check the kernel AND the reference against pencil-and-paper answers ---


def _front_to_front():
    """Sensor 2 at s = (10, 0, 0) in frame 1 facing sensor 1 (R = Rz(pi)), r1 = r2 = 10.

    The circle is x1 = 5, radius sqrt(75): p1(a) = (5, rho cos a, rho sin a). In frame 2,
    p2 = (5, -rho cos a, rho sin a), so both sensors see the same azimuth and elevation
    magnitudes.
    """
    R = np.diag([-1.0, -1.0, 1.0])
    t = np.array([10.0, 0.0, 0.0])  # p2 = R p1 + t puts sensor 2's origin at (10, 0, 0)
    return R, t


@pytest.mark.parametrize("azimuth_deg", [110.0, 100.0, 130.0, 125.0])
def test_closed_form_azimuth_crop(azimuth_deg):
    """|atan2(rho cos a, 5)| <= az/2  <=>  |cos a| <= 5 tan(az/2) / rho: length 4 rho asin(c)."""
    R, t = _front_to_front()
    rho = np.sqrt(75.0)
    c = 5.0 * np.tan(np.deg2rad(azimuth_deg) / 2.0) / rho
    if c >= 1.0:
        want_length, want_arcs = 2.0 * np.pi * rho, 1
    else:
        want_length, want_arcs = 4.0 * rho * np.arcsin(c), 2
    ap = (azimuth_deg, 180.0, 150.0)
    res = two_view_locus(R, t, 10.0, 10.0, Aperture(*ap), Aperture(*ap))
    ref = reference_locus(R, t, 10.0, 10.0, ApertureSpec(*ap), ApertureSpec(*ap))
    assert res.status == LocusStatus.CIRCLE
    assert res.radius == pytest.approx(rho, rel=1e-14)
    assert res.length == pytest.approx(want_length, rel=1e-12)
    assert res.n_arcs == want_arcs
    assert ref.length == pytest.approx(want_length, rel=1e-12)
    assert ref.n_arcs == want_arcs


@pytest.mark.parametrize("azimuth_deg", [360.0, 100.0])
@pytest.mark.parametrize("elevation_deg", [0.27, 30.0, 100.0])
def test_closed_form_elevation_and_azimuth_crop(azimuth_deg, elevation_deg):
    """Elevation |asin(rho sin a / 10)| <= el/2  <=>  |sin a| <= 10 sin(el/2) / rho.

    Sensor 1 has (azimuth_deg, elevation_deg); sensor 2 sees everything. With c1 the azimuth
    bound on |cos a| and c2 the elevation bound on |sin a|, the inside set is
    {|cos a| <= c1} n {|sin a| <= c2}: per quadrant asin(c1) + asin(c2) - pi/2 when positive.
    """
    R, t = _front_to_front()
    rho = np.sqrt(75.0)
    c1 = 5.0 * np.tan(np.deg2rad(azimuth_deg) / 2.0) / rho if azimuth_deg < 180 else np.inf
    c2 = 10.0 * np.sin(np.deg2rad(elevation_deg) / 2.0) / rho
    a1 = np.pi / 2 if c1 >= 1 else np.arcsin(c1)
    a2 = np.pi / 2 if c2 >= 1 else np.arcsin(c2)
    per_quadrant = a1 + a2 - np.pi / 2
    if c1 >= 1 and c2 >= 1:
        want_length, want_arcs = 2 * np.pi * rho, 1
    elif c1 >= 1:  # elevation only: arcs around a = 0 and a = pi
        want_length, want_arcs = 4 * rho * a2, 2
    else:  # both bind: one arc per quadrant
        want_length, want_arcs = 4 * rho * max(per_quadrant, 0.0), 4 if per_quadrant > 0 else 0
    ap1 = (azimuth_deg, elevation_deg, 150.0)
    ap2 = (360.0, 180.0, 150.0)
    res = two_view_locus(R, t, 10.0, 10.0, Aperture(*ap1), Aperture(*ap2))
    ref = reference_locus(R, t, 10.0, 10.0, ApertureSpec(*ap1), ApertureSpec(*ap2))
    assert res.length == pytest.approx(want_length, rel=1e-12, abs=1e-12)
    assert res.n_arcs == want_arcs
    assert ref.length == pytest.approx(want_length, rel=1e-12, abs=1e-12)
    assert ref.n_arcs == want_arcs
