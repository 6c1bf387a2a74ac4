"""Survey design: which lines to run for a sonar, a vehicle and an area, and how much better that
is than the standard sidescan plan (the survey-design chapter).

Typical use::

    from sss_locus.experiments.survey_design import front as sd
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.survey_design.area import load_area

    result = sd.design(load_platform("auv"), load_area("data/examples/survey_area.toml"), "flat")
    result.plans            # every plan searched, with cost, coverage and objectives
    result.recommended      # the recommended plan's row

Pieces: :mod:`~sss_locus.experiments.survey_design.area` (the polygon), :mod:`~sss_locus.experiments.
survey_lines` (lines and turns), :mod:`~sss_locus.experiments.survey_design.coverage` (who sees what),
:mod:`~sss_locus.experiments.survey_design.objectives` (locus, closure, reconstruction),
:mod:`~sss_locus.experiments.survey_design.plans` (plan space, limits, baselines).

Evaluation (:func:`evaluate`): ``n_features`` features uniform over the area (seeded), on the
terrain, observed by every segment of the plan; cost from the track the mission flies (lines,
U-turns, transits and the return to the start:
:func:`~sss_locus.experiments.survey_design.route.track_cost`) and the platform's speed; coverage measured on a grid (of ``grid_m``, coarser over an area that would
need more than :data:`MAX_COVERAGE_CELLS` cells: :func:`coverage_grid_m`); the objectives of every feature seen twice.
Every plan is evaluated on the same features (common random numbers), so plans are compared
on equal terms.

Objectives (:data:`OBJECTIVES`; all minimised): ``"locus"`` the median best-pair locus length
of the features seen by two or more lines; ``"three_view"`` the share of features *not*
resolved by three views; ``"reconstruction"`` the median 3-D error, under the noise model of
``data/noise.toml``, of the reconstruction chapter's two-view estimate (the locus point nearest
the flat-seafloor prior; the N-view estimate ``all`` is reported too, but it needs three views
off one plane and leaves most features of a surface vessel unestimated).

Front and recommendation (the rule): a plan is *eligible* when at least
``min(min_two_view_share, the standard plan's share)`` of the area is seen by two or more of its
lines, measured on the coverage grid (no worse a 200 % survey than the standard plan as flown); the Pareto front
is the eligible plans no other eligible plan beats in both track length and objective. The
**recommended plan** is the eligible plan with the smallest objective among those whose track is
no longer than the standard plan's (ties: the shorter track); when no eligible plan is that
short, the shortest plan on the front. This is the search's candidate; the recommendation is
decided under the noise model over independent seeds
(:mod:`sss_locus.experiments.survey_design.scoring`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_design.area import SurveyArea, area_from_key
from sss_locus.experiments.survey_design.coverage import coverage, observe_lines
from sss_locus.experiments.survey_design.objectives import pair_loci, reconstruction_errors, three_view_closure
from sss_locus.experiments.survey_design.plans import (Plan, check_mission, lawnmower_plan, plan_grid, plan_ok, standard_plan,
                                                       water_depth)
from sss_locus.experiments.survey_design.settings import load_settings
from sss_locus.experiments.survey_design.lines import heading_from_compass_deg
from sss_locus.experiments.survey_design.route import flight_path, track_cost
from sss_locus.experiments.datamodel.terrain import KINDS, load_terrain_config, terrain_from_config

OBJECTIVES = {"locus": "locus_median_m", "three_view": "unresolved_share", "reconstruction": "error_two_median_m"}
"""Objective name -> the column of the plans table it minimises."""


@dataclass(frozen=True)
class Setting:
    """What every plan is evaluated against."""

    platform: object
    area: SurveyArea
    terrain: object
    settings: dict
    xy: np.ndarray          # features, area frame (n, 2)
    heights_m: np.ndarray   # seafloor heights over the area (for the depth limits)
    centre: tuple[float, float]
    grid_m: float
    seed: int


def _ints(name, v, lo):
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
        raise ValueError(f"{name} must be an integer >= {lo}; got {v!r}")
    return int(v)


def _floats(name, values, lo=-math.inf, hi=math.inf, allow_nan=False):
    try:
        a = np.atleast_1d(np.asarray(values, float))
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a non-empty list of numbers; got {values!r}") from None
    bad = ~np.isfinite(a) & ~(np.isnan(a) if allow_nan else False)
    if a.ndim != 1 or a.size == 0 or bad.any() or np.any((a[~np.isnan(a)] < lo) | (a[~np.isnan(a)] > hi)):
        raise ValueError(f"{name} must be a non-empty list of numbers in [{lo:g}, {hi:g}]; got {values!r}")
    return [float(x) for x in a]


GRID_KEYS = {"headings_deg": (-360.0, 360.0), "spacing_fractions": (1e-3, 10.0), "crossing_angles_deg": (0.0, 180.0),
             "cross_spacing_factors": (1e-3, 10.0), "altitude_fractions": (1e-3, 0.999), "pitches_deg": (-90.0, 90.0)}
"""The plan grid's keys and the range of their values (``crossing_angles_deg`` may hold NaN: no cross lines)."""


