"""The sea-surface crop measured on the book's two studies (the chapter ``notebooks/water.ipynb``).

Each *condition* is one platform in one study (pose space or survey passes) with one
:class:`~sss_locus.experiments.datamodel.water_column.WaterColumn`. It is run twice with the same seed, without
and with the crop; the samples are identical, so :func:`crop_effect`
compares the two tables row by row (paired bootstrap intervals). Fragmentation (the share of
loci with more than one arc) is reported on all samples and, for the pose space, also on the
subset the pose-space chapter's ``multi_arc_fraction`` uses: sensor 2 on the port side, like
sensor 1 (its heatmap subset, ``heatmap_side2 = "port"``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.datadoc import label_key
from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope
from sss_locus.experiments.datamodel.platforms import Platform
from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.stats.replicates import (N_BATCHES, batch_statistic, check_batches, check_confidence,
                                                   replicate_interval)
from sss_locus.experiments.datamodel.water_column import WaterColumn

STUDIES = ("pose space", "survey passes")


@dataclass(frozen=True)
class Condition:
    """One platform, study and water column (see the module docstring).

    ``tilt_deg`` overrides the transducers' tilt (pose space only; ``None`` keeps the data's);
    ``envelope`` and ``offset_model`` are needed for the survey passes.
    """

    platform: Platform
    study: str
    water: WaterColumn
    tilt_deg: float | None = None
    envelope: SurveyEnvelope | None = None
    offset_model: OffsetModel | None = None

    def __post_init__(self) -> None:
        if self.study not in STUDIES:
            raise ValueError(f"study must be one of {list(STUDIES)}; got {self.study!r}")
        if self.study == "survey passes" and (self.envelope is None or self.offset_model is None):
            raise ValueError("a survey-passes condition needs an envelope and an offset_model")
        self.water.depth_for(self.platform)

    @property
    def slug(self) -> str:
        """Short key for glue names and file names, e.g. ``boat-pose-tilt15`` or
        ``auv-survey-depth2m``."""
        study = "pose" if self.study == "pose space" else "survey"
        parts = [label_key(self.platform.key), study]
        if self.tilt_deg is not None:
            parts.append(f"tilt{self.tilt_deg:g}".replace(".", "p"))
        if self.water.vehicle_depth_m is not None:
            parts.append(f"depth{self.water.vehicle_depth_m:g}m".replace(".", "p"))
        if self.water.seafloor_below_feature_m is not None:
            parts.append(f"floor{self.water.seafloor_below_feature_m:g}m".replace(".", "p"))
        return "-".join(parts)

    @property
    def crop(self) -> str:
        """``"surface"`` or ``"surface + seafloor"``: what the water crop bounds."""
        w = self.water
        return "surface" if w.max_water_depth_m is None and w.seafloor_below_feature_m is None else "surface + seafloor"

    @property
    def label(self) -> str:
        """Readable description for figures and tables."""
        pf = self.platform
        tilt = pf.transducers["port"].tilt_deg if self.tilt_deg is None else self.tilt_deg
        depth = self.water.depth_for(pf)
        where = "at the surface" if pf.fixed_depth else f"{depth:g} m deep"
        floor = self.water.seafloor_below_feature_m
        floor = "" if floor is None else f", floor {floor:g} m below feature"
        return f"{pf.key}, {where}, tilt {tilt:g}°{floor}, {self.study}"


def default_conditions(platforms: Sequence[Platform], *, surface_tilts_deg=(), submerged_depths_m=(),
                       envelopes=None, offset_model: OffsetModel | None = None,
                       seafloor_margins_m=()) -> list[Condition]:
    """The chapter's conditions: each surface vessel (fixed depth) at its own tilt and at each of
    ``surface_tilts_deg``; each submerged platform at each of ``submerged_depths_m`` inside its
    depth range (pose space). With ``envelopes`` (platform key -> envelope) also each platform's
    survey passes at its own tilt (submerged platforms at the shallowest depth given). Then, for
    each of ``seafloor_margins_m`` (m, >= 0), the first water column of each platform with a
    seafloor that far below each feature (``WaterColumn.seafloor_below_feature_m``), in the pose
    space and, with ``envelopes``, in the survey passes.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms.
    surface_tilts_deg : sequence of float
        Extra tilts of surface vessels, degrees.
    submerged_depths_m : sequence of float
        Depths of submerged platforms, metres.
    envelopes : dict of str to SurveyEnvelope, optional
        Survey envelopes by platform key.
    offset_model : OffsetModel, optional
        Offset model of the survey passes.
    seafloor_margins_m : sequence of float
        Seafloor distances below each feature, metres.

    Returns
    -------
    list of Condition
        The conditions, in the order above.
    """
    out = []
    for pf in platforms:
        if pf.fixed_depth:
            waters, tilts = [WaterColumn()], [None, *[float(t) for t in surface_tilts_deg]]
        else:
            depths = [float(d) for d in submerged_depths_m if pf.depth_min_m <= d <= pf.depth_max_m]
            if not depths:
                raise ValueError(f"none of submerged_depths_m {list(submerged_depths_m)} lies in platform "
                                 f"{pf.key!r}'s depth range [{pf.depth_min_m:g}, {pf.depth_max_m:g}] m")
            waters, tilts = [WaterColumn(d) for d in depths], [None]
        out += [Condition(pf, "pose space", w, t) for w in waters for t in tilts]
        if envelopes is not None:
            out.append(Condition(pf, "survey passes", waters[0], None, envelopes[pf.key], offset_model))
    for pf in platforms:
        first = next(c.water for c in out if c.platform is pf)
        for margin in seafloor_margins_m:
            w = replace(first, seafloor_below_feature_m=float(margin))
            out.append(Condition(pf, "pose space", w))
            if envelopes is not None:
                out.append(Condition(pf, "survey passes", w, None, envelopes[pf.key], offset_model))
    return out


def _tables(cond: Condition, water, *, n_samples, n_per_angle, crossing_angles_deg, seed, sample,
            simulate) -> pd.DataFrame:
    if cond.study == "pose space":
        # vehicle 1 at the condition's depth in both runs of a pair (same samples), vehicle 2 in the water
        spec = PoseSpaceSpec(cond.platform, tilt_deg=cond.tilt_deg, water=water,
                             vehicle1_depth_m=cond.water.vehicle_depth_m)
        return sample(spec, n_samples, seed)
    return simulate(cond.platform, cond.envelope, cond.offset_model, crossing_angles_deg,
                    n_per_angle, seed, water=water)[0]


def crop_effects(conditions: Sequence[Condition], *, n_samples: int, n_per_angle: int,
                 crossing_angles_deg, seed: int, n_batches: int = N_BATCHES,
                 sample: Callable = sample_pose_space, simulate: Callable = simulate_passes
                 ) -> pd.DataFrame:
    """The crop's effect for every condition, as one long table.

    Parameters
    ----------
    conditions : sequence of Condition
    n_samples : int
        Pose-space samples per run.
    n_per_angle : int
        Survey pass pairs per crossing angle.
    crossing_angles_deg : array_like
        Crossing angles of the survey passes (deg, in [-180, 180]).
    seed : int
        Seed of the samplers.
    n_batches : int
        Replicate batches for the intervals (:func:`crop_effect`).
    sample, simulate : callable
        :func:`~sss_locus.experiments.pose_space.study.sample_pose_space` and
        :func:`~sss_locus.experiments.survey_passes.study.simulate_passes`, or cached versions of
        them (same signatures).

    Returns
    -------
    pandas.DataFrame
        Columns ``condition`` (slug), ``label``, ``platform``, ``study``, ``crop``
        (:attr:`Condition.crop`), ``subset`` (``"all"``
        or ``"port-port"``: sensor 2 on the port side too, pose space only), then the columns of
        :func:`crop_effect`.
    """
    rows = []
    kw = dict(n_samples=n_samples, n_per_angle=n_per_angle, crossing_angles_deg=crossing_angles_deg,
              seed=seed, sample=sample, simulate=simulate)
    for cond in conditions:
        paper = _tables(cond, None, **kw)
        water = _tables(cond, cond.water, **kw)
        subsets = {"all": np.ones(len(paper), bool)}
        if cond.study == "pose space":
            subsets["port-port"] = ((paper["side1"] == "port") & (paper["side2"] == "port")).to_numpy()
        for name, keep in subsets.items():
            eff = crop_effect(paper[keep], water[keep], n_batches=n_batches)
            rows.append(eff.assign(condition=cond.slug, label=cond.label, platform=cond.platform.key,
                                   study=cond.study, crop=cond.crop, subset=name))
    out = pd.concat(rows, ignore_index=True)
    first = ["condition", "label", "platform", "study", "crop", "subset"]
    return out[first + [c for c in out.columns if c not in first]]


def pass2_above_surface_share(samples: pd.DataFrame, platform: Platform, water: WaterColumn) -> float:
    """Share of survey pass pairs whose pass 2 would run above the sea surface.

    The survey sampler draws each pass's altitude above the feature independently (for a
    platform without ``same_altitude``) and does not know the water depth, so with vehicle 1
    ``water.depth_for(platform)`` below the surface, pass 2's reference point is at depth
    ``depth1 + altitude1_m - altitude2_m``, negative when pass 2 flies more than ``depth1`` higher.

    Parameters
    ----------
    samples : pandas.DataFrame
        :func:`~sss_locus.experiments.survey_passes.study.simulate_passes` samples (columns
        ``altitude1_m``, ``altitude2_m``), non-empty.
    platform : Platform
    water : WaterColumn

    Returns
    -------
    float
        The share, in [0, 1].
    """
    if len(samples) == 0:
        raise ValueError("samples must be a non-empty survey-pass table")
    depth2 = water.depth_for(platform) + samples["altitude1_m"].to_numpy(float) - samples["altitude2_m"].to_numpy(float)
    return float(np.mean(depth2 < 0.0))


def crop_effect(uncropped: pd.DataFrame, cropped: pd.DataFrame, *, n_batches: int = N_BATCHES,
                confidence_level: float = 0.95) -> pd.DataFrame:
    """How the water crop changes the loci of the same samples, with replicate intervals.

    Parameters
    ----------
    uncropped, cropped : pandas.DataFrame
        The same configurations row by row (same sampler, spec and seed), without and with a
        :class:`~sss_locus.experiments.datamodel.water_column.WaterColumn`; columns ``locus_length_m`` (m) and ``n_arcs``.
    n_batches : int
        Replicate batches of the rows (a pair stays together; >= 3): each statistic is computed
        on each batch, and :func:`~sss_locus.experiments.stats.replicates.replicate_interval` turns
        their spread into an interval around the whole table's value, clipped to [0, 1] (every
        statistic below is a share; for a rare one, a handful of events, the interval is rough).
    confidence_level : float
        In (0, 1).

    Returns
    -------
    pandas.DataFrame
        One row per statistic, columns ``statistic, estimate, ci_low, ci_high, n``:

        - ``length_ratio``: total cropped length over total uncropped length (ratio of means);
        - ``shortened_share``: share of samples whose locus the crop shortens;
        - ``emptied_share``: share of non-empty loci the crop removes entirely;
        - ``multi_arc_share_uncropped`` / ``multi_arc_share_cropped``: share of samples whose
          locus has more than one arc (``n_arcs > 1``), without and with the crop;
        - ``extra_arcs_share``: share of fragmented loci (uncropped) whose every extra arc
          the crop removes (``n_arcs`` drops to <= 1), over all samples.
    """
    if len(uncropped) != len(cropped) or len(cropped) == 0:
        raise ValueError(f"uncropped and cropped must be the same non-empty samples; got "
                         f"{len(uncropped)} and {len(cropped)} rows")
    check_batches(n_batches)
    check_confidence(confidence_level)
    a = uncropped["locus_length_m"].to_numpy(float)
    b = cropped["locus_length_m"].to_numpy(float)
    if np.any(b > a * (1.0 + 1e-9) + 1e-12):
        raise ValueError("cropped lengths exceed uncropped ones: the two tables are not the same samples")
    na, nb = uncropped["n_arcs"].to_numpy(), cropped["n_arcs"].to_numpy()
    cols = {
        "length_a": a, "length_b": b,
        "shortened_share": (b < a * (1.0 - 1e-9)).astype(float),
        "emptied": ((a > 0) & (b == 0)).astype(float), "nonempty": (a > 0).astype(float),
        "multi_arc_share_uncropped": (na > 1).astype(float),
        "multi_arc_share_cropped": (nb > 1).astype(float),
        "extra_arcs_share": ((na > 1) & (nb <= 1)).astype(float),
    }
    names = list(cols)
    M = np.stack([cols[k] for k in names], axis=1)
    batches = batch_statistic(M, lambda rows: rows.mean(axis=0), n_batches)
    full = M.mean(axis=0)

    def stats(v):  # (..., columns) of means -> the reported statistics
        col = {k: v[..., i] for i, k in enumerate(names)}
        with np.errstate(invalid="ignore", divide="ignore"):
            return {
                "length_ratio": col["length_b"] / col["length_a"],
                "shortened_share": col["shortened_share"],
                "emptied_share": col["emptied"] / col["nonempty"],
                "multi_arc_share_uncropped": col["multi_arc_share_uncropped"],
                "multi_arc_share_cropped": col["multi_arc_share_cropped"],
                "extra_arcs_share": col["extra_arcs_share"],
            }

    est, bs = stats(full), stats(batches)
    ci = {k: replicate_interval(est[k], bs[k], confidence_level, bounds=(0.0, 1.0)) for k in est}  # all in [0, 1]
    return pd.DataFrame([{"statistic": k, "estimate": float(est[k]), "ci_low": float(ci[k][0]),
                          "ci_high": float(ci[k][1]), "n": len(M)} for k in est])
