"""XTF files as recorders write them: the real Scotsman recording (OpenSidescan, MIT licence,
``data/examples/your_pings/real/``), towed sensors with a layback, malformed bytes (a seeded
fuzzer), features seen once. References: the file's own bytes (transmit pulse, annotation),
pyproj geodesics, hand-built packets."""

from __future__ import annotations

import ctypes
import shutil

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.sonar_files import observations as ob
from sss_locus.experiments.sonar_files import observations_xtf as ox
from sss_locus.experiments.sonar_files import sample_order as so
from sss_locus.experiments.your_pings import study as yp
from sss_locus.paths import DATA_DIR

REAL = DATA_DIR / "examples" / "your_pings" / "real"
EXAMPLE = DATA_DIR / "examples" / "your_pings"
HEADER = 1024


@pytest.fixture(scope="module")
def iver2():
    from sss_locus.experiments.datamodel import userdata
    from sss_locus.experiments.datamodel.platforms import load_platform

    userdata.use([str(REAL / "iver2.toml")], [])
    try:
        yield load_platform("iver2")
    finally:
        userdata.use([], [])


def _packets(data: bytes) -> list[int]:
    """Byte offsets of every packet (walked by the length fields, independently of the reader)."""
    out, pos = [], HEADER
    while pos < len(data):
        out.append(pos)
        pos += int.from_bytes(data[pos + 10:pos + 14], "little")
    return out


def test_real_file_is_the_published_one():
    import hashlib

    data = (REAL / "scotsman-iver2.xtf").read_bytes()
    assert len(data) == 2_066_304 and hashlib.sha256(data).hexdigest().startswith("32965ca6")
    assert (REAL / "LICENSE-OpenSidescan.txt").read_text().startswith("MIT License")


def test_real_port_channel_is_stored_far_to_near():
    """The transmit pulse of the port channel is at its last samples (the file's bytes): the
    order is detected as far-first for port and near-first for starboard."""
    header, pings = ox.read_pings(REAL / "scotsman-iver2.xtf")
    assert sorted(pings) == list(range(461))
    port = np.array([p.data[0] for p in pings.values()])
    assert np.median(port[1:, 1016:1023]) == 32767 and np.median(port[1:, 1:8]) < 10000  # the pulse, read directly
    assert ox.channel_order(pings, header, 0, "detect", "f")[0] == "far_first"
    assert ox.channel_order(pings, header, 1, "detect", "f")[0] == "near_first"


def test_real_port_point_target_gets_the_range_its_samples_say(iver2):
    """The bright port point target of ping 242 at stored sample 130: 893 samples from the near
    end, (893.5) * 29.98 / 1024 = 26.2 m, not 3.8 m (below the 4.4 m altitude) as read near-first."""
    res = yp.run(REAL / "scotsman_matches.csv")
    s = res.sightings.set_index("feature")
    rng = s.loc["port_target_a", "slant_range_m"]
    chan_range = float(np.float32(29.983501434326172))
    assert rng == pytest.approx((1023 - 130 + 0.5) * chan_range / 1024, rel=1e-12)
    assert s.loc["port_target_a", "sample_order"] == "far_first" and s.loc["port_target_a", "sample_stored"] == 130
    assert s.loc["wreck_edge", "slant_range_m"] == pytest.approx((138 + 0.5) * chan_range / 1024, rel=1e-12)
    assert not s["flat_below_altitude"].any() and len(res.excluded) == 0


def test_a_wrong_sample_order_is_set_aside_and_named(iver2):
    """Read near-first (the old reader), the 26 m target is closer than the altitude: it is not
    placed at the nadir silently but set aside, named with its file and ping."""
    res = yp.run(REAL / "scotsman_matches.csv", sample_order="near_first")
    assert list(res.excluded["feature"]) == ["port_target_a"]
    assert "scotsman-iver2.xtf ping 242" in res.excluded["where"].iloc[0]
    assert "port_target_a" not in set(res.features["feature"])
    from sss_locus.report.your_pings.figures import summary_sentence

    assert "1 sighting(s) set aside" in summary_sentence(res) and "ping 242" in summary_sentence(res)


