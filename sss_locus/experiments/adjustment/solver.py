"""The joint adjustment (acoustic bundle adjustment): every feature and every pass's navigation
correction estimated together from all slant ranges, the beam-plane constraints and the
navigation priors.

Why a joint adjustment
----------------------
Many features seen from the same pair of passes all measure the same navigation error of those
passes; estimated feature by feature (fixed poses), that error stays in every feature; estimated
together, it is largely removed. What the sightings cannot see, a common shift (and turn) of
every pass and every feature together, is held by the navigation priors only: absolute position
stays as good as the navigation, the *shape* of the map (positions after removing the median
error vector, :func:`~sss_locus.experiments.adjustment.metrics.map_errors`) gets much better.

Solver: ``scipy.optimize.least_squares``, chosen by measurement
----------------------------------------------------------------
Trust-region reflective (``method="trf"``) with the analytic sparse Jacobian of
:class:`~sss_locus.experiments.adjustment.residuals.JointProblem`, ``tr_solver="lsmr"`` (tight
inner tolerances, :data:`LSMR_TOL`) and ``x_scale="jac"``; a quadratic-loss stage from the start,
then the robust loss from its solution. The alternative of the field, GTSAM (``gtsam`` 4.3 on
PyPI, which installs for Python 3.11 here), was measured on the same problem and residuals in
``benchmarks/bench_adjustment.py``: no built-in GTSAM factor holds a sidescan slant range with a
beam-plane angle and a pass-level heading bias, so its factors are Python ``CustomFactor``
callbacks (one call per sighting per linearisation). At survey scale (100 passes, 50,000
features, 291,486 sightings, one core) ``least_squares`` took 10 CPU s (quadratic loss) and
16 CPU s (with ``soft_l1``; 16 s wall on a quiet core), peak memory 0.9-1.0 GB; GTSAM's Gauss-Newton over its own
linearisation and sparse elimination took 72 CPU s plus 23 s to build the graph, to the same
optimum (map-shape error 0.198 m for both), and its own Levenberg-Marquardt optimiser was slower
still (15-25 s per iteration already at 10,000 sightings). ``least_squares`` is also already a
dependency, vectorises the residuals in numpy, gives the robust losses and their weights
directly, and keeps a 34 MB binary package out of the lock (numbers and commands in
``benchmarks/README.md``).

Wrong matches: a gate, then a robust loss
-----------------------------------------
Wrong data associations (a sighting attributed to the wrong feature) give residuals of tens or
hundreds of metres. First a *gate*: a sighting that misses the start by more than ``gate_m``
(:func:`misses_m`: its range or beam-plane miss in metres; default :func:`default_gate_m`, ten
metres plus five times the navigation priors) is left out, and taken back if it misses the
solution by less. Then ``loss`` (default ``"soft_l1"``, scale ``f_scale`` in sigmas) on the
sightings' rows only; the navigation priors stay quadratic. A sighting whose robust weight
``rho'`` at the optimum is below :data:`DOWNWEIGHT_BELOW` on its range or beam-plane row, or that
was gated, is reported as *down-weighted* (``JointAdjustment.downweighted``, ``.gated``).
Measured (``benchmarks/README.md``, 20 passes, 5,000 features, start the median of each
feature's flat-seafloor positions; a wrong match moves their mean): without the gate,
``least_squares``' one trust region for all unknowns crawls when some features start tens of
metres off and did not converge at 2 % of wrong matches, robust loss or not; with the gate and
the robust loss, 2 % and 5 % of wrong matches were all flagged and the map shape stayed within
0.12 m of the clean survey's; at 10 % it did not converge in 200 evaluations (shape error 2.6 m,
no better than the mosaic's).

Covariance
----------
``(J^T J)^-1`` at the optimum with the rows scaled by the square roots of their robust weights
(:func:`~sss_locus.experiments.adjustment.covariance.marginal_covariances`): first-order, from
the stated sigmas (not rescaled by the residuals).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.optimize import least_squares

from ...geometry.beam_plane import beam_plane_angle
from ...geometry.validation import as_float_array
from .covariance import marginal_covariances
from .model import NavigationPriors, Sightings, corrected_poses
from .residuals import JointProblem

LOSSES = ("linear", "soft_l1", "huber", "cauchy")
METHODS = ("trf", "dogbox")
"""``least_squares``' methods that take the sparse Jacobian with LSMR (``"lm"`` and
``"exact"`` need a dense one); the adjustment's is ``"trf"``."""
GATE_FLOOR_M = 10.0
GATE_SIGMAS = 5.0
"""The default gate (:func:`default_gate_m`): a start (a mosaic) misses a feature's right
sightings by the navigation error and the flat-seafloor error, metres; a wrong match by the
distance between features, tens to hundreds of metres."""
LSMR_TOL = 1e-10
"""``atol`` and ``btol`` of the LSMR inner solves (``least_squares``' default 1e-6 stops the
common-shift direction, held only by the priors, about a millimetre short on a small survey)."""
DOWNWEIGHT_BELOW = 0.5
"""A sighting whose robust weight ``rho'`` is below this (its residual beyond about 1.7 times
``f_scale`` for ``soft_l1``) is reported as down-weighted."""


