"""Mission files of a survey plan read back by independent readers: pymavlink's waypoint loader
(.waypoints, field by field), the keys QGroundControl requires (.plan), shapely (fences, GeoJSON
read back), RFC 7946's rules; convex, concave, holed and antimeridian areas; a vehicle without
ArduPilot and a missing origin refused; the files published with the figure's manifest."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")

from sss_locus.experiments.survey_design.area import MIN_CLEARANCE_M, area_from_vertices, load_area  # noqa: E402
from sss_locus.experiments.survey_design.plans import Plan  # noqa: E402
from sss_locus.pipeline.publish.missions import mission_files  # noqa: E402

ORIGIN = (-111.811, 40.234)
VERTS = [[0.0, 0.0], [900.0, 0.0], [900.0, 380.0], [520.0, 560.0], [0.0, 450.0]]
HARBOUR = [[0, 0], [900, 0], [900, 380], [520, 560], [300, 250], [0, 450]]  # concave: a notch
ISLAND = [[600, 120], [700, 120], [700, 200], [600, 200]]
AREAS = {  # name: vertices, holes, origin (lon, lat)
    "convex": (VERTS, [], ORIGIN),
    "concave": (HARBOUR, [], ORIGIN),
    "holed": (HARBOUR, [ISLAND], ORIGIN),
    "antimeridian": (HARBOUR, [ISLAND], (179.997, -16.5)),  # the area spans lon 180 (Fiji)
}
BOAT = dict(depth_m=0.0, turn_radius_m=3.0, speed_m_s=1.5)


def _plan(area, heading=30.0):
    """Main lines and cross lines at 90 deg, flown as the design flies them (reach, run-in)."""
    return Plan(heading, 150.0, 90.0, 300.0, 20.0, 0.0, "", 140.0, 6.0, 10.0).lines(area)


@pytest.fixture(scope="module")
def plan_files():
    verts, holes, origin = AREAS["holed"]
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name="test area")
    lines = _plan(area)
    return area, lines, mission_files(area, lines, ardupilot=True, **BOAT)


def _local(origin):
    """lon/lat -> local metres, built here with pyproj (independent of the area's own transform)."""
    from pyproj import Transformer

    t = Transformer.from_crs("EPSG:4326", f"+proj=aeqd +lat_0={origin[1]} +lon_0={origin[0]} +ellps=WGS84",
                             always_xy=True)
    return lambda lon, lat: np.column_stack(t.transform(np.asarray(lon, float), np.asarray(lat, float)))


def _csv(files):
    import io

    return pd.read_csv(io.StringIO(files["mission.csv"]))


def test_waypoints_read_back_by_pymavlink_field_by_field(plan_files, tmp_path):
    mavwp = pytest.importorskip("pymavlink.mavwp")
    area, lines, files = plan_files
    path = tmp_path / "m.waypoints"
    path.write_text(files["mission.waypoints"])
    loader = mavwp.MAVWPLoader()
    points = _csv(files)
    assert loader.load(str(path)) == len(points) + 3  # home, speed, the waypoints, return to launch
    items = [loader.wp(i) for i in range(loader.count())]
    assert items[0].frame == 0 and items[0].command == 16 and items[0].z == 0.0  # home, row 0
    speed = items[1]
    assert (speed.command, speed.param1, speed.param2, speed.param3) == (178, 1.0, BOAT["speed_m_s"], -1.0)
    assert items[-1].command == 20  # the end of the mission: return to launch
    wps = items[2:-1]
    assert {w.command for w in wps} == {16} and {w.frame for w in wps} == {3} and {w.z for w in wps} == {0.0}
    assert [w.seq for w in items] == list(range(len(items)))
    lon, lat = area.to_lonlat(points.east_m.to_numpy(), points.north_m.to_numpy())
    assert np.allclose([w.x for w in wps], lat, atol=1e-7) and np.allclose([w.y for w in wps], lon, atol=1e-7)
    # every segment's ends are waypoints, in run order
    ends = points[points.kind.isin(["line start", "line end"])][["east_m", "north_m"]].to_numpy()
    want = np.column_stack([lines[["x0_m", "y0_m"]].to_numpy(), lines[["x1_m", "y1_m"]].to_numpy()]).reshape(-1, 2)
    assert np.allclose(ends, want)
    for line in files["mission.waypoints"].splitlines()[1:]:
        assert len(line.split("\t")) == 12


def test_plan_has_every_key_qgroundcontrol_requires(plan_files):
    area, lines, files = plan_files
    doc = json.loads(files["mission.plan"])
    assert doc["fileType"] == "Plan" and {"version", "groundStation", "mission", "geoFence", "rallyPoints"} <= set(doc)
    mission = doc["mission"]
    assert {"items", "plannedHomePosition", "firmwareType", "vehicleType", "cruiseSpeed", "hoverSpeed",
            "version"} <= set(mission)
    assert mission["vehicleType"] == 11 and mission["firmwareType"] == 3  # an ArduPilot surface boat
    points = _csv(files)
    cmds = [i["command"] for i in mission["items"]]
    assert cmds == [178] + [16] * len(points) + [20]
    assert mission["items"][0]["params"][:3] == [1.0, BOAT["speed_m_s"], -1.0]
    for item, (_, p) in zip(mission["items"][1:-1], points.iterrows()):
        assert item["type"] == "SimpleItem" and len(item["params"]) == 7
        assert {"autoContinue", "doJumpId", "frame", "AltitudeMode", "Altitude"} <= set(item)
        assert item["params"][4] == pytest.approx(p.lat, abs=1e-7) and item["params"][5] == pytest.approx(p.lon, abs=1e-7)
    fences = doc["geoFence"]["polygons"]
    assert [f["inclusion"] for f in fences] == [True, False]  # the area's one hole is an exclusion fence


@pytest.mark.parametrize("name", AREAS)
def test_every_waypoint_and_turn_is_inside_the_written_fence(name):
    """Read back from the files: every waypoint and every leg between them (lines, U-turns,
    transits) inside the .plan's inclusion fence and outside its exclusion fences, in local
    metres of a projection made here; U-turns no tighter than the turn radius; the legs of a
    line's two segments do not cross the island."""
    import shapely

    verts, holes, origin = AREAS[name]
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name)
    files = mission_files(area, _plan(area), ardupilot=True, **BOAT)
    doc = json.loads(files["mission.plan"])
    local = _local(origin)
    items = [i for i in doc["mission"]["items"] if i["command"] == 16]
    xy = local([i["params"][5] for i in items], [i["params"][4] for i in items])
    fence = [shapely.Polygon(local([q[1] for q in f["polygon"]], [q[0] for q in f["polygon"]]))
             for f in doc["geoFence"]["polygons"]]
    track = shapely.LineString(xy)
    assert fence[0].buffer(0.01).covers(track), track.difference(fence[0]).length
    assert len(fence) == 1 + len(holes)
    for f, hole in zip(fence[1:], holes):
        assert f.equals_exact(shapely.Polygon(hole), 0.01) and not track.intersects(f.buffer(-0.01))
    # the turns: the circle through three consecutive turn points is no tighter than the radius
    kind = _csv(files).kind.to_numpy()
    for k in np.flatnonzero((kind[1:-1] == "turn") & (kind[:-2] == "turn") & (kind[2:] == "turn")) + 1:
        a, b, c = xy[k - 1], xy[k], xy[k + 1]
        area2 = abs((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0])
        if area2 > 1e-6:
            radius = np.linalg.norm(b - a) * np.linalg.norm(c - b) * np.linalg.norm(c - a) / (2 * area2)
            assert radius >= 0.98 * BOAT["turn_radius_m"]


