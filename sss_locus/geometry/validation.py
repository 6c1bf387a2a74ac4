"""Input validation shared by the kernels.

Every public kernel converts its inputs through these helpers so that bad input fails early with
a ``ValueError`` that names the argument and the allowed range, instead of surfacing later as a
NaN or a traceback from inside numpy.
"""

from __future__ import annotations

import numpy as np

ROTATION_ATOL = 1e-9
"""Tolerance on ``max |R^T R - I|`` and ``|det R - 1|`` for a matrix to count as a rotation."""


def as_float_array(value, name: str, *, tail: tuple[int, ...] = ()) -> np.ndarray:
    """Return ``value`` as a finite float64 array whose trailing dimensions are ``tail``."""
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a real numeric array; got {type(value).__name__}") from exc
    if tail and (arr.ndim < len(tail) or arr.shape[arr.ndim - len(tail):] != tail):
        want = "(..., " + ", ".join(str(n) for n in tail) + ")"
        raise ValueError(f"{name} must have shape {want}; got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(
            f"{name} must be finite; found NaN or infinity at index {tuple(int(i) for i in bad)}"
        )
    return arr


def as_positive_array(value, name: str) -> np.ndarray:
    """Return ``value`` as a finite float64 array of strictly positive numbers."""
    arr = as_float_array(value, name)
    if np.any(arr <= 0.0):
        raise ValueError(f"{name} must be > 0 (a measured range in metres); got min {arr.min()!r}")
    return arr


def as_rotation_matrices(value, name: str = "R") -> np.ndarray:
    """Return rotation matrices of shape ``(..., 3, 3)``.

    Accepts a ``scipy.spatial.transform.Rotation`` (single or stacked) or an array. A matrix must
    be orthonormal with determinant +1 to within :data:`ROTATION_ATOL`.
    """
    if hasattr(value, "as_matrix") and callable(value.as_matrix):
        value = value.as_matrix()
    R = as_float_array(value, name, tail=(3, 3))
    # Entries as nine contiguous rows, m[3 * row + column], so every product below runs over
    # one long row (much faster than matmul or einsum on stacks of 3x3 matrices).
    m = np.ascontiguousarray(R.reshape(-1, 9).T)
    orth_err = np.zeros(m.shape[1])
    for i in range(3):  # entries (i, j) of R^T R: dot products of columns i and j
        for j in range(i, 3):
            dot = m[i] * m[j] + m[3 + i] * m[3 + j] + m[6 + i] * m[6 + j]
            np.maximum(orth_err, np.abs(dot - (1.0 if i == j else 0.0)), out=orth_err)
    if np.any(orth_err > ROTATION_ATOL):
        raise ValueError(
            f"{name} must be a rotation matrix (orthonormal): max |{name}^T {name} - I| is "
            f"{orth_err.max():.3g}, allowed {ROTATION_ATOL:g}"
        )
    det = (m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6])
           + m[2] * (m[3] * m[7] - m[4] * m[6]))
    if np.any(np.abs(det - 1.0) > ROTATION_ATOL):
        raise ValueError(
            f"{name} must be a proper rotation (determinant +1); found determinant "
            f"{det[np.argmax(np.abs(det - 1.0))]:.6g} (a reflection?)"
        )
    return R


def broadcast_leading(named_shapes: dict[str, tuple[int, ...]]) -> tuple[int, ...]:
    """Broadcast the leading (batch) shapes of several arguments, naming them on failure."""
    try:
        return np.broadcast_shapes(*named_shapes.values())
    except ValueError:
        desc = ", ".join(f"{k} {v}" for k, v in named_shapes.items())
        raise ValueError(
            f"the batch shapes of the arguments do not broadcast together: {desc} "
            "(batch shape = shape without the trailing vector/matrix dimensions)"
        ) from None
