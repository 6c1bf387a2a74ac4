"""A walled harbour: the area is where to survey, ``navigable_m`` the water the vehicle may use
(a concave basin with a pier). Read back from the written .plan (json, a projection made here
with pyproj): every waypoint and the densified flown track inside the written fence, the fence
inside the navigable water, the track ``wall_clearance_m`` off the walls and the pier; a turn
that cannot fit is named; bad navigable water refused in one line."""

from __future__ import annotations

import json

import numpy as np
import pytest

shapely = pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.survey_design.area import load_area  # noqa: E402
from sss_locus.experiments.survey_design.plans import Plan  # noqa: E402
from sss_locus.experiments.survey_design.settings import load_settings  # noqa: E402
from sss_locus.experiments.survey_design.route import turn_misfits  # noqa: E402
from sss_locus.pipeline.publish.missions import mission_files  # noqa: E402

ORIGIN = (4.2840, 51.9010)  # a harbour basin near Rotterdam (invented)
BASIN = [[0, 0], [520, 0], [520, 260], [260, 260], [260, 460], [0, 460]]  # L-shaped: concave
AREA = [[10, 10], [510, 10], [510, 250], [250, 250], [250, 450], [10, 450]]
PIER = [[300, 60], [320, 60], [320, 150], [300, 150]]  # a pier head: land inside the area, a hole


def _area_file(tmp_path, extra="wall_clearance_m = 6.0\n", navigable=BASIN, area=AREA, holes=(PIER,)):
    p = tmp_path / "basin.toml"
    p.write_text(f'[area]\nname = "basin"\nvertices_m = {area}\nholes_m = {[list(h) for h in holes]}\n'
                 f'origin_lonlat = [{ORIGIN[0]}, {ORIGIN[1]}]\nwater_depth_m = 12.0\nnavigable_m = {navigable}\n{extra}')
    return p


def _local(lon, lat):
    from pyproj import Transformer

    t = Transformer.from_crs("EPSG:4326", f"+proj=aeqd +lat_0={ORIGIN[1]} +lon_0={ORIGIN[0]} +ellps=WGS84",
                             always_xy=True)
    return np.column_stack(t.transform(np.asarray(lon, float), np.asarray(lat, float)))


@pytest.mark.parametrize("radius_m, heading", [(3.0, 0.0), (3.0, 30.0), (3.0, 90.0), (10.0, 0.0), (10.0, 60.0)])
def test_the_track_and_fence_stay_in_the_basin_off_its_walls_and_pier(tmp_path, radius_m, heading):
    area = load_area(_area_file(tmp_path))
    assert area.wall_clearance_m == 6.0
    plan = Plan(heading, 70.0, 90.0, 140.0, 10.0, 0.0, "", 60.0, 2 * radius_m, 3.0, radius_m)
    files = mission_files(area, plan.lines(area), ardupilot=True, depth_m=0.0, turn_radius_m=radius_m, speed_m_s=1.5)
    doc = json.loads(files["mission.plan"])
    items = [i for i in doc["mission"]["items"] if i["command"] == 16]
    xy = _local([i["params"][5] for i in items], [i["params"][4] for i in items])
    fences = doc["geoFence"]["polygons"]
    fence = shapely.Polygon(_local([q[1] for q in fences[0]["polygon"]], [q[0] for q in fences[0]["polygon"]]))
    assert fences[0]["inclusion"] and not fences[1]["inclusion"]  # the pier is an exclusion fence
    basin, pier = shapely.Polygon(BASIN), shapely.Polygon(PIER)
    track = shapely.segmentize(shapely.LineString(xy), 1.0)  # densified: every metre flown
    points = shapely.points(shapely.get_coordinates(track))
    assert shapely.covers(fence.buffer(0.02), points).all()
    assert basin.buffer(0.02).covers(fence), fence.difference(basin).area  # the fence never reaches onto land
    assert track.distance(basin.exterior) >= 6.0 - 0.05
    assert track.distance(pier) >= 6.0 - 0.05


def test_the_clearance_defaults_to_the_runs_data(tmp_path):
    area = load_area(_area_file(tmp_path, extra=""))
    assert area.wall_clearance_m == load_settings()["wall_clearance_m"] == 5.0


