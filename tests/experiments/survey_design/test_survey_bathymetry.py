"""A survey area's bathymetry grid (a GeoTIFF the test writes with rasterio, in another CRS than
the area's): depths read back against the plane it holds, the design's coverage against a
closed-form swath at each cell's own depth, the AUV's limits from the shallowest and deepest
points, and every bad grid refused in one line naming the file."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")
rasterio = pytest.importorskip("rasterio")

from sss_locus.experiments.survey_design import front as sd  # noqa: E402
from sss_locus.experiments.datamodel.platforms import load_platform  # noqa: E402
from sss_locus.experiments.survey_design.area import load_area, with_water_depth  # noqa: E402
from sss_locus.experiments.survey_design.coverage import coverage  # noqa: E402
from sss_locus.experiments.survey_design.lines import LINE_COLUMNS  # noqa: E402
from sss_locus.experiments.survey_design.plans import altitude_limits  # noqa: E402

ORIGIN = (-111.811, 40.234)  # UTM zone 12 N
VERTS = [[0, 0], [600, 0], [600, 300], [0, 300]]
UTM = "EPSG:32612"
D0, GRADIENT = 12.0, 0.02  # depth at the origin, m; deepening 2 cm per metre toward UTM east


def _utm(lon, lat):
    from pyproj import Transformer

    return Transformer.from_crs("EPSG:4326", UTM, always_xy=True).transform(lon, lat)


def _plane_depth(lon, lat):
    """The test's seafloor, evaluated here from longitude/latitude: D0 + GRADIENT x (UTM easting -
    the origin's)."""
    e0, _ = _utm(*ORIGIN)
    e, _ = _utm(np.asarray(lon, float), np.asarray(lat, float))
    return D0 + GRADIENT * (np.asarray(e) - e0)


def _write_tif(path, *, sign=1.0, nodata_box=None, crs=UTM, all_nodata=False, pad_m=400.0):
    """A GeoTIFF of the plane in UTM 12 N, 5 m cells, around the area (``pad_m`` beyond it; a
    negative pad leaves part of the area uncovered)."""
    from rasterio.transform import from_origin

    e0, n0 = _utm(*ORIGIN)
    west, north = e0 - pad_m, n0 + 300 + pad_m
    nx = int((600 + 2 * pad_m) / 5)
    ny = int((300 + 2 * pad_m) / 5)
    E = west + 5 * (np.arange(nx) + 0.5)
    depth = np.tile(D0 + GRADIENT * (E - e0), (ny, 1)).astype("float32") * sign
    if nodata_box is not None:
        depth[nodata_box] = -9999.0
    if all_nodata:
        depth[:] = -9999.0
    with rasterio.open(path, "w", driver="GTiff", width=nx, height=ny, count=1, dtype="float32", crs=crs,
                       transform=from_origin(west, north, 5.0, 5.0), nodata=-9999.0) as dst:
        dst.write(depth, 1)
    return path


def _area_file(tmp_path, tif="harbour.tif", values="depth", extra=""):
    p = tmp_path / "harbour.toml"
    p.write_text(f'[area]\nname = "grid test"\nvertices_m = {VERTS}\norigin_lonlat = [{ORIGIN[0]}, {ORIGIN[1]}]\n'
                 f'bathymetry = "{tif}"\nbathymetry_values = "{values}"\n{extra}')
    return p


@pytest.fixture
def grid_area(tmp_path):
    _write_tif(tmp_path / "harbour.tif")
    return load_area(_area_file(tmp_path))


def test_depths_read_back_from_a_utm_grid_match_the_plane(grid_area):
    """The grid (UTM, 5 m) reprojected into the area's local frame: depths at random points
    against the plane evaluated from their longitude/latitude (pyproj, not the grid)."""
    b = sd.load_area_bathymetry(grid_area)
    rng = np.random.default_rng(0)
    xy = rng.uniform([0, 0], [600, 300], (200, 2))
    lon, lat = grid_area.to_lonlat(xy[:, 0], xy[:, 1])
    assert np.max(np.abs(b.depth_at(xy[:, 0], xy[:, 1]) - _plane_depth(lon, lat))) < 0.05
    stats = b.stats()
    assert 11.9 < stats["min"] < 12.2 and 23.8 < stats["max"] < 24.1  # 12 m to 12 + 0.02 x 600 m
    assert grid_area.water_depth_m == pytest.approx(stats["mean"])
    assert "harbour.tif" in grid_area.water_depth_source and b.sha256[:12] in grid_area.water_depth_source
    assert "12" in grid_area.water_depth_source and "24" in grid_area.water_depth_source


def test_elevation_values_give_the_same_depths(tmp_path):
    _write_tif(tmp_path / "harbour.tif", sign=-1.0)
    area = load_area(_area_file(tmp_path, values="elevation"))
    _write_tif(tmp_path / "other.tif")
    other = load_area(_area_file(tmp_path, tif="other.tif"))
    assert area.water_depth_m == pytest.approx(other.water_depth_m)


