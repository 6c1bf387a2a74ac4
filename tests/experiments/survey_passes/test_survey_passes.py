"""Two-pass survey simulation (sss_locus.experiments.survey_passes.study): exact in-beam solve, visibility, rejection
accounting, determinism and the symmetries the geometry must have.

References are independent of the module's algebra: a bracketing root find of the elevation
along the track, the transducer frame rebuilt from ``Transducer.rotation``/``position_m`` and
``vehicle_attitude`` point by point, and exact invariances (mirror, view swap, heading shift)
checked configuration by configuration on sampled inputs.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from sss_locus import two_view_locus
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope, load_envelope
from sss_locus.experiments.passes.straight_pass import (REJECTION_REASONS, observe_pass, solve_in_beam, swath_m,
                                                        vehicle_attitude)
from sss_locus.experiments.survey_passes.study import simulate_passes

PLATFORMS = ("boat", "auv")


@pytest.fixture(scope="module", params=PLATFORMS)
def platform(request):
    return load_platform(request.param)


def _draw(platform, n, seed, pitch_max=15.0):
    rng = np.random.default_rng(seed)
    half_el = math.radians(platform.sonar.elevation_deg / 2)
    return dict(is_port=rng.random(n) < 0.5, heading_deg=rng.uniform(-180, 180, n),
                ground_offset_m=rng.uniform(2, 140, n), altitude_m=rng.uniform(8, 30, n),
                pitch_deg=rng.uniform(-pitch_max, pitch_max, n),
                elevation_rad=rng.uniform(-1, 1, n) * half_el)


def _feature_in_sensor(platform, c, i, s):
    """Feature (world origin) in the transducer frame, rebuilt step by step (reference)."""
    side = "port" if c["is_port"][i] else "starboard"
    tr = platform.transducers[side]
    veh = vehicle_attitude(c["heading_deg"][i], c["pitch_deg"][i], 0.0)
    h = math.radians(c["heading_deg"][i])
    along, port_dir = np.array([math.cos(h), math.sin(h), 0]), np.array([-math.sin(h), math.cos(h), 0])
    y = c["ground_offset_m"][i] * (1 if side == "port" else -1)
    ref = s * along - y * port_dir + np.array([0, 0, c["altitude_m"][i]])
    origin = ref + veh.apply(tr.position_m)
    return tr.rotation.inv().apply(veh.inv().apply(-origin))


def test_in_beam_solve_matches_root_find_and_frame(platform):
    c = _draw(platform, 60, seed=3)
    ob = observe_pass(platform, **c)
    for i in range(60):
        elev = lambda s: math.asin(_feature_in_sensor(platform, c, i, s)[2]
                                   / np.linalg.norm(_feature_in_sensor(platform, c, i, s)))
        s_ref = brentq(lambda s: elev(s) - c["elevation_rad"][i], -1e4, 1e4, xtol=1e-12)
        assert ob["s"][i] == pytest.approx(s_ref, abs=1e-7)
        p = _feature_in_sensor(platform, c, i, ob["s"][i])
        np.testing.assert_allclose(ob["p"][i], p, atol=1e-9)
        assert math.asin(p[2] / np.linalg.norm(p)) == pytest.approx(c["elevation_rad"][i], abs=1e-12)
        np.testing.assert_allclose(ob["W"][i] @ p + ob["origin"][i], 0.0, atol=1e-9)


def test_zero_elevation_is_the_linear_solution():
    rng = np.random.default_rng(0)
    a = rng.normal(size=(50, 3)) * 40
    b = rng.normal(size=(50, 3))
    b /= np.linalg.norm(b, axis=1, keepdims=True)
    s, ok = solve_in_beam(a, b, np.zeros(50))
    assert ok.all()
    np.testing.assert_allclose(s, a[:, 2] / b[:, 2], rtol=1e-12)


def test_no_unique_ping_is_flagged_not_nan():
    a = np.array([[30.0, 5.0, 2.0]])
    b = np.array([[1.0, 0.0, 0.0]])  # track parallel to the beam plane: b_z = 0
    s, ok = solve_in_beam(a, b, np.array([0.001]))
    assert not ok[0] and s[0] == 0.0


def test_swath_edges_bound_visibility(platform):
    """Just inside the level swath at zero elevation: visible; just outside: the right reason."""
    for is_port in (True, False):
        for alt in (8.0, 25.0):
            near, far = (float(v[0]) for v in swath_m(platform, [is_port], [alt]))
            kw = dict(is_port=is_port, heading_deg=30.0, altitude_m=alt, pitch_deg=0.0, elevation_rad=0.0)
            inside = observe_pass(platform, ground_offset_m=[near + 1e-6, far - 1e-6], **kw)
            assert (inside["reason"] == -1).all()
            assert np.degrees(np.abs(inside["azimuth_rad"])).max() <= platform.sonar.azimuth_deg / 2
            out = observe_pass(platform, ground_offset_m=[near - 1e-3, far + 1e-3], **kw)
            assert REJECTION_REASONS[out["reason"][0]] == "outside_azimuth"
            assert REJECTION_REASONS[out["reason"][1]] == "out_of_range"
            assert out["range_m"][1] > platform.sonar.max_range_m


def test_accepted_samples_see_the_feature_and_contain_it(platform):
    env = load_envelope(platform.key)
    s, _ = simulate_passes(platform, env, OffsetModel("independent"), [0.0, 17.0, 90.0, 180.0], 300, 5)
    half_az, half_el = platform.sonar.azimuth_deg / 2, platform.sonar.elevation_deg / 2
    for k in (1, 2):
        assert (s[f"azimuth{k}_deg"].abs() <= half_az).all()
        assert (s[f"elevation{k}_deg"].abs() <= half_el + 1e-9).all()
        assert (s[f"r{k}_m"] <= platform.sonar.max_range_m).all()
        assert s[f"pitch{k}_deg"].between(env.pitch_min_deg, env.pitch_max_deg).all()
        assert s[f"altitude{k}_m"].between(env.altitude_min_m, env.altitude_max_m).all()
    if env.same_altitude:
        assert (s["altitude1_m"] == s["altitude2_m"]).all()
    assert set(s["side1"]) == set(s["side2"]) == {"port", "starboard"}
    # the true feature is on the locus, so the locus is never empty
    assert (s["status"] == 0).all() and (s["n_arcs"] >= 1).all() and (s["locus_length_m"] > 0).all()
    assert not s.isna().any().any()


def test_fixed_side_and_level_pass1():
    pf, env = load_platform("auv"), load_envelope("auv")
    model = OffsetModel("matched", 5.0, "same", side1="port")
    s, _ = simulate_passes(pf, replace(env, level_pass1=True), model, [10.0, 120.0], 200, 3)
    assert (s["side1"] == "port").all() and (s["side2"] == "port").all()
    assert (s["pitch1_deg"] == 0).all() and s["pitch2_deg"].abs().max() > 5
    assert ((s["ground_offset2_m"] - s["ground_offset1_m"]).abs() <= 5.0).all()


def test_rejections_are_counted():
    pf = load_platform("auv")
    env = load_envelope("auv")
    _, acc = simulate_passes(pf, env, OffsetModel("matched", 60.0, "same"), [0.0, 45.0], 500, 2)
    rejected = acc[[f"rejected_{r}" for r in REJECTION_REASONS]].sum(axis=1)
    assert (acc["n_tried"] == acc["n_accepted"] + rejected).all()
    assert (acc["rejected_outside_swath"] > 0).all()
    np.testing.assert_allclose(acc["acceptance"], acc["n_accepted"] / acc["n_tried"])
    # pitch steepens the in-fan depression of a ground point (H / cos(pitch) over the offset),
    # so a pitched boat loses the inner edge of its level swath (fan edge at 50 deg below the
    # horizontal) and lengthens its ranges: both rejections appear and are counted
    boat = load_platform("boat").with_attitude_limits(pitch_max_deg=40.0)
    _, acc2 = simulate_passes(boat, load_envelope("boat").with_pitch(30.0, 30.0), OffsetModel(),
                              [30.0], 500, 2)
    assert acc2.loc[0, "rejected_outside_azimuth"] > 0
    assert acc2.loc[0, "rejected_out_of_range"] > 0


def test_determinism_prefix_and_angle_independence():
    pf, env = load_platform("auv"), load_envelope("auv")
    model = OffsetModel("matched", 10.0)
    a, acc_a = simulate_passes(pf, env, model, [0.0, 20.0], 1500, 11)
    b, acc_b = simulate_passes(pf, env, model, [0.0, 20.0], 1500, 11)
    assert a.equals(b) and acc_a.equals(acc_b)
    small, _ = simulate_passes(pf, env, model, [20.0], 700, 11)
    big20 = a[a["crossing_angle_deg"] == 20.0].reset_index(drop=True)
    assert small.equals(big20.iloc[:700].reset_index(drop=True))
    other, _ = simulate_passes(pf, env, model, [0.0, 20.0], 1500, 12)
    assert not np.allclose(other["locus_length_m"], a["locus_length_m"])


def _length(platform, p1, p2):
    """Locus length and misalignment from two observe_pass results (kernel, frame 1 -> 2)."""
    from sss_locus import elevation_misalignment

    ap = platform.sonar.aperture()
    R = np.einsum("nji,njk->nik", p2["W"], p1["W"])
    t = np.einsum("nji,nj->ni", p2["W"], p1["origin"] - p2["origin"])
    res = two_view_locus(R, t, p1["range_m"], p2["range_m"], ap, ap)
    return res.length, elevation_misalignment(R, t).misalignment_deg


def _pair(platform, seed, n=200):
    c1, c2 = _draw(platform, n, seed), _draw(platform, n, seed + 100)
    if platform.pitch_max_deg == 0:
        c1["pitch_deg"] = c2["pitch_deg"] = np.zeros(n)
    c1["heading_deg"] = np.zeros(n)
    return c1, c2


def test_port_starboard_mirror(platform):
    """Reflecting the world in the vertical plane of pass 1 swaps port and starboard, turns
    heading gamma into -gamma and flips the sign of each in-beam elevation (the starboard frame
    is the mirror image of the port frame with z reversed): lengths are unchanged."""
    c1, c2 = _pair(platform, 21)
    base = _length(platform, observe_pass(platform, **c1), observe_pass(platform, **c2))
    m1, m2 = dict(c1), dict(c2)
    for m in (m1, m2):
        m["is_port"], m["elevation_rad"] = ~m["is_port"], -m["elevation_rad"]
    m2["heading_deg"] = -c2["heading_deg"]
    mirrored = _length(platform, observe_pass(platform, **m1), observe_pass(platform, **m2))
    np.testing.assert_allclose(mirrored[0], base[0], rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(mirrored[1], base[1], atol=1e-7)


def test_view_swap_and_heading_shift(platform):
    """Exchanging the passes (gamma -> -gamma seen from pass 2) and turning both headings by the
    same angle leave length and misalignment unchanged."""
    c1, c2 = _pair(platform, 31)
    base = _length(platform, observe_pass(platform, **c1), observe_pass(platform, **c2))
    swapped = _length(platform, observe_pass(platform, **c2), observe_pass(platform, **c1))
    np.testing.assert_allclose(swapped[0], base[0], rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(swapped[1], base[1], atol=1e-7)
    turn = np.random.default_rng(4).uniform(-180, 180, len(c1["heading_deg"]))
    s1, s2 = dict(c1), dict(c2)
    s1["heading_deg"], s2["heading_deg"] = c1["heading_deg"] + turn, c2["heading_deg"] + turn
    shifted = _length(platform, observe_pass(platform, **s1), observe_pass(platform, **s2))
    np.testing.assert_allclose(shifted[0], base[0], rtol=1e-7, atol=1e-9)


def test_pitch_reversal_identity(platform):
    """The starboard ping of a pass at heading h and pitch q is the port ping of the pass at
    heading h + 180 and pitch -q along the same line (same transducer pose, same feature
    coordinates; the along-track coordinate changes sign)."""
    c = _draw(platform, 100, seed=8, pitch_max=15.0 if platform.pitch_max_deg else 0.0)
    c["is_port"] = np.zeros(100, bool)
    r = dict(c, is_port=np.ones(100, bool), heading_deg=c["heading_deg"] + 180.0, pitch_deg=-c["pitch_deg"])
    a, b = observe_pass(platform, **c), observe_pass(platform, **r)
    for k in ("W", "origin", "p"):
        np.testing.assert_allclose(b[k], a[k], atol=1e-9)
    np.testing.assert_allclose(b["s"], -a["s"], atol=1e-9)
    assert np.array_equal(a["reason"], b["reason"])


def test_nose_up_and_nose_down_pairs_agree_in_distribution():
    """Consequence of the pitch reversal: with random sides, both passes at +q or both at -q
    give the same distribution of locus length (KS test, fixed seeds)."""
    from scipy.stats import ks_2samp

    pf, env = load_platform("auv"), load_envelope("auv")
    up, _ = simulate_passes(pf, env.with_pitch(12.0, 12.0), OffsetModel(), [30.0], 3000, 1)
    down, _ = simulate_passes(pf, env.with_pitch(-12.0, -12.0), OffsetModel(), [30.0], 3000, 2)
    assert ks_2samp(up["locus_length_m"], down["locus_length_m"]).pvalue > 1e-3


def test_mirror_symmetry_of_the_simulated_curve():
    """With random sides the simulation at -gamma is the mirror image of +gamma: same
    distribution of lengths (two-sample KS test at a strict level, fixed seeds)."""
    from scipy.stats import ks_2samp

    pf, env = load_platform("boat"), load_envelope("boat")
    plus, _ = simulate_passes(pf, env, OffsetModel(), [25.0], 3000, 1)
    minus, _ = simulate_passes(pf, env, OffsetModel(), [-25.0], 3000, 2)
    assert ks_2samp(plus["locus_length_m"], minus["locus_length_m"]).pvalue > 1e-3


@pytest.mark.parametrize("kwargs, match", [
    (dict(altitude_min_m=0.0, altitude_max_m=10.0), "altitude_min_m"),
    (dict(altitude_min_m=10.0, altitude_max_m=5.0), "altitude_min_m"),
    (dict(altitude_min_m=5.0, altitude_max_m=10.0, pitch_min_deg=10.0, pitch_max_deg=-10.0), "pitch"),
    (dict(altitude_min_m=5.0, altitude_max_m=math.nan), "finite"),
])
def test_bad_envelope(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SurveyEnvelope(**kwargs)


def test_bad_inputs():
    pf = load_platform("boat")
    env = load_envelope("boat")
    with pytest.raises(ValueError, match="kind"):
        OffsetModel("nearby")
    with pytest.raises(ValueError, match="jitter_m"):
        OffsetModel("independent", 5.0)
    with pytest.raises(ValueError, match="jitter_m"):
        OffsetModel("matched", -1.0)
    with pytest.raises(ValueError, match="side_rule"):
        OffsetModel("matched", 1.0, "left")
    with pytest.raises(ValueError, match="side1"):
        OffsetModel("matched", 1.0, "same", "left")
    with pytest.raises(ValueError, match="crossing_angles_deg"):
        simulate_passes(pf, env, OffsetModel(), [200.0], 10, 0)
    with pytest.raises(ValueError, match="n_per_angle"):
        simulate_passes(pf, env, OffsetModel(), [0.0], 0, 0)
    with pytest.raises(ValueError, match="limit"):
        simulate_passes(pf, env.with_pitch(-5.0, 5.0), OffsetModel(), [0.0], 10, 0)
    with pytest.raises(ValueError, match="altitude_m"):
        simulate_passes(pf, env.with_altitude(200.0, 200.0), OffsetModel(), [0.0], 10, 0)
    with pytest.raises(ValueError, match=r"no \[envelopes.submarine\] table .*\[envelopes\] has .auv., .boat."):
        load_envelope("submarine")


@pytest.mark.parametrize("spec, expected", [
    ("independent", OffsetModel("independent")),
    ("matched:10:same", OffsetModel("matched", 10.0, "same")),
    ("matched:2.5:opposite", OffsetModel("matched", 2.5, "opposite")),
    ("matched:0:random", OffsetModel("matched", 0.0, "random")),
])
def test_offset_model_parse(spec, expected):
    assert OffsetModel.parse(spec) == expected


@pytest.mark.parametrize("spec, message", [
    ("matched", "malformed"),
    ("matched:10", "malformed"),
    ("independent:0:same", "malformed"),
    ("fixed:1:same", "malformed"),
    ("matched:ten:same", "'ten' is not a number"),
    ("matched:10:left", "'left' is not one of"),
    ("matched:-1:same", "jitter_m must be a finite number >= 0"),
    ("matched:nan:same", "jitter_m must be a finite number >= 0"),
    (3, "must be a string"),
])
def test_offset_model_parse_names_the_spec_and_the_valid_forms(spec, message):
    with pytest.raises(ValueError, match=message) as err:
        OffsetModel.parse(spec)
    assert "valid forms" in str(err.value)
