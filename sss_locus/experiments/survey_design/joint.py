"""A survey plan flown with navigation error and adjusted jointly: the errors of the joint
estimate of features and navigation for one plan on one seed.

The plan's segments are flown as **passes** (a line cut by a hole or the area's edge is two
passes: the vehicle leaves it and comes back, so its navigation error is drawn anew). The
features of the setting (:func:`~sss_locus.experiments.survey_design.front.make_setting`: uniform over
the area, on its seafloor model) are observed by every segment that sees them, with the same
visibility as the coverage (:func:`~sss_locus.experiments.survey_design.coverage.observe_lines`: the
exact in-beam ping, both apertures, the range, the transducer abeam the feature on the segment).
Every view is perturbed by the platform's noise model under the **per-pass** navigation model
of ``data/noise.toml`` (:mod:`~sss_locus.experiments.passes.pass_noise`: one offset, heading bias and
drift per pass, shared by its pings, the drift growing from the segment's start; a per-ping
jitter; the sonar's range and the attitude errors per ping), and the reconstruction chapter's
joint adjustment (:func:`~sss_locus.experiments.reconstruction.joint.adjustment_estimators`,
``"joint"``: every feature seen on two or more passes and every pass's correction together,
with the navigation priors of the same model) estimates the features. Data association is known
(every view is attributed to its feature), so the solve uses the quadratic loss without a gate
(``known_association``). This is the
reconstruction chapter's machinery (:func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`)
run on the plan's lines instead of the chapter's layout: no second simulator.

Errors (:data:`JOINT_METRICS`, each the median over the features the joint estimate estimated,
as in :func:`~sss_locus.experiments.reconstruction.surveys.survey_errors`):

``horizontal``
    the horizontal distance to the truth (absolute position: what a target's coordinates are
    off by; the common shift of the whole survey is held by the navigation priors only);
``vertical``
    the absolute vertical error;
``shape``
    the *map-shape* error, the 3-D distance after removing the median error vector of the
    plan's estimated features (:func:`~sss_locus.experiments.adjustment.map_errors`): what the
    geometry of the lines determines, the absolute shift removed.

**The solver's path** (:func:`solver_path_shift`): a feature seen on only two passes has two
ranges and two beam-plane angles, and two ranges from two lines meet in two places, so its part
of the problem can have two local minima; which one the solve ends in depends on the path the
solver takes (``benchmarks/README.md``: on a sparse 5 km square, ``least_squares``' ``dogbox``,
``lm`` and ``exact`` land some such features in another minimum tens of metres away). The check
solves the same sightings again with ``dogbox`` and reports how far each feature moved.

Seeds: ``seed`` draws the features and seafloor (through the setting), the in-beam elevations
(``10 seed + 2``) and the noise (``10 seed + 3``), so different seeds are independent surveys
and every plan of one seed meets the same features (common random numbers).
"""

from __future__ import annotations

import math

import numpy as np

from sss_locus.experiments.adjustment import map_errors
from sss_locus.experiments.reconstruction.estimators import reconstruct
from sss_locus.experiments.reconstruction.joint import adjustment_estimators
from sss_locus.experiments.survey_design.coverage import observe_lines

SCORING_LSMR_TOL = 1e-8
"""``atol``/``btol`` of the joint solve's LSMR inner solves when a plan is scored (the
reconstruction chapter keeps :data:`~sss_locus.experiments.adjustment.solver.LSMR_TOL`, 1e-10).
On a sparse survey (200 features over 25 km^2, the AUV's 43 passes) LSMR runs to its iteration
limit at 1e-10 in every one of the 130-190 trust-region steps; at 1e-8 the scoring of the 5 km
benchmark took 90 instead of 145 CPU s, and every per-seed median of its 10 plans x 5 seeds moved
by at most 0.45 mm (horizontal 0.11 mm, shape 0.17 mm), with the same features estimated and the
same verdict (``benchmarks/README.md``, survey design; ``tests/test_survey_joint.py``)."""
SCORING_MAX_EVALUATIONS = 4000
"""Evaluation limit of the joint solve when a plan is scored (the reconstruction chapter keeps
:data:`~sss_locus.experiments.reconstruction.joint.JOINT_MAX_EVALUATIONS`, 400, measured on its
own surveys). A plan's survey has a hundred passes and more, and the quadratic solve can crawl
along a narrow valley where a feature seen on two passes moves between its two minima: the
standard plan of a 900 kHz ROV over a 3 km L-shaped area (103 passes, 60 features, seed 3;
``tests/experiments/survey_design/test_survey_joint.py``) reached the old limit of 400 with one
feature still 4.6 m from its optimum and converged at 624 evaluations. A solve stopped on the
limit estimates no feature (a whole seed lost), so the limit only guards against a solve that
never ends: 4000, six times the slowest measured."""
MOVED_M = 1.0
"""A feature whose two solutions (:func:`solver_path_shift`) lie farther apart than this (m) has
moved to another local minimum (the solutions of one minimum agree to millimetres)."""
JOINT_METRICS = ("horizontal", "vertical", "shape")
"""The errors of :func:`plan_joint_errors` (module docstring); columns ``<name>_median_m``."""