def _positions(geom):
    c = geom["coordinates"]
    depth = {"Point": 0, "LineString": 1, "Polygon": 2, "MultiLineString": 2, "MultiPolygon": 3}[geom["type"]]
    for _ in range(depth - 1):
        c = [x for part in c for x in part]
    return c


@pytest.mark.parametrize("name", ["holed", "antimeridian", "polar"])
def test_geojson_follows_rfc_7946(name):
    """RFC 7946: lon/lat in range, at most 7 decimals, exteriors counter-clockwise and holes
    clockwise, rings closed, nothing jumping across the antimeridian (cut there instead), and
    the track's lon/lat chords within 0.1 m of the local straight legs (densified)."""
    import re

    import shapely

    verts, holes, origin = AREAS[name] if name != "polar" else (HARBOUR, [ISLAND], (20.0, 86.0))  # lon/lat chords bend
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name)
    files = mission_files(area, _plan(area), ardupilot=False, **BOAT)
    text = files["mission.geojson"]
    assert not re.search(r"\d\.\d{8,}", text)  # at most 7 decimals
    doc = json.loads(text)
    signed = lambda r: 0.5 * np.sum(r[:-1, 0] * r[1:, 1] - r[1:, 0] * r[:-1, 1])  # noqa: E731
    types = set()
    for f in doc["features"]:
        g = f["geometry"]
        types.add(g["type"])
        pos = np.asarray(_positions(g))
        assert np.all(np.abs(pos[:, 0]) <= 180.0) and np.all(np.abs(pos[:, 1]) <= 90.0)
        polys = [g["coordinates"]] if g["type"] == "Polygon" else g["coordinates"] if g["type"] == "MultiPolygon" else []
        for poly in polys:
            rings = [np.asarray(r) for r in poly]
            assert all(np.array_equal(r[0], r[-1]) for r in rings)
            assert signed(rings[0]) > 0 and all(signed(r) < 0 for r in rings[1:])
        parts = [g["coordinates"]] if g["type"] == "LineString" else g["coordinates"] if g["type"] == "MultiLineString" \
            else [r for poly in polys for r in poly]
        for part in parts:
            assert np.all(np.abs(np.diff(np.asarray(part)[:, 0])) < 180.0)
    if name == "antimeridian":
        assert {"MultiLineString", "MultiPolygon"} <= types
    # densified: every chord of the track within 0.1 m (+ 1 cm of rounding) of the flown legs
    local = _local(origin)
    pts = _csv(files)
    legs = shapely.LineString(pts[["east_m", "north_m"]].to_numpy())
    track = next(f["geometry"] for f in doc["features"] if f["properties"].get("role") == "track")
    for part in ([track["coordinates"]] if track["type"] == "LineString" else track["coordinates"]):
        p = np.asarray(part)
        mid = local(0.5 * (p[1:, 0] + p[:-1, 0]), 0.5 * (p[1:, 1] + p[:-1, 1]))
        assert shapely.distance(legs, shapely.points(mid)).max() <= 0.11
    # compass courses: a line of local heading 30 deg (from east) runs at about 60 deg true
    lines = [f["properties"] for f in doc["features"] if f["properties"].get("role") == "survey line"]
    main = {round(p["course_true_deg"]) for p in lines if p["set"] == "main"}
    assert main <= {60, 240}, main


