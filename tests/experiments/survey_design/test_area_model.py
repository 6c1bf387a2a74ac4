"""The survey area file's ``[area]`` table on the data model (issue 41): its documentation in
``data/README.md`` ("Valid values of a survey area file") is the reference. Every key the model
declares is documented there; every documented bound is refused just outside and accepted on
a closed end, in one line naming the file, the key path, the value and the range as documented;
the documented choices of ``bathymetry_values`` are the only ones accepted, and a grid without
them is refused saying what is missing and the valid values (it ended with "got None" before).
The wall clearance has one bound: the area file's and ``[survey_design]``'s, both documented."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.datamodel import models  # noqa: E402
from sss_locus.experiments.survey_design.area import load_area  # noqa: E402

REPO = Path(__file__).resolve().parents[3]
ROW = re.compile(r"^\| `([a-z_.]+)` \| ([^|]+) \|")
VERTICES = "vertices_m = [[0, 0], [400, 0], [400, 300], [0, 300]]\n"


def _documented(heading: str) -> dict[str, str]:
    text = (REPO / "data" / "README.md").read_text(encoding="utf-8")
    section = text.split(f"## {heading}", 1)[1].split("\n## ", 1)[0]
    return {m.group(1): m.group(2).strip() for m in map(ROW.match, section.splitlines()) if m}


AREA = _documented("Valid values of a survey area file")
DATA = _documented("Valid values (checked before any work starts)")


def _bounds(rule: str):
    m = re.fullmatch(r"([\[(])(-?[\d.]+), (-?[\d.]+)([\])])", rule)
    return None if not m else (float(m.group(2)), m.group(1) == "[", float(m.group(3)), m.group(4) == "]")


def _refusal(path) -> str | None:
    try:
        load_area(path)
    except ValueError as exc:
        assert "\n" not in str(exc)
        return str(exc)
    return None


def _file(tmp_path, body: str, name: str = "area.toml") -> Path:
    p = tmp_path / name
    p.write_text("[area]\n" + VERTICES + body, encoding="utf-8")
    return p


def test_every_key_of_the_area_table_is_documented():
    assert set(AREA) == {f"area.{k}" for k in models.Area.model_fields}


NUMBERS = [(k, r) for k, r in AREA.items() if _bounds(r)]


@pytest.mark.parametrize("key, rule", NUMBERS, ids=[k for k, _ in NUMBERS])
def test_each_documented_bound_refuses_just_outside_and_accepts_on_it(tmp_path, key, rule):
    lo, lo_closed, hi, hi_closed = _bounds(rule)
    name = key.split(".", 1)[1]
    for end, closed, outward in ((lo, lo_closed, -math.inf), (hi, hi_closed, math.inf)):
        outside = math.nextafter(end, outward) if closed else end
        message = _refusal(_file(tmp_path, f"{name} = {outside!r}\n"))
        assert message is not None, f"{key} = {outside!r} accepted, documented {rule}"
        assert message.startswith(f"{tmp_path / 'area.toml'}: {key} must be a finite number in ")
        assert message.endswith(f"; got {outside!r}")
        shown = re.search(r"in ([\[(])(\S+), (\S+)([\])]);", message)
        assert (shown.group(1) == "[", float(shown.group(2)), float(shown.group(3)), shown.group(4) == "]") == \
            (lo_closed, lo, hi, hi_closed), message
        if closed:
            assert _refusal(_file(tmp_path, f"{name} = {end!r}\n")) is None
    for bad in ("true", '"5"', "nan", "inf"):
        assert f"{key} must be a finite number in" in _refusal(_file(tmp_path, f"{name} = {bad}\n"))


def test_the_wall_clearance_has_one_documented_bound_for_both_tables(tmp_path):
    """The same verdict from the area file and from ``[survey_design]`` on every value around the
    documented bound (they share one declaration, ``models.WallClearanceM``)."""
    from sss_locus.experiments.datamodel import datadoc

    assert AREA["area.wall_clearance_m"] == DATA["survey_design.wall_clearance_m"]
    lo, _, hi, _ = _bounds(AREA["area.wall_clearance_m"])
    for value in (math.nextafter(lo, -1), lo, 5.0, hi, math.nextafter(hi, 2 * hi)):
        doc = datadoc.shipped_document()
        doc["survey_design"]["wall_clearance_m"] = {"value": value, "assumption": "test"}
        try:
            models.validate_document(doc, ("survey_design",))
            design_ok = True
        except ValueError:
            design_ok = False
        area_ok = _refusal(_file(tmp_path, f"wall_clearance_m = {value!r}\nwater_depth_m = 5.0\n")) is None
        assert area_ok == design_ok == (lo <= value <= hi), value


def test_bathymetry_values_are_the_documented_choices(tmp_path):
    assert AREA["area.bathymetry_values"] == "`depth` or `elevation`"
    choices = re.findall(r"`(\w+)`", AREA["area.bathymetry_values"])
    assert tuple(choices) == models.BATHYMETRY_VALUES
    grid = 'origin_lonlat = [-111.81, 40.23]\nbathymetry = "none.tif"\n'
    for value in choices:  # accepted by the table: the next refusal is the missing grid file
        assert "none.tif does not exist" in _refusal(_file(tmp_path, grid + f'bathymetry_values = "{value}"\n'))
    message = _refusal(_file(tmp_path, grid + 'bathymetry_values = "height"\n'))
    assert message == (f"{tmp_path / 'area.toml'}: area.bathymetry_values must be one of {choices} (depth: metres "
                       "below the sea surface, positive down; elevation: positive up, negative in the water); "
                       "got 'height'")


def test_a_grid_without_bathymetry_values_says_what_is_missing_and_the_valid_values(tmp_path):
    # before: "harbour.tif: bathymetry_values must be one of [...] ...; got None", blamed on the grid
    message = _refusal(_file(tmp_path, 'origin_lonlat = [-111.81, 40.23]\nbathymetry = "harbour.tif"\n'))
    assert message.startswith(f"{tmp_path / 'area.toml'}: area.bathymetry_values is missing: a bathymetry grid "
                              "needs bathymetry_values = ")
    assert all(f'"{v}"' in message for v in re.findall(r"`(\w+)`", AREA["area.bathymetry_values"]))
    assert "None" not in message


@pytest.mark.parametrize("body, message", [
    ("", None),
    ('vertices_lonlat = [[0, 0], [0.01, 0], [0.01, 0.01]]\n', "area: needs exactly one of vertices_m or "
                                                             "vertices_lonlat; got both"),
    ('holes_lonlat = [[[0, 0], [0.001, 0], [0.001, 0.001]]]\n', "area.holes_lonlat goes with vertices_lonlat"),
    ('water_beyond_m = 5.0\nnavigable_m = [[-9, -9], [409, -9], [409, 309], [-9, 309]]\n',
     "area: give one of navigable_m, navigable_lonlat or water_beyond_m; got navigable_m, water_beyond_m"),
    ('navigable_lonlat = [[0, 0], [0.01, 0], [0.01, 0.01]]\n', "area.navigable_lonlat needs the area's origin_lonlat"),
    ('bathymetry_values = "depth"\n', "area.bathymetry is missing: bathymetry_values goes with bathymetry"),
    ('bathymetry = "x.tif"\nbathymetry_values = "depth"\nwater_depth_m = 3.0\n',
     "area.bathymetry goes without water_depth_m"),
    ('bathymetry = " "\nbathymetry_values = "depth"\n', "area.bathymetry must be a non-empty string; got ' '"),
    ("name = 3\n", "area.name must be a string; got 3"),
    ("holes_m = [3]\n", "area.holes_m.0 must be a list of [x, y] pairs of finite numbers; got 3"),
    ("origin_lonlat = [200, 40]\n", "area.origin_lonlat must be [longitude, latitude] in degrees"),
])
def test_the_rules_between_keys_are_refused_in_one_line_naming_the_file(tmp_path, body, message):
    found = _refusal(_file(tmp_path, body))
    if message is None:
        assert found is None or "no water depth" in found  # the table itself is fine
    else:
        assert found is not None and found.startswith(f"{tmp_path / 'area.toml'}: ") and message in found, found


def test_a_geojson_areas_properties_are_checked_by_the_same_model(tmp_path):
    import json

    ring = [[-111.81, 40.234], [-111.80, 40.234], [-111.80, 40.240], [-111.81, 40.240], [-111.81, 40.234]]
    doc = {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ring]},
           "properties": {"wall_clearance_m": -1, "colour": "red"}}  # other properties are the user's own
    path = tmp_path / "a.geojson"
    path.write_text(json.dumps(doc), encoding="utf-8")
    lo = _bounds(AREA["area.wall_clearance_m"])[0]
    assert _refusal(path) == f"{path}: wall_clearance_m must be a finite number in [{lo}, 1000.0]; got -1"
