"""Two straight survey passes over one seafloor feature (the paper's Sec. IV-D and Fig. 5).

Geometry (frames as in :mod:`sss_locus.platforms`)
--------------------------------------------------
World frame: origin at the feature, ``x`` along pass 1's heading, ``y`` to its port, ``z`` up.
Pass ``k`` is a straight, horizontal track at heading ``h_k`` (pass 1: 0; pass 2: the crossing
angle ``gamma``, positive toward port), with unit direction ``e = (cos h, sin h, 0)`` and port
normal ``n = (-sin h, cos h, 0)``. The vehicle holds a constant pitch (positive nose-up) and
zero roll, its body axis turned by the pitch about ``n`` while it moves along ``e`` (a trimmed
vehicle at constant altitude). At along-track position ``s`` its reference point is
``P(s) = s e - y n + a z``, where ``a`` is the altitude of the reference point above the feature
and ``y`` is the signed across-track ground offset of the feature (positive to port).

The observing transducer (rotation ``M`` and position ``m`` in the vehicle frame) has axes
``W = R_v M`` and origin ``o(s) = P(s) + R_v m`` in the world, so the feature in the transducer
frame is **linear in s**::

    p(s) = W^T (0 - o(s)) = a_vec - s b,   a_vec = W^T (y n - a z - R_v m),   b = W^T e,

with ``|b| = 1``. The ping that sees the feature at in-beam elevation ``phi`` satisfies
``p_z = sin(phi) |p|``. Squaring gives ``A s^2 + B s + C = 0`` with ``A = b_z^2 - sin^2 phi``,
``B = -2 (a_z b_z - sin^2 phi (a.b))``, ``C = a_z^2 - sin^2 phi |a|^2``. Its discriminant is
``B^2 - 4AC = 4 sin^2 phi D`` with ``D = b_z^2 |a|^2 + a_z^2 - 2 a_z b_z (a.b)
- sin^2 phi (|a|^2 - (a.b)^2)``, so the roots are ``s = (a_z b_z - sin^2 phi (a.b)
± |sin phi| sqrt(D)) / A`` without cancellation. For ``phi = 0`` the condition is linear,
``s = a_z / b_z``. When ``A > 0`` (the track crosses the beam plane more steeply than the beam's
half-width, ``|b_z| > |sin phi|``; ``|b_z| = cos(pitch)`` here) the elevation along the line runs
from ``-asin(b_z)`` to ``+asin(b_z)``, so the line meets the ``+phi`` and ``-phi`` cones exactly
once each: the root kept is the one whose ``p_z`` has the sign of ``phi``
(:func:`solve_in_beam`). ``A <= 0`` (pitch within the beam half-width of 90 deg) has no unique
ping and is reported as the rejection ``"no_solution"``.

Sampling (inputs and their defaults: :mod:`sss_locus.survey_envelope`)
-----------------------------------------------------------------------
For each crossing angle, configurations are drawn until ``n_per_angle`` are accepted:

1. **Altitudes** uniform in the envelope (:class:`SurveyEnvelope`, ``data/survey.toml``); the
   boat's two passes share one (the water depth at the feature).
2. **Pitch** of each pass uniform in ``[pitch_min_deg, pitch_max_deg]`` (pass 1 at zero if
   ``level_pass1``).
3. **Sides and offsets** (:class:`OffsetModel`): the side of pass 1 is port or starboard with
   probability 1/2 (or fixed by ``side1``); pass 2's side follows ``side_rule``. The ground offset toward the observing
   side is drawn uniformly over that pass's **swath** (:func:`swath_m`: the offsets a level
   vehicle at that altitude images at zero elevation) for ``"independent"``; for ``"matched"``
   pass 2's offset is pass 1's plus a uniform jitter in ``[-jitter_m, jitter_m]``.
4. **In-beam elevation** of each pass uniform in ``[-elevation/2, elevation/2]``; the ping
   position follows exactly (above).
5. **Visibility**: the feature must be inside the observing transducer's azimuth aperture and
   range at that ping. A draw failing any check is rejected and counted under one of
   :data:`REJECTION_REASONS` (first failing check, pass 1 before pass 2); the counts per angle
   are returned with the samples (never dropped silently).

Symmetries (exact for mirror-image transducers; tested in ``tests/test_survey.py``)
-------------------------------------------------------------------------------
- *Port/starboard mirror*: reflecting the world in pass 1's vertical plane swaps the sides,
  turns ``gamma`` into ``-gamma`` and flips each in-beam elevation; lengths are unchanged.
- *View swap*: exchanging the two passes leaves length and misalignment unchanged; so does
  turning both headings by one angle.
- *Pitch reversal*: a vehicle at heading ``h`` and pitch ``q`` turned by 180 deg about its own
  vertical axis is the vehicle at heading ``h + 180`` and pitch ``-q``, and its port transducer
  takes the pose of the starboard one. So the starboard ping of a nose-up pass is the port ping
  of a nose-down pass run the other way along the same line. With random sides (or both passes
  reversed together) nose-up and nose-down pass pairs of equal magnitude therefore have the
  same distribution of locus length at every crossing angle.

Reproducibility: each angle's draws come in blocks of :data:`BLOCK_SIZE` accepted rows; block
``k`` at angle ``gamma`` uses ``SeedSequence(seed, spawn_key=(platform id, gamma in
millidegrees, k))``. An angle's samples therefore do not depend on the other angles of the
grid, and the first ``m`` rows of a larger run equal a run of ``m`` rows.
"""

