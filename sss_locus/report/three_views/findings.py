"""Findings of the survey-pass and three-view chapters generated from a run's own numbers.

The counterpart of :mod:`sss_locus.report.pose_space.findings` for the chapters on passes: one
paragraph per platform (or per study platform), computed from the curves and tables the chapter
draws, for the cells tagged ``generated-findings``. Nothing here is typed for a particular platform.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_passes.planning import planning_bands
from sss_locus.experiments.datamodel.platforms import provenance_table
from sss_locus.experiments.three_views.patterns import cells_within, share_interval
from sss_locus.report.common.text import fmt_bands, fmt_change, fmt_percent, fmt_sig
from sss_locus.report.three_views.figures import share_text, sweep_texts

OBLIQUE_MAX_DEG = 45.0
"""A peak below this crossing angle counts as "at a moderate oblique angle" (the paper's shape)."""


def curve_shape(curve: pd.DataFrame, peak_deg: float, prefer_below: float, avoid_above: float,
                value: str = "locus_length_m") -> dict:
    """The shape of one median curve against crossing angle, as flags.

    Returns ``peak_deg``, ``where`` (``"oblique"`` below :data:`OBLIQUE_MAX_DEG`, ``"cross"`` up
    to 135°, ``"near-reciprocal"`` beyond), ``ends_preferred`` (both 0° and 180° in a prefer band
    of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`), ``ends_ratio`` (median at 180°
    over that at 0°) and ``bands`` (the bands).
    """
    bands = planning_bands(curve, value, prefer_below=prefer_below, avoid_above=avoid_above)
    c = curve.sort_values("crossing_angle_deg")
    g, m = c["crossing_angle_deg"].to_numpy(float), c[f"{value}_median"].to_numpy(float)
    pref = bands[bands["kind"] == "prefer"]

    def preferred(a: float) -> bool:
        return bool(((pref["lo_deg"] <= a + 1e-9) & (pref["hi_deg"] >= a - 1e-9)).any())

    where = "oblique" if peak_deg < OBLIQUE_MAX_DEG else "cross" if peak_deg <= 135.0 else "near-reciprocal"
    return {"peak_deg": float(peak_deg), "where": where, "bands": bands,
            "ends_preferred": preferred(g[0]) and preferred(g[-1]),
            "ends_ratio": float(m[-1] / m[0]) if m[0] > 0 else float("inf")}


_WHERE = {"oblique": "at a moderate oblique angle, the paper's shape",
          "cross": "near a cross-line, not at a moderate oblique angle",
          "near-reciprocal": "close to an anti-parallel pass"}


def curve_finding(cur, prefer_below: float, avoid_above: float) -> str:
    """The main curve of one platform (a
    :class:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve`) in words: where the median
    length peaks (with its bootstrap interval), its medians at 0°, 90° and 180°, the bands to
    prefer and to avoid, and whether repeat and anti-parallel passes are the shortest."""
    pk = cur.peak["locus_length_m"]
    s = curve_shape(cur.curve, pk["angle_deg"], prefer_below, avoid_above)
    at = {g: fmt_sig(cur.at(g)["median"], 2) for g in (0, 90, 180)}
    ends = ("repeat and anti-parallel passes both fall in the preferred bands (the shortest loci), "
            f"{'about equally short' if 0.8 <= s['ends_ratio'] <= 1.25 else 'though not equally short'} "
            f"(180° over 0°: {fmt_sig(s['ends_ratio'], 2)})" if s["ends_preferred"] else
            "repeat and anti-parallel passes are not both in the preferred bands")
    mis = cur.peak["elevation_misalignment_deg"]
    return (f"the median locus length is {at[0]} m at a repeat pass, peaks at γ = {pk['angle_deg']:.0f}° (95 % "
            f"bootstrap interval {pk['ci_low_deg']:.0f}–{pk['ci_high_deg']:.0f}°), {_WHERE[s['where']]}, is {at[90]} m "
            f"at 90° and {at[180]} m at 180°; {ends}. Prefer γ in {fmt_bands(s['bands'], 'prefer')}; avoid "
            f"{fmt_bands(s['bands'], 'avoid')}. The median elevation misalignment peaks at {mis['angle_deg']:.0f}°.")


def offset_models_finding(curves: Mapping[str, object]) -> str:
    """One platform's curves under several offset models (label -> curve): each peak angle, and
    which models give the paper's shape (a peak below :data:`OBLIQUE_MAX_DEG`)."""
    if not curves:
        raise ValueError("offset_models_finding needs at least one curve")
    peaks = {label: c.peak["locus_length_m"]["angle_deg"] for label, c in curves.items()}
    listed = "; ".join(f"{label}: {a:.0f}°" for label, a in peaks.items())
    oblique = [label for label, a in peaks.items() if a < OBLIQUE_MAX_DEG]
    said = (f"a peak at a moderate oblique angle (below {OBLIQUE_MAX_DEG:g}°) appears with "
            + ", ".join(oblique) if oblique else
            f"no offset model puts the peak below {OBLIQUE_MAX_DEG:g}°")
    return f"the median length peaks at {listed}; {said}."


def _effect(r) -> tuple[str, bool]:
    """A ratio row as change text and whether its interval excludes no change."""
    return fmt_change(r["ratio"], r["ratio_ci_low"], r["ratio_ci_high"]), not (r["ratio_ci_low"] <= 1 <= r["ratio_ci_high"])


def pitch_depth_finding(pitch: pd.DataFrame, depth: pd.DataFrame | None, n_both: int,
                        band: tuple[float, float]) -> str:
    """Nose-up against nose-down and the altitude effect inside a band, for the study platform.

    ``pitch``: ``n_both`` rows with both passes pitched, then the level-pass-1 rows turning to
    port and starboard; ``depth`` (or None to leave it out): one row per altitude, the first the reference (both with
    :func:`~sss_locus.experiments.survey_passes.planning.median_ratio` columns)."""
    both = [_effect(pitch.iloc[i]) for i in range(n_both)]
    clear = sum(flag for _, flag in both)
    said = ("at every level the interval includes 0 %" if not clear else
            f"at {clear} of {n_both} levels the interval excludes 0 %")
    text = (f"inside γ = {band[0]:.0f}–{band[1]:.0f}°, nose-up against nose-down with both passes pitched changes "
            f"the median length by {', '.join(t for t, _ in both)} ({said})")
    if len(pitch) >= n_both + 2:
        port, stbd = _effect(pitch.iloc[n_both]), _effect(pitch.iloc[n_both + 1])
        text += f"; with pass 1 level, by {port[0]} turning toward port and {stbd[0]} toward starboard"
    if depth is None:
        return text + "."
    hi, lo = depth.iloc[-1], depth.iloc[0]
    eff, sure = _effect(hi)
    norm = fmt_change(hi["norm_ratio"], hi["norm_ratio_ci_low"], hi["norm_ratio_ci_high"])
    return (text + f". Flying both passes at {hi['altitude (m)']:g} m instead of {lo['altitude (m)']:g} m above the "
            f"feature changes the median length by {eff}: {'a clear' if sure else 'no clear'} effect (per unit range "
            f"{norm}).")


def survey_summary(cur, prefer_below: float, avoid_above: float) -> str:
    """One sentence per platform for the survey chapter's summary."""
    pk = cur.peak["locus_length_m"]
    s = curve_shape(cur.curve, pk["angle_deg"], prefer_below, avoid_above)
    return (f"with the main offset model the median length peaks at {pk['angle_deg']:.0f}° "
            f"({_WHERE[s['where']]}); prefer {fmt_bands(s['bands'], 'prefer')}, avoid {fmt_bands(s['bands'], 'avoid')}.")


def closure_finding(summary: pd.DataFrame) -> str:
    """Three-view closure of one platform: per pattern the share resolved to one point and left
    two-fold ambiguous, the median plane angle and 95 % point error, and the best pattern.

    ``summary``: the chapter's table restricted to one platform (columns ``pattern``,
    ``resolved``, ``ambiguous``, ``none``, ``plane_angle_median_deg``, ``error_per_cm_median_m``,
    ``error_full_median_m``)."""
    if summary.empty:
        raise ValueError("closure_finding needs the rows of one platform")
    shares = "; ".join(f"{r.pattern}: {fmt_percent(r.resolved)} resolved, {fmt_percent(r.ambiguous)} ambiguous"
                       + (f", {fmt_percent(r.none)} with no candidate" if r.none > 0 else "")
                       for r in summary.itertuples())
    best = summary.loc[summary["error_per_cm_median_m"].idxmin()]
    worst = summary.loc[summary["error_per_cm_median_m"].idxmax()]
    return (f"{shares}. The best-conditioned pattern is {best.pattern} (median plane angle "
            f"{fmt_sig(best.plane_angle_median_deg, 2)}°, median 95 % point error {fmt_sig(best.error_per_cm_median_m, 2)} m "
            f"with the range error alone), the worst {worst.pattern} ({fmt_sig(worst.plane_angle_median_deg, 2)}°, "
            f"{fmt_sig(worst.error_per_cm_median_m, 2)} m); with the platform's full noise model the medians are "
            f"{fmt_sig(best.error_full_median_m, 2)} m and {fmt_sig(worst.error_full_median_m, 2)} m.")


def fan_top_clause(fan_deg: float, tilt_deg: float) -> str:
    """Where the top edge of a fan of full width ``fan_deg`` lies when its axis is tilted
    ``tilt_deg`` below the horizontal (a level platform).

    >>> fan_top_clause(50.0, 15.0), fan_top_clause(50.0, 25.0), fan_top_clause(50.0, 35.0)
    ('the fan reaches 10° above the horizontal', 'the top of the fan is horizontal', \
'the top of the fan is 10° below the horizontal')
    """
    top = fan_deg / 2 - tilt_deg
    if abs(top) < 1e-9:
        return "the top of the fan is horizontal"
    return f"the fan reaches {top:g}° above the horizontal" if top > 0 else \
        f"the top of the fan is {-top:g}° below the horizontal"


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


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
            + _and([f"{share_text(r.resolved, r.n)} ({r.pattern})" for r in first.itertuples()])
            + " of the configurations, a two-fold ambiguity remaining in "
            + _and([share_text(r.ambiguous, r.n) for r in first.itertuples()]))
    for tilt in tilts[1:]:
        g = rows[rows["tilt_deg"] == tilt]
        text += f"; at {tilt:g}° the shares resolved are " + _and([share_text(r.resolved, r.n) for r in g.itertuples()])
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
    or a sentence saying the table is empty."""
    if rows.empty:
        return "No platform of this run is a surface vessel: the tilt comparison is empty.\n"
    return "".join(f"- **{titles[k]}**: {tilt_finding(g, platforms[k])}\n"
                   for k, g in rows.groupby("platform", sort=False))


def pattern_ranking(summary: pd.DataFrame) -> str:
    """One platform's patterns from the smallest to the largest median 95 % point error with its
    full noise model (``pattern``, ``error_full_median_m``), and the share resolved of each."""
    s = summary.sort_values("error_full_median_m", kind="stable")
    return ("with the platform's full noise model the median 95 % point error is "
            + ", then ".join(f"{fmt_sig(r.error_full_median_m, 2)} m for {r.pattern}" for r in s.itertuples())
            + f"; the smallest share resolved is {fmt_percent(summary['resolved'].min())}.")


def skipped_study_note(study: str, capability: str, limits_deg: Mapping[str, float], need_deg: float) -> str:
    """Why a chapter's ``study`` is skipped: no platform of the run has ``capability``.

    ``limits_deg`` maps each platform's title to its pitch limit (degrees); ``need_deg`` is the
    largest magnitude the study asks for. One sentence for the chapter's page (MyST)."""
    have = "; ".join(f"{name}: ±{lim:g}°" for name, lim in limits_deg.items())
    return (f"The {study} is skipped in this run: it needs a platform that {capability} (a pitch envelope "
            f"and a limit of at least ±{need_deg:g}°), and no platform of this run does ({have}). "
            "Add one that pitches (e.g. `-p platforms '[..., \"auv\"]'`) to see it.")