@dataclass(frozen=True)
class JointAdjustment:
    """What :func:`adjust` returns (world frame of the sightings, metres).

    Attributes
    ----------
    point_m : ndarray, shape (N, 3)
        Every feature's estimate; the start where not ``adjusted``.
    adjusted : ndarray of bool, shape (N,)
        Seen on at least ``min_passes`` distinct passes, so estimated.
    covariance_m2 : ndarray, shape (N, 3, 3)
        First-order covariance of ``point_m``, including the pass corrections' uncertainty
        (m^2); NaN where not adjusted, ``inf`` where undetermined.
    corrections : ndarray, shape (P, 5)
        Each pass's estimated correction (true minus navigated), in
        :data:`~sss_locus.experiments.adjustment.model.CORRECTION_NAMES` order (m, m, rad, m/m,
        m/m); 0 where not estimated.
    correction_sigma : ndarray, shape (P, 5)
        Their first-order standard deviations; 0 where not estimated.
    common_shift_sigma_m : ndarray, shape (2,)
        First-order standard deviation of the mean of the passes' offsets (east, north), m: the
        common shift of every pass and feature that the ranges cannot see, held by the priors
        (NaN without the covariances or without estimated passes).
    range_residual, beam_plane_residual : ndarray, shape (m,)
        Each sighting's residuals at the optimum, in sigmas; NaN where the sighting was not used
        (its feature not adjusted; no beam-plane constraint).
    weight : ndarray, shape (m,)
        The smaller robust weight ``rho'`` of the sighting's rows (1 with the linear loss); NaN
        where not used.
    downweighted : ndarray of bool, shape (m,)
        ``weight < DOWNWEIGHT_BELOW`` (gated sightings included).
    gated : ndarray of bool, shape (m,)
        Sightings of adjusted features left out as gross outliers: missing the start, and the
        solution, by more than the gate (their weight is 0).
    cost : float
        Half the sum of the robust losses of all residuals at the optimum.
    success : bool
        ``least_squares`` stopped on a tolerance (not on the evaluation limit).
    message : str
    n_evaluations : int
    seconds : float
        Wall time of the solve (without the covariance).
    """

    point_m: np.ndarray
    adjusted: np.ndarray
    covariance_m2: np.ndarray
    corrections: np.ndarray
    correction_sigma: np.ndarray
    common_shift_sigma_m: np.ndarray
    range_residual: np.ndarray
    beam_plane_residual: np.ndarray
    weight: np.ndarray
    downweighted: np.ndarray
    gated: np.ndarray
    cost: float
    success: bool
    message: str
    n_evaluations: int
    seconds: float


def robust_loss(name: str, f_scale: float, n_robust: int):
    """``least_squares``' callable loss: ``name`` on the first ``n_robust`` residuals (scale
    ``f_scale``, in sigmas), linear on the rest. Returns ``loss(z) -> (3, len(z))``.

    Parameters
    ----------
    name : str
        ``"soft_l1"``, ``"huber"`` or ``"cauchy"`` (anything else: linear everywhere).
    f_scale : float
        Soft threshold, in sigmas.
    n_robust : int
        Number of leading residuals the robust loss applies to.

    Returns
    -------
    callable
        ``loss(z)`` of squared residuals ``z`` (shape (k,)) -> array (3, k): value, first and
        second derivatives.
    """
    c2 = float(f_scale) ** 2

    def loss(z):
        out = np.empty((3, z.size))
        out[0], out[1], out[2] = z, 1.0, 0.0
        t = z[:n_robust] / c2
        if name == "soft_l1":
            q = np.sqrt(1.0 + t)
            out[0, :n_robust], out[1, :n_robust], out[2, :n_robust] = 2 * c2 * (q - 1), 1 / q, -0.5 / (c2 * q ** 3)
        elif name == "huber":
            big = t > 1
            s = np.sqrt(np.where(big, t, 1.0))
            out[0, :n_robust] = np.where(big, c2 * (2 * s - 1), z[:n_robust])
            out[1, :n_robust] = np.where(big, 1 / s, 1.0)
            out[2, :n_robust] = np.where(big, -0.5 / (c2 * s ** 3), 0.0)
        elif name == "cauchy":
            out[0, :n_robust], out[1, :n_robust], out[2, :n_robust] = c2 * np.log1p(t), 1 / (1 + t), -1 / (c2 * (1 + t) ** 2)
        return out

    return loss


