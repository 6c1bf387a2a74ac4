"""Platform specification: reading, validation, and transducer frames."""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus.experiments.datamodel.platforms import (
    PLATFORMS_FILE,
    load_platform,
    load_platforms,
    parse_platforms,
    provenance_table,
)


@pytest.fixture(scope="module")
def doc():
    with open(PLATFORMS_FILE, "rb") as fh:
        return tomllib.load(fh)


def test_shipped_platforms_match_table_one():
    platforms = load_platforms()
    assert set(platforms) >= {"boat", "auv"}
    boat, auv = platforms["boat"], platforms["auv"]
    assert (boat.sonar.azimuth_deg, boat.sonar.elevation_deg, boat.sonar.max_range_m) == (50.0, 0.5, 150.0)
    assert (auv.sonar.azimuth_deg, auv.sonar.elevation_deg, auv.sonar.max_range_m) == (130.0, 0.27, 150.0)
    assert boat.roll_max_deg == boat.pitch_max_deg == 0.0
    assert auv.roll_max_deg == 0.0 and auv.pitch_max_deg == 45.0
    assert boat.fixed_depth and not auv.fixed_depth
    assert 24.0 <= auv.transducers["port"].tilt_deg <= 27.0  # EdgeTech guide's look-down range


def test_every_number_has_source_or_assumption(doc):
    """Walk the raw TOML: every numeric leaf sits in a {value, source|assumption} table."""

    def walk(node, path):
        for key, value in node.items():
            here = f"{path}.{key}" if path else key
            if isinstance(value, dict):
                if "value" in value:
                    notes = [k for k in ("source", "assumption") if k in value]
                    assert len(notes) == 1 and value[notes[0]].strip(), here
                else:
                    walk(value, here)
            elif isinstance(value, (int, float)) and not isinstance(value, bool):
                assert here == "schema_version", f"bare number at {here}"

    walk(doc, "")
    prov = load_platform("auv").provenance
    assert prov["platforms.auv.transducers.port.tilt_deg"].startswith("source:")
    assert prov["platforms.boat.transducers.port.tilt_deg".replace("boat", "auv")]
    assert load_platform("boat").provenance["platforms.boat.transducers.port.tilt_deg"].startswith(
        "assumption:")
    table = provenance_table(load_platform("boat"))
    assert {"key", "kind", "note"} <= set(table.columns) and set(table["kind"]) <= {"source", "assumption"}


@pytest.mark.parametrize(
    "mutate, path",
    [
        (lambda d: d["platforms"]["auv"]["transducers"]["port"].pop("tilt_deg"),
         "platforms.auv.transducers.port.tilt_deg"),
        (lambda d: d["platforms"]["auv"]["transducers"]["port"]["tilt_deg"].update(value="steep"),
         "platforms.auv.transducers.port.tilt_deg.value"),
        (lambda d: d["platforms"]["auv"]["transducers"]["port"]["tilt_deg"].pop("source"),
         "platforms.auv.transducers.port.tilt_deg"),
        (lambda d: d["platforms"]["boat"]["transducers"].pop("starboard"),
         "platforms.boat.transducers.starboard"),
        (lambda d: d["platforms"]["boat"]["attitude"]["pitch_max_deg"].update(value=120.0),
         "platforms.boat.attitude.pitch_max_deg.value"),
        (lambda d: d["platforms"]["boat"].update(sonar="sonar_x"), "platforms.boat.sonar"),
        (lambda d: d["sonars"]["edgetech_2205"]["azimuth_deg"].update(value=True),
         "sonars.edgetech_2205.azimuth_deg.value"),
        (lambda d: d["platforms"]["auv"]["depth_m"]["min"].update(value=-3.0),
         "platforms.auv.depth_m.min.value"),
        (lambda d: d["platforms"]["auv"]["azimuth_positive"].update(value="sideways"),
         "platforms.auv.azimuth_positive.value"),
        (lambda d: d["platforms"]["auv"]["transducers"]["port"]["depth_m"].update(source="x"),
         "platforms.auv.transducers.port.depth_m"),
        (lambda d: d["platforms"]["auv"].update(attitude=3), "platforms.auv.attitude"),
    ],
)
def test_malformed_entries_name_the_key(doc, mutate, path):
    bad = copy.deepcopy(doc)
    mutate(bad)
    with pytest.raises(ValueError, match=path.replace(".", r"\.")):
        parse_platforms(bad)


def test_new_platform_needs_no_code(doc, tmp_path):
    extended = copy.deepcopy(doc)
    extended["platforms"]["glider"] = copy.deepcopy(doc["platforms"]["auv"])
    extended["platforms"]["glider"]["name"] = "Test glider"
    extended["platforms"]["glider"]["attitude"]["pitch_max_deg"]["value"] = 30.0
    platforms = parse_platforms(extended)
    assert platforms["glider"].pitch_max_deg == 30.0 and platforms["glider"].name == "Test glider"
    with pytest.raises(ValueError, match="platform must be one of"):
        load_platform("submarine")


