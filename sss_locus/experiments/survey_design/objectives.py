"""What a survey plan buys: the two-view locus, three-view closure and reconstruction error of
features seen by its lines (the objectives of the survey design).

Per feature (views and ``seen`` from :func:`~sss_locus.experiments.survey_design.coverage.observe_lines`):

``best pair`` (:func:`pair_loci`)
    among every pair of lines that see the feature, the pair with the shortest two-view locus
    (:func:`~sss_locus.geometry.two_view_locus`, noise-free, both apertures the platform's): the
    constraint the best two views give. Its length and the crossing angle of that pair (the
    heading difference folded into [0, 180] degrees) are returned; NaN for a feature seen by
    fewer than two lines. (An open choice, named ``pair_rule = "best"``: a user who pairs views
    arbitrarily would see the median over all pairs, longer.)
``three-view closure`` (:func:`three_view_closure`)
    whether some triple of lines that see the feature resolves it to one point
    (:func:`~sss_locus.geometry.three_view_points`, ``resolved``: exactly one candidate inside
    the three apertures). At most :data:`MAX_TRIPLES` triples per feature are tried, in line
    order (the first lines of the plan first).
``reconstruction`` (:func:`reconstruction_errors`)
    the reconstruction chapter's estimators under the noise model
    (:func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`): the 3-D error of the N-view
    least-squares estimate from every view (``all``) and of the two-view estimate (``two``).
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

from sss_locus.geometry import relative_pose, three_view_points, two_view_locus
from sss_locus.experiments.reconstruction.estimators import reconstruct
from sss_locus.experiments.passes.view_sets import Views

MAX_TRIPLES = 20
PAIR_RULES = ("best",)


def _pairs(seen: np.ndarray, k: int, cap: int | None = None):
    """Rows ``(feature, line_1, ..., line_k)`` of every k-subset of the lines seeing each feature
    (at most ``cap`` per feature, in line order), ordered by the lines' subset, then the feature.
    Built per feature from the lines that see it, so the cost grows with the views, not with the
    number of k-subsets of all lines."""
    rows = []
    for f in range(seen.shape[0]):
        combos = itertools.combinations(np.flatnonzero(seen[f]).tolist(), k)
        rows += [(f, *c) for c in (itertools.islice(combos, cap) if cap is not None else combos)]
    if not rows:
        return np.zeros((0, k + 1), np.int64)
    out = np.asarray(rows, np.int64)
    return out[np.lexsort((out[:, 0], *(out[:, j] for j in range(k, 0, -1))))]


def pair_loci(views: Views, seen, aperture, heading_deg) -> pd.DataFrame:
    """Best-pair locus per feature (module docstring): ``n_seen``, ``locus_length_m``,
    ``crossing_angle_deg`` (NaN where ``n_seen < 2``).

    Parameters
    ----------
    views : Views
        The views, shape (n, L).
    seen : array_like
        Boolean (n, L).
    aperture : Aperture
        The sonar's beam aperture.
    heading_deg : array_like
        Heading per line, degrees, shape (L,).

    Returns
    -------
    pandas.DataFrame
        n rows: ``n_seen``, ``locus_length_m`` (m), ``crossing_angle_deg`` (in [0, 180]).
    """
    seen = np.asarray(seen, bool)
    n = seen.shape[0]
    best = np.full(n, np.inf)
    angle = np.full(n, np.nan)
    rows = _pairs(seen, 2)
    if len(rows):
        f, i, j = rows.T
        R, t = relative_pose(views.W[f, i], views.origin[f, i], views.W[f, j], views.origin[f, j])
        r = views.ranges
        length = two_view_locus(R, t, r[f, i], r[f, j], aperture, aperture, outputs="lengths").length
        order = np.lexsort((length, f))  # per feature, shortest first
        first = order[np.r_[True, f[order][1:] != f[order][:-1]]]
        best[f[first]] = length[first]
        h = np.asarray(heading_deg, float)
        d = np.abs((h[j[first]] - h[i[first]] + 180.0) % 360.0 - 180.0)
        angle[f[first]] = d
    n_seen = seen.sum(axis=1)
    return pd.DataFrame({"n_seen": n_seen, "locus_length_m": np.where(n_seen >= 2, best, np.nan),
                         "crossing_angle_deg": angle})


def three_view_closure(views: Views, seen, aperture) -> np.ndarray:
    """Per feature: True where some triple of its lines resolves it (module docstring).

    Parameters
    ----------
    views : Views
        The views, shape (n, L).
    seen : array_like
        Boolean (n, L).
    aperture : Aperture
        The sonar's beam aperture.

    Returns
    -------
    numpy.ndarray
        Boolean, shape (n,); False for features seen fewer than three times.
    """
    seen = np.asarray(seen, bool)
    out = np.zeros(seen.shape[0], bool)
    rows = _pairs(seen, 3, MAX_TRIPLES)
    if len(rows):
        f, a, b, c = rows.T
        W, o, r = views.W, views.origin, views.ranges
        R12, t12 = relative_pose(W[f, a], o[f, a], W[f, b], o[f, b])
        R13, t13 = relative_pose(W[f, a], o[f, a], W[f, c], o[f, c])
        res = three_view_points(R12, t12, R13, t13, r[f, a], r[f, b], r[f, c], aperture, aperture, aperture)
        np.logical_or.at(out, f, res.resolved)
    return out


def reconstruction_errors(views: Views, seen, sensor_height_m, noise, aperture, seed: int) -> pd.DataFrame:
    """Per feature, the 3-D error of the ``all`` and ``two`` estimates under ``noise`` (NaN where
    not estimated): columns ``error_all_m``, ``error_two_m``. A plan of fewer than three segments
    is padded with unseen copies of its last segment (the estimators index three views), so a
    one-segment plan estimates nothing (every feature NaN) and a two-segment plan no ``all``.

    Parameters
    ----------
    views : Views
        The views, shape (n, L).
    seen : array_like
        Boolean (n, L).
    sensor_height_m : array_like
        Sensor heights above the seafloor, m, shape (n, L) or broadcastable.
    noise : NoiseModel
        The noise model.
    aperture : Aperture
        The sonar's beam aperture.
    seed : int
        Seed of the noise.

    Returns
    -------
    pandas.DataFrame
        n rows: ``error_all_m``, ``error_two_m``, m.
    """
    seen = np.asarray(seen, bool)
    if seen.shape[1] < 3:
        pad = [seen.shape[1] - 1] * (3 - seen.shape[1])
        views = views.select(*range(seen.shape[1]), *pad)
        seen = np.concatenate([seen, np.zeros((seen.shape[0], len(pad)), bool)], axis=1)
        sensor_height_m = np.asarray(sensor_height_m)
        if sensor_height_m.ndim == 2:
            sensor_height_m = sensor_height_m[:, list(range(sensor_height_m.shape[1])) + pad]
    table = reconstruct(views, seen, sensor_height_m, noise, aperture, n_views=(3,), seed=seed)
    pick = lambda name: table.loc[table.estimator == name, "error_3d_m"].to_numpy()  # noqa: E731
    return pd.DataFrame({"error_all_m": pick("all"), "error_two_m": pick("two")})
