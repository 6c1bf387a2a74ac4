"""Facade of the chapter ``notebooks/noise.ipynb`` (Noise: ranges, poses and the locus' extent).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import noise as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from myst_nb import glue
import numpy as np
import pandas as pd

from sss_locus import Aperture
from sss_locus.experiments.envelopes import load_envelope, OffsetModel
from sss_locus.experiments.noise import (load_noise_model, survey_noise_table, monte_carlo,
                                         gaussian_norm_quantile, first_order)
from sss_locus.experiments.planning import crossing_angle_grid, curve_summary, peak_angle, planning_bands
from sss_locus.experiments.platforms import load_platform
from sss_locus.experiments.replicates import median_with_interval
from sss_locus.experiments.survey_passes import simulate_passes
from sss_locus.experiments.three_view_patterns import PATTERNS
from sss_locus.experiments.userdata import label_key
from sss_locus.experiments.verdicts import advice_verdict
from sss_locus.experiments.view_sets import views_from_survey, draw_pattern
from sss_locus.pipeline.cache import cached
from sss_locus.pipeline.chapters.common import show_table, use_data
from sss_locus.pipeline.publish import publish
from sss_locus.report.findings import noise_advice_findings
from sss_locus.report.noise import (level_label, plot_noise_curves, curve_frames, advice_texts, scale_text,
                                    plot_breakdown, plot_check)
from sss_locus.report.tables import readable_table
from sss_locus.report.text import fmt_interval, fmt_bands, fmt_sig

__all__ = ["advice_texts", "advice_verdict", "Aperture", "cached", "crossing_angle_grid", "curve_frames",
           "curve_summary", "draw_pattern", "first_order", "fmt_bands", "fmt_interval", "fmt_sig",
           "gaussian_norm_quantile", "glue", "label_key", "level_label", "load_envelope",
           "load_noise_model", "load_platform", "median_with_interval", "monte_carlo",
           "noise_advice_findings", "np", "OffsetModel", "PATTERNS", "pd", "peak_angle", "planning_bands",
           "plot_breakdown", "plot_check", "plot_noise_curves", "publish", "readable_table", "scale_text",
           "show_table", "simulate_passes", "survey_noise_table", "time", "use_data", "views_from_survey"]
