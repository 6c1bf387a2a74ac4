"""Numbers rounded to significant figures, and whether two numbers agree at a precision.

Shared by every chapter's prose and claims (the report layer's number formatting, the pose-space
claims, the ``answer`` command).
"""

from __future__ import annotations

import numpy as np


def round_sig(x, digits: int = 2):
    """Round to ``digits`` significant figures (array-friendly; 0 and NaN pass through).

    Parameters
    ----------
    x : float or array_like
        Values.
    digits : int
        Significant figures.

    Returns
    -------
    numpy.ndarray
        The rounded values (0-d for a scalar).
    """
    x = np.asarray(x, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        mag = np.where((x == 0) | ~np.isfinite(x), 0, np.floor(np.log10(np.abs(x))))
    scale = 10.0 ** (digits - 1 - mag)
    return np.where(np.isfinite(x), np.round(x * scale) / scale, x)


def agree_sig(a, b, digits: int = 2) -> np.ndarray:
    """Whether ``a`` and ``b`` are equal after rounding each to ``digits`` significant figures.

    Parameters
    ----------
    a, b : float or array_like
        Values compared (broadcast).
    digits : int
        Significant figures.

    Returns
    -------
    numpy.ndarray of bool
        Whether they agree at ``digits``.
    """
    return np.asarray(round_sig(a, digits) == round_sig(b, digits))
