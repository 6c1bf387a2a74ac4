"""Memory and time budgets of a run, estimated from its inputs before any kernel starts.

A parameter's own cost is declared in its chapter's model (``MemoryPerUnit(2800)`` bytes per
sample, :mod:`sss_locus.pipeline.run.params`); what grows with a *product* of parameters and input
files is estimated here, per chapter, and a run that would not fit is refused in one line naming
the parameter to change:

* ``planning`` (and ``sss-locus answer``): the crossing-angle grid (``fine_step_deg`` up to
  40 deg, then ``coarse_step_deg``) times ``n_per_angle`` pass pairs per angle, every row kept;
* ``survey_design``: per plan searched, the coverage cells (over the area at ``grid_m``, or at
  the coarser grid a large area is measured on, :func:`~sss_locus.experiments.survey_design.front.coverage_grid_m`)
  times the lines whose swath reaches a cell (the densest plan's), and the features times the
  plan's segments; then the joint scoring, ``noise_seeds`` times the ``n_scored`` leading plans
  and the baselines, each the features times the segments; memory the larger of one plan's
  coverage and one joint scoring (:func:`survey_design_cost`). And the feature sampler, which
  draws from the area's bounding box (a thin area far from its box would need unbounded draws).

The costs per unit were measured on this project's code (``BYTES_*``, ``SECONDS_*``, with the
command in each constant's note); the memory budget is :func:`params.memory_budget` (half
the RAM, ``$SSS_LOCUS_MEMORY_BUDGET``), the time budget :func:`time_budget_s`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from sss_locus.pipeline.run.params import memory_budget
from sss_locus.pipeline.run.context import TIME_BUDGET_ENV, current  # the time budget's setting (seconds)

#: Default time budget of one run, seconds (a day).
DEFAULT_TIME_BUDGET_S = 24 * 3600.0
#: Peak memory per kept pass-pair row of the planning curve, bytes (measured: 180 B kept, up to
#: ~2.2 kB of peak growth per row at 200 rows per angle, ~0.4 kB at 2000; tracemalloc/ru_maxrss
#: around ``crossing_angle_curve``).
BYTES_PER_PASS_PAIR = 2500.0
#: Time per pass-pair row, seconds (measured 18-74 us on a shared 2-core machine).
SECONDS_PER_PASS_PAIR = 20e-6
#: Peak memory per coverage cell, bytes (the cells near one segment observed at once; bounded
#: by all the cells: measured 555-852 B per cell and line with tracemalloc around
#: ``survey_design.evaluate``, example area, grid 10-20 m).
BYTES_PER_CELL_LINE = 900.0
#: Time per coverage cell and line reaching it, one plan, seconds (measured 6 us before one
#: attitude per heading: the 5 km boat's standard plan, 20,000 cells, 2.5 lines reaching a cell,
#: 0.31 s CPU of ``survey_design.evaluate``; the benchmark's 82 plans 36 s, 0.44 s a plan; since,
#: 12.3 s boat and 24 s AUV, bench_survey_design.py).
SECONDS_PER_CELL_LINE = 2e-6
#: Time per feature and segment of one plan in the search (observation, best pairs, triples),
#: seconds (measured 3.3 us: 200 and 4,000 features on the 5 km boat's 44 segments, 0.31 and
#: 0.87 s CPU).
SECONDS_PER_FEATURE_LINE = 4e-6
#: Time per feature and segment of one plan and seed of the joint scoring, seconds
#: (``surveydesign.joint.plan_joint_errors``; measured 30-70 us with 1,000-2,000 features on a
#: 5 km square, up to 0.5 ms where 200 features over 25 km^2 leave the passes weakly tied and the
#: solver needs a hundred evaluations: the AUV's 43 segments, 3-6 s CPU at LSMR tolerance 1e-10,
#: about 1.8 s at the scoring's 1e-8; the larger is used).
SECONDS_PER_JOINT_FEATURE_LINE = 5e-4
#: Fixed time per plan and seed of the joint scoring, seconds (measured 0.05-0.2 s on the
#: example area's 6-9 segments with 200 features).
SECONDS_PER_JOINT_RUN = 0.2
#: Peak memory per feature and segment of the joint scoring, bytes (measured 1.1-1.6 kB with
#: tracemalloc around ``plan_joint_errors``: 2,000 features on 44 and on 10 segments).
BYTES_PER_FEATURE_LINE = 2000.0
#: Most candidate points the feature sampler may draw (it draws from the area's bounding box).
MAX_FEATURE_DRAWS = 20_000_000


class BudgetError(ValueError):
    """A run that would not fit the memory or time budget (one line, naming the parameter)."""


def time_budget_s() -> float:
    """Seconds a run may be estimated to take: the run context's (``$SSS_LOCUS_TIME_BUDGET_S``) or a day."""
    text = current().time_budget_s
    if not text:
        return DEFAULT_TIME_BUDGET_S
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise BudgetError(f"{TIME_BUDGET_ENV} must be a number of seconds > 0; got {text!r}")
    return value


