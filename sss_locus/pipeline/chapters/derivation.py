"""Facade of the chapter ``notebooks/derivation.ipynb`` (The derivation: the locus in closed form, checked symbolically).

Everything the notebook calls, in one import: ``from sss_locus.pipeline.chapters import derivation as ch``.
No logic of its own (:mod:`sss_locus.pipeline.chapters`).
"""

from myst_nb import glue
import pandas as pd
import sympy as sp

from sss_locus.geometry.symbolic import (derive_plane, symbols, quaternion_rotation, derive_circle,
                                         derive_one_angle, derive_scaling, derive_crop,
                                         elevation_halfspaces, azimuth_halfspaces, halfspace_in_frame1,
                                         kernel_discrepancy, derive_range_jacobian,
                                         kernel_jacobian_discrepancy)
from sss_locus.pipeline.chapters.common import key
from sss_locus.report.derivation.figures import show
from sss_locus.report.common.tables import readable_table


class KEYS:
    """The glue keys this chapter fills by :func:`~sss_locus.pipeline.chapters.common.key`."""

    residual = "derivation-{identity}-residual"  # a derivation's residual, simplified (0 when it holds)


__all__ = ["KEYS", "azimuth_halfspaces", "derive_circle", "derive_crop", "derive_one_angle", "derive_plane",
           "derive_range_jacobian", "derive_scaling", "elevation_halfspaces", "glue",
           "halfspace_in_frame1", "kernel_discrepancy", "kernel_jacobian_discrepancy", "key", "pd",
           "quaternion_rotation", "readable_table", "show", "sp", "symbols"]