def test_features_seen_once_get_flat_positions_and_say_so(iver2):
    res = yp.run(REAL / "scotsman_matches.csv")
    f = res.features
    assert (f["n_sightings"] == 1).all() and len(f) == 4
    assert (f["two_view_status"] == "one sighting: no locus").all() and (f["nview_status"] == "one sighting: no locus").all()
    assert np.isfinite(f["flat_east_m"]).all() and len(res.locus) == 0
    # the flat position of a sighting seen once is its own: the slant range on the flat seafloor
    s = res.sightings.iloc[0]
    d = np.array([s.flat_east_m - s.sensor_east_m, s.flat_north_m - s.sensor_north_m, s.flat_up_m - s.sensor_up_m])
    assert np.linalg.norm(d) == pytest.approx(s.slant_range_m, rel=1e-9)


def test_one_row_of_the_example_runs(tmp_path):
    lines = (EXAMPLE / "example_sightings.csv").read_text().splitlines()
    (tmp_path / "one.csv").write_text("\n".join(lines[:3]) + "\n")
    res = yp.run(tmp_path / "one.csv")
    assert res.features["two_view_status"].tolist() == ["one sighting: no locus"]


def test_ambiguous_order_is_refused_saying_how_to_set_it(tmp_path):
    pings = pd.DataFrame({"ping": [1, 2], "lon_deg": -70.0, "lat_deg": 43.0, "depth_m": 10.0, "altitude_m": 5.0,
                          "heading_deg": 0.0, "pitch_deg": 0.0, "roll_deg": 0.0, "time_s": [1.0, 2.0],
                          "range_setting_m": 50.0, "n_samples": 400})
    ox.write_xtf(tmp_path / "a.xtf", pings)
    data = bytearray((tmp_path / "a.xtf").read_bytes())
    for pos in _packets(bytes(data)):  # flat data: no pulse, no water column
        data[pos + 256 + 64:pos + 256 + 64 + 800] = (1000).to_bytes(2, "little") * 400
    (tmp_path / "a.xtf").write_bytes(bytes(data))
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,auv,a.xtf,1,0,100\n")
    with pytest.raises(ob.ObservationError, match=r"cannot tell which end of channel 0 \(port\).*-p sample_order"):
        ox.read_xtf_sightings(tmp_path / "m.csv")
    t = ox.read_xtf_sightings(tmp_path / "m.csv", sample_order="port_far_first")
    assert t["slant_range_m"].iloc[0] == (399 - 100 + 0.5) * 50 / 400


def _real_cut(tmp_path, n=30):
    data = (REAL / "scotsman-iver2.xtf").read_bytes()
    offs = _packets(data)
    path = tmp_path / "cut.xtf"
    path.write_bytes(data[:offs[n]])
    return path


def test_repeated_ping_number_is_refused(tmp_path):
    path = _real_cut(tmp_path)
    data = bytearray(path.read_bytes())
    offs = _packets(bytes(data))
    data[offs[5] + 28:offs[5] + 32] = (4).to_bytes(4, "little")  # PingNumber of the 6th ping := 4
    path.write_bytes(bytes(data))
    with pytest.raises(ob.ObservationError, match=rf"cut.xtf: PingNumber 4 is repeated \(the pings at byte {offs[4]} and byte {offs[5]}\)"):
        ox.read_pings(path)


@pytest.mark.parametrize("edit, message", [
    (lambda d, o: d.__setitem__(256, 255), "cut.xtf byte 256: sonar channel 0 has TypeOfChannel 255"),
    (lambda d, o: d.__setitem__(slice(o[3] + 4, o[3] + 6), (3).to_bytes(2, "little")),
     "ping 3 has NumChansToFollow 3; the file header declares 2"),
    (lambda d, o: d.__setitem__(slice(o[3] + 10, o[3] + 14), (255).to_bytes(4, "little")),
     "byte {o3}: sonar packet of 255 bytes (NumBytesThisRecord), shorter than its 256-byte ping header"),
    # NumberOfSonarChannels is at byte 166 of XTF.H's file header (1+1+8+8+16+2+64+64+2 bytes before it)
    (lambda d, o: d.__setitem__(166, 7), "cut.xtf byte 166: the file header declares 7 channels"),
    (lambda d, o: d.__setitem__(slice(o[3] + 10, o[3] + 14), (10).to_bytes(4, "little")),
     "cut.xtf byte {o3}: packet of 10 bytes (NumBytesThisRecord), shorter than its 14-byte packet start"),
])
def test_malformed_headers_are_refused_naming_file_and_byte(tmp_path, edit, message):
    path = _real_cut(tmp_path)
    data = bytearray(path.read_bytes())
    offs = _packets(bytes(data))
    edit(data, offs)
    path.write_bytes(bytes(data))
    with pytest.raises(ob.ObservationError) as err:
        ox.read_pings(path)
    assert message.format(o3=offs[3]) in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("path, message", [
    ("", "XTF file: the path is empty"), ("/dev/null", "XTF file /dev/null is a character device, not a file"),
])
def test_an_xtf_path_that_is_no_file_says_what_it_is(path, message):
    """/dev/null exists (it was "does not exist"); an empty path is not the current folder."""
    with pytest.raises(ob.ObservationError, match=message):
        ox.read_pings(path)


