"""The reconstruction chapter's study: estimators against terrain relief, terrain shape, noise
level and the open choices, for one platform; and the paired test that decides the verdict.

One *case* is a terrain, a noise level and the open choices: features are placed on the
terrain (:func:`~sss_locus.experiments.datamodel.terrain.place_features`), the survey of
:mod:`~sss_locus.experiments.reconstruction.terrain_survey` observes them, and every estimator of
:mod:`~sss_locus.experiments.reconstruction.estimators` runs on the same noisy views. The relief sweep
scales one seeded random field (the same shape at every RMS relief; RMS 0 is the flat
seafloor), so the features keep their horizontal positions across the sweep.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.reconstruction.estimators import reconstruct_many
from sss_locus.experiments.datamodel.terrain import Terrain, place_features, random_terrain, terrain_from_config
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features


def _extent(layout: SurveyLayout, platform) -> float:
    return layout.area_m + 2.0 * (platform.sonar.max_range_m + layout.margin_m) + 10.0


def survey_altitude_m(envelope) -> float:
    """The altitude the chapter's survey flies: the middle of the envelope's altitude range (above
    the mean seafloor for a platform holding one height, ``same_altitude``; above the local
    seafloor otherwise).

    Parameters
    ----------
    envelope : Envelope
        The platform's operating envelope (``altitude_min_m``, ``altitude_max_m``, m).

    Returns
    -------
    float
        Altitude, m.
    """
    return 0.5 * (envelope.altitude_min_m + envelope.altitude_max_m)


def run_case(platform, envelope, noise, terrain, layout: SurveyLayout, *, n_features: int,
             noise_scale: float, seed: int, shadowing: str = "off", below_sensors: bool = True,
             margin_sigmas: float = 5.0, n_views=(3, 4, 6)) -> pd.DataFrame:
    """One case: the per-feature table of :func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`
    with ``noise_scale`` (the noise model scaled; 0 is noise-free), and per feature the number
    of views lost to shadowing (``n_shadowed``). The vehicle flies at the middle of the
    envelope's altitude range (above the mean seafloor for a fixed-height platform, above the
    local seafloor otherwise).

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope (altitude range, ``same_altitude``).
    noise : NoiseModel
        The noise model (scaled by ``noise_scale``).
    terrain : Terrain
        The seafloor (local metres).
    layout : SurveyLayout
        The survey's lines and area.
    n_features : int
        Features placed on the seafloor.
    noise_scale : float
        Factor on the noise model (0: noise-free).
    seed : int
        Seed of features, observations and noise.
    shadowing : str
        Shadowing model (``"off"`` or as :func:`observe_features`).
    below_sensors : bool
        Keep N-view estimates below the sensors.
    margin_sigmas : float
        Aperture margin of the N-view estimate, in noise sigmas.
    n_views : sequence of int
        View counts of the N-view estimators.

    Returns
    -------
    pandas.DataFrame
        One row per feature and estimator (errors in m, world ENU), with ``n_shadowed``.
    """
    return run_cases(platform, envelope, noise, [(terrain, noise_scale)], layout, n_features=n_features, seed=seed,
                     shadowing=shadowing, below_sensors=below_sensors, margin_sigmas=margin_sigmas,
                     n_views=n_views)[0]


def run_cases(platform, envelope, noise, cases, layout: SurveyLayout, *, n_features: int, seed: int,
              shadowing: str = "off", below_sensors: bool = True, margin_sigmas: float = 5.0,
              n_views=(3, 4, 6)) -> list[pd.DataFrame]:
    """:func:`run_case` of each ``(terrain, noise_scale)`` of ``cases``, the same tables, the
    cases' N-view estimates solved together
    (:func:`~sss_locus.experiments.reconstruction.estimators.reconstruct_many`).

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope.
    noise : NoiseModel
        The noise model.
    cases : sequence of tuple
        ``(terrain, noise_scale)`` pairs.
    layout : SurveyLayout
        The survey's lines and area.
    n_features : int
        Features per case.
    seed : int
        Seed (the same for every case: common random numbers).
    shadowing : str
        Shadowing model.
    below_sensors : bool
        Keep N-view estimates below the sensors.
    margin_sigmas : float
        Aperture margin, in noise sigmas.
    n_views : sequence of int
        View counts of the N-view estimators.

    Returns
    -------
    list of pandas.DataFrame
        One table per case, in order (as :func:`run_case`).
    """
    altitude = survey_altitude_m(envelope)
    observed, jobs = [], []
    for terrain, noise_scale in cases:
        f = place_features(terrain, n_features, layout.area_m, seed)
        views, seen, info = observe_features(platform, terrain, f, layout, altitude, envelope.same_altitude,
                                             seed + 1, shadowing)
        observed.append(info["shadowed"].sum(axis=1))
        jobs.append(dict(views=views, seen=seen, sensor_height_m=info["sensor_height_m"],
                         noise=noise.scaled(noise_scale), seed=seed + 2, below_sensors=below_sensors))
    tables = reconstruct_many(jobs, platform.sonar.aperture(), n_views=n_views, margin_sigmas=margin_sigmas)
    return [tab.assign(n_shadowed=lost[tab.feature.to_numpy()]) for tab, lost in zip(tables, observed)]


def relief_sweep(platform, envelope, noise, config: dict, rms_values, noise_scales, *,
                 n_features: int, seed: int, **choices) -> pd.DataFrame:
    """:func:`run_case` on the random terrain of ``config`` scaled to each RMS relief in
    ``rms_values`` (m), for each noise scale; columns ``rms_relief_m``, ``noise_scale`` added.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope.
    noise : NoiseModel
        The noise model.
    config : dict
        The terrain configuration (``survey`` and ``random`` tables).
    rms_values : sequence of float
        RMS reliefs, m.
    noise_scales : sequence of float
        Factors on the noise model.
    n_features : int
        Features per case.
    seed : int
        Seed of the random field and the cases.
    **choices
        Keywords of :func:`run_cases`.

    Returns
    -------
    pandas.DataFrame
        The cases' tables stacked, with ``rms_relief_m`` and ``noise_scale``.
    """
    layout = SurveyLayout(**config["survey"])
    rc = config["random"]
    base = random_terrain(1.0, rc["correlation_length_m"], _extent(layout, platform),
                          rc["grid_spacing_m"], seed)
    x0, y0, dx, h = base.grid
    keys = [(float(rms), float(k)) for rms in rms_values for k in noise_scales]
    cases = [(Terrain("random", {**base.params, "rms_relief_m": rms}, grid=(x0, y0, dx, h * rms)), k)
             for rms, k in keys]
    tables = run_cases(platform, envelope, noise, cases, layout, n_features=n_features, seed=seed + 10, **choices)
    return pd.concat([t.assign(rms_relief_m=rms, noise_scale=k) for t, (rms, k) in zip(tables, keys)],
                     ignore_index=True)


def shape_cases(platform, envelope, noise, config: dict, noise_scales, *, n_features: int, seed: int,
                **choices) -> pd.DataFrame:
    """:func:`run_case` on the analytic terrains of ``config`` (flat, slope, mound, step) and on
    its random terrain, for each noise scale; column ``terrain`` added.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope.
    noise : NoiseModel
        The noise model.
    config : dict
        The terrain configuration.
    noise_scales : sequence of float
        Factors on the noise model.
    n_features : int
        Features per case.
    seed : int
        Seed of the terrains and the cases.
    **choices
        Keywords of :func:`run_cases`.

    Returns
    -------
    pandas.DataFrame
        The cases' tables stacked, with ``terrain`` and ``noise_scale``.
    """
    layout = SurveyLayout(**config["survey"])
    kinds = ("flat", "slope", "mound", "step", "random")
    terrains = {kind: terrain_from_config(kind, config, extent_m=_extent(layout, platform), seed=seed)
                for kind in kinds}
    keys = [(kind, float(k)) for kind in kinds for k in noise_scales]
    tables = run_cases(platform, envelope, noise, [(terrains[kind], k) for kind, k in keys], layout,
                       n_features=n_features, seed=seed + 10, **choices)
    return pd.concat([t.assign(terrain=kind, noise_scale=k) for t, (kind, k) in zip(tables, keys)],
                     ignore_index=True)


def paired_comparison(table: pd.DataFrame, a: str, b: str, by=()) -> pd.DataFrame:
    """``a`` against ``b`` on the features both estimated, per group of ``by``: the number of
    pairs, the median of ``error_3d(a) - error_3d(b)`` (m), the share where ``a`` is closer,
    and the one-sided Wilcoxon signed-rank p-values for "``a`` is closer" (``p_value``) and for
    "``b`` is closer" (``p_value_b_closer``) (``scipy.stats``; NaN for fewer than 10 pairs or
    all differences 0).

    Parameters
    ----------
    table : pandas.DataFrame
        Per-feature rows (``feature``, ``estimator``, ``estimated``, ``error_3d_m``).
    a : str
        First estimator.
    b : str
        Second estimator.
    by : sequence of str
        Grouping columns (empty: one group).

    Returns
    -------
    pandas.DataFrame
        One row per group: ``n_pairs``, ``median_difference_m``, ``share_closer``, ``p_value``,
        ``p_value_b_closer``.
    """
    from scipy.stats import wilcoxon

    rows = []
    groups = table.groupby(list(by), sort=False) if by else [((), table)]
    for key, t in groups:
        ea = t[t.estimator == a].set_index("feature")
        eb = t[t.estimator == b].set_index("feature")
        both = ea.estimated & eb.reindex(ea.index).estimated.fillna(False).astype(bool)
        d = (ea.error_3d_m - eb.error_3d_m.reindex(ea.index))[both].to_numpy()
        testable = d.size >= 10 and np.any(d != 0)
        p = wilcoxon(d, alternative="less").pvalue if testable else np.nan
        q = wilcoxon(d, alternative="greater").pvalue if testable else np.nan
        key = key if isinstance(key, tuple) else (key,)
        rows.append(dict(zip(by, key), n_pairs=int(d.size),
                         median_difference_m=float(np.median(d)) if d.size else np.nan,
                         share_closer=float(np.mean(d < 0)) if d.size else np.nan, p_value=float(p),
                         p_value_b_closer=float(q)))
    return pd.DataFrame(rows)
