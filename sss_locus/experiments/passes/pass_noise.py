"""Navigation error as a survey has it: shared by every ping of a pass (the reconstruction chapter).

Two named models of the errors of the views of a survey (features ``i`` times passes ``l``):

``"per_pass"`` (:data:`NAVIGATION_MODELS`, the chapter's default)
    every ping of pass ``l`` shares one horizontal offset ``b_l`` (two independent Gaussian
    components, standard deviation ``pass_offset_sigma_m`` each: a GNSS bias correlated over
    minutes, the dead-reckoning error at the start of the pass) and one heading bias
    ``psi_l`` (``pass_heading_bias_sigma_deg``: a compass bias, a gyro misalignment), plus a
    drift growing along the pass, ``s * d_l`` with ``s`` the distance travelled since the start
    of the pass (m) and ``d_l`` a horizontal drift rate with independent components of standard
    deviation ``drift_sigma_fraction`` (dead reckoning: a fraction of the distance travelled),
    and per ping a small independent jitter of the horizontal position
    (``ping_horizontal_sigma_m`` per axis) and heading (``ping_heading_sigma_deg``). Range,
    vertical, roll and pitch errors stay per view, with the sigmas of the
    :class:`~sss_locus.experiments.datamodel.noise_model.NoiseModel`;
``"per_view"``
    the noise chapter's model: all seven errors independent per view (per feature and pass),
    the horizontal and heading sigmas those of the ``NoiseModel``. Kept so the earlier numbers
    can be reproduced.

The values live in ``data/noise.toml`` beside the per-view ones, each with its source or marked
as an assumption (:data:`PASS_FIELDS`). A platform whose table lacks them (a user's own noise
file written before they existed) gets the documented fallback of :func:`parse_pass_noise`:
its per-view horizontal and heading sigmas become the per-pass offset and heading bias, with
no drift and no jitter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models
from sss_locus.experiments.datamodel.noise_model import check_sigmas, parse_noise_model

NAVIGATION_MODELS = ("per_pass", "per_view")
"""The named navigation-error models (module docstring)."""

PASS_FIELDS = ("pass_offset_sigma_m", "pass_heading_bias_sigma_deg", "drift_sigma_fraction",
               "ping_horizontal_sigma_m", "ping_heading_sigma_deg")
"""Keys of ``[noise.<platform>]`` read by :func:`parse_pass_noise`."""


@dataclass(frozen=True)
class PassNoise:
    """Standard deviations of the per-pass navigation errors (module docstring); all finite and
    >= 0, lengths in metres, angles in degrees, ``drift_sigma_fraction`` in metres per metre."""

    pass_offset_sigma_m: float = 0.0
    pass_heading_bias_sigma_deg: float = 0.0
    drift_sigma_fraction: float = 0.0
    ping_horizontal_sigma_m: float = 0.0
    ping_heading_sigma_deg: float = 0.0

    def __post_init__(self) -> None:
        check_sigmas(self)

    def scaled(self, k: float) -> "PassNoise":
        """Every standard deviation multiplied by ``k`` (>= 0).

        Parameters
        ----------
        k : float
            Finite factor >= 0 (0: no navigation error).

        Returns
        -------
        PassNoise
            A new instance; units unchanged.
        """
        if not (isinstance(k, (int, float, np.integer, np.floating)) and math.isfinite(k) and k >= 0):
            raise ValueError(f"k must be a finite number >= 0; got {k!r}")
        return replace(self, **{f.name: k * getattr(self, f.name) for f in fields(self)})

    def key(self) -> dict:
        """The standard deviations by field name (for cache keys and manifests).

        Returns
        -------
        dict of str to float
            Field name (unit in the name: ``_m``, ``_deg``; ``drift_sigma_fraction`` in m/m) ->
            value.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}


def parse_pass_noise(table, where: str, per_view) -> PassNoise:
    """The :class:`PassNoise` of a ``[noise.<platform>]`` table (a validated
    :class:`~sss_locus.experiments.datamodel.models.NoiseTable`, or a parsed table validated
    here; ``where`` its key path). With none of :data:`PASS_FIELDS` present, the fallback of
    the module docstring from ``per_view`` (a :class:`~sss_locus.experiments.datamodel.noise_model.NoiseModel`);
    with some but not all, a ``ValueError`` naming the missing ones.

    Parameters
    ----------
    table : NoiseTable or Mapping
        A platform's ``[noise.<platform>]`` table.
    where : str
        Its key path (e.g. ``noise.auv``), used in error messages.
    per_view : NoiseModel
        The platform's per-view noise model, for the fallback (its ``horizontal_sigma_m``
        and ``heading_sigma_deg``).

    Returns
    -------
    PassNoise
        From the table's values, or the fallback (no drift, no jitter).
    """
    from sss_locus.experiments.datamodel import models

    if not isinstance(table, models.NoiseTable):
        table = models.validated(models.NoiseTable, table, where)
    present = [k for k in PASS_FIELDS if getattr(table, k) is not None]
    if not present:
        return PassNoise(pass_offset_sigma_m=per_view.horizontal_sigma_m,
                         pass_heading_bias_sigma_deg=per_view.heading_sigma_deg)
    missing = [k for k in PASS_FIELDS if getattr(table, k) is None]
    if missing:
        raise ValueError(f"{where} has some per-pass navigation keys but not {missing} (give all of "
                         f"{list(PASS_FIELDS)}, or none for the per-view fallback)")
    return PassNoise(**{k: getattr(table, k).value for k in PASS_FIELDS})


