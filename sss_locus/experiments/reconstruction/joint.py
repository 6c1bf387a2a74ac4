"""The joint adjustment and the N-view estimate with the beam plane as estimators of the
reconstruction chapter (the ``extra`` estimators of
:func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`, on the same noisy views as the others).

``beam``
    every feature seen on two or more passes, alone, from the navigated poses: its slant ranges
    and beam-plane angles (:mod:`sss_locus.geometry.beam_plane`), least squares with the passes'
    corrections held at zero (:func:`~sss_locus.experiments.adjustment.beam_plane_points`). Its
    range sigmas are the N-view estimator's (range error plus the whole sensor-position error
    along the line of sight) and its beam-plane sigmas carry the whole heading and pitch error;
``joint``
    every feature seen on two or more passes and every pass's correction (offset, heading bias,
    and drift where the model has one) together, with the navigation priors of the per-pass
    model (:mod:`~sss_locus.experiments.passes.pass_noise`): the shared errors are unknowns, so the
    sightings' sigmas carry only the per-ping parts (range, jitter, vertical; heading jitter
    and pitch). Needs the ``"per_pass"`` model: with per-view errors there is nothing shared
    to estimate.

Both start from the flat-seafloor mosaic; ``beam`` uses the quadratic loss (data association is
known), ``joint`` the solver's default soft-L1 robust loss after its quadratic start, and its
features count as not estimated when the solver stops on its evaluation limit
(:data:`JOINT_MAX_EVALUATIONS`) instead of a tolerance. With ``known_association`` (a simulation
that attributes every view to its feature, as the survey design's) ``joint`` uses the quadratic
loss and no gate too, like ``beam``: without outliers the same features to within centimetres (the
robust loss down-weights the few residuals beyond three sigmas a little), in a seventh of the
solver's evaluations on a sparse survey (200 features over 25 km^2: 133 evaluations against 936). The beam-plane angle's sigma is evaluated at each sighting's depression angle
(``asin`` of the sensor's height above the seafloor below it over the range).
"""

from __future__ import annotations

import math

import numpy as np

from sss_locus.geometry.beam_plane import beam_plane_sigma_rad
from sss_locus.experiments.adjustment import NavigationPriors, Sightings, adjust, beam_plane_points
from sss_locus.experiments.adjustment.solver import LSMR_TOL

JOINT_ESTIMATORS = ("beam", "joint")
JOINT_MAX_EVALUATIONS = 400
"""Evaluation limit of each phase of the joint solve (it converges in tens on the chapter's surveys)."""


def _sightings(inputs: dict, elevation_deg: float, joint: bool) -> Sightings:
    seen = np.asarray(inputs["seen"], bool)
    i, l = np.nonzero(seen)
    W, o, r = inputs["W"][i, l], inputs["origin"][i, l], inputs["ranges"][i, l]
    noise, pn = inputs["noise"], inputs["pass_noise"]
    H = np.maximum(np.asarray(inputs["sensor_height_m"], float)[i, l], 0.0)
    depression = np.degrees(np.arcsin(np.clip(H / np.maximum(r, 1e-9), 0.0, 1.0)))
    if joint:
        sig = inputs["sigmas"][i, l]
        los = inputs["flat"][i, l] - o
        los /= np.maximum(np.linalg.norm(los, axis=-1, keepdims=True), 1e-12)
        jit = pn.ping_horizontal_sigma_m
        range_sigma = np.sqrt(sig[:, 0] ** 2 + (jit * los[:, 0]) ** 2 + (jit * los[:, 1]) ** 2
                              + (sig[:, 3] * los[:, 2]) ** 2)
        heading = pn.ping_heading_sigma_deg
    else:
        range_sigma = inputs["range_sigma_m"][i, l]
        heading = (math.hypot(pn.pass_heading_bias_sigma_deg, pn.ping_heading_sigma_deg)
                   if inputs["navigation"] == "per_pass" else noise.heading_sigma_deg)
    along = inputs["along_m"]
    return Sightings(feature=i, pass_index=l, origin_m=o, W=W, range_m=r,
                     range_sigma_m=np.maximum(range_sigma, 1e-6),
                     beam_plane_sigma_rad=beam_plane_sigma_rad(elevation_deg, heading, noise.pitch_sigma_deg,
                                                               depression),
                     along_track_m=np.zeros(i.size) if along is None else np.asarray(along, float)[i, l])


