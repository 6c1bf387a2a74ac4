"""sss-locus: the two-view sidescan-sonar ambiguity locus, exactly.

Reproduces and extends Norman & Mangelson, *Beyond the Flat Seafloor: A Closed-Form Two-View
Constraint to Aid Sidescan Sonar Reconstruction*. The entry point is :func:`two_view_locus`.
"""

from .aperture import Aperture
from .locus import MAX_ARCS, LocusResult, LocusStatus, two_view_locus
from .misalignment import ElevationMisalignment, elevation_misalignment
from .poses import relative_pose

__version__ = "0.1.0"

__all__ = [
    "Aperture",
    "ElevationMisalignment",
    "LocusResult",
    "LocusStatus",
    "MAX_ARCS",
    "__version__",
    "elevation_misalignment",
    "relative_pose",
    "two_view_locus",
]
