"""Memory and time budgets of a run, estimated from its inputs before any kernel starts.

A parameter's own cost is declared in its comment (``~2.8 kB`` per sample,
:mod:`sss_locus.pipeline.constraints`); what grows with a *product* of parameters and input
files is estimated here, per chapter, and a run that would not fit is refused in one line naming
the parameter to change:

* ``planning`` (and ``sss-locus answer``): the crossing-angle grid (``fine_step_deg`` up to
  40 deg, then ``coarse_step_deg``) times ``n_per_angle`` pass pairs per angle, every row kept;
* ``survey_design``: the coverage grid's cells (the area's bounding box over ``grid_m``) times
  the lines of the densest plan searched, per plan; and the feature sampler, which draws from
  the area's bounding box (a thin area far from its box would need unbounded draws).

The costs per unit were measured on this project's code (``BYTES_*``, ``SECONDS_*``, with the
command in each constant's note); the memory budget is :func:`constraints.memory_budget` (half
the RAM, ``$SSS_LOCUS_MEMORY_BUDGET``), the time budget :func:`time_budget_s`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from sss_locus.pipeline.constraints import memory_budget
from sss_locus.pipeline.context import TIME_BUDGET_ENV, current  # the time budget's setting (seconds)

#: Default time budget of one run, seconds (a day).
DEFAULT_TIME_BUDGET_S = 24 * 3600.0
#: Peak memory per kept pass-pair row of the planning curve, bytes (measured: 180 B kept, up to
#: ~2.2 kB of peak growth per row at 200 rows per angle, ~0.4 kB at 2000; tracemalloc/ru_maxrss
#: around ``crossing_angle_curve``).
BYTES_PER_PASS_PAIR = 2500.0
#: Time per pass-pair row, seconds (measured 18-74 us on a shared 2-core machine).
SECONDS_PER_PASS_PAIR = 20e-6
#: Peak memory per coverage cell and line of a plan, bytes (measured 555-852 B with tracemalloc
#: around ``survey_design.evaluate`` of the standard plan, example area, grid 10-20 m).
BYTES_PER_CELL_LINE = 900.0
#: Time per coverage cell and line of one plan, seconds (measured 5.6-20 us, 100 us at ~4k
#: cell-lines where fixed costs dominate).
SECONDS_PER_CELL_LINE = 10e-6
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
    """Number of angles of :func:`sss_locus.experiments.planning.crossing_angle_grid`, counted
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


def check_survey_design(parameters: Mapping[str, Any], area: Any, platforms: list[Any], settings: Mapping[str, Any]) -> None:
    """The survey design's budget (module docstring): ``area`` a
    :class:`~sss_locus.experiments.survey_area.SurveyArea`, ``platforms`` the
    :class:`~sss_locus.experiments.platforms.Platform` of the run, ``settings`` the validated
    ``survey_design`` table. Checked before the features are drawn."""
    x0, y0, x1, y1 = area.polygon.bounds
    box_m2 = max((x1 - x0) * (y1 - y0), 1e-9)
    fill = area.area_m2 / box_m2
    n_features = parameters["n_features"]
    if n_features / fill > MAX_FEATURE_DRAWS:
        raise BudgetError(
            f"area {area.name!r} fills only {fill:.2g} of its bounding box ({x1 - x0:,.0f} m x {y1 - y0:,.0f} m), so "
            f"drawing n_features = {n_features} features inside it would take about {n_features / fill:.2g} draws "
            f"(at most {MAX_FEATURE_DRAWS:,}): use a wider area (-p area) or fewer n_features")
    grid_m = parameters["grid_m"]
    cells = math.ceil((x1 - x0) / grid_m) * math.ceil((y1 - y0) / grid_m)
    diagonal = math.hypot(x1 - x0, y1 - y0)
    fractions = list(parameters["spacing_fractions"]) + [settings["standard_spacing_fraction"]]
    cross = min(parameters["cross_spacing_factors"]) if parameters["crossing_angles_deg"] else math.inf
    plans = _plan_count(parameters)  # the search, then a few of them rescored on every noise seed
    runs = plans + len(parameters.get("noise_seeds", [])) * min(plans, 30)
    for platform in platforms:
        spacing = min(fractions) * platform.sonar.max_range_m * settings["range_scale_fraction"]
        lines = (diagonal / spacing + 1) * (1 + (1 / cross if math.isfinite(cross) else 0))
        need, need_s = cells * lines * BYTES_PER_CELL_LINE, runs * cells * lines * SECONDS_PER_CELL_LINE
        coarser = grid_m * math.sqrt(max(need / memory_budget(), need_s / time_budget_s())) * 1.05
        _refuse(f"the coverage of area {area.name!r} ({cells:,} cells of grid_m = {grid_m:g} m x up to "
                f"{lines:,.0f} lines of {platform.key!r}, {runs} plan runs)", need, need_s,
                f"raise grid_m (to about {coarser:,.3g} m or more) or use a smaller area (-p area)")


def check_parameters(parameters: Mapping[str, Any]) -> None:
    """The budgets a run's parameters alone decide (the planning curve's, when it has its
    parameters); the survey design's is checked where its area is read
    (:func:`sss_locus.pipeline.userfiles.check_files`)."""
    if {"fine_step_deg", "coarse_step_deg", "n_per_angle"} <= set(parameters):
        check_planning(parameters)
