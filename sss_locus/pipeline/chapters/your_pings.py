"""Facade of the chapter ``notebooks/your_pings.ipynb`` (Your pings: a user's recorded pings).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import your_pings as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from IPython.display import Markdown, HTML
from myst_nb import glue
from pathlib import Path
import pandas as pd

from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.sonar_files.observations import LocalFrame
from sss_locus.experiments.sonar_files.observations_xtf import observation_files, observation_warnings
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.sonar_files.xtf_summary import summary as xtf_summary, waterfall_data
from sss_locus.experiments.your_pings.study import run
from sss_locus.experiments.your_pings.files import read_truth, against_truth, geojson_text
from sss_locus.experiments.your_pings.joint import joint_estimate, with_joint
from sss_locus.paths import REPO_ROOT
from sss_locus.pipeline.chapters.common import show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.concept.figures import offline_html
from sss_locus.report.your_pings.waterfall import waterfall
from sss_locus.report.your_pings.figures import (summary_sentence, page_data_words, plan_view, map_caption,
                                                 feature_panels, view_3d)
from sss_locus.report.your_pings.joint import passes_caption, joint_sentence, passes_shown
from sss_locus.report.your_pings.real import (marks, read_hits, waterfall_caption, positions_table,
                                              one_pass_text)

__all__ = ["against_truth", "feature_panels", "geojson_text", "glue", "HTML", "joint_estimate",
           "joint_sentence", "load_pass_noise", "load_platform", "LocalFrame", "map_caption", "Markdown",
           "marks", "observation_files", "observation_warnings", "offline_html", "one_pass_text", "page_data_words",
           "passes_caption", "passes_shown", "Path", "pd", "plan_view", "positions_table", "publish",
           "read_hits", "read_truth", "REPO_ROOT", "run", "show_table", "summary_sentence", "use_data",
           "view_3d", "waterfall", "waterfall_caption", "waterfall_data", "with_joint", "xtf_summary"]
