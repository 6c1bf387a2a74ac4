"""Extra physical constraints on the locus: half-spaces ``n . p1 <= d`` in sensor 1's frame.

The sensors' apertures are not the only thing that bounds where a feature can be: it must be in
the water (below the sea surface) and, where the water depth is known, above the seafloor. Each
such constraint is a half-space of frame 1,

    n . p1 <= d        (n: (3,) normal, d: offset in metres times |n|),

and on the locus circle ``p1(alpha) = c + rho (cos(alpha) e1 + sin(alpha) e2)`` it becomes

    A cos(alpha) + B sin(alpha) + D >= 0,   A = -rho n.e1,  B = -rho n.e2,  D = d - n.c,

the same form as the aperture bounds, so :func:`~sss_locus.geometry.locus.two_view_locus` crops
the circle by them with the same exact interval arithmetic (:mod:`sss_locus.geometry.arcs`),
intersected with both apertures. Nothing is sampled.

Degenerate half-spaces (documented behaviour, tested in ``tests/geometry/test_locus_halfspaces.py``)
------------------------------------------------------------------------------------------
``n = 0``
    The condition is ``0 <= d``: vacuous (the whole circle) when ``d >= 0``, empty when
    ``d < 0``. A row of ``n = 0, d = 0`` therefore pads a ragged batch without effect.
Plane parallel to the circle's plane (``n`` along the circle's normal)
    ``n . p1`` is constant on the circle: the whole circle or nothing, by the sign of ``D``.
Plane tangent to the circle
    Exactly, the closed half-space keeps the whole circle when the circle lies inside it and
    touches the plane, and a single point (no length) when the circle lies outside and touches
    it. Computed, the tangency is decided by the rounded coefficients, and near ``-D/M = ±1``
    the arc half-width ``arccos(-D/M)`` turns a relative rounding error ``e`` into about
    ``sqrt(2 e)`` rad: a gap or an arc of up to a few 1e-8 rad (about 3e-7 m on a circle of
    radius 8.7 m in ``tests/geometry/test_locus_halfspaces.py``) can appear at the point of tangency.
    No tolerance snaps it away, as for the aperture bounds; configurations exactly tangent to
    a plane have probability zero in the Monte Carlo studies.
Circle wholly outside
    ``length`` 0 and ``n_arcs`` 0; the ``status`` still describes the two spheres
    (``CIRCLE``): it says whether a circle exists, the length says how much of it is allowed.

World frame of the helpers
--------------------------
The helpers take sensor 1's sensor-to-world rotation in a world frame with ``z`` up (the
frame of :mod:`sss_locus.experiments.datamodel.platforms` and :func:`sss_locus.relative_pose`); only the
world's vertical matters. ``up = W^T e_z`` (the third row of ``W``) is the vertical in frame 1,
so a point ``p1`` lies ``up . p1`` metres above sensor 1.
"""

from __future__ import annotations

import numpy as np

from .validation import (LENGTH_MAX, as_float_array, as_rotation_matrices, broadcast_leading,
                         check_max_abs)

MAX_HALF_SPACES = 32
"""Most half-spaces per configuration (the arc arrangement counts boundaries in bytes)."""


def as_half_spaces(normals, offsets) -> tuple[np.ndarray, np.ndarray]:
    """Validate half-spaces ``n . p1 <= d`` and broadcast their ``K`` axes together.

    Parameters
    ----------
    normals : array_like, shape S_n + (K, 3)
        Normals ``n`` in sensor 1's frame (any non-negative length; ``n = 0`` is allowed).
    offsets : array_like, shape S_d + (K,) or S_d + (1,)
        Offsets ``d`` (m times ``|n|``), each in [-1e150, 1e150].

    Returns
    -------
    normals : ndarray, shape S_n + (K_n, 3)
        Each nonzero normal divided by its largest absolute component (so in [-1, 1], one
        component of magnitude 1); zero normals stay zero.
    offsets : ndarray, shape broadcast(S_n, S_d) + (K,)
        The offsets divided by the same factor (the half-space is unchanged); may be infinite
        where a tiny normal meets a large offset (then the half-space is all or nothing).

    Raises
    ------
    TypeError, ValueError
        Naming ``half_space_normals`` or ``half_space_offsets``: non-real or non-finite
        values, wrong trailing shapes, ``K`` axes that do not broadcast, more than
        :data:`MAX_HALF_SPACES` half-spaces, an offset beyond 1e150 m.
    """
    n = as_float_array(normals, "half_space_normals", tail=(3,))
    if n.ndim < 2:
        raise ValueError(f"half_space_normals must have shape (..., K, 3); got shape {n.shape}")
    d = as_float_array(offsets, "half_space_offsets")
    if d.ndim < 1:
        raise ValueError(f"half_space_offsets must have shape (..., K); got shape {d.shape}")
    check_max_abs(d, "half_space_offsets")
    try:
        (k,) = np.broadcast_shapes(n.shape[-2:-1], d.shape[-1:])
    except ValueError:
        raise ValueError(
            f"half_space_normals (..., K, 3) and half_space_offsets (..., K) must have the same "
            f"number K of half-spaces; got {n.shape[-2]} and {d.shape[-1]}") from None
    if k > MAX_HALF_SPACES:
        raise ValueError(f"at most {MAX_HALF_SPACES} half-spaces per configuration; got K = {k}")
    big = np.abs(n).max(axis=-1)
    scale = np.where(big > 0.0, big, 1.0)
    n = n / scale[..., None]
    with np.errstate(over="ignore"):  # |d| / tiny |n|: an infinite offset is exactly right
        d = d / scale
    return n, d


