"""The mission of a new user's trial plan (their 900 kHz ROV over an L-shaped block of Bedford
Basin with an island hole, ``tests/data/trial/``): the standard plan's first line runs 32 m
south of the area's edge, joined to the rest only by its U-turn at the east end; its inclusion
fence had a 10 m x 3 km slit between that line and the area. Read back from the ``.plan`` with
pymavlink (the waypoints) and the fence with shapely."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.datamodel import userdata  # noqa: E402
from sss_locus.experiments.datamodel.platforms import load_platform  # noqa: E402
from sss_locus.experiments.survey_design.area import load_area  # noqa: E402
from sss_locus.experiments.survey_design.front import make_setting  # noqa: E402
from sss_locus.experiments.survey_design.plans import standard_plan  # noqa: E402
from sss_locus.pipeline.publish.missions import mission_files  # noqa: E402

DATA = Path(__file__).parents[2] / "data" / "trial"
MARGIN_M = 5.0  # the fence's margin beyond the track grown by the turn radius (route.fences' default)


@pytest.fixture(scope="module")
def trial():
    userdata.use([str(DATA / "rov9.toml")], [])
    try:
        pf = load_platform("rov9")
        area = load_area(DATA / "bedford.toml")
        s = make_setting(pf, area, "flat", n_features=60, seed=1, grid_m=40.0)
        plan = standard_plan(pf, area, s.terrain, s.settings, s.heights_m)
        lines = plan.lines(area)
        files = mission_files(area, lines, depth_m=34.4, turn_radius_m=pf.turn_radius_m, speed_m_s=pf.speed_m_s,
                              ardupilot=True)
        yield area, pf, lines, files
    finally:
        userdata.use()  # leave the process with the shipped data only


def _local(origin):
    """lon/lat -> local metres, built here with pyproj (independent of the area's own transform)."""
    from pyproj import Transformer

    t = Transformer.from_crs("EPSG:4326", f"+proj=aeqd +lat_0={origin[1]} +lon_0={origin[0]} +ellps=WGS84",
                             always_xy=True)
    return lambda lon, lat: np.column_stack(t.transform(np.asarray(lon, float), np.asarray(lat, float)))


def test_the_fence_has_no_slit_and_holds_the_whole_track_read_back_by_pymavlink(trial, tmp_path):
    """The ``.plan``'s inclusion fence is a valid polygon that covers every leg of the mission as
    pymavlink loads it from the ``.waypoints`` (and the last leg home), holds the whole area, and
    has no notch narrower than twice the fence's own room about the track (``R + margin``): a
    closing by that distance adds nothing (the old fence: 30,000 m^2, the slit)."""
    import shapely
    from pymavlink import mavwp

    area, pf, lines, files = trial
    doc = json.loads(files["mission.plan"])
    local = _local(area.origin_lonlat)
    ring = doc["geoFence"]["polygons"][0]["polygon"]
    fence = shapely.Polygon(local([q[1] for q in ring], [q[0] for q in ring]))
    assert fence.is_valid, shapely.is_valid_reason(fence)
    (tmp_path / "m.waypoints").write_text(files["mission.waypoints"])
    loader = mavwp.MAVWPLoader()
    loader.load(str(tmp_path / "m.waypoints"))
    wps = [loader.wp(i) for i in range(loader.count()) if loader.wp(i).command == 16]
    track = shapely.LineString(local([w.y for w in wps], [w.x for w in wps]))
    assert track.length > 0.95 * lines.length_m.sum()  # every line is in it
    assert fence.buffer(0.01).covers(track), track.difference(fence).length
    vertices = np.asarray(area.polygon.exterior.coords)
    lon, lat = area.to_lonlat(vertices[:, 0], vertices[:, 1])
    assert fence.buffer(0.01).covers(shapely.Polygon(local(lon, lat)))
    room = pf.turn_radius_m + MARGIN_M
    closed = fence.buffer(room, join_style="mitre").buffer(-room, join_style="mitre")
    assert closed.area - fence.area < 1.0, f"a slit of {closed.area - fence.area:.0f} m^2"


def test_the_first_line_runs_outside_the_area_as_in_the_trial(trial):
    """The case this file is about: a line more than twice the fence's room off the area's edge."""
    import shapely

    area, pf, lines, _ = trial
    first = lines.iloc[0]
    d = area.polygon.distance(shapely.LineString([(first.x0_m, first.y0_m), (first.x1_m, first.y1_m)]))
    assert d > 2 * (pf.turn_radius_m + MARGIN_M)
