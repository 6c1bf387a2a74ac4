"""Elevation misalignment between two sensor poses (the paper's Sec. IV-B)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .validation import as_float_array, as_rotation_matrices, broadcast_leading, row_exponents


class ElevationMisalignment(NamedTuple):
    """Elevation angles of the baseline in each sensor's frame, degrees.

    Attributes
    ----------
    psi1_deg, psi2_deg : ndarray
        Elevation, in sensor 1's (sensor 2's) own frame, of the direction from that sensor's
        origin towards the other sensor's origin: ``arcsin(z / |.|)`` of ``-R^T t`` in frame 1
        and of ``t`` in frame 2. Signed: positive when the other sensor lies above the sensor's
        own ``xy`` plane.
    misalignment_deg : ndarray
        ``max(|psi1|, |psi2|)``, in [0, 90]. The paper uses ``max(psi1, psi2)`` of the line
        through both origins; a line has no sign, so magnitudes are compared.
    defined : ndarray of bool
        False where the two origins coincide (no baseline); there the three angles are NaN.
    """

    psi1_deg: np.ndarray
    psi2_deg: np.ndarray
    misalignment_deg: np.ndarray
    defined: np.ndarray


def elevation_misalignment(R, t) -> ElevationMisalignment:
    """Elevation misalignment of two sensor poses related by ``p2 = R p1 + t``.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3), or scipy.spatial.transform.Rotation
        Rotation from sensor-1 to sensor-2 coordinates.
    t : array_like, shape (..., 3)
        Translation (m); sensor 1's origin in frame 2 is ``t``, sensor 2's origin in frame 1 is
        ``-R^T t``. Finite real numbers of any magnitude (the angles are computed at a
        power-of-two scale where ``|t|^2`` would overflow or underflow).

    Returns
    -------
    ElevationMisalignment
        Batch shape is the broadcast of ``R``'s and ``t``'s batch shapes (may be empty).

    Raises
    ------
    TypeError
        (:class:`~sss_locus.geometry.validation.InputTypeError`, also a ``ValueError``) naming
        ``R`` or ``t`` given as booleans, complex numbers, strings, dates or timedeltas, ``None``
        or an object array.
    ValueError
        Naming the argument: ``R`` not a proper rotation (to 1e-9), a non-finite value, a wrong
        trailing shape, or batch shapes that do not broadcast.
    """
    R = as_rotation_matrices(R, "R")
    t = as_float_array(t, "t", tail=(3,))
    shape = broadcast_leading({"R": R.shape[:-2], "t": t.shape[:-1]})
    R = np.broadcast_to(R, shape + (3, 3))
    t = np.broadcast_to(t, shape + (3,))
    e = row_exponents(t[..., 0], t[..., 1], t[..., 2])
    if e is not None:  # angles are scale-free: a power-of-two scale keeps |t|^2 representable
        t = np.ldexp(t, -e[..., None])
    to_2_in_1 = -np.einsum("...ji,...j->...i", R, t)
    baseline = np.linalg.norm(t, axis=-1)
    defined = baseline > 0.0
    safe = np.where(defined, baseline, 1.0)
    psi1 = np.degrees(np.arcsin(np.clip(to_2_in_1[..., 2] / safe, -1.0, 1.0)))
    psi2 = np.degrees(np.arcsin(np.clip(t[..., 2] / safe, -1.0, 1.0)))
    psi1 = np.where(defined, psi1, np.nan)
    psi2 = np.where(defined, psi2, np.nan)
    mis = np.where(defined, np.maximum(np.abs(psi1), np.abs(psi2)), np.nan)
    return ElevationMisalignment(psi1, psi2, mis, defined)