def check_grid(grid) -> dict:
    """Refuse a plan grid with a missing or unknown key or a value out of range, in one line.

    Parameters
    ----------
    grid : dict
        The plan grid: exactly the keys of :data:`GRID_KEYS`, each a number or a list of numbers
        (degrees, fractions or factors as the key names).

    Returns
    -------
    dict
        Key -> list of float, every value checked against its range in :data:`GRID_KEYS`.

    Raises
    ------
    ValueError
        A key missing or unknown, an empty list, a value non-finite (NaN allowed only in
        ``crossing_angles_deg``) or out of range.
    """
    if not isinstance(grid, dict) or set(grid) != set(GRID_KEYS):
        got = sorted(grid) if isinstance(grid, dict) else type(grid).__name__
        raise ValueError(f"grid must be a dict with exactly the keys {sorted(GRID_KEYS)}; got {got}")
    return {k: _floats(k, v, lo, hi, allow_nan=k == "crossing_angles_deg") for k, (lo, hi) in GRID_KEYS.items()
            for v in [grid[k]]}


def search_grid(*, headings_compass_deg, spacing_fractions, crossing_angles_deg, no_cross_lines: bool,
                cross_spacing_factors, altitude_fractions, pitches_deg) -> dict:
    """The plan grid :func:`search_plans` searches, from a chapter's parameters.

    Parameters
    ----------
    headings_compass_deg : sequence of float
        Main-line compass headings, deg clockwise from north (converted to the computation's
        convention, deg counter-clockwise from east, by
        :func:`~sss_locus.experiments.survey_design.lines.heading_from_compass_deg`).
    spacing_fractions : sequence of float
        Main-line spacings, times the platform's range scale.
    crossing_angles_deg : sequence of float
        Angles of the second line set to the main lines, deg (0: an offset repeat).
    no_cross_lines : bool
        Also search plans of main lines only (a NaN crossing angle, put first).
    cross_spacing_factors, altitude_fractions, pitches_deg : sequence of float
        As the keys of :data:`GRID_KEYS` of the same names.

    Returns
    -------
    dict
        The grid, checked by :func:`check_grid` (key -> list of float).
    """
    return check_grid(dict(
        headings_deg=[heading_from_compass_deg(h) for h in headings_compass_deg], spacing_fractions=spacing_fractions,
        crossing_angles_deg=([float("nan")] if no_cross_lines else []) + list(crossing_angles_deg),
        cross_spacing_factors=cross_spacing_factors, altitude_fractions=altitude_fractions, pitches_deg=pitches_deg))


MAX_COVERAGE_CELLS = 20_000
"""Most coverage cells over an area: a larger area is measured on a coarser grid
(:func:`coverage_grid_m`), so a km-scale area is planned in minutes."""