def test_a_boats_coverage_follows_each_cells_depth(grid_area):
    """One east-west line of a surface boat over the sloping grid: the cells it sees against the
    swath's closed form at each cell's own depth (evaluated here from the plane), and not at
    the mean depth (the old single number would miss or add a strip)."""
    boat = load_platform("boat")
    s = sd.make_setting(boat, grid_area, "flat", n_features=10, seed=0, grid_m=5.0)
    alt = s.settings["water_depth_m"]  # the boat's reference point at the surface
    lines = pd.DataFrame([("main", 0, 0, -50.0, 150.0, 650.0, 150.0, 0.0, 700.0)], columns=list(LINE_COLUMNS))
    cov = coverage(boat, s.terrain, grid_area, lines, alt, 0.0, True, grid_m=5.0, seed=1, centre=s.centre)
    g = cov["grid"]
    lon, lat = grid_area.to_lonlat(g.x_m.to_numpy(), g.y_m.to_numpy())
    t = boat.transducers["port"]
    fan = math.radians(t.tilt_deg + boat.sonar.azimuth_deg / 2)

    def seen(depth):
        H = depth - t.depth_m
        near = t.lateral_offset_m + H / math.tan(fan)
        far = t.lateral_offset_m + np.sqrt(boat.sonar.max_range_m ** 2 - H ** 2)
        across = np.abs(g.y_m.to_numpy() - 150.0)
        return (across >= near) & (across <= far)

    local = seen(_plane_depth(lon, lat))
    measured = g.n_lines.to_numpy() >= 1
    wrong = int(np.sum(measured != local))
    assert wrong < 0.005 * len(g)  # cells on a swath edge
    flat = seen(np.full(len(g), alt))
    assert np.sum(flat != local) > 5 * max(wrong, 10)  # the depth under each cell matters here


def test_an_auvs_limits_use_the_shallowest_and_deepest_points(tmp_path):
    """The AUV's depth rating (2-100 m) against the grid's 12-24 m: an altitude above 10 m puts
    it above 2 m of depth over the shallow end, so no plan at 12 m altitude is kept."""
    _write_tif(tmp_path / "harbour.tif")
    area = load_area(_area_file(tmp_path))
    auv = load_platform("auv")
    s = sd.make_setting(auv, area, "flat", n_features=10, seed=0, grid_m=20.0)
    hmax = float(np.max(s.heights_m))
    assert s.settings["water_depth_m"] - hmax == pytest.approx(12.0, abs=0.2)  # the shallowest depth
    lo, hi = altitude_limits(auv, s.settings, s.heights_m)
    assert hi == pytest.approx(12.0 - 2.0, abs=0.2)


@pytest.mark.parametrize("setup, message", [
    (dict(pad_m=-100.0), r"harbour\.tif does not cover the area: \d+% of it has no value"),
    (dict(nodata_box=(slice(100, 120), slice(100, 120))), r"harbour\.tif does not cover the area"),
    (dict(all_nodata=True), r"harbour\.tif: band 1 holds no value"),
    (dict(sign=-1.0), r"harbour\.tif: bathymetry_values = 'depth' needs values over the area in \(0, 12000\].*"
                      r"is it elevation\?"),
])
def test_bad_grids_are_refused_in_one_line_naming_the_file(tmp_path, setup, message):
    _write_tif(tmp_path / "harbour.tif", **setup)
    with pytest.raises(ValueError, match=message) as err:
        load_area(_area_file(tmp_path))
    assert "\n" not in str(err.value)


def test_grid_and_depth_together_are_refused(tmp_path):
    _write_tif(tmp_path / "harbour.tif")
    with pytest.raises(ValueError, match="area.bathymetry goes without water_depth_m"):
        load_area(_area_file(tmp_path, extra="water_depth_m = 10.0\n"))
    area = load_area(_area_file(tmp_path))
    with pytest.raises(ValueError, match=r"-p water_depth_m: .* bathymetry grid"):
        with_water_depth(area, 10.0, "-p water_depth_m")
    with pytest.raises(ValueError, match="bathymetry_values must be one of"):
        load_area(_area_file(tmp_path, values="height"))
    with pytest.raises(ValueError, match="missing.tif"):
        load_area(_area_file(tmp_path, tif="missing.tif"))
    with pytest.raises(ValueError, match="terrain 'slope' and the area's bathymetry grid"):
        sd.make_setting(load_platform("boat"), area, "slope", n_features=10, seed=0, grid_m=20.0)


def test_a_grid_without_a_crs_is_refused(tmp_path):
    from rasterio.transform import from_origin

    with rasterio.open(tmp_path / "harbour.tif", "w", driver="GTiff", width=4, height=4, count=1, dtype="float32",
                       transform=from_origin(0, 0, 1, 1)) as dst:
        dst.write(np.ones((4, 4), "float32"), 1)
    with pytest.raises(ValueError, match=r"harbour\.tif: the raster has no CRS"):
        load_area(_area_file(tmp_path))


def test_the_area_key_round_trips_the_grid(grid_area):
    from sss_locus.experiments.survey_design.area import area_from_key

    back = area_from_key(grid_area.key())
    assert back.bathymetry == grid_area.bathymetry
    assert sd.load_area_bathymetry(back).mean_m == pytest.approx(grid_area.water_depth_m)