def test_a_vehicle_without_ardupilot_gets_csv_and_geojson_only(plan_files):
    area, lines, _ = plan_files
    files = mission_files(area, lines, ardupilot=False, **BOAT)
    assert list(files) == ["mission.csv", "mission.geojson"]
    with pytest.raises(ValueError, match="does not run ArduPilot") as err:
        mission_files(area, lines, ardupilot=False, formats=["plan"], **BOAT)
    assert "\n" not in str(err.value)


def test_geojson_round_trips_through_shapely(plan_files, tmp_path):
    from shapely.geometry import shape

    area, lines, files = plan_files
    doc = json.loads(files["mission.geojson"])
    roles = [f["properties"]["role"] for f in doc["features"]]
    assert roles.count("survey line") == len(lines) and roles.count("exclusion fence") == 1
    polygon = shape(doc["features"][0]["geometry"])
    rings = [np.column_stack(area.to_lonlat(*np.asarray(r.coords).T)).tolist()
             for r in (area.polygon.exterior, *area.polygon.interiors)]
    assert shape({"type": "Polygon", "coordinates": rings}).symmetric_difference(polygon).area < 1e-4 * polygon.area
    fence = shape(doc["features"][1]["geometry"])
    assert all(fence.buffer(1e-7).contains(shape(f["geometry"])) for f in doc["features"][3:])
    # read back as a survey area: the same polygon in local metres
    path = tmp_path / "back.geojson"
    path.write_text(files["mission.geojson"])
    back = load_area(path)
    assert back.origin_lonlat == pytest.approx(ORIGIN)
    assert back.polygon.hausdorff_distance(area.polygon) < 0.05