def coverage_grid_m(area: SurveyArea, grid_m: float) -> float:
    """The coverage grid's spacing over ``area``: ``grid_m``, or the spacing that puts
    :data:`MAX_COVERAGE_CELLS` cells over it when ``grid_m`` would put more, m.

    Parameters
    ----------
    area : SurveyArea
        The survey area (local metres; its ``area_m2``).
    grid_m : float
        The requested coverage grid spacing, m.

    Returns
    -------
    float
        The spacing used, m: never finer than ``grid_m``.
    """
    return float(max(grid_m, math.sqrt(area.area_m2 / MAX_COVERAGE_CELLS)))


def depth_settings(area: SurveyArea, settings: dict) -> dict:
    """``settings`` with the water depth of the area (given by its file or the run) or, failing
    that, of a user's ``survey_design.water_depth_m``; ``water_depth_source`` says which. No
    depth at all is refused in one line.

    Parameters
    ----------
    area : SurveyArea
        The survey area; its ``water_depth_m`` (m, positive down) wins when given.
    settings : dict
        The survey-design settings (``data/survey_design.toml`` keys).

    Returns
    -------
    dict
        A copy of ``settings`` with ``water_depth_m`` (m) and ``water_depth_source`` (str).

    Raises
    ------
    ValueError
        No water depth from the area nor the settings, or one out of range.
    """
    out = dict(settings)
    if area.water_depth_m is not None:
        out["water_depth_m"], out["water_depth_source"] = area.water_depth_m, area.water_depth_source
    elif out.get("water_depth_m") is not None:
        out["water_depth_source"] = "survey_design.water_depth_m of the run's data"
    water_depth(out)
    return out


def load_area_bathymetry(area: SurveyArea):
    """The :class:`~sss_locus.experiments.survey_design.bathymetry.Bathymetry` of an area whose
    file gives a grid (``area.bathymetry``), read again (cached per file and area); ``None``
    without one.

    Parameters
    ----------
    area : SurveyArea
        The survey area; ``area.bathymetry`` is ``(path, shown name, SHA-256, values)`` or empty.

    Returns
    -------
    Bathymetry or None
        The grid over the area (local metres, depth positive down), or ``None`` when the area has
        no grid.

    Raises
    ------
    ValueError
        The grid file's SHA-256 differs from the one read with the area.
    """
    from sss_locus.experiments.survey_design.bathymetry import load_bathymetry

    if not area.bathymetry:
        return None
    path, shown, sha, values = area.bathymetry
    b = load_bathymetry(path, values, area, shown=shown)
    if sha and b.sha256 != sha:
        raise ValueError(f"{shown} changed since the area was read (SHA-256 {b.sha256[:12]}, was {sha[:12]}): rerun")
    return b


def vehicle_depth_m(platform, area: SurveyArea, settings: dict, altitude_m: float):
    """The depth (m, below the sea surface) a plan's vehicle flies at, for its mission files: a
    platform of fixed depth (a surface vessel) ``water depth - altitude`` (its own depth); any
    other over the mean seafloor ``water depth - altitude``, or, over a bathymetry grid (it
    follows the terrain at ``altitude_m``), a function of local east/north metres: the depth there
    minus ``altitude_m``.

    Parameters
    ----------
    platform : Platform
        The platform (its ``fixed_depth`` flag).
    area : SurveyArea
        The survey area (its bathymetry grid, if any).
    settings : dict
        Survey-design settings with ``water_depth_m`` (m, positive down).
    altitude_m : float
        The plan's altitude above the seafloor, m.

    Returns
    -------
    float or callable
        The depth, m below the surface; or, over a bathymetry grid, a function
        ``(east_m, north_m) -> depth_m`` of local metres (arrays broadcast).
    """
    grid = None if platform.fixed_depth else load_area_bathymetry(area)
    if grid is None:
        return float(settings["water_depth_m"]) - float(altitude_m)
    return lambda east_m, north_m: grid.depth_at(east_m, north_m) - float(altitude_m)


