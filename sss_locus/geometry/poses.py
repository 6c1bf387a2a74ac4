"""Relative pose of two sensors from their world poses."""

from __future__ import annotations

import numpy as np

from .validation import as_float_array, as_rotation_matrices, broadcast_leading


def relative_pose(rotation_a, origin_a, rotation_b, origin_b) -> tuple[np.ndarray, np.ndarray]:
    """Relative pose ``(R, t)`` with ``p_b = R p_a + t`` from two sensors' world poses.

    Parameters
    ----------
    rotation_a, rotation_b : array_like, shape (..., 3, 3), or scipy.spatial.transform.Rotation
        Sensor-to-world rotations (columns are the sensor axes in the world frame).
    origin_a, origin_b : array_like, shape (..., 3)
        Sensor origins in the world frame (m): finite real numbers (Python or NumPy ints and
        floats, or arrays of them) whose difference ``origin_a - origin_b`` is finite.

    The batch shapes (shapes without the trailing ``(3, 3)`` or ``(3,)``) of the four arguments
    broadcast together to ``S``, which may be empty.

    Returns
    -------
    R : ndarray, shape S + (3, 3)
        ``Rb^T Ra``.
    t : ndarray, shape S + (3,)
        ``Rb^T (oa - ob)``.

    Raises
    ------
    TypeError
        (:class:`~sss_locus.geometry.validation.InputTypeError`, also a ``ValueError``) naming
        the argument given as booleans, complex numbers, strings, dates or timedeltas, ``None``
        or an object array.
    ValueError
        Naming the argument(s): a rotation that is not proper (to 1e-9), a non-finite value, a
        wrong trailing shape, batch shapes that do not broadcast, or origins whose difference
        overflows float64.
    """
    Ra = as_rotation_matrices(rotation_a, "rotation_a")
    Rb = as_rotation_matrices(rotation_b, "rotation_b")
    oa = as_float_array(origin_a, "origin_a", tail=(3,))
    ob = as_float_array(origin_b, "origin_b", tail=(3,))
    shape = broadcast_leading({"rotation_a": Ra.shape[:-2], "origin_a": oa.shape[:-1],
                               "rotation_b": Rb.shape[:-2], "origin_b": ob.shape[:-1]})
    with np.errstate(over="ignore", invalid="ignore"):
        d = oa - ob
    if not np.all(np.isfinite(d)):
        raise ValueError(
            "origin_a - origin_b overflows float64 (components beyond about 1.8e308 m); "
            "origins must differ by a representable amount"
        )
    R = np.einsum("...ji,...jk->...ik", Rb, Ra)
    t = np.einsum("...ji,...j->...i", Rb, d)
    return np.broadcast_to(R, shape + (3, 3)).copy(), np.broadcast_to(t, shape + (3,)).copy()
