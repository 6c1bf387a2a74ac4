"""Tables of the survey-design chapter (``notebooks/survey_design.ipynb``) as a reader reads them.

Inputs are the per-platform tables of :mod:`sss_locus.experiments.survey_design`: the plans
table of :func:`~sss_locus.experiments.survey_design.front.search_plans` with a boolean
``recommended`` column, and the joint-adjustment summary of
:func:`~sss_locus.experiments.survey_design.scoring.summarise`. Every published table gives
headings as compass headings (:func:`with_compass`) and marks the recommended plan in its
``kind`` (``"search = recommended"``).
"""

from __future__ import annotations

import pandas as pd

from sss_locus.experiments.survey_design.front import by_crossing_angle
from sss_locus.experiments.survey_design.scoring import ERRORS, lower_end_cut
from sss_locus.report.common.text import fmt_ci_cells
from sss_locus.report.survey_design.prose import ERROR_LABELS, with_cut_note

#: Columns of the plans table (:func:`plans_table`) besides ``platform`` and ``kind``.
PLAN_COLUMNS = ["heading_deg", "spacing_m", "crossing_deg", "cross_spacing_m", "altitude_m", "total_m", "time_h",
                "covered_once", "covered_twice", "n_holes", "two_view_share", "three_view_share", "locus_median_m"]
#: Columns of the joint-adjustment table (:func:`noise_table`) besides its index.
NOISE_COLUMNS = (["total_m", "covered_twice", "n_seeds", "min_features", "mean_features"]
                 + [f"error_{e}{s}_m" for e in ERRORS for s in ("", "_lo", "_hi")])


def _marked(frame: pd.DataFrame, recommended) -> pd.DataFrame:
    """``frame`` with ``" = recommended"`` appended to ``kind`` where ``recommended`` (aligned on
    the index) is true."""
    flag = pd.Series(recommended, index=frame.index).astype(bool)
    return frame.assign(kind=frame["kind"].where(~flag, frame["kind"] + " = recommended"))


def all_plans(plans: dict) -> pd.DataFrame:
    """Every plan of every platform in one table, with compass headings: the data of the front
    figure.

    Parameters
    ----------
    plans : dict of str to pandas.DataFrame
        Per platform key, its plans table (any columns; ``heading_deg`` counter-clockwise from
        east, if present).

    Returns
    -------
    pandas.DataFrame
        The tables one after another with a ``platform`` column, ``heading_deg`` replaced by
        ``heading_compass_deg`` (:func:`with_compass`); empty for no platform.
    """
    if not plans:
        return pd.DataFrame()
    return with_compass(pd.concat([t.assign(platform=k) for k, t in plans.items()]))


def plans_table(plans: dict) -> pd.DataFrame:
    """The baselines and the recommended plan of each platform: the chapter's plans table.

    Parameters
    ----------
    plans : dict of str to pandas.DataFrame
        Per platform key, its plans table with ``kind`` (``"standard"``, ``"lawnmower"``,
        ``"search"``), a boolean ``recommended`` and the columns of :data:`PLAN_COLUMNS`
        (``total_m`` in m, ``heading_deg`` counter-clockwise from east).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``(platform, kind)``: every plan that is not a searched one, and the
        searched plans that are recommended (their kind ``"search = recommended"``; a baseline
        recommended is marked the same way). ``heading_deg`` becomes ``heading_compass_deg``
        (deg clockwise from north) and ``total_m`` becomes ``track_km`` (km).
    """
    rows = []
    for key, t in plans.items():
        keep = t[(t.kind != "search") | t.recommended]
        rows.append(_marked(keep[["kind"] + PLAN_COLUMNS], keep.recommended).assign(platform=key))
    picked = pd.concat(rows).set_index(["platform", "kind"])
    picked = picked.assign(total_m=picked.total_m / 1e3).rename(columns={"total_m": "track_km"})
    return with_compass(picked)


def noise_table(summary: dict, plans: dict) -> pd.DataFrame:
    """The plans scored with the joint adjustment, all their numbers: the data of the chapter's
    noise table (shown by :func:`noise_table_shown`).

    Parameters
    ----------
    summary : dict of str to pandas.DataFrame
        Per platform key, the joint-adjustment summary
        (:func:`~sss_locus.experiments.survey_design.scoring.summarise`): indexed by plan index
        of the plans table, with ``kind`` and the columns of :data:`NOISE_COLUMNS`.
    plans : dict of str to pandas.DataFrame
        Per platform key, its plans table with a boolean ``recommended``.

    Returns
    -------
    pandas.DataFrame
        Indexed by ``(platform, kind, plan_index)`` (the recommended plan's kind marked
        ``" = recommended"``), columns :data:`NOISE_COLUMNS`.
    """
    marked = [_marked(s, s.index.to_series().map(plans[k].recommended)).assign(platform=k)
              for k, s in summary.items()]
    return (pd.concat(marked).rename_axis("plan_index").reset_index()
            .set_index(["platform", "kind", "plan_index"])[NOISE_COLUMNS])


