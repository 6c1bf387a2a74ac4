"""Survey-area files refused in one line, or read right (issue 38, items 2, 3, 5 and 6): GeoJSON
members of the wrong type, nesting, vertex count and file size, far vertices, holes with
longitude/latitude vertices, booleans and strings as coordinates, NaN blamed on the right key,
and paths that are not regular files. Expected values come from pyproj's geodesic and
shapely's area, never from the reader."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.survey_design import area as sa  # noqa: E402
from sss_locus.experiments.survey_design.area import load_area  # noqa: E402

SQUARE = [[-111.81, 40.234], [-111.80, 40.234], [-111.80, 40.240], [-111.81, 40.240], [-111.81, 40.234]]


def _geojson(tmp_path, doc, name="a.geojson"):
    path = tmp_path / name
    path.write_text(doc if isinstance(doc, str) else json.dumps(doc), encoding="utf-8")
    return path


def _toml(tmp_path, body, name="a.toml"):
    path = tmp_path / name
    path.write_text("[area]\n" + body, encoding="utf-8")
    return path


def _one_line_refusal(path, *fragments):
    with pytest.raises(ValueError) as info:
        load_area(path)
    text = str(info.value)
    assert "\n" not in text and all(f in text for f in fragments), text
    return text


POLY = {"type": "Polygon", "coordinates": [SQUARE]}


@pytest.mark.parametrize("doc, fragment", [
    ({"type": "FeatureCollection", "features": "abc"}, "'features' must be an array"),
    ({"type": "FeatureCollection", "features": [1, 2]}, "features[0] must be an object"),
    ({"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": "x"}]}, "'geometry' must be an object"),
    ({"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": [1]}]}, "'geometry' must be an object"),
    ({"type": "Feature", "geometry": "Polygon"}, "'geometry' must be an object"),
    ({"type": "Feature", "geometry": POLY, "properties": [1, 2]}, "'properties' must be an object"),
    ({"type": "Polygon", "coordinates": "abc"}, "array of rings"),
    ({"type": "Polygon", "coordinates": [1, 2, 3]}, "array of rings"),
])
def test_geojson_members_of_the_wrong_type_are_refused_naming_the_member(tmp_path, doc, fragment):
    _one_line_refusal(_geojson(tmp_path, doc), "a.geojson", fragment)


def test_deeply_nested_geojson_names_the_file(tmp_path):
    path = _geojson(tmp_path, '{"type": "Polygon", "coordinates": ' + "[" * 100_000 + "]" * 100_000 + "}")
    _one_line_refusal(path, "a.geojson", "nested too deeply")


@pytest.mark.parametrize("value", ["true", '"380"', '[[true, 0], [900, 0], [900, 400]]'])
def test_booleans_and_strings_are_not_coordinates(tmp_path, value):
    body = (f"vertices_m = {value}\n" if value.startswith("[[") else
            f"vertices_m = [[0, 0], [900, 0], [900, 400], [0, {value}]]\n")
    _one_line_refusal(_toml(tmp_path, body), "area.vertices_m must be a list of [x, y] pairs")


def test_a_boolean_origin_is_refused(tmp_path):
    _one_line_refusal(_toml(tmp_path, "vertices_m = [[0, 0], [900, 0], [900, 400]]\norigin_lonlat = [true, 40]\n"),
                      "origin_lonlat")


def test_nan_in_vertices_lonlat_is_blamed_on_the_vertices(tmp_path):
    path = _toml(tmp_path, "vertices_lonlat = [[nan, 40.234], [-111.80, 40.234], [-111.80, 40.24]]\n")
    text = _one_line_refusal(path, "vertices_lonlat")
    assert "origin_lonlat must" not in text


def test_vertices_far_from_the_origin_are_refused_with_the_limit(tmp_path):
    # 900 m x 400 m in Utah with the origin in Spain: the geodesic distance is ~8,500 km
    body = ("vertices_lonlat = [[-111.81, 40.234], [-111.8, 40.234], [-111.8, 40.238]]\n"
            "origin_lonlat = [-3.7, 40.4]\n")
    _one_line_refusal(_toml(tmp_path, body), "km from origin_lonlat", "within 100 km")
    far_m = "vertices_m = [[0, 0], [900, 0], [900, 400]]\norigin_lonlat = [0, 0]\n"
    assert load_area(_toml(tmp_path, far_m)).area_m2 == pytest.approx(180_000)
    moved = "vertices_m = [[5e6, 0], [5000900, 0], [5000900, 400]]\norigin_lonlat = [0, 0]\n"
    _one_line_refusal(_toml(tmp_path, moved), "from the local origin", "within 100 km")


def test_lines_near_the_origin_keep_their_geodesic_length(tmp_path):
    import pyproj

    body = "vertices_lonlat = [[-111.81, 40.234], [-111.8, 40.234], [-111.8, 40.238], [-111.81, 40.238]]\n"
    area = load_area(_toml(tmp_path, body))
    xy = np.asarray(area.polygon.exterior.coords)
    _, _, south = pyproj.Geod(ellps="WGS84").inv(-111.81, 40.234, -111.8, 40.234)
    assert np.hypot(*(xy[1] - xy[0])) == pytest.approx(south, rel=1e-6)


def test_holes_m_with_vertices_lonlat_are_holes(tmp_path):
    import shapely

    outer = "vertices_lonlat = [[-111.81, 40.234], [-111.8, 40.234], [-111.8, 40.238], [-111.81, 40.238]]\n"
    whole = load_area(_toml(tmp_path, outer, "whole.toml"))
    hole = [[100, 100], [200, 100], [200, 200], [100, 200]]
    holed = load_area(_toml(tmp_path, outer + f"holes_m = {[hole]}\n", "holed.toml"))
    assert len(holed.polygon.interiors) == 1
    assert whole.area_m2 - holed.area_m2 == pytest.approx(shapely.Polygon(hole).area, rel=1e-9)


def test_too_many_vertices_and_too_large_files_are_refused_before_parsing(tmp_path, monkeypatch):
    t = np.linspace(0, 2 * np.pi, sa.MAX_VERTICES + 2)[:-1]
    ring = np.column_stack([1000 * np.cos(t), 1000 * np.sin(t)]).round(3).tolist()
    _one_line_refusal(_toml(tmp_path, f"vertices_m = {ring}\n"), "vertices, more than 100,000")
    monkeypatch.setattr(sa, "MAX_FILE_BYTES", 1000)
    _one_line_refusal(_toml(tmp_path, "vertices_m = [[0, 0], [900, 0], [900, 400]]\n" + "#" * 2000 + "\n"),
                      "bytes, more than 1,000")


def test_paths_that_are_not_files_say_what_they_are(tmp_path):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    for path, fragment in [(tmp_path, "is a directory"), (fifo, "is a FIFO"), ("/dev/zero", "character device"),
                           ("", "the path is empty"), (tmp_path / "none.toml", "does not exist")]:
        _one_line_refusal(path, fragment)
    link = tmp_path / "broken.toml"
    link.symlink_to(tmp_path / "gone.toml")
    _one_line_refusal(link, "broken link")


def _area_toml(tmp_path, body):
    p = tmp_path / "a.toml"
    p.write_text('[area]\nvertices_m = [[0, 0], [400, 0], [400, 300], [0, 300]]\nwater_depth_m = 9.0\n' + body)
    return str(p)


def test_a_misspelt_area_key_gets_the_nearest_known_key(tmp_path):
    """As in the data files (``--data``), a misspelt key of the area file is refused naming it
    and the key it was probably meant to be."""
    with pytest.raises(ValueError, match=r"a\.toml: area\.hole_m: unknown key 'hole_m'; did you mean `holes_m`\?"):
        load_area(_area_toml(tmp_path, "hole_m = [[[10, 10], [20, 10], [20, 20]]]\n"))


@pytest.mark.parametrize("hole, message", [
    ([[350, 100], [450, 100], [450, 150], [350, 150]], r"hole 1 is not inside the area's outline \(50% of it lies outside\)"),
    ([[100, 100], [150, 150], [150, 100], [100, 150]], r"hole 1 is not valid \(Self-intersection"),
    ([[380, 100], [400, 100], [400, 200], [380, 200]], r"hole 1 runs along the area's outline; .* notch"),
])
def test_a_bad_hole_is_named_with_what_is_wrong(tmp_path, hole, message):
    """A pier drawn half outside the outline, a hole whose vertices cross, a pier drawn against
    the wall: each refused naming the hole and what is wrong (the polygon's own validity reason,
    from shapely, named the outline before)."""
    with pytest.raises(ValueError, match=message):
        load_area(_area_toml(tmp_path, f"holes_m = [{hole}]\n"))
    fine = [[100, 100], [150, 100], [150, 200], [100, 200]]
    assert len(load_area(_area_toml(tmp_path, f"holes_m = [{fine}]\n")).polygon.interiors) == 1