def make_setting(platform, area: SurveyArea, terrain_kind: str, *, n_features: int, seed: int,
                 grid_m: float, settings: dict | None = None) -> Setting:
    """Validate the inputs and draw the features (module docstring).

    Parameters
    ----------
    platform : Platform
        The sonar platform (checked by :func:`~sss_locus.experiments.survey_design.plans.check_mission`).
    area : SurveyArea
        The survey area (local metres).
    terrain_kind : str
        One of :data:`~sss_locus.experiments.datamodel.terrain.KINDS`; ``"flat"`` when the area
        has a bathymetry grid.
    n_features : int
        Number of features drawn uniformly inside the area, at least 10.
    seed : int
        Seed (>= 0) of the features and the terrain.
    grid_m : float
        Requested coverage grid spacing, m (made coarser by :func:`coverage_grid_m`).
    settings : dict or None
        Survey-design settings; ``None`` reads ``data/survey_design.toml``.

    Returns
    -------
    Setting
        Features ``xy`` (n_features, 2) in the area frame (local east/north metres), the terrain
        centred on the area's centroid, the seafloor heights (m) over the area and the settings.

    Raises
    ------
    ValueError
        Any input out of range, in one line naming it.
    """
    import shapely

    if not isinstance(area, SurveyArea):
        raise ValueError(f"area must be a SurveyArea (sss_locus.experiments.survey_design.area.load_area); got {type(area).__name__}")
    if terrain_kind not in KINDS:
        raise ValueError(f"terrain must be one of {list(KINDS)}; got {terrain_kind!r}")
    check_mission(platform)
    n = _ints("n_features", n_features, 10)
    seed = _ints("seed", seed, 0)
    grid_m = coverage_grid_m(area, _floats("grid_m", grid_m, 1e-3)[0])
    settings = depth_settings(area, load_settings() if settings is None else settings)
    c = area.polygon.centroid
    x0, y0, x1, y1 = area.polygon.bounds
    grid_depths = np.zeros(0)
    if area.bathymetry:  # the area's own seafloor
        if terrain_kind != "flat":
            raise ValueError(f"terrain {terrain_kind!r} and the area's bathymetry grid ({area.bathymetry[1]}) both give "
                             "the seafloor: keep terrain 'flat' (the default) with a bathymetry grid")
        bathy = load_area_bathymetry(area)
        terrain, grid_depths = bathy.terrain((c.x, c.y)), bathy.area_depths_m
    else:
        terrain = terrain_from_config(terrain_kind, load_terrain_config(),
                                      extent_m=2.5 * max(x1 - x0, y1 - y0), seed=seed)
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(2801,)))
    xy = np.zeros((0, 2))
    while len(xy) < n:
        cand = np.column_stack([rng.uniform(x0, x1, 4 * n), rng.uniform(y0, y1, 4 * n)])
        xy = np.vstack([xy, cand[shapely.contains_xy(area.polygon, cand[:, 0], cand[:, 1])]])
    edge = np.asarray(area.polygon.exterior.coords)
    probe = np.vstack([edge, xy])
    heights = np.concatenate([terrain.height_m(probe[:, 0] - c.x, probe[:, 1] - c.y),
                              settings["water_depth_m"] - grid_depths])  # every grid cell of the area
    return Setting(platform, area, terrain, settings, xy[:n], heights, (c.x, c.y), grid_m, seed)


_FLOWN: dict = {}


def flown_cost(area: SurveyArea, lines: pd.DataFrame, turn_radius_m: float) -> dict:
    """:func:`~sss_locus.experiments.survey_design.route.track_cost` of the track the mission of
    ``lines`` flies over ``area`` (remembered for the last few hundred line tables: the scoring
    evaluates a plan again on every seed, with the same track).

    Parameters
    ----------
    area : SurveyArea
        The survey area (local metres).
    lines : pandas.DataFrame
        The plan's line segments (one row per segment, area frame, ``heading_deg``).
    turn_radius_m : float
        The platform's turn radius, m.

    Returns
    -------
    dict
        :func:`~sss_locus.experiments.survey_design.route.track_cost`'s keys (``n_segments``,
        ``lines_m``, ``turns_m``, ``transits_m``, ``total_m``; lengths in m), a fresh copy.
    """
    import json

    key = (json.dumps(area.key(), sort_keys=True, default=str), pd.util.hash_pandas_object(lines, index=False).to_numpy().tobytes(),
           float(turn_radius_m))
    if key not in _FLOWN:
        if len(_FLOWN) > 512:
            _FLOWN.clear()
        _FLOWN[key] = track_cost(flight_path(area, lines, turn_radius_m)[0])
    return dict(_FLOWN[key])


