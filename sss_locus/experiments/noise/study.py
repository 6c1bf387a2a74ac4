"""The noise chapter's study: the Monte Carlo spread of every pass pair's locus under the noise
models of the chapter (:func:`survey_noise_table`). The noise model:
:mod:`sss_locus.experiments.datamodel.noise_model`; its propagation:
:mod:`sss_locus.experiments.passes.propagation`."""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.passes.propagation import monte_carlo
from sss_locus.experiments.passes.view_sets import views_from_survey


def survey_noise_table(platform, samples: pd.DataFrame, noise_models: dict, *, n_draws: int,
                       seed: int, quantile: float = 0.95) -> pd.DataFrame:
    """:func:`monte_carlo` for every pass pair of :func:`sss_locus.experiments.survey_passes.study.simulate_passes`.

    ``noise_models`` maps a label to a :class:`NoiseModel`. Returns one row per pass pair and
    model: ``noise`` (label), ``crossing_angle_deg``, ``locus_length_m`` (noise-free),
    ``band_width_m`` (twice the ``quantile`` of the distance from the feature to the perturbed
    circle: the width of the band the locus sweeps), ``extent_m`` (``hypot(locus_length_m,
    band_width_m)``: the diagonal of a band that long and that wide), ``empty_fraction`` and
    ``far_q_m`` (see :func:`monte_carlo`).

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    samples : pandas.DataFrame
        Its pass pairs.
    noise_models : dict of str to NoiseModel
        Models by label.
    n_draws : int
        Noisy draws per pass pair.
    seed : int
        Seed.
    quantile : float
        Quantile of the distance, in (0, 1).

    Returns
    -------
    pandas.DataFrame
        The rows described above.
    """

    views = views_from_survey(platform, samples)
    ap = platform.sonar.aperture()
    frames = []
    for i, (label, model) in enumerate(noise_models.items()):
        mc = monte_carlo(views, model, ap, kind="two", n_draws=n_draws, seed=seed + i, quantile=quantile)
        band = 2.0 * mc["circle_miss_q"].to_numpy()
        frames.append(pd.DataFrame({
            "noise": label, "crossing_angle_deg": samples["crossing_angle_deg"].to_numpy(float),
            "locus_length_m": mc["length0_m"].to_numpy(), "band_width_m": band,
            "extent_m": np.hypot(mc["length0_m"].to_numpy(), band),
            "empty_fraction": mc["empty_fraction"].to_numpy(), "far_q_m": mc["far_q"].to_numpy()}))
    return pd.concat(frames, ignore_index=True)
