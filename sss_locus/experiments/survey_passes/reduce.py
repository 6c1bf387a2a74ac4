"""The crossing-angle curve reduced where its samples are made: one row per angle travels.

:func:`~sss_locus.experiments.survey_passes.planning.crossing_angle_curve` brings every accepted pass pair
back as a row (about 180 bytes a sample on a Dask cluster). Each crossing angle is already one
chunk of the study (:func:`~sss_locus.experiments.survey_passes.study.simulate_passes`), and every
column of the curve (the median, quartiles and replicate interval of each value, the
acceptance) depends on that angle's rows alone, so :func:`reduce_crossing_angle_curve`
computes each angle's row in its chunk and sends only that row: the curve is bit for bit
:func:`~sss_locus.experiments.survey_passes.planning.crossing_angle_curve`'s, in-process and on any number of
workers. Not reduced: the peak angle's bootstrap interval, whose resamples are drawn from one
generator across all angles (:func:`~sss_locus.experiments.survey_passes.planning.curve_summary`).
"""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope
from sss_locus.experiments.survey_passes.planning import VALUES, curve_frame, curve_row
from sss_locus.experiments.datamodel.platforms import Platform
from sss_locus.experiments.stats.replicates import N_BATCHES, check_batches, check_confidence
from sss_locus.experiments.stats.scale import map_chunks
from sss_locus.experiments.survey_passes.study import check_envelope, check_inputs, simulate_passes


def _angle(platform, envelope, offset_model, gamma, n, seed, n_batches, confidence_level, values):
    """One angle's chunk: its curve row (with ``acceptance``), no samples."""
    samples, acc = simulate_passes(platform, envelope, offset_model, [gamma], n, seed)
    row = curve_row(gamma, samples, values, n_batches, confidence_level)
    return {**row, "acceptance": float(acc["acceptance"].iloc[0])}


def reduce_crossing_angle_curve(platform: Platform, envelope: SurveyEnvelope, offset_model: OffsetModel,
                                crossing_angles_deg, n_per_angle: int, seed: int, *,
                                n_batches: int = N_BATCHES, confidence_level: float = 0.95,
                                values=VALUES, progress=None) -> tuple[pd.DataFrame, int]:
    """``(curve, bytes_to_client)``: the ``curve`` of
    :func:`~sss_locus.experiments.survey_passes.planning.crossing_angle_curve` for the same arguments (one
    row per angle, the same numbers bit for bit), computed in each angle's chunk; and the
    pickled size of what the client received. Arguments as there (the angles distinct), checked
    before any chunk runs.

    Parameters
    ----------
    platform : Platform
        Sonar and mounting (apertures and tilts in degrees, ranges in metres).
    envelope : SurveyEnvelope
        The platform's survey envelope (altitudes, attitudes, line spacing).
    offset_model : OffsetModel
        How the two passes' lateral offsets are drawn.
    crossing_angles_deg : array_like, shape (G,)
        Distinct crossing angles between the two passes, degrees (any order; rows come out
        sorted).
    n_per_angle : int
        Accepted pass pairs per angle.
    seed : int
        Random seed, passed to each angle's :func:`~sss_locus.experiments.survey_passes.study.simulate_passes`.
    n_batches : int
        Replicate batches of each angle's rows for the medians' intervals.
    confidence_level : float
        Of those intervals, in (0, 1).
    values : sequence of str
        The per-pair columns summarised (default :data:`~sss_locus.experiments.survey_passes.planning.VALUES`).
    progress : callable, optional
        ``progress(done, total)`` after each chunk (:func:`~sss_locus.experiments.stats.scale.map_chunks`).

    Returns
    -------
    curve : pandas.DataFrame
        One row per angle (sorted): ``crossing_angle_deg``, the medians, quartiles and
        intervals of ``values``, and ``acceptance`` (share of drawn pairs accepted).
    bytes_to_client : int
        Pickled size, bytes, of the per-angle rows the chunks returned.

    Raises
    ------
    ValueError
        Repeated angles, wrong argument types, or any argument out of its range.
    """
    angles, n, seed = check_inputs(crossing_angles_deg, n_per_angle, seed)
    if np.unique(angles).size != angles.size:
        raise ValueError(f"crossing_angles_deg must be distinct angles; got {crossing_angles_deg!r}")
    if not (isinstance(platform, Platform) and isinstance(envelope, SurveyEnvelope)
            and isinstance(offset_model, OffsetModel)):
        raise ValueError("platform must be a Platform, envelope a SurveyEnvelope and offset_model an OffsetModel")
    check_envelope(platform, envelope)
    check_batches(n_batches)
    check_confidence(confidence_level)
    rows = map_chunks(_angle, [(platform, envelope, offset_model, float(g), n, seed, n_batches,
                                confidence_level, tuple(values)) for g in np.sort(angles)], progress)
    curve = curve_frame(rows, values)
    curve["acceptance"] = [r["acceptance"] for r in rows]
    return curve, len(pickle.dumps(rows))
