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
    col = [R[..., :, i] for i in range(3)]
    orth_err = np.zeros(R.shape[:-2])
    for i in range(3):  # entries of R^T R, explicitly (much faster than matmul on 3x3 stacks)
        for j in range(i, 3):
            dot = col[i][..., 0] * col[j][..., 0] + col[i][..., 1] * col[j][..., 1] + col[i][..., 2] * col[j][..., 2]
            orth_err = np.maximum(orth_err, np.abs(dot - (1.0 if i == j else 0.0)))
    if np.any(orth_err > ROTATION_ATOL):
        raise ValueError(
            f"{name} must be a rotation matrix (orthonormal): max |{name}^T {name} - I| is "
            f"{orth_err.max():.3g}, allowed {ROTATION_ATOL:g}"
        )
    det = np.sum(R[..., 0, :] * np.cross(R[..., 1, :], R[..., 2, :]), axis=-1)
    if np.any(np.abs(det - 1.0) > ROTATION_ATOL):
        raise ValueError(
            f"{name} must be a proper rotation (determinant +1); found determinant "
            f"{det.flat[np.argmax(np.abs(det - 1.0))]:.6g} (a reflection?)"
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