def test_an_empty_file_cell_names_its_line(tmp_path):
    """It was read as the matches file's folder ("XTF file ... is a directory")."""
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,iver2,,1,0,5\n")
    with pytest.raises(ob.ObservationError, match=r"^m.csv line 2, column file: empty"):
        ox.read_xtf_sightings(tmp_path / "m.csv")


def test_altitude_zero_names_the_xtf_field(tmp_path):
    path = _real_cut(tmp_path)
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,iver2,cut.xtf,0,1,100\n")
    with pytest.raises(ob.ObservationError, match=r"m.csv line 2: SensorPrimaryAltitude of ping 0 of cut.xtf "
                                                  r"\(packet at byte 1024\) is 0"):
        ox.read_xtf_sightings(tmp_path / "m.csv")


def _towed_file(tmp_path, *, layback, cable=0, ship_offset_m=None, heading=30.0):
    """Three pings of a towed sensor (NavUnits 3): ``SensorX/Y`` at the ship's position, or,
    with ``ship_offset_m``, the towfish's position that far behind the ship's (pyproj geodesic)."""
    from pyproj import Geod

    ship = (-70.0, 43.0)
    if ship_offset_m is None:
        sensor = ship
    else:
        lo, la, _ = Geod(ellps="WGS84").fwd(ship[0], ship[1], heading + 180.0, ship_offset_m)
        sensor = (float(lo), float(la))
    pings = pd.DataFrame({"ping": [1, 2, 3], "lon_deg": sensor[0], "lat_deg": sensor[1], "depth_m": 12.0,
                          "altitude_m": 8.0, "heading_deg": heading, "pitch_deg": 0.0, "roll_deg": 0.0,
                          "time_s": [1.0, 2.0, 3.0], "range_setting_m": 60.0, "n_samples": 600,
                          "ship_x": ship[0], "ship_y": ship[1], "layback_m": layback, "cable_out_m": cable})
    ox.write_xtf(tmp_path / "t.xtf", pings)
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,auv,t.xtf,2,1,300\n")
    return tmp_path / "m.csv", ship


def _geodesic_behind(ship, heading, distance):
    from pyproj import Geod

    lo, la, _ = Geod(ellps="WGS84").fwd(ship[0], ship[1], heading + 180.0, distance)
    return float(lo), float(la)


@pytest.mark.parametrize("layback, cable, expected", [(40.0, 0, 40.0), (0.0, 37, np.sqrt(37.0 ** 2 - 12.0 ** 2))])
def test_towfish_is_behind_the_ship_by_the_layback(tmp_path, layback, cable, expected):
    """Layback (or a straight cable of CableOut to the fish's depth) moves the sensor behind the
    ship along its heading: the result against a pyproj geodesic."""
    from sss_locus.experiments.sonar_files.observations import LocalFrame

    matches, ship = _towed_file(tmp_path, layback=layback, cable=cable)
    frame = LocalFrame(-70.0, 43.0)
    res = yp.run(matches, None, frame)
    s = res.sightings.iloc[0]
    e, n = frame.to_local(*_geodesic_behind(ship, 30.0, expected))
    assert s["layback_m"] == pytest.approx(expected, rel=1e-6)
    assert np.hypot(s["east_m"] - e, s["north_m"] - n) < 0.01  # the reference point moved to the towfish
    assert s["position_read_as"] == "shifted by the layback" and s["layback_from"] == ("Layback" if layback else "CableOut")


def test_a_recorded_towfish_position_is_not_shifted_twice(tmp_path):
    from sss_locus.experiments.sonar_files.observations import LocalFrame

    matches, ship = _towed_file(tmp_path, layback=40.0, ship_offset_m=40.0)
    frame = LocalFrame(-70.0, 43.0)
    s = yp.run(matches, None, frame).sightings.iloc[0]
    e, n = frame.to_local(*_geodesic_behind(ship, 30.0, 40.0))
    assert s["layback_m"] == 0.0 and s["position_read_as"] == "recorded (already the towfish's)"
    assert np.hypot(s["east_m"] - e, s["north_m"] - n) < 0.01