def test_a_turn_that_cannot_fit_is_named_and_joined_inside_the_water(tmp_path):
    """A channel 30 m wide with 6 m of clearance: lines across it (18 m long) leave no room for a
    10 m U-turn even pulled back; the design names each such turn and the track still stays in
    the water. With 3 m turns the ends are pulled back and every turn fits."""
    channel = [[0, 0], [400, 0], [400, 30], [0, 30]]
    area = load_area(_area_file(tmp_path, navigable=channel, area=channel, holes=()))
    plan = Plan(90.0, 30.0, float("nan"), 30.0, 10.0, 0.0, "", 40.0, 0.0, 3.0, 10.0)
    lines = plan.lines(area)
    notes = turn_misfits(area, lines, 10.0)
    assert notes and all(" does not fit in the navigable water" in n for n in notes)
    assert "the turn from main line 1 to line 2 does not fit" in notes[0]  # line 1 was pulled back for turn 0
    assert (lines.length_m >= 1.0).all()
    files = mission_files(area, lines, ardupilot=True, depth_m=0.0, turn_radius_m=10.0, speed_m_s=1.5)
    doc = json.loads(files["mission.plan"])
    items = [i for i in doc["mission"]["items"] if i["command"] == 16]
    track = shapely.LineString(_local([i["params"][5] for i in items], [i["params"][4] for i in items]))
    assert shapely.Polygon(channel).buffer(-6.0 + 0.05).covers(track)
    small = Plan(90.0, 30.0, float("nan"), 30.0, 10.0, 0.0, "", 40.0, 0.0, 3.0, 3.0)
    fitted = small.lines(area)
    assert turn_misfits(area, fitted, 3.0) == []
    assert fitted.length_m.max() < 30.0 - 2 * 6.0 - 1.0  # pulled back from the 18 m the clearance leaves


@pytest.mark.parametrize("navigable, extra, message", [
    ([[20, 20], [520, 0], [520, 260], [0, 460]], "", r"the navigable water must contain the area; \d+ m\^2 of the area"),
    (BASIN, "water_beyond_m = 5.0\n", "give one of navigable_m, navigable_lonlat or water_beyond_m"),
    (BASIN, "wall_clearance_m = -1\n", r"area\.wall_clearance_m must be a finite number in \[0\.0, 1000\.0\]; got -1"),
    ([[0, 0], [520, 460], [520, 0], [0, 460]], "", "not valid"),
])
def test_bad_navigable_water_is_refused_in_one_line(tmp_path, navigable, extra, message):
    with pytest.raises(ValueError, match=message) as err:
        load_area(_area_file(tmp_path, extra=extra, navigable=navigable))
    assert "\n" not in str(err.value) and "basin.toml" in str(err.value)


def test_the_plan_caption_names_the_navigable_water_its_clearance_and_the_turns_that_do_not_fit(tmp_path):
    import math

    import pandas as pd

    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.report.survey_design.prose import plan_caption

    area = load_area(_area_file(tmp_path))
    row = pd.Series(dict(heading_deg=0.0, spacing_m=120.0, crossing_deg=math.nan, cross_spacing_m=120.0,
                         altitude_m=12.0, pitch_deg=0.0, total_m=5000.0, time_h=0.9, run_m=6.0))
    note = "the turn from main line 3 to line 4 does not fit in the navigable water"
    text = plan_caption(load_platform("boat"), area, "basin.toml", row, dict(once=1.0, twice=0.5, n_holes=0),
                        ["mission.csv"], water_depth_m=12.0, depth_source="basin.toml: water_depth_m",
                        turn_notes=[note])
    assert "stay in the navigable water (its navigable outline), 6 m off its edge and holes" in text
    assert note in text and "never reaches past it" in text
    assert "5.00 km flown (the mission's track: lines, turns of radius 3 m, transits and the return" in text


def test_a_geojson_area_gives_its_navigable_water_and_clearance_as_properties(tmp_path):
    """The same basin as a GeoJSON Feature (RFC 7946 longitude/latitude): ``navigable_lonlat`` and
    ``wall_clearance_m`` in its properties, read into the area's local frame (checked here
    against the basin's metres through pyproj)."""
    from pyproj import Transformer

    t = Transformer.from_crs(f"+proj=aeqd +lat_0={ORIGIN[1]} +lon_0={ORIGIN[0]} +ellps=WGS84", "EPSG:4326",
                             always_xy=True)
    ll = lambda ring: [list(t.transform(x, y)) for x, y in ring]  # noqa: E731
    doc = {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ll(AREA + AREA[:1]), ll(PIER + PIER[:1])]},
           "properties": {"name": "basin", "origin_lonlat": list(ORIGIN), "water_depth_m": 12.0,
                          "navigable_lonlat": ll(BASIN), "wall_clearance_m": 3.0}}
    (tmp_path / "basin.geojson").write_text(json.dumps(doc))
    area = load_area(tmp_path / "basin.geojson")
    assert area.wall_clearance_m == 3.0
    water = shapely.from_wkt(area.navigable_wkt)
    assert water.symmetric_difference(shapely.Polygon(BASIN)).area < 1.0
