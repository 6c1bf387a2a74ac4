"""Mission files of a survey plan read back by independent readers: pymavlink's waypoint loader
(.waypoints), the keys QGroundControl requires (.plan), shapely (GeoJSON); a missing origin
refused; the files published with the figure's manifest."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.survey_area import area_from_vertices, load_area  # noqa: E402
from sss_locus.experiments.survey_plans import Plan  # noqa: E402
from sss_locus.pipeline.missions import mission_files  # noqa: E402

ORIGIN = (-111.811, 40.234)
VERTS = [[0.0, 0.0], [900.0, 0.0], [900.0, 380.0], [520.0, 560.0], [0.0, 450.0]]


@pytest.fixture(scope="module")
def plan_files():
    area = area_from_vertices(VERTS, origin_lonlat=ORIGIN, name="test area")
    lines = Plan(0.0, 150.0, 90.0, 300.0, 20.0).lines(area)
    files = mission_files(area, lines, depth_m=10.0, submerged=True, speed_m_s=1.5)
    return area, lines, files


def _ends_lonlat(area, lines):
    x = np.ravel(np.column_stack([lines.x0_m, lines.x1_m]))
    y = np.ravel(np.column_stack([lines.y0_m, lines.y1_m]))
    return area.to_lonlat(x, y)


def test_waypoints_read_back_by_pymavlink(plan_files, tmp_path):
    mavwp = pytest.importorskip("pymavlink.mavwp")
    area, lines, files = plan_files
    path = tmp_path / "m.waypoints"
    path.write_text(files["mission.waypoints"])
    loader = mavwp.MAVWPLoader()
    assert loader.load(str(path)) == 2 * len(lines) + 1
    items = [loader.wp(i) for i in range(loader.count())]
    assert items[0].frame == 0 and items[0].z == 0.0  # home, row 0
    lon, lat = _ends_lonlat(area, lines)
    assert np.allclose([w.x for w in items[1:]], lat, atol=1e-7)
    assert np.allclose([w.y for w in items[1:]], lon, atol=1e-7)
    assert {w.command for w in items} == {16} and {w.z for w in items[1:]} == {-10.0}
    for line in files["mission.waypoints"].splitlines()[1:]:
        assert len(line.split("\t")) == 12


def test_plan_has_every_key_qgroundcontrol_requires(plan_files):
    area, lines, files = plan_files
    doc = json.loads(files["mission.plan"])
    assert doc["fileType"] == "Plan" and {"version", "groundStation", "mission", "geoFence", "rallyPoints"} <= set(doc)
    mission = doc["mission"]
    assert {"items", "plannedHomePosition", "firmwareType", "vehicleType", "cruiseSpeed", "hoverSpeed",
            "version"} <= set(mission)
    assert len(mission["plannedHomePosition"]) == 3
    lon, lat = _ends_lonlat(area, lines)
    assert len(mission["items"]) == len(lon)
    for item, x, y in zip(mission["items"], lat, lon):
        assert item["type"] == "SimpleItem" and item["command"] == 16 and len(item["params"]) == 7
        assert {"autoContinue", "doJumpId", "frame", "AltitudeMode", "Altitude"} <= set(item)
        assert item["params"][4] == pytest.approx(x, abs=1e-9) and item["params"][5] == pytest.approx(y, abs=1e-9)
    fence = doc["geoFence"]["polygons"][0]
    assert fence["inclusion"] and len(fence["polygon"]) == len(VERTS)


def test_geojson_round_trips_through_shapely(plan_files, tmp_path):
    from shapely.geometry import shape

    area, lines, files = plan_files
    doc = json.loads(files["mission.geojson"])
    polygons = [shape(f["geometry"]) for f in doc["features"] if f["geometry"]["type"] == "Polygon"]
    segments = [shape(f["geometry"]) for f in doc["features"] if f["geometry"]["type"] == "LineString"]
    assert len(polygons) == 1 and len(segments) == len(lines)
    ring = np.asarray(area.polygon.exterior.coords)
    assert np.allclose(np.asarray(polygons[0].exterior.coords), np.column_stack(area.to_lonlat(*ring.T)))
    assert all(polygons[0].buffer(1e-6).contains(s) for s in segments)  # 1e-6 deg: 0.1 m
    # read back as a survey area: the same polygon in local metres
    path = tmp_path / "back.geojson"
    path.write_text(files["mission.geojson"])
    back = load_area(path)
    assert back.origin_lonlat == pytest.approx(ORIGIN)
    assert back.polygon.hausdorff_distance(area.polygon) < 1e-6


def test_geographic_formats_need_an_origin():
    area = area_from_vertices(VERTS)
    lines = Plan(0.0, 150.0, math.nan, 150.0, 20.0).lines(area)
    only_csv = mission_files(area, lines, depth_m=0.0, submerged=False, speed_m_s=1.0)
    assert "-0.0" not in only_csv["mission.csv"]
    assert list(only_csv) == ["mission.csv"]
    assert list(pd.read_csv(__import__("io").StringIO(only_csv["mission.csv"])).columns) == [
        "seq", "set", "line", "segment", "point", "east_m", "north_m", "depth_m"]
    for fmt in ("plan", "waypoints", "geojson"):
        with pytest.raises(ValueError, match="has no origin") as err:
            mission_files(area, lines, depth_m=0.0, submerged=False, speed_m_s=1.0, formats=[fmt])
        assert "\n" not in str(err.value)


def test_attachments_are_listed_in_the_figure_manifest(tmp_path):
    import hashlib

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.pipeline.export import export_figure

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    manifest = export_figure(fig, "fig-mission-test", pd.DataFrame({"a": [1]}), caption="A test.",
                             parameters={}, out_dir=tmp_path, attachments={"mission.plan": "{}\n"})
    plt.close(fig)
    entry = manifest["files"]["fig-mission-test--mission.plan"]
    assert isinstance(manifest["text"], dict) and manifest["text"]["min_size_pt"] > 0  # readability kept
    assert entry["sha256"] == hashlib.sha256(b"{}\n").hexdigest()
    with pytest.raises(ValueError, match="attachments must map"):
        export_figure(fig, "fig-mission-test", pd.DataFrame({"a": [1]}), caption="A test.", parameters={},
                      out_dir=tmp_path, attachments={"../evil": "x"})