def view_errors(sigmas, standard, *, model: str, pass_noise: PassNoise | None = None, along_m=None,
                rng: np.random.Generator | None = None) -> np.ndarray:
    """The errors (physical units) of every view of a survey: shape (n, L, 7) in the order of
    :data:`~sss_locus.experiments.passes.propagation.ERROR_NAMES` (range m, x y z m, roll pitch heading rad).

    Parameters
    ----------
    sigmas : ndarray, shape (n, L, 7)
        Per-view standard deviations (:func:`~sss_locus.experiments.passes.propagation.noise_sigmas`).
    standard : ndarray, shape (n, L, 7)
        Independent standard normal draws, one set per view.
    model : {"per_pass", "per_view"}
    pass_noise : PassNoise
        ``"per_pass"`` only.
    along_m : ndarray, shape (n, L)
        ``"per_pass"`` only: the distance travelled along pass ``l`` from its start to the ping
        that sees feature ``i``, m (>= 0).
    rng : numpy.random.Generator
        ``"per_pass"`` only: draws the pass errors (5 standard normals per pass, after
        ``standard`` was drawn).

    Returns
    -------
    ndarray, shape (n, L, 7)
        ``"per_view"``: ``standard * sigmas``. ``"per_pass"``: range, vertical, roll and pitch
        as ``"per_view"``; horizontal ``b_l + s d_l + jitter``; heading ``psi_l + jitter``.
    """
    sig, z = np.asarray(sigmas, float), np.asarray(standard, float)
    if model not in NAVIGATION_MODELS:
        raise ValueError(f"model must be one of {list(NAVIGATION_MODELS)}; got {model!r}")
    if sig.shape != z.shape or sig.ndim != 3 or sig.shape[-1] != 7:
        raise ValueError(f"sigmas and standard must both have shape (n, L, 7); got {sig.shape}, {z.shape}")
    d = z * sig
    if model == "per_view":
        return d
    if pass_noise is None or along_m is None or rng is None:
        raise ValueError("model 'per_pass' needs pass_noise, along_m and rng")
    s = np.asarray(along_m, float)
    if s.shape != sig.shape[:2] or not np.all(np.isfinite(s)):
        raise ValueError(f"along_m must be finite with shape {sig.shape[:2]}; got {s.shape}")
    L = sig.shape[1]
    p = pass_noise
    g = rng.standard_normal((L, 5))
    offset = g[:, 0:2] * p.pass_offset_sigma_m  # (L, 2)
    drift = g[:, 2:4] * p.drift_sigma_fraction  # (L, 2), m per m
    heading = g[:, 4] * math.radians(p.pass_heading_bias_sigma_deg)  # (L,)
    d[..., 1:3] = offset[None] + s[..., None] * drift[None] + z[..., 1:3] * p.ping_horizontal_sigma_m
    d[..., 6] = heading[None] + z[..., 6] * math.radians(p.ping_heading_sigma_deg)
    return d


def load_pass_noise(platform_key: str, path: str | Path | None = None) -> PassNoise:
    """The per-pass navigation errors (:mod:`~sss_locus.experiments.passes.pass_noise`) of
    ``platform_key``, read like :func:`~sss_locus.experiments.datamodel.noise_model.load_noise_model` from the same table.

    Parameters
    ----------
    platform_key : str
        The platform's key in the noise table (``[noise.<key>]``).
    path : str or pathlib.Path, optional
        A noise TOML file of the same schema; default: the run's data set (``data/noise.toml``
        merged with the user's files).

    Returns
    -------
    PassNoise
        The per-pass offset, heading bias, drift and per-ping jitter standard deviations.
    """
    def parse(doc):
        m = models.entry(models.validate_document(doc, ("noise",)).noise, "noise", platform_key)
        return parse_pass_noise(m, f"noise.{platform_key}", parse_noise_model(doc, platform_key))

    return datadoc.load_table(parse, path, f"noise.{platform_key}")