def test_a_towfish_position_that_fits_neither_reading_is_refused(tmp_path):
    matches, _ = _towed_file(tmp_path, layback=40.0, ship_offset_m=15.0)
    with pytest.raises(ob.ObservationError, match=r"m.csv line 2: ping 2 of t.xtf: SensorX/Ycoordinate is 15 m from "
                                                  r"ShipX/Ycoordinate but the layback is 40 m.*-p towfish"):
        ox.read_xtf_sightings(matches)
    t = ox.read_xtf_sightings(matches, towfish="recorded")
    assert t["layback_m"].iloc[0] == 0.0


@pytest.mark.parametrize("layback, cable, message", [
    (-40.0, 0, r"m.csv line 2: Layback of ping 2 of t.xtf \(packet at byte \d+\) is -40; it must be in \[0, 10000\]"),
    (float("nan"), 0, r"m.csv line 2: Layback of ping 2 of t.xtf \(packet at byte \d+\) is nan"),
    (0.0, 20000, r"m.csv line 2: the layback of ping 2 of t.xtf \(packet at byte \d+\) from CableOut 20000 m is 20000 m; it must be in \[0, 10000\]"),
])
def test_an_unusable_layback_is_refused_naming_the_xtf_field(tmp_path, layback, cable, message):
    """Not read as "no layback" (the sensor left at the ship), nor blamed on a CSV column."""
    from sss_locus.experiments.sonar_files.xtf_summary import summary

    matches, _ = _towed_file(tmp_path, layback=layback, cable=cable)
    with pytest.raises(ob.ObservationError, match=message):
        ox.read_xtf_sightings(matches)
    assert summary(tmp_path / "t.xtf")["layback_bad"] == (3 if layback < 0 or layback != layback else 0)


def test_a_csv_layback_column_moves_the_sensor(tmp_path):
    text = ("feature,platform,side,east_m,north_m,depth_m,altitude_m,heading_deg,pitch_deg,roll_deg,slant_range_m,layback_m\n"
            "A,auv,port,100,200,20,15,90,0,0,30,25\nA,auv,starboard,10,5,20,15,0,0,0,35,\n")
    (tmp_path / "s.csv").write_text(text)
    s = yp.run(tmp_path / "s.csv").sightings
    assert (s["east_m"].tolist(), s["north_m"].tolist()) == ([75.0, 10.0], [200.0, 5.0])
    assert s["tow_east_m"].tolist() == [100.0, 10.0]


MUTATIONS = ("byte", "field", "truncate", "duplicate")


def _mutate(data: bytes, rng) -> bytes:
    """One seeded mutation: random bytes, an extreme value in a header field, a truncation, or a
    packet repeated."""
    d = bytearray(data)
    offs = _packets(data)
    kind = MUTATIONS[rng.integers(len(MUTATIONS))]
    if kind == "byte":
        for _ in range(rng.integers(1, 6)):
            d[rng.integers(len(d))] = rng.integers(256)
    elif kind == "field":
        base = 0 if rng.random() < 0.3 else offs[rng.integers(len(offs))]
        size = (1, 2, 4, 8)[rng.integers(4)]
        at = base + rng.integers(0, (1024 if base == 0 else 256 + 64) - size)
        value = (0, 255, 2 ** (8 * size) - 1, 2 ** (8 * size - 1))[rng.integers(4)]
        if size == 4 and rng.random() < 0.3:
            value = int.from_bytes(np.float32(np.nan).tobytes(), "little")
        d[at:at + size] = int(value).to_bytes(size, "little")
    elif kind == "truncate":
        d = d[:rng.integers(len(d))]
    else:
        k = rng.integers(len(offs) - 1)
        d = d[:offs[k + 1]] + data[offs[k]:offs[k + 1]] + d[offs[k + 1]:]
    return bytes(d)