def crossing_table(plans: dict, objective: str) -> pd.DataFrame:
    """The searched eligible plans of every platform grouped by their second line set
    (:func:`~sss_locus.experiments.survey_design.front.by_crossing_angle`).

    Parameters
    ----------
    plans : dict of str to pandas.DataFrame
        Per platform key, its plans table.
    objective : str
        A key of :data:`~sss_locus.experiments.survey_design.front.OBJECTIVES`.

    Returns
    -------
    pandas.DataFrame
        Indexed by ``(platform, second_set)``; columns ``n_plans``, ``best``, ``median`` (of the
        objective) and ``best_pair_angle_median_deg``.
    """
    return (pd.concat([by_crossing_angle(t, objective).assign(platform=k) for k, t in plans.items()])
            .set_index(["platform", "second_set"]).drop(columns="crossing_deg"))


def with_compass(frame: pd.DataFrame) -> pd.DataFrame:
    """``frame`` with its ``heading_deg`` (degrees counter-clockwise from east, the computation's
    convention) replaced by ``heading_compass_deg``: degrees clockwise from north of the area's
    local frame (true north at its origin), as written in every published table.

    Parameters
    ----------
    frame : pandas.DataFrame
        A table, perhaps with ``heading_deg``.

    Returns
    -------
    pandas.DataFrame
        A copy with ``heading_compass_deg`` (0–360 deg) in its place, or ``frame`` itself
        without ``heading_deg``.
    """
    if "heading_deg" not in frame:
        return frame
    at = list(frame.columns).index("heading_deg")
    out = frame.drop(columns="heading_deg")
    out.insert(at, "heading_compass_deg", (90.0 - frame["heading_deg"].to_numpy(float)) % 360.0)
    return out


def noise_table_shown(frame: pd.DataFrame) -> pd.DataFrame:
    """The plans scored with the joint adjustment as a reader reads them: one row a plan, each
    error with its interval.

    Parameters
    ----------
    frame : pandas.DataFrame
        Indexed by ``(platform, kind, plan_index)``, with ``total_m``, ``covered_twice``,
        ``n_seeds``, ``min_features`` (the fewest features a seed's medians used) and, for each
        error of :data:`ERROR_LABELS`, ``error_<e>_m`` with its 95 % interval
        ``error_<e>_lo_m``/``error_<e>_hi_m`` (NaN where a seed had under 30 features).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``(platform, plan)``: ``plan`` is the kind, searched plans named by their
        number (``"search, plan 4"``: several searched plans of one platform are told apart);
        columns ``track_km``, ``covered_twice``, ``horizontal_error_m``, ``vertical_error_m``,
        ``map_shape_error_m`` (text: the mean over the seeds of the median error and its 95 %
        interval, saying where its lower end was cut at 0, or ``"—"`` under 30 features),
        ``seeds`` and ``fewest_features``.

    >>> f = pd.DataFrame({"total_m": [8000.0, 7000.0], "covered_twice": [1.0, 1.0], "n_seeds": [5, 5],
    ...     "min_features": [120, 12], "error_horizontal_m": [0.9, float("nan")],
    ...     "error_horizontal_lo_m": [0.6, float("nan")], "error_horizontal_hi_m": [1.2, float("nan")],
    ...     "error_vertical_m": [0.2, float("nan")], "error_vertical_lo_m": [0.1, float("nan")],
    ...     "error_vertical_hi_m": [0.3, float("nan")], "error_shape_m": [0.5, float("nan")],
    ...     "error_shape_lo_m": [0.4, float("nan")], "error_shape_hi_m": [0.6, float("nan")]},
    ...     index=pd.MultiIndex.from_tuples([("boat", "standard", 0), ("boat", "search", 4)],
    ...                                     names=["platform", "kind", "plan_index"]))
    >>> noise_table_shown(f).reset_index()[["plan", "horizontal_error_m", "fewest_features"]].values.tolist()
    [['standard', '0.90 (95 % CI 0.60–1.2)', 120], ['search, plan 4', '—', 12]]
    """
    rows = frame.reset_index()
    plan = rows["kind"].where(rows["kind"] != "search", "search, plan " + rows["plan_index"].astype(str))
    out = pd.DataFrame({"platform": rows["platform"], "plan": plan, "track_km": rows["total_m"] / 1e3,
                        "covered_twice": rows["covered_twice"]})
    for e, label in ERROR_LABELS.items():
        v, lo, hi = (rows[f"error_{e}{s}_m"].to_numpy(float) for s in ("", "_lo", "_hi"))
        out[f"{label.replace('-', '_')}_error_m"] = [
            with_cut_note(text, cut) for text, cut in zip(fmt_ci_cells(v, lo, hi), lower_end_cut(v, lo, hi))]
    out["seeds"] = rows["n_seeds"]
    out["fewest_features"] = rows["min_features"]
    return out.set_index(["platform", "plan"])
