"""Facade of the chapter ``notebooks/three_views.ipynb`` (Three views: patterns that resolve the feature).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import three_views as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue
import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.noise_model import NoiseModel, load_noise_model
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.three_views.patterns import (PATTERNS, three_view_table, heading_sweep,
                                                        median_intervals)
from sss_locus.experiments.passes.view_sets import draw_pattern
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.three_views.findings import closure_finding, pattern_ranking, tilt_markdown, sweep_finding
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.common.text import fmt_interval, run_platforms_md
from sss_locus.report.three_views.figures import (plot_patterns, PATTERN_TAGS, share_text, plot_heading_sweep,
                                                  sweep_texts)


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    resolved = "tv-{platform}-{pattern}-resolved"  # share resolved to one candidate (pattern: report.three_views.figures.PATTERN_TAGS)
    ambiguous = "tv-{platform}-{pattern}-ambiguous"  # share left two-fold ambiguous
    amb_no_el = "tv-{platform}-{pattern}-amb-no-el"  # share ambiguous without the elevation test
    amb_no_az = "tv-{platform}-{pattern}-amb-no-az"  # share ambiguous without the azimuth test
    interval = "tv-{platform}-{pattern}-{quantity}"  # a median with its interval; quantity: angle, per-cm, full or range
    generated = "tv-{finding}-generated"  # a generated finding (report.three_views.findings)
    tilt_resolved = "tv-{platform}-tilt{tilt}-{pattern}-resolved"  # tilted transducers (tilt: deg, '.' written 'p')
    tilt_ambiguous = "tv-{platform}-tilt{tilt}-{pattern}-ambiguous"  # tilted transducers, ambiguous share
    sweep = "tv-{platform}-{text}"  # a text of report.three_views.figures.sweep_texts (its name)


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "closure_finding", "draw_pattern", "findings_markdown", "fmt_interval", "glue", "heading_sweep",
           "load_envelope", "load_noise_model", "load_platform", "Markdown",
           "median_intervals", "NoiseModel", "np", "pattern_ranking", "PATTERN_TAGS", "PATTERNS", "pd",
           "platform_title", "plot_heading_sweep", "plot_patterns", "publish", "share_text", "show_table",
           "sweep_finding", "sweep_texts", "three_view_table", "tilt_markdown", "time", "use_data"]