@pytest.mark.parametrize("base", ["example", "real"])
def test_fuzzed_xtf_bytes_give_a_result_or_one_line(tmp_path, base):
    """A seeded byte-and-field mutator over the example file and the real file (its first 30
    pings): every case either reads, with every sighting's range and position finite and in
    range (a file cut inside a packet: read up to it, with its warning), or is refused in one line
    naming the file; never another exception."""
    if base == "example":
        data = (EXAMPLE / "example.xtf").read_bytes()
        (tmp_path / "cut.xtf").write_bytes(data[:_packets(data)[16]])
        src = tmp_path / "cut.xtf"
        rows = pd.read_csv(EXAMPLE / "example_xtf_matches.csv", comment="#").query("ping < 16").head(6)
        matches = rows.assign(file="f.xtf").to_csv(index=False)
    else:
        src = _real_cut(tmp_path)
        matches = "feature,platform,file,ping,channel,sample\nA,auv,f.xtf,12,1,500\nB,auv,f.xtf,20,0,300\n"
    data = src.read_bytes()
    (tmp_path / "m.csv").write_text(matches)
    rng = np.random.default_rng(36 if base == "example" else 38)
    outcomes = {"read": 0, "refused": 0, "read cut": 0}
    boundaries = set(_packets(data))
    for case in range(120):
        mutated = _mutate(data, rng)
        (tmp_path / "f.xtf").write_bytes(mutated)
        try:
            t = ox.read_xtf_sightings(tmp_path / "m.csv")
        except ob.ObservationError as exc:
            msg = str(exc)
            assert "\n" not in msg and ("f.xtf" in msg or "m.csv" in msg), (case, msg)
            outcomes["refused"] += 1
            continue
        xy = ["lon_deg", "lat_deg"] if np.isfinite(t["lon_deg"]).all() else ["east_m", "north_m"]  # NavUnits 3 or 0
        assert np.isfinite(t[["slant_range_m", *xy, "depth_m", "altitude_m"]].to_numpy(float)).all()
        assert ((t["slant_range_m"] > 0) & (t["altitude_m"] > 0)).all()
        cut = len(mutated) < len(data) and len(mutated) not in boundaries  # ends inside a packet
        assert t.attrs["xtf_truncated"] or not cut, case  # read in part: said so
        outcomes["read cut" if cut else "read"] += 1
    # the mutator reaches every outcome (a cut file was refused whole before; now read up to the cut)
    assert outcomes["read"] > 10 and outcomes["refused"] > 10 and outcomes["read cut"] > 0, outcomes


def test_xtf_summary_on_one_screen(capsys):
    from sss_locus.pipeline.cli.command import main

    assert main(["xtf", str(REAL / "scotsman-iver2.xtf")]) == 0
    out = capsys.readouterr().out
    assert len(out.splitlines()) <= 24 and "461 sonar pings, PingNumber 0 to 460" in out
    assert "0  port" in out and "far_first: detected" in out and "1  starboard" in out and "near_first: detected" in out
    assert "(52.2 s)" in out and "1 ping(s) with altitude 0" in out and "layback: none recorded" in out
    assert main(["xtf", str(REAL)]) == 2
    assert "is a directory" in capsys.readouterr().err


def test_waterfall_axes_are_ping_and_stored_sample():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.experiments.sonar_files.xtf_summary import waterfall_data
    from sss_locus.report.your_pings.waterfall import waterfall

    numbers, image = waterfall_data(REAL / "scotsman-iver2.xtf", 0)
    _, pings = ox.read_pings(REAL / "scotsman-iver2.xtf")
    assert numbers.tolist() == list(range(461)) and np.array_equal(image[242], pings[242].data[0])
    marks = pd.DataFrame({"channel": [1], "ping": [281], "sample": [138], "label": ["hit"]})
    fig, data = waterfall(REAL / "scotsman-iver2.xtf", marks=marks)
    ax = fig.axes[1]
    assert ax.get_xlabel() == "sample (as stored)" and "starboard" in ax.get_title()
    assert ax.collections[0].get_offsets().tolist() == [[138.0, 281.0]]
    plt.close(fig)


