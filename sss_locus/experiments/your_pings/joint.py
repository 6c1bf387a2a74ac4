"""The joint adjustment on a user's own sightings: every feature seen on two or more passes and
every pass's navigation correction estimated together
(:func:`~sss_locus.experiments.adjustment.adjust`), beside the flat-seafloor mosaic.

Frames: the local frame of :mod:`sss_locus.experiments.your_pings.study` (``x`` grid east, ``y`` grid
north, ``z`` up, metres).

Passes (:func:`infer_passes`): the survey lines, found from the sightings alone (the file has no
line column): sightings in time order (file order without ``time_s``), per source file, start a
new pass where the grid heading turns by more than :data:`TURN_DEG` from the pass's first
sighting, or the vehicle jumps more than :data:`JUMP_ACROSS_M` across its track (a parallel line
flown in the same direction). An open choice: the pass table lists each pass's file lines and
heading, so a user can check it.

Measurements and priors: each sighting's slant range (its ``range_sigma_m``), its beam-plane
angle (sigma from the sonar's elevation beam width, ``ping_attitude_sigma_deg`` and
``ping_position_sigma_m``: the per-ping noise left after a pass's heading bias and offset are
estimated; by default the platform's ``ping_horizontal_sigma_m`` and ``ping_heading_sigma_deg``
of ``data/noise.toml``); per pass a horizontal offset (sigma: the platform's
``pass_offset_sigma_m``) and a heading bias (its ``pass_heading_bias_sigma_deg``) turning the
sonar only (positions from the navigation solution), both from the per-pass navigation-error
model of :mod:`~sss_locus.experiments.passes.pass_noise`. No drift along the pass is estimated here
(the sightings carry no distance travelled along their line).

What the user's own residuals say (:class:`JointPings` ``.summary``): how far apart a feature's
sightings are placed by the mosaic (the RMS horizontal distance of its flat-seafloor positions
from their mean: the lines' disagreement the mosaic leaves in the map's shape) and by the joint
estimate (the RMS misfit of its sightings after the adjustment, range and beam-plane angle in
metres), medians over the adjusted features; and what stays unobservable: a common shift of
every pass and feature, held only by the navigation priors (its 1-sigma per axis).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from sss_locus.geometry.beam_plane import beam_plane_sigma_rad
from sss_locus.experiments.adjustment import NavigationPriors, Sightings, adjust
from sss_locus.experiments.passes.pass_noise import PassNoise
from sss_locus.experiments.your_pings.study import PingResults, ellipse_axes, sensor_poses

TURN_DEG = 45.0
JUMP_ACROSS_M = 15.0


@dataclass(frozen=True)
class JointPings:
    """What :func:`joint_estimate` returns.

    Attributes
    ----------
    features : pandas.DataFrame
        One row per feature, in the order of ``PingResults.features``: ``feature``, ``n_passes``
        (columns named like the other estimators', so the chapter's figures draw it:
        :func:`with_joint`), ``joint_status`` (``"adjusted"`` or ``"one pass"``), ``joint_east_m``, ``joint_north_m``,
        ``joint_up_m`` (NaN where not adjusted), the 1-sigma ``joint_ellipse_major_m``,
        ``joint_ellipse_minor_m``, ``joint_ellipse_azimuth_deg`` (clockwise from grid north) and
        ``joint_sigma_up_m``, ``joint_rms_misfit_m``, ``mosaic_minus_joint_h_m`` and
        ``mosaic_minus_joint_up_m``; ``joint_lon_deg``/``joint_lat_deg`` with a frame.
    passes : pandas.DataFrame
        One row per pass: ``pass``, ``source``, ``first_line``, ``last_line``, ``n_sightings``,
        ``heading_deg`` (grid), ``offset_east_m``, ``offset_north_m``, ``heading_bias_deg`` (true
        minus navigated, clockwise positive like the heading) and their 1-sigma ``..._sigma``
        columns.
    sightings : pandas.DataFrame
        ``PingResults.sightings`` with ``pass``, ``range_residual`` and ``beam_plane_residual`` (in
        sigmas) and ``downweighted``.
    summary : dict
        ``n_adjusted``, ``n_passes``, ``mosaic_disagreement_m``, ``joint_misfit_m``,
        ``shape_ratio`` (mosaic over joint), ``common_shift_sigma_m`` (the larger axis),
        ``n_downweighted`` (gated sightings included), ``n_gated``, ``n_used`` (sightings of
        adjusted features), the ``ping_position_sigma_m`` and ``ping_attitude_sigma_deg`` used,
        ``success``.
    """

    features: pd.DataFrame
    passes: pd.DataFrame
    sightings: pd.DataFrame
    summary: dict


def infer_passes(sightings: pd.DataFrame) -> np.ndarray:
    """The pass of each sighting (module docstring): integers from 0, shape (m,).

    ``sightings`` needs ``source``, ``line``, ``time_s``, ``grid_heading_deg``, ``east_m`` and
    ``north_m`` (``PingResults.sightings``).

    Parameters
    ----------
    sightings : pandas.DataFrame
        The sightings, m rows.

    Returns
    -------
    numpy.ndarray
        Pass index per sighting, int, shape (m,); empty for no sightings.
    """
    t = sightings["time_s"].to_numpy(float)
    key = np.where(np.isfinite(t), t, sightings["line"].to_numpy(float))
    order = np.lexsort((key, sightings["source"].astype(str).to_numpy()))
    src = sightings["source"].astype(str).to_numpy()[order]
    hdg = sightings["grid_heading_deg"].to_numpy(float)[order]
    xy = sightings[["east_m", "north_m"]].to_numpy(float)[order]
    out = np.empty(len(order), np.int64)
    current, h0, p0 = -1, 0.0, np.zeros(2)
    for k in range(len(order)):
        turn = abs((hdg[k] - h0 + 180.0) % 360.0 - 180.0)
        a = np.radians(h0)
        across = abs(-(xy[k, 0] - p0[0]) * np.cos(a) + (xy[k, 1] - p0[1]) * np.sin(a))  # grid heading: cw from north
        if k == 0 or src[k] != src[k - 1] or turn > TURN_DEG or across > JUMP_ACROSS_M:
            current, h0, p0 = current + 1, hdg[k], xy[k]
        out[order[k]] = current
    return out


def joint_estimate(res: PingResults, platform, noise: PassNoise, *, ping_position_sigma_m: float | None = None,
                   ping_attitude_sigma_deg: float | None = None, loss: str = "soft_l1") -> JointPings:
    """The joint adjustment of a user's sightings (module docstring).

    Parameters
    ----------
    res : PingResults
        :func:`~sss_locus.experiments.your_pings.study.analyse` of the sightings (the median of each
        feature's flat-seafloor positions is the start: robust to a wrong match, where the mean is not).
    platform : Platform
        The platform that took them (mounting, sonar beam width).
    noise : PassNoise
        Its per-pass navigation errors (:func:`~sss_locus.experiments.passes.pass_noise.load_pass_noise`):
        ``pass_offset_sigma_m`` and ``pass_heading_bias_sigma_deg`` are the priors of each pass's
        offset (per axis) and heading bias.
    ping_position_sigma_m : float, >= 0, optional
        Per-ping horizontal position noise left after a pass's offset (m): added along track to
        the beam-plane sigma (over the range); the range's own is the file's ``range_sigma_m``.
        Default: ``noise.ping_horizontal_sigma_m``.
    ping_attitude_sigma_deg : float, >= 0, optional
        Per-ping heading and pitch noise in the beam-plane sigma, degrees. Default:
        ``noise.ping_heading_sigma_deg``.
    loss : str
        Robust loss (:data:`~sss_locus.experiments.adjustment.LOSSES`).

    Returns
    -------
    JointPings
        The features' joint estimates, the passes' corrections, the sightings with residuals and a
        summary.

    Raises
    ------
    ValueError
        A ping sigma that is not a finite number >= 0.
    """
    if not isinstance(noise, PassNoise):
        raise ValueError(f"noise must be a PassNoise (noise.load_pass_noise); got {type(noise).__name__}")
    if ping_position_sigma_m is None:
        ping_position_sigma_m = noise.ping_horizontal_sigma_m
    if ping_attitude_sigma_deg is None:
        ping_attitude_sigma_deg = noise.ping_heading_sigma_deg
    for name, v in (("ping_position_sigma_m", ping_position_sigma_m), ("ping_attitude_sigma_deg", ping_attitude_sigma_deg)):
        if not (isinstance(v, (int, float)) and np.isfinite(v) and v >= 0):
            raise ValueError(f"{name} must be a finite number >= 0; got {v!r}")
    sights = res.sightings
    pose = sensor_poses(sights, platform)
    fid = sights["feature_index"].to_numpy(np.int64)
    pid = infer_passes(sights)
    P = int(pid.max()) + 1 if len(pid) else 0
    depression = np.degrees(np.arcsin(np.clip(np.maximum(pose["height"], 0.0) / pose["ranges"], 0.0, 1.0)))
    sig_phi = np.hypot(beam_plane_sigma_rad(platform.sonar.elevation_deg, ping_attitude_sigma_deg,
                                            ping_attitude_sigma_deg, depression), ping_position_sigma_m / pose["ranges"])
    ref = np.stack([np.bincount(pid, sights[c].to_numpy(float), minlength=P) / np.bincount(pid, minlength=P)
                    for c in ("east_m", "north_m")], -1)
    s = Sightings(feature=fid, pass_index=pid, origin_m=pose["origin"], W=pose["W"], range_m=pose["ranges"],
                  range_sigma_m=sights["range_sigma_m"].to_numpy(float), beam_plane_sigma_rad=sig_phi,
                  along_track_m=np.zeros(len(sights)))
    priors = NavigationPriors(offset_sigma_m=max(noise.pass_offset_sigma_m, 1e-3),
                              heading_sigma_deg=noise.pass_heading_bias_sigma_deg,
                              drift_sigma=0.0, reference_m=ref)
    feats = res.features
    start = feats[["flat_east_m", "flat_north_m", "flat_up_m"]].to_numpy(float)
    # the start: the median of each feature's flat-seafloor positions (a wrong match moves a mean)
    med = sights.groupby(fid)[["flat_east_m", "flat_north_m", "flat_up_m"]].median().reindex(range(len(feats)))
    out = adjust(s, priors, np.where(np.isfinite(med.to_numpy(float)), med.to_numpy(float), start), loss=loss)
    ok = out.adjusted
    n_passes = np.bincount(np.unique(fid * max(P, 1) + pid) // max(P, 1), minlength=len(feats))
    major, minor, azimuth, sigma_up = ellipse_axes(np.where(ok[:, None, None], out.covariance_m2, np.nan))
    point = np.where(ok[:, None], out.point_m, np.nan)
    misfit_m = np.hypot(out.range_residual * s.range_sigma_m, np.nan_to_num(out.beam_plane_residual) * sig_phi * s.range_m)
    rms = np.sqrt(np.bincount(fid, np.nan_to_num(misfit_m ** 2), minlength=len(feats))
                  / np.maximum(np.bincount(fid, minlength=len(feats)), 1))
    flat = sights[["flat_east_m", "flat_north_m"]].to_numpy(float)
    mean = start[fid, :2]
    scatter = np.sqrt(np.bincount(fid, np.sum((flat - mean) ** 2, axis=1), minlength=len(feats))
                      / np.maximum(np.bincount(fid, minlength=len(feats)), 1))
    table = pd.DataFrame({"feature": feats["feature"].to_numpy(), "n_passes": n_passes,
                          "joint_status": np.where(ok, "adjusted", "one pass"),
                          "joint_east_m": point[:, 0], "joint_north_m": point[:, 1], "joint_up_m": point[:, 2],
                          "joint_ellipse_major_m": major, "joint_ellipse_minor_m": minor,
                          "joint_ellipse_azimuth_deg": azimuth, "joint_sigma_up_m": sigma_up,
                          "joint_rms_misfit_m": np.where(ok, rms, np.nan),
                          "mosaic_minus_joint_h_m": np.hypot(*(start[:, :2] - point[:, :2]).T),
                          "mosaic_minus_joint_up_m": start[:, 2] - point[:, 2]})
    if res.frame is not None:
        lon, lat = res.frame.to_lonlat(np.nan_to_num(point[:, 0]), np.nan_to_num(point[:, 1]))
        table["joint_lon_deg"], table["joint_lat_deg"] = np.where(ok, lon, np.nan), np.where(ok, lat, np.nan)
    passes = pass_table(sights, pid, out.corrections, out.correction_sigma)
    sights = sights.assign(**{"pass": pid, "range_residual": out.range_residual,
                              "beam_plane_residual": out.beam_plane_residual, "downweighted": out.downweighted,
                              "gated": out.gated})
    mosaic_d = float(np.median(scatter[ok])) if ok.any() else np.nan
    joint_d = float(np.median(rms[ok])) if ok.any() else np.nan
    summary = dict(n_adjusted=int(ok.sum()), n_passes=P, mosaic_disagreement_m=mosaic_d, joint_misfit_m=joint_d,
                   shape_ratio=mosaic_d / joint_d if joint_d > 0 else np.nan,
                   common_shift_sigma_m=float(np.nanmax(out.common_shift_sigma_m)) if ok.any() else np.nan,
                   n_downweighted=int(np.sum(out.downweighted)), n_gated=int(np.sum(out.gated)),
                   n_used=int(np.sum(np.isfinite(out.weight))), ping_position_sigma_m=float(ping_position_sigma_m),
                   ping_attitude_sigma_deg=float(ping_attitude_sigma_deg), success=out.success)
    return JointPings(features=table, passes=passes, sightings=sights, summary=summary)


def pass_table(sights: pd.DataFrame, pid, corrections, sigma) -> pd.DataFrame:
    """Each pass's lines, heading and estimated correction (see :class:`JointPings`).

    Parameters
    ----------
    sights : pandas.DataFrame
        The sightings (``source``, ``line``, ``grid_heading_deg``), m rows.
    pid : numpy.ndarray
        Pass index per sighting, shape (m,).
    corrections : numpy.ndarray
        Pass corrections, shape (P, 5) (offsets m, heading rad).
    sigma : numpy.ndarray
        Their 1-sigma, shape (P, 5).

    Returns
    -------
    pandas.DataFrame
        One row per pass: ``source``, ``first_line``, ``last_line``, ``n_sightings``,
        ``heading_deg``, offsets (m) and heading bias (deg) with their sigmas.
    """
    g = pd.DataFrame({"pass": pid, "source": sights["source"].astype(str).to_numpy(), "line": sights["line"].to_numpy(),
                      "h": sights["grid_heading_deg"].to_numpy(float)}).groupby("pass", sort=True)
    t = g.agg(source=("source", "first"), first_line=("line", "min"), last_line=("line", "max"),
              n_sightings=("line", "size"), heading_deg=("h", "median")).reset_index()
    P = len(t)
    return t.assign(offset_east_m=corrections[:P, 0], offset_east_sigma_m=sigma[:P, 0],
                    offset_north_m=corrections[:P, 1], offset_north_sigma_m=sigma[:P, 1],
                    heading_bias_deg=-np.degrees(corrections[:P, 2]), heading_bias_sigma_deg=np.degrees(sigma[:P, 2]))


def with_joint(res: PingResults, joint: JointPings) -> PingResults:
    """``res`` with the joint estimate's columns added to its features table (``joint_...``,
    ``n_passes``) and its sightings table (``pass``, residuals, ``downweighted``), so that the
    chapter's tables, figures and GeoJSON carry it beside the other estimates.

    Parameters
    ----------
    res : PingResults
        The per-feature results.
    joint : JointPings
        :func:`joint_estimate` of them.

    Returns
    -------
    PingResults
        A new result (``excluded`` not carried over).
    """
    feats = res.features.merge(joint.features, on="feature", how="left", validate="one_to_one")
    extra = [c for c in joint.sightings.columns if c not in res.sightings.columns]
    return PingResults(features=feats, sightings=res.sightings.join(joint.sightings[extra]), locus=res.locus,
                       frame=res.frame)
