"""Verdicts of the water chapter, generated from a run's own numbers, for any platform.

One function per paragraph (CONTRIBUTING.md, "One source per sentence"): each reads the long
table of :func:`~sss_locus.experiments.water.study.crop_effects` and the conditions it was
computed for (:class:`~sss_locus.experiments.water.study.Condition`) and returns one platform's
paragraph, the paper's AUV and boat included. The numbers are the texts
:func:`~sss_locus.report.water.figures.effect_texts` glues (shares in per cent with their 95 %
replicate-batch intervals), so the paragraph and the table cannot disagree; every qualitative word
(the fan's top above or below the horizontal, "cannot remove anything", which depth the crop
matters at) is computed from the platform's data and the numbers.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import pandas as pd

from sss_locus.experiments.datamodel.platforms import Platform, provenance_table
from sss_locus.report.common.text import fmt_sig
from sss_locus.report.water.figures import effect_texts


STUDY_WORDS = {"pose space": "pose-space", "survey passes": "survey-pass"}
"""A study's name as an adjective."""


def fan_top_above_horizontal_deg(platform: Platform, tilt_deg: float | None = None) -> float:
    """How far the top edge of sensor 1's fan lies above the horizontal for a level vehicle
    (degrees; negative: below it): half the fan (``azimuth_deg``) minus the downward tilt.

    Parameters
    ----------
    platform : Platform
        The platform.
    tilt_deg : float, optional
        A tilt instead of the data's (port transducer), degrees down.

    Returns
    -------
    float
        Degrees above the horizontal.
    """
    tilt = platform.transducers["port"].tilt_deg if tilt_deg is None else tilt_deg
    return platform.sonar.azimuth_deg / 2 - tilt


class _Effects:
    """One platform's conditions and the glued texts of their effects."""

    def __init__(self, effects: pd.DataFrame, conditions: Sequence, key: str):
        self.conds = [c for c in conditions if c.platform.key == key]
        if not self.conds:
            raise ValueError(f"no condition of platform {key!r}")
        self.pf = self.conds[0].platform
        self.rows = effects[effects["platform"] == key]
        self.texts = effect_texts(self.rows)

    def pick(self, study: str, *, tilt=None, floor=None, depth=None) -> list:
        """The conditions of ``study`` with that tilt override and seafloor margin (``depth``: any)."""
        return [c for c in self.conds if c.study == study and c.tilt_deg == tilt
                and c.water.seafloor_below_feature_m == floor
                and (depth is None or c.water.vehicle_depth_m == depth)]

    def text(self, cond, stat: str, subset: str = "all", pct: bool = False) -> str:
        return self.texts[f"{cond.slug}-{subset}-{stat}" + ("-pct" if pct else "")]

    def value(self, cond, stat: str, subset: str = "all") -> pd.Series:
        r = self.rows[(self.rows["condition"] == cond.slug) & (self.rows["subset"] == subset)
                      & (self.rows["statistic"] == stat)]
        return r.iloc[0]


def _depth(c) -> str:
    return f"{c.water.depth_for(c.platform):g} m"