def test_geographic_formats_need_an_origin():
    area = area_from_vertices(VERTS)
    lines = Plan(0.0, 150.0, math.nan, 150.0, 20.0).lines(area)
    only_csv = mission_files(area, lines, ardupilot=True, **BOAT)
    assert "-0.0" not in only_csv["mission.csv"]
    assert list(only_csv) == ["mission.csv"]
    assert list(pd.read_csv(__import__("io").StringIO(only_csv["mission.csv"])).columns) == [
        "seq", "kind", "set", "line", "segment", "east_m", "north_m", "depth_m"]
    for fmt in ("plan", "waypoints", "geojson"):
        with pytest.raises(ValueError, match="has no origin") as err:
            mission_files(area, lines, ardupilot=True, formats=[fmt], **BOAT)
        assert "\n" not in str(err.value)


def test_attachments_are_listed_in_the_figure_manifest(tmp_path):
    import hashlib

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.pipeline.publish.export import export_figure

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


def test_a_harbour_with_a_shore_keeps_the_track_in_its_water():
    """An L-shaped harbour with an island whose water ends 10 m past its edge (water_beyond_m):
    every waypoint and leg (lines, turns, transits) within that water, none across the island,
    read back from the .plan in a projection made here; the fence is no wider than the water
    grown by a few metres."""
    import dataclasses

    import shapely

    harbour = [[0, 0], [600, 0], [600, 330], [300, 330], [300, 660], [0, 660]]
    island = [[380, 120], [460, 120], [460, 200], [380, 200]]
    origin = (-70.671, 41.524)
    area = dataclasses.replace(area_from_vertices(harbour, holes_m=[island], origin_lonlat=origin, name="cove"),
                               water_beyond_m=10.0)
    for heading in (0.0, 90.0, 30.0):
        files = mission_files(area, _plan(area, heading), ardupilot=True, **BOAT)
        doc = json.loads(files["mission.plan"])
        local = _local(origin)
        items = [i for i in doc["mission"]["items"] if i["command"] == 16]
        track = shapely.LineString(local([i["params"][5] for i in items], [i["params"][4] for i in items]))
        water = shapely.Polygon(harbour).buffer(10.0)
        assert water.buffer(0.05).covers(track), (heading, track.difference(water).length)
        assert not track.intersects(shapely.Polygon(island).buffer(-0.01))
        fence = doc["geoFence"]["polygons"][0]["polygon"]
        fence_xy = shapely.Polygon(local([q[1] for q in fence], [q[0] for q in fence]))
        assert fence_xy.covers(track) and fence_xy.difference(water).area < 0.05 * water.area


