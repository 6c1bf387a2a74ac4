"""Facade of the chapter ``notebooks/pose_space.ipynb`` (The pose space: what drives locus length).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import pose_space as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue
import numpy as np
import pandas as pd

from sss_locus import two_view_locus
from sss_locus.experiments.choices import reading_effect, fan_share_removed, bin_window, hotspot_check
from sss_locus.experiments.platforms import load_platform
from sss_locus.experiments.pose_claims import map_intervals, claim_metrics, batch_medians, batches
from sss_locus.experiments.pose_space import PoseSpaceSpec, sample_pose_space, sample_geometry
from sss_locus.experiments.pose_stats import with_derived, spearman_table, heatmaps
from sss_locus.experiments.userdata import label_key
from sss_locus.pipeline.cache import cached
from sss_locus.pipeline.chapters.common import show_table, use_data
from sss_locus.pipeline.publish import publish, place
from sss_locus.report.pose_findings import (findings_markdown, platform_title, drivers_finding,
                                            panels_finding, choices_finding, reading_finding, fan_finding,
                                            hotspot_finding, pose_summary)
from sss_locus.report.pose_space import (scatter_subset, plot_sensitivity, plot_heatmaps,
                                         seed_stability_table, check_row, reading_texts, fan_texts,
                                         hotspot_texts, metric_texts)
from sss_locus.report.text import plain_label, fmt_ci, fmt_span

__all__ = ["batch_medians", "batches", "bin_window", "cached", "check_row", "choices_finding",
           "claim_metrics", "drivers_finding", "fan_finding", "fan_share_removed", "fan_texts",
           "findings_markdown", "fmt_ci", "fmt_span", "glue", "heatmaps", "hotspot_check",
           "hotspot_finding", "hotspot_texts", "label_key", "load_platform", "map_intervals", "Markdown",
           "metric_texts", "np", "panels_finding", "pd", "place", "plain_label", "platform_title",
           "plot_heatmaps", "plot_sensitivity", "pose_summary", "PoseSpaceSpec", "publish",
           "reading_effect", "reading_finding", "reading_texts", "sample_geometry", "sample_pose_space",
           "scatter_subset", "seed_stability_table", "show_table", "spearman_table", "time",
           "two_view_locus", "use_data", "with_derived"]
