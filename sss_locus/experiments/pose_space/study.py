"""Seeded, vectorised Monte Carlo sampler of two-view relative poses (the paper's Sec. IV-A).

Method (Norman & Mangelson, Sec. IV-A, with every choice the paper leaves open named here)
----------------------------------------------------------------------------------------------
1. **Sensor 1 is fixed**: vehicle 1 sits at the world origin with zero yaw, pitch and roll; sensor 1
   is its ``side1`` transducer (``"port"`` by default, so the feature is on vehicle 1's port side).
2. **The feature** is drawn inside sensor 1's aperture and range (frame 1: range ``r1``, azimuth
   ``theta1``, elevation ``phi1``). ``feature_distribution`` says what "uniform" means:
   ``"angles"`` (default) draws ``r``, ``theta`` and ``phi`` independently and uniformly over
   their intervals; ``"volume"`` draws uniformly in the volume of the aperture
   (``r**3`` and ``sin(phi)`` uniform, ``theta`` uniform).
3. **Sensor 2** is drawn independently: its side (``side2``: ``"either"`` by default, each with
   probability 1/2), vehicle 2's attitude (yaw uniform in [-180, 180) deg; pitch uniform in
   [-pitch_max, pitch_max]; roll uniform in [-roll_max, roll_max], from the platform's limits),
   and the feature's range, azimuth and elevation in sensor 2's frame (same distribution as for
   sensor 1). Sensor 2's position follows: ``o2 = f - R2 p2``. ``R = R2^T R1``, ``t = R2^T (o1 - o2)``
   (``p2 = R p1 + t``, the kernel's convention).
4. **Physical plausibility** (``profile="platform"``):
   - the feature lies strictly below both sensors (a draw with the feature at or above either
     sensor is redrawn; ``feature_below=False`` lifts this rule, to measure what it does). For
     a transducer tilted down by ``tilt`` this keeps only azimuths ``theta > -tilt`` (to first
     order in the narrow elevation), so part of a fan wider than ``2 tilt`` is never sampled
     (:func:`sss_locus.experiments.pose_space.choices.fan_share_removed` measures that part);
   - a platform whose depth is fixed (a surface vessel, ``depth_min_m == depth_max_m``) keeps
     both vehicles' reference points at that depth **exactly**: sensor 2's range and elevation
     are drawn as above and its azimuth is then *solved* so that sensor 2 sits at the right
     depth (of the two solutions, those inside the azimuth aperture; one at random if both are);
     draws where neither solution is in the aperture are redrawn. So for the boat ``theta2`` is
     not independently uniform — it is conditioned on the equal draft;
   - for other platforms, ``vehicle_depths`` says how the two vehicles' depths are bounded (the
     paper does not say; an open choice). ``"in_water"`` (default): vehicle 1's reference point
     is at ``vehicle1_depth_m`` below the surface, or, if that is ``None``, at a depth drawn
     uniformly in the platform's depth range ``[depth_min_m, depth_max_m]``, and vehicle 2's
     must lie in that range too, so both vehicles are in the water (``depth_min_m >= 0`` is
     enforced by the data reader). ``"difference"``: only the two depths' difference is bounded
     by ``depth_max_m - depth_min_m``; vehicle 2 may then be above the sea surface (the pose-space
     chapter measures how often), the relative sampler of earlier versions.
     ``"free"``: no depth rule;
   Because draws are redrawn *jointly*, the accepted samples follow the product distribution
   above conditioned on the constraints: marginals can differ from uniform (for the boat, for
   example, features deep below sensor 1 need a long ``r2`` and are accepted less often, so
   ``theta1`` is not exactly uniform).
   ``profile="unconstrained"`` is the idealised sweep the paper tried first: sensor 2's
   orientation is uniform over all rotations, and none of the constraints above apply.
5. **The locus** is the circle cropped to both apertures (the paper's definition). With
   ``water`` (a :class:`~sss_locus.experiments.datamodel.water_column.WaterColumn`; off by default, so the
   paper is reproduced as written) it is also cropped exactly to the water: below the sea
   surface (vehicle 1's reference point ``water.vehicle_depth_m`` below it; the boat's at the
   waterline) and, optionally, above a seafloor (``water.seafloor_below_feature_m`` below each
   feature; a fixed ``max_water_depth_m`` is refused where sampled features lie below it). The samples do not change, only the
   locus: the tables with and without ``water`` compare row by row.

Targeted sampling: ``azimuth1_window_deg`` / ``azimuth2_window_deg`` draw ``theta1`` /
``theta2`` uniformly inside a window instead of the whole fan (for a fixed-depth platform, whose
``theta2`` is solved, the window of ``theta2`` rejects draws outside it). As every other draw is
independent of these angles before the joint rejection, the accepted rows follow the default
sampler's distribution conditioned on the angles lying in the windows: a cheap way to put many
more samples in one sparse heatmap bin.

Reproducibility: samples are produced in blocks of :data:`BLOCK_SIZE` rows; block ``k`` uses its
own generator seeded by ``SeedSequence(seed, spawn_key=(k,))``. The table for ``(seed, n)`` is
therefore the same whatever ``chunk_size`` (rows per kernel call, a memory knob) is, and the
first ``m`` rows of a larger run equal a run of ``m`` rows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from sss_locus.geometry import elevation_misalignment, relative_pose, two_view_locus
from sss_locus.experiments.datamodel.platforms import SIDES, Platform
from sss_locus.experiments.pose_space.draw import draw_round, spherical_to_cartesian  # noqa: F401 (spherical_to_cartesian: re-exported)
from sss_locus.experiments.stats.scale import map_chunks
from sss_locus.experiments.passes.straight_pass import transducer_stack
from sss_locus.experiments.datamodel.water_column import WaterColumn

BLOCK_SIZE = 4096
"""Rows per independently seeded block (fixed: changing it changes every table)."""
PROFILES = ("platform", "unconstrained")
FEATURE_DISTRIBUTIONS = ("angles", "volume")
SIDE_CHOICES = ("port", "starboard", "either")
VEHICLE_DEPTHS = ("in_water", "difference", "free")
MIN_ACCEPTANCE = 1e-3
"""Below this fraction of accepted draws the constraints are declared unsatisfiable."""

COLUMNS = (
    "r1_m", "r2_m", "mean_range_m", "baseline_m", "azimuth1_deg", "azimuth2_deg",
    "elevation1_deg", "elevation2_deg", "psi1_deg", "psi2_deg", "elevation_misalignment_deg",
    "yaw2_deg", "pitch2_deg", "roll2_deg", "depth2_minus_depth1_m", "side1", "side2",
    "locus_length_m", "locus_length_normalized", "n_arcs", "status",
)


@dataclass(frozen=True)
class PoseSpaceSpec:
    """Everything that determines a pose-space table besides ``n`` and ``seed``.

    Parameters
    ----------
    platform : Platform
        Both vehicles are of this platform (see :mod:`sss_locus.experiments.datamodel.platforms`).
    profile : {"platform", "unconstrained"}
    feature_distribution : {"angles", "volume"}
    side1, side2 : {"port", "starboard", "either"}
    pitch_max_deg, roll_max_deg : float or None
        Override the platform's attitude limits (degrees, in [0, 90]); ``None`` keeps them.
    vehicle_depths : {"in_water", "difference", "free"}
        How the two vehicles' depths are bounded (module docstring, step 4; not for fixed-depth
        platforms, which are held at their depth exactly).
    vehicle1_depth_m : float or None
        Depth of vehicle 1's reference point below the surface for ``"in_water"`` (metres, in the
        platform's depth range); ``None`` draws it uniformly in that range.
    tilt_deg : float or None
        Override the downward tilt of both transducers (degrees); ``None`` keeps the platform's.
    water : WaterColumn or None
        Crop every locus to the water column as well (see step 5 of the module docstring);
        ``None`` (default): the paper's locus, cropped to the apertures only.
    feature_below : bool
        Redraw configurations whose feature is not strictly below both sensors (the default;
        ``profile="platform"`` only).
    azimuth1_window_deg, azimuth2_window_deg : (float, float) or None
        Draw sensor 1's (sensor 2's) azimuth only inside this window, degrees, within the
        aperture (targeted sampling, module docstring); ``None`` samples the whole fan.
    """

    platform: Platform
    profile: str = "platform"
    feature_distribution: str = "angles"
    side1: str = "port"
    side2: str = "either"
    pitch_max_deg: float | None = None
    roll_max_deg: float | None = None
    vehicle_depths: str = "in_water"
    vehicle1_depth_m: float | None = None
    tilt_deg: float | None = None
    water: WaterColumn | None = None
    feature_below: bool = True
    azimuth1_window_deg: tuple[float, float] | None = None
    azimuth2_window_deg: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        for name, choices in (("profile", PROFILES), ("feature_distribution", FEATURE_DISTRIBUTIONS),
                              ("side1", SIDE_CHOICES), ("side2", SIDE_CHOICES),
                              ("vehicle_depths", VEHICLE_DEPTHS)):
            if getattr(self, name) not in choices:
                raise ValueError(f"{name} must be one of {list(choices)}; got {getattr(self, name)!r}")
        if not isinstance(self.platform, Platform):
            raise ValueError(f"platform must be a sss_locus.experiments.datamodel.platforms.Platform; got {type(self.platform).__name__}")
        limited = self.platform.with_attitude_limits(pitch_max_deg=self.pitch_max_deg,
                                                     roll_max_deg=self.roll_max_deg)
        if self.tilt_deg is not None:
            limited = limited.with_tilt(self.tilt_deg)
        if self.water is not None:
            if not isinstance(self.water, WaterColumn):
                raise ValueError(f"water must be a WaterColumn or None; got {type(self.water).__name__}")
            self.water.depth_for(limited)  # a depth the platform can have
        object.__setattr__(self, "platform", limited)
        d1 = self.vehicle1_depth_m
        if d1 is not None and not (isinstance(d1, (int, float)) and limited.depth_min_m <= d1 <= limited.depth_max_m):
            raise ValueError(f"vehicle1_depth_m must lie in platform {limited.key!r}'s depth range "
                             f"[{limited.depth_min_m:g}, {limited.depth_max_m:g}] m; got {d1!r}")
        half = limited.sonar.azimuth_deg / 2
        for name in ("azimuth1_window_deg", "azimuth2_window_deg"):
            w = getattr(self, name)
            if w is None:
                continue
            if (len(w) != 2 or not all(math.isfinite(float(v)) for v in w) or not -half <= w[0] < w[1] <= half):
                raise ValueError(f"{name} must be (lo, hi) degrees with -{half:g} <= lo < hi <= {half:g} "
                                 f"(the azimuth aperture); got {w!r}")
            object.__setattr__(self, name, (float(w[0]), float(w[1])))
        object.__setattr__(self, "pitch_max_deg", limited.pitch_max_deg)
        object.__setattr__(self, "roll_max_deg", limited.roll_max_deg)

    def key(self) -> dict:
        """Plain-data description (for cache keys and figure manifests).

        Returns
        -------
        dict
            The platform key, constraints and windows as plain numbers and strings.
        """
        d = {k: getattr(self, k) for k in self.__dataclass_fields__ if k not in ("platform", "water")}
        d["platform"] = self.platform.key
        if self.water is not None:  # absent when off: the paper's runs keep their keys
            d["water"] = self.water.key()
        return d


def draw_block(spec: PoseSpaceSpec, seed: int, block: int) -> dict[str, np.ndarray]:
    """Block ``block`` (:data:`BLOCK_SIZE` accepted configurations) of the stream for ``seed``.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study (platform, constraints, windows).
    seed : int
        Seed of the stream, ``>= 0``.
    block : int
        Index of the block in the stream, ``>= 0``.

    Returns
    -------
    dict of str to numpy.ndarray
        The raw configurations of the block (:func:`sample_geometry`'s arrays), each with
        :data:`BLOCK_SIZE` rows.
    """
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(block,)))
    parts, have, tried = [], 0, 0  # parts: the kept rows of each round
    while have < BLOCK_SIZE:
        m = max(BLOCK_SIZE, 2 * (BLOCK_SIZE - have))
        rows, accepted = draw_round(spec, rng, m, BLOCK_SIZE - have)  # accepted rows beyond the block: unused
        tried += m
        parts.append(rows)
        have += accepted
        if tried >= 20 * BLOCK_SIZE and have < MIN_ACCEPTANCE * tried:
            raise ValueError(
                f"the constraints of platform {spec.platform.key!r} accept only {have} of {tried} "
                "draws: check its mounting, attitude limits and depth envelope")
    out = {k: np.concatenate([rows[k] for rows in parts]) for k in parts[0]}
    # row by row, so the same numbers as for every candidate, computed for the accepted ones only
    R, t = relative_pose(out.pop("R1"), out["o1"], out.pop("R2"), out["o2"])
    return {"R": R, "t": t, **out}


def _evaluate(spec: PoseSpaceSpec, g: dict[str, np.ndarray]) -> pd.DataFrame:
    ap = spec.platform.sonar.aperture()
    crop = {}
    if spec.water is not None:  # vehicle 1 is the world frame; its reference point at z = 0
        R1, o1 = transducer_stack(spec.platform, g["port1"])
        normals, offsets = spec.water.half_spaces(R1, o1[:, 2], spec.water.depth_for(spec.platform),
                                                  feature_z=g["f"][:, 2])
        crop = dict(half_space_normals=normals, half_space_offsets=offsets)
    res = two_view_locus(g["R"], g["t"], g["r1"], g["r2"], ap, ap, outputs="lengths", **crop)
    mis = elevation_misalignment(g["R"], g["t"])
    mean_range = 0.5 * (g["r1"] + g["r2"])
    side = lambda port: pd.Categorical.from_codes(  # = Categorical of the names, without strings
        np.where(port, SIDES.index("port"), SIDES.index("starboard")).astype(np.int8), categories=list(SIDES))
    return pd.DataFrame({
        "r1_m": g["r1"], "r2_m": g["r2"], "mean_range_m": mean_range,
        "baseline_m": np.linalg.norm(g["t"], axis=-1),
        "azimuth1_deg": np.degrees(g["th1"]), "azimuth2_deg": np.degrees(g["th2"]),
        "elevation1_deg": np.degrees(g["ph1"]), "elevation2_deg": np.degrees(g["ph2"]),
        "psi1_deg": mis.psi1_deg, "psi2_deg": mis.psi2_deg,
        "elevation_misalignment_deg": mis.misalignment_deg,
        "yaw2_deg": g["yaw"], "pitch2_deg": g["pitch"], "roll2_deg": g["roll"],
        "depth2_minus_depth1_m": -g["v2_z"],
        "side1": side(g["port1"]), "side2": side(g["port2"]),
        "locus_length_m": res.length, "locus_length_normalized": res.length / mean_range,
        "n_arcs": res.n_arcs.astype(np.int8), "status": res.status.astype(np.int8),
    })


def evaluate_blocks(spec: PoseSpaceSpec, seed: int, first: int, stop: int, n: int) -> pd.DataFrame:
    """Rows of blocks ``first .. stop - 1`` (cut at row ``n``): one chunk of the study.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    seed : int
        Seed of the stream.
    first, stop : int
        Blocks ``first .. stop - 1`` of the stream.
    n : int
        Rows of the whole study: the last block is cut at row ``n``.

    Returns
    -------
    pandas.DataFrame
        The rows of :func:`sample_pose_space` of those blocks, in stream order.
    """
    blocks = [draw_block(spec, seed, k) for k in range(first, stop)]
    g = {key: np.concatenate([b[key] for b in blocks])[:n - first * BLOCK_SIZE] for key in blocks[0]}
    return _evaluate(spec, g)


def sample_geometry(spec: PoseSpaceSpec, n: int, seed: int) -> dict[str, np.ndarray]:
    """The first ``n`` raw configurations (``R``, ``t``, ranges, angles, world positions ``f``,
    ``o1``, ``o2`` ...) for ``seed``; the rows of :func:`sample_pose_space` in the same order.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    n : int
        Number of configurations, ``>= 1``.
    seed : int
        Seed of the stream, ``>= 0``.

    Returns
    -------
    dict of str to numpy.ndarray
        Per quantity, an array with ``n`` rows along its first axis (rotations ``(n, 3, 3)``,
        vectors ``(n, 3)``, metres and radians).
    """
    n, seed = check_n_seed(n, seed)
    blocks = [draw_block(spec, seed, k) for k in range(-(-n // BLOCK_SIZE))]
    return {k: np.concatenate([b[k] for b in blocks])[:n] for k in blocks[0]} if blocks else {}


def check_n_seed(n, seed):
    """The sample count and seed as ``int``, checked before any work starts.

    Parameters
    ----------
    n : int
        Number of samples, ``>= 1``.
    seed : int
        Seed, ``>= 0``.

    Returns
    -------
    (int, int)
        ``(n, seed)``.

    Raises
    ------
    ValueError
        Naming ``n_samples`` or ``seed`` and the valid range.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n_samples must be a positive integer; got {n!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer; got {seed!r}")
    return int(n), int(seed)


def sample_pose_space(spec: PoseSpaceSpec, n_samples: int, seed: int, *,
                      chunk_size: int = 65536, progress=None) -> pd.DataFrame:
    """Monte Carlo table of ``n_samples`` two-view configurations (one row each).

    Parameters
    ----------
    spec : PoseSpaceSpec
    n_samples : int
    seed : int
        Non-negative; the table depends only on ``(spec, n_samples, seed)``.
    chunk_size : int
        Rows per kernel evaluation (memory; rounded down to whole blocks of
        :data:`BLOCK_SIZE`, at least one) and per chunk of work (:mod:`sss_locus.experiments.stats.scale`:
        chunks run in-process or on a Dask cluster); does not change the result.
    progress : callable or None
        ``progress(done, total)`` after each chunk (``scale.map_chunks``); no effect on the result.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS`. Lengths in metres, angles in degrees (sensor frames as in
        :mod:`sss_locus.experiments.datamodel.platforms`). ``yaw2_deg``/``pitch2_deg``/``roll2_deg`` are vehicle 2's
        attitude relative to vehicle 1 (yaw toward port positive, pitch nose-up positive);
        ``depth2_minus_depth1_m`` how much deeper vehicle 2's reference point is;
        ``locus_length_normalized`` = ``locus_length_m / mean_range_m``; ``status`` is the
        kernel's :class:`~sss_locus.geometry.locus.LocusStatus`.
    """
    n, seed = check_n_seed(n_samples, seed)
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be a positive integer; got {chunk_size!r}")
    per_task = max(1, chunk_size // BLOCK_SIZE)  # whole blocks per kernel call and per chunk
    n_blocks = -(-n // BLOCK_SIZE)
    tasks = [(spec, seed, k, min(k + per_task, n_blocks), n) for k in range(0, n_blocks, per_task)]
    out = pd.concat(map_chunks(evaluate_blocks, tasks, progress), ignore_index=True)
    return out[list(COLUMNS)]
