"""Sightings, origin and truth inputs refused in one line before any kernel starts, or read
right (issue 38, items 4-6): the frame's origin across the antimeridian, far origins, duplicate
and conflicting columns, trailing commas, huge identifiers, ``-p origin`` and ``-p truth``.
Distances are checked against pyproj's geodesic, not against the reader."""

from __future__ import annotations

import os

import numpy as np
import pytest

pytest.importorskip("pyproj")

from sss_locus import paths  # noqa: E402
from sss_locus.experiments.sonar_files import observations as ob  # noqa: E402
from sss_locus.pipeline.cli import command as cli
from sss_locus.pipeline.run import runner  # noqa: E402
from sss_locus.pipeline.run.registry import ParameterError, get_entry  # noqa: E402
from sss_locus.pipeline.run.runner import resolve_parameters  # noqa: E402

EXAMPLE = paths.REPO_ROOT / "data" / "examples" / "your_pings" / "example_sightings.csv"


def _rows():
    lines = [ln for ln in EXAMPLE.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def _write(tmp_path, header, rows, name="s.csv", tail=""):
    path = tmp_path / name
    path.write_text("\n".join(",".join(r) + tail for r in [header, *rows]) + "\n", encoding="utf-8")
    return path


def _refused(path, *fragments):
    with pytest.raises(ob.ObservationError) as info:
        ob.read_sightings(path)
    text = str(info.value)
    assert "\n" not in text and all(f in text for f in fragments), text


def test_the_frame_origin_of_a_survey_across_180_degrees_is_among_its_sightings():
    import pyproj

    lon = np.array([179.99, 179.995, -179.995, -179.99])
    lat = np.full(4, -16.5)
    frame = ob.survey_frame(lon, lat)
    _, _, d = pyproj.Geod(ellps="WGS84").inv(np.full(4, frame.lon0_deg), np.full(4, frame.lat0_deg), lon, lat)
    assert d.max() < 2000  # the plain mean (0 deg) put it ~19,000 km away
    assert ob.survey_frame([10.0, 10.002], [43.0, 43.0]).lon0_deg == pytest.approx(10.001, abs=1e-3)


def test_a_far_origin_is_refused_with_the_limit(tmp_path):
    table = ob.read_sightings(EXAMPLE)
    with pytest.raises(ob.ObservationError, match="km from the local frame's origin .* within 100 km"):
        ob.to_local_frame(table, ob.LocalFrame(-60.0, 43.0))
    ob.to_local_frame(table, ob.LocalFrame(-70.0, 43.0))  # the example's own origin


def test_a_second_feature_column_is_refused(tmp_path):
    header, rows = _rows()
    _refused(_write(tmp_path, header + ["feature"], [r + ["X"] for r in rows]), "'feature' appears twice")


def test_east_north_beside_lon_lat_is_refused(tmp_path):
    header, rows = _rows()
    _refused(_write(tmp_path, header + ["east_m", "north_m"], [r + ["1", "2"] for r in rows]), "not both")


def test_a_trailing_comma_on_every_row_is_named_not_blamed_on_side(tmp_path):
    header, rows = _rows()
    path = tmp_path / "t.csv"
    path.write_text(",".join(header) + "\n" + "\n".join(",".join(r) + "," for r in rows) + "\n", encoding="utf-8")
    _refused(path, "line 2", "trailing comma")


def test_a_10_mb_identifier_is_refused_quickly(tmp_path):
    import time

    header, rows = _rows()
    rows[3][0] = "F" * 10_000_000
    path = _write(tmp_path, header, rows)
    start = time.perf_counter()
    _refused(path, "line 5")
    assert time.perf_counter() - start < 10


@pytest.mark.parametrize("origin, fragment", [
    ("[-70, 91]", "lat0_deg"), ("[1, 2, 3]", "two numbers"), ('["a", "b"]', "two numbers"),
    ("[5]", "two numbers"), ("[True, 43]", "two numbers"), ("[-70, 43.0]", None),
    ("[true, 43]", "two numbers"),  # JSON's spelling: refused for what it is, not as "expected a list"
])
def test_origin_is_checked_before_the_kernel(origin, fragment):
    entry = get_entry("your_pings")
    if fragment is None:
        resolve_parameters(entry, "quick", {"origin": origin}, from_text=True)
        return
    with pytest.raises(ValueError) as info:
        resolve_parameters(entry, "quick", {"origin": origin}, from_text=True)
    assert str(info.value).startswith("-p origin") and fragment in str(info.value), info.value


def test_nan_in_origin_is_named_as_not_finite():
    with pytest.raises(ParameterError, match="'nan' is not a number here; every number must be finite"):
        resolve_parameters(get_entry("your_pings"), "quick", {"origin": "[nan, 43]"}, from_text=True)


@pytest.mark.parametrize("content, fragment", [
    (b"\x00\xff\xfe binary", "not UTF-8"), (b"", "not a readable CSV"), (b"a,b\n1,2\n", "missing column"),
    (b"feature,east_m,north_m,up_m\nF1,1,x,3\n", "column north_m"), (None, "is a directory"),
])
def test_truth_is_checked_before_the_kernel(tmp_path, content, fragment):
    truth = tmp_path / "truth.csv"
    if content is None:
        truth.mkdir()
    else:
        truth.write_bytes(content)
    observations = tmp_path / "mine.csv"
    observations.write_bytes(EXAMPLE.read_bytes())
    with pytest.raises(ValueError) as info:
        resolve_parameters(get_entry("your_pings"), "quick", {"observations": str(observations), "truth": str(truth)},
                           from_text=True)
    text = str(info.value)
    assert text.startswith("-p truth") and fragment in text and "\n" not in text, text


def test_sightings_paths_that_are_not_files_say_what_they_are(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    for path, fragment in [(tmp_path, "is a directory"), (fifo, "FIFO"), ("/dev/zero", "character device")]:
        with pytest.raises(ob.ObservationError, match=fragment):
            ob.read_sightings(path)


def test_a_refusal_reaches_the_command_line_in_one_line(tmp_path, capsys, monkeypatch, build_area):
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    assert cli.main(["run", "your_pings", "--profile", "quick", "-p", "origin", "[nan, 43]"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "origin" in err and not started


def _once(tmp_path):
    header, rows = _rows()
    seen, kept = set(), []
    for r in rows:
        if r[0] not in seen:
            seen.add(r[0])
            kept.append(r)
    return _write(tmp_path, header, kept, name="once.csv")


def test_no_feature_seen_twice_is_a_defined_result_in_the_library(tmp_path):
    from sss_locus.experiments.your_pings import study as yp

    res = yp.run(_once(tmp_path))
    assert (res.features["n_sightings"] == 1).all()
    # issue 36: a feature seen once keeps its flat-seafloor position and says why it has no locus
    assert set(res.features["two_view_status"]) == {"one sighting: no locus"}
    assert res.features["locus_length_m"].isna().all() and len(res.locus) == 0


def test_no_feature_seen_twice_passes_the_checks_before_the_kernel(tmp_path):
    # a file of one sighting per feature is valid input (issue 36): the chapter runs and every feature
    # gets its flat-seafloor position with the status "one sighting: no locus"
    resolve_parameters(get_entry("your_pings"), "quick", {"observations": str(_once(tmp_path)), "truth": '""'},
                       from_text=True)


@pytest.mark.parametrize("value, fragment", [("", "the path is empty"), ('""', "the path is empty"),
                                             ("/dev/zero", "character device"), ("/tmp", "is a directory"),
                                             ("no/such.csv", "does not exist")])
@pytest.mark.parametrize("notebook, parameter", [("your_pings", "observations"), ("survey_design", "area")])
def test_user_file_parameters_say_what_a_non_file_is(notebook, parameter, value, fragment):
    with pytest.raises(ValueError) as info:
        resolve_parameters(get_entry(notebook), "quick", {parameter: value}, from_text=True)
    assert str(info.value).startswith(f"-p {parameter}: ") and fragment in str(info.value), info.value


def test_a_survey_moved_across_the_antimeridian_gives_the_same_features(tmp_path):
    """The example moved in longitude so that it straddles +-180 deg: a rigid move of the whole
    survey (same latitude), so every feature's status and spread must be unchanged (the plain mean
    longitude put the origin ~180 deg away: resolved features diverged, spreads grew)."""
    import io

    import pandas as pd

    from sss_locus.experiments.your_pings import study as yp

    lines = [ln for ln in EXAMPLE.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    table = pd.read_csv(io.StringIO("\n".join(lines)))
    table["lon_deg"] = (table["lon_deg"] + 250.0 + 180.0) % 360.0 - 180.0
    assert (table["lon_deg"] > 179).any() and (table["lon_deg"] < -179).any()
    table.to_csv(tmp_path / "moved.csv", index=False)
    moved, home = yp.run(tmp_path / "moved.csv").features, yp.run(EXAMPLE).features
    assert list(moved["nview_status"]) == list(home["nview_status"])
    np.testing.assert_allclose(moved["flat_spread_m"], home["flat_spread_m"], atol=1e-6)
    np.testing.assert_allclose(moved["locus_length_m"], home["locus_length_m"], atol=1e-6)


def _header_command(path):
    """The ``sss-locus ...`` command a data file's header comment documents, as arguments."""
    import shlex

    lines = [ln[1:].strip() for ln in path.read_text(encoding="utf-8").splitlines() if ln.startswith("#")]
    start = next(i for i, ln in enumerate(lines) if ln.startswith("sss-locus "))
    text = lines[start]
    while text.endswith("\\"):
        start += 1
        text = text[:-1] + " " + lines[start]
    return shlex.split(text)[1:]


def test_the_real_recordings_documented_command_passes_every_check_before_the_kernel(capsys, monkeypatch, build_area):
    # the command in iver2.toml's header failed in cell 3 (no [noise.iver2] for the joint adjustment)
    from sss_locus.experiments.datamodel import userdata
    from sss_locus.experiments.passes.pass_noise import load_pass_noise

    real = paths.REPO_ROOT / "data" / "examples" / "your_pings" / "real"
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a, **k: started.append(a))
    monkeypatch.chdir(paths.REPO_ROOT)  # the command's paths are relative to the checkout
    try:
        args = _header_command(real / "iver2.toml")
        assert args[:2] == ["run", "your_pings"] and "--data" in args
        cli.main(args)
        assert started, capsys.readouterr().err  # every check passed; the kernel would start
        userdata.use([real / "iver2.toml"])
        assert load_pass_noise("iver2").pass_offset_sigma_m > 0
    finally:
        userdata.use()


def test_a_sightings_platform_without_a_noise_model_is_refused_before_the_kernel(tmp_path):
    from sss_locus.experiments.datamodel import userdata

    mine = tmp_path / "mine.toml"
    example = (paths.REPO_ROOT / "data" / "examples" / "my_auv.toml").read_text(encoding="utf-8")
    mine.write_text(example.split("[noise.my_auv]")[0], encoding="utf-8")  # the platform, no noise model
    header, rows = _rows()
    at = header.index("platform")
    sightings = _write(tmp_path, header, [[*r[:at], "my_auv", *r[at + 1:]] for r in rows], name="mine.csv")
    userdata.use([mine], ["sonars.narrow_fan_450.max_range_m=200"])  # the example's ranges reach 141 m
    try:
        with pytest.raises(ValueError) as info:
            resolve_parameters(get_entry("your_pings"), "quick", {"observations": str(sightings), "truth": '""'},
                               from_text=True)
    finally:
        userdata.use()
    text = str(info.value)
    assert text.startswith("-p observations mine.csv: no [noise.my_auv] table") and "data/noise.toml" in text, text