def evaluate(s: Setting, plan: Plan, *, noise=None, seed_offset: int = 0, lines: pd.DataFrame | None = None) -> dict:

    """Cost, coverage and objectives of one plan (module docstring); with ``noise`` also the
    reconstruction errors under it. ``lines``: ``plan.lines(s.area)`` when the caller has it.

    Parameters
    ----------
    s : Setting
        The setting (:func:`make_setting`).
    plan : Plan
        The plan evaluated.
    noise : NoiseModel or None
        The noise model of the reconstruction errors; ``None`` skips them.
    seed_offset : int
        Added to ``s.seed`` for the coverage and observation draws (independent repetitions).
    lines : pandas.DataFrame or None
        ``plan.lines(s.area)`` when already computed.

    Returns
    -------
    dict
        The plan's row: :meth:`Plan.row` plus track cost (m), ``time_h`` (hours), coverage shares
        (``covered_once``, ``covered_twice``, in [0, 1]), holes, ``nadir_gap_m``, view shares,
        ``locus_median_m`` and ``best_pair_angle_median_deg`` (NaN when no feature is seen twice);
        with ``noise`` also ``error_*_median_m`` and the estimated counts.

    Raises
    ------
    ValueError
        The plan leaves no line inside the area.
    """
    p = s.platform
    lines = plan.lines(s.area) if lines is None else lines
    if lines.empty:
        raise ValueError(f"plan {plan} leaves no line inside the area")
    cost = flown_cost(s.area, lines, p.turn_radius_m)  # the track the mission flies
    same = p.fixed_depth
    seed = s.seed + seed_offset
    cov = coverage(p, s.terrain, s.area, lines, plan.altitude_m, plan.pitch_deg, same, grid_m=s.grid_m,
                   seed=seed, centre=s.centre)
    views, seen, info = observe_lines(p, s.terrain, s.xy, lines, plan.altitude_m, plan.pitch_deg, same,
                                      seed, s.centre)
    ap = p.sonar.aperture()
    pairs = pair_loci(views, seen, ap, lines["heading_deg"].to_numpy())
    two = pairs["n_seen"] >= 2
    closed = three_view_closure(views, seen, ap)
    row = {**plan.row(), "n_segments": cost["n_segments"], "lines_m": cost["lines_m"], "turns_m": cost["turns_m"],
           "transits_m": cost["transits_m"], "total_m": cost["total_m"], "time_h": cost["total_m"] / p.speed_m_s / 3600.0,
           "covered_once": cov["once"], "covered_twice": cov["twice"], "holes": cov["holes"],
           "n_holes": cov["n_holes"], "nadir_gap_m": cov["nadir_gap_m"],
           "two_view_share": float(two.mean()), "three_view_share": float(closed.mean()),
           "unresolved_share": float(1.0 - closed.mean()),
           "locus_median_m": float(np.nanmedian(pairs["locus_length_m"])) if two.any() else math.nan,
           "best_pair_angle_median_deg": float(np.nanmedian(pairs["crossing_angle_deg"])) if two.any() else math.nan}
    if noise is not None:
        err = reconstruction_errors(views, seen, info["sensor_height_m"], noise, ap, seed)
        row["error_all_median_m"] = float(err["error_all_m"].median())
        row["error_two_median_m"] = float(err["error_two_m"].median())
        row["estimated_share"] = float(err["error_all_m"].notna().mean())
        row["n_two_estimated"] = int(err["error_two_m"].notna().sum())
        row["n_all_estimated"] = int(err["error_all_m"].notna().sum())
    return row


