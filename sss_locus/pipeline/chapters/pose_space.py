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
from sss_locus.experiments.pose_space.choices import reading_effect, fan_share_removed, bin_window, hotspot_check
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.claims import map_intervals, claim_metrics, batch_medians, batches
from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space, sample_geometry
from sss_locus.experiments.pose_space.stats import with_derived, spearman_table, heatmaps
from sss_locus.pipeline.run.cache import cached
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish, place
from sss_locus.report.pose_space.findings import (findings_markdown, platform_title, drivers_finding,
                                                  panels_finding, choices_finding, reading_finding, fan_finding,
                                                  hotspot_finding, pose_summary, yaw0_text)
from sss_locus.report.pose_space.figures import (scatter_subset, plot_sensitivity, plot_heatmaps,
                                                 seed_stability_table, check_row, reading_texts, fan_texts,
                                                 hotspot_texts, metric_texts)
from sss_locus.report.common.text import plain_label, fmt_span, run_platforms_md


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    fig_sensitivity = "fig-sensitivity-{platform}"  # figure label
    fig_heatmaps = "fig-heatmaps-{platform}"  # figure label
    prefix = "ps-{platform}"  # prefix of the keys report.pose_space.figures's *_texts functions return
    text = "ps-{platform}-{text}"  # a text of report.pose_space.figures.metric_texts (its name)
    unc_top_norm = "ps-unc-{platform}-top-norm"  # unconstrained sweep: top quantity for the normalised length
    unc_rho_mis = "ps-unc-{platform}-rho-mis"  # unconstrained sweep: rho of misalignment (norm.)
    unc_yaw0 = "ps-unc-{platform}-yaw0"  # unconstrained sweep: yaw 0 / peak with its interval
    below_top_norm = "ps-below-{platform}-top-norm"  # feature-below rule lifted: top quantity (norm.)
    below_rho_mis = "ps-below-{platform}-rho-mis"  # feature-below rule lifted: rho of misalignment (norm.)
    below_hotspot = "ps-below-{platform}-hotspot"  # feature-below rule lifted: hotspot region
    below_hotspot_equal = "ps-below-{platform}-hotspot-equal"  # feature-below rule lifted: whether the hotspot includes equal azimuths
    depth_top_norm = "ps-depth-{platform}-top-norm"  # vehicle 2 above the surface allowed: top quantity (norm.)
    depth_rho_mis = "ps-depth-{platform}-rho-mis"  # vehicle 2 above the surface allowed: rho of misalignment (norm.)
    depth_hotspot = "ps-depth-{platform}-hotspot"  # vehicle 2 above the surface allowed: hotspot bin
    depth_above = "ps-depth-{platform}-above"  # share of draws with vehicle 2 above the surface
    depth_min = "ps-depth-{platform}-min"  # the platform's shallowest depth (m)
    depth_same_top = "ps-depth-{platform}-same-top"  # whether the top quantity is the main run's


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "batch_medians", "batches", "bin_window", "cached", "check_row", "choices_finding",
           "claim_metrics", "drivers_finding", "fan_finding", "fan_share_removed", "fan_texts",
           "findings_markdown", "fmt_span", "glue", "heatmaps", "hotspot_check",
           "hotspot_finding", "hotspot_texts", "load_platform", "map_intervals", "Markdown",
           "metric_texts", "np", "panels_finding", "pd", "place", "plain_label", "platform_title",
           "plot_heatmaps", "plot_sensitivity", "pose_summary", "PoseSpaceSpec", "publish",
           "reading_effect", "reading_finding", "reading_texts", "sample_geometry", "sample_pose_space",
           "scatter_subset", "seed_stability_table", "show_table", "spearman_table", "time",
           "two_view_locus", "use_data", "with_derived", "yaw0_text"]
