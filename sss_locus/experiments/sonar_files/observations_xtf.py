"""Sightings from sidescan XTF files (read with ``pyxtf``'s structures), and a writer of small
XTF files (the worked example and the tests).

The user supplies the matches, a CSV file with one row per sighting: ``feature``, ``platform``,
``file`` (an XTF file, relative to the matches file's folder), ``ping`` (the ping's
``PingNumber`` as recorded), ``channel`` (0-based, in the order of the ping's channels) and
``sample`` (0-based sample index of the feature's return), and optionally ``range_sigma_m``.
**Data association is the user's.** From each matched ping header:

* position: ``SensorXcoordinate``/``SensorYcoordinate`` as longitude/latitude (deg) when the file
  header's ``NavUnits`` is 3, as east/north metres when it is 0;
* ``SensorDepth`` (m, the reference point's depth), ``SensorPrimaryAltitude`` (m),
  ``SensorHeading``, ``SensorPitch`` (nose up positive), ``SensorRoll`` (starboard down positive),
  degrees; the time of day from the ping's clock (``time_s``);
* the side from the channel's ``TypeOfChannel`` (1 port, 2 starboard) in the file header, and the
  slant range from the sample index, the channel's ``SlantRange`` (the range setting) and
  ``NumSamples`` (:func:`~sss_locus.experiments.sonar_files.observations.slant_range_from_sample`); a channel
  recorded with a ``TimeDelay`` is refused (not supported).

These become the rows of a sightings table and go through the same validation as a CSV file
(:func:`~sss_locus.experiments.sonar_files.observations.parse_sightings`), so CSV and XTF inputs of the
same sightings give the same numbers. Errors are one line naming the matches file's line and
column, or the XTF file and the byte offset of a truncated or malformed packet.
"""

from __future__ import annotations

import ctypes
from pathlib import Path

import numpy as np
import pandas as pd

from sss_locus.experiments.sonar_files import sample_order as so
from sss_locus.experiments.sonar_files import towfish as tf
from sss_locus.experiments.sonar_files.observations import NUMBERS, ObservationError, line_of, parse_sightings
from sss_locus.experiments.sonar_files.xtf_packets import CHANNEL_TYPES, channel_types, read_pings  # noqa: F401  read_pings: the public reader

MATCH_COLUMNS = ("feature", "platform", "file", "ping", "channel", "sample")
_NAV_UNITS = {0: ("east_m", "north_m"), 3: ("lon_deg", "lat_deg")}


_FIELDS = (("SensorXcoordinate", None), ("SensorYcoordinate", None), ("SensorDepth", "depth_m"),
           ("SensorPrimaryAltitude", "altitude_m"), ("SensorHeading", "heading_deg"), ("SensorPitch", "pitch_deg"),
           ("SensorRoll", "roll_deg"), ("Layback", "layback_m"))


def _check_fields(ping, nav_units: int, name: str, where: str) -> None:
    """The matched ping's navigation and attitude fields in range, or one line naming the XTF
    field, the file, the ping and its byte offset."""
    x, y = _NAV_UNITS[nav_units]
    for field, col in _FIELDS:
        col = col or (x if field == "SensorXcoordinate" else y)
        lo, hi = NUMBERS[col]
        v = float(getattr(ping, field))
        if not (np.isfinite(v) and lo <= v <= hi):
            raise ObservationError(f"{where}: {field} of ping {ping.PingNumber} of {name} (packet at byte {ping.offset}) "
                                   f"is {v:g}; it must be in [{lo:g}, {hi:g}]"
                                   + (" (0: no altitude recorded for this ping; match another ping)"
                                      if field == "SensorPrimaryAltitude" and v == 0 else ""))


DETECT_PINGS = 2000
"""At most about this many pings of a channel are read to detect its sample order."""


