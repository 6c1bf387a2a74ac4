"""Facade of the chapter ``notebooks/water.ipynb`` (Water: the locus cropped to the water column).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import water as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

import time

from IPython.display import Markdown
from myst_nb import glue
import numpy as np

from sss_locus.experiments.datamodel.envelopes import load_envelope, OffsetModel
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import sample_pose_space
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.datamodel.water_column import deepest_feature_m
from sss_locus.experiments.water.study import default_conditions, crop_effects, pass2_above_surface_share
from sss_locus.pipeline.run.cache import cached
from sss_locus.report.common.text import run_platforms_md
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.water.findings import seafloor_finding, subset_finding, surface_finding, water_summary
from sss_locus.report.water.figures import crop_caption, effect_table, effect_texts, effects_caption, plot_crop_effects, seafloor_caption


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    effect = "wa-{effect}"  # a sentence of report.water.figures.effect_texts (its name)
    pass2_above = "wa-{condition}-pass2-above"  # share of survey pass pairs whose pass 2 flies above the surface (condition: WaterCondition.slug)
    deepest = "wa-{platform}-deepest-m"  # deepest feature the platform's geometry reaches (m)


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "cached", "findings_markdown", "Markdown", "platform_title", "seafloor_finding",
           "subset_finding", "surface_finding", "water_summary", "crop_caption", "effects_caption", "seafloor_caption", "crop_effects", "deepest_feature_m", "default_conditions", "effect_table",
           "effect_texts", "glue", "load_envelope", "load_platform", "np", "OffsetModel",
           "pass2_above_surface_share", "plot_crop_effects", "publish", "sample_pose_space", "show_table",
           "simulate_passes", "time", "use_data"]
