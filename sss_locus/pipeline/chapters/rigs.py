"""Facade of the chapter ``notebooks/rigs.ipynb`` (The rigs: each platform's sonar mountings).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import rigs as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from IPython.display import Markdown
from myst_nb import glue
import pandas as pd

from sss_locus.experiments.datamodel.platforms import load_platforms, provenance_table
from sss_locus.pipeline.chapters.common import key, use_data
from sss_locus.pipeline.publish.publish import publish
from sss_locus.report.rigs import figures as rigs
from sss_locus.report.rigs.figures import coverage_text, plot_rigs, rig_outlines, data_sources
from sss_locus.report.common.tables import readable_table


class KEYS:
    """The glue keys (and figure labels) this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`;
    ``{platform}`` takes a data key."""

    tilt = "rigs-tilt-{platform}"  # port transducer's tilt (deg)
    fan = "rigs-fan-{platform}"  # azimuth aperture (deg)
    top = "rigs-top-{platform}"  # fan's upper edge above the horizontal (deg)
    bottom = "rigs-bottom-{platform}"  # fan's lower edge below the horizontal (deg)
    drawn_range = "rigs-range-{platform}"  # range the frusta are drawn to (m)


__all__ = ["key", "KEYS", "coverage_text", "data_sources", "glue", "load_platforms", "Markdown", "pd",
           "plot_rigs", "provenance_table", "publish", "readable_table", "rig_outlines", "rigs",
           "use_data"]