def test_a_transit_along_a_shore_steps_in_by_the_turn_radius_not_across_the_harbour():
    """A harbour with a shore all round (water_beyond_m = 0) whose lines end on its walls, 192 m
    apart: no U-turn fits, so each junction is a transit; the shortest way that keeps the turn
    radius R off the shore is in by R, along the wall, out by R (192 + 2 R m). Before, the ends
    could see only far corners of the shrunk water and the boat crossed the harbour (0.7-1 km)."""
    import dataclasses

    from sss_locus.experiments.survey_design.route import flight_path

    harbour = [[0, 0], [800, 0], [800, 350], [500, 350], [500, 700], [0, 700]]  # L-shaped, concave
    area = dataclasses.replace(area_from_vertices(harbour, name="walled"), water_beyond_m=0.0)
    c = MIN_CLEARANCE_M  # the lines end as close to the walls as a track may come
    lines = pd.DataFrame([("main", 0, 0, 90.0, c, 96, 800 - c, 96), ("main", 1, 0, 270.0, 800 - c, 288, c, 288),
                          ("main", 2, 0, 90.0, c, 480, 500 - c, 480), ("main", 3, 0, 270.0, 500 - c, 672, c, 672)],
                         columns=["set", "line", "segment", "heading_deg", "x0_m", "y0_m", "x1_m", "y1_m"])
    R = 5.0
    path, _, _ = flight_path(area, lines, R)
    xy = path[["east_m", "north_m"]].to_numpy()
    ends, starts = np.flatnonzero(path.kind == "line end")[:-1], np.flatnonzero(path.kind == "line start")[1:]
    assert len(ends) == len(starts) == 3
    for e, s in zip(ends, starts):
        flown = np.linalg.norm(np.diff(xy[e:s + 1], axis=0), axis=1).sum()
        assert flown == pytest.approx(192.0 + 2 * R, abs=0.5), (e, s, flown)


@pytest.mark.parametrize("name", ["concave", "holed"])
def test_a_line_segment_beyond_the_notch_is_inside_the_fence_and_the_mission_is_written(name):
    """Lines heading east over the notched harbour: the top line's second segment lies beyond
    the notch, more than twice the fence's margin from the rest; the fence kept only its largest
    part, so that segment was outside it and writing the mission failed ("592.4 m of the track
    leave the inclusion fence"): the chapter crashed on such a plan. Read back from the .plan:
    every leg inside the inclusion fence, none across the island."""
    import shapely

    verts, holes, origin = AREAS[name]
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name)
    lines = _plan(area, heading=0.0)
    outer = shapely.Polygon(verts).buffer(2 * (BOAT["turn_radius_m"] + 5.0))
    apart = [r for r in lines.itertuples() if not outer.intersects(shapely.LineString([(r.x0_m, r.y0_m), (r.x1_m, r.y1_m)]))]
    assert apart  # the case this test is about: a segment away from the area
    doc = json.loads(mission_files(area, lines, ardupilot=True, **BOAT)["mission.plan"])
    local = _local(origin)
    items = [i for i in doc["mission"]["items"] if i["command"] == 16]
    track = shapely.LineString(local([i["params"][5] for i in items], [i["params"][4] for i in items]))
    f = doc["geoFence"]["polygons"][0]["polygon"]
    fence = shapely.Polygon(local([q[1] for q in f], [q[0] for q in f]))
    assert fence.buffer(0.01).covers(track), track.difference(fence).length
    assert not any(track.intersects(shapely.Polygon(h).buffer(-0.01)) for h in holes)


@pytest.mark.parametrize("name", AREAS)
def test_return_to_launch_flies_no_leg_outside_the_fence(name, tmp_path):
    """ArduPilot's return to launch (the last item) flies straight from the last waypoint to home
    (item 0): read back with pymavlink, that leg stays inside the .plan's inclusion fence and off
    the island for every heading. Before, it ran from the last line's end across the area and out
    of the fence (32.5 m outside on the convex area at 30 deg)."""
    import shapely
    from pymavlink import mavwp

    verts, holes, origin = AREAS[name]
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name)
    local = _local(origin)
    for heading in (0.0, 30.0, 90.0):
        files = mission_files(area, _plan(area, heading), ardupilot=True, **BOAT)
        (tmp_path / "m.waypoints").write_text(files["mission.waypoints"])
        loader = mavwp.MAVWPLoader()
        loader.load(str(tmp_path / "m.waypoints"))
        items = [loader.wp(i) for i in range(loader.count())]
        assert items[-1].command == 20  # MAV_CMD_NAV_RETURN_TO_LAUNCH
        last = [it for it in items if it.command == 16][-1]
        leg = shapely.LineString(local([last.y, items[0].y], [last.x, items[0].x]))
        f = json.loads(files["mission.plan"])["geoFence"]["polygons"][0]["polygon"]
        fence = shapely.Polygon(local([q[1] for q in f], [q[0] for q in f]))
        assert fence.buffer(0.01).covers(leg), (heading, leg.difference(fence).length)
        assert not any(leg.intersects(shapely.Polygon(h).buffer(-0.01)) for h in holes), heading


