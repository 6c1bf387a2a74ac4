"""How measurement errors spread the two- and three-view loci: the views perturbed by a
:class:`~sss_locus.experiments.datamodel.noise_model.NoiseModel` (whose module states the error
model), their Monte Carlo spread and the first-order propagation (shared by the noise chapter,
the three-view chapter's error ellipses and the reconstruction's estimators).

Spread of the locus (:func:`monte_carlo`)
-----------------------------------------
The locus is computed from the estimates and expressed in the world through the estimated pose
of sensor 1, exactly as a user would. For two views, per noise draw:

``circle_miss_m``
    distance from the true feature to the perturbed (uncropped) circle: the half-width of the
    band that the locus sweeps under noise, at the feature;
``near_m`` / ``far_m``
    distance from the true feature to the nearest / farthest point of the perturbed *cropped*
    locus (closed form on each arc); ``far_m`` is the worst error made by picking any point
    of the computed locus (without noise it is at most the locus length);
``empty``
    the perturbed locus is empty (the spheres miss, or the estimated apertures crop it away).

For three views: ``point_error_m``, the distance from the true feature to the nearest valid
candidate of :func:`sss_locus.geometry.three_view_points.three_view_points`, and ``lost`` (no valid candidate).

First-order estimate (:func:`first_order`)
------------------------------------------
The offset vector (true feature -> nearest perturbed circle point, or -> three-view point) is a
smooth function of the ``7 k`` standardised errors; its Jacobian by central differences gives
the covariance ``J J^T`` and from it the 95 % quantile of the offset's length
(:func:`~sss_locus.experiments.stats.gaussian_norm.gaussian_norm_quantile`, exact to about 1e-7), to
compare with the Monte Carlo percentile.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from sss_locus.geometry import Aperture, relative_pose, three_view_points, two_view_locus
from sss_locus.geometry.validation import check_memory
from sss_locus.experiments.datamodel.noise_model import NoiseModel
from sss_locus.experiments.stats.rowstats import nanquantile_rows
from sss_locus.experiments.passes.view_sets import Views

ERROR_NAMES = ("range", "x", "y", "z", "roll", "pitch", "heading")
"""The seven standardised errors of one view, in this order."""
_CHUNK = 20000
#: Memory one noise draw of one configuration takes in :func:`monte_carlo` (its errors and the
#: perturbed locus's arrays; 1.1-1.3 kB measured with tracemalloc), for the memory guard.
_BYTES_PER_DRAW = 1500
_MC_COLUMNS = {"two": ["circle_miss_q", "near_q", "far_q", "empty_fraction", "length_median_m", "length0_m",
                       "far0_m"], "three": ["point_error_q", "lost_fraction", "ambiguous_fraction", "n_valid0"]}


# --------------------------------------------------------------------------------------------
# Perturbation of world-frame views (sss_locus.experiments.passes.view_sets.Views)
# --------------------------------------------------------------------------------------------
def noise_sigmas(views: Views, noise: NoiseModel) -> np.ndarray:
    """Standard deviations of the seven errors of every view, shape (n, k, 7).

    Parameters
    ----------
    views : Views
        The configurations (their ranges set the range errors).
    noise : NoiseModel
        The error model.

    Returns
    -------
    numpy.ndarray, shape (n, k, 7)
        Standard deviations: range (metres), horizontal position (2, metres), vertical
        position (metres), roll, pitch and heading (radians).
    """
    n, k = views.origin.shape[:2]
    s = np.empty((n, k, 7))
    s[..., 0] = noise.range_sigma_m(views.ranges)
    s[..., 1:3] = noise.horizontal_sigma_m
    s[..., 3] = noise.vertical_sigma_m
    s[..., 4:] = np.radians([noise.roll_sigma_deg, noise.pitch_sigma_deg, noise.heading_sigma_deg])
    return s


def perturb(views: Views, sigmas: np.ndarray, errors: np.ndarray):
    """Estimated poses and ranges for standardised ``errors`` of shape (n, ..., k, 7).

    Returns ``W_hat`` (n, ..., k, 3, 3), ``origin_hat`` (n, ..., k, 3), ``r_hat`` (n, ..., k).

    Parameters
    ----------
    views : Views
        The true configurations.
    sigmas : numpy.ndarray, shape (n, k, 7)
        Standard deviations (:func:`noise_sigmas`).
    errors : numpy.ndarray, shape (n, ..., k, 7)
        Standardised errors.

    Returns
    -------
    W_hat : numpy.ndarray, shape (n, ..., k, 3, 3)
        Estimated transducer axes in the world.
    origin_hat : numpy.ndarray, shape (n, ..., k, 3)
        Estimated origins, metres.
    r_hat : numpy.ndarray, shape (n, ..., k)
        Estimated ranges, metres.
    """
    extra = errors.ndim - 3
    def ex(a, tail):  # (n, k) + tail -> (n, 1 ... 1, k) + tail
        return a.reshape(a.shape[:1] + (1,) * extra + a.shape[1:2] + tail)

    sig = ex(sigmas, (7,))
    d = errors * sig
    r_hat = ex(views.ranges, ()) + d[..., 0]
    o_hat = ex(views.origin, (3,)) + d[..., 1:4]
    rotvec = np.einsum("...ij,...j->...i", ex(views.vehicle, (3, 3)), d[..., 4:7])
    rot = Rotation.from_rotvec(rotvec.reshape(-1, 3)).as_matrix().reshape(rotvec.shape + (3,))
    W_hat = rot @ ex(views.W, (3, 3))
    return W_hat, o_hat, np.maximum(r_hat, 1e-9)


# --------------------------------------------------------------------------------------------
# Distances from the true feature to a perturbed locus
# --------------------------------------------------------------------------------------------
def _in_arcs(alpha, start, end):
    """Whether angle ``alpha`` (...) lies in any arc ``[start, end]`` (..., MAX_ARCS)."""
    with np.errstate(invalid="ignore"):
        inside = np.mod(alpha[..., None] - start, 2 * np.pi) <= (end - start)
    return np.any(inside & ~np.isnan(start), axis=-1)


def two_view_offsets(W_hat, o_hat, r_hat, feature, aperture: Aperture) -> dict:
    """Distances from the true ``feature`` to the locus computed from estimated views 1 and 2.

    Parameters: ``W_hat`` (..., 2, 3, 3), ``o_hat`` (..., 2, 3), ``r_hat`` (..., 2), ``feature``
    (..., 3) broadcastable. Returns ``circle_offset`` (..., 3) (world vector from the feature to
    the nearest point of the circle), ``circle_miss_m``, ``near_m``, ``far_m`` (NaN where the
    locus is empty), ``empty``, ``length_m``.

    Parameters
    ----------
    W_hat : numpy.ndarray, shape (..., 2, 3, 3)
        Estimated transducer axes of views 1 and 2.
    o_hat : numpy.ndarray, shape (..., 2, 3)
        Estimated origins, metres.
    r_hat : numpy.ndarray, shape (..., 2)
        Estimated ranges, metres.
    feature : numpy.ndarray, shape (..., 3)
        True feature in the world, metres.
    aperture : Aperture
        Both views' aperture.

    Returns
    -------
    dict of str to numpy.ndarray
        The quantities named above (metres; ``empty`` boolean).
    """
    R, t = relative_pose(W_hat[..., 0, :, :], o_hat[..., 0, :], W_hat[..., 1, :, :], o_hat[..., 1, :])
    loc = two_view_locus(R, t, r_hat[..., 0], r_hat[..., 1], aperture, aperture)
    W1 = W_hat[..., 0, :, :]
    f1 = np.einsum("...ji,...j->...i", W1, feature - o_hat[..., 0, :])
    d = f1 - loc.center
    h = np.sum(d * loc.normal, -1)
    a, b = np.sum(d * loc.basis1, -1), np.sum(d * loc.basis2, -1)
    rho_f, rho = np.hypot(a, b), loc.radius
    alpha_f = np.arctan2(b, a)
    safe = np.where(rho_f > 0, rho_f, 1.0)
    q1 = loc.center + (rho / safe)[..., None] * (a[..., None] * loc.basis1 + b[..., None] * loc.basis2)
    offset = np.einsum("...ij,...j->...i", W1, q1 - f1)
    miss = np.hypot(h, rho_f - rho)

    def dist(alpha):  # distance to the circle point at angle alpha (..., m)
        x = lambda v: v[..., None]  # noqa: E731
        return np.sqrt(np.maximum(x(h * h + rho_f**2 + rho**2)
                                  - x(2 * rho * rho_f) * np.cos(alpha - x(alpha_f)), 0.0))

    empty = loc.n_arcs == 0
    ends = np.concatenate([loc.arc_start, loc.arc_end], -1)
    with np.errstate(invalid="ignore"):
        de = dist(ends)
    end_min = np.nanmin(np.where(np.isnan(ends), np.inf, de), -1)
    end_max = np.nanmax(np.where(np.isnan(ends), -np.inf, de), -1)
    near = np.where(_in_arcs(alpha_f, loc.arc_start, loc.arc_end), miss, end_min)
    far = np.where(_in_arcs(alpha_f + np.pi, loc.arc_start, loc.arc_end), np.hypot(h, rho_f + rho), end_max)
    return dict(circle_offset=offset, circle_miss_m=miss, near_m=np.where(empty, np.nan, near),
                far_m=np.where(empty, np.nan, far), empty=empty, length_m=loc.length,
                exists=loc.exists)


def three_view_offsets(W_hat, o_hat, r_hat, feature, aperture: Aperture, *,
                       require_valid: bool = True) -> dict:
    """The three-view point from estimated views 1–3 against the true ``feature``.

    Returns ``point_offset`` (..., 3) (world vector feature -> nearest candidate, valid only
    if ``require_valid``; zeros where there is none), ``point_error_m`` (NaN where lost),
    ``lost``, ``n_valid``.

    Parameters
    ----------
    W_hat : numpy.ndarray, shape (..., 3, 3, 3)
        Estimated transducer axes of views 1 to 3.
    o_hat : numpy.ndarray, shape (..., 3, 3)
        Estimated origins, metres.
    r_hat : numpy.ndarray, shape (..., 3)
        Estimated ranges, metres.
    feature : numpy.ndarray, shape (..., 3)
        True feature in the world, metres.
    aperture : Aperture
        The views' aperture.
    require_valid : bool
        Take only candidates inside every aperture.

    Returns
    -------
    dict of str to numpy.ndarray
        The quantities named above (metres; ``lost`` boolean, ``n_valid`` integer).
    """
    W, o = W_hat, o_hat
    R12, t12 = relative_pose(W[..., 0, :, :], o[..., 0, :], W[..., 1, :, :], o[..., 1, :])
    R13, t13 = relative_pose(W[..., 0, :, :], o[..., 0, :], W[..., 2, :, :], o[..., 2, :])
    res = three_view_points(R12, t12, R13, t13, r_hat[..., 0], r_hat[..., 1], r_hat[..., 2],
                            aperture, aperture, aperture)
    world = np.einsum("...ij,...kj->...ki", W[..., 0, :, :], res.candidates) + o[..., 0, None, :]
    off = world - np.asarray(feature)[..., None, :]
    dist = np.linalg.norm(off, axis=-1)
    exists = np.stack([res.status <= 1, res.status == 0], -1)  # TWO_POINTS = 0, ONE_POINT = 1
    usable = res.valid if require_valid else exists
    dist = np.where(usable, dist, np.inf)
    pick = np.argmin(dist, -1)
    lost = ~np.any(usable, -1)
    best = np.take_along_axis(off, pick[..., None, None], -2)[..., 0, :]
    err = np.take_along_axis(dist, pick[..., None], -1)[..., 0]
    return dict(point_offset=np.where(lost[..., None], 0.0, best),
                point_error_m=np.where(lost, np.nan, err), lost=lost, n_valid=res.n_valid)


# --------------------------------------------------------------------------------------------
# Monte Carlo and first-order propagation
# --------------------------------------------------------------------------------------------
def _offsets(kind, views, sigmas, errors, aperture, **kw):
    W_hat, o_hat, r_hat = perturb(views, sigmas, errors)
    f = views.feature.reshape(views.feature.shape[:1] + (1,) * (errors.ndim - 3) + (3,))
    fun = two_view_offsets if kind == "two" else three_view_offsets
    return fun(W_hat, o_hat, r_hat, f, aperture, **kw)


def _check(views: Views, kind: str, aperture) -> int:
    if kind not in ("two", "three"):
        raise ValueError(f"kind must be 'two' or 'three'; got {kind!r}")
    k = views.origin.shape[1]
    if k != (2 if kind == "two" else 3):
        raise ValueError(f"views must hold {2 if kind == 'two' else 3} views for kind={kind!r}; got {k}")
    if not isinstance(aperture, Aperture):
        raise ValueError(f"aperture must be an sss_locus.Aperture; got {type(aperture).__name__}")
    return k


def monte_carlo(views: Views, noise: NoiseModel, aperture: Aperture, *, kind: str = "two",
                n_draws: int = 200, seed: int = 0, quantile: float = 0.95) -> pd.DataFrame:
    """Monte Carlo spread of the locus (``kind="two"``) or three-view point (``"three"``).

    One row per configuration. Two views: ``circle_miss_q``, ``near_q``, ``far_q`` (the
    ``quantile`` over draws; ``near``/``far`` over the draws whose locus is not empty),
    ``empty_fraction``, ``length_median_m``; plus the noise-free ``length0_m`` and ``far0_m``.
    Three views: ``point_error_q`` (over draws with a valid candidate), ``lost_fraction``,
    ``ambiguous_fraction`` (two valid candidates); plus the noise-free ``n_valid0``.

    Parameters
    ----------
    views : Views
        The true configurations.
    noise : NoiseModel
        The error model.
    aperture : Aperture
        The views' aperture.
    kind : {"two", "three"}
        Locus of views 1 and 2, or three-view point.
    n_draws : int
        Noisy draws per configuration.
    seed : int
        Seed.
    quantile : float
        Quantile taken over draws, in (0, 1).

    Returns
    -------
    pandas.DataFrame
        One row per configuration, the columns named above (metres, shares in [0, 1]).
    """
    k = _check(views, kind, aperture)
    if isinstance(n_draws, bool) or not isinstance(n_draws, (int, np.integer)) or n_draws < 2:
        raise ValueError(f"n_draws must be an integer >= 2; got {n_draws!r}")
    if not 0.0 < quantile < 1.0:
        raise ValueError(f"quantile must be in (0, 1); got {quantile!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer; got {seed!r}")
    rng = np.random.default_rng(seed)
    sig = noise_sigmas(views, noise)
    n = len(views.feature)
    step = max(1, _CHUNK // n_draws)
    check_memory(_BYTES_PER_DRAW * n_draws * min(step, max(n, 1)), f"monte_carlo(n_draws={n_draws})")
    if n == 0:  # no configuration: no rows
        return pd.DataFrame(columns=_MC_COLUMNS[kind])
    rows = []
    for i in range(0, n, step):
        sub = views.take(slice(i, i + step))
        e = rng.standard_normal((len(sub.feature), n_draws, k, 7))
        out = _offsets(kind, sub, sig[i:i + step], e, aperture)
        zero = _offsets(kind, sub, sig[i:i + step], np.zeros((len(sub.feature), 1, k, 7)), aperture)
        if kind == "two":
            rows.append(pd.DataFrame({
                "circle_miss_q": np.quantile(out["circle_miss_m"], quantile, axis=1),
                "near_q": nanquantile_rows(out["near_m"], quantile), "far_q": nanquantile_rows(out["far_m"], quantile),
                "empty_fraction": out["empty"].mean(axis=1),
                "length_median_m": np.median(out["length_m"], axis=1),
                "length0_m": zero["length_m"][:, 0], "far0_m": zero["far_m"][:, 0]}))
        else:
            rows.append(pd.DataFrame({
                "point_error_q": nanquantile_rows(out["point_error_m"], quantile),
                "lost_fraction": out["lost"].mean(axis=1),
                "ambiguous_fraction": (out["n_valid"] == 2).mean(axis=1),
                "n_valid0": zero["n_valid"][:, 0]}))
    return pd.concat(rows, ignore_index=True)


def first_order(views: Views, noise: NoiseModel, aperture: Aperture, *, kind: str = "two",
                step: float = 1e-3) -> np.ndarray:
    """Covariance (n, 3, 3) of the offset vector, to first order in the errors.

    Central differences in each of the ``7 k`` standardised errors (``+-step``): ``J J^T``.
    For ``kind="two"`` the offset is feature -> nearest point of the perturbed circle, for
    ``"three"`` feature -> nearest three-view candidate (the branch need not pass the aperture
    test: at first order the candidate stays put).

    Parameters
    ----------
    views : Views
        The true configurations.
    noise : NoiseModel
        The error model.
    aperture : Aperture
        The views' aperture.
    kind : {"two", "three"}
        The offset differentiated.
    step : float
        Step of the central differences, in standard deviations.

    Returns
    -------
    numpy.ndarray, shape (n, 3, 3)
        Covariance of the offset, square metres.
    """
    k = _check(views, kind, aperture)
    if isinstance(step, bool) or not isinstance(step, (int, float, np.integer, np.floating)) \
            or not (math.isfinite(step) and step > 0):
        raise ValueError(f"step must be a positive number; got {step!r}")
    sig = noise_sigmas(views, noise)
    n, m = len(views.feature), 7 * k
    e = np.zeros((n, 2 * m, k, 7))
    for j in range(m):
        e[:, 2 * j, j // 7, j % 7] = step
        e[:, 2 * j + 1, j // 7, j % 7] = -step
    key, kw = ("circle_offset", {}) if kind == "two" else ("point_offset", {"require_valid": False})
    off = _offsets(kind, views, sig, e, aperture, **kw)[key]  # (n, 2m, 3)
    J = (off[:, 0::2] - off[:, 1::2]) / (2 * step)  # (n, m, 3)
    return np.einsum("nmi,nmj->nij", J, J)
