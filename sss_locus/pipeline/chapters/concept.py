"""Facade of the chapter ``notebooks/concept.ipynb`` (The concept: two range spheres and their locus).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import concept as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from IPython.display import HTML
from myst_nb import glue
from scipy.spatial.transform import Rotation
import numpy as np
import pandas as pd

from sss_locus import Aperture, two_view_locus, elevation_misalignment
from sss_locus.experiments.datamodel.platforms import load_platforms
from sss_locus.pipeline.chapters.common import show_table, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.concept.figures import concept_data, plot_locus_concept, interactive_locus_concept, offline_html

__all__ = ["Aperture", "concept_data", "elevation_misalignment", "glue", "HTML",
           "interactive_locus_concept", "load_platforms", "np", "offline_html", "pd", "plot_locus_concept",
           "publish", "Rotation", "show_table", "two_view_locus", "use_data"]
