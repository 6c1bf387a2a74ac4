"""The survey-design chapter's prose (``notebooks/survey_design.ipynb``): the captions of its
tables, of the Pareto front and of the recommended plans' maps, the plans in words, the
verdict of the joint adjustment under noise, and the sentences it glues about the standard plan,
the features' best pairs and the solver's path, so the notebook's cells stay short.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_design.coverage import reach_limits_m
from sss_locus.experiments.survey_design.scoring import MIN_FEATURES, lower_end_cut
from sss_locus.report.common.text import count_noun, fmt_ci, fmt_percent, fmt_sig
from sss_locus.report.survey_design.figures import OBJECTIVE_LABELS


def area_note(area, seafloor: str, n_features: int, seed: int) -> str:
    """The sentence every table caption ends with: the area file and its SHA-256, the seafloor,
    the features and the seed.

    Parameters
    ----------
    area : sss_locus.experiments.survey_design.area.SurveyArea
        The survey area (its ``source`` and ``sha256`` are written).
    seafloor : str
        The seafloor model's name, or ``"measured (bathymetry grid)"``.
    n_features : int
        Features per plan.
    seed : int
        The search's random seed.

    Returns
    -------
    str
        E.g. ``"Area file data/examples/survey_area.toml (SHA-256 0123456789ab), flat seafloor,
        200 features, seed 1."``
    """
    return f"Area file {area.source} (SHA-256 {area.sha256[:12]}), {seafloor} seafloor, {count_noun(n_features, 'feature')}, seed {seed}."


def plans_caption(area_name: str, note: str) -> str:
    """Caption of the table of the baselines and recommended plans (``tab-survey-design-plans``),
    without its files sentence.

    Parameters
    ----------
    area_name : str
        The survey area's name.
    note : str
        :func:`area_note`.

    Returns
    -------
    str
        The caption.
    """
    return (f"The baselines and the recommended plan of each platform over {area_name}: main-line compass heading (degrees "
            f"clockwise from north) and spacing, crossing angle and spacing of the second set, altitude, track length and time, the shares of "
            f"the area covered once and twice, the gaps seen by no line, the shares of features seen by two lines and resolved by "
            f"three, and the median locus length. {note}")


def front_caption(objective: str, area_name: str, seafloor: str, n_features: int, decide_on: str) -> str:
    """Caption of the Pareto front (``fig-survey-front``).

    Parameters
    ----------
    objective : str
        The search's objective, a key of :data:`~.figures.OBJECTIVE_LABELS`.
    area_name : str
        The survey area's name.
    seafloor : str
        As for :func:`area_note`.
    n_features : int
        Features per plan.
    decide_on : str
        The joint estimate's error the recommendation is decided on, a key of
        :data:`~.figures.ERROR_LABELS`.

    Returns
    -------
    str
        The caption.
    """
    return (f"Track flown (lines, turns, transits and the return to the start) against the {OBJECTIVE_LABELS[objective]} for every plan "
            f"searched over {area_name} ({seafloor} seafloor, {count_noun(n_features, 'feature')}); hollow: fewer "
            "of the area seen twice than the standard plan; the line joins the Pareto front; the circle marks the "
            f"recommended plan, decided with the joint adjustment under the noise model on the {ERROR_LABELS[decide_on]} "
            "error (the standard plan unless a plan's interval excludes it), "
            "so it may lie off this noise-free front.")


def noise_caption(noise_seeds: Sequence[int], decide_on: str, note: str) -> str:
    """Caption of the table of the plans scored with the joint adjustment
    (``tab-survey-design-noise``), without its files sentence.

    Parameters
    ----------
    noise_seeds : sequence of int
        The independent seeds the plans were scored on.
    decide_on : str
        As for :func:`front_caption`.
    note : str
        :func:`area_note`.

    Returns
    -------
    str
        The caption.
    """
    return (f"The plans the rule could recommend, flown with each platform's per-pass navigation and sonar noise and "
            f"adjusted jointly over seeds {', '.join(map(str, noise_seeds))}: track length, share of the area seen twice, "
            f"the median horizontal, vertical and map-shape error of the joint estimate (mean over the seeds, 95 % "
            f"interval; decided on: {ERROR_LABELS[decide_on]}), and the fewest features a seed's median used "
            f"(under 30: left empty). The interval is Student's t over the seeds, symmetric about the mean; where it "
            f"reaches below 0 its lower end is cut at 0 and the cell says \"{CUT_NOTE}\" (an error is not negative: "
            f"the cut keeps the interval's coverage, and the rule reads the ends shown). {note}")


def crossing_caption(objective: str, note: str) -> str:
    """Caption of the table of the eligible plans by their second set of lines
    (``tab-survey-design-crossing``), without its files sentence.

    Parameters
    ----------
    objective : str
        As for :func:`front_caption`.
    note : str
        :func:`area_note`.

    Returns
    -------
    str
        The caption.
    """
    return (f"The eligible plans searched, by their second set of lines: their number, the best and the median "
            f"value over them of the {OBJECTIVE_LABELS[objective]}, and the median crossing angle of the features' best "
            f"pairs. {note}")


def standard_twice_text(plans: pd.DataFrame) -> str:
    """The share of the area the standard plan sees twice, as glued (``"100.0 %"``).

    Parameters
    ----------
    plans : pandas.DataFrame
        One platform's plans (:func:`sss_locus.experiments.survey_design.front.search_plans`),
        with one row of ``kind`` ``"standard"`` and its ``covered_twice`` share.

    Returns
    -------
    str
        The share in per cent.
    """
    return fmt_percent(plans[plans.kind == "standard"].covered_twice.iloc[0])


def standard_twice_sentence(plans: dict[str, pd.DataFrame], platforms: dict) -> str:
    """The check of the standard plan's 200 % on the area, one clause per platform (``"the
    AUV's standard plan sees 98.0 % of the area twice; ..."``).

    Parameters
    ----------
    plans : dict of str to pandas.DataFrame
        Each platform's plans, by data key (as for :func:`standard_twice_text`).
    platforms : dict of str to sss_locus.experiments.datamodel.platforms.Platform
        The platforms, by the same keys (their ``name`` is written).

    Returns
    -------
    str
        The sentence, ending in a full stop.
    """
    return "; ".join(f"the {pf.name}'s standard plan sees {standard_twice_text(plans[k])} of the area twice"
                     for k, pf in platforms.items()) + "."


def best_pairs_sentence(plans: dict[str, pd.DataFrame], platforms: dict) -> str:
    """The median crossing angle of the features' best pairs of lines on the recommended and on
    the standard plan, one clause per platform (``"for the AUV, 12.0° apart on the recommended
    plan and 0.500° on the standard plan; ..."``, three significant figures).

    Parameters
    ----------
    plans : dict of str to pandas.DataFrame
        Each platform's plans, by data key, with a boolean ``recommended`` column (one row true)
        and ``best_pair_angle_median_deg`` (deg).
    platforms : dict of str to sss_locus.experiments.datamodel.platforms.Platform
        The platforms, by the same keys.

    Returns
    -------
    str
        The sentence, ending in a full stop.
    """
    pairs = [f"for the {platforms[k].name}, {fmt_sig(t[t.recommended].best_pair_angle_median_deg.iloc[0], 3)}° apart "
             f"on the recommended plan and {fmt_sig(t[t.kind == 'standard'].best_pair_angle_median_deg.iloc[0], 3)}° "
             "on the standard plan" for k, t in plans.items()]
    return "; ".join(pairs) + "."


def solver_path_sentence(shifts: dict, platforms: dict) -> str:
    """What the solver's path changes (:func:`~sss_locus.experiments.survey_design.scoring.solver_path_shifts`),
    per platform: features of the standard plan that moved to another local minimum when solved
    with ``dogbox`` instead of ``trf``, how many of them were seen on only two passes, the largest
    move, and how far the median horizontal error moved.

    Parameters
    ----------
    shifts : dict of str to pandas.DataFrame
        Platform key -> ``solver_path_shifts``' table (one row per seed).
    platforms : dict
        Platform key -> platform (its ``name``).

    Returns
    -------
    str
        One sentence per platform; lengths in m and mm.
    """
    from sss_locus.experiments.survey_design.joint import MOVED_M

    parts = []
    for key, t in shifts.items():
        name, n = platforms[key].name, int(t.n_joint.sum())
        moved = (f"{int(t.n_moved.sum()):,} of {n:,} feature estimates moved by more than {fmt_sig(MOVED_M, 2)} m "
                 f"({int(t.n_moved_two_pass.sum()):,} of them of features seen on only two passes, which are "
                 f"{int(t.n_two_pass.sum()):,} of the {n:,})")
        largest = float(t.max_shift_m.max())
        largest = f"{fmt_sig(largest, 2)} m" if largest >= 1.0 else f"{fmt_sig(1e3 * largest, 2)} mm"
        parts.append(f"For the {name}, over {count_noun(len(t), 'seed')}, {moved}; the largest move was "
                     f"{largest} and the median horizontal error moved by at most "
                     f"{fmt_sig(1e3 * float(t.horizontal_median_shift_m.max()), 2)} mm.")
    return " ".join(parts)


def plan_label(row) -> str:
    """A plan in words, with the lines' compass heading (degrees clockwise from grid north of
    the area's local frame): ``"090°/270° lines 120 m apart + cross lines at 90°, 240 m;
    altitude 21 m"``.

    Parameters
    ----------
    row : pandas.Series
        One plan: ``heading_deg`` (deg counter-clockwise from east), ``spacing_m``,
        ``crossing_deg`` (deg, NaN without cross lines), ``cross_spacing_m``, ``altitude_m`` (m),
        ``pitch_deg`` (deg).

    Returns
    -------
    str
        The plan in words.
    """
    a = round((90.0 - row["heading_deg"]) % 180.0, 1)
    text = f"{a:03.0f}°/{a + 180:03.0f}° lines {row['spacing_m']:.0f} m apart"
    if not math.isnan(row["crossing_deg"]):
        what = "offset repeat" if row["crossing_deg"] % 180 == 0 else f"cross lines at {row['crossing_deg']:g}°"
        text += f" + {what}, {row['cross_spacing_m']:.0f} m"
    text += f"; altitude {row['altitude_m']:.3g} m"  # a boat's altitude is the water depth: 8.5 m, not "8 m"
    return text + (f", pitch {row['pitch_deg']:g}°" if row["pitch_deg"] else "")


def plan_caption(platform, area, area_file: str, row, cov: dict, files, *, water_depth_m: float,
                 depth_source: str, ardupilot: bool = True, turn_notes=()) -> str:
    """The caption of a recommended plan's figure: the plan, the water depth it used and where
    that came from, its cost and coverage (``cov`` of
    :func:`sss_locus.experiments.survey_design.front.plan_coverage`), the area file with its SHA-256
    and the mission ``files`` beside the figure (without an origin only the CSV, and why; for a
    vehicle that does not run ArduPilot no ArduPilot mission, and why); the cost is the track the
    mission flies (``row.total_m``: lines, U-turns, transits and the return to the start); in
    navigable water (a walled harbour) its clearance, and ``turn_notes`` the turns that did not fit
    (:func:`sss_locus.experiments.survey_design.route.turn_misfits`).

    Parameters
    ----------
    platform : Platform
        The vehicle (``name``, ``turn_radius_m``, ``speed_m_s``, depth limits).
    area : SurveyArea
        The survey area (``name``, ``origin_lonlat``, ``sha256``, navigable water and clearance).
    area_file : str
        The area file's name as shown.
    row : pandas.Series
        The recommended plan (:func:`plan_label`'s columns, ``run_m``, ``total_m`` in m, ``time_h``).
    cov : dict
        Its coverage: shares ``once``, ``twice`` (0–1), ``n_holes`` and the out-of-reach parts
        (:func:`reach_sentence`).
    files : iterable of str
        Names of the mission files written.
    water_depth_m : float
        The water depth the plan used (m).
    depth_source : str
        Where that depth came from, in words.
    ardupilot : bool
        Whether the vehicle runs ArduPilot (its ``.plan``/``.waypoints`` files exist).
    turn_notes : iterable of str
        The turns that did not fit, in words.

    Returns
    -------
    str
        The caption (markdown); lengths in m and km, time in h.
    """
    names = ", ".join(f"`{n}`" for n in files)
    why = ("" if area.origin_lonlat is not None else
           " (the others need longitude/latitude: give the area file an `origin_lonlat`)")
    if area.origin_lonlat is not None and not ardupilot:
        why = (" (no `.plan` or `.waypoints`: this vehicle does not run ArduPilot; convert the CSV or GeoJSON "
               "into its own planner's mission format)")
    return (f"Recommended plan for the {platform.name} over {area.name}: {plan_label(row)}; water depth "
            f"{water_depth_m:.3g} m ({depth_source}); " + (
                f"lines run past the area by their swath's reach and a run-in of {row.run_m:.0f} m; "
                if area.water() is None else
                "lines, run-ins, turns and transits stay in the navigable water ("
                + ("its navigable outline" if area.navigable_wkt else f"{area.water_beyond_m:g} m past the area's edge")
                + f"), {area.clearance_m:g} m off its edge and holes, line ends pulled back where a turn needs room; "
                "the inclusion fence (red dashed) never reaches past it; ")
            + (f"turns that do not fit: {'; '.join(turn_notes)}; " if turn_notes else "")
            + f"{row.total_m / 1e3:.2f} km flown (the mission's track: lines, turns of radius "
            f"{platform.turn_radius_m:g} m, transits and the return to the start), "
            + f"{row.time_h:.1f} h at {platform.speed_m_s:g} m/s; seen once {fmt_percent(cov['once'])}, twice "
            f"{fmt_percent(cov['twice'])} of the area, gaps (groups of cells seen by no line): {cov['n_holes']}. "
            + reach_sentence(platform, cov) + "Grey dotted: WGS 84 meridians and "
            f"parallels. Area file `{area_file}` "
            f"(SHA-256 `{area.sha256[:12]}`); mission files beside the figure: {names}{why}.")


def reach_sentence(platform, cov: dict) -> str:
    """The part of the area no plan can see (``cov["out_of_reach"]``, its area
    ``cov["out_of_reach_m2"]`` and its parts ``too_deep``, ``too_shallow``:
    :func:`~sss_locus.experiments.survey_design.coverage.out_of_reach`) in one sentence with the
    depths the sonar reaches, ``""`` when there is none.

    Parameters
    ----------
    platform : Platform
        The vehicle (``name``, ``fixed_depth``, ``depth_min_m`` and the sonar's reach).
    cov : dict
        The coverage with ``out_of_reach`` (share 0–1), ``out_of_reach_m2`` (m²), ``too_deep``
        and ``too_shallow`` (shares).

    Returns
    -------
    str
        The sentence (areas in percent and ha, depths in m) ending in a space, or ``""``.
    """
    if float(cov.get("out_of_reach", 0.0)) <= 0:
        return ""
    area_m2 = cov["out_of_reach_m2"] / cov["out_of_reach"]
    part = lambda share: f"{fmt_percent(share)} of the area ({share * area_m2 / 1e4:.2g} ha)"
    if not platform.fixed_depth:
        return (f"{part(cov['out_of_reach'])} lies where the sonar cannot see the seafloor at the plan's altitude; "
                "no plan can see it (dark grey). ")
    low, high = (platform.depth_min_m + v for v in reach_limits_m(platform))
    parts = ([f"{part(cov['too_deep'])} lies deeper than the sonar reaches at {high:.3g} m below the surface"]
             if cov["too_deep"] > 0 else [])
    parts += ([f"{part(cov['too_shallow'])} is shallower than the {low:.3g} m the sonar needs"]
              if cov["too_shallow"] > 0 else [])
    return " and ".join(parts) + f"; no plan can see {'it' if len(parts) == 1 else 'them'} (dark grey). "


#: The joint estimate's errors (:data:`~sss_locus.experiments.survey_design.scoring.ERRORS`) in words.
ERROR_LABELS = {"horizontal": "horizontal", "vertical": "vertical", "shape": "map-shape"}


#: Said inside the parentheses of an interval whose lower end was cut at 0
#: (:func:`~sss_locus.experiments.survey_design.scoring.lower_end_cut`).
CUT_NOTE = "lower end cut at 0"


def with_cut_note(text: str, cut: bool) -> str:
    """An estimate with its interval, saying where the interval's lower end was cut at 0.

    Parameters
    ----------
    text : str
        An estimate with its interval in parentheses (:func:`~sss_locus.report.common.text.fmt_ci`).
    cut : bool
        Whether the lower end was cut
        (:func:`~sss_locus.experiments.survey_design.scoring.lower_end_cut`).

    Returns
    -------
    str
        ``"1.6 (95 % CI 0–3.4)"`` -> ``"1.6 (95 % CI 0–3.4, lower end cut at 0)"`` when ``cut``;
        ``text`` unchanged otherwise or without a closing parenthesis.
    """
    return f"{text[:-1]}, {CUT_NOTE})" if cut and text.endswith(")") else text


def error_text(row, name: str = "horizontal") -> str:
    """A plan's mean error ``name`` (of :data:`ERROR_LABELS`) over the seeds with its 95 %
    interval (a row of :func:`~sss_locus.experiments.survey_design.scoring.summarise`), e.g.
    ``"2.6 (95 % CI 2.4–2.8) m"``, or ``"1.6 (95 % CI 0–3.4, lower end cut at 0) m"`` where the
    symmetric interval reached below 0; ``"too few features"`` without an interval.

    Parameters
    ----------
    row : pandas.Series
        A row of ``summarise`` with ``error_<name>_m``, ``error_<name>_lo_m``,
        ``error_<name>_hi_m`` (m).
    name : str
        A key of :data:`ERROR_LABELS`.

    Returns
    -------
    str
        The error with its interval in m, or ``"too few features"``.
    """
    if not math.isfinite(row[f"error_{name}_lo_m"]):
        return "too few features"
    mean, lo, hi = (row[f"error_{name}{s}_m"] for s in ("", "_lo", "_hi"))
    return with_cut_note(fmt_ci(mean, lo, hi), lower_end_cut(mean, lo, hi)) + " m"


def _counts(row) -> str:
    return f"{count_noun(int(row.n_seeds), 'seed')}, at least {count_noun(int(row.min_features), 'feature')} each"


def _beside(row, decided: str) -> str:
    others = [e for e in ERROR_LABELS if e != decided]
    return "; ".join(f"{ERROR_LABELS[e]} {error_text(row, e)}" for e in others)


SAME_LENGTH = 5e-4
"""Tracks whose lengths differ by less than this fraction are "of the same length" in the verdict
(the lawn-mower is spaced by bisection to the standard plan's track length)."""


def _line_compass_deg(heading_deg: float) -> int:
    """A line's compass heading, its two directions as one number in [0, 180) (deg clockwise
    from north; ``heading_deg`` counter-clockwise from east)."""
    return round((90.0 - heading_deg) % 180.0) % 180


def none_as_short(plans: pd.DataFrame) -> str:
    """Why no searched plan could be recommended, when none was: the rule recommends only an
    eligible plan no longer than the standard plan; and, where the headings searched are not the
    standard plan's (which follows the area: its long axis, or the slope), that ``headings_deg``
    cannot force a heading whose lines make a longer track. ``""`` when some searched plan is
    eligible and no longer than the standard plan, or none was searched.

    Parameters
    ----------
    plans : pandas.DataFrame
        The search's plans (``kind``, ``eligible``, ``total_m``, ``heading_deg`` in deg
        counter-clockwise from east, and :func:`plan_label`'s columns).

    Returns
    -------
    str
        One sentence, or ``""``.
    """
    search = plans[plans.kind == "search"]
    std = plans[plans.kind == "standard"].iloc[0]
    if search.empty or (search.eligible.astype(bool) & (search.total_m <= std.total_m)).any():
        return ""
    searched = sorted({_line_compass_deg(h) for h in search.heading_deg})
    n_ok = int(search.eligible.astype(bool).sum())
    text = (f" None of the {len(search)} searched plans could be recommended: {n_ok} of them "
            f"{'sees' if n_ok == 1 else 'see'} enough of the area twice, and none of those is as short as the "
            f"standard plan ({plan_label(std)}); the rule recommends only a plan no longer than the standard plan.")
    if _line_compass_deg(std.heading_deg) not in searched:
        text += (f" The headings searched (lines at {', '.join(f'{a:03d}°/{a + 180:03d}°' for a in searched)}) are "
                 "not the standard plan's, which follows the area (its long axis, or the slope): where such lines make "
                 "a longer track, `headings_deg` cannot force a heading.")
    return text


def noise_verdict_sentence(summary: pd.DataFrame, verdict: dict, plans: pd.DataFrame, platform) -> str:
    """The recommendation with the joint adjustment under the noise model in one or two sentences
    (:func:`sss_locus.experiments.survey_design.scoring.recommend_under_noise`): the deciding
    error of the standard plan and of the best plan with their intervals over the seeds and the
    counts behind them, the other two errors beside, and whether the interval excludes the
    standard plan's.

    Parameters
    ----------
    summary : pandas.DataFrame
        The plans' scores (``summarise``), indexed as ``verdict`` names them.
    verdict : dict
        ``recommend_under_noise``'s verdict: ``standard``, ``best``, ``error``, ``reason``,
        ``holds``.
    plans : pandas.DataFrame
        The plans (:func:`plan_label`'s columns), same index.
    platform : Platform
        The vehicle (its ``name``).

    Returns
    -------
    str
        One to three sentences; errors in m. Where no searched plan was eligible and as short as
        the standard plan, the last one says so (:func:`none_as_short`).
    """
    return _noise_verdict(summary, verdict, plans, platform) + none_as_short(plans)


def too_few_sentence(row) -> str:
    """Why a plan's joint estimate had too few features on some seed, in a surveyor's words: how
    many features the plan saw on two or more passes on that seed (a feature seen on one pass is
    not tied to a second one, so it is not estimated), and whether the adjustment lost the
    others (it stopped on its evaluation limit before converging: none estimated).

    Parameters
    ----------
    row : pandas.Series
        A plan's row of :func:`~sss_locus.experiments.survey_design.scoring.summarise`
        (``min_features``; ``fewest_seed`` and ``fewest_seen_twice`` when the scores had them).

    Returns
    -------
    str
        One sentence, starting in lower case.

    Examples
    --------
    >>> import pandas as pd
    >>> too_few_sentence(pd.Series({"min_features": 0, "fewest_seed": 3, "fewest_seen_twice": 60})).split(",")[0]
    'on seed 3 the plan saw 60 features on two or more passes'
    """
    n, least = int(row["min_features"]), f"fewer than the {MIN_FEATURES} a median is taken over"
    if not np.isfinite(row.get("fewest_seed", np.nan)):
        return f"some seed gave the plan's joint estimate only {n:,} features, {least}."
    seed, twice = int(row["fewest_seed"]), int(row["fewest_seen_twice"])
    if twice < MIN_FEATURES:
        return (f"on seed {seed} the plan saw only {twice:,} features on two or more passes ({least}; a feature "
                "seen on one pass only is not tied to a second pass, so the joint adjustment does not estimate it).")
    if n == 0:
        return (f"on seed {seed} the plan saw {twice:,} features on two or more passes, but the joint adjustment did "
                "not converge within its evaluation limit, so it estimated none of them.")
    return (f"on seed {seed} the plan saw {twice:,} features on two or more passes, but the joint adjustment "
            f"estimated only {n:,} of them, {least}.")


def _noise_verdict(summary: pd.DataFrame, verdict: dict, plans: pd.DataFrame, platform) -> str:
    name, std = platform.name, summary.loc[verdict["standard"]]
    e = verdict["error"]
    what = f"{ERROR_LABELS[e]} error of the joint estimate"
    if verdict["reason"] == "too few features":
        return f"For the {name}, {too_few_sentence(std)} Its errors are not findings and the standard plan is kept."
    if verdict["reason"] == "the standard plan is the best":
        return (f"For the {name}, no plan as short as the standard plan has a smaller mean {what}: the standard plan "
                f"({error_text(std, e)}; {_beside(std, e)}; {_counts(std)}) is kept.")
    b = summary.loc[verdict["best"]]
    label = plan_label(plans.loc[verdict["best"]])
    longer = b.total_m / std.total_m - 1.0
    length = (f"a track {fmt_percent(abs(longer))} {'shorter' if longer < 0 else 'longer'}"
              if abs(longer) >= SAME_LENGTH else "a track of the same length (within 0.05 %)")
    head = (f"For the {name}, the {'plan' if verdict['holds'] else 'best plan as short as the standard plan'} of "
            f"{label} has a {what} of {error_text(b, e)} ({_beside(b, e)}; {_counts(b)}) against the standard plan's "
            f"{error_text(std, e)} ({_beside(std, e)}; {_counts(std)}), on {length}: ")
    return head + ("its interval lies below the standard plan's, so it is recommended." if verdict["holds"]
                   else "the intervals overlap, so the standard plan is kept.")


def verdict_words(verdicts: dict, platforms: dict) -> str:
    """The claims-page verdict: per platform, whether a plan beat the standard plan on the
    deciding error of the joint estimate, the platforms by their keys (``"a plan beats the
    standard plan on the horizontal error (auv); standard plan kept (boat)"``).

    Parameters
    ----------
    verdicts : dict of str to dict
        Platform key -> its verdict (``holds``, ``error``).
    platforms : dict
        The platforms shown (keys of ``verdicts`` outside it are left out).

    Returns
    -------
    str
        The verdicts, ``"; "``-separated, capitalised.
    """
    parts = [(f"a plan beats the standard plan on the {ERROR_LABELS[v['error']]} error" if v["holds"]
              else "standard plan kept") + f" ({k})" for k, v in verdicts.items() if k in platforms]
    text = "; ".join(parts)
    return text[0].upper() + text[1:]
