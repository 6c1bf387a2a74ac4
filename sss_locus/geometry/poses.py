"""Relative pose of two sensors from their world poses."""

from __future__ import annotations

import numpy as np

from .validation import as_float_array, as_rotation_matrices


def relative_pose(rotation_a, origin_a, rotation_b, origin_b) -> tuple[np.ndarray, np.ndarray]:
    """Relative pose ``(R, t)`` with ``p_b = R p_a + t`` from two sensors' world poses.

    Parameters
    ----------
    rotation_a, rotation_b : array_like, shape (..., 3, 3)
        Sensor-to-world rotations (columns are the sensor axes in the world frame).
    origin_a, origin_b : array_like, shape (..., 3)
        Sensor origins in the world frame (m).

    Returns
    -------
    R : ndarray, shape (..., 3, 3)
        ``Rb^T Ra``.
    t : ndarray, shape (..., 3)
        ``Rb^T (oa - ob)``.
    """
    Ra = as_rotation_matrices(rotation_a, "rotation_a")
    Rb = as_rotation_matrices(rotation_b, "rotation_b")
    oa = as_float_array(origin_a, "origin_a", tail=(3,))
    ob = as_float_array(origin_b, "origin_b", tail=(3,))
    R = np.einsum("...ji,...jk->...ik", Rb, Ra)
    t = np.einsum("...ji,...j->...i", Rb, oa - ob)
    return R, t