def misses_m(sightings: Sightings, priors: NavigationPriors, points_m, corrections) -> np.ndarray:
    """How far each sighting misses its feature at ``points_m`` (N, 3) with the pass
    ``corrections`` (P, 5), metres: the larger of the range miss and the beam-plane miss (the
    distance times the beam-plane angle), shape (m,).

    Parameters
    ----------
    sightings : Sightings
        The sightings, m of them.
    priors : NavigationPriors
        The passes' navigation priors.
    points_m : array_like
        Feature positions, world ENU, m, shape (N, 3).
    corrections : array_like
        Pass corrections, shape (P, 5).

    Returns
    -------
    numpy.ndarray
        Miss per sighting, m, shape (m,).
    """
    o, W = corrected_poses(sightings, priors, corrections)
    p = np.asarray(points_m, float)[sightings.feature]
    d = np.linalg.norm(p - o, axis=1)
    phi, _ = beam_plane_angle(p, o, W)
    plane = np.where(np.isfinite(sightings.beam_plane_sigma_rad), d * np.abs(phi), 0.0)
    return np.maximum(np.abs(d - sightings.range_m), plane)


def default_gate_m(sightings: Sightings, priors: NavigationPriors) -> float:
    """The default gate of :func:`adjust`, metres: ``GATE_FLOOR_M`` plus ``GATE_SIGMAS`` times the
    largest offset prior and the largest heading prior times the median range.

    Parameters
    ----------
    sightings : Sightings
        The sightings (their ranges, m).
    priors : NavigationPriors
        The passes' priors (offset sigmas m, heading sigmas deg).

    Returns
    -------
    float
        The gate, m (``GATE_FLOOR_M`` with no sightings and no priors).
    """
    r = float(np.median(sightings.range_m)) if sightings.n else 0.0
    return float(GATE_FLOOR_M + GATE_SIGMAS * (np.max(priors.offset_sigma_m, initial=0.0)
                                               + np.radians(np.max(priors.heading_sigma_deg, initial=0.0)) * r))


