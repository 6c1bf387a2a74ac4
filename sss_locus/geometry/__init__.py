"""The exact two-view (and three-view) geometry: numpy-only batched kernels.

Everything here takes batched arrays and returns batched arrays; nothing imports pandas,
matplotlib, SymPy or ``scipy.stats`` (SymPy lives in :mod:`sss_locus.geometry.symbolic`, imported
only on request). Frames, units and shapes are stated in each function's docstring.

Entry points
------------
:func:`two_view_locus`
    Circle, visible arcs and locus length for two range measurements with known relative pose.
:func:`sea_surface_half_space`, :func:`max_depth_half_space`
    Physical constraints (the water column) as half-spaces for ``two_view_locus``.
:func:`relative_pose`
    Sensor 1 in sensor 2's frame from two sensor poses in one world frame.
:func:`elevation_misalignment`
    How far each sensor's zero-elevation plane is from the other sensor.
:func:`three_view_points`
    The (at most two) points three range measurements allow, inside all three apertures.
:func:`multiview_points`, :func:`solve_ranges`
    A feature from N >= 3 views: closed-form start, batched Levenberg-Marquardt on the ranges,
    a status and a covariance for every feature.
:func:`flat_seafloor_points`, :func:`nearest_locus_points`
    The flat-seafloor baseline (slant-range correction) and the two-view locus point nearest
    a prior.
"""

from .aperture import Aperture
from .halfspaces import max_depth_half_space, sea_surface_half_space
from .locus import MAX_ARCS, LocusResult, LocusStatus, two_view_locus
from .multiview import RangeSolution, solve_ranges
from .multiview_points import MultiViewResult, MultiViewStatus, multiview_points
from .slant_range import TwoViewStatus, flat_seafloor_points, nearest_locus_points
from .misalignment import ElevationMisalignment, elevation_misalignment
from .poses import relative_pose
from .three_view_points import ThreeViewResult, ThreeViewStatus, three_view_points

__all__ = [
    "Aperture",
    "ElevationMisalignment",
    "LocusResult",
    "LocusStatus",
    "MAX_ARCS",
    "MultiViewResult",
    "MultiViewStatus",
    "RangeSolution",
    "TwoViewStatus",
    "ThreeViewResult",
    "ThreeViewStatus",
    "elevation_misalignment",
    "flat_seafloor_points",
    "multiview_points",
    "nearest_locus_points",
    "solve_ranges",
    "max_depth_half_space",
    "relative_pose",
    "sea_surface_half_space",
    "three_view_points",
    "two_view_locus",
]