def _vertical(rotation, depth_m, depth_name):
    """``up`` (frame 1) and the validated depth, broadcast to one batch shape ``S``."""
    W = as_rotation_matrices(rotation, "rotation")
    depth = as_float_array(depth_m, depth_name)
    check_max_abs(depth, depth_name, LENGTH_MAX)
    shape = broadcast_leading({"rotation": W.shape[:-2], depth_name: depth.shape})
    up = np.broadcast_to(W[..., 2, :], shape + (3,))
    return up, np.broadcast_to(depth, shape)


def sea_surface_half_space(depth_m, rotation) -> tuple[np.ndarray, np.ndarray]:
    """The water below the sea surface, as a half-space of sensor 1's frame.

    Parameters
    ----------
    depth_m : array_like, shape S_1
        Depth (m) of sensor 1's origin below the sea surface (>= 0; a transducer in the water).
    rotation : array_like, shape S_2 + (3, 3), or scipy.spatial.transform.Rotation
        Sensor 1's sensor-to-world rotation (columns: its axes in a world frame with ``z`` up),
        e.g. from ``Transducer.world_pose``; carries the vehicle's pitch and roll.

    Returns
    -------
    normals : ndarray, shape S + (1, 3)
        ``up``, the world's vertical in frame 1 (``S``: ``S_1`` and ``S_2`` broadcast).
    offsets : ndarray, shape S + (1,)
        ``depth_m``: the half-space ``up . p1 <= depth_m`` is ``z_world <= z_surface``.
        Pass both to ``two_view_locus(..., half_space_normals=, half_space_offsets=)``.

    Examples
    --------
    >>> import numpy as np
    >>> n, d = sea_surface_half_space(2.0, np.eye(3))  # sensor 1 level, 2 m deep
    >>> n.tolist(), d.tolist()
    ([[0.0, 0.0, 1.0]], [2.0])
    """
    up, depth = _vertical(rotation, depth_m, "depth_m")
    if depth.size and depth.min() < 0.0:
        raise ValueError(f"depth_m must be >= 0 m (sensor 1 in the water); got {depth.min():.6g}")
    return up[..., None, :].copy(), depth[..., None].copy()


def max_depth_half_space(water_depth_m, depth_m, rotation) -> tuple[np.ndarray, np.ndarray]:
    """The water above a known maximum depth (the seafloor), as a half-space of frame 1.

    Parameters
    ----------
    water_depth_m : array_like, shape S_0
        Greatest depth (m) below the sea surface a feature can have (the water depth), > 0.
    depth_m : array_like, shape S_1
        Depth (m) of sensor 1's origin below the sea surface, in [0, ``water_depth_m``).
    rotation : array_like, shape S_2 + (3, 3), or scipy.spatial.transform.Rotation
        Sensor 1's sensor-to-world rotation (world ``z`` up), as for
        :func:`sea_surface_half_space`.

    Returns
    -------
    normals : ndarray, shape S + (1, 3)
        ``-up`` (``S``: the three batch shapes broadcast).
    offsets : ndarray, shape S + (1,)
        ``water_depth_m - depth_m``: the half-space ``-up . p1 <= water_depth_m - depth_m`` is
        ``z_world >= z_surface - water_depth_m``.
    """
    water = as_float_array(water_depth_m, "water_depth_m")
    check_max_abs(water, "water_depth_m", LENGTH_MAX)
    up, depth = _vertical(rotation, depth_m, "depth_m")
    shape = broadcast_leading({"water_depth_m": water.shape, "depth_m and rotation": depth.shape})
    water, depth, up = (np.broadcast_to(water, shape), np.broadcast_to(depth, shape),
                        np.broadcast_to(up, shape + (3,)))
    if water.size and water.min() <= 0.0:
        raise ValueError(f"water_depth_m must be > 0 m; got {water.min():.6g}")
    if depth.size and (depth.min() < 0.0 or np.any(depth >= water)):
        raise ValueError("depth_m must lie in [0, water_depth_m) (sensor 1 in the water, above "
                         f"the seafloor); got depth_m {depth.min():.6g}..{depth.max():.6g} m")
    return -up[..., None, :], (water - depth)[..., None].copy()