def test_attitude_limit_is_a_parameter():
    auv = load_platform("auv")
    survey = auv.with_attitude_limits(pitch_max_deg=15.0)
    assert survey.pitch_max_deg == 15.0 and auv.pitch_max_deg == 45.0
    with pytest.raises(ValueError, match="pitch_max_deg"):
        auv.with_attitude_limits(pitch_max_deg=-1.0)


@pytest.mark.parametrize("key", ["boat", "auv"])
def test_port_transducer_frame(key):
    tr = load_platform(key).transducers["port"]
    M = tr.rotation.as_matrix()  # columns: sensor axes in the vehicle frame
    x, y, z = M[:, 0], M[:, 1], M[:, 2]
    tau = math.radians(tr.tilt_deg)
    assert x[1] > 0 and x[2] < 0  # outward to port, tilted down
    assert math.isclose(math.degrees(math.asin(-x[2])), tr.tilt_deg, abs_tol=1e-9)
    assert abs(x[0]) < 1e-12 and abs(y[0]) < 1e-12  # the fan is across-track and vertical
    assert np.allclose(np.abs(z), [1.0, 0.0, 0.0])  # elevation axis is along-track
    # positive azimuth points further down ("down" convention): depression grows with theta
    for theta in (-10.0, 0.0, 10.0):
        th = math.radians(theta)
        d = tr.rotation.apply([math.cos(th), math.sin(th), 0.0])
        assert math.isclose(-d[2], math.sin(tau + th), abs_tol=1e-12)
    # an independent construction: yaw +90 (boresight to port), roll -90 about the boresight
    # (sensor y down), then tilt about the vehicle's forward axis by -tilt
    ref = (Rotation.from_rotvec([-tau, 0, 0]) * Rotation.from_rotvec([0, 0, math.pi / 2])
           * Rotation.from_rotvec([-math.pi / 2, 0, 0]))
    assert np.allclose(ref.as_matrix(), M, atol=1e-12)


@pytest.mark.parametrize("key", ["boat", "auv"])
def test_starboard_is_mirror_of_port(key):
    p = load_platform(key)
    port, stbd = p.transducers["port"], p.transducers["starboard"]
    mirror = np.diag([1.0, -1.0, 1.0])
    # reflecting the port frame through the x-z plane and flipping its z axis (to stay
    # right-handed) gives the starboard frame
    expect = mirror @ port.rotation.as_matrix() @ np.diag([1.0, 1.0, -1.0])
    assert np.allclose(stbd.rotation.as_matrix(), expect, atol=1e-12)
    assert np.allclose(stbd.position_m, mirror @ port.position_m)
    assert port.position_m[1] >= 0 and stbd.position_m[1] <= 0


def test_up_convention_flips_azimuth():
    import dataclasses

    tr = load_platform("auv").transducers["port"]
    up = dataclasses.replace(tr, azimuth_positive="up")
    d_down = tr.rotation.apply([math.cos(0.2), math.sin(0.2), 0.0])
    d_up = up.rotation.apply([math.cos(0.2), math.sin(0.2), 0.0])
    assert d_up[2] > tr.rotation.apply([1.0, 0, 0])[2] > d_down[2]
    assert np.allclose(up.rotation.apply([1.0, 0, 0]), tr.rotation.apply([1.0, 0, 0]))


def test_frustum_points_lie_in_the_aperture():
    from sss_locus.experiments.datamodel.platforms import frustum_points

    pf = load_platform("auv")
    tr = pf.transducers["starboard"]
    pts = frustum_points(pf.sonar, tr, 2.0, n=9)
    assert np.allclose(pts[0], tr.position_m)
    local = tr.rotation.inv().apply(pts[1:] - tr.position_m)
    assert np.allclose(np.linalg.norm(local, axis=1), 2.0)
    from sss_locus import Aperture

    loose = Aperture(pf.sonar.azimuth_deg + 1e-6, pf.sonar.elevation_deg + 1e-6, 2.0 + 1e-9)
    assert loose.contains(local).all()
    # the fan's deepest ray is at depression tilt + azimuth/2 below the horizontal
    depth = -(pts[1:, 2] - tr.position_m[2])
    expect = 2.0 * math.sin(math.radians(min(90.0, tr.tilt_deg + pf.sonar.azimuth_deg / 2)))
    assert depth.max() == pytest.approx(expect, rel=1e-3)
    with pytest.raises(ValueError, match="plot_range_m"):
        frustum_points(pf.sonar, tr, -1.0)


def test_tilt_override():
    boat = load_platform("boat")
    steep = boat.with_tilt(40.0)
    assert all(t.tilt_deg == 40.0 for t in steep.transducers.values())
    assert boat.transducers["port"].tilt_deg == 25.0
    d = steep.transducers["port"].rotation.apply([1.0, 0.0, 0.0])
    assert math.degrees(math.asin(-d[2])) == pytest.approx(40.0)
    with pytest.raises(ValueError, match="tilt_deg"):
        boat.with_tilt(120.0)