from __future__ import annotations

import math
import zlib

import numpy as np
import pandas as pd

from .locus import two_view_locus
from .misalignment import elevation_misalignment
from .platforms import SIDES, Platform
from .poses import relative_pose
from .sampling import _per_side, vehicle_attitude
from .survey_envelope import (OFFSET_KINDS, SIDE1_CHOICES, SIDE_RULES, SURVEY_FILE,  # noqa: F401
                              _read_survey,
                              OffsetModel, SurveyEnvelope, default_offset_model, load_envelope)

BLOCK_SIZE = 256
"""Accepted rows per independently seeded block (fixed: changing it changes every table)."""
REJECTION_REASONS = ("outside_swath", "no_solution", "outside_azimuth", "out_of_range")
"""Why a draw is rejected: pass 2's matched offset falls outside its swath; no unique ping
(``A <= 0``); the feature is outside the observing transducer's azimuth aperture, or outside
its range limits, at the ping."""
MIN_ACCEPTANCE = 1e-3

COLUMNS = (
    "crossing_angle_deg", "locus_length_m", "locus_length_normalized",
    "elevation_misalignment_deg", "psi1_deg", "psi2_deg", "r1_m", "r2_m", "mean_range_m",
    "baseline_m", "azimuth1_deg", "azimuth2_deg", "elevation1_deg", "elevation2_deg",
    "ground_offset1_m", "ground_offset2_m", "side1", "side2", "altitude1_m", "altitude2_m",
    "pitch1_deg", "pitch2_deg", "along_track1_m", "along_track2_m", "n_arcs", "status",
)


def check_envelope(platform: Platform, envelope: SurveyEnvelope) -> None:
    """Raise ``ValueError`` if the envelope does not fit the platform (attitude limits, a swath
    at every altitude of the envelope)."""
    lim = platform.pitch_max_deg
    if max(abs(envelope.pitch_min_deg), abs(envelope.pitch_max_deg)) > lim:
        raise ValueError(f"envelope pitch [{envelope.pitch_min_deg}, {envelope.pitch_max_deg}] deg "
                         f"exceeds platform {platform.key!r}'s limit of ±{lim} deg")
    for side in SIDES:
        for alt in (envelope.altitude_min_m, envelope.altitude_max_m):
            swath_m(platform, np.array([side == "port"]), np.array([alt]))


