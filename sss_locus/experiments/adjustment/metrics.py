"""Errors of a map of features against the truth: absolute (horizontal, vertical) and map shape.

The ranges of a survey measure distances between sensors and features, so a common shift of
every feature (and every pass) is invisible to them; only the navigation holds it. The *map
shape* error separates what the geometry determines from what it cannot: the error of each
feature after removing the median error vector of all features (the median per axis, robust to
the few features a wrong match throws far).
"""

from __future__ import annotations

import numpy as np

from ...geometry.validation import as_float_array


def map_errors(estimate_m, truth_m, mask=None) -> dict[str, np.ndarray]:
    """Per-feature errors of an estimate (module docstring).

    Parameters
    ----------
    estimate_m, truth_m : array_like, shape (n, 3)
        Estimated and true positions, one world frame (``z`` up), metres.
    mask : array_like of bool, shape (n,), optional
        The features that count (default: all); the median error vector is taken over them.

    Returns
    -------
    dict
        ``horizontal_m`` (n,): horizontal distance; ``vertical_m`` (n,): estimate minus truth in
        ``z``; ``error_3d_m`` (n,); ``shape_m`` (n,): 3-D distance after removing the median
        error vector; ``shape_horizontal_m`` (n,): its horizontal part; ``median_error_m`` (3,):
        that vector. NaN outside ``mask``.
    """
    e = as_float_array(estimate_m, "estimate_m", tail=(3,), finite=False)
    t = as_float_array(truth_m, "truth_m", tail=(3,))
    if e.shape != t.shape or e.ndim != 2:
        raise ValueError(f"estimate_m and truth_m must have one shape (n, 3); got {e.shape}, {t.shape}")
    m = np.ones(len(e), bool) if mask is None else np.asarray(mask, bool)
    if m.shape != (len(e),):
        raise ValueError(f"mask must have shape ({len(e)},); got {m.shape}")
    if np.any(m & ~np.all(np.isfinite(e), axis=1)):
        raise ValueError("estimate_m must be finite wherever mask is True")
    d = np.where(m[:, None], e - t, np.nan)
    med = np.median(d[m], axis=0) if m.any() else np.full(3, np.nan)
    s = d - med
    return dict(horizontal_m=np.hypot(d[:, 0], d[:, 1]), vertical_m=d[:, 2], error_3d_m=np.linalg.norm(d, axis=1),
                shape_m=np.linalg.norm(s, axis=1), shape_horizontal_m=np.hypot(s[:, 0], s[:, 1]), median_error_m=med)
