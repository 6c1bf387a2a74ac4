"""Two straight survey passes over one seafloor feature (the paper's Sec. IV-D and Fig. 5).

The geometry of one pass (frames, the exact ping solve) is in
:mod:`sss_locus.experiments.passes.straight_pass`.

Sampling (inputs and their defaults: :mod:`sss_locus.experiments.datamodel.envelopes`)
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
6. **Water** (``water``, off by default so the paper is reproduced as written): each locus is
   also cropped exactly to the water (:class:`~sss_locus.experiments.datamodel.water_column.WaterColumn`): the
   sea surface lies ``altitude1_m + water.vehicle_depth_m`` above the feature (the boat's
   reference point is at the waterline, so its altitude is the water depth at the feature);
   a seafloor is ``water.seafloor_below_feature_m`` below the feature. The samples are the same with and without it.

Symmetries (exact for mirror-image transducers; tested in ``tests/experiments/survey_passes/test_survey_passes.py``)
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

from sss_locus.geometry import elevation_misalignment, relative_pose, two_view_locus
from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope
from sss_locus.experiments.datamodel.platforms import SIDES, Platform
from sss_locus.experiments.stats.scale import map_chunks
from sss_locus.experiments.passes.straight_pass import REJECTION_REASONS, observe_pass, swath_m
from sss_locus.experiments.datamodel.water_column import WaterColumn

BLOCK_SIZE = 256
"""Accepted rows per independently seeded block (fixed: changing it changes every table)."""
BATCH_BLOCKS = 64
"""Blocks drawn together in one batch (speed and memory only; the result does not depend on it)."""
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
    at every altitude of the envelope).

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    """
    lim = platform.pitch_max_deg
    if max(abs(envelope.pitch_min_deg), abs(envelope.pitch_max_deg)) > lim:
        raise ValueError(f"envelope pitch [{envelope.pitch_min_deg}, {envelope.pitch_max_deg}] deg "
                         f"exceeds platform {platform.key!r}'s limit of ±{lim} deg")
    for side in SIDES:
        for alt in (envelope.altitude_min_m, envelope.altitude_max_m):
            swath_m(platform, np.array([side == "port"]), np.array([alt]))


def _seed_sequence(platform: Platform, seed: int, gamma_deg: float, block: int):
    pid = zlib.crc32(platform.key.encode())
    return np.random.SeedSequence(seed, spawn_key=(pid, int(round((gamma_deg + 360.0) * 1000)), block))