@pytest.mark.parametrize("name", ["concave", "holed"])
def test_a_plans_cost_is_the_length_the_mission_flies(name, tmp_path):
    """The design's cost of a plan (``evaluate``'s ``total_m`` and ``time_h``) against the path
    of the mission file's waypoints read back by pymavlink, measured here with pyproj's geodesic
    on WGS 84 (home, then every waypoint; return to launch flies no leg: the track ends at home).
    The old formula (lines plus U-turns, no transits, no return) is shorter than the mission."""
    from pymavlink import mavwp
    from pyproj import Geod

    from sss_locus.experiments.survey_design import front as sd
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.survey_design.front import plan_from_row
    from sss_locus.experiments.survey_design.lines import track_length

    verts, holes, origin = AREAS[name]
    area = dataclasses.replace(area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name),
                               water_depth_m=20.0, water_depth_source="test")
    boat = load_platform("boat")
    s = sd.make_setting(boat, area, "flat", n_features=20, seed=0, grid_m=20.0)
    plan = sd.standard_for(s)
    row = sd.evaluate(s, plan)
    lines = plan_from_row(row).lines(area)
    files = mission_files(area, lines, ardupilot=True, depth_m=0.0, turn_radius_m=boat.turn_radius_m,
                          speed_m_s=boat.speed_m_s)
    (tmp_path / "m.waypoints").write_text(files["mission.waypoints"])
    loader = mavwp.MAVWPLoader()
    loader.load(str(tmp_path / "m.waypoints"))
    items = [loader.wp(i) for i in range(loader.count())]
    nav = [it for it in items if it.command == 16]  # home and the waypoints
    lat, lon = np.array([it.x for it in nav]), np.array([it.y for it in nav])
    flown = float(np.sum(Geod(ellps="WGS84").inv(lon[:-1], lat[:-1], lon[1:], lat[1:])[2]))
    assert row["total_m"] == pytest.approx(flown, rel=1e-4, abs=0.5)
    assert row["time_h"] == pytest.approx(flown / boat.speed_m_s / 3600.0, rel=1e-4)
    assert row["lines_m"] + row["turns_m"] + row["transits_m"] == pytest.approx(row["total_m"])
    assert row["lines_m"] == pytest.approx(lines.length_m.sum())
    assert track_length(lines, boat.turn_radius_m)["total_m"] < flown - 100.0


@pytest.mark.parametrize("name", AREAS)
def test_no_waypoint_repeats_the_one_before_it(name, tmp_path):
    """Every leg of the mission, as pymavlink loads it, has a length: a U-turn's first arc ends at
    its tangent point once, not twice (a zero-length leg the autopilot reaches on the spot)."""
    mavwp = pytest.importorskip("pymavlink.mavwp")
    verts, holes, origin = AREAS[name]
    area = area_from_vertices(verts, holes_m=holes, origin_lonlat=origin, name=name)
    files = mission_files(area, _plan(area), ardupilot=True, **BOAT)
    (tmp_path / "m.waypoints").write_text(files["mission.waypoints"])
    loader = mavwp.MAVWPLoader()
    loader.load(str(tmp_path / "m.waypoints"))
    wps = [loader.wp(i) for i in range(2, loader.count() - 1)]  # after home and the speed item, before RTL
    leg = np.hypot(np.diff([w.x for w in wps]) * 111e3,
                   np.diff([w.y for w in wps]) * 111e3 * math.cos(math.radians(origin[1])))
    assert len(wps) > 20 and leg.min() > 0.01, np.flatnonzero(leg <= 0.01)