def eligible(table: pd.DataFrame, settings: dict) -> pd.Series:
    """The rule's eligibility (module docstring): the share of the area seen by two or more lines
    at least the standard plan's (capped at ``min_two_view_share``).

    Parameters
    ----------
    table : pandas.DataFrame
        The plans table (columns ``kind`` with one ``"standard"`` row, ``covered_twice``).
    settings : dict
        Survey-design settings with ``min_two_view_share`` (in [0, 1]).

    Returns
    -------
    pandas.Series
        Boolean, one per row of ``table``.
    """
    need = min(settings["min_two_view_share"], float(table.loc[table.kind == "standard", "covered_twice"].iloc[0]))
    return table["covered_twice"] >= need


def pareto_front(cost, value, eligible) -> np.ndarray:
    """Boolean mask: eligible rows that no other eligible row beats (<= in both, < in one).

    Parameters
    ----------
    cost : array_like
        Cost per row, shape (n,) (track length, m).
    value : array_like
        Objective per row, shape (n,) (minimised; NaN never on the front).
    eligible : array_like
        Boolean eligibility per row, shape (n,).

    Returns
    -------
    numpy.ndarray
        Boolean mask, shape (n,); all False when no row is eligible and finite.
    """
    c, v, e = (np.asarray(a) for a in (cost, value, eligible))
    ok = e & np.isfinite(v)
    front = np.zeros(c.size, bool)
    for i in np.flatnonzero(ok):
        dominated = ok & (c <= c[i]) & (v <= v[i]) & ((c < c[i]) | (v < v[i]))
        front[i] = not dominated.any()
    return front


def recommend(plans: pd.DataFrame, objective: str, standard_total_m: float) -> int | None:
    """Index of the recommended plan (module docstring's rule), or ``None`` (no eligible plan).

    Parameters
    ----------
    plans : pandas.DataFrame
        The plans table with ``eligible``, ``front``, ``total_m`` and the objective's column.
    objective : str
        A key of :data:`OBJECTIVES`.
    standard_total_m : float
        The standard plan's total track length, m.

    Returns
    -------
    int or None
        The index label of the recommended row; ``None`` when no plan is eligible.
    """
    col = OBJECTIVES[objective]
    cand = plans[plans["eligible"] & (plans["total_m"] <= standard_total_m) & plans[col].notna()]
    if cand.empty:
        front = plans[plans["front"]]
        return None if front.empty else int(front.sort_values(["total_m", col], kind="stable").index[0])
    return int(cand.sort_values([col, "total_m"], kind="stable").index[0])


@dataclass(frozen=True)
class DesignResult:
    plans: pd.DataFrame        # every plan searched (+ the baselines, kind column)
    recommended: int | None    # index into plans
    objective: str
    setting: Setting


def standard_for(s: Setting) -> Plan:
    """The standard plan of setting ``s``; refused in one line when no altitude of the platform
    fits or no line of it is left (checked before any work by the runner).

    Parameters
    ----------
    s : Setting
        The setting (:func:`make_setting`).

    Returns
    -------
    Plan
        The standard plan.

    Raises
    ------
    ValueError
        No altitude of the platform fits the water depth, or no line of the plan is left.
    """
    std = standard_plan(s.platform, s.area, s.terrain, s.settings, s.heights_m)
    if not plan_ok(s.platform, s.settings, s.heights_m, std):
        raise ValueError(f"no altitude of platform {s.platform.key!r} fits water_depth_m = "
                         f"{s.settings['water_depth_m']:g} m over this terrain (depth rating "
                         f"{s.platform.depth_min_m:g}-{s.platform.depth_max_m:g} m)")
    if std.lines(s.area).empty:
        x0, y0, x1, y1 = s.area.polygon.bounds
        raise ValueError(f"area {s.area.name!r} leaves no line of the standard plan of {s.platform.key!r}: "
                         f"the area spans {x1 - x0:.0f} m x {y1 - y0:.0f} m and its water_beyond_m or holes leave no "
                         "line of at least 1 m")
    return std