def channel_order(pings: dict, header, ch: int, choice: str, name: str) -> tuple[str, str]:
    """The sample order of channel ``ch`` of one file (:mod:`~sss_locus.experiments.sonar_files.sample_order`)
    and how it was decided; a file the data cannot decide is refused, saying how to set it.

    Parameters
    ----------
    pings : dict
        Ping number -> ``pyxtf`` ping of one file.
    header : pyxtf.XTFFileHeader
        The file's header (channel types).
    ch : int
        Channel index.
    choice : str
        One of :data:`~sss_locus.experiments.sonar_files.sample_order.CHOICES` (``"detect"`` reads
        the data).
    name : str
        The file's name, for the error message.

    Returns
    -------
    order : str
        ``"near_first"`` or ``"far_first"``.
    how : str
        How it was decided (the choice, or the detection's evidence).

    Raises
    ------
    ObservationError
        ``"detect"`` and the data cannot tell the order.
    """
    kind = channel_types(header)[ch]
    if choice != "detect":
        return so.chosen(choice, kind), f"sample_order {choice!r}"
    n = pd.Series([len(p.data[ch]) for p in pings.values() if len(p.data) > ch]).mode()
    rows = [p for p in pings.values() if len(p.data) > ch and len(p.data[ch]) == n.iloc[0]]
    rows = rows[::max(1, len(rows) // DETECT_PINGS)]  # evenly spread over the file: enough to decide
    data = np.stack([p.data[ch].astype(float) for p in rows])
    rng = np.array([p.ping_chan_headers[ch].SlantRange for p in rows], float)
    alt = np.array([p.SensorPrimaryAltitude for p in rows], float)
    with np.errstate(divide="ignore", invalid="ignore"):
        bottom = np.where((alt > 0) & (rng > 0), alt / rng * data.shape[1], np.nan)
    order, evidence = so.detect(data, bottom)
    if order is None:
        side = CHANNEL_TYPES.get(kind, str(kind))
        raise ObservationError(f"{name}: cannot tell which end of channel {ch} ({side}) is the near end from the data "
                               f"({evidence}); set it: -p sample_order '\"port_far_first\"' (port stored far-to-near) "
                               "or '\"near_first\"' (every channel near-to-far)")
    return order, f"detected: {evidence}"


def read_xtf_sightings(matches_path, *, missing_attitude: str = "refuse", range_sigma_m: float = 0.1,
                       sample_order: str = "detect", towfish: str = "auto") -> pd.DataFrame:
    """Sightings from XTF files and the user's matches (module docstring): the table of
    :func:`~sss_locus.experiments.sonar_files.observations.parse_sightings`, with each sighting's
    ``sample_stored`` (as in the file), ``sample_order`` and how it was decided, and how its
    position was read (``towfish``).

    Parameters
    ----------
    matches_path : str or os.PathLike
        The matches CSV (:data:`MATCH_COLUMNS`), the XTF files beside it.
    missing_attitude : str
        ``"refuse"`` or ``"level"``.
    range_sigma_m : float
        Default slant-range standard deviation, m.
    sample_order : str
        One of :data:`~sss_locus.experiments.sonar_files.sample_order.CHOICES`.
    towfish : str
        One of :data:`~sss_locus.experiments.sonar_files.towfish.CHOICES`.

    Returns
    -------
    pandas.DataFrame
        One row per sighting: the sightings columns (positions as recorded, degrees or metres;
        slant range from the sample, m) plus ``xtf_file``, ``ping``, ``channel``,
        ``sample_stored``, ``sample_order``, ``sample_order_how``, ``xtf_layback_m``,
        ``layback_from``, ``position_read_as``; ``attrs["xtf_truncated"]`` lists the one-line
        warning of each XTF file cut short (only its complete pings were read).

    Raises
    ------
    ObservationError
        A missing file or column, or a cell or packet out of range, naming file, line or byte.
    ValueError
        ``sample_order`` or ``towfish`` unknown.
    """
    if sample_order not in so.CHOICES:
        raise ValueError(f"sample_order must be one of {list(so.CHOICES)}; got {sample_order!r}")
    if towfish not in tf.CHOICES:
        raise ValueError(f"towfish must be one of {list(tf.CHOICES)}; got {towfish!r}")
    matches_path = Path(matches_path)
    if not matches_path.is_file():
        raise ObservationError(f"matches file {matches_path} does not exist")
    from sss_locus.experiments.sonar_files.observations import read_table

    raw = read_table(matches_path)
    src = matches_path.name
    for c in MATCH_COLUMNS:
        if c not in raw.columns:
            raise ObservationError(f"{src} line {raw.attrs.get('header_line', 1)}, column {c}: missing; an XTF matches file needs {list(MATCH_COLUMNS)}")
    files: dict[str, tuple] = {}
    orders: dict[tuple, tuple] = {}
    rows, extra = [], []
    for i in range(len(raw)):
        line = line_of(raw, i)
        name = str(raw["file"].iloc[i]).strip()
        if not name:
            raise ObservationError(f"{src} line {line}, column file: empty; give the XTF file's name (beside {src})")
        if name not in files:
            files[name] = read_pings(matches_path.parent / name)
            units = files[name][0].NavUnits
            if units not in _NAV_UNITS:
                import pyxtf

                raise ObservationError(f"{name} byte {pyxtf.XTFFileHeader.NavUnits.offset}: NavUnits {units} not "
                                       "supported (0 metres or 3 longitude/latitude)")
        header, pings = files[name]
        values = {}
        for col in ("ping", "channel", "sample"):
            text = str(raw[col].iloc[i]).strip()
            if not text.isdigit():
                raise ObservationError(f"{src} line {line}, column {col}: must be an integer >= 0; got {text!r}")
            values[col] = int(text)
        if values["ping"] not in pings:
            known = sorted(pings)
            span = f"its pings run {known[0]} to {known[-1]}" if known else "it has no sonar pings"
            if header.truncation:
                span += f"; {header.truncation.message()}"
            raise ObservationError(f"{src} line {line}, column ping: ping {values['ping']} is not in {name} ({span})")
        ping = pings[values["ping"]]
        ch = values["channel"]
        if ch >= len(ping.ping_chan_headers):
            raise ObservationError(f"{src} line {line}, column channel: must be in [0, {len(ping.ping_chan_headers) - 1}] "
                                   f"for ping {values['ping']} of {name}; got {ch}")
        chan = ping.ping_chan_headers[ch]
        kind = channel_types(header)[ch]
        if kind not in (1, 2):
            raise ObservationError(f"{src} line {line}, column channel: channel {ch} of {name} is not a port or starboard sidescan channel")
        if chan.TimeDelay != 0:
            raise ObservationError(f"{src} line {line}, column channel: channel {ch} of {name} was recorded with a "
                                   f"TimeDelay of {chan.TimeDelay:g} s (not supported: the sample-to-range rule assumes 0)")
        if values["sample"] >= chan.NumSamples:
            raise ObservationError(f"{src} line {line}, column sample: must be in [0, {chan.NumSamples - 1}] for channel "
                                   f"{ch} of ping {values['ping']} of {name}; got {values['sample']}")
        if not chan.SlantRange > 0:
            raise ObservationError(f"{src} line {line}: SlantRange of channel {ch} of ping {values['ping']} of {name} "
                                   f"(packet at byte {ping.offset}) is {chan.SlantRange:g}; it must be > 0")
        _check_fields(ping, header.NavUnits, name, f"{src} line {line}")
        if (name, ch) not in orders:
            orders[name, ch] = channel_order(pings, header, ch, sample_order, name)
        order, how = orders[name, ch]
        layback, lb_source, apart = tf.xtf_layback(ping, header.NavUnits)
        if layback > NUMBERS["layback_m"][1]:  # a CableOut too long (Layback itself is checked above)
            raise ObservationError(f"{src} line {line}: the layback of ping {values['ping']} of {name} (packet at byte "
                                   f"{ping.offset}) from CableOut {ping.CableOut} m is {layback:g} m; it must be in "
                                   f"[0, {NUMBERS['layback_m'][1]:g}]")
        try:
            shift, read_as = tf.towfish_decision(layback, apart, towfish)
        except ValueError as exc:
            raise ObservationError(f"{src} line {line}: ping {values['ping']} of {name}: {exc}") from None
        x, y = _NAV_UNITS[header.NavUnits]
        f = lambda v: repr(float(v))  # noqa: E731  exact: every float32/float64 as its double
        rows.append({
            "feature": raw["feature"].iloc[i], "platform": raw["platform"].iloc[i],
            "side": "port" if kind == 1 else "starboard",
            x: f(ping.SensorXcoordinate), y: f(ping.SensorYcoordinate),
            "depth_m": f(ping.SensorDepth), "altitude_m": f(ping.SensorPrimaryAltitude),
            "heading_deg": f(ping.SensorHeading), "pitch_deg": f(ping.SensorPitch), "roll_deg": f(ping.SensorRoll),
            "sample": str(so.from_near(values["sample"], int(chan.NumSamples), order)),
            "range_setting_m": f(chan.SlantRange), "n_samples": str(chan.NumSamples),
            "range_sigma_m": raw["range_sigma_m"].iloc[i] if "range_sigma_m" in raw.columns else "",
            "time_s": f(ping_time_s(ping)), "layback_m": f(shift),
        })
        extra.append({"xtf_file": name, "ping": values["ping"], "channel": ch, "sample_stored": values["sample"],
                      "sample_order": order, "sample_order_how": how, "xtf_layback_m": layback,
                      "layback_from": lb_source, "position_read_as": read_as})
    table = pd.DataFrame(rows, dtype=object)
    table.attrs.update(raw.attrs)
    out = parse_sightings(table, src, missing_attitude=missing_attitude, range_sigma_m=range_sigma_m)
    out = pd.concat([out, pd.DataFrame(extra, index=out.index)], axis=1)
    out.attrs["xtf_truncated"] = [h.truncation.message() for h, _ in files.values() if h.truncation]
    return out


def ping_time_s(ping) -> float:
    """Seconds since midnight of the ping's clock (hour, minute, second, hundredths).

    Parameters
    ----------
    ping : pyxtf.XTFPingHeader
        The ping.

    Returns
    -------
    float
        Seconds since midnight, in [0, 86400).
    """
    return 3600.0 * ping.Hour + 60.0 * ping.Minute + ping.Second + ping.HSeconds / 100.0


def write_xtf(path, pings: pd.DataFrame, *, nav_units: int = 3, note: str = "", port_order: str = "far_first") -> None:
    """Write a small two-channel (port, starboard) XTF file with ``pyxtf``'s structures.

    ``pings`` has one row per ping: ``ping`` (``PingNumber``), the position (``lon_deg``,
    ``lat_deg`` for ``nav_units`` 3, ``east_m``, ``north_m`` for 0), ``depth_m``,
    ``altitude_m``, ``heading_deg``, ``pitch_deg``, ``roll_deg``, ``time_s`` (seconds of the
    day), ``range_setting_m``, ``n_samples``, optionally ``echo_port``/``echo_starboard`` (a
    sample index counted from the near end, drawn bright; -1 none) and the tow fields
    ``layback_m``, ``cable_out_m``, ``ship_x``, ``ship_y`` (``Layback``, ``CableOut``,
    ``ShipX/Ycoordinate``). Each channel is drawn as a sonar records it: a saturated transmit
    pulse at the near end, a dark water column down to the altitude, then seafloor
    backscatter (seeded by the ping number); the port channel is stored ``port_order``
    (``"far_first"`` as the real file and ``pyxtf``'s convention, or ``"near_first"``), the
    starboard one near-first. Angles, depth and altitude are stored as float32 (as XTF does),
    positions as float64.

    Parameters
    ----------
    path : str or os.PathLike
        The file written (overwritten).
    pings : pandas.DataFrame
        One row per ping (columns above).
    nav_units : int
        XTF ``NavUnits``: 3 longitude/latitude (degrees), 0 metres.
    note : str
        The header's note (ASCII, at most 63 characters kept).
    port_order : str
        ``"far_first"`` or ``"near_first"``: how the port channel is stored.
    """
    import pyxtf

    header = pyxtf.XTFFileHeader()
    header.SonarName = b"sss-locus"
    header.NoteString = note.encode("ascii", "replace")[:63]
    header.NavUnits = int(nav_units)
    header.NumberOfSonarChannels = 2
    for k, kind in enumerate((1, 2)):
        header.ChanInfo[k].TypeOfChannel = kind
        header.ChanInfo[k].BytesPerSample = 2
        header.ChanInfo[k].SampleFormat = 3  # uint16
    x, y = _NAV_UNITS[int(nav_units)]
    out = [bytes(header)]
    for _, p in pings.iterrows():
        ping = pyxtf.XTFPingHeader()
        ping.PingNumber = int(p["ping"])
        ping.NumChansToFollow = 2
        t = float(p["time_s"])
        ping.Hour, ping.Minute = int(t // 3600), int(t % 3600 // 60)
        ping.Second, ping.HSeconds = int(t % 60), int(round((t % 1) * 100)) % 100
        ping.SensorXcoordinate, ping.SensorYcoordinate = float(p[x]), float(p[y])
        ping.ShipXcoordinate, ping.ShipYcoordinate = float(p.get("ship_x", 0.0)), float(p.get("ship_y", 0.0))
        ping.Layback, ping.CableOut = float(p.get("layback_m", 0.0)), int(p.get("cable_out_m", 0))
        ping.SensorDepth, ping.SensorPrimaryAltitude = float(p["depth_m"]), float(p["altitude_m"])
        ping.SensorHeading, ping.SensorPitch, ping.SensorRoll = (float(p[c]) for c in ("heading_deg", "pitch_deg", "roll_deg"))
        n = int(p["n_samples"])
        rng = np.random.default_rng(int(p["ping"]))
        bottom = int(np.clip(float(p["altitude_m"]) / float(p["range_setting_m"]) * n, 0, n))
        ping.ping_chan_headers, ping.data = [], []
        for k, side in enumerate(("port", "starboard")):
            chan = pyxtf.XTFPingChanHeader()
            chan.ChannelNumber, chan.SlantRange, chan.NumSamples = k, float(p["range_setting_m"]), n
            near = rng.integers(60, 140, n).astype(np.uint16)  # water column
            near[bottom:] = rng.integers(3000, 9000, n - bottom)  # seafloor
            near[:max(4, n // 128) + 1] = 65535  # transmit pulse
            echo = int(p.get(f"echo_{side}", -1))
            if 0 <= echo < n:
                near[max(echo - 1, 0):echo + 2] = 60000
            ping.ping_chan_headers.append(chan)
            ping.data.append(near[::-1].copy() if side == "port" and port_order == "far_first" else near)
        ping.NumBytesThisRecord = ctypes.sizeof(pyxtf.XTFPingHeader) + 2 * (ctypes.sizeof(pyxtf.XTFPingChanHeader) + 2 * n)
        out.append(ping.to_bytes())
    Path(path).write_bytes(b"".join(out))


def read_observations(path, **kw) -> pd.DataFrame:
    """A sightings CSV file, or an XTF matches file (a CSV with ``file`` and ``ping`` columns):
    the validated sightings table either way (keywords as :func:`read_xtf_sightings`).

    Parameters
    ----------
    path : str or os.PathLike
        A sightings CSV or an XTF matches CSV.
    **kw
        Keywords of :func:`read_xtf_sightings` (``sample_order`` and ``towfish`` are dropped for a
        sightings CSV).

    Returns
    -------
    pandas.DataFrame
        The validated sightings table.

    Raises
    ------
    ObservationError
        A missing file, an XTF file given directly, or bad content.
    """
    from sss_locus.experiments.sonar_files.observations import read_sightings, read_table

    path = Path(path)
    if not path.is_file():
        raise ObservationError(f"observations file {path} does not exist")
    if path.suffix.lower() == ".xtf":
        raise ObservationError(f"{path.name}: give the matches CSV (feature, platform, file, ping, channel, "
                               "sample) that names the XTF file's pings, not the XTF file itself")
    cols = set(read_table(path).columns.str.strip())
    if {"file", "ping"} <= cols:
        return read_xtf_sightings(path, **kw)
    return read_sightings(path, **{k: v for k, v in kw.items() if k not in ("sample_order", "towfish")})


def observation_warnings(path) -> list[str]:
    """The one-line warnings of the XTF files an observations file names that are cut short
    (:func:`~sss_locus.experiments.sonar_files.xtf_packets.truncation_note`): only their complete
    pings are read. ``[]`` for a sightings CSV or whole files; a file that cannot be read is left to
    the reader's one-line error.

    Parameters
    ----------
    path : str or os.PathLike
        The observations file.

    Returns
    -------
    list of str
        One warning per truncated XTF file, in the order the matches file names them.
    """
    from sss_locus.experiments.sonar_files.xtf_packets import truncation_note

    out = []
    for f in observation_files(path)[1:]:
        try:
            note = truncation_note(f)
        except ObservationError:
            continue
        out += [note] if note else []
    return out


def observation_files(path) -> list[Path]:
    """The files an observations file stands for: itself and, for an XTF matches file, the XTF
    files it names that exist (in order; a missing or unreadable file is left to the reader's
    one-line error). ``[]`` when ``path`` is not a file.

    Parameters
    ----------
    path : str or os.PathLike
        The observations file.

    Returns
    -------
    list of pathlib.Path
        ``path`` first, then the existing XTF files it names (each once).
    """
    from sss_locus.experiments.sonar_files.observations import read_table

    path = Path(path)
    if not path.is_file():
        return []
    out = [path]
    try:
        raw = read_table(path)
    except ObservationError:
        return out
    if "file" in raw.columns:
        for name in dict.fromkeys(raw["file"].astype(str).str.strip()):
            if (path.parent / name).is_file():
                out.append(path.parent / name)
    return out
