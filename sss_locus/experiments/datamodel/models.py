"""The schema of the data files (``data/*.toml`` and users' ``--data`` files) as pydantic v2 models.

One model per table: :class:`Sonar`, :class:`Platform` (with :class:`Transducer`,
:class:`Attitude`, :class:`DepthRange`, :class:`PlatformSurvey`, :class:`Mission`),
:class:`Envelope`, :class:`OffsetModels`, :class:`NoiseTable`, :class:`Terrain`,
:class:`Survey`, :class:`SurveyDesign`, and :class:`Data` for a whole (merged) document; and
:class:`Area` (:class:`AreaFile`) for a survey area file, whose values are plain (no provenance).

Every number is a :class:`Sourced` value ``{value = ..., source = "..."}`` or ``{value = ...,
assumption = "..."}`` (exactly one of the two notes); its bounds are the ``Field(ge=, le=, gt=)``
of its declaration (:func:`~sss_locus.experiments.datamodel.sourced.number`), units are in the field names. Every table refuses keys it
does not declare (``extra="forbid"``) with the nearest declared key suggested; an error becomes a
one-line ``ValueError`` naming the key path, the value and the valid range
(:func:`~sss_locus.experiments.datamodel.sourced.validation_message`), e.g. ``platforms.auv.transducers.port.tilt_deg.value must be a
finite number in [-90.0, 90.0]; got 120.0``.

The merge of shipped data, users' files and ``--set`` overrides stays on plain dicts
(:mod:`sss_locus.experiments.datamodel.datadoc`); the merged document is validated once by
:func:`validate_document`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Annotated, Any, Literal

from pydantic import BaseModel, Field, model_validator
from pydantic_core import PydanticCustomError

from sss_locus.experiments.datamodel.inputs import suggestion
from .sourced import Key, Sourced, Table, Text, bounded, described, number, validated

Finite = number()
NonNegative = number(ge=0.0)
Angle90 = number(ge=-90.0, le=90.0)
Limit90 = number(ge=0.0, le=90.0)
Fraction = number(ge=0.0, le=1.0)


class Sonar(Table):
    """``[sonars.<key>]``: a sidescan transducer model (the paper's Table I), FULL apertures."""

    name: Text
    azimuth_deg: number(gt=0.0, le=360.0)
    elevation_deg: number(gt=0.0, le=180.0)
    max_range_m: number(gt=0.0)
    min_range_m: NonNegative

    @model_validator(mode="after")
    def _ranges(self):
        if not self.max_range_m.value > self.min_range_m.value:
            raise PydanticCustomError("order", "must exceed min_range_m = {other}; got {got}",
                                      {"field": "max_range_m", "other": repr(self.min_range_m.value),
                                       "got": repr(self.max_range_m.value)})
        return self


class Transducer(Table):
    """``[platforms.<key>.transducers.<side>]``: one transducer's mounting."""

    forward_offset_m: Finite
    lateral_offset_m: NonNegative
    depth_m: Finite
    tilt_deg: Angle90


class Transducers(Table):
    port: Transducer
    starboard: Transducer


class DepthRange(Table):
    """``[platforms.<key>.depth_m]``: depths of the reference point, metres."""

    min: NonNegative
    max: NonNegative

    @model_validator(mode="after")
    def _order(self):
        if self.max.value < self.min.value:
            raise PydanticCustomError("order", "must be >= min = {other}; got {got}",
                                      {"field": "max", "other": repr(self.min.value), "got": repr(self.max.value)})
        return self


class Attitude(Table):
    roll_max_deg: Limit90
    pitch_max_deg: Limit90


class PlatformSurvey(Table):
    altitude_fraction_of_range: NonNegative | None = None


class Mission(Table):
    turn_radius_m: number(ge=0.0, le=1e4) | None = None
    speed_m_s: number(ge=1e-3, le=100.0) | None = None


class Platform(Table):
    """``[platforms.<key>]``: a vehicle, its sonar (a key of ``[sonars]``) and their mounting.
    (Fields in the order their provenance is listed.)"""

    name: Text
    sonar: Text
    reference_point: str = ""
    azimuth_positive: Sourced[Literal["down", "up"]]
    transducers: Transducers
    depth_m: DepthRange
    attitude: Attitude
    length_m: NonNegative | None = None
    survey: PlatformSurvey = PlatformSurvey()
    mission: Mission = Mission()


class Envelope(Table):
    """``[envelopes.<platform>]``: the survey envelope of a platform's pose-space study."""

    altitude_min_m: Finite
    altitude_max_m: Finite
    pitch_min_deg: Finite
    pitch_max_deg: Finite
    same_altitude: Sourced[bool]


class MatchedOffsets(Table):
    jitter_m: NonNegative


class OffsetModels(Table):
    matched: MatchedOffsets


class NoiseTable(Table):
    """``[noise.<platform>]``: per-view measurement errors (standard deviations) and, optionally,
    the per-pass navigation errors (all five or none)."""

    range_resolution_m: NonNegative
    range_sigma_per_resolution: NonNegative
    sound_speed_relative_sigma: NonNegative
    horizontal_sigma_m: NonNegative
    vertical_sigma_m: NonNegative
    roll_sigma_deg: NonNegative
    pitch_sigma_deg: NonNegative
    heading_sigma_deg: NonNegative
    pass_offset_sigma_m: NonNegative | None = None
    pass_heading_bias_sigma_deg: NonNegative | None = None
    drift_sigma_fraction: NonNegative | None = None
    ping_horizontal_sigma_m: NonNegative | None = None
    ping_heading_sigma_deg: NonNegative | None = None


Azimuth360 = number(ge=-360.0, le=360.0)
Relief = number(ge=-1e3, le=1e3)


class Slope(Table):
    slope_deg: number(ge=0.0, le=60.0)
    azimuth_deg: Azimuth360


class Mound(Table):
    height_m: Relief
    sigma_m: number(ge=1e-3, le=1e5)


class Step(Table):
    height_m: Relief
    width_m: number(ge=0.0, le=1e5)
    azimuth_deg: Azimuth360


class RandomRelief(Table):
    rms_relief_m: number(ge=0.0, le=1e3)
    correlation_length_m: number(ge=1e-2, le=1e5)
    grid_spacing_m: number(ge=1e-3, le=1e3)


class Terrain(Table):
    """``[terrain]``: the parameters of the synthetic seafloors."""

    slope: Slope
    mound: Mound
    step: Step
    random: RandomRelief


Length = number(ge=1.0, le=1e5)


class Survey(Table):
    """``[survey]``: the reconstruction study's survey."""

    area_m: Length
    line_spacing_m: Length
    cross_line_spacing_m: Length
    margin_m: number(ge=0.0, le=1e5)


#: How far a track keeps off the navigable water's edge, m: ``survey_design.wall_clearance_m``
#: (sourced) and an area file's own ``wall_clearance_m`` (plain).
WallClearanceM = bounded(ge=0.0, le=1000.0)


class SurveyDesign(Table):
    """``[survey_design]``: the rules of the survey-design chapter's plans."""

    range_scale_fraction: number(ge=1e-3, le=10.0)
    standard_spacing_fraction: number(ge=1e-3, le=10.0)
    standard_offset_fraction: Fraction
    standard_altitude_min_fraction: Fraction
    standard_altitude_max_fraction: Fraction
    min_two_view_share: Fraction
    run_in_turn_radii: number(ge=0.0, le=1000.0)
    wall_clearance_m: Sourced[WallClearanceM]
    water_depth_m: number(ge=1e-3, le=12000.0) | None = None

    @model_validator(mode="after")
    def _order(self):
        if self.standard_altitude_min_fraction.value > self.standard_altitude_max_fraction.value:
            raise PydanticCustomError("order", "must not exceed standard_altitude_max_fraction = {other}; got {got}",
                                      {"field": "standard_altitude_min_fraction",
                                       "other": repr(self.standard_altitude_max_fraction.value),
                                       "got": repr(self.standard_altitude_min_fraction.value)})
        return self


# ---------------------------------------------------------------------------------------------
# The survey area file (sss_locus.experiments.survey_design.area): plain values, no provenance
# ---------------------------------------------------------------------------------------------
MAX_VERTICES = 100_000
"""Most vertices (all rings) an area may have: a survey boundary needs far fewer; more (a
coastline traced at centimetres) would make every coverage test slow."""
#: The mean water depth over an area, m (an area file's ``water_depth_m``, a run's ``-p water_depth_m``).
WaterDepthM = bounded(gt=0.0, le=12000.0)
#: How far past an area's outer edge the water is navigable, m.
WaterBeyondM = bounded(ge=0.0, le=1e5)
BATHYMETRY_VALUES = ("depth", "elevation")
"""``bathymetry_values``: ``depth`` (positive down) or ``elevation`` (positive up, negative in water)."""
#: The sign convention of a bathymetry grid, one of :data:`BATHYMETRY_VALUES`.
BathymetryValues = described(Literal[BATHYMETRY_VALUES], f"one of {list(BATHYMETRY_VALUES)} (depth: metres below "
                             "the sea surface, positive down; elevation: positive up, negative in the water)")
_FINITE = Annotated[float, Field(strict=True, allow_inf_nan=False)]
_LON = Annotated[float, Field(strict=True, allow_inf_nan=False, ge=-180.0, le=180.0)]
_LAT = Annotated[float, Field(strict=True, allow_inf_nan=False, ge=-90.0, le=90.0)]
_DEGREES = "in degrees (|lon| <= 180, |lat| <= 90)"
#: ``[longitude, latitude]``, WGS 84 degrees.
LonLat = described(Annotated[tuple[_LON, _LAT], Field(strict=False)], f"[longitude, latitude] {_DEGREES}")
#: A ring of ``[x, y]`` pairs, local east/north metres.
LocalRing = described(Annotated[list[Annotated[tuple[_FINITE, _FINITE], Field(strict=False)]], Field(min_length=1)],
                      "a list of [x, y] pairs of finite numbers")
#: A ring of ``[longitude, latitude]`` pairs, WGS 84 degrees.
LonLatRing = described(Annotated[list[LonLat], Field(min_length=1)],
                       f"a list of [longitude, latitude] pairs of finite numbers {_DEGREES}")
LocalRings = described(list[LocalRing], "a list of rings, each a list of [x, y] pairs", whole=False)
LonLatRings = described(list[LonLatRing], "a list of rings, each a list of [longitude, latitude] pairs", whole=False)
_RINGS = ("vertices_m", "vertices_lonlat", "holes_m", "holes_lonlat", "navigable_m", "navigable_lonlat")


def too_many_vertices(rings) -> str | None:
    """Why an area of these rings has too many vertices (more than :data:`MAX_VERTICES`), else
    ``None``.

    Parameters
    ----------
    rings : sequence
        Rings (sequences of vertices; anything else counts 0).

    Returns
    -------
    str or None
        The count and the limit, in words.
    """
    count = sum(len(r) if isinstance(r, (list, tuple)) or hasattr(r, "shape") else 0 for r in rings)
    if count > MAX_VERTICES:
        return (f"the area has {count:,} vertices, more than {MAX_VERTICES:,}; simplify its boundary (e.g. "
                "shapely's simplify or QGIS's Simplify)")
    return None


def _rule(message: str, field: str | None = None, **ctx) -> PydanticCustomError:
    return PydanticCustomError("rule", message, {**ctx, **({"field": field} if field else {})})


class Area(Table):
    """``[area]`` of a survey area file (:mod:`sss_locus.experiments.survey_design.area`; a GeoJSON
    area's polygon and properties are read into the same keys): plain values (no provenance but
    the table's own ``source``/``assumption`` text). The polygon's own checks (distinct vertices,
    no crossing, its size, holes inside it, distance from the origin) are the area module's."""

    name: Text | None = None
    source: Text | None = None
    assumption: Text | None = None
    vertices_m: LocalRing | None = None
    vertices_lonlat: LonLatRing | None = None
    origin_lonlat: LonLat | None = None
    holes_m: LocalRings = []
    holes_lonlat: LonLatRings = []
    water_depth_m: WaterDepthM | None = None
    water_beyond_m: WaterBeyondM | None = None
    navigable_m: LocalRing | None = None
    navigable_lonlat: LonLatRing | None = None
    wall_clearance_m: WallClearanceM | None = None
    bathymetry: Text | None = None
    bathymetry_values: BathymetryValues | None = None

    @model_validator(mode="before")
    @classmethod
    def _vertex_count(cls, data: Any):
        if isinstance(data, Mapping):
            rings = [data.get("vertices_m"), data.get("vertices_lonlat"), data.get("navigable_m"),
                     data.get("navigable_lonlat")]
            for key in ("holes_m", "holes_lonlat"):
                rings += data.get(key) if isinstance(data.get(key), list) else []
            why = too_many_vertices(rings)
            if why:
                raise _rule(why)
        return data

    @model_validator(mode="after")
    def _combinations(self):
        given = {k for k in type(self).model_fields if getattr(self, k) not in (None, [])}
        if ("vertices_m" in given) == ("vertices_lonlat" in given):
            raise _rule("needs exactly one of vertices_m or vertices_lonlat; got {got}",
                        got="both" if "vertices_m" in given else "neither")
        if "holes_lonlat" in given and "vertices_lonlat" not in given:
            raise _rule("goes with vertices_lonlat (with vertices_m, give holes_m)", "holes_lonlat")
        water = sorted(given & {"navigable_m", "navigable_lonlat", "water_beyond_m"})
        if len(water) > 1:
            raise _rule("give one of navigable_m, navigable_lonlat or water_beyond_m; got {got}", got=", ".join(water))
        if "navigable_lonlat" in given and "vertices_m" in given and "origin_lonlat" not in given:
            raise _rule("needs the area's origin_lonlat = [longitude, latitude] (to place it in the area's "
                        "local metres)", "navigable_lonlat")
        values = " or ".join(f'"{v}"' for v in BATHYMETRY_VALUES)
        if "bathymetry" in given and "bathymetry_values" not in given:
            raise _rule(f"is missing: a bathymetry grid needs bathymetry_values = {values} (depth: metres below "
                        "the sea surface, positive down; elevation: positive up, negative in the water)",
                        "bathymetry_values")
        if "bathymetry_values" in given and "bathymetry" not in given:
            raise _rule('is missing: bathymetry_values goes with bathymetry = "FILE" (a raster, path relative '
                        "to the area file)", "bathymetry")
        if "bathymetry" in given and "water_depth_m" in given:
            raise _rule("goes without water_depth_m: the depths are the bathymetry grid's", "bathymetry")
        return self


class AreaFile(Table):
    """A survey area TOML file: its ``[area]`` table."""

    area: Area


class Data(Table):
    """A whole data document (shipped files, users' files and overrides merged); every table
    optional here (a loader reading one file names a missing table it needs)."""

    schema_version: int | None = None
    sonars: dict[Key, Sonar] = {}
    platforms: dict[Key, Platform] = {}
    envelopes: dict[Key, Envelope] = {}
    offset_models: OffsetModels | None = None
    noise: dict[Key, NoiseTable] = {}
    terrain: Terrain | None = None
    survey: Survey | None = None
    survey_design: SurveyDesign | None = None

    @model_validator(mode="before")
    @classmethod
    def _sonars_exist(cls, data: Any):
        if isinstance(data, Mapping) and isinstance(data.get("platforms"), Mapping):
            sonars = data.get("sonars") if isinstance(data.get("sonars"), Mapping) else {}
            for key, platform in data["platforms"].items():
                name = platform.get("sonar") if isinstance(platform, Mapping) else None
                if isinstance(name, str) and name not in sonars:
                    raise PydanticCustomError("unknown_sonar", "platforms.{key}.sonar names unknown sonar {name}"
                                              "{hint}; known: {known}",
                                              {"key": key, "name": repr(name), "hint": suggestion(name, sonars),
                                               "known": str(sorted(sonars))})
        return data


def validate_document(doc: Mapping[str, Any], tables: tuple[str, ...] = ()) -> Data:
    """The validated :class:`Data` of a parsed (merged) document.

    Parameters
    ----------
    doc : mapping
        A parsed TOML document (shipped data, users' files and ``--set`` overrides merged).
    tables : tuple of str
        Validate only these top-level tables, each of which must be present (the sonars are
        validated with the platforms that name them); empty: the whole document.

    Returns
    -------
    Data
        The validated document.

    Raises
    ------
    ValueError
        In one line, naming the key path of the first bad entry, its value and the valid range.
    """
    if not isinstance(doc, Mapping):
        raise ValueError(f"a data document must be a table; got {type(doc).__name__}")
    if tables:
        for name in tables:
            if name not in doc:
                raise ValueError(f"missing table {name}")
        wanted = set(tables) | ({"sonars"} if "platforms" in tables else set())
        doc = {k: v for k, v in doc.items() if k in wanted}
    return validated(Data, doc)


def entry(tables: Mapping[str, Any], section: str, key: str) -> Any:
    """The validated ``[<section>.<key>]`` table; an unknown ``key`` is refused naming the keys
    the section has.

    Parameters
    ----------
    tables : mapping
        The validated tables of the section by key (e.g. ``Data.noise``).
    section : str
        The section's name, for the message.
    key : str
        The platform's key.

    Returns
    -------
    Table
        ``tables[key]``.
    """
    if key not in tables:
        raise ValueError(missing_table(section, key, tables))
    return tables[key]


#: The shipped file whose schema each per-platform section follows (for the messages).
SECTION_FILES = {"platforms": "platforms.toml", "sonars": "platforms.toml", "envelopes": "survey.toml",
                 "noise": "noise.toml"}


def missing_table(section: str, key: str, tables: Any) -> str:
    """The one-line message for a platform ``key`` without a ``[<section>.<key>]`` table.

    Parameters
    ----------
    section : str
        The section (``envelopes``, ``noise`` ...).
    key : str
        The platform's key.
    tables : iterable of str
        The keys the section has (shipped data and the active user data).

    Returns
    -------
    str
        Names the missing table, the keys the section has and the file whose schema to follow.
    """
    where = f" (schema of data/{SECTION_FILES[section]})" if section in SECTION_FILES else ""
    return (f"no [{section}.{key}] table in data/ or the --data files: add one to your data file{where}; "
            f"[{section}] has {', '.join(map(repr, sorted(tables))) or 'no tables'}")


def provenance(table: BaseModel, path: str) -> dict[str, str]:
    """Where each sourced value of a table comes from.

    Parameters
    ----------
    table : pydantic.BaseModel
        A validated table.
    path : str
        Its dotted key path (e.g. ``platforms.auv``).

    Returns
    -------
    dict of str to str
        ``{dotted key path: "source: ..." | "assumption: ..."}`` of every sourced value in
        ``table``, at any depth, in declaration order.
    """
    out: dict[str, str] = {}
    for name in type(table).model_fields:
        value = getattr(table, name)
        if isinstance(value, Sourced):
            out[f"{path}.{name}"] = value.note
        elif isinstance(value, BaseModel):
            out.update(provenance(value, f"{path}.{name}"))
    return out


def values(table: BaseModel) -> dict[str, Any]:
    """The sourced values of a flat table.

    Parameters
    ----------
    table : pydantic.BaseModel
        A validated table of sourced values.

    Returns
    -------
    dict of str to Any
        The values by key (absent optional keys left out).
    """
    return {name: getattr(table, name).value for name in type(table).model_fields
            if isinstance(getattr(table, name), Sourced)}
