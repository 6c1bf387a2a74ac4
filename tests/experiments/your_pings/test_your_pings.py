"""Your own pings: CSV and XTF readers, per-feature results (independent references: the
simulator's truth, hand-built level passes on a flat seafloor, pyproj geodesics)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.sonar_files import observations as ob
from sss_locus.experiments.sonar_files import observations_xtf as ox
from sss_locus.experiments.your_pings import study as yp
from sss_locus.experiments.your_pings import example as ex
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.terrain import flat_terrain, load_terrain_config, terrain_from_config
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout

FRAME = ob.LocalFrame(-70.0, 43.0)
LAYOUT = SurveyLayout(area_m=200.0, line_spacing_m=50.0, cross_line_spacing_m=100.0, margin_m=40.0)


@pytest.fixture(scope="module")
def auv():
    return load_platform("auv")


def _sim(auv, terrain=None, **kw):
    terrain = terrain or terrain_from_config("random", load_terrain_config(), extent_m=600.0, seed=2)
    kw = {"n_features": 6, "altitude_m": 15.0, "seed": 4, "frame": FRAME, **kw}
    return ex.simulate(auv, terrain, LAYOUT, **kw)


def _exact_csv(path, sights):
    """Sightings with their exact slant ranges (no sample quantisation)."""
    keep = sights.drop(columns=["sample", "range_setting_m", "n_samples", "east_m", "north_m", "grid_heading_deg"])
    ex.write_csv(path, keep)


def test_xtf_written_with_pyxtf_reads_back(tmp_path):
    pings = pd.DataFrame({"ping": [7, 8, 9], "lon_deg": [-70.001, -70.0, -69.999], "lat_deg": [43.0, 43.0005, 43.001],
                          "depth_m": [20.5, 21.0, 19.25], "altitude_m": [14.1, 15.2, 16.3],
                          "heading_deg": [10.3, 190.7, 271.1], "pitch_deg": [1.5, -2.0, 0.0], "roll_deg": [0.2, -0.4, 3.0],
                          "time_s": [36000.0, 36001.5, 36003.25], "range_setting_m": 150.0, "n_samples": 500})
    ox.write_xtf(tmp_path / "a.xtf", pings)
    header, got = ox.read_pings(tmp_path / "a.xtf")
    assert header.NavUnits == 3 and sorted(got) == [7, 8, 9]
    import pyxtf  # an independent reader: pyxtf's own

    _, packets = pyxtf.xtf_read(str(tmp_path / "a.xtf"))
    for ping in packets[pyxtf.XTFHeaderType.sonar]:
        row = pings.set_index("ping").loc[ping.PingNumber]
        assert ping.SensorXcoordinate == row.lon_deg and ping.SensorYcoordinate == row.lat_deg
        for field, col in (("SensorDepth", "depth_m"), ("SensorPrimaryAltitude", "altitude_m"),
                           ("SensorHeading", "heading_deg"), ("SensorPitch", "pitch_deg"), ("SensorRoll", "roll_deg")):
            assert getattr(ping, field) == np.float32(row[col])
        assert ox.ping_time_s(ping) == row.time_s
        assert [c.NumSamples for c in ping.ping_chan_headers] == [500, 500] and len(ping.data[1]) == 500


def test_csv_and_xtf_give_identical_results(tmp_path, auv):
    sights, _ = _sim(auv)
    paths = {}
    ex.write_csv(tmp_path / "s.csv", sights.drop(columns=list(ex.CHECK_COLUMNS)))
    pings, matches = ex.xtf_tables(sights, "s.xtf")
    ox.write_xtf(tmp_path / "s.xtf", pings)
    ex.write_csv(tmp_path / "m.csv", matches)
    a, b = (yp.run(tmp_path / n, auv, aperture_margin_deg=10.0) for n in ("s.csv", "m.csv"))
    pd.testing.assert_frame_equal(a.features, b.features)
    pd.testing.assert_frame_equal(a.locus, b.locus)
    assert a.features["nview_status"].isin(["resolved", "ambiguous"]).any()  # the comparison is not vacuous


def test_noise_free_sightings_recover_the_truth(tmp_path, auv):
    sights, truth = _sim(auv, noise=False, float32=False)
    _exact_csv(tmp_path / "s.csv", sights)
    res = yp.run(tmp_path / "s.csv", auv, FRAME)
    f = res.features.merge(truth, on="feature")
    ok = f["nview_status"] == "resolved"
    assert ok.sum() >= 4
    est = f.loc[ok, ["nview_east_m", "nview_north_m", "nview_up_m"]].to_numpy()
    true = f.loc[ok, ["east_m", "north_m", "up_m"]].to_numpy()
    scale = np.max(res.sightings["slant_range_m"])
    assert np.max(np.abs(est - true)) <= 1e-9 * scale
    # the truth lies on the first two sightings' circle: its distance to the locus arcs' points
    # is at most the spacing of those points
    loc = res.locus.merge(truth, on="feature", suffixes=("", "_true"))
    d = np.linalg.norm(loc[["east_m", "north_m", "up_m"]].to_numpy() - loc[["east_m_true", "north_m_true", "up_m_true"]].to_numpy(), axis=1)
    assert pd.Series(d).groupby(loc["feature"]).min().max() < 0.05


def _level_passes(auv, feature, passes, surface_depth=0.0):
    """Sightings of ``feature`` (local frame) by level passes (heading, side, ground offset, depth)
    at the ping where it lies in the zero-elevation plane."""
    from scipy.spatial.transform import Rotation

    rows = []
    for heading, side, g, depth in passes:
        tr = auv.transducers[side]
        Rv = Rotation.from_euler("Z", 90.0 - heading, degrees=True).as_matrix()
        s = 1.0 if side == "port" else -1.0
        ref = feature - Rv @ np.array([tr.position_m[0], s * g, 0.0])
        ref[2] = -depth
        o = ref + Rv @ tr.position_m
        rows.append({"feature": "A", "platform": auv.key, "side": side, "east_m": ref[0], "north_m": ref[1],
                     "depth_m": depth, "altitude_m": ref[2] - feature[2], "heading_deg": heading,
                     "pitch_deg": 0.0, "roll_deg": 0.0, "slant_range_m": np.linalg.norm(feature - o)})
    return pd.DataFrame(rows)


def test_flat_seafloor_position_is_exact_on_a_flat_seafloor(tmp_path, auv):
    feature = np.array([12.0, -7.0, -40.0])
    table = _level_passes(auv, feature, [(0.0, "port", 30.0, 20.0), (90.0, "starboard", 45.0, 25.0),
                                         (225.0, "port", 60.0, 22.0), (300.0, "starboard", 20.0, 30.0)])
    ex.write_csv(tmp_path / "s.csv", table)
    res = yp.run(tmp_path / "s.csv", auv)
    flat = res.sightings[["flat_east_m", "flat_north_m", "flat_up_m"]].to_numpy()
    assert np.max(np.abs(flat - feature)) <= 1e-9 * 100
    assert res.features["flat_spread_m"].iloc[0] <= 1e-9 * 100


def test_lonlat_and_local_metres_give_the_same_results(tmp_path, auv):
    sights, _ = _sim(auv, float32=False)
    base = sights.drop(columns=["sample", "range_setting_m", "n_samples"])
    ex.write_csv(tmp_path / "geo.csv", base.drop(columns=["east_m", "north_m", "grid_heading_deg"]))
    local = base.drop(columns=["lon_deg", "lat_deg", "heading_deg"]).rename(columns={"grid_heading_deg": "heading_deg"})
    ex.write_csv(tmp_path / "local.csv", local)
    a = yp.run(tmp_path / "geo.csv", auv, FRAME, aperture_margin_deg=10.0)
    b = yp.run(tmp_path / "local.csv", auv, FRAME, aperture_margin_deg=10.0)
    num = [c for c in a.features.columns if a.features[c].dtype.kind == "f"]
    np.testing.assert_allclose(a.features[num], b.features[num], rtol=1e-9, atol=1e-9 * 150)
    assert (a.features["nview_status"] == b.features["nview_status"]).all()


def test_grid_heading_follows_the_geodesic():
    """A heading is turned into the grid azimuth of the projected geodesic (pyproj's Geod)."""
    from pyproj import Geod

    lon, lat = np.array([-70.3, -69.6, -70.0]), np.array([43.2, 42.7, 43.0])
    for h in (0.0, 37.0, 250.0):
        lo2, la2, _ = Geod(ellps="WGS84").fwd(lon, lat, np.full(3, h), np.full(3, 1.0))
        x1, y1 = FRAME.to_local(lon, lat)
        x2, y2 = FRAME.to_local(lo2, la2)
        az = np.degrees(np.arctan2(x2 - x1, y2 - y1))
        np.testing.assert_allclose(np.mod(FRAME.grid_heading_deg(h, lon, lat) - az + 180, 360) - 180, 0, atol=1e-5)


GOOD = ("feature,platform,side,east_m,north_m,depth_m,altitude_m,heading_deg,pitch_deg,roll_deg,slant_range_m\n"
        "A,auv,port,0,0,20,15,0,0,0,30\nA,auv,starboard,10,5,20,15,90,0,0,35\n")


@pytest.mark.parametrize("edit, where", [
    (lambda t: t.replace(",slant_range_m\n", ",slant_range_ft\n"), "line 2, column slant_range_ft: wrong unit"),
    (lambda t: t.replace("heading_deg,", "").replace(",0,0,0,30", ",0,0,30").replace(",90,0,0,35", ",0,0,35"),
     "line 2, column heading_deg: missing"),
    (lambda t: t.replace(",90,0,0,35", ",nan,0,0,35"), "line 4, column heading_deg: must be a finite number"),
    (lambda t: t.replace(",15,90,", ",-3,90,"), "line 4, column altitude_m: must be a finite number in"),
    (lambda t: t.replace("starboard", "stbd"), "line 4, column side: must be one of"),
    (lambda t: t.replace(",pitch_deg,roll_deg", "").replace(",0,0,0,30", ",0,30").replace(",90,0,0,35", ",90,35"),
     "line 2, column pitch_deg: missing"),
])
def test_malformed_csv_refused_in_one_line(tmp_path, edit, where):
    (tmp_path / "s.csv").write_text("# a comment line\n" + edit(GOOD))
    with pytest.raises(ob.ObservationError) as err:
        ob.read_sightings(tmp_path / "s.csv")
    msg = str(err.value)
    assert "\n" not in msg and msg.startswith("s.csv ") and where in msg


def test_missing_attitude_is_an_explicit_choice(tmp_path):
    text = GOOD.replace(",90,0,0,35", ",90,,,35")
    (tmp_path / "s.csv").write_text(text)
    with pytest.raises(ob.ObservationError, match="line 3, column pitch_deg"):
        ob.read_sightings(tmp_path / "s.csv")
    t = ob.read_sightings(tmp_path / "s.csv", missing_attitude="level")
    assert t["attitude_assumed"].tolist() == [False, True] and t["pitch_deg"].tolist() == [0.0, 0.0]


def test_malformed_xtf_refused_in_one_line(tmp_path, auv):
    sights, _ = _sim(auv, n_features=2)
    pings, matches = ex.xtf_tables(sights, "s.xtf")
    ox.write_xtf(tmp_path / "s.xtf", pings)
    bad = matches.copy()
    bad.loc[1, "ping"] = 999
    ex.write_csv(tmp_path / "m.csv", bad)
    with pytest.raises(ob.ObservationError, match=r"^m.csv line 4, column ping: ping 999 is not in s.xtf \(its pings run 0 to"):
        ox.read_xtf_sightings(tmp_path / "m.csv")
    ex.write_csv(tmp_path / "m.csv", matches)
    data = (tmp_path / "s.xtf").read_bytes()
    (tmp_path / "s.xtf").write_bytes(data[:-100])
    with pytest.raises(ob.ObservationError) as err:
        ox.read_xtf_sightings(tmp_path / "m.csv")
    # a file cut inside its last packet is now read up to it: the sighting of the lost ping is refused,
    # saying the file is cut short, where it was cut and how much is missing (it was refused whole)
    assert "ping 12 is not in s.xtf (its pings run 0 to 11; s.xtf is truncated: the packet at byte" in str(err.value)
    assert "(100 bytes missing); read the 12 complete pings before it" in str(err.value)
    assert "\n" not in str(err.value)


def test_observations_parameter_is_resolved_and_hashed(tmp_path, monkeypatch, auv):
    """The runner's observations parameter: a path relative to the current directory or the
    repository, and a hash that changes with the bytes of the file and of the XTF files it names."""
    from sss_locus.pipeline.run.userfiles import observation_parameters

    shipped = observation_parameters("data/examples/your_pings/example_sightings.csv")
    assert shipped["observations"] == "data/examples/your_pings/example_sightings.csv"
    sights, _ = _sim(auv, n_features=2)
    pings, matches = ex.xtf_tables(sights, "s.xtf")
    ox.write_xtf(tmp_path / "s.xtf", pings)
    ex.write_csv(tmp_path / "m.csv", matches)
    monkeypatch.chdir(tmp_path)
    first = observation_parameters("m.csv")
    assert observation_parameters('"m.csv"') == first  # the command line's quoted form
    assert first["observations"] == str(tmp_path / "m.csv")
    data = bytearray((tmp_path / "s.xtf").read_bytes())
    data[-1] ^= 1
    (tmp_path / "s.xtf").write_bytes(bytes(data))
    assert observation_parameters("m.csv")["observations_sha256"] != first["observations_sha256"]


def test_a_user_survey_is_not_the_reproduction():
    from sss_locus.pipeline.book.areas import differs_from_paper
    from sss_locus.pipeline.run.registry import load_registry

    entry = load_registry()["your_pings"]
    assert differs_from_paper(entry, {"observations": "data/examples/your_pings/example_sightings.csv"}) == []
    why = differs_from_paper(entry, {"observations": "/somewhere/my_sightings.csv"})
    assert why and "my_sightings.csv" in why[0]


def test_geojson_loci_and_points(auv):
    from sss_locus.experiments.your_pings import files as yf

    sights, truth = _sim(auv, noise=False, float32=False)
    table, frame = ob.to_local_frame(ob.parse_sightings(
        sights.drop(columns=["sample", "range_setting_m", "n_samples", "east_m", "north_m", "grid_heading_deg"])
        .astype(str), "sim"), FRAME)
    res = yp.analyse(table, auv, frame)
    doc = json.loads(yf.geojson_text(res, notice="synthetic"))
    kinds = pd.Series([f["properties"]["kind"] for f in doc["features"]])
    assert doc["description"] == "synthetic"
    assert (kinds == "flat").sum() == len(sights) and (kinds == "flat_mean").sum() == len(truth)
    lines = [f for f in doc["features"] if f["properties"]["kind"] == "locus"]
    assert len(lines) == res.locus.groupby(["feature", "arc"]).ngroups > 0
    for f in lines:  # every vertex back in the local frame lies on the feature's locus points
        lon, lat, up = np.array(f["geometry"]["coordinates"]).T
        e, n = FRAME.to_local(lon, lat)
        part = res.locus[(res.locus.feature == f["properties"]["feature"]) & (res.locus.arc == f["properties"]["arc"])]
        assert np.max(np.abs(e - part.east_m.to_numpy())) < 1e-3 and np.max(np.abs(up - part.up_m.to_numpy())) < 1e-3
    nview = [f for f in doc["features"] if f["properties"]["kind"] == "nview"]
    assert nview and all(f["properties"]["ellipse_major_m"] >= f["properties"]["ellipse_minor_m"] > 0 for f in nview)
    with pytest.raises(ValueError, match="GeoJSON needs longitude/latitude"):
        yf.geojson(yp.PingResults(res.features, res.sightings, res.locus, None))


def test_export_records_input_files_and_attachments(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.pipeline.publish import export
    from sss_locus.pipeline.publish.provenance import file_sha256

    obs = tmp_path / "my_sightings.csv"
    obs.write_text(GOOD)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    m = export.export_figure(fig, "fig-test-pings", pd.DataFrame({"a": [1]}), caption="A test.", parameters={},
                             out_dir=tmp_path / "figs", input_files=[obs], attachments={"results.geojson": '{"type": "x"}\n'})
    assert {"path": "my_sightings.csv", "sha256": file_sha256(obs), "role": "observations"} in m["data_inputs"]["files"]
    assert m["files"]["fig-test-pings--results.geojson"]["sha256"] == file_sha256(tmp_path / "figs" / "fig-test-pings--results.geojson")
    assert "my\\_sightings.csv (sha256" in (tmp_path / "figs" / "fig-test-pings.bib").read_text()
    with pytest.raises(ValueError, match="attachments must map"):
        export.export_figure(fig, "fig-test-pings", pd.DataFrame({"a": [1]}), caption="A test.", parameters={},
                             out_dir=tmp_path / "figs", attachments={"png": "x"})
    plt.close(fig)


def test_covariance_columns_agree_with_the_ellipse(auv):
    """The ellipse's semi-axes are the square roots of the horizontal covariance's eigenvalues:
    their squares sum to its trace and multiply to its determinant."""
    sights, _ = _sim(auv)
    table, frame = ob.to_local_frame(ob.parse_sightings(sights.drop(columns=list(ex.CHECK_COLUMNS)).astype(str), "sim"),
                                     FRAME)
    f = yp.analyse(table, auv, frame, aperture_margin_deg=10.0).features
    f = f[np.isfinite(f["ellipse_major_m"])]
    assert len(f)
    ee, nn, en = f["cov_east_east_m2"], f["cov_north_north_m2"], f["cov_east_north_m2"]
    np.testing.assert_allclose(f["ellipse_major_m"] ** 2 + f["ellipse_minor_m"] ** 2, ee + nn, rtol=1e-9)
    np.testing.assert_allclose((f["ellipse_major_m"] * f["ellipse_minor_m"]) ** 2, ee * nn - en ** 2, rtol=1e-7)
    np.testing.assert_allclose(f["sigma_up_m"] ** 2, f["cov_up_up_m2"], rtol=1e-12)


def test_an_unknown_platform_is_refused_naming_line_and_column(tmp_path):
    (tmp_path / "s.csv").write_text(GOOD.replace("auv", "my_boat"))
    with pytest.raises(ValueError, match=r"^s.csv line 2, column platform: platform must be one of \[.*'auv'.*got 'my_boat'"):
        yp.run(tmp_path / "s.csv")


def test_the_map_caption_lists_only_the_files_written():
    """Sightings in local metres without an origin get no GeoJSON (it needs longitude/latitude):
    the caption says so and how to get one, instead of listing a file that is not there."""
    from sss_locus.report.your_pings.figures import map_caption

    with_frame = map_caption(9, known=False, synthetic=False, geojson=True)
    assert "`--results.geojson`" in with_frame and "Synthetic" not in with_frame
    local = map_caption(9, known=False, synthetic=False, geojson=False)
    assert "`--results.geojson`" not in local and "-p origin" in local
    assert map_caption(9, known=True, synthetic=True, geojson=True).startswith("**Synthetic example**")
    assert "from the true position" in map_caption(9, known=True, synthetic=False, geojson=True)