def _start(inputs: dict) -> np.ndarray:
    seen = np.asarray(inputs["seen"], float)
    return np.einsum("nli,nl->ni", inputs["flat"], seen) / np.maximum(seen.sum(axis=1), 1)[:, None]


def adjustment_estimators(elevation_deg: float, names=JOINT_ESTIMATORS, *, known_association: bool = False,
                          lsmr_tol: float = LSMR_TOL, method: str = "trf",
                          max_evaluations: int = JOINT_MAX_EVALUATIONS) -> dict:
    """The estimators ``names`` (of :data:`JOINT_ESTIMATORS`, module docstring) as the ``extra``
    mapping of :func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`, for a sonar of full
    elevation beam width ``elevation_deg``; ``known_association``: the joint solve without the
    robust loss and the gate (module docstring); ``lsmr_tol``: the joint solve's LSMR tolerance
    (:func:`~sss_locus.experiments.adjustment.adjust`).

    Parameters
    ----------
    elevation_deg : float
        The sonar's full elevation beam width, degrees.
    names : sequence of str
        Estimators, among :data:`JOINT_ESTIMATORS` (``"beam"``, ``"joint"``).
    known_association : bool
        Solve without the robust loss and the gate.
    lsmr_tol : float
        LSMR tolerance of the joint solve.
    method : str
        ``least_squares``' method of the joint solve (:func:`~sss_locus.experiments.adjustment.adjust`).
    max_evaluations : int
        Evaluation limit of each phase of the joint solve (default :data:`JOINT_MAX_EVALUATIONS`);
        a solve that stops on it estimates no feature.

    Returns
    -------
    dict
        Name -> callable ``(inputs) -> (points, estimated)``: points (n, 3) world ENU m, estimated
        boolean (n,).

    Raises
    ------
    ValueError
        An unknown name (and, when called, ``"joint"`` without ``navigation="per_pass"``).
    """
    unknown = set(names) - set(JOINT_ESTIMATORS)
    if unknown:
        raise ValueError(f"names must be among {list(JOINT_ESTIMATORS)}; got {sorted(unknown)}")

    def run(inputs: dict, joint: bool):
        seen = np.asarray(inputs["seen"], bool)
        s = _sightings(inputs, elevation_deg, joint)
        if not joint:
            i, l = s.feature, s.pass_index
            rs, bs = (np.ones(seen.shape) for _ in range(2))
            rs[i, l], bs[i, l] = s.range_sigma_m, s.beam_plane_sigma_rad
            res = beam_plane_points(inputs["W"], inputs["origin"], inputs["ranges"], rs, bs, seen, _start(inputs))
            return res.point, res.estimated
        if inputs["navigation"] != "per_pass":
            raise ValueError("the joint estimator needs navigation='per_pass' (per-view errors share nothing)")
        pn = inputs["pass_noise"]
        priors = NavigationPriors(offset_sigma_m=max(pn.pass_offset_sigma_m, 1e-6),
                                  heading_sigma_deg=pn.pass_heading_bias_sigma_deg,
                                  drift_sigma=pn.drift_sigma_fraction, reference_m=np.zeros((seen.shape[1], 2)))
        robust = {} if not known_association else {"loss": "linear", "gate_m": math.inf}
        res = adjust(s, priors, _start(inputs), covariance=False, max_nfev=int(max_evaluations), lsmr_tol=lsmr_tol,
                     method=method, **robust)
        return res.point_m, res.adjusted & res.success & np.all(np.isfinite(res.point_m), axis=1)

    table = {"beam": lambda inputs: run(inputs, False), "joint": lambda inputs: run(inputs, True)}
    return {name: table[name] for name in names}
