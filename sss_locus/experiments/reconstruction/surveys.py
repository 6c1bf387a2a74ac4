"""The reconstruction chapter's study over independent simulated surveys.

One *survey* is a seed: a new random seafloor (or the plane of a slope case), new features, new
in-beam elevations and new navigation errors (:mod:`~sss_locus.experiments.passes.pass_noise`), observed
by the layout of ``data/terrain.toml`` with its main lines ``spacing_m`` apart. Every estimator of
:mod:`~sss_locus.experiments.reconstruction.estimators` (and any ``extra`` one) runs on the same noisy views.

Errors of one survey and estimator (:func:`survey_errors`), over the features every compared
estimator estimated (the *common subset*, so the estimators are compared on the same features):

``horizontal_m``
    the median horizontal error;
``vertical_m``
    the median |vertical error|;
``shape_m``
    the *map-shape* error: the median length of the error vector after removing the survey's
    median error vector (componentwise median over the common subset): what is left when the
    whole map is shifted onto the truth, i.e. the error of the map's shape, which ranges can
    observe, against its absolute position, which they cannot
    (:func:`~sss_locus.experiments.adjustment.map_errors`);
``coverage``
    the share of the seen features the estimator estimated (over all its seen features, not
    only the common subset).

Intervals are over the surveys (:func:`over_surveys`): each survey is an independent replicate,
the point estimate the mean of the survey values and the interval Student's t over them
(:func:`~sss_locus.experiments.stats.replicates.replicate_interval`), never over features.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from sss_locus.experiments.adjustment import map_errors
from sss_locus.experiments.reconstruction.estimators import reconstruct_many
from sss_locus.experiments.stats.replicates import replicate_interval
from sss_locus.experiments.datamodel.terrain import Terrain, place_features, random_terrain, slope_terrain
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features
from sss_locus.experiments.reconstruction.study import survey_altitude_m

METRICS = ("horizontal_m", "vertical_m", "shape_m")
"""The errors of :func:`survey_errors`, each a median over the common subset of a survey (m)."""


def layout_with_spacing(config: dict, spacing_m: float) -> SurveyLayout:
    """The layout of ``config["survey"]`` with main lines ``spacing_m`` apart.

    Parameters
    ----------
    config : dict
        The configuration with a ``survey`` table.
    spacing_m : float
        Main-line spacing, m.

    Returns
    -------
    SurveyLayout
        The layout.
    """
    return SurveyLayout(**{**config["survey"], "line_spacing_m": float(spacing_m)})


def extent_m(layout: SurveyLayout, platform) -> float:
    """Side of the square where the seafloor must be defined for ``layout`` (m).

    Parameters
    ----------
    layout : SurveyLayout
        The survey layout (``area_m``, ``margin_m``).
    platform : Platform
        The platform (its sonar's ``max_range_m``).

    Returns
    -------
    float
        Side length, m.
    """
    return layout.area_m + 2.0 * (platform.sonar.max_range_m + layout.margin_m) + 10.0


def survey_cases(platform, envelope, noise, pass_noise, config: dict, *, kind: str, values, spacings_m,
                 seeds: Sequence[int], n_features: int, navigation: str = "per_pass", extra: Mapping | None = None,
                 n_views=(3,), shadowing: str = "off", below_sensors: bool = True) -> pd.DataFrame:
    """The per-feature tables of every survey: for each seed, spacing and value.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope (the altitude flown).
    noise : NoiseModel
        The measurement noise model.
    pass_noise : PassNoise
        The per-pass navigation noise.
    config : dict
        The terrain configuration (``survey``, ``random``, ``slope`` tables).
    kind : {"relief", "slope"}
        ``"relief"``: ``values`` are RMS reliefs (m) of one random field per seed (correlation
        length and grid of ``config["random"]``), scaled to each; ``"slope"``: ``values`` are
        slopes (deg) of the plane of ``config["slope"]`` (its azimuth).
    values : sequence of float
        The reliefs (m) or slopes (deg).
    spacings_m : sequence of float
        Main-line spacings (m); cross lines as in ``config["survey"]``.
    seeds : sequence of int
        One independent survey per seed (>= 0).
    n_features : int
        Features per survey.
    navigation, extra, n_views, shadowing, below_sensors
        As :func:`~sss_locus.experiments.reconstruction.estimators.reconstruct`.

    Returns
    -------
    pandas.DataFrame
        The rows of :func:`~sss_locus.experiments.reconstruction.estimators.reconstruct` (a view whose sensor
        would be below the seafloor under it, a boat over a steep slope, is not seen) with ``seed``,
        ``spacing_m``, ``value`` (relief m or slope deg) and ``n_shadowed`` added.
    """
    if kind not in ("relief", "slope"):
        raise ValueError(f"kind must be 'relief' or 'slope'; got {kind!r}")
    altitude = survey_altitude_m(envelope)
    keys, jobs, lost = [], [], []
    for spacing in spacings_m:
        layout = layout_with_spacing(config, spacing)
        for seed in seeds:
            base = None
            if kind == "relief":
                rc = config["random"]
                base = random_terrain(1.0, rc["correlation_length_m"], extent_m(layout, platform),
                                      rc["grid_spacing_m"], 10 * int(seed))
            for value in values:
                if kind == "relief":
                    x0, y0, dx, h = base.grid
                    terrain = Terrain("random", {**base.params, "rms_relief_m": float(value)},
                                      grid=(x0, y0, dx, h * float(value)))
                else:
                    terrain = slope_terrain(float(value), config["slope"]["azimuth_deg"])
                f = place_features(terrain, n_features, layout.area_m, 10 * int(seed) + 1)
                views, seen, info = observe_features(platform, terrain, f, layout, altitude, envelope.same_altitude,
                                                     10 * int(seed) + 2, shadowing)
                seen = seen & (info["sensor_height_m"] > 0)  # a boat over a steep slope runs aground: no view
                keys.append((int(seed), float(spacing), float(value)))
                lost.append(info["shadowed"].sum(axis=1))
                jobs.append(dict(views=views, seen=seen, sensor_height_m=info["sensor_height_m"], noise=noise,
                                 seed=10 * int(seed) + 3, below_sensors=below_sensors, navigation=navigation,
                                 pass_noise=pass_noise, along_m=info["along_m"], extra=extra))
    tables = reconstruct_many(jobs, platform.sonar.aperture(), n_views=n_views)
    return pd.concat([t.assign(seed=s, spacing_m=sp, value=v, n_shadowed=x[t.feature.to_numpy()])
                      for t, (s, sp, v), x in zip(tables, keys, lost)], ignore_index=True)


def survey_errors(table: pd.DataFrame, estimators: Sequence[str], by=("seed", "spacing_m", "value")) -> pd.DataFrame:
    """One row per survey (group of ``by``) and estimator of ``estimators``: ``n_common`` (the
    features every one of ``estimators`` estimated), ``coverage``, and the :data:`METRICS` over
    the common subset (module docstring; NaN where it is empty).

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`survey_cases`' rows.
    estimators : sequence of str
        The estimators compared.
    by : sequence of str
        Columns naming a survey.

    Returns
    -------
    pandas.DataFrame
        One row per survey and estimator: ``n_common``, ``coverage``, ``horizontal_m``,
        ``vertical_m``, ``shape_m`` (medians, m).
    """
    rows = []
    for key, t in table[table.estimator.isin(list(estimators))].groupby(list(by), sort=True):
        key = key if isinstance(key, tuple) else (key,)
        wide = t.pivot(index="feature", columns="estimator", values="estimated")
        common = wide.reindex(columns=list(estimators)).fillna(False).astype(bool).all(axis=1)
        common = set(common[common].index)
        for est in estimators:
            e = t[t.estimator == est]
            seen = e[e.n_seen >= 1]
            c = e[e.feature.isin(common)]
            d = c[["error_x_m", "error_y_m", "error_v_m"]].to_numpy(float)
            m = map_errors(d, np.zeros_like(d)) if len(d) else None
            rows.append(dict(zip(by, key), estimator=est, n_common=len(c),
                             coverage=float(seen.estimated.mean()) if len(seen) else np.nan,
                             horizontal_m=float(np.median(m["horizontal_m"])) if m else np.nan,
                             vertical_m=float(np.median(np.abs(m["vertical_m"]))) if m else np.nan,
                             shape_m=float(np.median(m["shape_m"])) if m else np.nan))
    return pd.DataFrame(rows)


def over_surveys(per_survey: pd.DataFrame, by, columns=METRICS + ("coverage",),
                 confidence_level: float = 0.95) -> pd.DataFrame:
    """Mean over the surveys (the ``seed`` rows) of each of ``columns``, per group of ``by``, with
    its interval (``<column>_low``, ``<column>_high``) and the number of surveys ``n_surveys``
    (surveys with a NaN value, an empty common subset, are left out of that column).

    Parameters
    ----------
    per_survey : pandas.DataFrame
        One row per survey (:func:`survey_errors`).
    by : sequence of str
        Grouping columns.
    columns : sequence of str
        Columns averaged.
    confidence_level : float
        Interval level, in (0, 1).

    Returns
    -------
    pandas.DataFrame
        One row per group: ``n_surveys`` and, per column, the mean, ``_low`` and ``_high`` (NaN
        interval with fewer than 3 finite surveys).
    """
    rows = []
    for key, g in per_survey.groupby(list(by), sort=False):
        key = key if isinstance(key, tuple) else (key,)
        row = dict(zip(by, key), n_surveys=len(g))
        for col in columns:
            v = g[col].to_numpy(float)
            v = v[np.isfinite(v)]
            mean = float(v.mean()) if v.size else np.nan
            lo, hi = replicate_interval(mean, v, confidence_level) if v.size >= 3 else (np.nan, np.nan)
            row.update({col: mean, f"{col}_low": float(lo), f"{col}_high": float(hi)})
        rows.append(row)
    return pd.DataFrame(rows)


def paired_over_surveys(per_survey: pd.DataFrame, a: str, b: str, by=("spacing_m", "value"),
                        columns=METRICS, confidence_level: float = 0.95) -> pd.DataFrame:
    """``a`` minus ``b`` per survey for each of ``columns`` (m; negative: ``a`` closer), its
    mean over the surveys and interval (:func:`over_surveys`), per group of ``by``. The verdict
    "``a`` closer" holds where the interval's high end is below 0, "``b`` closer" where its low
    end is above 0.

    Parameters
    ----------
    per_survey : pandas.DataFrame
        One row per survey and estimator (:func:`survey_errors`).
    a : str
        First estimator.
    b : str
        Second estimator.
    by : sequence of str
        Grouping columns (besides ``seed``).
    columns : sequence of str
        Metrics differenced, m.
    confidence_level : float
        Interval level, in (0, 1).

    Returns
    -------
    pandas.DataFrame
        :func:`over_surveys` of the differences, with ``a`` and ``b``.
    """
    keys = ["seed", *by]
    pa = per_survey[per_survey.estimator == a].set_index(keys)[list(columns)]
    pb = per_survey[per_survey.estimator == b].set_index(keys)[list(columns)]
    diff = (pa - pb.reindex(pa.index)).reset_index()
    return over_surveys(diff, by, columns, confidence_level).assign(a=a, b=b)