def swath_m(platform: Platform, is_port, altitude_m) -> tuple[np.ndarray, np.ndarray]:
    """Across-track ground offsets a level vehicle images at zero elevation.

    Parameters
    ----------
    platform : Platform
    is_port : array_like of bool
        Observing transducer: port (True) or starboard (False).
    altitude_m : array_like
        Height of the vehicle reference point above the feature, metres (broadcast with
        ``is_port``).

    Returns
    -------
    near, far : ndarray
        Ground offset from the vehicle centreline, toward the observing side, metres: the
        feature is inside the transducer's azimuth fan and range for ``near <= offset <= far``.
        From the depression angles ``tilt ± azimuth/2`` of the fan edges and the range limits;
        ``near`` may be slightly negative when the fan reaches past nadir. (With a minimum range
        above the transducer's height, the sliver past nadir is left out.)

    Raises
    ------
    ValueError
        If some altitude leaves no swath (transducer not above the feature, or higher than
        the maximum range).
    """
    is_port, alt = np.broadcast_arrays(np.asarray(is_port, bool), np.asarray(altitude_m, float))
    son = platform.sonar
    tr = {s: platform.transducers[s] for s in SIDES}
    pick = lambda f: np.where(is_port, f(tr["port"]), f(tr["starboard"]))
    H = alt - pick(lambda t: t.depth_m)
    tilt, lateral = pick(lambda t: t.tilt_deg), pick(lambda t: t.lateral_offset_m)
    bad = ~(H > 0) | ~(H < son.max_range_m)
    if np.any(bad):
        raise ValueError(f"altitude_m must put the transducer above the feature and less than the "
                         f"maximum range ({son.max_range_m} m) above it; got {alt[bad][:3]}")
    reach = np.sqrt(son.max_range_m ** 2 - H ** 2)
    d_max, d_min = tilt + son.azimuth_deg / 2, tilt - son.azimuth_deg / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        near = np.where(d_max >= 180, -reach, np.where(d_max <= 0, np.inf, H / np.tan(np.radians(d_max))))
        far = np.where(d_min > 0, H / np.tan(np.radians(d_min)), np.inf)
    near = np.maximum(near, -reach)
    if son.min_range_m > 0:
        near = np.maximum(near, np.sqrt(np.maximum(son.min_range_m ** 2 - H ** 2, 0.0)))
    far = np.minimum(far, reach)
    if np.any(far <= near):
        raise ValueError(f"no swath: the {platform.key!r} fan sees no seafloor at altitude_m "
                         f"{alt[far <= near][:3]}")
    return lateral + near, lateral + far