def _gb(n: float) -> str:
    return f"{n / 1e9:.3g} GB"


def _hours(s: float) -> str:
    return f"{s / 3600:.3g} h"


def _refuse(what: str, need_bytes: float, need_s: float, change: str) -> None:
    """Raise :class:`BudgetError` when ``need_bytes`` or ``need_s`` exceed the budgets."""
    mem, secs = memory_budget(), time_budget_s()
    if need_bytes > mem:
        raise BudgetError(f"{what} would need about {_gb(need_bytes)} of memory, more than the budget of "
                          f"{_gb(mem)} (half the RAM; SSS_LOCUS_MEMORY_BUDGET): {change}")
    if need_s > secs:
        raise BudgetError(f"{what} would take about {_hours(need_s)}, more than the budget of {_hours(secs)} "
                          f"({TIME_BUDGET_ENV}): {change}")


def crossing_angle_count(fine_step_deg: float, coarse_step_deg: float, fine_max_deg: float = 40.0) -> float:
    """Number of angles of :func:`sss_locus.experiments.survey_passes.planning.crossing_angle_grid`, counted
    without building it (within one or two of its length)."""
    return math.floor(fine_max_deg / fine_step_deg) + 1 + math.floor((180.0 - fine_max_deg) / coarse_step_deg) + 1


def check_planning(parameters: Mapping[str, Any]) -> None:
    """The planning curve's budget (module docstring)."""
    angles = crossing_angle_count(parameters["fine_step_deg"], parameters["coarse_step_deg"])
    per_angle = parameters["n_per_angle"]
    rows = angles * float(sum(per_angle) if isinstance(per_angle, (list, tuple)) else per_angle)
    n_platforms = max(1, len(parameters.get("platforms", [])) or 1)
    fine_angles = crossing_angle_count(parameters["fine_step_deg"], 180.0) - 1
    change = (f"raise fine_step_deg (now {parameters['fine_step_deg']:g}, {fine_angles:,.0f} angles up to 40 deg)"
              if fine_angles > angles / 2 else
              f"raise coarse_step_deg (now {parameters['coarse_step_deg']:g})")
    change += f" or lower n_per_angle (now {per_angle})"
    _refuse(f"the crossing-angle curve ({angles:,.0f} angles x {per_angle} pass pairs)",
            rows * BYTES_PER_PASS_PAIR, rows * SECONDS_PER_PASS_PAIR * n_platforms, change)


def _plan_count(parameters: Mapping[str, Any]) -> int:
    crossings = len(parameters["crossing_angles_deg"]) * len(parameters["cross_spacing_factors"])
    crossings += 1 if parameters.get("no_cross_lines", True) else 0
    return (len(parameters["headings_deg"]) * len(parameters["spacing_fractions"]) * crossings
            * len(parameters["altitude_fractions"]) * len(parameters["pitches_deg"]) + 2)