def plan_joint_errors(setting, plan, noise, pass_noise, *, seed: int) -> dict:
    """The joint estimate's errors of one plan on one seed (module docstring).

    Parameters
    ----------
    setting : sss_locus.experiments.survey_design.front.Setting
        Platform, area, seafloor and the features (drawn with ``setting.seed``).
    plan : sss_locus.experiments.survey_design.plans.Plan
        The plan; its segments over ``setting.area`` are the passes.
    noise : sss_locus.experiments.datamodel.noise_model.NoiseModel
        The platform's per-ping noise (range, vertical, roll, pitch).
    pass_noise : sss_locus.experiments.passes.pass_noise.PassNoise
        The platform's per-pass navigation errors (offset, heading bias, drift, jitter).
    seed : int
        Seed of the in-beam elevations and the noise (module docstring), >= 0.

    Returns
    -------
    dict
        ``n_passes`` (segments), ``n_seen_twice`` (features seen on two or more passes),
        ``n_joint`` (features the joint estimate estimated: the solver converged and the feature
        was seen on two or more passes), and ``<metric>_median_m`` for each of
        :data:`JOINT_METRICS` (m; NaN when ``n_joint`` is 0).
    """
    table, seen = _joint_tables(setting, plan, noise, pass_noise, seed, ("trf",))
    joint = table[table.estimator == "trf"]
    ok = joint.estimated.to_numpy(bool)
    out = {"n_passes": int(seen.shape[1]), "n_seen_twice": int((seen.sum(axis=1) >= 2).sum()),
           "n_joint": int(ok.sum())}
    if not ok.any():
        return {**out, **{f"{m}_median_m": math.nan for m in JOINT_METRICS}}
    d = joint[["error_x_m", "error_y_m", "error_v_m"]].to_numpy(float)[ok]
    e = map_errors(d, np.zeros_like(d))
    return {**out, "horizontal_median_m": float(np.median(e["horizontal_m"])),
            "vertical_median_m": float(np.median(np.abs(e["vertical_m"]))),
            "shape_median_m": float(np.median(e["shape_m"]))}


def _joint_tables(setting, plan, noise, pass_noise, seed: int, methods):
    """The plan flown on ``seed`` and adjusted jointly with each ``least_squares`` method of
    ``methods`` on the same sightings: the reconstruction table (estimators named by their
    method) and the ``seen`` matrix (features x passes)."""
    p = setting.platform
    lines = plan.lines(setting.area)
    if lines.empty:
        raise ValueError(f"plan {plan} leaves no line inside the area")
    views, seen, info = observe_lines(p, setting.terrain, setting.xy, lines, plan.altitude_m, plan.pitch_deg,
                                      p.fixed_depth, 10 * int(seed) + 2, setting.centre)
    extra = {m: adjustment_estimators(p.sonar.elevation_deg, ("joint",), known_association=True,
                                      lsmr_tol=SCORING_LSMR_TOL, method=m,
                                      max_evaluations=SCORING_MAX_EVALUATIONS)["joint"] for m in methods}
    table = reconstruct(views, seen, info["sensor_height_m"], noise, p.sonar.aperture(), n_views=(3,),
                        seed=10 * int(seed) + 3, navigation="per_pass", pass_noise=pass_noise,
                        along_m=info["along_m"], extra=extra)
    return table, seen


def solver_path_shift(setting, plan, noise, pass_noise, *, seed: int) -> dict:
    """How far the joint estimate of one plan on one seed moves when the same sightings are
    solved along another path: ``least_squares``' ``"dogbox"`` against the adjustment's
    ``"trf"`` (module docstring, :data:`MOVED_M`).

    Parameters
    ----------
    setting, plan, noise, pass_noise, seed
        As for :func:`plan_joint_errors`.

    Returns
    -------
    dict
        ``n_joint`` (features both solves estimated), ``n_two_pass`` (of them, seen on exactly
        two passes), ``n_moved`` (of them, moved by more than :data:`MOVED_M`), ``n_moved_two_pass``
        (of those, seen on two passes), ``max_shift_m`` (the largest move, 3-D, m; 0 without
        features) and ``horizontal_median_shift_m`` (how far the median horizontal error moved,
        m; NaN without features).
    """
    table, seen = _joint_tables(setting, plan, noise, pass_noise, seed, ("trf", "dogbox"))
    a, b = (table[table.estimator == m].set_index("feature").sort_index() for m in ("trf", "dogbox"))
    ok = (a.estimated & b.estimated).to_numpy(bool)
    cols = ["error_x_m", "error_y_m", "error_v_m"]
    shift = np.linalg.norm(a[cols].to_numpy(float) - b[cols].to_numpy(float), axis=1)[ok]
    two = (seen.sum(axis=1)[a.index.to_numpy()] == 2)[ok]
    moved = shift > MOVED_M
    med = (abs(float(np.median(a.error_h_m.to_numpy(float)[ok])) - float(np.median(b.error_h_m.to_numpy(float)[ok])))
           if ok.any() else math.nan)
    return {"n_joint": int(ok.sum()), "n_two_pass": int(two.sum()), "n_moved": int(moved.sum()),
            "n_moved_two_pass": int((moved & two).sum()), "max_shift_m": float(shift.max()) if ok.any() else 0.0,
            "horizontal_median_shift_m": med}