def solve_in_beam(a, b, elevation_rad) -> tuple[np.ndarray, np.ndarray]:
    """Along-track position ``s`` at which ``p(s) = a - s b`` has elevation ``elevation_rad``.

    Parameters
    ----------
    a : array_like, shape (..., 3)
        Feature in the transducer frame at ``s = 0``, metres.
    b : array_like, shape (..., 3)
        Unit track direction in the transducer frame.
    elevation_rad : array_like, shape (...)
        In-beam elevation, radians.

    Returns
    -------
    s : ndarray, shape (...)
        Metres along the track (0 where there is no unique solution).
    ok : ndarray of bool
        False where ``b_z**2 <= sin(elevation)**2`` (no unique ping; see the module docstring).
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    sphi = np.sin(np.asarray(elevation_rad, float))
    sig = sphi ** 2
    az, bz = a[..., 2], b[..., 2]
    ab, aa = np.sum(a * b, axis=-1), np.sum(a * a, axis=-1)
    A = bz ** 2 - sig
    ok = A > 0
    A = np.where(ok, A, 1.0)
    D = np.maximum(bz ** 2 * aa + az ** 2 - 2 * az * bz * ab - sig * (aa - ab ** 2), 0.0)
    mid, half = (az * bz - sig * ab) / A, np.abs(sphi) * np.sqrt(D) / A
    roots = np.stack([mid + half, mid - half])
    pz = az - roots * bz
    s = np.where(np.sign(sphi) * pz[0] >= np.sign(sphi) * pz[1], roots[0], roots[1])
    return np.where(ok, s, 0.0), ok


def observe_pass(platform: Platform, is_port, heading_deg, ground_offset_m, altitude_m,
                 pitch_deg, elevation_rad) -> dict[str, np.ndarray]:
    """The ping of one straight pass that sees the feature (at the origin) at ``elevation_rad``.

    Parameters (arrays broadcast to one shape ``(n,)``)
    ----------
    is_port : bool
        Observing transducer.
    heading_deg : float
        Track heading, degrees, positive toward port (counter-clockwise from above).
    ground_offset_m : float
        Feature's across-track ground offset from the centreline toward the observing side, m.
    altitude_m : float
        Vehicle reference point above the feature, metres.
    pitch_deg : float
        Vehicle pitch, degrees, positive nose-up.
    elevation_rad : float
        In-beam elevation of the feature, radians.

    Returns
    -------
    dict
        ``W`` (n, 3, 3): transducer axes in the world (``p_world = W p + origin``); ``origin``
        (n, 3): transducer origin at the ping, m; ``p`` (n, 3): feature in the transducer frame;
        ``s`` (n,): along-track position of the vehicle at the ping, m; ``range_m``,
        ``azimuth_rad``, ``elevation_rad``; ``reason`` (n,) int8: -1 if visible, else the index
        in :data:`REJECTION_REASONS`.
    """
    arrays = np.broadcast_arrays(np.asarray(is_port, bool), *(np.asarray(v, float) for v in (
        heading_deg, ground_offset_m, altitude_m, pitch_deg, elevation_rad)))
    port, head, g, alt, pitch, phi = (np.atleast_1d(x) for x in arrays)
    M, m = _per_side(platform, port)
    Rv = vehicle_attitude(head, pitch, np.zeros_like(head)).as_matrix().reshape(-1, 3, 3)
    W = Rv @ M
    h = np.radians(head)
    e = np.stack([np.cos(h), np.sin(h), np.zeros_like(h)], -1)
    n = np.stack([-np.sin(h), np.cos(h), np.zeros_like(h)], -1)
    y = np.where(port, g, -g)
    mount = np.einsum("nij,nj->ni", Rv, m)
    rel0 = y[:, None] * n - alt[:, None] * np.array([0.0, 0.0, 1.0]) - mount  # feature - o(0)
    a = np.einsum("nji,nj->ni", W, rel0)
    b = np.einsum("nji,nj->ni", W, e)
    s, ok = solve_in_beam(a, b, phi)
    p = a - s[:, None] * b
    rng_m = np.linalg.norm(p, axis=-1)
    azim = np.arctan2(p[:, 1], p[:, 0])
    son = platform.sonar
    reason = np.full(port.shape, -1, np.int8)
    out_range = (rng_m > son.max_range_m) | (rng_m < son.min_range_m)
    for code, bad in ((3, out_range), (2, np.abs(azim) > math.radians(son.azimuth_deg / 2)), (1, ~ok)):
        reason = np.where(bad, np.int8(code), reason)
    origin = s[:, None] * e - y[:, None] * n + alt[:, None] * np.array([0.0, 0.0, 1.0]) + mount
    return dict(W=W, origin=origin, p=p, s=s, range_m=rng_m, azimuth_rad=azim,
                elevation_rad=np.arcsin(np.clip(p[:, 2] / np.where(rng_m > 0, rng_m, 1.0), -1, 1)),
                reason=reason)


def _seed_sequence(platform: Platform, seed: int, gamma_deg: float, block: int):
    pid = zlib.crc32(platform.key.encode())
    return np.random.SeedSequence(seed, spawn_key=(pid, int(round((gamma_deg + 360.0) * 1000)), block))


def _candidates(platform, env, model, gamma_deg, rng, m):
    """``m`` candidate pass pairs: observations of both passes and the draw's rejection code."""
    u = rng.random((10, m))
    port1 = u[0] < 0.5 if model.side1 == "random" else np.full(m, model.side1 == "port")
    port2 = {"random": u[1] < 0.5, "same": port1, "opposite": ~port1}[model.side_rule]
    span = env.altitude_max_m - env.altitude_min_m
    alt1 = env.altitude_min_m + span * u[4]
    alt2 = alt1 if env.same_altitude else env.altitude_min_m + span * u[5]
    near1, far1 = swath_m(platform, port1, alt1)
    near2, far2 = swath_m(platform, port2, alt2)
    g1 = near1 + (far1 - near1) * u[2]
    if model.kind == "independent":
        g2 = near2 + (far2 - near2) * u[3]
    else:
        g2 = g1 + model.jitter_m * (2.0 * u[3] - 1.0)
    pspan = env.pitch_max_deg - env.pitch_min_deg
    pitch1, pitch2 = env.pitch_min_deg + pspan * u[6], env.pitch_min_deg + pspan * u[7]
    if env.level_pass1:
        pitch1 = np.zeros(m)
    half_el = math.radians(platform.sonar.elevation_deg / 2)
    phi1, phi2 = (2.0 * u[8] - 1.0) * half_el, (2.0 * u[9] - 1.0) * half_el
    ob1 = observe_pass(platform, port1, 0.0, g1, alt1, pitch1, phi1)
    ob2 = observe_pass(platform, port2, gamma_deg, g2, alt2, pitch2, phi2)
    reason = np.where(ob1["reason"] >= 0, ob1["reason"], ob2["reason"])
    reason = np.where((g2 < near2) | (g2 > far2), np.int8(0), reason)
    draws = dict(port1=port1, port2=port2, g1=g1, g2=g2, alt1=alt1, alt2=alt2,
                 pitch1=pitch1, pitch2=pitch2)
    return ob1, ob2, draws, reason


