"""Facade of the chapter ``notebooks/survey_design.ipynb`` (Survey design: which lines to run).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import survey_design as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue

from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.survey_design.area import load_area, with_water_depth
from sss_locus.experiments.survey_design.front import (OBJECTIVES, coverage_grid_m, depth_settings, load_area_bathymetry,
                                                       plan_coverage, search_grid, search_plans, vehicle_depth_m)
from sss_locus.experiments.survey_design.settings import load_settings
from sss_locus.experiments.survey_design.route import turn_misfits
from sss_locus.experiments.survey_design.scoring import recommend_under_noise, score_plans, solver_path_shifts, summarise
from sss_locus.pipeline.chapters.common import key, show_table, use_data
from sss_locus.pipeline.publish.missions import mission_files, waypoints
from sss_locus.pipeline.publish.publish import place, publish
from sss_locus.pipeline.run.cache import cached
from sss_locus.report.common.text import fmt_percent, fmt_sig
from sss_locus.report.survey_design.figures import OBJECTIVE_LABELS, plot_front, plot_plan
from sss_locus.report.survey_design.prose import (area_note, best_pairs_sentence, crossing_caption, ERROR_LABELS,
                                                  error_text, front_caption, noise_caption, noise_verdict_sentence,
                                                  plan_caption, plan_label, plans_caption, solver_path_sentence,
                                                  standard_twice_sentence, standard_twice_text, verdict_words)
from sss_locus.report.survey_design.tables import (all_plans, crossing_table, noise_table, noise_table_shown,
                                                   plans_table, with_compass)


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    std_error = "sd-{platform}-std-error"  # the standard plan's deciding error of the joint estimate, with its interval (report.survey_design.prose.error_text)
    best_error = "sd-{platform}-best-error"  # the same for the best plan no longer than the standard plan ("no estimate" without one)
    std_features = "sd-{platform}-std-features"  # the fewest features a seed's median used, standard plan
    best_features = "sd-{platform}-best-features"  # the same for the best plan ("no" without one)
    std_twice = "sd-{platform}-std-twice"  # share of the area the standard plan sees twice
    fig_plan = "fig-survey-plan-{platform}"  # figure label of the platform's recommended plan


__all__ = ["all_plans", "area_note", "best_pairs_sentence", "cached", "coverage_grid_m", "crossing_caption",
           "crossing_table", "depth_settings", "ERROR_LABELS", "error_text", "fmt_percent", "fmt_sig",
           "front_caption", "glue", "key", "KEYS", "load_area", "load_area_bathymetry",
           "load_noise_model", "load_pass_noise", "load_platform", "load_settings", "Markdown", "mission_files",
           "noise_caption", "noise_table", "noise_table_shown", "noise_verdict_sentence", "OBJECTIVE_LABELS",
           "OBJECTIVES", "place", "plan_caption", "plan_coverage", "plan_label", "plans_caption", "plans_table",
           "plot_front", "plot_plan", "publish", "recommend_under_noise", "score_plans", "search_grid", "search_plans",
           "show_table", "solver_path_sentence", "solver_path_shifts", "standard_twice_sentence", "standard_twice_text", "summarise", "time", "turn_misfits",
           "use_data", "vehicle_depth_m", "verdict_words", "waypoints", "with_compass", "with_water_depth"]
