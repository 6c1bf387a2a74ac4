"""sss-locus: the two-view sidescan-sonar ambiguity locus, exactly.

Reproduces and extends Norman & Mangelson, *Beyond the Flat Seafloor: A Closed-Form Two-View
Constraint to Aid Sidescan Sonar Reconstruction*. The entry point is :func:`two_view_locus`.

The package has four layers, each a subpackage importing only those before it:
:mod:`sss_locus.geometry` (exact numpy kernels; re-exported here) <- :mod:`sss_locus.experiments`
(data files, samplers, studies, statistics) <- :mod:`sss_locus.report` (plots and prose) and
:mod:`sss_locus.pipeline` (registry, runs, cache, figure export, book build, CLI).
:mod:`sss_locus.paths` holds every path.
"""

from . import geometry
from .geometry import *  # noqa: F403 - the geometry API is the package's API

__version__ = "0.1.0"

__all__ = [*geometry.__all__, "__version__"]
