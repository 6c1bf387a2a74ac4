"""The survey-design chapter's prose (``notebooks/survey_design.ipynb``): the captions of its
tables and of the Pareto front, and the sentences it glues about the standard plan and the
features' best pairs, so the notebook's cells stay short.

The recommended plan's caption and the noise verdict are in :mod:`.figures`
(:func:`~.figures.plan_caption`, :func:`~.figures.noise_verdict_sentence`).
"""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd

from sss_locus.report.common.text import count_noun, fmt_percent, fmt_sig
from sss_locus.report.survey_design.figures import CUT_NOTE, ERROR_LABELS, OBJECTIVE_LABELS


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
