"""Verdicts of the three-view chapter, generated from a run's own numbers (the survey-pass
chapter's are in :mod:`sss_locus.report.survey_passes.curve_findings`).

One function per verdict (CONTRIBUTING.md, "One source per sentence"): it takes the curves and
tables the chapter draws and returns the paragraph for one platform (or for all platforms of the
run), the paper's platforms included; the chapter glues it into one untagged markdown cell.
Every qualitative word is computed from the numbers; nothing is typed for a particular platform.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.platforms import provenance_table
from sss_locus.experiments.three_views.patterns import cells_within, share_interval
from sss_locus.report.common.text import and_list, fmt_interval, fmt_sig
from sss_locus.report.three_views.figures import share_text, sweep_texts


def closure_finding(summary: pd.DataFrame, intervals: Mapping[str, Mapping[str, Mapping[str, float]]]) -> str:
    """Three-view closure of one platform in words: the one source of this paragraph
    (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    summary : pandas.DataFrame
        The chapter's table restricted to one platform: ``pattern``, ``n``, the shares
        ``resolved``, ``ambiguous``, ``none``, ``ambiguous_no_elevation`` and
        ``ambiguous_no_azimuth`` (left ambiguous with the elevation bound, or the azimuth and
        range bounds, lifted), ``error_per_cm_median_m`` and ``error_full_median_m``.
    intervals : mapping pattern -> mapping column -> estimate
        :func:`~sss_locus.experiments.three_views.patterns.median_intervals` of each pattern's
        ``plane_angle_deg``, ``point_error_q95_m`` and ``r1_m``.

    Returns
    -------
    str
        Per pattern the shares resolved and left ambiguous (as
        :func:`~sss_locus.report.three_views.figures.share_text`, the chapter's glued values), the
        shares with each bound lifted and which bound rejects the mirror candidate (the one whose
        lifting leaves more configurations ambiguous), the median plane angles, point errors and
        ranges with their intervals, and the best- and worst-conditioned patterns by the median
        point error.
    """
    if summary.empty:
        raise ValueError("closure_finding needs the rows of one platform")
    rows = list(summary.itertuples())

    def each(col: str, fmt=None) -> str:
        return and_list([(fmt or (lambda r: share_text(getattr(r, col), r.n)))(r) for r in rows])

    def med(col: str, unit: str) -> str:
        return and_list([fmt_interval(intervals[r.pattern][col], unit) for r in rows])
    el, az = summary["ambiguous_no_elevation"].sum(), summary["ambiguous_no_azimuth"].sum()
    bound = ("the elevation bound" if el > az else "the azimuth and range bounds" if az > el else
             "either bound alike")
    best = summary.loc[summary["error_per_cm_median_m"].idxmin()]
    worst = summary.loc[summary["error_per_cm_median_m"].idxmax()]
    text = ("resolved to one point in " + and_list([f"{share_text(r.resolved, r.n)} ({r.pattern})" for r in rows])
            + " of the configurations, a two-fold ambiguity remaining in " + each("ambiguous")
            + ("" if not (summary["none"] > 0).any() else ", none left in " + each("none"))
            + ". With the elevation bound of every aperture lifted, " + each("ambiguous_no_elevation")
            + " would be left ambiguous; with the azimuth and range bounds lifted instead, " + each("ambiguous_no_azimuth")
            + f": {bound} reject{'s' if bound == 'the elevation bound' else ''} the mirror candidate. "
            + "The median angle between the two planes is " + med("plane_angle_deg", "°")
            + "; the range error gives a median 95 % point error of " + med("point_error_q95_m", "m")
            + " (median ranges " + med("r1_m", "m") + "). ")
    return (text + f"The best-conditioned pattern is {best.pattern}, the worst {worst.pattern} (median point error "
            f"{fmt_sig(worst.error_per_cm_median_m / best.error_per_cm_median_m, 2)} times the best's); with the "
            f"platform's full noise model the medians are {fmt_sig(best.error_full_median_m, 2)} m and "
            f"{fmt_sig(worst.error_full_median_m, 2)} m.")


def fan_top_clause(fan_deg: float, tilt_deg: float) -> str:
    """Where the top edge of a fan of full width ``fan_deg`` lies when its axis is tilted
    ``tilt_deg`` below the horizontal (a level platform).

    Parameters
    ----------
    fan_deg : float
        Full vertical width of the fan (deg).
    tilt_deg : float
        Tilt of its axis below the horizontal (deg).

    Returns
    -------
    str
        The clause, angles in degrees.

    Examples
    --------
    >>> fan_top_clause(50.0, 15.0), fan_top_clause(50.0, 25.0), fan_top_clause(50.0, 35.0)
    ('the fan reaches 10° above the horizontal', 'the top of the fan is horizontal', \
'the top of the fan is 10° below the horizontal')
    """
    top = fan_deg / 2 - tilt_deg
    if abs(top) < 1e-9:
        return "the top of the fan is horizontal"
    return f"the fan reaches {top:g}° above the horizontal" if top > 0 else \
        f"the top of the fan is {-top:g}° below the horizontal"


def tilt_finding(rows: pd.DataFrame, platform) -> str:
    """The three-view tilt check of one surface platform in words, for any platform (the paper's
    boat included): the one source of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    rows : pandas.DataFrame
        The chapter's tilt table restricted to the platform: ``tilt_deg``, ``pattern``, ``n``,
        ``resolved`` and ``ambiguous`` (shares of ``n`` configurations).
    platform : sss_locus.experiments.datamodel.platforms.Platform
        The platform: its fan (``sonar.azimuth_deg``), its port transducer's tilt in the data,
        and whether that tilt is an assumption (its data note).

    Returns
    -------
    str
        The first tilt with the fan's top edge, the shares resolved and left two-fold ambiguous
        per pattern; the shares resolved at every further tilt; and, when a pattern's resolved
        share changes between two tilts beyond both exact 95 % intervals, that the resolution at
        the data's tilt rests on where the top of the fan lies (", an assumed value" when the
        data mark the tilt as an assumption). Shares as
        :func:`~sss_locus.report.three_views.figures.share_text` (the chapter's glued values).
    """
    tilts = sorted(rows["tilt_deg"].unique())
    first = rows[rows["tilt_deg"] == tilts[0]]
    text = (f"With its transducers tilted {tilts[0]:g}° {fan_top_clause(platform.sonar.azimuth_deg, tilts[0])}: "
            "the feature is resolved in "
            + and_list([f"{share_text(r.resolved, r.n)} ({r.pattern})" for r in first.itertuples()])
            + " of the configurations, a two-fold ambiguity remaining in "
            + and_list([share_text(r.ambiguous, r.n) for r in first.itertuples()]))
    for tilt in tilts[1:]:
        g = rows[rows["tilt_deg"] == tilt]
        text += f"; at {tilt:g}° the shares resolved are " + and_list([share_text(r.resolved, r.n) for r in g.itertuples()])
    text += "."
    intervals = {(r.pattern, r.tilt_deg): share_interval(int(round(r.resolved * r.n)), int(r.n))
                 for r in rows.itertuples()}
    changes = any(intervals[(p, a)][1] < intervals[(p, b)][0] or intervals[(p, b)][1] < intervals[(p, a)][0]
                  for p in rows["pattern"].unique() for a in tilts for b in tilts if a < b)
    if changes:
        data_tilt = platform.transducers["port"].tilt_deg
        notes = provenance_table(platform).set_index("key")["kind"]
        assumed = notes.get(f"platforms.{platform.key}.transducers.port.tilt_deg") == "assumption"
        text += (f" Its resolution at {data_tilt:g}° therefore rests on where the top of its fan lies"
                 + (", an assumed value." if assumed else "."))
    return text


def sweep_finding(sweep: pd.DataFrame) -> str:
    """The heading sweep of one platform in words, for any platform (the paper's included): the
    one source of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    sweep : pandas.DataFrame
        A heading sweep with noise (:func:`~sss_locus.experiments.three_views.patterns.heading_sweep`):
        ``heading2_deg``, ``heading3_deg``, ``point_error_q95_median_m`` with its interval columns,
        ``resolved_fraction`` and ``n``.

    Returns
    -------
    str
        The worst and best cells (those the sampling cannot tell from the largest and smallest
        median 95 % point error, :func:`~sss_locus.report.three_views.figures.sweep_texts`) with their
        medians; "the corners, where all three headings are equal or reciprocal" only when every
        worst cell is one; "a flat optimum" when several cells share the best; whether the rest
        of the diagonal (passes 2 and 3 parallel) is degenerate, by its largest median against
        the worst cell's interval; the largest median with the headings spread out; and the
        share resolved with the one-sided bound of the share unresolved.
    """
    t = sweep_texts(sweep)
    v = "point_error_q95_median_m"
    worst, best = cells_within(sweep, "max"), cells_within(sweep, "min")
    corners = bool(np.all(np.isclose(np.mod(worst.heading2_deg, 180.0), 0.0)
                          & np.isclose(np.mod(worst.heading3_deg, 180.0), 0.0)))
    h2, h3 = sweep.heading2_deg, sweep.heading3_deg
    diagonal = sweep[np.isclose(h2, h3) & ~np.isclose(np.mod(h2, 180.0), 0.0)]
    top = sweep.loc[sweep[v].idxmax()]
    text = ("The worst cells are " + ("the corners, where all three headings are equal or reciprocal: " if corners
                                       else "")
            + f"{t['worst']} (median up to {t['worst-err']}). The best cells, read the same way, are {t['best']} "
            f"(down to {t['best-err']})"
            + (": a flat optimum, not one best pair of headings." if len(best) > 1 else ": one best pair of headings."))
    if len(diagonal):
        degenerate = diagonal[v].max() >= top[v[:-2] + "_ci_low_m"]
        text += (" The rest of the diagonal ($h_2 = h_3$: passes 2 and 3 parallel, both crossing pass 1) is "
                 + ("as degenerate as the worst cells" if degenerate else "not degenerate")
                 + f": its largest median error is {t['parallel-err']}.")
    if t["spread-err"] != "n/a":
        text += (" With the three headings spread out (pass 2 and pass 3 each at least 45° from pass 1 and from "
                 f"each other, within 45–135°) the largest median error is {t['spread-err']}.")
    return (text + f" Over all cells {t['resolved']} of the configurations are resolved; the share left "
            f"unresolved is at most {t['unresolved-upper']} (one-sided exact 95 % bound).")


def tilt_markdown(rows: pd.DataFrame, platforms: Mapping[str, object], titles: Mapping[str, str]) -> str:
    """:func:`tilt_finding` of every platform in the tilt table ``rows`` (column ``platform``;
    ``platforms`` maps its keys to the platforms), titled by ``titles`` (platform key -> title),
    or a sentence saying the table is empty.

    Parameters
    ----------
    rows : pandas.DataFrame
        The tilt table (a ``platform`` column and :func:`tilt_finding`'s columns).
    platforms : mapping of str to Platform
        Platform key -> platform.
    titles : mapping of str to str
        Platform key -> title.

    Returns
    -------
    str
        A Markdown list, one item per platform, or the sentence for an empty table.
    """
    if rows.empty:
        return "No platform of this run is a surface vessel: the tilt comparison is empty.\n"
    return "".join(f"- **{titles[k]}**: {tilt_finding(g, platforms[k])}\n"
                   for k, g in rows.groupby("platform", sort=False))


def pattern_ranking(summary: pd.DataFrame) -> str:
    """One platform's patterns from the smallest to the largest median 95 % point error with its
    full noise model (``pattern``, ``error_full_median_m``), and the smallest share resolved
    (``resolved`` of ``n``, as :func:`~sss_locus.report.three_views.figures.share_text`): the one
    source of the chapter's planning advice (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    summary : pandas.DataFrame
        One row per pattern: ``pattern``, ``error_full_median_m`` (m), ``resolved`` (share 0–1),
        ``n``.

    Returns
    -------
    str
        The paragraph, errors in m.
    """
    s = summary.sort_values("error_full_median_m", kind="stable")
    low = summary.loc[summary["resolved"].idxmin()]
    return ("with the platform's full noise model the median 95 % point error is "
            + ", then ".join(f"{fmt_sig(r.error_full_median_m, 2)} m for {r.pattern}" for r in s.itertuples())
            + f": {s.iloc[0].pattern} is the best-conditioned choice and {s.iloc[-1].pattern} the worst. Whatever the "
            f"pattern, the third pass resolves the feature in at least {share_text(low.resolved, low.n)} of the "
            "configurations.")


