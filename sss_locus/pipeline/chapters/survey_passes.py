"""Facade of the chapter ``notebooks/survey_passes.ipynb`` (Survey passes: locus length against crossing angle).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import survey_passes as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from dataclasses import replace
import time

from IPython.display import Markdown
from myst_nb import glue
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import load_envelope, OffsetModel
from sss_locus.experiments.survey_passes.planning import (crossing_angle_grid, crossing_angle_curve,
                                                          pitch_study_platform, worst_band, band_samples, median_ratio)
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.survey_passes.verdicts import near_end_check, peak_agreement
from sss_locus.pipeline.run.cache import cached
from sss_locus.report.common.text import run_platforms_md
from sss_locus.pipeline.chapters.common import key, paper_platforms, show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.survey_passes.curve_findings import (curve_finding, offset_models_finding, pitch_depth_finding,
                                                          shorter_finding, skipped_study_note, survey_summary)
from sss_locus.report.pose_space.findings import findings_markdown, platform_title
from sss_locus.report.survey_passes.figures import (plot_fig5, describe_setup, describe_offset_model, curve_texts,
                                                    peak_table, plot_offset_models, offset_models_bimodal_note,
                                                    model_tag, offset_model_texts, offset_model_table,
                                                    near_end_texts, peak_agreement_texts, near_end_caption,
                                                    pitch_depth_texts, plot_pitch_depth)
from sss_locus.report.common.tables import key_caption


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    prefix = "sp-{platform}"  # prefix of the keys report.survey_passes.figures' *_texts functions return
    model_prefix = "sp-{platform}-{model}"  # prefix of peak_agreement_texts' keys (model: report.survey_passes.figures.model_tag)
    paperband_prefix = "sp-{platform}-paperband"  # prefix of pitch_depth_texts' keys in the paper's band
    worst_band = "sp-{platform}-worst-band"  # the avoid band holding the peak (deg)
    paper_band = "sp-{platform}-paper-band"  # the paper's avoid band (deg)


__all__ = ["paper_platforms", "run_platforms_md", "key", "KEYS", "band_samples", "cached", "crossing_angle_curve", "crossing_angle_grid", "curve_finding",
           "curve_texts", "describe_offset_model", "describe_setup", "findings_markdown", "glue",
           "key_caption", "load_envelope", "load_platform", "Markdown", "median_ratio",
           "model_tag", "near_end_caption", "near_end_check", "near_end_texts", "offset_model_table",
           "offset_model_texts", "offset_models_bimodal_note", "offset_models_finding", "OffsetModel",
           "pd", "peak_agreement", "peak_agreement_texts", "peak_table", "pitch_depth_finding",
           "pitch_depth_texts", "pitch_study_platform", "platform_title", "plot_fig5",
           "plot_offset_models", "plot_pitch_depth", "publish", "replace", "show_table", "simulate_passes",
           "shorter_finding", "skipped_study_note", "survey_summary", "time", "use_data", "worst_band"]