def surface_finding(effects: pd.DataFrame, conditions: Sequence, key: str,
                    pass2_above: Mapping[str, float] | None = None) -> str:
    """What the crop to the sea surface does for one platform: for a surface vessel at its own
    tilt and each extra tilt, for a submerged platform at each depth, in the pose space and the
    survey passes.

    Parameters
    ----------
    effects : pandas.DataFrame
        The long table of :func:`~sss_locus.experiments.water.study.crop_effects`.
    conditions : sequence of Condition
        The conditions it was computed for.
    key : str
        The platform.
    pass2_above : mapping of str to float, optional
        Condition slug -> share of survey pass pairs whose pass 2 flies above the surface.

    Returns
    -------
    str
        One paragraph: the fan's top against the horizontal and whether the crop can remove
        anything (a level surface vessel whose fan stops at the horizontal: nothing, exactly),
        the shares shortened and fragmented and the length kept, with 95 % intervals.
    """
    e = _Effects(effects, conditions, key)
    pf, parts = e.pf, []
    pose, survey = e.pick("pose space"), e.pick("survey passes")
    if pf.fixed_depth:
        top, level = fan_top_above_horizontal_deg(pf), pf.roll_max_deg == 0 and pf.pitch_max_deg == 0
        depth = pf.depth_min_m + pf.transducers["port"].depth_m
        where = "at the horizontal" if top == 0 else (f"{fmt_sig(abs(top), 2)}° " + ("above" if top > 0 else "below")
                                                       + " the horizontal")
        text = (f"at the documented tilt of {pf.transducers['port'].tilt_deg:g}° the top of the "
                f"{pf.sonar.azimuth_deg:g}° fan is {where}, and the vessel is "
                + ("level (roll and pitch 0)" if level else "not level")
                + f", its transducers {fmt_sig(depth, 2)} m under the waterline")
        if level and top <= 0 < depth:
            text += (": every point inside sensor 1's fan lies at or below the horizontal through the transducer and "
                     "every locus point is inside that fan, so the crop cannot remove anything, exactly")
        said = [f"{e.text(c, 'shortened_share')} of its {STUDY_WORDS[c.study]} loci" for c in pose[:1] + survey[:1]]
        parts.append(text + "; measured, it shortens " + " and ".join(said) + ".")
        for c in [c for c in e.conds if c.tilt_deg is not None]:
            up = fan_top_above_horizontal_deg(pf, c.tilt_deg)
            removed = 1 - e.value(c, "length_ratio").estimate
            u, k = e.value(c, "multi_arc_share_uncropped"), e.value(c, "multi_arc_share_cropped")
            parts.append(
                f"Tilted down by {c.tilt_deg:g}°, the fan reaches {fmt_sig(up, 2)}° "
                + ("above the horizontal, so the locus can leave the water" if up > 0 else "short of the horizontal")
                + f". Without the crop {e.text(c, 'multi_arc_share_uncropped')} of the loci are fragmented; cropped to "
                f"the water, {e.text(c, 'multi_arc_share_cropped')}. The crop keeps {e.text(c, 'length_ratio')} of the "
                f"total locus length: {100 * removed:.0f} % of it lies above the waterline"
                + (", and so do most second arcs." if k.ci_high < u.ci_low and k.estimate < u.estimate / 2 else "."))
    else:
        first, *rest = pose
        text = (f"with vehicle 1 at {_depth(first)} the crop keeps {e.text(first, 'length_ratio')} of the pose-space "
                f"locus length and changes fragmentation from {e.text(first, 'multi_arc_share_uncropped')} to "
                f"{e.text(first, 'multi_arc_share_cropped')}")
        text += "".join(f"; at {_depth(c)} it keeps {e.text(c, 'length_ratio')}" for c in rest) + "."
        for c in survey:
            text += (f" In the survey passes (vehicle 1 at {_depth(c)}) it keeps {e.text(c, 'length_ratio')} of the "
                     f"length and fragmentation goes from {e.text(c, 'multi_arc_share_uncropped')} to "
                     f"{e.text(c, 'multi_arc_share_cropped')}")
            if pass2_above and c.slug in pass2_above:
                text += (f"; in {100 * pass2_above[c.slug]:.0f} % of the pass pairs pass 2 flies more than "
                         f"{_depth(c)} higher than pass 1, above the surface (kept, as in the survey-pass chapter)")
            text += "."
        notes = provenance_table(pf).set_index("key")["kind"] if pf.provenance else pd.Series(dtype=str)
        kinds = {notes.get(f"platforms.{key}.depth_m.{f}") for f in ("min", "max")}
        text += (f" Its depth envelope ({pf.depth_min_m:g}–{pf.depth_max_m:g} m) is "
                 + ("an assumption" if "assumption" in kinds else "sourced") + " (`data/platforms.toml`).")
        parts.append(text)
    return " ".join(parts)


def subset_finding(effects: pd.DataFrame, conditions: Sequence, key: str) -> str:
    """The fragmentation share of the paper's locus on all pose-space samples against the
    port–port samples the pose-space chapter's heatmaps use, per pose-space condition.

    Parameters
    ----------
    effects, conditions, key
        As for :func:`surface_finding`.

    Returns
    -------
    str
        One clause per pose-space condition of the surface crop: both shares and both counts.
    """
    e = _Effects(effects, conditions, key)
    parts = [f"{c.label.split(', pose space')[0]}: {e.text(c, 'multi_arc_share_uncropped', pct=True)} of all "
             f"{e.text(c, 'n')} samples and {e.text(c, 'multi_arc_share_uncropped', 'port-port', pct=True)} of the "
             f"{e.text(c, 'n', 'port-port')} port–port samples"
             for c in e.conds if c.study == "pose space" and c.crop == "surface"]
    return "; ".join(parts) + "."


