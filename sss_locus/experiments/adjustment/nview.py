"""The N-view estimate with the beam-plane constraint, feature by feature (navigation held fixed),
in the ``(n, k)`` layout of the reconstruction chapter's estimators
(:mod:`sss_locus.experiments.reconstruction.estimators`): every view's slant range *and* its beam-plane
angle (:mod:`sss_locus.geometry.beam_plane`), least squares on both.

Two views then determine a feature (four measurements, three unknowns) where the ranges alone
leave a circle; three or more no longer have the mirror image above the sensors that the ranges
alone allow. It is :func:`~sss_locus.experiments.adjustment.adjust` with the passes' corrections
held at zero (each view its own pass), so one solver and one residual model serve the per-feature
and the joint estimates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...geometry.validation import as_float_array
from .model import NavigationPriors, Sightings
from .solver import adjust


@dataclass(frozen=True)
class BeamPlanePoints:
    """What :func:`beam_plane_points` returns for ``n`` features (world frame, metres).

    Attributes
    ----------
    point : ndarray, shape (n, 3)
        The estimate; the start where not ``estimated``.
    estimated : ndarray of bool, shape (n,)
        Seen in two or more views, and the solve finished.
    covariance : ndarray, shape (n, 3, 3)
        ``(J^T J)^-1`` from the stated sigmas, m^2 (NaN where not estimated).
    downweighted : ndarray of bool, shape (n, k)
        Views the robust loss down-weighted (all False with the linear loss).
    """

    point: np.ndarray
    estimated: np.ndarray
    covariance: np.ndarray
    downweighted: np.ndarray


def beam_plane_points(W, origin, ranges, range_sigmas, beam_plane_sigmas, mask, start, *,
                      loss: str = "linear", f_scale: float = 3.0) -> BeamPlanePoints:
    """Each feature from its views' ranges and beam-plane angles (module docstring).

    Parameters
    ----------
    W : array_like, shape (n, k, 3, 3)
        Sensor axes of each view in the world frame (estimated poses; columns ``x``, ``y``,
        ``z``, ``z`` the beam plane's normal).
    origin : array_like, shape (n, k, 3)
        Sensor origins, metres.
    ranges, range_sigmas : array_like, shape (n, k)
        Measured slant ranges and their standard deviations (> 0 where ``mask``), metres.
    beam_plane_sigmas : array_like, shape (n, k) or scalar
        Standard deviations of the beam-plane angles, radians (> 0; ``inf``: range only)
        (:func:`~sss_locus.geometry.beam_plane.beam_plane_sigma_rad`).
    mask : array_like of bool, shape (n, k)
        Views that saw each feature.
    start : array_like, shape (n, 3)
        Start positions (e.g. the flat-seafloor mosaic), metres.
    loss : str
        Robust loss on the views' residuals
        (:data:`~sss_locus.experiments.adjustment.LOSSES`; default linear).
    f_scale : float
        The robust loss's scale, in sigmas.

    Returns
    -------
    BeamPlanePoints
    """
    W = as_float_array(W, "W", tail=(3, 3))
    o = as_float_array(origin, "origin", tail=(3,))
    if W.ndim != 4 or o.shape != W.shape[:2] + (3,):
        raise ValueError(f"W must have shape (n, k, 3, 3) and origin (n, k, 3); got {W.shape}, {o.shape}")
    n, k = o.shape[:2]
    mask = np.asarray(mask)
    if mask.dtype != bool or mask.shape != (n, k):
        raise ValueError(f"mask must be a boolean array of shape {(n, k)}; got {mask.dtype} {mask.shape}")
    arrays = {}
    for name, value in (("ranges", ranges), ("range_sigmas", range_sigmas), ("beam_plane_sigmas", beam_plane_sigmas)):
        a = np.broadcast_to(as_float_array(value, name, finite=name == "ranges"), (n, k))
        arrays[name] = a
    f, v = np.nonzero(mask)
    s = Sightings(feature=f, pass_index=v, origin_m=o[f, v], W=W[f, v], range_m=arrays["ranges"][f, v],
                  range_sigma_m=arrays["range_sigmas"][f, v], beam_plane_sigma_rad=arrays["beam_plane_sigmas"][f, v],
                  along_track_m=np.zeros(f.size))
    priors = NavigationPriors(offset_sigma_m=1.0, heading_sigma_deg=0.0, drift_sigma=0.0, reference_m=np.zeros((k, 2)))
    res = adjust(s, priors, start, estimate_passes=False, loss=loss, f_scale=f_scale)
    down = np.zeros((n, k), bool)
    down[f, v] = res.downweighted
    ok = res.adjusted & np.all(np.isfinite(res.covariance_m2), axis=(1, 2))
    return BeamPlanePoints(point=res.point_m, estimated=ok, covariance=np.where(ok[:, None, None], res.covariance_m2, np.nan),
                           downweighted=down)