def test_an_edited_grid_changes_the_runs_area_hash(tmp_path):
    """The run key's ``area_sha256`` covers the grid beside the area file (an edited grid makes
    the run stale), not only the area file's bytes."""
    from sss_locus.pipeline.run.userfiles import area_parameters

    _write_tif(tmp_path / "harbour.tif")
    path = str(_area_file(tmp_path))
    before = area_parameters(path)["area_sha256"]
    _write_tif(tmp_path / "harbour.tif", sign=2.0)
    assert area_parameters(path)["area_sha256"] != before
    (tmp_path / "harbour.tif").unlink()
    assert area_parameters(path)["area_sha256"] not in ("", before)  # the area file alone


def test_an_auvs_mission_depth_follows_the_grid_and_a_boat_stays_at_the_surface(grid_area):
    """The mission CSV's depth at each waypoint: the AUV (terrain following at 8 m altitude) at
    the plane's depth there minus 8 m (evaluated here from longitude/latitude); the boat at 0."""
    import io

    from sss_locus.pipeline.publish.missions import mission_files

    auv, boat = load_platform("auv"), load_platform("boat")
    settings = sd.depth_settings(grid_area, sd.load_settings())
    lines = pd.DataFrame([("main", 0, 0, 20.0, 150.0, 580.0, 150.0, 0.0, 560.0)], columns=list(LINE_COLUMNS))
    for pf, want in ((auv, lambda lon, lat: _plane_depth(lon, lat) - 8.0), (boat, lambda lon, lat: 0.0 * lon)):
        depth = sd.vehicle_depth_m(pf, grid_area, settings, 8.0 if pf is auv else settings["water_depth_m"])
        files = mission_files(grid_area, lines, depth_m=depth, turn_radius_m=pf.turn_radius_m, speed_m_s=1.5,
                              ardupilot=False)
        csv = pd.read_csv(io.StringIO(files["mission.csv"]))
        assert np.allclose(csv.depth_m, want(csv.lon.to_numpy(), csv.lat.to_numpy()), atol=0.05), pf.key
    assert csv.depth_m.eq(0.0).all()


def test_the_plan_map_draws_the_grids_depth_contours(grid_area):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.report.survey_design.figures import plot_plan

    boat = load_platform("boat")
    lines = pd.DataFrame([("main", 0, 0, -50.0, 150.0, 650.0, 150.0, 0.0, 700.0)], columns=list(LINE_COLUMNS))
    cov = coverage(boat, sd.load_area_bathymetry(grid_area).terrain(grid_area.polygon.centroid.coords[0]), grid_area,
                   lines, grid_area.water_depth_m, 0.0, True, grid_m=20.0, seed=1,
                   centre=grid_area.polygon.centroid.coords[0])
    fig = plot_plan(grid_area, lines, cov["grid"], 20.0, 0.0, boat, "t", bathymetry=sd.load_area_bathymetry(grid_area))
    ax = fig.axes[0]
    levels = [float(t.get_text().removesuffix(" m")) for t in ax.texts if t.get_text().endswith(" m")]
    assert levels and min(levels) >= 12.0 and max(levels) <= 24.0  # labelled contours within the area's depths
    assert any("depth contour (" in t.get_text() for t in ax.get_legend().get_texts())
    legend = [t.get_text() for t in ax.get_legend().get_texts()]  # red cells: unseen, not the area's holes (a pier)
    assert "gap (seen by no line)" in legend and not any(t.startswith("hole") for t in legend)
    assert ax.get_xlim()[1] < 800  # the grid's margin does not widen the map
    plt.close(fig)


def test_every_manifest_of_the_chapter_records_the_grid_with_its_sha256(grid_area, tmp_path):
    """A plan computed over a bathymetry grid depends on the grid's bytes: each figure and table
    the chapter publishes lists the grid (role ``bathymetry``, SHA-256 of its bytes, computed here
    with hashlib) beside the area file, not only in the caption's prose."""
    import hashlib
    import json

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.paths import REPO_ROOT
    from sss_locus.pipeline.publish.export import export_figure

    fig = plt.figure()
    manifest = export_figure(fig, "fig-grid-test", pd.DataFrame({"a": [1]}), caption="C.", parameters={},
                             input_files=grid_area.input_files(), out_dir=tmp_path / "out")
    plt.close(fig)
    roles = {f["role"]: f["sha256"] for f in manifest["data_inputs"]["files"]}
    assert roles["bathymetry"] == hashlib.sha256((tmp_path / "harbour.tif").read_bytes()).hexdigest()
    assert roles["area"] == hashlib.sha256((tmp_path / "harbour.toml").read_bytes()).hexdigest()
    cells = json.loads((REPO_ROOT / "notebooks" / "survey_design.ipynb").read_text())["cells"]
    code = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    calls = code.count("publish(") + code.count("show_table(")
    assert calls and code.count("input_files=survey_area.input_files()") == calls