def seafloor_finding(effects: pd.DataFrame, conditions: Sequence, key: str, deepest_m: float) -> str:
    """The crop to the water column between the surface and a seafloor a margin below each feature.

    Parameters
    ----------
    effects, conditions, key
        As for :func:`surface_finding`.
    deepest_m : float
        The deepest a feature of sensor 1's fan lies below the surface (m,
        :func:`~sss_locus.experiments.datamodel.water_column.deepest_feature_m`).

    Returns
    -------
    str
        How deep a feature can lie; per margin the length kept in each study against the surface
        alone, the fragmentation at the smallest margin, and whether the smaller column keeps no
        more than the larger (containment).
    """
    e = _Effects(effects, conditions, key)
    margins = sorted({c.water.seafloor_below_feature_m for c in e.conds} - {None})
    text = (f"in the pose space a feature can lie up to {deepest_m:.0f} m below the surface"
            + ("" if e.pf.fixed_depth else " with vehicle 1 at its shallowest depth") + " (sensor 1's fan at full range)")
    if not margins:
        return text + "; no seafloor margin was run (`seafloor_margins_m` is empty)."
    surface = {c.study: c for c in e.pick("pose space")[:1] + e.pick("survey passes")}
    by = {m: {c.study: c for c in e.conds if c.water.seafloor_below_feature_m == m} for m in margins}
    for m in margins:
        kept = [f"{e.text(c, 'length_ratio')} of the {STUDY_WORDS[s]} length (surface alone: "
                f"{e.text(surface[s], 'length_ratio', pct=True)})" for s, c in by[m].items()]
        text += f". With the floor {m:g} m below the feature the crop keeps " + " and ".join(kept)
    m0 = margins[0]
    text += f". Fragmentation with the floor {m0:g} m below: " + "; ".join(
        f"{STUDY_WORDS[s]} loci {e.text(c, 'multi_arc_share_cropped', pct=True)} against {e.text(c, 'multi_arc_share_uncropped', pct=True)} "
        "for the paper's locus" for s, c in by[m0].items()) + "."
    if len(margins) > 1:
        worse = [(a, b, s) for a, b in zip(margins, margins[1:]) for s in by[a]
                 if s in by[b] and e.value(by[a][s], "length_ratio").estimate > e.value(by[b][s], "length_ratio").estimate]
        text += (" The water column with the floor nearer is contained in the one with it farther, and on the same "
                 "samples it keeps " + ("no more of the length, as it must." if not worse else
                                        "more of the length here, which containment forbids: a defect to report."))
    return text


def water_summary(effects: pd.DataFrame, conditions: Sequence, key: str) -> str:
    """The chapter's summary for one platform.

    Parameters
    ----------
    effects, conditions, key
        As for :func:`surface_finding`.

    Returns
    -------
    str
        For a surface vessel: whether the crop changes anything at its tilt (and why), the paper's
        fragmentation there and at each extra tilt with the share of it the crop removes; for a
        submerged platform: the length kept at each depth and where the crop removes most; then the
        length kept with each seafloor margin (pose space).
    """
    e = _Effects(effects, conditions, key)
    pf, pose = e.pf, e.pick("pose space")
    if pf.fixed_depth:
        c = pose[0]
        nothing = e.value(c, "shortened_share").estimate == 0
        by_geometry = (fan_top_above_horizontal_deg(pf) <= 0 and pf.roll_max_deg == 0 and pf.pitch_max_deg == 0)
        text = (("the crop changes nothing at its documented tilt" + (", by geometry" if by_geometry else ""))
                if nothing else f"the crop shortens {e.text(c, 'shortened_share', pct=True)} of the loci at its documented tilt")
        text += (f", and the paper's loci fragment in {e.text(c, 'multi_arc_share_uncropped', pct=True)} of "
                 f"{e.text(c, 'n')} pose-space samples")
        for t in [c for c in e.conds if c.tilt_deg is not None and c.crop == "surface"]:
            u, k = e.value(t, "multi_arc_share_uncropped").estimate, e.value(t, "multi_arc_share_cropped").estimate
            text += (f"; tilted {t.tilt_deg:g}° they fragment in {e.text(t, 'multi_arc_share_uncropped', pct=True)}"
                     + (f", and the crop removes {100 * (1 - k / u):.0f} % of that (the part above the waterline)" if u > 0 else ""))
    else:
        kept = {c.water.vehicle_depth_m: e.value(c, "length_ratio").estimate for c in pose}
        most = min(kept, key=kept.get)
        text = ("the crop keeps " + ", ".join(f"{e.text(c, 'length_ratio', pct=True)} at {_depth(c)}" for c in pose)
                + " of the pose-space locus length"
                + ("; it removes nothing at any of these depths" if kept[most] == 1 else
                   f"; it removes most at {most:g} m" + (", the shallowest depth" if most == min(kept) else "")))
    floors = [c for c in e.conds if c.study == "pose space" and c.water.seafloor_below_feature_m is not None]
    text += "".join(f"; with the floor {c.water.seafloor_below_feature_m:g} m below each feature the crop to the "
                    f"water column keeps {e.text(c, 'length_ratio', pct=True)} of the pose-space length" for c in floors)
    return text + "."