def survey_design_cost(parameters: Mapping[str, Any], area: Any, platform: Any, settings: Mapping[str, Any]) -> dict:
    """The survey design's estimated cost for one platform (module docstring).

    Parameters
    ----------
    parameters : mapping
        The run's parameters (``grid_m``, ``n_features``, the search grid, ``noise_seeds``,
        ``n_scored``).
    area : SurveyArea
    platform : Platform
    settings : mapping
        The validated ``survey_design`` table.

    Returns
    -------
    dict
        ``cells`` (coverage cells), ``grid_m`` (the grid they are on), ``segments`` (of the
        densest plan; the scored plans, no longer than the standard plan, are costed with its
        two sets of lines), ``plans``, ``scored`` (plans scored per seed), ``search_s``,
        ``scoring_s`` (seconds), ``bytes`` (peak memory).
    """
    from sss_locus.experiments.survey_design.front import coverage_grid_m

    x0, y0, x1, y1 = area.polygon.bounds
    grid = coverage_grid_m(area, float(parameters["grid_m"]))
    cells = math.ceil((x1 - x0) / grid) * math.ceil((y1 - y0) / grid) * min(1.0, area.area_m2 / max((x1 - x0) * (y1 - y0), 1e-9))
    fractions = list(parameters["spacing_fractions"]) + [settings["standard_spacing_fraction"]]
    cross = min(parameters["cross_spacing_factors"]) if parameters["crossing_angles_deg"] else math.inf
    second = 1 / cross if math.isfinite(cross) else 0.0
    reach = platform.sonar.max_range_m * settings["range_scale_fraction"]
    spacing = min(fractions) * reach
    segments = (math.hypot(x1 - x0, y1 - y0) / spacing + 1) * (1 + second)
    per_cell = 2 * reach / spacing * (1 + second) + 1
    # the scored plans are no longer than the standard plan: its two sets of lines
    scored_segments = (math.hypot(x1 - x0, y1 - y0) / (settings["standard_spacing_fraction"] * reach) + 1) * 2
    plans = _plan_count(parameters)
    n = float(parameters["n_features"])
    scored = min(int(parameters.get("n_scored", 8)), plans) + 3
    seeds = len(parameters.get("noise_seeds", []))
    search_s = plans * (cells * per_cell * SECONDS_PER_CELL_LINE + n * segments * SECONDS_PER_FEATURE_LINE)
    scoring_s = seeds * scored * (SECONDS_PER_JOINT_RUN + n * scored_segments * SECONDS_PER_JOINT_FEATURE_LINE)
    return {"cells": cells, "grid_m": grid, "segments": segments, "plans": plans, "scored": scored,
            "search_s": search_s, "scoring_s": scoring_s,
            "bytes": max(cells * BYTES_PER_CELL_LINE, n * segments * BYTES_PER_FEATURE_LINE)}


def check_survey_design(parameters: Mapping[str, Any], area: Any, platforms: list[Any], settings: Mapping[str, Any]) -> None:
    """The survey design's budget (module docstring): ``area`` a
    :class:`~sss_locus.experiments.survey_design.area.SurveyArea`, ``platforms`` the
    :class:`~sss_locus.experiments.datamodel.platforms.Platform` of the run, ``settings`` the validated
    ``survey_design`` table. Checked before the features are drawn; a refusal names the
    parameters whose cost dominates (the coverage grid is coarsened to at most
    :data:`~sss_locus.experiments.survey_design.front.MAX_COVERAGE_CELLS` cells, so ``grid_m`` never
    dominates)."""
    x0, y0, x1, y1 = area.polygon.bounds
    box_m2 = max((x1 - x0) * (y1 - y0), 1e-9)
    fill = area.area_m2 / box_m2
    n_features = parameters["n_features"]
    if n_features / fill > MAX_FEATURE_DRAWS:
        raise BudgetError(
            f"area {area.name!r} fills only {fill:.2g} of its bounding box ({x1 - x0:,.0f} m x {y1 - y0:,.0f} m), so "
            f"drawing n_features = {n_features} features inside it would take about {n_features / fill:.2g} draws "
            f"(at most {MAX_FEATURE_DRAWS:,}): use a wider area (-p area) or fewer n_features")
    costs = [survey_design_cost(parameters, area, platform, settings) for platform in platforms]
    if not costs:
        return
    need = max(c["bytes"] for c in costs)
    search_s, scoring_s = sum(c["search_s"] for c in costs), sum(c["scoring_s"] for c in costs)
    worst = max(costs, key=lambda c: c["bytes"])
    seeds = len(parameters.get("noise_seeds", []))
    if need > memory_budget() or search_s >= scoring_s:  # the features times the segments dominate
        change = f"lower n_features (now {n_features}) or use a smaller area (-p area)"
    else:
        change = (f"lower noise_seeds (now {seeds} seeds), n_scored (now {parameters.get('n_scored', 8)}) or "
                  f"n_features (now {n_features}), or use a smaller area (-p area)")
    _refuse(f"the survey design over area {area.name!r} ({n_features:,} features, {worst['cells']:,.0f} coverage cells "
            f"of {worst['grid_m']:.3g} m, up to {worst['segments']:,.0f} segments a plan, {worst['plans']} plans, "
            f"{worst['scored']} scored with the joint adjustment on {seeds} seeds)", need, search_s + scoring_s, change)


def check_parameters(parameters: Mapping[str, Any]) -> None:
    """The budgets a run's parameters alone decide (the planning curve's, when it has its
    parameters); the survey design's is checked where its area is read
    (:func:`sss_locus.pipeline.run.userfiles.check_files`)."""
    if {"fine_step_deg", "coarse_step_deg", "n_per_angle"} <= set(parameters):
        check_planning(parameters)
