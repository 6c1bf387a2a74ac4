"""The measurement-noise model of one view: :class:`NoiseModel` and its loaders (``[noise.<platform>]``
of ``data/noise.toml`` merged with the user's files).

Model (:class:`NoiseModel`, numbers in ``data/noise.toml`` with sources or marked assumptions)
--------------------------------------------------------------------------------------------
Each view ``k`` of a feature (world frame as in :mod:`sss_locus.experiments.survey_passes.study`: ``z`` up) has a
true sensor pose (axes ``W_k``, origin ``o_k``, vehicle attitude ``V_k``) and a true range
``r_k = |f - o_k|``. What a user has are estimates, perturbed by seven independent zero-mean
Gaussian errors per view (:data:`ERROR_NAMES`): the range (standard deviation
``hypot(range_sigma_per_resolution * range_resolution_m, sound_speed_relative_sigma * r)``),
the three coordinates of the origin (horizontal, horizontal, vertical sigmas) and a small
attitude rotation about the vehicle's forward, port and up axes (roll, pitch, heading sigmas):
``W_k_hat = Exp(V_k (d_roll, d_pitch, d_heading)) W_k`` (about the sensor origin: the
attitude error does not move the origin through the lever arm, decimetres against metres of
position error). Errors are independent between views.

How the errors spread the loci: :mod:`sss_locus.experiments.passes.propagation`; the per-pass
navigation errors read from the same table: :mod:`sss_locus.experiments.passes.pass_noise`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models


def check_sigmas(table) -> None:
    """Refuse, naming the field, a frozen dataclass of standard deviations with a field that is
    not a finite number >= 0 (``true`` and ``"0.1"`` are not numbers); store every field as a float.

    Parameters
    ----------
    table : dataclass instance
        A frozen dataclass whose every field is a standard deviation (e.g. :class:`NoiseModel`,
        :class:`~sss_locus.experiments.passes.pass_noise.PassNoise`).
    """
    for f in fields(table):
        v = getattr(table, f.name)
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                or not math.isfinite(v) or v < 0:
            raise ValueError(f"{type(table).__name__}.{f.name} must be a finite number >= 0; got {v!r}")
        object.__setattr__(table, f.name, float(v))


@dataclass(frozen=True)
class NoiseModel:
    """Standard deviations of the measurement errors of one view (see the module docstring).

    All fields are finite and >= 0; lengths in metres, angles in degrees.
    """

    range_resolution_m: float
    range_sigma_per_resolution: float = 1.0
    sound_speed_relative_sigma: float = 0.0
    horizontal_sigma_m: float = 0.0
    vertical_sigma_m: float = 0.0
    roll_sigma_deg: float = 0.0
    pitch_sigma_deg: float = 0.0
    heading_sigma_deg: float = 0.0

    def __post_init__(self) -> None:
        check_sigmas(self)

    def scaled(self, k: float) -> "NoiseModel":
        """Every standard deviation multiplied by ``k`` (>= 0); ``scaled(0)`` is noise-free.

        Parameters
        ----------
        k : float
            Factor, ``>= 0``.

        Returns
        -------
        NoiseModel
            The scaled copy.
        """
        if not (isinstance(k, (int, float, np.integer, np.floating)) and math.isfinite(k) and k >= 0):
            raise ValueError(f"k must be a finite number >= 0; got {k!r}")
        return replace(self, range_resolution_m=k * self.range_resolution_m,
                       sound_speed_relative_sigma=k * self.sound_speed_relative_sigma,
                       horizontal_sigma_m=k * self.horizontal_sigma_m,
                       vertical_sigma_m=k * self.vertical_sigma_m,
                       roll_sigma_deg=k * self.roll_sigma_deg, pitch_sigma_deg=k * self.pitch_sigma_deg,
                       heading_sigma_deg=k * self.heading_sigma_deg)

    def only(self, *groups: str) -> "NoiseModel":
        """A copy keeping only the error groups named (``"range"``, ``"position"``,
        ``"attitude"``); the others are set to 0.

        Parameters
        ----------
        *groups : str
            Groups kept.

        Returns
        -------
        NoiseModel
            The copy.
        """
        known = {"range": ("range_resolution_m", "sound_speed_relative_sigma"),
                 "position": ("horizontal_sigma_m", "vertical_sigma_m"),
                 "attitude": ("roll_sigma_deg", "pitch_sigma_deg", "heading_sigma_deg")}
        bad = set(groups) - set(known)
        if bad:
            raise ValueError(f"groups must be among {sorted(known)}; got {sorted(bad)}")
        return replace(self, **{n: 0.0 for g, names in known.items() if g not in groups for n in names})

    def range_sigma_m(self, r) -> np.ndarray:
        """Range standard deviation (m) at true range ``r`` (m).

        Parameters
        ----------
        r : array_like
            True ranges, metres.

        Returns
        -------
        numpy.ndarray
            Standard deviations, metres.
        """
        return np.hypot(self.range_sigma_per_resolution * self.range_resolution_m,
                        self.sound_speed_relative_sigma * np.asarray(r, float))

    def key(self) -> dict:
        """Plain-data description (for cache keys and figure manifests).

        Returns
        -------
        dict
            Every field by name.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}


def load_noise_model(platform_key: str, path: str | Path | None = None) -> NoiseModel:
    """The noise model of ``platform_key`` from ``data/`` merged with the active user data
    (:mod:`sss_locus.experiments.datamodel.userdata`), or from the file ``path`` only.

    Parameters
    ----------
    platform_key : str
        Key of the platform in ``[noise]``.
    path : str or pathlib.Path, optional
        A TOML file read alone instead.

    Returns
    -------
    NoiseModel
        The validated model.
    """
    return datadoc.load_table(lambda doc: parse_noise_model(doc, platform_key), path, f"noise.{platform_key}")


def parse_noise_model(doc: dict, platform_key: str) -> NoiseModel:
    """The validated ``[noise.<platform_key>]`` table of a parsed document.

    Parameters
    ----------
    doc : dict
        A parsed TOML document.
    platform_key : str
        Key of the platform in ``[noise]``.

    Returns
    -------
    NoiseModel
        The validated model.
    """
    m = models.entry(models.validate_document(doc, ("noise",)).noise, "noise", platform_key)
    return NoiseModel(**{f.name: getattr(m, f.name).value for f in fields(NoiseModel)})
