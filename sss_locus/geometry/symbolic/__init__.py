"""Symbolic (SymPy) derivation of the two-view sidescan locus.

This module re-derives, as exact symbolic identities, every formula the
numeric kernel (:mod:`sss_locus.geometry.locus`, :mod:`sss_locus.geometry.arcs`) evaluates:

* :func:`derive_plane` -- the plane ``2 (R^T t)^T p1 = r2^2 - r1^2 - |t|^2``
  from the two range spheres (paper, Sec. III, eq. (plane));
* :func:`derive_circle` -- centre ``C u / (2 |u|^2)``, radius
  ``sqrt(r1^2 - C^2 / (4 |u|^2))``, the existence condition
  ``C^2 <= 4 |u|^2 r1^2`` and ``|u| = |t|``;
* :func:`derive_one_angle` -- the paper's one-angle form (eq. (onelocus)) and
  its closed-form solutions for ``phi1`` given ``theta1`` and vice versa;
* :func:`derive_scaling` -- the scaling law ``(r1, r2, t) -> k (r1, r2, t)``;
* :func:`derive_crop` -- an affine half-space ``a . p + b >= 0`` restricted to
  the circle becomes ``A cos(alpha) + B sin(alpha) + D >= 0``, with boundary
  angles ``alpha0 +- arccos(-D / hypot(A, B))``, ``alpha0 = atan2(B, A)``;
  :func:`elevation_halfspaces`, :func:`azimuth_halfspaces` and
  :func:`halfspace_in_frame1` give the aperture bounds in that form;
* :func:`derive_range_jacobian` -- the gradient of the weighted range residual
  ``(|p - o| - rho) / sigma`` of the N-view reconstruction, the unit line of
  sight over ``sigma`` (:mod:`.range_residuals`), and
  :func:`kernel_jacobian_discrepancy`, its check against the kernel.

Each ``derive_*`` function returns ``(result, steps)``: ``result`` is a dict
of the final SymPy expressions, ``steps`` an ordered dict of intermediate
expressions (for display in ``notebooks/derivation.ipynb``), including
``residual`` entries that :func:`sympy.simplify` reduces to exactly 0 when
the derivation holds.  Rotations are treated generally in two ways: as a
3x3 matrix of free symbols with the orthonormality ``R^T R = I`` applied as
an explicit substitution (the paper's route), and as the rotation of a
non-zero quaternion ``q``, ``R(q) = M(q) / |q|^2``, which is a proper
rotation for every ``q != 0`` and reaches every rotation, so identities in
``q`` hold over all of SO(3) with no side condition.

Frames and units follow the package: sensor frame x boresight, y left,
z up; ``p2 = R p1 + t``; lengths in metres, angles in radians.

SymPy is imported here only; ``sss_locus/__init__.py`` does not import this
module (SymPy is an optional ``book`` dependency).
"""
from __future__ import annotations

from .derivation import (
    azimuth_halfspaces,
    derive_circle,
    derive_crop,
    derive_one_angle,
    derive_plane,
    derive_scaling,
    elevation_halfspaces,
    halfspace_in_frame1,
    quaternion_rotation,
    symbols,
)
from .numeric import kernel_discrepancy, numeric_functions
from .range_residuals import derive_range_jacobian, kernel_jacobian_discrepancy, numeric_range_jacobian

__all__ = [
    "symbols",
    "quaternion_rotation",
    "derive_plane",
    "derive_circle",
    "derive_one_angle",
    "derive_scaling",
    "derive_crop",
    "elevation_halfspaces",
    "azimuth_halfspaces",
    "halfspace_in_frame1",
    "numeric_functions",
    "kernel_discrepancy",
    "derive_range_jacobian",
    "numeric_range_jacobian",
    "kernel_jacobian_discrepancy",
]
