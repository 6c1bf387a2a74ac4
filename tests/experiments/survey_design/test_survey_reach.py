"""The part of a survey area no plan can see (a trench deeper than a surface boat's sonar
reaches), read from a GeoTIFF the test writes: its share against the test's own reading of the
raster and the sonar's range and fan, stated in the plan caption and drawn apart on the map."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("shapely")
pytest.importorskip("pyproj")
rasterio = pytest.importorskip("rasterio")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sss_locus.experiments.datamodel.platforms import load_platform  # noqa: E402
from sss_locus.experiments.survey_design import front as sd  # noqa: E402
from sss_locus.experiments.survey_design.area import load_area  # noqa: E402
from sss_locus.experiments.survey_design.coverage import coverage  # noqa: E402
from sss_locus.experiments.survey_design.lines import LINE_COLUMNS  # noqa: E402
from sss_locus.report.survey_design.figures import OUT_OF_REACH, plot_plan  # noqa: E402
from sss_locus.report.survey_design.prose import plan_caption  # noqa: E402

ORIGIN = (-111.811, 40.234)
UTM = "EPSG:32612"
SHALLOW_M, TRENCH_M = 12.0, 140.0  # depths, m; the trench runs north-south
TRENCH_E = (200.0, 350.0)  # its west and east edges, UTM metres east of the origin (a quarter of the area)
CELL_M = 5.0
LINE = pd.DataFrame([("main", 0, 0, -50.0, 150.0, 650.0, 150.0, 0.0, 700.0)], columns=list(LINE_COLUMNS))


def _utm(lon, lat):
    from pyproj import Transformer

    return Transformer.from_crs("EPSG:4326", UTM, always_xy=True).transform(lon, lat)


@pytest.fixture
def trench(tmp_path):
    """A 600 m x 300 m area over a GeoTIFF (UTM, 5 m cells) 12 m deep with a 140 m trench."""
    return _write(tmp_path, TRENCH_M)


def _write(tmp_path, trench_m):
    from rasterio.transform import from_origin

    e0, n0 = _utm(*ORIGIN)
    west, north = e0 - 400.0, n0 + 700.0
    nx, ny = int(1400 / CELL_M), int(1100 / CELL_M)
    east = west + CELL_M * (np.arange(nx) + 0.5) - e0
    row = np.where((east >= TRENCH_E[0]) & (east <= TRENCH_E[1]), trench_m, SHALLOW_M)
    depth = np.tile(row, (ny, 1)).astype("float32")
    with rasterio.open(tmp_path / "trench.tif", "w", driver="GTiff", width=nx, height=ny, count=1,
                       dtype="float32", crs=UTM, transform=from_origin(west, north, CELL_M, CELL_M)) as dst:
        dst.write(depth, 1)
    (tmp_path / "trench.toml").write_text(
        '[area]\nname = "trench"\nvertices_m = [[0, 0], [600, 0], [600, 300], [0, 300]]\n'
        f'origin_lonlat = [{ORIGIN[0]}, {ORIGIN[1]}]\nbathymetry = "trench.tif"\nbathymetry_values = "depth"\n')
    return load_area(tmp_path / "trench.toml"), (west, north, depth)


def _boat_coverage(area, grid_m=10.0):
    boat = load_platform("boat")
    s = sd.make_setting(boat, area, "flat", n_features=10, seed=0, grid_m=grid_m)
    cov = coverage(boat, s.terrain, area, LINE, s.settings["water_depth_m"], 0.0, True, grid_m=grid_m, seed=1,
                   centre=s.centre)
    return boat, cov


def test_the_share_beyond_the_sonars_reach_matches_the_raster_and_the_sonar(trench):
    """Each coverage cell's depth read here from the raster written (nearest cell, through
    longitude/latitude and UTM), against the deepest seafloor the boat's steepest ray reaches:
    the transducer's depth plus max_range sin(tilt + azimuth/2)."""
    area, (west, north, depth) = trench
    boat, cov = _boat_coverage(area)
    t, son = boat.transducers["port"], boat.sonar
    deepest = boat.depth_min_m + t.depth_m + son.max_range_m * math.sin(math.radians(min(t.tilt_deg + son.azimuth_deg / 2, 90)))
    assert SHALLOW_M < deepest < TRENCH_M
    g = cov["grid"]
    e, n = _utm(*area.to_lonlat(g.x_m.to_numpy(), g.y_m.to_numpy()))
    cells = depth[((north - np.asarray(n)) // CELL_M).astype(int), ((np.asarray(e) - west) // CELL_M).astype(int)]
    expected = float(np.mean(cells > deepest))
    assert abs(expected - 0.25) < 0.03  # the trench is a quarter of the area
    assert abs(cov["out_of_reach"] - expected) <= 1.5 * 300 / 10 / len(g)  # a column of cells on its edges
    assert cov["out_of_reach_m2"] == pytest.approx(cov["out_of_reach"] * 600 * 300)
    assert cov["too_deep"] == cov["out_of_reach"] and cov["too_shallow"] == 0.0
    assert np.all(g.n_lines[g.out_of_reach] == 0)  # the line runs across the trench and sees none of it


def test_the_caption_states_the_share_and_the_depth_the_sonar_reaches(trench):
    area, _ = trench
    boat, cov = _boat_coverage(area)
    row = pd.Series({"heading_deg": 0.0, "spacing_m": 100.0, "crossing_deg": float("nan"), "altitude_m": 44.0,
                     "pitch_deg": 0.0, "run_m": 20.0, "total_m": 4000.0, "time_h": 1.0})
    text = plan_caption(boat, area, "trench.toml", row, cov, ["plan.csv"], water_depth_m=44.0, depth_source="grid")
    import re

    found = re.search(r"([\d.]+) % of the area \(([\d.]+) ha\) lies deeper than the sonar reaches at 115 m below the surface; no plan", text)
    assert found, text
    assert float(found[1]) == pytest.approx(100 * cov["out_of_reach"], abs=0.051)
    assert float(found[2]) == pytest.approx(cov["out_of_reach_m2"] / 1e4, abs=0.051)
    assert "shallower" not in text  # no part of this area is too shallow


def test_a_shoal_shallower_than_the_transducers_is_named_as_such(tmp_path):
    """The same strip 5 cm deep: the boat's transducers (10 cm down) are below its seafloor."""
    area, _ = _write(tmp_path, 0.05)
    boat, cov = _boat_coverage(area)
    assert cov["too_deep"] == 0.0 and abs(cov["too_shallow"] - 0.25) < 0.03
    row = pd.Series({"heading_deg": 0.0, "spacing_m": 100.0, "crossing_deg": float("nan"), "altitude_m": 9.0,
                     "pitch_deg": 0.0, "run_m": 20.0, "total_m": 4000.0, "time_h": 1.0})
    text = plan_caption(boat, area, "trench.toml", row, cov, ["plan.csv"], water_depth_m=9.0, depth_source="grid")
    assert "ha) is shallower than the 0.1 m the sonar needs; no plan can see it" in text and "deeper" not in text


def test_the_map_draws_the_unreachable_cells_apart_from_the_gaps(trench):
    area, _ = trench
    boat, cov = _boat_coverage(area)
    fig = plot_plan(area, LINE, cov["grid"], cov["grid_m"], 0.0, boat, "t")
    ax = fig.axes[0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "beyond the sonar's reach" in legend and "gap (seen by no line)" in legend
    meshes = [c for c in ax.collections if isinstance(c, matplotlib.collections.QuadMesh)]
    dark = [m for m in meshes if np.allclose(m.get_cmap()(0.0)[:3], matplotlib.colors.to_rgb(OUT_OF_REACH))]
    assert len(dark) == 1 and int(np.ma.count(dark[0].get_array())) == int(cov["grid"].out_of_reach.sum())
    plt.close(fig)
    shallow = cov["grid"].assign(out_of_reach=False)  # a grid the sonar reaches everywhere: no such entry
    fig = plot_plan(area, LINE, shallow, cov["grid_m"], 0.0, boat, "t")
    assert "beyond the sonar's reach" not in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    plt.close(fig)


def test_latitude_labels_lie_outside_the_plan(trench):
    """The parallels' labels are drawn right of the axes, where no plan is drawn; the meridians'
    on an opaque box."""
    area, _ = trench
    boat, cov = _boat_coverage(area, grid_m=20.0)
    fig = plot_plan(area, LINE, cov["grid"], cov["grid_m"], 0.0, boat, "t")
    ax = fig.axes[0]
    fig.canvas.draw()
    frame = ax.get_window_extent()
    labels = [t for t in ax.texts if t.get_text().endswith(("°N", "°S", "°E", "°W"))]
    parallels = [t for t in labels if t.get_text().endswith(("°N", "°S"))]
    assert parallels
    for t in parallels:
        assert t.get_window_extent().x0 >= frame.x1
    for t in set(labels) - set(parallels):
        assert t.get_bbox_patch() is not None and t.get_bbox_patch().get_alpha() >= 0.8
    legend = ax.get_legend().get_window_extent()
    assert all(t.get_window_extent().x1 <= legend.x0 for t in parallels)  # nor under the legend
    plt.close(fig)


@pytest.mark.parametrize("key", ["boat", "auv"])
def test_the_reach_window_is_where_swath_m_gives_a_swath(key):
    """The closed-form heights of :func:`side_reach_m` against :func:`swath_m` itself on a sweep
    of heights: a swath inside the window, refused outside it."""
    from sss_locus.experiments.passes.straight_pass import swath_m
    from sss_locus.experiments.survey_design.coverage import side_reach_m

    pf = load_platform(key)
    for side in pf.transducers:
        low, high = side_reach_m(pf, side)
        for alt in np.linspace(-1.0, pf.sonar.max_range_m + 5.0, 997):
            if abs(alt - low) < 1e-6 or abs(alt - high) < 1e-6:
                continue
            try:
                near, far = swath_m(pf, [side == "port"], [alt])
                swath = bool(near[0] < far[0])
            except ValueError:
                swath = False
            assert swath == (low < alt < high), (side, alt, low, high)


def test_depth_contours_run_along_the_trench_walls_not_around_its_flat_floor(trench):
    """The trench's floor (140 m) is one of the contour levels (every 20 m). Every contour the map
    draws lies on a wall of the trench, where the depth crosses the levels (within two cells, the
    grid's reprojection and the frame's convergence allowed for), and none over the floor: the
    floor, reprojected, came out within 1e-13 m of 140 m, and the contour at 140 m circled every
    cell of it a hair deeper."""
    from sss_locus.experiments.survey_design.front import load_area_bathymetry

    area, _ = trench
    boat, cov = _boat_coverage(area)
    fig = plot_plan(area, LINE, cov["grid"], cov["grid_m"], 0.0, boat, "t", bathymetry=load_area_bathymetry(area))
    contours = [c for c in fig.axes[0].collections if isinstance(c, matplotlib.contour.ContourSet)]
    assert len(contours) == 1
    east = np.concatenate([p.vertices[:, 0] for p in contours[0].get_paths() if len(p.vertices)])
    assert east.size  # the walls are drawn
    off_wall = np.minimum(np.abs(east - TRENCH_E[0]), np.abs(east - TRENCH_E[1]))
    assert off_wall.max() <= 2 * CELL_M, f"a contour {off_wall.max():.0f} m from the trench's walls"
    plt.close(fig)
