"""Verdicts of the survey-pass chapter about its locus-length curves, generated from a run's own
numbers.

One function per verdict (CONTRIBUTING.md, "One source per sentence"): it takes the curves and
tables the chapter draws and returns the paragraph for one platform (or for all platforms of the
run), the paper's platforms included; the chapter glues it into one untagged markdown cell.
Every qualitative word is computed from the numbers; nothing is typed for a particular platform.
The verdicts the claims page shows from computed flags are in :mod:`.findings`.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_passes.planning import planning_bands
from sss_locus.report.common.text import and_list, fmt_bands, fmt_change, fmt_sig
from sss_locus.report.survey_passes.figures import curve_texts


OBLIQUE_MAX_DEG = 45.0
"""A peak below this crossing angle counts as "at a moderate oblique angle" (the paper's shape)."""


def curve_shape(curve: pd.DataFrame, peak_deg: float, prefer_below: float, avoid_above: float,
                value: str = "locus_length_m") -> dict:
    """The shape of one median curve against crossing angle, as flags.

    Returns ``peak_deg``, ``where`` (``"oblique"`` below :data:`OBLIQUE_MAX_DEG`, ``"cross"`` up
    to 135°, ``"near-reciprocal"`` beyond), ``ends_preferred`` (both 0° and 180° in a prefer band
    of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`), ``ends_ratio`` (median at 180°
    over that at 0°) and ``bands`` (the bands).

    Parameters
    ----------
    curve : pandas.DataFrame
        A crossing-angle curve: ``crossing_angle_deg`` and ``<value>_median`` (and the quartiles
        :func:`~sss_locus.experiments.survey_passes.planning.planning_bands` reads).
    peak_deg : float
        The curve's peak angle (deg).
    prefer_below, avoid_above : float
        The planning bands' thresholds, as ``planning_bands`` takes them.
    value : str
        The quantity of the curve.

    Returns
    -------
    dict
        The flags named above.
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


PAPER_PEAK_DEG = 20.0
"""The paper's peak angle: locus length "peaks at a moderate oblique crossing angle of approximately
20°" (its abstract)."""


_WHERE = {"oblique": "at a moderate oblique angle, the paper's shape",
          "cross": "near a cross-line, not at a moderate oblique angle",
          "near-reciprocal": "close to an anti-parallel pass"}


def curve_finding(cur, prefer_below: float, avoid_above: float) -> str:
    """The main curve of one platform in words: the one source of this paragraph
    (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    cur : CrossingAngleCurve
        The platform's main curve (:class:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve`:
        ``curve``, ``peak``, ``at`` and ``acceptance``).
    prefer_below, avoid_above : float
        The band rule of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`.

    Returns
    -------
    str
        The median length at 0°, 90° and 180° with their intervals and its peak with the bootstrap
        interval, the shape's name from the peak (:data:`OBLIQUE_MAX_DEG`), whether repeat and
        anti-parallel passes both fall in the preferred bands and "about equally short" (180°
        over 0° within 0.8–1.25); the misalignment's rank correlation with the length, its peak and
        medians; the bands; and the share of drawn pass pairs rejected. Numbers formatted as the
        chapter's glued values (:func:`~sss_locus.report.survey_passes.figures.curve_texts`).
    """
    pk = cur.peak["locus_length_m"]
    s = curve_shape(cur.curve, pk["angle_deg"], prefer_below, avoid_above)
    t = curve_texts("", cur, over=False)
    ends = ("repeat and anti-parallel passes both fall in the preferred bands (the shortest loci), "
            f"{'about equally short' if 0.8 <= s['ends_ratio'] <= 1.25 else 'though not equally short'} "
            f"(180° over 0°: {fmt_sig(s['ends_ratio'], 2)})" if s["ends_preferred"] else
            "repeat and anti-parallel passes are not both in the preferred bands")
    return (f"the median locus length is {t['-len-0']} at a repeat pass, peaks at γ = {t['-len-peak-deg']}° (95 % "
            f"bootstrap interval {t['-len-peak-ci']}°), {_WHERE[s['where']]}, is {t['-len-90']} at 90° and "
            f"{t['-len-180']} at 180°; {ends}. Prefer γ in {fmt_bands(s['bands'], 'prefer')}; avoid "
            f"{fmt_bands(s['bands'], 'avoid')}. The median misalignment's rank correlation with the median length "
            f"over the grid is {t['-shape-rho']}; its largest median is at {t['-mis-peak-deg']}° (interval "
            f"{t['-mis-peak-ci']}°), its medians at 0°, 90° and 180° are {t['-mis-0']}, {t['-mis-90']} and "
            f"{t['-mis-180']}. Of all pass pairs drawn, {t['-rejected']} were rejected because a pass did not see "
            f"the feature (at most {t['-rejected-max']} at any one angle).")


def shorter_finding(curves: Mapping[str, object], titles: Mapping[str, str]) -> str:
    """Which platform's median locus is shorter, angle by angle, over the main curves.

    ``curves`` maps platform keys to main curves on one grid, ``titles`` the keys to names.
    Returns one sentence per consecutive pair of platforms ordered by their overall median
    (the number of crossing angles where the first one's median is the shorter), or ``""`` for
    a single platform.

    Parameters
    ----------
    curves : mapping of str to CrossingAngleCurve
        Platform key -> main curve (``curve`` with ``crossing_angle_deg`` and
        ``locus_length_m_median``, m).
    titles : mapping of str to str
        Platform key -> its name in the sentence.

    Returns
    -------
    str
        The sentence(s), or ``""``.
    """
    if len(curves) < 2:
        return ""
    med = {k: c.curve.sort_values("crossing_angle_deg")["locus_length_m_median"].to_numpy(float)
           for k, c in curves.items()}
    order = sorted(med, key=lambda k: float(np.median(med[k])))
    parts = []
    for a, b in zip(order, order[1:]):
        n, total = int(np.sum(med[a] < med[b])), len(med[a])
        parts.append(f"{titles[a]}'s median locus is shorter than {titles[b]}'s at "
                     + ("every crossing angle" if n == total else f"{n} of {total} crossing angles"))
    return "; ".join(parts) + "."


def _oblique(curves: Mapping[str, object]) -> list[str]:
    """The labels of the curves whose median length peaks below :data:`OBLIQUE_MAX_DEG`."""
    return [label for label, c in curves.items() if c.peak["locus_length_m"]["angle_deg"] < OBLIQUE_MAX_DEG]


def offset_models_finding(curves: Mapping[str, object]) -> str:
    """One platform's curves under several offset models in words: the one source of this
    paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    curves : mapping str -> CrossingAngleCurve
        Label -> curve (:class:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve`
        with its ``offset_model``), the main figure's first.

    Returns
    -------
    str
        Each peak angle of the median length with its bootstrap interval (and the misalignment's
        peak); those whose interval holds :data:`PAPER_PEAK_DEG`; the models whose peak
        lies at a moderate oblique angle (below :data:`OBLIQUE_MAX_DEG`), the paper's shape, or
        that none does; and, when every such model plans pass 2 on the same side as pass 1 and
        some model does not, that the paper's shape points to passes planned on the same side.
    """
    if not curves:
        raise ValueError("offset_models_finding needs at least one curve")

    def peak(c) -> str:
        p, q = c.peak["locus_length_m"], c.peak["elevation_misalignment_deg"]
        return (f"{p['angle_deg']:.0f}° ({p['ci_low_deg']:.0f}–{p['ci_high_deg']:.0f}°; misalignment "
                f"{q['angle_deg']:.0f}°)")
    listed = "; ".join(f"{label}: {peak(c)}" for label, c in curves.items())
    oblique = _oblique(curves)
    if not oblique:
        return (f"the median length peaks (95 % bootstrap interval) at {listed}; no offset model puts the peak "
                f"at a moderate oblique angle (below {OBLIQUE_MAX_DEG:g}°), the paper's shape.")
    sides = {label: c.offset_model.side_rule for label, c in curves.items()}
    text = (f"the median length peaks (95 % bootstrap interval) at {listed}; the paper's shape, a peak at a "
            f"moderate oblique angle (below {OBLIQUE_MAX_DEG:g}°), appears with " + and_list(oblique))
    near = [label for label in oblique if curves[label].peak["locus_length_m"]["ci_low_deg"] <= PAPER_PEAK_DEG
            <= curves[label].peak["locus_length_m"]["ci_high_deg"]]
    if near:
        text += f" ({and_list(near)}: an interval that holds the paper's ≈{PAPER_PEAK_DEG:g}°)"
    if len(oblique) < len(curves) and all(sides[label] == "same" for label in oblique):
        text += (", each with pass 2 planned on the same side of the vehicle as pass 1: the paper's curve points to "
                 "passes planned around the feature on the same side, a choice it does not state")
    return text + "."


def _effect(r) -> tuple[str, bool]:
    """A ratio row as change text and whether its interval excludes no change."""
    return fmt_change(r["ratio"], r["ratio_ci_low"], r["ratio_ci_high"]), not (r["ratio_ci_low"] <= 1 <= r["ratio_ci_high"])


def _sign(r) -> int:
    """+1 or -1 when the interval of a ratio row lies above or below 1, else 0."""
    return 1 if r["ratio_ci_low"] > 1 else -1 if r["ratio_ci_high"] < 1 else 0


def _levels_clause(pitch: pd.DataFrame, levels_deg) -> str:
    """Nose-up against nose-down with both passes pitched, per level, and what the symmetry says."""
    both = [_effect(pitch.iloc[i]) for i in range(len(levels_deg))]
    clear = sum(flag for _, flag in both)
    said = ("no clear effect at any level, as the mirror symmetry requires" if not clear else
            f"at {clear} of {len(both)} levels the interval excludes 0 %, though the mirror symmetry allows no effect "
            "(a 95 % interval misses the true value once in 20)")
    return ("with both passes pitched, nose-up against nose-down changes the median locus length by "
            + and_list([f"{t} at ±{p:g}°" for (t, _), p in zip(both, levels_deg)]) + f": {said}")


def _turn_clause(port, stbd) -> str:
    """Pass 1 level, pass 2 nose-up against nose-down turning to port and to starboard."""
    text = (f"with pass 1 level and the feature to its port, pitching pass 2 nose-up instead of nose-down "
            f"changes the median by {_effect(port)[0]} when pass 2 turns toward port and by {_effect(stbd)[0]} "
            "toward starboard")
    a, b = _sign(port), _sign(stbd)
    if a and b and a != b:
        return text + (": clear effects of opposite sign, set by the turn direction relative to the side the "
                       "feature is on, not by the pitch alone")
    if a and b:
        return text + ": clear effects of the same sign either way"
    return text + ": no clear effect turning toward " + and_list([s for s, f in (("port", a), ("starboard", b)) if not f])


def _depth_clause(depth: pd.DataFrame) -> str:
    """The highest altitude against the lowest, for the length and the length per unit range."""
    hi, lo = depth.iloc[-1], depth.iloc[0]
    eff, sure = _effect(hi)
    norm = {"ratio": hi["norm_ratio"], "ratio_ci_low": hi["norm_ratio_ci_low"], "ratio_ci_high": hi["norm_ratio_ci_high"]}
    way = {1: "lengthens", -1: "shortens"}.get(_sign(hi))
    text = (f"Flying both passes at {hi['altitude (m)']:g} m instead of {lo['altitude (m)']:g} m above the feature "
            f"changes the median length by {eff}, the length per unit range by {_effect(norm)[0]}")
    if not sure:
        return text + ": no clear effect."
    return (text + f": a clear effect, flying {'higher' if hi['altitude (m)'] > lo['altitude (m)'] else 'lower'} "
            f"{way} the locus" + (", and not merely by changing the range." if _sign(norm) else
                                  "; per unit range no clear change, so it is the change of range."))


def pitch_depth_finding(pitch: pd.DataFrame, depth: pd.DataFrame | None, levels_deg,
                        band: tuple[float, float]) -> str:
    """Nose-up against nose-down and the altitude effect inside a band, for the study platform:
    the one source of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    pitch : pandas.DataFrame
        One row per level of ``levels_deg`` with both passes pitched, optionally followed by the
        level-pass-1 rows turning to port and to starboard
        (:func:`~sss_locus.experiments.survey_passes.planning.median_ratio` columns: nose-up over
        nose-down).
    depth : pandas.DataFrame or None
        One row per altitude (``altitude (m)``), the first the reference, with ``median_ratio``
        columns for the length and ``norm_``-prefixed ones for the length per unit range; None
        leaves the altitude out.
    levels_deg : sequence of float
        The pitch magnitudes of the first rows of ``pitch`` (degrees).
    band : (float, float)
        The crossing-angle band the runs were made in (degrees).

    Returns
    -------
    str
        The effects with their 95 % intervals; "no clear effect at any level, as the mirror
        symmetry requires" only when every interval of the both-pitched rows includes 0 %;
        "opposite sign, set by the turn direction" only when the port and starboard intervals
        exclude 0 % on opposite sides; "a clear effect, flying higher shortens/lengthens the locus"
        and "not merely by changing the range" from the altitude rows' intervals.
    """
    text = f"inside γ = {band[0]:.0f}–{band[1]:.0f}°, {_levels_clause(pitch, levels_deg)}"
    n = len(levels_deg)
    if len(pitch) >= n + 2:
        text += ". W" + _turn_clause(pitch.iloc[n], pitch.iloc[n + 1])[1:]
    text += "."
    return text if depth is None else text + " " + _depth_clause(depth)


def survey_summary(cur, models: Mapping[str, object], prefer_below: float, avoid_above: float,
                   study: tuple[pd.DataFrame, pd.DataFrame] | None = None) -> str:
    """The survey chapter's summary for one platform: the one source of this paragraph
    (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    cur : CrossingAngleCurve
        The platform's main curve.
    models : mapping str -> CrossingAngleCurve
        Its curves under the other offset models (label -> curve).
    prefer_below, avoid_above : float
        The band rule of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`.
    study : (pitch, depth) or None
        For the pitch study's platform, its tables in the worst band (as :func:`pitch_depth_finding`,
        the last two ``pitch`` rows the level-pass-1 turns); None for any other platform.

    Returns
    -------
    str
        Where the main curve peaks and its shape's name, whether repeat and anti-parallel passes
        are the shortest, which offset models give the paper's oblique peak, the bands; for the
        study platform whether the sign of pitch changes anything when either side may see the
        feature and what flying higher does.
    """
    pk = cur.peak["locus_length_m"]
    s = curve_shape(cur.curve, pk["angle_deg"], prefer_below, avoid_above)
    oblique = _oblique(models)
    text = (f"with the main offset model the median length peaks at {pk['angle_deg']:.0f}° ({_WHERE[s['where']]}); "
            + ("repeat and anti-parallel passes give the shortest loci" if s["ends_preferred"] else
               "repeat and anti-parallel passes are not both among the shortest")
            + ". " + ("A peak at a moderate oblique angle appears with " + and_list(oblique)
                      + (", so the shape of the curve is set by an offset model the paper does not state"
                         if s["where"] != "oblique" else "") if oblique else
                      "No other offset model shown puts the peak at a moderate oblique angle")
            + f". Prefer {fmt_bands(s['bands'], 'prefer')}, avoid {fmt_bands(s['bands'], 'avoid')}.")
    if study is None:
        return text
    pitch, depth = study
    levels = [_sign(pitch.iloc[i]) for i in range(len(pitch) - 2)]
    hi, lo = depth.iloc[-1], depth.iloc[0]
    way = {1: "lengthens", -1: "shortens"}.get(_sign(hi), "does not clearly change")
    return text + (" Inside its worst band the sign of its pitch "
                   + ("changes nothing" if not any(levels) else "changes the median at some levels")
                   + f" when either side may see the feature, while flying {'higher' if hi['altitude (m)'] > lo['altitude (m)'] else 'lower'} "
                   f"above the feature {way} the locus ({_effect(hi)[0]}).")


def skipped_study_note(study: str, capability: str, limits_deg: Mapping[str, float], need_deg: float) -> str:
    """Why a chapter's ``study`` is skipped: no platform of the run has ``capability``.

    ``limits_deg`` maps each platform's title to its pitch limit (degrees); ``need_deg`` is the
    largest magnitude the study asks for. One sentence for the chapter's page (MyST).

    Parameters
    ----------
    study : str
        The study's name, in words.
    capability : str
        What a platform must do, in words (a relative clause: "can pitch").
    limits_deg : mapping of str to float
        Platform title -> its pitch limit (deg).
    need_deg : float
        The largest pitch the study asks for (deg).

    Returns
    -------
    str
        The sentence (MyST).
    """
    have = "; ".join(f"{name}: ±{lim:g}°" for name, lim in limits_deg.items())
    return (f"The {study} is skipped in this run: it needs a platform that {capability} (a pitch envelope "
            f"and a limit of at least ±{need_deg:g}°), and no platform of this run does ({have}). "
            "Add one that pitches (e.g. `-p platforms '[..., \"auv\"]'`) to see it.")
