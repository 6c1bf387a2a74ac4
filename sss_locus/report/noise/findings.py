"""Verdicts of the noise chapter, generated from a run's own numbers, for any platform.

One function per paragraph (CONTRIBUTING.md, "One source per sentence"): each turns the chapter's
curves (:func:`~sss_locus.experiments.survey_passes.planning.curve_summary` per noise model, keyed
by its label: the levels ``"×1"``, ``"×0.1"``, and ``"range only"``, ``"position only"``,
``"attitude only"``), its noise tables and its Monte Carlo check into text, the paper's AUV and
boat included. Every number and every qualitative word comes from the arguments.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from sss_locus.experiments.stats.replicates import median_with_interval
from sss_locus.experiments.survey_passes.planning import peak_angle, planning_bands
from sss_locus.experiments.survey_passes.verdicts import advice_verdict
from sss_locus.report.common.text import fmt_bands, fmt_interval, fmt_sig
from sss_locus.report.survey_passes.findings import verdict_word

ANGLES = (0.0, 90.0, 180.0)
"""The crossing angles quoted: a repeat pass, a cross-line and an anti-parallel pass (deg)."""
LINEAR_WITHIN = 0.10
"""A pass pair propagates its errors 'nearly linearly' where first order is within this fraction
of the Monte Carlo."""
FAIR_GUIDE = 0.20
"""First order is called a fair guide where its median relative difference from the Monte Carlo
is at most this fraction (the Monte Carlo's own sampling error of a 95 % quantile is of this order
at the quick profile's draws)."""


def _at(curve: pd.DataFrame, value: str, angle: float) -> dict[str, float]:
    row = curve.set_index("crossing_angle_deg").loc[angle]
    return {q: float(row[f"{value}_{q}"]) for q in ("median", "ci_low", "ci_high")}


def _three(curve: pd.DataFrame, value: str) -> str:
    a, b, c = (fmt_interval(_at(curve, value, g), "m") for g in ANGLES)
    return f"{a} at 0°, {b} at 90° and {c} at 180°"


def _overlap(a: Mapping[str, float], b: Mapping[str, float]) -> bool:
    return not (a["ci_high"] < b["ci_low"] or b["ci_high"] < a["ci_low"])


def answer_finding(curves: Mapping[str, pd.DataFrame], boot: Mapping[str, np.ndarray], table: pd.DataFrame,
                   head: str, oblique_band_deg: tuple[float, float] = (10.0, 40.0)) -> str:
    """The paper's crossing-angle advice at the headline noise for one platform, with the locus
    length, the band and the extent that decide it.

    Parameters
    ----------
    curves : mapping of str to pandas.DataFrame
        The platform's median curves by noise label (``head`` and ``"range only"`` at least), with
        ``locus_length_m``, ``band_width_m`` and ``extent_m`` medians and replicate-batch
        intervals at 0°, 90° and 180°.
    boot : mapping of str to numpy.ndarray
        Bootstrap medians of the headline curve (``extent_m``: shape (n_resamples, n_angles)).
    table : pandas.DataFrame
        The platform's noise table (``noise``, ``band_width_m``, ``locus_length_m`` per pass pair).
    head : str
        Label of the headline level.
    oblique_band_deg : (float, float)
        The band the paper says to avoid (deg).

    Returns
    -------
    str
        The verdict on the median extent (m) with the numbers it compares, the noise-free length
        and the band at 0°, 90° and 180° with their 95 % intervals, whether band or length sets
        the size, whether the band narrows toward 90° (and whether the intervals separate), where
        the extent is smallest and largest, and the bands to prefer and avoid by the planning rule.
    """
    c, lo, hi = curves[head], *oblique_band_deg
    v = advice_verdict(c, "extent_m", oblique_band_deg=oblique_band_deg)
    rows = table[table["noise"] == head]
    ratio = float(np.median(rows["band_width_m"] / rows["locus_length_m"]))
    text = (f"on the median extent (the diagonal of the region the feature lies in, m), the paper's advice "
            f"{'survives' if v['holds'] else 'does not survive'} noise {head}: the worse end (0° or 180°) "
            f"{fmt_sig(v['ends'], 2)} m against {fmt_sig(v['oblique'], 2)} m over {lo:g}°–{hi:g}° and "
            f"{fmt_sig(v['perpendicular'], 2)} m at 90°. Without noise the locus is {_three(c, 'locus_length_m')} "
            f"long; with noise the band it sweeps is {_three(c, 'band_width_m')} wide. The median pass pair's band "
            f"is {fmt_sig(ratio, 2)} times as wide as its locus is long, so "
            + ("the band, not the locus length, sets the size of the uncertainty. " if ratio > 1 else
               "the locus length, not the band, sets the size of the uncertainty. "))
    band = {g: _at(c, "band_width_m", g) for g in ANGLES}
    if band[90.0]["median"] < min(band[0.0]["median"], band[180.0]["median"]):
        apart = [f"{g:.0f}°" for g in (0.0, 180.0) if not _overlap(band[g], band[90.0])]
        text += ("Like classical stereo, the band is wider toward near-repeat (0°) and anti-parallel (180°) passes "
                 "than at a perpendicular crossing ("
                 + (f"intervals apart from 90° at {' and '.join(apart)}). " if apart else
                    "the intervals overlap, so the sampling does not separate them). "))
    else:
        text += "Unlike classical stereo, the band is not narrower at 90° than at both ends. "
    at = c.set_index("crossing_angle_deg")
    low = at["extent_m_median"].idxmin()
    peak = peak_angle(c, boot["extent_m"], "extent_m")
    bl, be = planning_bands(c, "locus_length_m"), planning_bands(c, "extent_m")
    return text + (f"The median extent is smallest at {low:.0f}°, {fmt_interval(_at(c, 'extent_m', low), 'm')}, and "
                   f"largest at {peak['angle_deg']:.0f}° (bootstrap 95 % interval of that angle "
                   f"{peak['ci_low_deg']:.0f}°–{peak['ci_high_deg']:.0f}°), against "
                   f"{fmt_interval(_at(c, 'extent_m', 0.0), 'm')} at 0° and "
                   f"{fmt_interval(_at(c, 'extent_m', 180.0), 'm')} at 180°. By the survey-planning chapter's band "
                   f"rule, without noise prefer {fmt_bands(bl, 'prefer')} and avoid {fmt_bands(bl, 'avoid')}; with "
                   f"noise {head} prefer {fmt_bands(be, 'prefer')} and avoid {fmt_bands(be, 'avoid')}.")


def range_floor_finding(curves: Mapping[str, pd.DataFrame], head: str, levels: Sequence[str]) -> str:
    """The extent with range errors alone, against the noise-free locus, and at the other levels.

    Parameters
    ----------
    curves : mapping of str to pandas.DataFrame
        As for :func:`answer_finding` (``"range only"`` and each of ``levels``).
    head : str
        Label of the headline level (its noise-free length is compared).
    levels : sequence of str
        Labels of the other levels quoted (may be empty).

    Returns
    -------
    str
        The range-only extent at 0°, 90° and 180° with intervals, how many times the noise-free
        length it is there, and the extent at each other level.
    """
    ratios = [_at(curves["range only"], "extent_m", g)["median"] / _at(curves[head], "locus_length_m", g)["median"]
              for g in ANGLES]
    text = (f"range errors alone, with exactly known poses, give an extent of {_three(curves['range only'], 'extent_m')}: "
            f"{fmt_sig(min(ratios), 2)}–{fmt_sig(max(ratios), 2)} times the noise-free locus length there "
            f"(larger at {sum(r > 1 for r in ratios)} of the 3 angles).")
    for label in levels:
        text += f" With every standard deviation {label} the extent is {_three(curves[label], 'extent_m')}."
    return text


def crop_finding(table: pd.DataFrame, head: str, levels: Sequence[str], beam_deg: float, model) -> str:
    """How often the noisy crop leaves the computed locus empty, and what attitude errors do.

    Parameters
    ----------
    table : pandas.DataFrame
        The platform's noise table (``noise``, ``empty_fraction`` per pass pair).
    head : str
        Label of the headline level.
    levels : sequence of str
        Labels of the other levels.
    beam_deg : float
        The sonar's thin beam width, along-track (``Sonar.elevation_deg``), degrees.
    model : NoiseModel
        The platform's noise model at the headline level (its attitude standard deviations, deg).

    Returns
    -------
    str
        The mean share of empty loci at each level and with attitude errors alone, the beam's
        thickness against the attitude standard deviations, and whether the beams must be widened.
    """
    def share(label):
        return f"{100 * float(table.loc[table['noise'] == label, 'empty_fraction'].mean()):.0f} %"
    att = float(table.loc[table["noise"] == "attitude only", "empty_fraction"].mean())
    largest = max(model.roll_sigma_deg, model.pitch_sigma_deg, model.heading_sigma_deg)
    text = (f"averaged over all pass pairs, {share(head)} of the noisy draws give an *empty* computed locus at "
            f"noise {head}" + "".join(f" ({share(lab)} at {lab})" for lab in levels)
            + f"; attitude errors alone empty {share('attitude only')} of them. The beams are {fmt_sig(beam_deg, 2)}° "
            f"thick along-track, against attitude standard deviations of {fmt_sig(model.roll_sigma_deg, 2)}° (roll), "
            f"{fmt_sig(model.pitch_sigma_deg, 2)}° (pitch) and {fmt_sig(model.heading_sigma_deg, 2)}° (heading), the "
            f"largest {fmt_sig(largest / beam_deg, 2)} times that thickness")
    if att > 0:
        return text + (": errors of that order move the estimated beams off the circle, so a practical use of the "
                       "locus has to widen the beams by the attitude uncertainty, which lengthens the locus.")
    return text + ": attitude errors alone never empty the locus here."


def _dominant(curves: Mapping[str, pd.DataFrame]) -> tuple[pd.Series, pd.Series, int, str]:
    pos = curves["position only"].set_index("crossing_angle_deg")["band_width_m_median"]
    rng = curves["range only"].set_index("crossing_angle_deg")["band_width_m_median"]
    more = int((pos > rng).sum())
    return pos, rng, more, "sensor-position" if more > len(pos) / 2 else "range"


def breakdown_finding(curves: Mapping[str, pd.DataFrame], head: str) -> str:
    """Which error group sets the band: sensor position against range, angle by angle.

    Parameters
    ----------
    curves : mapping of str to pandas.DataFrame
        As for :func:`answer_finding` (``head``, ``"position only"`` and ``"range only"``).
    head : str
        Label of the headline level.

    Returns
    -------
    str
        At how many grid angles the position-only band exceeds the range-only band, the three
        bands at 90°, the range-only floor over the angles, and which groups widen toward both
        ends.
    """
    pos, rng, more, who = _dominant(curves)
    text = (f"{who} errors dominate the band at noise {head}: the position-only band is wider than the range-only "
            f"band at {more} of {len(pos)} crossing angles (at 90°: {fmt_interval(_at(curves['position only'], 'band_width_m', 90.0), 'm')} "
            f"against {fmt_interval(_at(curves['range only'], 'band_width_m', 90.0), 'm')}; all errors "
            f"{fmt_interval(_at(curves[head], 'band_width_m', 90.0), 'm')}). Range errors alone set a floor of "
            f"{fmt_sig(rng.min(), 2)}–{fmt_sig(rng.max(), 2)} m (median band over the angles) that no navigation "
            "upgrade removes.")
    grow = [name for name, s in (("position", pos), ("range", rng)) if s.at[90.0] < min(s.at[0.0], s.at[180.0])]
    if len(grow) == 2:
        return text + " Both grow toward near-repeat and anti-parallel passes (wider at 0° and 180° than at 90°)."
    if grow:
        return text + f" Only the {grow[0]}-only band is wider at 0° and 180° than at 90°."
    return text + " Neither is wider at both 0° and 180° than at 90°."


def guide_sentence(check: pd.DataFrame, head_scale: float) -> str:
    """Whether first-order propagation is a fair guide (:data:`FAIR_GUIDE`) at the headline noise,
    for the band and for the three-view point.

    Parameters
    ----------
    check : pandas.DataFrame
        As for :func:`check_finding`.
    head_scale : float
        The headline level.

    Returns
    -------
    str
        "first order is a fair guide for the band but not for the three-view point", or the
        combination the medians give.
    """
    at = check[np.isclose(check["scale"], head_scale)]
    fair = [float(at.loc[at["kind"] == k, "rel_diff"].abs().median()) <= FAIR_GUIDE for k in ("two", "three")]
    if fair[0] == fair[1]:
        return f"first order is {'a fair guide' if fair[0] else 'not a fair guide'} for both the band and the three-view point"
    return ("first order is a fair guide for the band but not for the three-view point" if fair[0] else
            "first order is a fair guide for the three-view point but not for the band")


def check_finding(check: pd.DataFrame, lost: Mapping[str, float], names: Mapping[str, str],
                  small: float, head_scale: float) -> str:
    """Monte Carlo against first order, for the band and the three-view point.

    Parameters
    ----------
    check : pandas.DataFrame
        One row per pass pair or configuration: ``platform``, ``kind`` (``"two"`` or
        ``"three"``), ``scale``, ``monte_carlo_m`` and ``rel_diff`` (first order over Monte Carlo
        minus 1).
    lost : mapping of str to float
        Platform key -> share of noisy three-view draws with no candidate (real apertures).
    names : mapping of str to str
        Platform key -> the name to print.
    small, head_scale : float
        The small and the headline level (multiples of the noise model).

    Returns
    -------
    str
        The largest relative difference at the small level, the median and largest at the
        headline, the share of pass pairs within :data:`LINEAR_WITHIN`, whether first order is a
        fair guide (:data:`FAIR_GUIDE`) for each, and per platform the Monte Carlo median of the
        three-view point's 95 % error and the share of draws it is lost.
    """
    def rel(kind, scale):
        return check.loc[(check["kind"] == kind) & np.isclose(check["scale"], scale), "rel_diff"].abs()
    two, three = rel("two", head_scale), rel("three", head_scale)
    text = (f"At {100 * small:g} % of the headline noise the two estimates agree to within "
            f"{100 * rel('two', small).max():.1f} % for the band and {100 * rel('three', small).max():.1f} % for "
            "the three-view point (largest relative difference, which includes the Monte Carlo sampling error "
            f"of a 95 % quantile). At the headline noise the median relative difference is {100 * two.median():.0f} % "
            f"for the band (largest {100 * two.max():.0f} %; {100 * float((two <= LINEAR_WITHIN).mean()):.0f} % of the "
            f"pass pairs within {100 * LINEAR_WITHIN:.0f} %) and {100 * three.median():.0f} % for the point (largest "
            f"{100 * three.max():.0f} %). So {guide_sentence(check, head_scale)} (fair: a median within "
            f"{100 * FAIR_GUIDE:.0f} %)"
            + ("; at the headline noise the first-order figures of the three-views chapter are indications of "
               "conditioning, not error predictions" if three.median() > FAIR_GUIDE else "")
            + ". The curves above are Monte Carlo throughout. By Monte Carlo, the median 95 % error of the "
            "three-view point of the cross-line pattern at the headline noise is ")
    parts = []
    for key, name in names.items():
        mc = check.loc[(check["kind"] == "three") & np.isclose(check["scale"], head_scale)
                       & (check["platform"] == key), "monte_carlo_m"].to_numpy()
        est = dict(zip(("median", "ci_low", "ci_high"), median_with_interval(mc)))
        parts.append(f"{fmt_interval(est, 'm')} for the {name}, whose noisy three-view solution with the real "
                     f"apertures keeps no candidate in {100 * lost[key]:.0f} % of the draws")
    return text + "; ".join(parts) + " (the same crop failure as for two views)."


def offset_models_finding(verdicts: Mapping[tuple[str, str, float], Mapping[str, float]], key: str,
                          model_labels: Mapping[str, str],
                          oblique_band_deg: tuple[float, float] = (10.0, 40.0)) -> str:
    """The advice test on the pass pairs of the offset models other than ``independent``, for one
    platform at every level.

    Parameters
    ----------
    verdicts : mapping (platform key, offset-model spec, noise scale) -> dict
        :func:`~sss_locus.experiments.survey_passes.verdicts.advice_verdict` on the median extent.
    key : str
        The platform.
    model_labels : mapping spec -> str
        Display label of each offset model.
    oblique_band_deg : (float, float)
        The oblique band the verdicts were computed with (deg).

    Returns
    -------
    str
        Per model and level: holds or fails, with the median extents at the worse end, over the
        oblique band and at 90° (m); or that no other model was run.
    """
    parts = []
    for spec in dict.fromkeys(s for k, s, _ in verdicts if k == key and s != "independent"):
        levels = [(scale, v) for (k, s, scale), v in verdicts.items() if k == key and s == spec]
        said = [f"at ×{scale:g} the advice {'holds' if v['holds'] else 'fails'} (median extent: worse end "
                f"{fmt_sig(v['ends'], 2)} m, {oblique_band_deg[0]:g}°–{oblique_band_deg[1]:g}° {fmt_sig(v['oblique'], 2)} m, 90° "
                f"{fmt_sig(v['perpendicular'], 2)} m)" for scale, v in levels]
        parts.append(f"with offsets {model_labels[spec]} (`{spec}`), " + "; ".join(said))
    return ("; ".join(parts) + ".") if parts else "no other offset model was run (`other_offset_models` is empty)."


def summary_finding(curves: Mapping[str, pd.DataFrame], table: pd.DataFrame, head: str,
                    oblique_band_deg: tuple[float, float] = (10.0, 40.0)) -> str:
    """The chapter's summary for one platform: the verdict, where the extent is smallest, band
    against length, which error group dominates and how often attitude errors empty the locus.

    Parameters
    ----------
    curves, table, head, oblique_band_deg
        As for :func:`answer_finding`.

    Returns
    -------
    str
        One paragraph.
    """
    c = curves[head]
    v = advice_verdict(c, "extent_m", oblique_band_deg=oblique_band_deg)
    rows = table[table["noise"] == head]
    ratio = float(np.median(rows["band_width_m"] / rows["locus_length_m"]))
    low = c.set_index("crossing_angle_deg")["extent_m_median"].idxmin()
    att = float(table.loc[table["noise"] == "attitude only", "empty_fraction"].mean())
    dominant = _dominant(curves)[3]
    return (f"the paper's advice {'survives' if v['holds'] else 'does not survive'} (median extent smallest at "
            f"{low:.0f}°); the band is {fmt_sig(ratio, 2)} times the locus length, so "
            + ("the band sets the size of a fix" if ratio > 1 else "the locus length sets the size of a fix")
            + f"; {dominant} errors dominate the band; attitude errors alone leave the computed locus empty in "
            f"{100 * att:.0f} % of the draws.")


NOISE_WORDS = ("Survives", "Survives in part", "Does not survive")
"""Verdict words of the paper's advice with noise (beyond the paper: it has no noise claim)."""


def noise_advice_findings(prefix: str, verdicts: Mapping[tuple[str, str, float], Mapping[str, float]],
                          model_labels: Mapping[str, str], empty_share: Mapping[str, float],
                          oblique_band_deg: tuple[float, float] = (10.0, 40.0)) -> dict[str, str]:
    """The paper's crossing-angle advice with measurement noise, from computed flags, with the
    conditions under which it was tested.

    Parameters
    ----------
    prefix : str
        Start of both glue keys.
    verdicts : mapping (platform key, offset-model spec, noise scale) -> dict
        :func:`~sss_locus.experiments.survey_passes.verdicts.advice_verdict` on the median extent (its
        ``holds`` flag decides).
    model_labels : mapping spec -> str
        Display label of each offset model.
    empty_share : mapping platform key -> float
        Mean share of noisy draws with an empty computed locus at the headline level.
    oblique_band_deg : (float, float)
        The oblique band (deg) the ends are compared with, as the verdicts were computed.

    Returns
    -------
    dict of str
        ``<prefix>-advice-finding`` (the sentence) and ``<prefix>-advice-finding-verdict``
        (:data:`NOISE_WORDS` of the same flags).
    """
    if not verdicts:
        raise ValueError("noise_advice_findings needs at least one verdict")
    groups: dict[tuple[str, float], dict[bool, list[str]]] = {}
    for (key, spec, scale), v in verdicts.items():
        groups.setdefault((spec, scale), {True: [], False: []})[bool(v["holds"])].append(key)
    clauses = []
    for (spec, scale), by in groups.items():
        said = [f"{word} for {' and '.join(by[flag])}" for flag, word in ((True, "holds"), (False, "fails")) if by[flag]]
        clauses.append(f"offsets {model_labels[spec]}, every standard deviation ×{scale:g}: {', '.join(said)}")
    flags = [bool(v["holds"]) for v in verdicts.values()]
    lo, hi = oblique_band_deg
    empty = " / ".join(f"{100 * e:.0f} % ({k})" for k, e in empty_share.items())
    out = {f"{prefix}-advice-finding-verdict": verdict_word(flags, NOISE_WORDS)}
    out[f"{prefix}-advice-finding"] = (
        f"Tested on the median extent (the worse end, 0° or 180°, no worse than the median over {lo:g}°–{hi:g}° "
        f"and than 90°), the advice holds in {sum(flags)} of {len(flags)} cases: {'; '.join(clauses)}. "
        f"Conditions: errors independent between the two passes (errors common "
        f"to both would cancel and are left out); each level multiplies every standard deviation of "
        f"the platform's noise model at once, the range error as well as position and attitude; and the extent "
        f"combines the band width with the noise-free locus length, while the locus computed from the noisy "
        f"measurements is empty in {empty} of the draws at the headline level.")
    return out
