"""Survey envelopes and across-track offset models of the two-pass study (inputs of
:mod:`sss_locus.experiments.survey_passes.study`), with their defaults read from ``data/survey.toml``.

``data/survey.toml`` holds one ``[envelopes.<platform key>]`` table per platform (altitude and
pitch ranges, whether both passes share one altitude) and ``[offset_models.matched]`` (the
default jitter); every number carries a ``source`` or an ``assumption`` as in
``data/platforms.toml``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from sss_locus.paths import DATA_DIR
from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models

SURVEY_FILE: Path = DATA_DIR / "survey.toml"
OFFSET_KINDS = ("independent", "matched")
SIDE_RULES = ("random", "same", "opposite")
SIDE1_CHOICES = ("random", "port", "starboard")


@dataclass(frozen=True)
class SurveyEnvelope:
    """Operating envelope of a platform on survey passes.

    Parameters
    ----------
    altitude_min_m, altitude_max_m : float
        Height of the vehicle reference point above the feature, metres (uniform per pass).
    pitch_min_deg, pitch_max_deg : float
        Pitch per pass, degrees, positive nose-up, in [-90, 90] (uniform per pass).
    same_altitude : bool
        Both passes at one altitude (a surface vessel over a fixed feature).
    level_pass1 : bool
        Pass 1 flown at zero pitch (a level reference pass, like vehicle 1 of the pose-space
        study); only pass 2 draws its pitch.
    """

    altitude_min_m: float
    altitude_max_m: float
    pitch_min_deg: float = 0.0
    pitch_max_deg: float = 0.0
    same_altitude: bool = False
    level_pass1: bool = False

    def __post_init__(self) -> None:
        for name in ("altitude_min_m", "altitude_max_m", "pitch_min_deg", "pitch_max_deg"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                    or not math.isfinite(v):
                raise ValueError(f"SurveyEnvelope.{name} must be a finite number; got {v!r}")
            object.__setattr__(self, name, float(v))
        if not 0.0 < self.altitude_min_m <= self.altitude_max_m:
            raise ValueError("SurveyEnvelope needs 0 < altitude_min_m <= altitude_max_m; got "
                             f"{self.altitude_min_m}, {self.altitude_max_m}")
        if not -90.0 <= self.pitch_min_deg <= self.pitch_max_deg <= 90.0:
            raise ValueError("SurveyEnvelope needs -90 <= pitch_min_deg <= pitch_max_deg <= 90; got "
                             f"{self.pitch_min_deg}, {self.pitch_max_deg}")
        object.__setattr__(self, "same_altitude", bool(self.same_altitude))
        object.__setattr__(self, "level_pass1", bool(self.level_pass1))

    def with_pitch(self, lo: float, hi: float) -> "SurveyEnvelope":
        """A copy with pitch drawn in ``[lo, hi]`` degrees (``lo == hi`` fixes it).

        Parameters
        ----------
        lo, hi : float
            Pitch range, degrees, nose-up positive.

        Returns
        -------
        SurveyEnvelope
            The copy.
        """
        return replace(self, pitch_min_deg=lo, pitch_max_deg=hi)

    def with_altitude(self, lo: float, hi: float) -> "SurveyEnvelope":
        """A copy with altitude drawn in ``[lo, hi]`` metres (``lo == hi`` fixes it).

        Parameters
        ----------
        lo, hi : float
            Altitude range, metres.

        Returns
        -------
        SurveyEnvelope
            The copy.
        """
        return replace(self, altitude_min_m=lo, altitude_max_m=hi)

    def key(self) -> dict:
        """Plain-data description (for cache keys and figure manifests).

        Returns
        -------
        dict
            Every field by name.
        """
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class OffsetModel:
    """Across-track offsets of the two passes from the feature (the paper does not state them).

    Parameters
    ----------
    kind : {"independent", "matched"}
        ``"independent"``: each pass's ground offset uniform over its own swath.
        ``"matched"``: pass 2's offset is pass 1's plus a uniform jitter in
        ``[-jitter_m, jitter_m]`` (rejected, and counted, if outside pass 2's swath).
    jitter_m : float
        Half-width of the matched jitter, metres (>= 0); must be 0 for ``"independent"``.
    side_rule : {"random", "same", "opposite"}
        Which transducer of pass 2 sees the feature: port/starboard at random, the same side as
        pass 1, or the other side.
    side1 : {"random", "port", "starboard"}
        Which transducer of pass 1 sees the feature (default: either, with probability 1/2).
    """

    kind: str = "independent"
    jitter_m: float = 0.0
    side_rule: str = "random"
    side1: str = "random"

    def __post_init__(self) -> None:
        if self.kind not in OFFSET_KINDS:
            raise ValueError(f"OffsetModel.kind must be one of {list(OFFSET_KINDS)}; got {self.kind!r}")
        if self.side1 not in SIDE1_CHOICES:
            raise ValueError(f"OffsetModel.side1 must be one of {list(SIDE1_CHOICES)}; got {self.side1!r}")
        if self.side_rule not in SIDE_RULES:
            raise ValueError(f"OffsetModel.side_rule must be one of {list(SIDE_RULES)}; got {self.side_rule!r}")
        j = self.jitter_m
        if isinstance(j, bool) or not isinstance(j, (int, float, np.integer, np.floating)) \
                or not math.isfinite(j) or j < 0:
            raise ValueError(f"OffsetModel.jitter_m must be a finite number >= 0 (metres); got {j!r}")
        if self.kind == "independent" and j != 0:
            raise ValueError("OffsetModel.jitter_m applies only to kind='matched'; use 0 for 'independent'")
        object.__setattr__(self, "jitter_m", float(j))

    @classmethod
    def parse(cls, spec: str) -> "OffsetModel":
        """The model named by a parameter string: ``"independent"`` or
        ``"matched:<jitter_m>:<side_rule>"`` (``side_rule`` one of :data:`SIDE_RULES`).

        Parameters
        ----------
        spec : str
            The parameter string.

        Returns
        -------
        OffsetModel
            The model.

        Examples
        --------
        >>> OffsetModel.parse("matched:10:same")
        OffsetModel(kind='matched', jitter_m=10.0, side_rule='same', side1='random')
        >>> OffsetModel.parse("independent").label
        'independent'
        """
        forms = ("valid forms: 'independent' or 'matched:<jitter_m>:<side_rule>' with jitter_m a "
                 f"number of metres >= 0 and side_rule one of {list(SIDE_RULES)}")
        if not isinstance(spec, str):
            raise ValueError(f"offset model spec must be a string; got {spec!r} ({forms})")
        if spec == "independent":
            return cls("independent")
        parts = spec.split(":")
        if len(parts) != 3 or parts[0] != "matched":
            raise ValueError(f"offset model spec {spec!r} is malformed; {forms}")
        try:
            jitter = float(parts[1])
        except ValueError:
            raise ValueError(f"offset model spec {spec!r}: jitter_m {parts[1]!r} is not a number; "
                             f"{forms}") from None
        if parts[2] not in SIDE_RULES:
            raise ValueError(f"offset model spec {spec!r}: side_rule {parts[2]!r} is not one of "
                             f"{list(SIDE_RULES)}; {forms}")
        try:
            return cls("matched", jitter, parts[2])
        except ValueError as err:
            raise ValueError(f"offset model spec {spec!r}: {err}; {forms}") from None

    @property
    def label(self) -> str:
        """Short human-readable name."""
        core = "independent" if self.kind == "independent" else f"matched ±{self.jitter_m:g} m"
        core = core if self.side_rule == "random" else f"{core}, {self.side_rule} side"
        return core if self.side1 == "random" else f"{core}, pass 1 {self.side1}"

    def key(self) -> dict:
        """Plain-data description (for cache keys and figure manifests).

        Returns
        -------
        dict
            Every field by name.
        """
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def load_envelope(platform_key: str, path: str | Path | None = None) -> SurveyEnvelope:
    """The survey envelope of ``platform_key`` from ``data/`` merged with the active user data
    (:mod:`sss_locus.experiments.datamodel.userdata`), or from the file ``path`` only.

    Parameters
    ----------
    platform_key : str
        Key of the platform in ``[envelopes]``.
    path : str or pathlib.Path, optional
        A TOML file read alone instead.

    Returns
    -------
    SurveyEnvelope
        The validated envelope.
    """
    return datadoc.load_table(lambda doc: parse_envelope(doc, platform_key), path, f"envelopes.{platform_key}")


def parse_envelope(doc: dict, platform_key: str) -> SurveyEnvelope:
    """The validated ``[envelopes.<platform_key>]`` table of a parsed document.

    Parameters
    ----------
    doc : dict
        A parsed TOML document.
    platform_key : str
        Key of the platform in ``[envelopes]``.

    Returns
    -------
    SurveyEnvelope
        The validated envelope.
    """
    return envelope_from(models.validate_document(doc, ("envelopes",)), platform_key)


def envelope_from(data: models.Data, platform_key: str) -> SurveyEnvelope:
    """The :class:`SurveyEnvelope` of ``platform_key`` in a validated data document.

    Parameters
    ----------
    data : sss_locus.experiments.datamodel.models.Data
        The validated document.
    platform_key : str
        Key of the platform in ``[envelopes]``.

    Returns
    -------
    SurveyEnvelope
        The envelope.
    """
    m = models.entry(data.envelopes, "envelopes", platform_key)
    return SurveyEnvelope(m.altitude_min_m.value, m.altitude_max_m.value, m.pitch_min_deg.value,
                          m.pitch_max_deg.value, same_altitude=m.same_altitude.value)


def default_offset_model(kind: str = "independent", side_rule: str = "random",
                         path: str | Path | None = None, doc: dict | None = None) -> OffsetModel:
    """An :class:`OffsetModel` with the defaults of the data (matched jitter): ``doc``, the file
    ``path``, or ``data/`` merged with the active user data.

    Parameters
    ----------
    kind : {"independent", "matched"}
        Kind of model.
    side_rule : str
        One of :data:`SIDE_RULES`.
    path : str or pathlib.Path, optional
        A TOML file read alone instead.
    doc : dict, optional
        A parsed document used instead of any file.

    Returns
    -------
    OffsetModel
        The model.
    """
    if kind != "matched":
        return OffsetModel(kind, 0.0, side_rule)
    data = datadoc.load_table(lambda d: models.validate_document(d, ("offset_models",)), path,
                              "offset_models.matched", doc=doc)
    return OffsetModel(kind, data.offset_models.matched.jitter_m.value, side_rule)
