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

from sss_locus.experiments import observations as ob
from sss_locus.experiments import observations_xtf as ox
from sss_locus.experiments import sample_order as so
from sss_locus.experiments import your_pings as yp
from sss_locus.paths import DATA_DIR

REAL = DATA_DIR / "examples" / "your_pings" / "real"
EXAMPLE = DATA_DIR / "examples" / "your_pings"
HEADER = 1024


@pytest.fixture(scope="module")
def iver2():
    from sss_locus.experiments import userdata
    from sss_locus.experiments.platforms import load_platform

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
    from sss_locus.report.your_pings import summary_sentence

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


def test_altitude_zero_names_the_xtf_field(tmp_path):
    path = _real_cut(tmp_path)
    (tmp_path / "m.csv").write_text("feature,platform,file,ping,channel,sample\nA,iver2,cut.xtf,0,1,100\n")
    with pytest.raises(ob.ObservationError, match=r"m.csv line 2: SensorPrimaryAltitude of ping 0 of cut.xtf "
                                                  r"\(packet at byte 1024\) is 0"):
        ox.read_xtf_sightings(tmp_path / "m.csv")
