"""Facade of the chapter ``notebooks/planning.ipynb`` (Planning: crossing-angle bands).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import planning as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from IPython.display import Markdown
from myst_nb import glue
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import load_envelope, OffsetModel
from sss_locus.experiments.survey_passes.planning import crossing_angle_grid, crossing_angle_curve, planning_bands
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.survey_passes.verdicts import near_end_check
from sss_locus.pipeline.run.cache import cached
from sss_locus.report.common.text import run_platforms_md
from sss_locus.pipeline.chapters.common import paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.survey_passes.findings import near_end_findings
from sss_locus.report.survey_passes.planning import (band_texts, plot_planning_bands, PAPER_AVOID_DEG, bands_table,
                                                     bands_markdown, cross_line_finding, offset_model_words,
                                                     paper_band_finding)
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.survey_passes.figures import near_end_caption
from sss_locus.report.common.tables import readable_table, key_caption

__all__ = ["paper_platforms", "run_platforms_md", "band_texts", "bands_markdown", "bands_table", "cross_line_finding", "findings_markdown", "offset_model_words",
           "paper_band_finding", "platform_title", "cached", "crossing_angle_curve",
           "crossing_angle_grid", "glue", "key_caption", "load_envelope", "load_platform", "Markdown",
           "near_end_caption", "near_end_check", "near_end_findings", "OffsetModel", "PAPER_AVOID_DEG",
           "pd", "planning_bands", "plot_planning_bands", "publish", "readable_table", "show_table",
           "simulate_passes", "use_data"]
