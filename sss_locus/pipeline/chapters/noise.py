"""Facade of the chapter ``notebooks/noise.ipynb`` (Noise: ranges, poses and the locus' extent).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import noise as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue
import numpy as np
import pandas as pd

from sss_locus import Aperture
from sss_locus.experiments.datamodel.envelopes import load_envelope, OffsetModel
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.noise.study import survey_noise_table
from sss_locus.experiments.passes.propagation import monte_carlo, first_order
from sss_locus.experiments.stats.gaussian_norm import gaussian_norm_quantile
from sss_locus.experiments.survey_passes.planning import crossing_angle_grid, curve_summary, peak_angle, planning_bands
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.stats.replicates import median_with_interval
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.three_views.patterns import PATTERNS
from sss_locus.experiments.survey_passes.verdicts import advice_verdict
from sss_locus.experiments.passes.view_sets import views_from_survey, draw_pattern
from sss_locus.pipeline.run.cache import cached
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.noise.findings import (answer_finding, breakdown_finding, check_finding, crop_finding,
                                             guide_sentence, noise_advice_findings, offset_models_finding,
                                             range_floor_finding, summary_finding)
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.noise.figures import (level_label, plot_noise_curves, curve_frames, advice_texts, scale_text,
                                            plot_breakdown, plot_check)
from sss_locus.report.common.tables import readable_table
from sss_locus.report.common.text import fmt_interval, fmt_bands, fmt_sig, run_platforms_md


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    at_angle = "nz-{platform}-{quantity}-{angle}"  # median with interval at 0, 90 or 180 deg; quantity: length, extent, band or range-extent
    scaled_extent = "nz-{platform}-x{scale}-extent-{angle}"  # extent at a scaled noise level (scale: the factor, '.' written 'p')
    length_peak = "nz-{platform}-length-peak"  # crossing angle of the locus length's peak (deg)
    extent_peak = "nz-{platform}-extent-peak"  # crossing angle of the extent's peak (deg)
    extent_peak_ci = "nz-{platform}-extent-peak-ci"  # its bootstrap interval
    extent_min_angle = "nz-{platform}-extent-min-angle"  # crossing angle of the smallest extent (deg)
    extent_min = "nz-{platform}-extent-min"  # the smallest extent with its interval
    scaled_empty = "nz-{platform}-x{scale}-empty"  # share of empty loci at a scaled noise level
    attitude_empty = "nz-{platform}-attitude-empty"  # share of empty loci with attitude noise only
    band_length = "nz-{platform}-{band}-length"  # prefer/avoid bands of the locus length
    band_extent = "nz-{platform}-{band}-extent"  # prefer/avoid bands of the extent
    band_over_length = "nz-{platform}-band-over-length"  # median band width over locus length
    empty = "nz-{platform}-empty"  # share of empty loci at the headline noise
    verdict = "nz-{platform}-verdict"  # whether the paper's advice survives noise
    oblique_extent = "nz-{platform}-oblique-extent"  # median extent over 10-40 deg (m)
    check_small = "nz-check-{views}-small"  # first order against Monte Carlo at small noise (views: two or three)
    check_head_median = "nz-check-{views}-head-median"  # the same at the headline noise, median
    check_head_max = "nz-check-{views}-head-max"  # the same at the headline noise, largest
    check_mc_median = "nz-check-{views}-{platform}-mc-median"  # Monte Carlo median with its interval
    three_lost = "nz-{platform}-three-lost"  # share of three-view draws lost


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "advice_texts", "answer_finding", "breakdown_finding", "check_finding", "crop_finding",
           "findings_markdown", "guide_sentence", "Markdown", "offset_models_finding", "platform_title",
           "range_floor_finding", "summary_finding", "advice_verdict", "Aperture", "cached", "crossing_angle_grid", "curve_frames",
           "curve_summary", "draw_pattern", "first_order", "fmt_bands", "fmt_interval", "fmt_sig",
           "gaussian_norm_quantile", "glue", "level_label", "load_envelope",
           "load_noise_model", "load_platform", "median_with_interval", "monte_carlo",
           "noise_advice_findings", "np", "OffsetModel", "PATTERNS", "pd", "peak_angle", "planning_bands",
           "plot_breakdown", "plot_check", "plot_noise_curves", "publish", "readable_table", "scale_text",
           "show_table", "simulate_passes", "survey_noise_table", "time", "use_data", "views_from_survey"]
