"""Facade of the chapter ``notebooks/rigs.ipynb`` (The rigs: each platform's sonar mountings).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import rigs as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from IPython.display import Markdown
from myst_nb import glue
import pandas as pd

from sss_locus.experiments.platforms import load_platforms, provenance_table
from sss_locus.experiments.userdata import label_key
from sss_locus.pipeline.chapters.common import use_data
from sss_locus.pipeline.publish import publish
from sss_locus.report import rigs
from sss_locus.report.rigs import coverage_text, plot_rigs, rig_outlines, data_sources
from sss_locus.report.tables import readable_table

__all__ = ["coverage_text", "data_sources", "glue", "label_key", "load_platforms", "Markdown", "pd",
           "plot_rigs", "provenance_table", "publish", "readable_table", "rig_outlines", "rigs",
           "use_data"]