def search(s: Setting, objective: str, grid: dict, *, noise=None, progress=None) -> pd.DataFrame:
    """Every plan of ``grid`` (:func:`~sss_locus.experiments.survey_design.plans.plan_grid` keywords),
    the standard plan and the equal-length lawnmower, evaluated; columns of :func:`evaluate`
    plus ``kind`` (``search``/``standard``/``lawnmower``), ``eligible`` and ``front``.

    Parameters
    ----------
    s : Setting
        The setting (:func:`make_setting`).
    objective : str
        A key of :data:`OBJECTIVES`.
    grid : dict
        The plan grid (:func:`check_grid`).
    noise : NoiseModel or None
        The noise model; needed by ``objective="reconstruction"``.
    progress : callable or None
        Called as ``progress(done, total)`` after each plan.

    Returns
    -------
    pandas.DataFrame
        One row per plan with at least one line (columns of :func:`evaluate`, ``kind``,
        ``eligible``, ``front``).

    Raises
    ------
    ValueError
        Unknown objective, a bad grid, or ``"reconstruction"`` without ``noise``.
    """
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {list(OBJECTIVES)}; got {objective!r}")
    grid = check_grid(grid)
    if objective == "reconstruction" and noise is None:
        raise ValueError("objective 'reconstruction' needs noise (a NoiseModel)")
    std = standard_for(s)
    plans = [(std, "standard"), (lawnmower_plan(s.platform, s.area, std), "lawnmower")]
    same = lambda a, b: {**a.row(), "name": ""} == {**b.row(), "name": ""}  # noqa: E731
    plans += [(p, "search") for p in plan_grid(s.platform, s.area, s.terrain, s.settings, s.heights_m, **grid)
              if not any(same(p, q) for q, _ in plans)]
    rows = []
    for k, (plan, kind) in enumerate(plans):
        lines = plan.lines(s.area)
        if lines.empty:
            continue
        rows.append({**evaluate(s, plan, noise=noise if objective == "reconstruction" else None, lines=lines),
                     "kind": kind})
        if progress is not None:
            progress(k + 1, len(plans))
    table = pd.DataFrame(rows)
    table["eligible"] = eligible(table, s.settings)
    col = OBJECTIVES[objective]
    table["front"] = pareto_front(table["total_m"], table[col], table["eligible"])
    return table


def design(platform, area: SurveyArea, terrain: str, *, objective: str = "locus", grid: dict,
           n_features: int = 300, seed: int = 0, grid_m: float = 10.0, noise=None) -> DesignResult:
    """The whole design (module docstring): search, front, recommended plan.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    area : SurveyArea
        The survey area (local metres).
    terrain : str
        One of :data:`~sss_locus.experiments.datamodel.terrain.KINDS`.
    objective : str
        A key of :data:`OBJECTIVES`.
    grid : dict
        The plan grid (:func:`check_grid`).
    n_features : int
        Number of features drawn over the area.
    seed : int
        Seed of the features and the terrain.
    grid_m : float
        Requested coverage grid spacing, m.
    noise : NoiseModel or None
        The noise model (needed by ``"reconstruction"``).

    Returns
    -------
    DesignResult
        The plans table, the recommended index (``None`` when no plan is eligible), the objective
        and the setting.
    """
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {list(OBJECTIVES)}; got {objective!r}")
    check_grid(grid)
    s = make_setting(platform, area, terrain, n_features=n_features, seed=seed, grid_m=grid_m)
    table = search(s, objective, grid, noise=noise)
    std = float(table.loc[table.kind == "standard", "total_m"].iloc[0])
    return DesignResult(table, recommend(table, objective, std), objective, s)