def test_a_towed_survey_gives_the_results_of_its_towfish_positions(tmp_path):
    """The worked example recorded by a towed sensor: SensorX/Y holds the ship, 35 m ahead of the
    towfish along its heading (pyproj geodesic), with Layback 35. The results are those of the
    towfish positions themselves (the example's CSV), to the millimetre."""
    from pyproj import Geod

    from sss_locus.experiments.your_pings import example as ex

    sights = pd.read_csv(EXAMPLE / "example_sightings.csv", comment="#")
    sights["n_samples"] = sights["n_samples"].astype(int)
    pings, matches = ex.xtf_tables(sights, "towed.xtf")
    lon, lat, _ = Geod(ellps="WGS84").fwd(pings["lon_deg"], pings["lat_deg"], pings["heading_deg"], np.full(len(pings), 35.0))
    towed = pings.assign(lon_deg=lon, lat_deg=lat, layback_m=35.0)
    ox.write_xtf(tmp_path / "towed.xtf", towed)
    ex.write_csv(tmp_path / "towed_matches.csv", matches)
    a = yp.run(EXAMPLE / "example_sightings.csv")
    b = yp.run(tmp_path / "towed_matches.csv", None, a.frame)
    assert (b.sightings["layback_m"] == 35.0).all()
    np.testing.assert_allclose(b.sightings[["east_m", "north_m"]], a.sightings[["east_m", "north_m"]], atol=1e-3)
    ok = np.isfinite(a.features["nview_east_m"])
    np.testing.assert_allclose(b.features.loc[ok, ["nview_east_m", "nview_north_m"]],
                               a.features.loc[ok, ["nview_east_m", "nview_north_m"]], atol=0.01)
    untouched = yp.run(tmp_path / "towed_matches.csv", None, a.frame, towfish="recorded")
    d = np.hypot(*(untouched.sightings[["east_m", "north_m"]].to_numpy() - a.sightings[["east_m", "north_m"]].to_numpy()).T)
    np.testing.assert_allclose(d, 35.0, atol=0.01)  # without the layback every position is 35 m off


def test_unsupported_nav_units_are_refused_naming_the_byte(tmp_path):
    path = _real_cut(tmp_path)
    data = bytearray(path.read_bytes())
    data[164:166] = (1).to_bytes(2, "little")  # NavUnits (Triton's layout: after the 64-byte file name)
    path.write_bytes(bytes(data))
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,iver2,cut.xtf,3,1,100\n")
    with pytest.raises(ob.ObservationError, match=r"^cut.xtf byte 164: NavUnits 1 not supported"):
        ox.read_xtf_sightings(tmp_path / "m.csv")


def test_the_real_pass_section_says_what_one_pass_cannot_tell(iver2):
    from sss_locus.report.common.text import fmt_sig
    from sss_locus.report.your_pings.real import marks, one_pass_text, positions_table, read_hits

    hits = read_hits(REAL / "scotsman-iver2.xtf.hits")
    assert hits.to_dict("records") == [{"channel": 1, "sample": 138, "row": 281}]
    m = marks(pd.read_csv(REAL / "scotsman_matches.csv", comment="#"), hits, np.arange(461))
    assert len(m) == 4 and m.iloc[0].to_dict() == {"channel": 1, "ping": 281, "sample": 138,
                                                   "label": "wreck_edge = annotated hit (.hits)"}
    other = marks(pd.read_csv(REAL / "scotsman_matches.csv", comment="#").iloc[1:], hits, np.arange(461))
    assert other.iloc[-1].to_dict() == {"channel": 1, "ping": 281, "sample": 138, "label": "annotated hit (.hits)"}
    res = yp.run(REAL / "scotsman_matches.csv")
    table = positions_table(res)
    text = one_pass_text(res, table, 220, 461)
    r, h = table.loc["wreck_edge", ["slant_range_m", "transducer_height_m"]]
    moved = np.sqrt(r ** 2 - (h - 1.0) ** 2) - np.sqrt(r ** 2 - h ** 2)  # a point 1 m up, on the same sphere
    assert "4 of the 4 picks" in text and f"{fmt_sig(moved)} m longer" in text and "wreck_edge" in text
    np.testing.assert_allclose(table["ground_range_m"] ** 2 + table["transducer_height_m"] ** 2,
                               table["slant_range_m"] ** 2, rtol=1e-9)


def test_the_page_summary_says_which_end_of_each_channel_is_near(iver2):
    """The port channel of the real file is stored far-to-near (transmit pulse at its last
    samples, test above); the chapter's summary says so, with how it was decided."""
    from sss_locus.report.your_pings.figures import summary_sentence

    res = yp.run(REAL / "scotsman_matches.csv", iver2)
    text = summary_sentence(res)
    assert "scotsman-iver2.xtf channel 0 (port) far-first (detected:" in text
    assert "scotsman-iver2.xtf channel 1 (starboard) near-first (detected:" in text