def _candidates(platform, env, model, gamma_deg, u):
    """Candidate pass pairs from uniforms ``u`` (10, m): observations of both passes and the
    draw's rejection code. Row by row (no reductions across rows), so candidates of several
    blocks evaluated together equal those evaluated block by block, bit for bit."""
    m = u.shape[1]
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
    (including those past :data:`BLOCK_SIZE`, which are not used) over all draws made.

    Block ``block`` draws rounds of ``m = max(BLOCK_SIZE, 2 * missing)`` candidates from its own
    generator until it has :data:`BLOCK_SIZE` accepted ones.

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    model : OffsetModel
        How the passes' ground offsets are drawn.
    gamma_deg : float
        Crossing angle, degrees.
    seed : int
        Seed of the stream, ``>= 0``.
    block : int
        Index of the block in the stream.

    Returns
    -------
    rows : dict of str to numpy.ndarray
        The accepted pass pairs, :data:`BLOCK_SIZE` rows each.
    rejected : numpy.ndarray of int
        Rejected draws per reason of :data:`REJECTION_REASONS`.
    accepted : int
        Accepted draws.
    """
    return draw_blocks(platform, envelope, model, gamma_deg, seed, [block])[0]


def draw_blocks(platform: Platform, envelope: SurveyEnvelope, model: OffsetModel, gamma_deg: float,
                seed: int, blocks) -> list[tuple[dict[str, np.ndarray], np.ndarray, int]]:
    """:func:`draw_block` for each of ``blocks``, the same bit for bit, with each round's
    candidates of all unfinished blocks evaluated in one batch (blocks of 256 rows are too
    small for NumPy to run near its speed one by one).

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    model : OffsetModel
        How the passes' ground offsets are drawn.
    gamma_deg : float
        Crossing angle, degrees.
    seed : int
        Seed of the stream.
    blocks : sequence of int
        Indices of the blocks.

    Returns
    -------
    list of (dict, numpy.ndarray, int)
        :func:`draw_block`'s result for each block, in the order of ``blocks``.
    """
    blocks = list(blocks)
    rngs = [np.random.default_rng(_seed_sequence(platform, seed, gamma_deg, k)) for k in blocks]
    parts = [[] for _ in blocks]
    have, tried = np.zeros(len(blocks), np.int64), np.zeros(len(blocks), np.int64)
    rejected = np.zeros((len(blocks), len(REJECTION_REASONS)), np.int64)
    active = list(range(len(blocks)))
    while active:
        sizes = [max(BLOCK_SIZE, 2 * (BLOCK_SIZE - int(have[i]))) for i in active]
        u = np.concatenate([rngs[i].random((10, m)) for i, m in zip(active, sizes)], axis=1)
        ob1, ob2, draws, reason = _candidates(platform, envelope, model, gamma_deg, u)
        row = dict(draws, **{f"{k}1": v for k, v in ob1.items()}, **{f"{k}2": v for k, v in ob2.items()})
        start = 0
        for i, m in zip(active, sizes):
            sl = slice(start, start + m)
            start += m
            keep = reason[sl] < 0
            rejected[i] += np.bincount(reason[sl][~keep], minlength=len(REJECTION_REASONS))
            tried[i] += m
            parts[i].append({k: v[sl][keep] for k, v in row.items()})
            have[i] += int(keep.sum())
            if tried[i] >= 20 * BLOCK_SIZE and have[i] < MIN_ACCEPTANCE * tried[i]:
                raise ValueError(f"only {have[i]} of {tried[i]} pass pairs of platform {platform.key!r} at "
                                 f"crossing angle {gamma_deg} deg see the feature: check the envelope")
        active = [i for i in active if have[i] < BLOCK_SIZE]
    return [({k: np.concatenate([p[k] for p in parts[i]])[:BLOCK_SIZE] for k in parts[i][0]},
             rejected[i], int(have[i])) for i in range(len(blocks))]


def check_inputs(angles, n, seed):
    """The crossing angles, pass pairs per angle and seed, checked before any work starts.

    Parameters
    ----------
    angles : array_like
        Crossing angles, degrees, each in [-180, 180] (a 1-D list, not empty).
    n : int
        Accepted pass pairs per angle, ``>= 1``.
    seed : int
        Seed, ``>= 0``.

    Returns
    -------
    (numpy.ndarray, int, int)
        The angles as a float array, ``n`` and ``seed`` as ``int``.
    """
    g = np.atleast_1d(np.asarray(angles, float))
    if g.ndim != 1 or g.size == 0 or not np.all(np.isfinite(g)) or np.any(np.abs(g) > 180):
        raise ValueError(f"crossing_angles_deg must be a non-empty 1-D list of finite angles in "
                         f"[-180, 180] degrees; got {angles!r}")
    for name, v, lo in (("n_per_angle", n, 1), ("seed", seed, 0)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
            raise ValueError(f"{name} must be an integer >= {lo}; got {v!r}")
    return g, int(n), int(seed)


def _evaluate(platform, gamma_deg, d, water=None) -> pd.DataFrame:
    ap = platform.sonar.aperture()
    R, t = relative_pose(d["W1"], d["origin1"], d["W2"], d["origin2"])
    r1, r2 = d["range_m1"], d["range_m2"]
    crop = {}
    if water is not None:  # world origin at the feature: the surface is above vehicle 1
        normals, offsets = water.half_spaces(d["W1"], d["origin1"][:, 2],
                                             d["alt1"] + water.depth_for(platform),
                                             feature_z=np.zeros(len(d["alt1"])))
        crop = dict(half_space_normals=normals, half_space_offsets=offsets)
    res = two_view_locus(R, t, r1, r2, ap, ap, outputs="lengths", **crop)
    mis = elevation_misalignment(R, t)
    side = lambda port: pd.Categorical.from_codes(  # = Categorical of the names, without strings
        np.where(port, SIDES.index("port"), SIDES.index("starboard")).astype(np.int8), categories=list(SIDES))
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


def _simulate_angle(platform, envelope, offset_model, gamma, n, seed, water=None) -> tuple[pd.DataFrame, dict]:
    """One crossing angle (one chunk of the study): its samples and its acceptance row."""
    n_blocks = -(-n // BLOCK_SIZE)
    blocks = [b for first in range(0, n_blocks, BATCH_BLOCKS) for b in draw_blocks(
        platform, envelope, offset_model, gamma, seed, range(first, min(first + BATCH_BLOCKS, n_blocks)))]
    d = {k: np.concatenate([b[0][k] for b in blocks])[:n] for k in blocks[0][0]}
    rej, accepted = sum(b[1] for b in blocks), sum(b[2] for b in blocks)
    return _evaluate(platform, gamma, d, water), {
        "crossing_angle_deg": float(gamma), "n_tried": int(accepted + rej.sum()),
        "n_accepted": int(accepted), "acceptance": accepted / float(accepted + rej.sum()),
        **{f"rejected_{r}": int(c) for r, c in zip(REJECTION_REASONS, rej)}}


def simulate_passes(platform: Platform, envelope: SurveyEnvelope, offset_model: OffsetModel,
                    crossing_angles_deg, n_per_angle: int, seed: int, *,
                    water: WaterColumn | None = None, progress=None) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Monte Carlo pairs of straight passes over one feature, per crossing angle.

    Parameters
    ----------
    platform : Platform
        Both passes by this platform (:mod:`sss_locus.experiments.datamodel.platforms`).
    envelope : SurveyEnvelope
    offset_model : OffsetModel
    crossing_angles_deg : array_like
        Heading of pass 2 relative to pass 1, degrees in [-180, 180] (positive toward port).
    n_per_angle : int
        Accepted pass pairs per angle.
    seed : int
        Non-negative; the result depends only on the arguments.
    water : WaterColumn or None
        Also crop every locus to the water column (step 6 above); ``None`` (default): the
        paper's locus. The samples and the acceptance table do not depend on it.
    progress : callable or None
        Called as ``progress(done, total)`` after each crossing angle (one chunk,
        :func:`~sss_locus.experiments.stats.scale.map_chunks`); does not change the result.

    Returns
    -------
    samples : pandas.DataFrame
        One row per accepted pair, columns :data:`COLUMNS`: lengths in m, angles in degrees
        (``azimuth*``/``elevation*`` in each observing transducer's frame; ``pitch*`` positive
        nose-up), ``status`` the kernel's :class:`~sss_locus.geometry.locus.LocusStatus`.
    acceptance : pandas.DataFrame
        One row per angle: ``crossing_angle_deg, n_tried, n_accepted, acceptance`` and
        ``rejected_<reason>`` for each of :data:`REJECTION_REASONS`, counted over every draw
        made (``n_accepted`` includes accepted draws beyond ``n_per_angle`` in the last block).
    """
    angles, n, seed = check_inputs(crossing_angles_deg, n_per_angle, seed)
    if not isinstance(platform, Platform):
        raise ValueError(f"platform must be a sss_locus.experiments.datamodel.platforms.Platform; got {type(platform).__name__}")
    if not isinstance(envelope, SurveyEnvelope) or not isinstance(offset_model, OffsetModel):
        raise ValueError("envelope must be a SurveyEnvelope and offset_model an OffsetModel")
    check_envelope(platform, envelope)
    if water is not None:
        if not isinstance(water, WaterColumn):
            raise ValueError(f"water must be a WaterColumn or None; got {type(water).__name__}")
        water.depth_for(platform)
    chunks = map_chunks(_simulate_angle, [(platform, envelope, offset_model, float(g), n, seed, water)
                                          for g in angles], progress)
    frames, acc = [c[0] for c in chunks], [c[1] for c in chunks]
    return pd.concat(frames, ignore_index=True)[list(COLUMNS)], pd.DataFrame(acc)