def search_plans(platform, area_key: dict, terrain: str, objective: str, grid: dict, n_features: int,
                 seed: int, grid_m: float, noise=None) -> pd.DataFrame:
    """:func:`design`'s plans table, with the area given by :meth:`SurveyArea.key` (plain data, so
    the call can be cached: ``cached(search_plans)(...)``); the recommended plan is the row with
    ``recommended`` True.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    area_key : dict
        The area as :meth:`SurveyArea.key` gives it.
    terrain : str
        One of :data:`~sss_locus.experiments.datamodel.terrain.KINDS`.
    objective : str
        A key of :data:`OBJECTIVES`.
    grid : dict
        The plan grid (:func:`check_grid`).
    n_features : int
        Number of features drawn over the area.
    seed : int
        Seed of the features and the terrain.
    grid_m : float
        Requested coverage grid spacing, m.
    noise : NoiseModel or None
        The noise model (needed by ``"reconstruction"``).

    Returns
    -------
    pandas.DataFrame
        :func:`design`'s plans table plus a boolean ``recommended`` column (all False when no
        plan is eligible).
    """
    res = design(platform, area_from_key(area_key), terrain, objective=objective, grid=grid,
                 n_features=n_features, seed=seed, grid_m=grid_m, noise=noise)
    return res.plans.assign(recommended=res.plans.index == res.recommended)


def plan_from_row(row) -> Plan:
    """The :class:`~sss_locus.experiments.survey_design.plans.Plan` of a row of the plans table.

    Parameters
    ----------
    row : Mapping
        A row of the plans table (a pandas Series or dict holding every field of ``Plan``).

    Returns
    -------
    Plan
        The plan.
    """
    return Plan(**{k: row[k] for k in Plan.__dataclass_fields__})


def plan_coverage(platform, area: SurveyArea, terrain: str, row, *, grid_m: float, seed: int):
    """A plan's segments (from its row of the plans table) and its measured coverage
    (:func:`~sss_locus.experiments.survey_design.coverage.coverage`) on the design's terrain.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    area : SurveyArea
        The survey area (local metres).
    terrain : str
        One of :data:`~sss_locus.experiments.datamodel.terrain.KINDS`.
    row : Mapping
        The plan's row of the plans table.
    grid_m : float
        Requested coverage grid spacing, m.
    seed : int
        The design's seed (same terrain).

    Returns
    -------
    lines : pandas.DataFrame
        The plan's line segments in the area frame.
    cov : dict
        :func:`~sss_locus.experiments.survey_design.coverage.coverage`'s result.
    """
    s = make_setting(platform, area, terrain, n_features=10, seed=seed, grid_m=grid_m)
    plan = plan_from_row(row)
    lines = plan.lines(area)
    cov = coverage(platform, s.terrain, area, lines, plan.altitude_m, plan.pitch_deg, platform.fixed_depth,
                   grid_m=s.grid_m, seed=seed, centre=s.centre)
    return lines, cov


def by_crossing_angle(plans: pd.DataFrame, objective: str) -> pd.DataFrame:
    """The searched eligible plans grouped by their second line set: ``second_set`` (``"none"``,
    ``"repeat"`` for an offset repeat at 0°, else ``"cross <angle>°"``), ``crossing_deg`` (NaN
    for none), the number of plans, the best and the median objective, and the median crossing
    angle of the features' best pairs.

    Parameters
    ----------
    plans : pandas.DataFrame
        The plans table (:func:`search`).
    objective : str
        A key of :data:`OBJECTIVES`.

    Returns
    -------
    pandas.DataFrame
        One row per second line set, columns ``second_set``, ``crossing_deg``, ``n_plans``,
        ``best``, ``median``, ``best_pair_angle_median_deg``; sorted by ``crossing_deg`` (none
        first); empty when no searched plan is eligible.
    """
    col = OBJECTIVES[objective]
    t = plans[(plans.kind == "search") & plans.eligible].copy()
    t["second_set"] = [("none" if math.isnan(g) else "repeat" if g % 180 == 0 else f"cross {g:g}°")
                       for g in t.crossing_deg]
    out = t.groupby("second_set", sort=False).agg(
        crossing_deg=("crossing_deg", "first"), n_plans=(col, "size"), best=(col, "min"),
        median=(col, "median"), best_pair_angle_median_deg=("best_pair_angle_median_deg", "median"))
    return out.reset_index().sort_values("crossing_deg", na_position="first", kind="stable").reset_index(drop=True)
