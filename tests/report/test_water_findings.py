"""The water chapter's findings (sss_locus.report.water.findings) say what their numbers say: effects
are built here by hand for the real platforms' conditions, each deciding word is flipped by the
numbers or the data, and one real crop run checks the geometric claim for the level boat."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.water.study import crop_effects, default_conditions
from sss_locus.report.water import findings as wf

STATS = ("length_ratio", "shortened_share", "emptied_share", "multi_arc_share_uncropped",
         "multi_arc_share_cropped", "extra_arcs_share")


def _conditions(platforms, **kw):
    pfs = [load_platform(k) for k in platforms]
    return default_conditions(pfs, envelopes={k: load_envelope(k) for k in platforms},
                              offset_model=OffsetModel("independent"), **kw)


def _effects(conditions, values):
    """``values(cond) -> {statistic: estimate}``; intervals ±0.01 (clipped to [0, 1])."""
    rows = []
    for c in conditions:
        for subset in ("all", "port-port") if c.study == "pose space" else ("all",):
            for stat in STATS:
                v = values(c).get(stat, 0.0)
                rows.append(dict(condition=c.slug, label=c.label, platform=c.platform.key, study=c.study, crop=c.crop,
                                 subset=subset, statistic=stat, estimate=v, ci_low=max(v - 0.01, 0.0),
                                 ci_high=min(v + 0.01, 1.0), n=1000 if subset == "all" else 500))
    return pd.DataFrame(rows)


def test_fan_top_is_half_the_fan_minus_the_tilt():
    boat = load_platform("boat")  # 50° fan tilted 25°: its top at the horizontal (data/platforms.toml)
    assert wf.fan_top_above_horizontal_deg(boat) == 0.0 and wf.fan_top_above_horizontal_deg(boat, 15.0) == 10.0


def test_the_level_boat_cannot_lose_anything_but_a_tilted_or_rolling_one_can():
    conds = _conditions(["boat"], surface_tilts_deg=[15.0])
    eff = _effects(conds, lambda c: {"length_ratio": 0.671, "multi_arc_share_uncropped": 0.167,
                                     "multi_arc_share_cropped": 0.002} if c.tilt_deg else {"length_ratio": 1.0})
    text = wf.surface_finding(eff, conds, "boat")
    assert "the top of the 50° fan is at the horizontal" in text and "cannot remove anything, exactly" in text
    assert "0.10 m under the waterline" in text
    assert "Tilted down by 15°, the fan reaches 10° above the horizontal" in text
    assert "33 % of it lies above the waterline, and so do most second arcs" in text  # 1 - 0.671
    summary = wf.water_summary(eff, conds, "boat")
    assert "changes nothing at its documented tilt, by geometry" in summary and "removes 99 % of that" in summary
    rolling = dataclasses.replace(conds[0].platform, roll_max_deg=5.0)
    conds2 = [dataclasses.replace(c, platform=rolling) for c in conds]
    text = wf.surface_finding(eff, conds2, "boat")
    assert "not level" in text and "cannot remove anything" not in text
    assert ", by geometry" not in wf.water_summary(eff, conds2, "boat")


def test_the_auv_finding_follows_its_depths_and_names_an_assumed_envelope():
    conds = _conditions(["auv"], submerged_depths_m=[2.0, 10.0, 50.0], seafloor_margins_m=[1.0, 10.0])
    keep = {2.0: 0.9, 10.0: 0.99, 50.0: 1.0}
    eff = _effects(conds, lambda c: {"length_ratio": (keep[c.water.vehicle_depth_m] if c.water.seafloor_below_feature_m
                                                      is None else 0.8 + 0.01 * c.water.seafloor_below_feature_m)})
    text = wf.surface_finding(eff, conds, "auv", {c.slug: 0.41 for c in conds if c.study == "survey passes"})
    assert "with vehicle 1 at 2 m the crop keeps 90.0 %" in text and "at 50 m it keeps 100.0 %" in text
    assert "in 41 % of the pass pairs pass 2 flies more than 2 m higher" in text
    assert "(2–100 m) is an assumption" in text  # both ends marked as assumptions in data/platforms.toml
    summary = wf.water_summary(eff, conds, "auv")
    assert "it removes most at 2 m, the shallowest depth" in summary
    assert "with the floor 1 m below each feature the crop to the water column keeps 81.0 %" in summary
    deep = _effects(conds, lambda c: {"length_ratio": 0.95 if c.water.vehicle_depth_m == 10.0 else 1.0})
    assert "removes most at 10 m" in wf.water_summary(deep, conds, "auv")
    assert "removes nothing at any" in wf.water_summary(_effects(conds, lambda c: {"length_ratio": 1.0}), conds, "auv")


def test_seafloor_containment_is_checked_on_the_numbers():
    conds = _conditions(["boat"], seafloor_margins_m=[1.0, 10.0])
    ok = _effects(conds, lambda c: {"length_ratio": {None: 1.0, 1.0: 0.765, 10.0: 0.989}[c.water.seafloor_below_feature_m]})
    text = wf.seafloor_finding(ok, conds, "boat", 115.0)
    assert text.startswith("in the pose space a feature can lie up to 115 m below the surface (sensor")
    assert "floor 1 m below the feature the crop keeps 76.5 %" in text and "(surface alone: 100.0 %)" in text
    assert "keeps no more of the length, as it must" in text
    bad = _effects(conds, lambda c: {"length_ratio": {None: 1.0, 1.0: 0.99, 10.0: 0.9}[c.water.seafloor_below_feature_m]})
    assert "a defect to report" in wf.seafloor_finding(bad, conds, "boat", 115.0)
    assert "no seafloor margin was run" in wf.seafloor_finding(ok, _conditions(["boat"]), "boat", 115.0)


def test_subsets_name_both_counts():
    conds = _conditions(["boat"], surface_tilts_deg=[15.0])
    eff = _effects(conds, lambda c: {"multi_arc_share_uncropped": 0.167 if c.tilt_deg else 0.0})
    text = wf.subset_finding(eff, conds, "boat")
    assert "tilt 15°: 16.7 % of all 1,000 samples and 16.7 % of the 500 port–port samples" in text


def test_real_crop_of_the_level_boat_removes_nothing_and_of_the_tilted_boat_removes_length():
    """The geometric claim ("cannot remove anything, exactly") against a real crop run."""
    conds = [c for c in _conditions(["boat"], surface_tilts_deg=[15.0]) if c.study == "pose space"]
    eff = crop_effects(conds, n_samples=2000, n_per_angle=1, crossing_angles_deg=[0.0], seed=3, n_batches=5)
    text = wf.surface_finding(eff, conds, "boat")
    level = eff[(eff.condition == conds[0].slug) & (eff.subset == "all")].set_index("statistic")
    assert "cannot remove anything, exactly" in text and level.at["shortened_share", "estimate"] == 0.0
    tilted = eff[(eff.condition == conds[1].slug) & (eff.subset == "all")].set_index("statistic")
    assert tilted.at["length_ratio", "estimate"] < 1.0
    removed = f"{100 * (1 - tilted.at['length_ratio', 'estimate']):.0f} % of it lies above the waterline"
    assert removed in text


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_every_finding_is_written_for_each_shipped_platform(key):
    conds = _conditions([key], surface_tilts_deg=[15.0], submerged_depths_m=[2.0], seafloor_margins_m=[1.0])
    eff = _effects(conds, lambda c: {"length_ratio": 0.9, "multi_arc_share_uncropped": 0.1})
    for text in (wf.surface_finding(eff, conds, key), wf.subset_finding(eff, conds, key),
                 wf.seafloor_finding(eff, conds, key, 100.0), wf.water_summary(eff, conds, key)):
        assert text.endswith(".") and "nan" not in text
    with pytest.raises(ValueError, match="no condition of platform"):
        wf.surface_finding(eff, conds, "other")
    assert np.isfinite(wf.fan_top_above_horizontal_deg(conds[0].platform))