def draw_block(platform: Platform, envelope: SurveyEnvelope, model: OffsetModel, gamma_deg: float,
               seed: int, block: int) -> tuple[dict[str, np.ndarray], np.ndarray, int]:
    """:data:`BLOCK_SIZE` accepted pass pairs at crossing angle ``gamma_deg``; the number of
    rejected draws per reason (aligned with :data:`REJECTION_REASONS`) and of accepted draws
    (including those past :data:`BLOCK_SIZE`, which are not used) over all draws made."""
    rng = np.random.default_rng(_seed_sequence(platform, seed, gamma_deg, block))
    parts, have, tried, rejected = [], 0, 0, np.zeros(len(REJECTION_REASONS), np.int64)
    while have < BLOCK_SIZE:
        m = max(BLOCK_SIZE, 2 * (BLOCK_SIZE - have))
        ob1, ob2, draws, reason = _candidates(platform, envelope, model, gamma_deg, rng, m)
        keep = reason < 0
        rejected += np.bincount(reason[~keep], minlength=len(REJECTION_REASONS))
        tried += m
        row = dict(draws, **{f"{k}1": v for k, v in ob1.items()}, **{f"{k}2": v for k, v in ob2.items()})
        parts.append({k: v[keep] for k, v in row.items()})
        have += int(keep.sum())
        if tried >= 20 * BLOCK_SIZE and have < MIN_ACCEPTANCE * tried:
            raise ValueError(f"only {have} of {tried} pass pairs of platform {platform.key!r} at "
                             f"crossing angle {gamma_deg} deg see the feature: check the envelope")
    return {k: np.concatenate([p[k] for p in parts])[:BLOCK_SIZE] for k in parts[0]}, rejected, have


