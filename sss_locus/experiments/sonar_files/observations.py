"""A user's own sightings of seafloor features: a CSV file, validated row by row, into sensor
poses and ranges in a local metric frame (numbers only; the XTF reader is
:mod:`sss_locus.experiments.sonar_files.observations_xtf`).

The CSV file has one row per *sighting* (one feature seen in one ping); units are part of the
column names, and a column whose name has the right quantity but another unit
(``heading_rad``, ``slant_range_ft``) is refused:

``feature``
    the feature's identifier (text). **Data association is the user's**: every row with the same
    identifier is taken to be the same feature, without checking.
``platform``
    the key of the platform (``data/platforms.toml`` or the user's ``--data`` file) whose mounting
    and sonar the ping was taken with; one platform per file.
``side``
    ``port`` or ``starboard``: which transducer saw the feature.
``lon_deg``, ``lat_deg`` *or* ``east_m``, ``north_m``
    the vehicle reference point (WGS 84 longitude/latitude, or metres east/north in a local
    grid). Longitude/latitude go through ``pyproj`` into a local transverse-Mercator frame
    (:class:`LocalFrame`) whose origin is the survey's mean position rounded to 0.001 deg (or
    a given origin).
``depth_m``
    the reference point's depth below the sea surface (>= 0; 0 for a surface vessel).
``altitude_m``
    the reference point's height above the seafloor below it (altimeter or echo sounder; > 0):
    the flat-seafloor baseline places the feature on a horizontal seafloor at this height below.
``heading_deg``
    compass heading, clockwise from (true) north. In the transverse-Mercator frame the heading is
    turned by the meridian convergence at the vehicle (``pyproj``'s ``meridian_convergence``) so
    that it is a grid azimuth; local ``east_m``/``north_m`` files give grid headings directly.
``pitch_deg``, ``roll_deg``
    pitch positive nose up, roll positive starboard down (the XTF convention). A missing column
    or empty cell is refused unless the run says ``missing_attitude="level"`` (then it is taken
    as 0 and the sighting is flagged ``attitude_assumed``): never a silent zero.
``slant_range_m`` *or* ``sample``, ``range_setting_m``, ``n_samples``
    the slant range, or the sample index (0-based, counted from the near end) in a ping of ``n_samples`` samples over
    ``range_setting_m``: ``r = (sample + 1/2) range_setting_m / n_samples`` (the sample's centre,
    an open choice; :func:`slant_range_from_sample`).
``range_sigma_m`` (optional)
    the standard deviation of the range (> 0); default the run's ``range_sigma_m``.
``time_s`` (optional)
    any time stamp in seconds, carried through.
``layback_m`` (optional, >= 0; empty is 0)
    a towed sensor: the position columns are the tow point's (the ship's) and the sensor is
    this far behind it along ``heading_deg``
    (:func:`~sss_locus.experiments.sonar_files.towfish.apply_layback`).

Every cell is checked before any work; the first bad one is refused in one line naming the file,
its line (the header is line 1), its column and the valid range (:func:`read_sightings`).
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.inputs import missing_file

MISSING_ATTITUDE = ("refuse", "level")
SIDES = ("port", "starboard")
#: Numeric columns: (name, lo, hi, lo inclusive).
NUMBERS = {
    "lon_deg": (-180.0, 180.0), "lat_deg": (-85.0, 85.0), "east_m": (-1e7, 1e7), "north_m": (-1e7, 1e7),
    "depth_m": (0.0, 11000.0), "altitude_m": (1e-3, 11000.0), "heading_deg": (-360.0, 360.0),
    "pitch_deg": (-90.0, 90.0), "roll_deg": (-180.0, 180.0), "slant_range_m": (1e-3, 1e5),
    "sample": (0.0, 1e9), "range_setting_m": (1e-3, 1e5), "n_samples": (1.0, 1e9),
    "range_sigma_m": (1e-9, 1e3), "time_s": (-1e12, 1e12), "layback_m": (0.0, 1e4),
}
TEXT = ("feature", "platform", "side")
#: Column names sharing a quantity with a numeric column but in another unit are refused.
_QUANTITIES = {name.rsplit("_", 1)[0]: name for name in NUMBERS if "_" in name}
ATTITUDE = ("pitch_deg", "roll_deg")
#: The columns every reader returns (the sightings table, one row per sighting).
COLUMNS = ("feature", "platform", "side", "east_m", "north_m", "lon_deg", "lat_deg", "depth_m",
           "altitude_m", "heading_deg", "grid_heading_deg", "pitch_deg", "roll_deg", "slant_range_m",
           "range_sigma_m", "time_s", "layback_m", "attitude_assumed", "source", "line")


class ObservationError(ValueError):
    """A malformed observations file; the message is one line naming where."""


def slant_range_from_sample(sample, range_setting_m, n_samples) -> np.ndarray:
    """Slant range (m) of a sample index counted from the near end (sample 0 the first after
    transmission): ``(sample + 1/2) range_setting_m / n_samples``, the centre of the sample's
    range cell (recording assumed to start at transmission). An XTF channel stored far-to-near
    is turned round first (:mod:`~sss_locus.experiments.sonar_files.sample_order`).

    Parameters
    ----------
    sample : array_like
        Sample index from the near end (0 first), any shape.
    range_setting_m : array_like
        The channel's range setting, m (broadcast with ``sample``).
    n_samples : array_like
        Samples per channel (broadcast with ``sample``).

    Returns
    -------
    numpy.ndarray
        Slant range, m, the broadcast shape of the inputs.
    """
    return (np.asarray(sample, float) + 0.5) * np.asarray(range_setting_m, float) / np.asarray(n_samples, float)


@dataclass(frozen=True)
class LocalFrame:
    """A local transverse-Mercator frame (WGS 84, scale 1) centred on ``(lon0_deg, lat0_deg)``:
    ``east_m``, ``north_m`` grid metres from that point (``pyproj``)."""

    lon0_deg: float
    lat0_deg: float

    def __post_init__(self):
        for name, lo, hi in (("lon0_deg", -180.0, 180.0), ("lat0_deg", -85.0, 85.0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and lo <= v <= hi):
                raise ValueError(f"origin {name} must be a finite number in [{lo}, {hi}]; got {v!r}")

    @property
    def proj4(self) -> str:
        return (f"+proj=tmerc +lat_0={self.lat0_deg!r} +lon_0={self.lon0_deg!r} +k=1 +x_0=0 +y_0=0 "
                "+ellps=WGS84 +units=m +no_defs")

    def _proj(self):
        from pyproj import Proj

        return Proj(self.proj4)

    def to_local(self, lon_deg, lat_deg) -> tuple[np.ndarray, np.ndarray]:
        """Longitude/latitude (deg) to grid east/north (m).

        Parameters
        ----------
        lon_deg : array_like
            Longitude, degrees.
        lat_deg : array_like
            Latitude, degrees (same shape).

        Returns
        -------
        east_m, north_m : numpy.ndarray
            Grid east and north from the origin, m, the input shape.
        """
        e, n = self._proj()(np.asarray(lon_deg, float), np.asarray(lat_deg, float))
        return np.asarray(e, float), np.asarray(n, float)

    def to_lonlat(self, east_m, north_m) -> tuple[np.ndarray, np.ndarray]:
        """Grid east/north (m) to longitude/latitude (deg).

        Parameters
        ----------
        east_m : array_like
            Grid east from the origin, m.
        north_m : array_like
            Grid north from the origin, m (same shape).

        Returns
        -------
        lon_deg, lat_deg : numpy.ndarray
            Longitude and latitude, degrees, the input shape.
        """
        lon, lat = self._proj()(np.asarray(east_m, float), np.asarray(north_m, float), inverse=True)
        return np.asarray(lon, float), np.asarray(lat, float)

    def convergence_deg(self, lon_deg, lat_deg) -> np.ndarray:
        """Meridian convergence (deg, ``pyproj``'s ``meridian_convergence``): grid north is this
        far clockwise from true north, so a grid azimuth is a true azimuth minus it.

        Parameters
        ----------
        lon_deg : array_like
            Longitude, degrees.
        lat_deg : array_like
            Latitude, degrees (same shape).

        Returns
        -------
        numpy.ndarray
            Convergence, degrees (0 on the origin's meridian), the input shape.
        """
        f = self._proj().get_factors(np.asarray(lon_deg, float), np.asarray(lat_deg, float))
        return np.asarray(f.meridian_convergence, float)

    def grid_heading_deg(self, heading_deg, lon_deg, lat_deg) -> np.ndarray:
        """True heading (deg clockwise from true north) to grid azimuth (deg clockwise from grid
        north): ``heading - convergence`` (checked against ``pyproj`` geodesics in the tests).

        Parameters
        ----------
        heading_deg : array_like
            True heading, degrees clockwise from true north.
        lon_deg : array_like
            Longitude, degrees.
        lat_deg : array_like
            Latitude, degrees.

        Returns
        -------
        numpy.ndarray
            Grid azimuth, degrees (not wrapped), the broadcast shape.
        """
        return np.asarray(heading_deg, float) - self.convergence_deg(lon_deg, lat_deg)

    def key(self) -> dict:
        """The frame as plain data (its origin), for cache keys and records.

        Returns
        -------
        dict
            ``{"lon0_deg": ..., "lat0_deg": ...}``, degrees.
        """
        return {"lon0_deg": self.lon0_deg, "lat0_deg": self.lat0_deg}


def survey_frame(lon_deg, lat_deg) -> LocalFrame:
    """The default frame: the mean position of the sightings rounded to 0.001 deg, longitudes
    averaged as directions (the circular mean), so a survey across the antimeridian (+-180 deg)
    gets its origin among its sightings, not half the globe away.

    Parameters
    ----------
    lon_deg : array_like
        Longitudes of the sightings, degrees, shape (n,), n >= 1.
    lat_deg : array_like
        Latitudes of the sightings, degrees, shape (n,).

    Returns
    -------
    LocalFrame
        Transverse Mercator frame (local east/north metres) at the rounded mean position;
        longitude 180 is given as -180.
    """
    lam = np.radians(np.asarray(lon_deg, float))
    lon = math.degrees(math.atan2(float(np.mean(np.sin(lam))), float(np.mean(np.cos(lam)))))
    lon = round(lon, 3)
    return LocalFrame(-180.0 if lon == 180.0 else lon, round(float(np.mean(lat_deg)), 3))


#: Farthest a sighting may lie from its frame's origin, metres: the transverse-Mercator frame's
#: scale error grows as (d / 6371 km)^2 / 2 across its meridian, 1.2e-4 (12 cm per km) at 100 km;
#: thousands of km away positions and spreads change by percents.
MAX_FRAME_DISTANCE_M = 100_000.0


def frame_from_origin(origin) -> LocalFrame | None:
    """The frame of a run's ``origin`` parameter (``[lon_deg, lat_deg]``; ``[]``: ``None``),
    refused in one line unless it is two finite numbers in range.

    Parameters
    ----------
    origin : list or tuple or None
        ``[lon_deg, lat_deg]``, degrees; ``[]`` or ``None`` for none.

    Returns
    -------
    LocalFrame or None
        The frame with that origin, or ``None``.

    Raises
    ------
    ValueError
        Not two numbers.
    """
    if origin is None or (isinstance(origin, (list, tuple)) and len(origin) == 0):
        return None
    ok = (isinstance(origin, (list, tuple)) and len(origin) == 2
          and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in origin))
    if not ok:
        raise ValueError(f"origin must be [lon_deg, lat_deg], two numbers (or [] for the sightings' mean); got {origin!r}")
    return LocalFrame(float(origin[0]), float(origin[1]))


def _check_frame_distance(t: pd.DataFrame, frame: LocalFrame) -> None:
    d = np.hypot(t["east_m"].to_numpy(float), t["north_m"].to_numpy(float))
    i = int(np.argmax(d))
    if d[i] > MAX_FRAME_DISTANCE_M:
        raise ObservationError(
            f"{t['source'].iloc[i] if 'source' in t else 'sightings'} line {t['line'].iloc[i] if 'line' in t else i + 2}: the sighting lies {d[i] / 1000:,.0f} km from the local "
            f"frame's origin (lon {frame.lon0_deg:g}, lat {frame.lat0_deg:g}); every sighting must be within "
            f"{MAX_FRAME_DISTANCE_M / 1000:g} km of it (the frame's distortion grows with the distance): give "
            "-p origin near the survey, or split the survey")


def _fail(source, line, column, message):
    raise ObservationError(f"{source} line {line}, column {column}: {message}")


def line_of(raw: pd.DataFrame, i: int) -> int:
    """The file line of data row ``i`` (``raw.attrs["lines"]`` when comments were skipped).

    Parameters
    ----------
    raw : pandas.DataFrame
        The table of text cells (:func:`read_table`).
    i : int
        Data row index, 0-based.

    Returns
    -------
    int
        1-based line in the file (header at line 1 when ``attrs["lines"]`` is absent).
    """
    lines = raw.attrs.get("lines")
    return int(lines[i]) if lines is not None else i + 2


def _numbers(raw: pd.DataFrame, name: str, source: str, *, optional=False) -> np.ndarray:
    """One numeric column, every cell finite and in its range (empty cells NaN if ``optional``)."""
    lo, hi = NUMBERS[name]
    text = raw[name].astype(str).str.strip()
    empty = text == ""
    values = pd.to_numeric(text.where(~empty, "nan"), errors="coerce").to_numpy(float)
    bad = ~(np.isfinite(values) & (values >= lo) & (values <= hi))
    if optional:
        bad &= ~empty
    if name in ("sample", "n_samples"):
        bad |= np.isfinite(values) & (values != np.round(values))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        kind = "an integer" if name in ("sample", "n_samples") else "a finite number"
        _fail(source, line_of(raw, i), name, f"must be {kind} in [{lo:g}, {hi:g}]; got {raw[name].iloc[i]!r}")
    return values


def parse_sightings(raw: pd.DataFrame, source: str, *, missing_attitude: str = "refuse",
                    range_sigma_m: float = 0.1) -> pd.DataFrame:
    """Validate a table of text cells (as read from a CSV file) into the sightings table.

    Returns the columns :data:`COLUMNS` (``east_m``/``north_m`` as given; ``lon_deg``/``lat_deg``
    NaN for local files, and the reverse; the frame is applied by :func:`to_local_frame`).

    Parameters
    ----------
    raw : pandas.DataFrame
        Text cells with the file's header as columns (:func:`read_table`).
    source : str
        The file's name, for the error messages.
    missing_attitude : str
        ``"refuse"`` (roll/pitch must be given) or ``"level"`` (missing attitude taken as 0 deg,
        flagged in ``attitude_assumed``).
    range_sigma_m : float
        Slant-range standard deviation, m (> 0), for rows without ``range_sigma_m``.

    Returns
    -------
    pandas.DataFrame
        One row per sighting, columns :data:`COLUMNS` (slant range in m, angles in degrees).

    Raises
    ------
    ObservationError
        A missing column, a wrong unit, an empty or out-of-range cell, in one line naming the
        file, line and column.
    ValueError
        ``missing_attitude`` or ``range_sigma_m`` invalid.
    """
    if missing_attitude not in MISSING_ATTITUDE:
        raise ValueError(f"missing_attitude must be one of {list(MISSING_ATTITUDE)}; got {missing_attitude!r}")
    if not (isinstance(range_sigma_m, (int, float)) and math.isfinite(range_sigma_m) and range_sigma_m > 0):
        raise ValueError(f"range_sigma_m must be a finite number > 0; got {range_sigma_m!r}")
    cols = [str(c).strip() for c in raw.columns]
    attrs = dict(raw.attrs)
    raw = raw.set_axis(cols, axis=1)
    raw.attrs.update(attrs)
    hdr = attrs.get("header_line", 1)
    for c in cols:
        base = c.rsplit("_", 1)[0]
        if c not in NUMBERS and c not in TEXT and base in _QUANTITIES:
            _fail(source, hdr, c, f"wrong unit: expected {_QUANTITIES[base]!r}")
    if len(raw) == 0:
        raise ObservationError(f"{source}: no sightings (only a header)")

    def need(*names, why=""):
        for name in names:
            if name not in cols:
                _fail(source, hdr, name, f"missing{why}; the header has {cols}")

    need(*TEXT, "depth_m", "altitude_m", "heading_deg")
    geo = "lon_deg" in cols or "lat_deg" in cols
    if geo and ("east_m" in cols or "north_m" in cols):
        _fail(source, hdr, "east_m" if "east_m" in cols else "north_m",
              "give the position once: lon_deg and lat_deg, or east_m and north_m, not both")
    need(*(("lon_deg", "lat_deg") if geo else ("east_m", "north_m")), why=" (a position needs lon_deg and lat_deg, or east_m and north_m)")
    direct = "slant_range_m" in cols
    if not direct:
        need("sample", "range_setting_m", "n_samples", why=" (a range needs slant_range_m, or sample, range_setting_m and n_samples)")
    out = {}
    for name in TEXT:
        text = raw[name].astype(str).str.strip()
        if (text == "").any():
            _fail(source, line_of(raw, int(np.flatnonzero(text == "")[0])), name, "must not be empty")
        out[name] = text.to_numpy()
    bad_side = ~np.isin(out["side"], SIDES)
    if bad_side.any():
        i = int(np.flatnonzero(bad_side)[0])
        _fail(source, line_of(raw, i), "side", f"must be one of {list(SIDES)}; got {out['side'][i]!r}")
    if len(set(out["platform"])) > 1:
        i = int(np.flatnonzero(out["platform"] != out["platform"][0])[0])
        _fail(source, line_of(raw, i), "platform", f"one platform per file; got {out['platform'][i]!r} after {out['platform'][0]!r}")
    for name in ("lon_deg", "lat_deg") if geo else ("east_m", "north_m"):
        out[name] = _numbers(raw, name, source)
    for name in ("depth_m", "altitude_m", "heading_deg"):
        out[name] = _numbers(raw, name, source)
    assumed = np.zeros(len(raw), bool)
    for name in ATTITUDE:
        if name not in cols:
            if missing_attitude == "refuse":
                _fail(source, hdr, name, "missing; give it, or run with missing_attitude='level' to take the vehicle as level")
            out[name] = np.zeros(len(raw))
            assumed[:] = True
            continue
        v = _numbers(raw, name, source, optional=missing_attitude == "level")
        if missing_attitude == "refuse" and np.isnan(v).any():  # unreachable: _numbers refused it
            raise AssertionError
        assumed |= np.isnan(v)
        out[name] = np.where(np.isnan(v), 0.0, v)
    if direct:
        out["slant_range_m"] = _numbers(raw, "slant_range_m", source)
    else:
        s, rs, ns = (_numbers(raw, n, source) for n in ("sample", "range_setting_m", "n_samples"))
        past = s >= ns
        if past.any():
            i = int(np.flatnonzero(past)[0])
            _fail(source, line_of(raw, i), "sample", f"must be in [0, n_samples - 1] = [0, {ns[i] - 1:g}]; got {raw['sample'].iloc[i]!r}")
        out["slant_range_m"] = slant_range_from_sample(s, rs, ns)
    sig = _numbers(raw, "range_sigma_m", source, optional=True) if "range_sigma_m" in cols else np.full(len(raw), np.nan)
    out["range_sigma_m"] = np.where(np.isnan(sig), float(range_sigma_m), sig)
    out["time_s"] = _numbers(raw, "time_s", source, optional=True) if "time_s" in cols else np.full(len(raw), np.nan)
    lb = _numbers(raw, "layback_m", source, optional=True) if "layback_m" in cols else np.zeros(len(raw))
    out["layback_m"] = np.where(np.isnan(lb), 0.0, lb)
    for name in ("east_m", "north_m", "lon_deg", "lat_deg"):
        out.setdefault(name, np.full(len(raw), np.nan))
    out["grid_heading_deg"] = np.full(len(raw), np.nan)
    out["attitude_assumed"] = assumed
    out["source"] = source
    out["line"] = [line_of(raw, i) for i in range(len(raw))]
    return pd.DataFrame({c: out[c] for c in COLUMNS})


def to_local_frame(table: pd.DataFrame, origin: LocalFrame | None = None) -> tuple[pd.DataFrame, LocalFrame | None]:
    """Fill ``east_m``/``north_m``/``grid_heading_deg`` (and ``lon_deg``/``lat_deg`` when an
    ``origin`` is given for a local file) through ``pyproj``; return the table and its frame
    (``None``: a local file without an origin has no longitude/latitude).

    Parameters
    ----------
    table : pandas.DataFrame
        The sightings table (:func:`parse_sightings`).
    origin : LocalFrame or None
        The frame to use; ``None``: :func:`survey_frame` of geographic sightings, none for local ones.

    Returns
    -------
    table : pandas.DataFrame
        A copy with ``east_m``/``north_m`` (local metres), ``grid_heading_deg`` (degrees from
        grid north) and, for a local file with an origin, ``lon_deg``/``lat_deg``.
    frame : LocalFrame or None
        The frame used.

    Raises
    ------
    ObservationError
        Geographic and local positions mixed, or sightings too far from the origin.
    """
    t = table.copy()
    geo = np.isfinite(t["lon_deg"].to_numpy(float))
    if geo.all():
        frame = origin or survey_frame(t["lon_deg"], t["lat_deg"])
        t["east_m"], t["north_m"] = frame.to_local(t["lon_deg"], t["lat_deg"])
        _check_frame_distance(t, frame)
        t["grid_heading_deg"] = frame.grid_heading_deg(t["heading_deg"], t["lon_deg"], t["lat_deg"])
        return t, frame
    if geo.any():
        raise ObservationError("sightings mix longitude/latitude and local metres; use one")
    t["grid_heading_deg"] = t["heading_deg"]
    if origin is not None:
        _check_frame_distance(t, origin)
        t["lon_deg"], t["lat_deg"] = origin.to_lonlat(t["east_m"], t["north_m"])
    return t, origin


#: Longest text cell (a feature identifier, a platform key), characters.
MAX_TEXT_CHARS = 200


def _check_fields(kept: list[tuple[int, str]], source: str) -> None:
    """Refuse a header naming a column twice and rows with more fields than the header (a
    trailing comma shifts every column), naming the line."""
    import csv

    def fields_of(line: int, text: str) -> list[str]:
        if len(text) > 100 * MAX_TEXT_CHARS:
            raise ObservationError(f"{source} line {line}: {len(text):,} characters; a row of sightings needs far fewer "
                                   f"(a value holds at most {MAX_TEXT_CHARS})")
        try:
            return next(csv.reader([text]))
        except (csv.Error, StopIteration) as exc:
            raise ObservationError(f"{source} line {line}: not a CSV row ({exc})") from None

    header = [c.strip() for c in fields_of(*kept[0])]
    seen: dict[str, int] = {}
    for k, name in enumerate(header):
        if name in seen:
            raise ObservationError(f"{source} line {kept[0][0]}: column {name!r} appears twice (columns {seen[name] + 1} "
                                   f"and {k + 1}); keep one")
        seen[name] = k
    for line, text in kept[1:]:
        fields = fields_of(line, text)
        if len(fields) > len(header):
            extra = "a trailing comma?" if all(not f.strip() for f in fields[len(header):]) else "a comma inside a value?"
            raise ObservationError(f"{source} line {line}: {len(fields)} fields but the header (line {kept[0][0]}) "
                                   f"names {len(header)} columns ({extra})")
        long = [f for f in fields if len(f) > MAX_TEXT_CHARS]
        if long:
            column = header[fields.index(long[0])] if fields.index(long[0]) < len(header) else "?"
            raise ObservationError(f"{source} line {line}, column {column}: a value of {len(long[0]):,} characters; "
                                   f"at most {MAX_TEXT_CHARS}")


def read_table(path: Path) -> pd.DataFrame:
    """A CSV file as text cells; comment lines (``# ...``, e.g. the synthetic example's notice)
    and blank lines are skipped, ``attrs["lines"]`` keeps each row's line in the file.

    Parameters
    ----------
    path : pathlib.Path
        The CSV file (UTF-8, optional BOM).

    Returns
    -------
    pandas.DataFrame
        Every cell as a string; ``attrs["lines"]`` (file line per row) and ``attrs["header_line"]``.

    Raises
    ------
    ObservationError
        Not UTF-8, no header, a bad row, or not readable as CSV.
    """
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ObservationError(f"{path.name}: not UTF-8 text (byte {exc.start})") from None
    kept = [(k + 1, ln) for k, ln in enumerate(text.splitlines()) if ln.strip() and not ln.lstrip().startswith("#")]
    if not kept:
        raise ObservationError(f"{path.name}: no header line")
    _check_fields(kept, path.name)
    try:
        raw = pd.read_csv(io.StringIO("\n".join(ln for _, ln in kept)), dtype=str, keep_default_na=False,
                          index_col=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise ObservationError(f"{path.name}: not a readable CSV file: {str(exc).strip().splitlines()[-1]}") from None
    raw.attrs["lines"] = [k for k, _ in kept[1:]]
    raw.attrs["header_line"] = kept[0][0]
    return raw


def read_sightings(path, *, missing_attitude: str = "refuse", range_sigma_m: float = 0.1) -> pd.DataFrame:
    """Read and validate a sightings CSV file (module docstring); an :class:`ObservationError`
    in one line naming the file, line, column and valid range otherwise.

    Parameters
    ----------
    path : str or os.PathLike
        The sightings CSV file.
    missing_attitude : str
        ``"refuse"`` or ``"level"`` (:func:`parse_sightings`).
    range_sigma_m : float
        Default slant-range standard deviation, m.

    Returns
    -------
    pandas.DataFrame
        The sightings table, columns :data:`COLUMNS`, positions not yet in a local frame
        (:func:`to_local_frame`).

    Raises
    ------
    ObservationError
        A missing file or bad content, in one line.
    """
    path = Path(path)
    if not path.is_file():
        raise ObservationError(missing_file(path, "observations file"))
    return parse_sightings(read_table(path), path.name, missing_attitude=missing_attitude,
                           range_sigma_m=range_sigma_m)
