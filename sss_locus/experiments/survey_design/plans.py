"""Survey plans: the plan space searched by the survey design, the platform's limits on it, and
the baselines a hydrographer runs today.

A :class:`Plan` is a set of main lines (heading, spacing), optionally a set of cross lines at a
``crossing_deg`` to them (0: a repeat of the main lines offset by half a spacing, the standard
second coverage) with their own spacing, and the vehicle's altitude and pitch on every line.

Limits (:func:`plan_limits`, each plan outside them is left out of the search, never clipped):
the altitude must leave a swath (``altitude < range``, above the transducer) and put the vehicle
within its depth rating (``depth_m.min <= water depth - seafloor height - altitude <=
depth_m.max`` over the whole area, the seafloor height from the terrain); a platform of fixed
depth (a surface vessel) flies at the one altitude the water depth gives; ``|pitch|`` within
the platform's pitch limit. Turns use the platform's ``mission.turn_radius_m``
(:mod:`sss_locus.experiments.survey_design.lines`).

Baselines (:func:`standard_plan`, :func:`lawnmower_plan`), values in ``data/survey_design.toml``
with their sources:

Every plan is flown the same way (:func:`flown`): lines extended to wherever their swath reaches
the area (also lines outside it), with a run-in and run-out of ``run_in_turn_radii`` turn radii.

``standard``
    the standard sidescan plan: lines ``standard_spacing_fraction`` (1.6) x the range scale
    apart, 200 % coverage by a second set offset by ``standard_offset_fraction`` of a spacing,
    altitude the middle of ``[standard_altitude_min_fraction, standard_altitude_max_fraction]`` x
    the range scale (clipped to the platform's limits; a surface vessel: the water depth), lines
    perpendicular to the depth contours on a slope (along its azimuth), else along the area's
    long axis;
``lawnmower``
    one set of lines at the standard heading and altitude, spaced so that its flown track
    (:func:`~sss_locus.experiments.survey_design.route.track_cost`) is as long as the standard plan's (bisection on the spacing; lines come in whole numbers, so the
    longest track not longer than the standard's): the same effort spent on plain parallel
    lines.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_design.area import SurveyArea, principal_heading_deg
from sss_locus.experiments.survey_design.lines import across_extent, flown_positions, line_set
from sss_locus.experiments.survey_design.route import flight_path, track_cost


@dataclass(frozen=True)
class Plan:
    """One survey plan (see the module docstring); angles in degrees, lengths in metres.
    ``crossing_deg`` NaN: no cross lines."""

    heading_deg: float
    spacing_m: float
    crossing_deg: float
    cross_spacing_m: float
    altitude_m: float
    pitch_deg: float = 0.0
    name: str = ""
    reach_m: float = 0.0
    run_m: float = 0.0
    near_m: float = 0.0
    turn_radius_m: float = 0.0

    def lines(self, area: SurveyArea) -> pd.DataFrame:
        """The plan's segments in run order: main lines, then the second set (``set`` ``"cross"``
        for cross lines, ``"repeat"`` for an offset repeat at the main lines' heading; as flown
        when ``reach_m`` > 0: :func:`~sss_locus.experiments.survey_design.lines.line_set`).

        Parameters
        ----------
        area : SurveyArea
            The survey area (local east/north metres).

        Returns
        -------
        pandas.DataFrame
            One row per segment in run order, area frame (local metres), with ``heading_deg`` and
            ``set`` (``"main"``, ``"cross"`` or ``"repeat"``); empty when no line falls inside the area.
        """
        fly = dict(reach_m=self.reach_m, run_m=self.run_m, near_m=self.near_m)
        repeat = not math.isnan(self.crossing_deg) and self.crossing_deg % 180.0 == 0.0
        at = [None, None]
        if repeat and self.reach_m > 0:  # the two sets at one heading are trimmed together
            lo, hi = across_extent(area, self.heading_deg)
            at = flown_positions(lo, hi, [(self.spacing_m, 0.0), (self.cross_spacing_m, 0.5)], self.reach_m,
                                 self.near_m)
        main = line_set(area, self.heading_deg, self.spacing_m, name="main", across_m=at[0], **fly)
        if math.isnan(self.crossing_deg):
            return self._fit(area, main)
        offset = 0.5 if repeat else 0.0
        cross = line_set(area, (self.heading_deg + self.crossing_deg) % 360.0, self.cross_spacing_m,
                         offset=offset, name="repeat" if repeat else "cross", across_m=at[1], **fly)
        return self._fit(area, pd.concat([main, cross], ignore_index=True))

    def _fit(self, area: SurveyArea, lines: pd.DataFrame) -> pd.DataFrame:
        """``lines`` with their ends pulled back where a U-turn would leave the navigable water
        (:func:`~sss_locus.experiments.survey_design.turns.fit_turns`; open water: as they are)."""
        from sss_locus.experiments.survey_design.turns import fit_turns

        water = area.water()
        if water is None or self.turn_radius_m <= 0 or lines.empty:
            return lines
        return fit_turns(lines, water.buffer(-area.clearance_m), self.turn_radius_m)[0]

    def row(self) -> dict:
        """The plan as a plain dict (field -> value), a row of the plans table.

        Returns
        -------
        dict
            Every field of the plan (angles in degrees, lengths in metres).
        """
        return asdict(self)


def range_scale_m(platform, settings) -> float:
    """The sonar's range scale: ``max_range_m`` times the setting ``range_scale_fraction``, m.

    Parameters
    ----------
    platform : Platform
        The platform (its ``sonar.max_range_m``, m).
    settings : dict
        Survey-design settings (:func:`~sss_locus.experiments.survey_design.settings.load_settings`).

    Returns
    -------
    float
        The range scale, m.
    """
    return platform.sonar.max_range_m * settings["range_scale_fraction"]


def swath_reach_m(platform, settings, altitude_m: float) -> float:
    """Horizontal reach of the swath (its far edge from the track, the wider side) at
    ``altitude_m`` over a flat seafloor, within the range scale, m.

    Parameters
    ----------
    platform : Platform
        The platform (sonar fan and transducers).
    settings : dict
        Survey-design settings (:func:`~sss_locus.experiments.survey_design.settings.load_settings`).
    altitude_m : float
        Altitude above the seafloor, m.

    Returns
    -------
    float
        Horizontal distance from the track to the swath's far edge, m (the lateral offset of the
        transducers when the altitude exceeds the range scale).
    """
    from sss_locus.experiments.passes.straight_pass import swath_m

    far = max(float(swath_m(platform, [port], [altitude_m])[1][0]) for port in (True, False))
    scale = range_scale_m(platform, settings)
    lateral = max(abs(t.lateral_offset_m) for t in platform.transducers.values())
    return min(far, lateral + math.sqrt(max(scale ** 2 - altitude_m ** 2, 0.0)))


def flown(platform, settings, plan: Plan) -> Plan:
    """``plan`` as flown: every line whose swath reaches the area, run-in and run-out of
    ``run_in_turn_radii`` x the turn radius (module docstring of
    :mod:`~sss_locus.experiments.survey_design.lines`).

    Parameters
    ----------
    platform : Platform
        The platform (sonar fan, turn radius).
    settings : dict
        Survey-design settings with ``run_in_turn_radii``.
    plan : Plan
        The plan as designed.

    Returns
    -------
    Plan
        A copy with ``reach_m``, ``near_m`` (nadir-gap half width, m), ``run_m`` and
        ``turn_radius_m`` set.
    """
    from dataclasses import replace

    from sss_locus.experiments.passes.straight_pass import swath_m

    near = max(0.0, min(float(swath_m(platform, [port], [plan.altitude_m])[0][0]) for port in (True, False)))
    return replace(plan, reach_m=swath_reach_m(platform, settings, plan.altitude_m), near_m=near,
                   run_m=settings["run_in_turn_radii"] * platform.turn_radius_m, turn_radius_m=platform.turn_radius_m)


def check_mission(platform) -> None:
    """Refuse a platform without the ``mission`` values the design needs, in one line.

    Parameters
    ----------
    platform : Platform
        The platform; its ``turn_radius_m`` (m) and ``speed_m_s`` (m/s) must be given.

    Raises
    ------
    ValueError
        A mission value missing, naming the TOML key to add.
    """
    for name in ("turn_radius_m", "speed_m_s"):
        if getattr(platform, name, None) is None:
            raise ValueError(f"platforms.{platform.key}.mission.{name} is needed by the survey design: add "
                             f"[platforms.{platform.key}.mission] {name} = {{ value = ..., source|assumption = ... }}")


def altitude_limits(platform, settings, heights_m) -> tuple[float, float]:
    """The altitudes (above the local seafloor, m) the platform may fly over seafloor heights
    ``heights_m`` (module docstring); ``lo > hi`` when none.

    Parameters
    ----------
    platform : Platform
        The platform (depth rating, transducer depths, sonar range).
    settings : dict
        Survey-design settings with ``water_depth_m`` (m).
    heights_m : array_like
        Seafloor heights over the area, m (up, relative to the mean seafloor), any shape.

    Returns
    -------
    lo, hi : float
        The lowest and highest allowed altitude, m; ``lo > hi`` when no altitude fits.
    """
    water = water_depth(settings)
    hmin, hmax = float(np.min(heights_m)), float(np.max(heights_m))
    t_depth = max(t.depth_m for t in platform.transducers.values())
    lo = max(1e-6, t_depth + 1e-6, water - hmin - platform.depth_max_m)
    hi = min(platform.sonar.max_range_m * 0.999, water - hmax - platform.depth_min_m)
    return lo, hi


def fixed_altitude_m(platform, settings) -> float | None:
    """A platform of fixed depth flies at ``water depth - its depth`` above the mean seafloor;
    a water depth that puts the seafloor above its transducers or where its fan sees none of it
    (deeper than ``max_range_m`` times the sine of the fan's steepest look-down, below 90°) is
    refused in one line naming the platform, the depth's source and the depths it can survey.

    Parameters
    ----------
    platform : Platform
        The platform (``fixed_depth``, depth rating, transducers, sonar).
    settings : dict
        Survey-design settings with ``water_depth_m`` (m) and optionally ``water_depth_source``.

    Returns
    -------
    float or None
        The altitude above the mean seafloor, m; ``None`` for a platform that is not of fixed depth.

    Raises
    ------
    ValueError
        The water depth is outside the depths the platform's sonar sees the seafloor in.
    """
    if not platform.fixed_depth:
        return None
    depth = water_depth(settings)
    son = platform.sonar
    sides = platform.transducers.values()
    lo = platform.depth_min_m + max(t.depth_m for t in sides)
    steepest = {t.tilt_deg + son.azimuth_deg / 2 for t in sides}
    hi = platform.depth_min_m + min(t.depth_m + son.max_range_m * math.sin(math.radians(min(d, 90.0)))
                                    for t, d in zip(sides, (t.tilt_deg + son.azimuth_deg / 2 for t in sides)))
    if not lo < depth < hi:
        raise ValueError(f"platforms.{platform.key}: the water depth {depth:g} m "
                         f"({settings.get('water_depth_source') or 'survey_design.water_depth_m'}) is outside "
                         f"({lo:g}, {hi:.4g}) m, the depths its sonar sees the seafloor in (transducers "
                         f"{lo - platform.depth_min_m:g} m deep, fan down to {min(steepest):g}° below the horizontal, "
                         f"sonars.{son.key}.max_range_m = {son.max_range_m:g} m)")
    return depth - platform.depth_min_m


def water_depth(settings) -> float:
    """The mean water depth of ``settings`` (set from the area or the run by the design), refused
    in one line when nobody gave one.

    Parameters
    ----------
    settings : dict
        Survey-design settings.

    Returns
    -------
    float
        ``settings["water_depth_m"]``, m (positive down).

    Raises
    ------
    ValueError
        No ``water_depth_m`` given.
    """
    if settings.get("water_depth_m") is None:
        raise ValueError("no water depth: give the area file a water_depth_m (mean water depth over the area, m), "
                         "or the run -p water_depth_m VALUE (or --set survey_design.water_depth_m=VALUE)")
    return float(settings["water_depth_m"])


def plan_ok(platform, settings, heights_m, plan: Plan) -> bool:
    """Whether ``plan`` is within the platform's limits (module docstring).

    Parameters
    ----------
    platform : Platform
        The platform (pitch limit, depth rating).
    settings : dict
        Survey-design settings with ``water_depth_m`` (m).
    heights_m : array_like
        Seafloor heights over the area, m.
    plan : Plan
        The plan checked.

    Returns
    -------
    bool
        True when pitch and altitude are within the limits.
    """
    if abs(plan.pitch_deg) > platform.pitch_max_deg:
        return False
    fixed = fixed_altitude_m(platform, settings)
    if fixed is not None:
        return plan.altitude_m == fixed and fixed - float(np.max(heights_m)) > 0
    lo, hi = altitude_limits(platform, settings, heights_m)
    return lo <= plan.altitude_m <= hi


def standard_heading_deg(area: SurveyArea, terrain) -> float:
    """The standard plan's line heading: along the slope's azimuth on a slope, else along the area's long axis.

    Parameters
    ----------
    area : SurveyArea
        The survey area (local metres).
    terrain : Terrain
        The terrain (its ``kind`` and ``params``).

    Returns
    -------
    float
        Heading, degrees counter-clockwise from east (the area frame), in [0, 180).
    """
    if terrain.kind == "slope" and terrain.params.get("slope_deg", 0.0) > 0:
        return float(terrain.params["azimuth_deg"] % 180.0)
    return principal_heading_deg(area)


def standard_plan(platform, area: SurveyArea, terrain, settings, heights_m) -> Plan:
    """The standard sidescan plan (module docstring).

    Parameters
    ----------
    platform : Platform
        The platform.
    area : SurveyArea
        The survey area (local metres).
    terrain : Terrain
        The terrain (sets the heading on a slope).
    settings : dict
        Survey-design settings (:func:`~sss_locus.experiments.survey_design.settings.load_settings`, with ``water_depth_m``).
    heights_m : array_like
        Seafloor heights over the area, m.

    Returns
    -------
    Plan
        The standard plan, as flown (:func:`flown`); its altitude is clipped to the limits, so
        check it with :func:`plan_ok`.
    """
    R = range_scale_m(platform, settings)
    fixed = fixed_altitude_m(platform, settings)
    if fixed is not None:
        alt = fixed
    else:
        lo, hi = altitude_limits(platform, settings, heights_m)
        mid = 0.5 * (settings["standard_altitude_min_fraction"] + settings["standard_altitude_max_fraction"]) * R
        alt = float(np.clip(mid, lo, hi))
    spacing = settings["standard_spacing_fraction"] * R
    return flown(platform, settings, Plan(standard_heading_deg(area, terrain), spacing, 0.0, spacing, alt, 0.0,
                                          "standard"))


def lawnmower_plan(platform, area: SurveyArea, standard: Plan) -> Plan:
    """Parallel lines only, spaced so the track is as long as the standard plan's (bisection).

    Parameters
    ----------
    platform : Platform
        The platform (turn radius).
    area : SurveyArea
        The survey area (local metres).
    standard : Plan
        The standard plan (heading, altitude, flight values).

    Returns
    -------
    Plan
        The lawnmower plan (``crossing_deg`` NaN), spacing in [1, 4 x the standard's spacing] m.
    """
    flown_m = lambda lines: track_cost(flight_path(area, lines, platform.turn_radius_m)[0])["total_m"]  # noqa: E731
    target = flown_m(standard.lines(area))
    mk = lambda s: Plan(standard.heading_deg, s, math.nan, s, standard.altitude_m, 0.0, "lawnmower",  # noqa: E731
                        standard.reach_m, standard.run_m, standard.near_m, standard.turn_radius_m)
    lo, hi = 1.0, standard.spacing_m * 4
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lines = mk(mid).lines(area)
        total = flown_m(lines) if len(lines) else 0.0
        lo, hi = (mid, hi) if total > target else (lo, mid)
    return mk(hi)


def plan_grid(platform, area: SurveyArea, terrain, settings, heights_m, *, headings_deg, spacing_fractions,
              crossing_angles_deg, cross_spacing_factors, altitude_fractions, pitches_deg) -> list[Plan]:
    """Every plan of the grid within the platform's limits. ``crossing_angles_deg`` may hold NaN
    (no cross lines); spacings are fractions of the range scale, cross spacings factors of the
    main spacing, altitudes fractions of the range scale (a fixed-depth platform: its one).

    Parameters
    ----------
    platform : Platform
        The platform.
    area : SurveyArea
        The survey area (local metres).
    terrain : Terrain
        The terrain.
    settings : dict
        Survey-design settings (:func:`~sss_locus.experiments.survey_design.settings.load_settings`, with ``water_depth_m``).
    heights_m : array_like
        Seafloor heights over the area, m.
    headings_deg : sequence of float
        Main-line headings, degrees counter-clockwise from east (the area frame).
    spacing_fractions : sequence of float
        Main-line spacings as fractions of the range scale.
    crossing_angles_deg : sequence of float
        Angles of the second set to the main lines, degrees (NaN: none, 0: offset repeat).
    cross_spacing_factors : sequence of float
        Second-set spacings as factors of the main spacing.
    altitude_fractions : sequence of float
        Altitudes as fractions of the range scale (ignored for a fixed-depth platform).
    pitches_deg : sequence of float
        Vehicle pitches, degrees.

    Returns
    -------
    list of Plan
        The plans within the limits, as flown; empty when none is.
    """
    R = range_scale_m(platform, settings)
    fixed = fixed_altitude_m(platform, settings)
    alts = [fixed] if fixed is not None else [float(a) * R for a in altitude_fractions]
    plans = []
    for h in headings_deg:
        for s in spacing_fractions:
            for g in crossing_angles_deg:
                for cf in ([1.0] if math.isnan(g) else cross_spacing_factors):
                    for a in alts:
                        for p in pitches_deg:
                            plan = Plan(float(h), float(s) * R, float(g), float(s) * R * float(cf), float(a), float(p))
                            if plan_ok(platform, settings, heights_m, plan):
                                plans.append(flown(platform, settings, plan))
    return plans