def _check_inputs(angles, n, seed):
    g = np.atleast_1d(np.asarray(angles, float))
    if g.ndim != 1 or g.size == 0 or not np.all(np.isfinite(g)) or np.any(np.abs(g) > 180):
        raise ValueError(f"crossing_angles_deg must be a non-empty 1-D list of finite angles in "
                         f"[-180, 180] degrees; got {angles!r}")
    for name, v, lo in (("n_per_angle", n, 1), ("seed", seed, 0)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
            raise ValueError(f"{name} must be an integer >= {lo}; got {v!r}")
    return g, int(n), int(seed)


def _evaluate(platform, gamma_deg, d) -> pd.DataFrame:
    ap = platform.sonar.aperture()
    R, t = relative_pose(d["W1"], d["origin1"], d["W2"], d["origin2"])
    r1, r2 = d["range_m1"], d["range_m2"]
    res = two_view_locus(R, t, r1, r2, ap, ap)
    mis = elevation_misalignment(R, t)
    side = lambda port: pd.Categorical(np.where(port, "port", "starboard"), categories=list(SIDES))
    return pd.DataFrame({
        "crossing_angle_deg": np.full(len(r1), float(gamma_deg)),
        "locus_length_m": res.length, "locus_length_normalized": res.length / (0.5 * (r1 + r2)),
        "elevation_misalignment_deg": mis.misalignment_deg, "psi1_deg": mis.psi1_deg,
        "psi2_deg": mis.psi2_deg, "r1_m": r1, "r2_m": r2, "mean_range_m": 0.5 * (r1 + r2),
        "baseline_m": np.linalg.norm(t, axis=-1),
        "azimuth1_deg": np.degrees(d["azimuth_rad1"]), "azimuth2_deg": np.degrees(d["azimuth_rad2"]),
        "elevation1_deg": np.degrees(d["elevation_rad1"]), "elevation2_deg": np.degrees(d["elevation_rad2"]),
        "ground_offset1_m": d["g1"], "ground_offset2_m": d["g2"],
        "side1": side(d["port1"]), "side2": side(d["port2"]),
        "altitude1_m": d["alt1"], "altitude2_m": d["alt2"],
        "pitch1_deg": d["pitch1"], "pitch2_deg": d["pitch2"],
        "along_track1_m": d["s1"], "along_track2_m": d["s2"],
        "n_arcs": res.n_arcs.astype(np.int8), "status": res.status.astype(np.int8),
    })


def simulate_passes(platform: Platform, envelope: SurveyEnvelope, offset_model: OffsetModel,
                    crossing_angles_deg, n_per_angle: int, seed: int
                    ) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Monte Carlo pairs of straight passes over one feature, per crossing angle.

    Parameters
    ----------
    platform : Platform
        Both passes by this platform (:mod:`sss_locus.platforms`).
    envelope : SurveyEnvelope
    offset_model : OffsetModel
    crossing_angles_deg : array_like
        Heading of pass 2 relative to pass 1, degrees in [-180, 180] (positive toward port).
    n_per_angle : int
        Accepted pass pairs per angle.
    seed : int
        Non-negative; the result depends only on the arguments.

    Returns
    -------
    samples : pandas.DataFrame
        One row per accepted pair, columns :data:`COLUMNS`: lengths in m, angles in degrees
        (``azimuth*``/``elevation*`` in each observing transducer's frame; ``pitch*`` positive
        nose-up), ``status`` the kernel's :class:`~sss_locus.locus.LocusStatus`.
    acceptance : pandas.DataFrame
        One row per angle: ``crossing_angle_deg, n_tried, n_accepted, acceptance`` and
        ``rejected_<reason>`` for each of :data:`REJECTION_REASONS`, counted over every draw
        made (``n_accepted`` includes accepted draws beyond ``n_per_angle`` in the last block).
    """
    angles, n, seed = _check_inputs(crossing_angles_deg, n_per_angle, seed)
    if not isinstance(platform, Platform):
        raise ValueError(f"platform must be a sss_locus.platforms.Platform; got {type(platform).__name__}")
    if not isinstance(envelope, SurveyEnvelope) or not isinstance(offset_model, OffsetModel):
        raise ValueError("envelope must be a SurveyEnvelope and offset_model an OffsetModel")
    check_envelope(platform, envelope)
    frames, acc = [], []
    for gamma in angles:
        blocks = [draw_block(platform, envelope, offset_model, gamma, seed, k)
                  for k in range(-(-n // BLOCK_SIZE))]
        d = {k: np.concatenate([b[0][k] for b in blocks])[:n] for k in blocks[0][0]}
        rej, accepted = sum(b[1] for b in blocks), sum(b[2] for b in blocks)
        frames.append(_evaluate(platform, gamma, d))
        acc.append({"crossing_angle_deg": float(gamma), "n_tried": int(accepted + rej.sum()),
                    "n_accepted": int(accepted), "acceptance": accepted / float(accepted + rej.sum()),
                    **{f"rejected_{r}": int(c) for r, c in zip(REJECTION_REASONS, rej)}})
    return pd.concat(frames, ignore_index=True)[list(COLUMNS)], pd.DataFrame(acc)


def cached_passes(platform: Platform, envelope: SurveyEnvelope, offset_model: OffsetModel,
                  crossing_angles_deg, n_per_angle: int, seed: int, *,
                  notebook: str = "notebooks/survey_passes.ipynb") -> tuple[pd.DataFrame, pd.DataFrame]:
    """:func:`simulate_passes` through the result cache (:mod:`sss_locus.cache`)."""
    from .cache import cached_frame

    angles, n, seed = _check_inputs(crossing_angles_deg, n_per_angle, seed)
    key = {"notebook": notebook, "platform": platform.key, "envelope": envelope.key(),
           "offset_model": offset_model.key(), "angles": [float(a) for a in angles],
           "n_per_angle": n, "seed": seed}
    made = {}

    def run():
        made["s"], made["a"] = simulate_passes(platform, envelope, offset_model, angles, n, seed)
        return made["s"]

    samples = cached_frame({**key, "step": "survey-samples"}, run)
    acceptance = cached_frame({**key, "step": "survey-acceptance"},
                              lambda: made["a"] if "a" in made else
                              simulate_passes(platform, envelope, offset_model, angles, n, seed)[1])
    return samples, acceptance