def _solve(sightings, priors, start, use, min_passes, estimate_passes, loss, f_scale, hp, hs, ftol, xtol, max_nfev,
           lsmr_tol=LSMR_TOL, method="trf"):
    """One adjustment with the sightings ``use``: returns the problem, ``x``, the residuals, the
    status, message, evaluations and cost."""
    N, P = start.shape[0], priors.n_passes
    pairs = np.unique(sightings.feature[use] * P + sightings.pass_index[use])
    feats = np.flatnonzero(np.bincount(pairs // P, minlength=N) >= min_passes)
    prob = JointProblem(sightings, priors, feats, estimate_passes=estimate_passes, use=use,
                        height_prior_m=None if hp is None else np.where(np.isfinite(hs), hp, 0.0)[feats],
                        height_sigma_m=None if hs is None else hs[feats])
    x0 = prob.pack(start[feats], np.zeros((P, 5)))
    if not feats.size:
        return prob, x0, prob.residuals(x0), 1, "no feature seen on enough passes", 0, 0.0
    # Gauss-Newton from the start first (quadratic loss: a few iterations), then the robust
    # loss from there (started at metres of navigation error, every residual would look like an
    # outlier); lsmr solved tightly, or the weak common-shift direction stops early
    opts = dict(method=method, tr_solver="lsmr", x_scale="jac", tr_options=dict(atol=lsmr_tol, btol=lsmr_tol),
                ftol=ftol, xtol=xtol, gtol=1e-10, max_nfev=max_nfev)
    sol = least_squares(prob.residuals, x0, jac=prob.jacobian, loss="linear", **opts)
    nfev = sol.nfev
    if loss != "linear":
        sol = least_squares(prob.residuals, sol.x, jac=prob.jacobian, loss=robust_loss(loss, f_scale, prob.n_meas), **opts)
        nfev += sol.nfev
    return prob, sol.x, sol.fun, sol.status, sol.message, nfev, float(sol.cost)


def adjust(sightings: Sightings, priors: NavigationPriors, start_m, *, min_passes: int = 2,
           estimate_passes: bool = True, loss: str = "soft_l1", f_scale: float = 3.0, gate_m: float | None = None,
           height_prior_m=None, height_sigma_m=None, covariance: bool = True,
           max_nfev: int | None = None, ftol: float = 1e-10, xtol: float = 1e-10,
           lsmr_tol: float = LSMR_TOL, method: str = "trf") -> JointAdjustment:
    """Jointly adjust the features seen on ``min_passes`` or more passes and the passes'
    navigation corrections (module docstring).

    Parameters
    ----------
    sightings : Sightings
        ``m`` sightings of ``N`` features (``feature`` in ``[0, N)``) on ``P`` passes.
    priors : NavigationPriors
        The ``P`` passes' correction priors (``pass_index`` in ``[0, P)``).
    start_m : array_like, shape (N, 3)
        A start for every feature, world frame, metres (e.g. the flat-seafloor mosaic: it puts
        the feature on the right side of the tracks and below them, where the solution is; with
        possible wrong matches the median of each feature's flat-seafloor positions, which a
        wrong match does not move, rather than their mean).
    min_passes : int, >= 2
        Features seen on fewer distinct passes are not adjusted (a range and a beam-plane angle
        from one pass leave a feature on a circle).
    estimate_passes : bool
        False holds every correction at zero: the per-feature N-view estimate with the
        beam-plane constraint, from the navigated poses.
    loss : {"linear", "soft_l1", "huber", "cauchy"}
        Robust loss on the sightings' residuals.
    f_scale : float, > 0
        Its scale, in sigmas.
    gate_m : float, optional
        Sightings that miss the start by more than this (metres; range or beam-plane miss,
        :func:`misses_m`) are left out as gross outliers (wrong matches), and taken back where
        they miss the solution by less; default :func:`default_gate_m`; ``inf``: no gate.
    height_prior_m, height_sigma_m : array_like, shape (N,), optional
        A prior on each feature's height ``z`` (e.g. from a depth sounding below it) and its
        sigma (m; ``inf``: none).
    covariance : bool
        Compute the covariances (the Schur complement; skip for speed).
    max_nfev : int, optional
        Evaluation limit of ``least_squares`` (default: its own, 100 times the unknowns).
    ftol, xtol : float
        ``least_squares`` tolerances.
    lsmr_tol : float, in (0, 1)
        ``atol`` and ``btol`` of its LSMR inner solves (default :data:`LSMR_TOL`; the survey
        design's scoring uses a looser one, measured:
        :data:`~sss_locus.experiments.survey_design.joint.SCORING_LSMR_TOL`).
    method : {"trf", "dogbox"}
        ``least_squares``' trust-region method (:data:`METHODS`; both with the sparse Jacobian
        and LSMR). ``"trf"`` is the adjustment's; ``"dogbox"`` takes another path to an optimum,
        which shows which features' estimates depend on the path
        (:func:`~sss_locus.experiments.survey_design.joint.solver_path_shift`).

    Returns
    -------
    JointAdjustment

    Raises
    ------
    ValueError
        Naming the argument: shapes that do not match, a pass or feature index out of range,
        an unknown loss, ``f_scale`` <= 0, ``min_passes`` < 2, ``lsmr_tol`` outside (0, 1), an
        unknown ``method``.
    """
    N = int(np.asarray(start_m).shape[0]) if np.ndim(start_m) == 2 else -1
    start = as_float_array(start_m, "start_m", tail=(3,))
    if start.ndim != 2:
        raise ValueError(f"start_m must have shape (N, 3); got {start.shape}")
    if sightings.n and sightings.feature.max() >= N:
        raise ValueError(f"sightings.feature must be < the number of rows of start_m ({N}); got {sightings.feature.max()}")
    P = priors.n_passes
    if sightings.n and sightings.pass_index.max() >= P:
        raise ValueError(f"sightings.pass_index must be < the number of passes of priors ({P}); "
                         f"got {sightings.pass_index.max()}")
    if loss not in LOSSES:
        raise ValueError(f"loss must be one of {list(LOSSES)}; got {loss!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {list(METHODS)}; got {method!r}")
    if not (np.isfinite(f_scale) and f_scale > 0):
        raise ValueError(f"f_scale must be a finite number > 0; got {f_scale!r}")
    if isinstance(min_passes, bool) or int(min_passes) != min_passes or min_passes < 2:
        raise ValueError(f"min_passes must be an integer >= 2; got {min_passes!r}")
    if not (isinstance(lsmr_tol, (int, float)) and 0 < lsmr_tol < 1):
        raise ValueError(f"lsmr_tol must be a number in (0, 1); got {lsmr_tol!r}")
    if gate_m is not None and not (isinstance(gate_m, (int, float)) and gate_m > 0 and not np.isnan(gate_m)):
        raise ValueError(f"gate_m must be a number > 0 (inf: no gate) or None; got {gate_m!r}")
    hp = hs = None
    if height_sigma_m is not None:
        hs = as_float_array(height_sigma_m, "height_sigma_m", finite=False)
        hp = as_float_array(height_prior_m if height_prior_m is not None else np.zeros(N), "height_prior_m", finite=False)
        if hs.shape != (N,) or hp.shape != (N,):
            raise ValueError(f"height_prior_m and height_sigma_m must have shape ({N},); got {hp.shape}, {hs.shape}")

    t0 = time.perf_counter()
    gate = gate_m if gate_m is not None else default_gate_m(sightings, priors)
    use = misses_m(sightings, priors, start, np.zeros((P, 5))) <= gate
    prob, x, fun, status, msg, nfev, cost = _solve(sightings, priors, start, use, min_passes, estimate_passes, loss,
                                                   f_scale, hp, hs, ftol, xtol, max_nfev, lsmr_tol, method)
    if gate_m != np.inf:  # a sighting gated out at the start but within the gate at the solution comes back
        p_now, c_now = prob.split(x)
        s_now = start.copy()
        s_now[prob.features] = p_now
        again = misses_m(sightings, priors, s_now, c_now) <= gate
        if np.any(again & ~use):
            use = use | again
            prob, x, fun, status, msg, n2, cost = _solve(sightings, priors, s_now, use, min_passes, estimate_passes,
                                                         loss, f_scale, hp, hs, ftol, xtol, max_nfev, lsmr_tol,
                                                         method)
            nfev += n2
    seconds = time.perf_counter() - t0
    feats = prob.features
    adjusted = np.zeros(N, bool)
    adjusted[feats] = True
    robust = loss != "linear"

    points, corr = prob.split(x)
    m = sightings.n
    nr = prob.rows.size
    w_rows = robust_loss(loss, f_scale, prob.n_meas)(fun ** 2)[1] if robust else np.ones(fun.size)
    range_res = np.full(m, np.nan)
    beam_res = np.full(m, np.nan)
    weight = np.full(m, np.nan)
    range_res[prob.rows] = fun[:nr]
    weight[prob.rows] = w_rows[:nr]
    beam_rows = prob.rows[prob.beam]
    beam_res[beam_rows] = fun[nr:prob.n_meas]
    weight[beam_rows] = np.minimum(weight[beam_rows], w_rows[nr:prob.n_meas])
    gated = ~use & adjusted[sightings.feature]
    weight[gated] = 0.0

    point = start.copy()
    point[feats] = points
    cov = np.full((N, 3, 3), np.nan)
    csig = np.zeros((P, 5))
    common = np.full(2, np.nan)
    if covariance and feats.size:
        J = prob.jacobian(x)
        J = sp.diags(np.sqrt(w_rows)) @ J
        fcov, pcov = marginal_covariances(J, feats.size)
        cov[feats] = fcov
        csig[prob.free] = np.sqrt(np.maximum(np.diag(pcov), 0.0))
        index = np.full((P, 5), -1)
        index[prob.free] = np.arange(int(prob.free.sum()))
        for a in range(2):
            k = index[:, a][index[:, a] >= 0]
            if k.size:
                common[a] = np.sqrt(max(pcov[np.ix_(k, k)].sum(), 0.0)) / k.size
    return JointAdjustment(point_m=point, adjusted=adjusted, covariance_m2=cov, corrections=corr,
                           correction_sigma=csig, common_shift_sigma_m=common, range_residual=range_res, beam_plane_residual=beam_res,
                           weight=weight, downweighted=weight < DOWNWEIGHT_BELOW, gated=gated, cost=cost,
                           success=bool(status > 0), message=str(msg), n_evaluations=int(nfev), seconds=seconds)
