"""Facade of the chapter ``notebooks/reconstruction.ipynb`` (Reconstruction: a terrain from survey passes).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import reconstruction as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue
import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.reconstruction.joint import adjustment_estimators
from sss_locus.experiments.reconstruction.surveys import (survey_cases, layout_with_spacing, survey_errors,
                                                          over_surveys, paired_over_surveys)
from sss_locus.experiments.reconstruction.slope_error import slope_views
from sss_locus.experiments.survey_design.settings import load_settings
from sss_locus.experiments.datamodel.terrain import load_terrain_config
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.reconstruction.findings import comparisons_finding, errors_finding, models_finding, slope_finding
from sss_locus.report.reconstruction.figures import (spacing_label, plot_sweep, METRIC_LABELS, plot_slope,
                                                     plot_views, verdict_sentence, ESTIMATORS, comparison_word,
                                                     with_intervals, height_sentence)
from sss_locus.report.common.text import fmt_ci, fmt_percent, fmt_sig, run_platforms_md


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    error = "rc-{platform}-{estimator}-{metric}{relief}"  # median error with its interval; metric: horizontal, vertical or shape; relief: '' (default RMS relief), '-rmax' or '-r0'
    coverage = "rc-{platform}-{estimator}-coverage{relief}"  # share of features estimated; relief as for error
    spacing = "rc-{platform}-spacing"  # the routine line spacing (m)
    slope = "rc-{platform}-slope-{method}-{error}"  # one view on the steepest slope: method closed or simulated, error 3d, across or vertical
    comparison_word = "rc-{platform}-{estimator}-{metric}-word"  # estimator against the mosaic at the routine spacing (report.reconstruction.figures.comparison_word)
    terrain = "rc-{setting}"  # a terrain or survey setting: corr-len, area, cross-spacing


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "adjustment_estimators", "comparisons_finding", "errors_finding", "findings_markdown",
           "models_finding", "platform_title", "slope_finding", "comparison_word", "ESTIMATORS", "fmt_ci", "fmt_percent", "fmt_sig",
           "glue", "height_sentence", "layout_with_spacing", "load_envelope",
           "load_noise_model", "load_pass_noise", "load_platform", "load_settings", "load_terrain_config",
           "Markdown", "METRIC_LABELS", "np", "over_surveys", "paired_over_surveys", "pd", "plot_slope",
           "plot_sweep", "plot_views", "publish", "show_table", "slope_views", "spacing_label",
           "survey_cases", "survey_errors", "time", "use_data", "verdict_sentence", "with_intervals"]
