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
  ``NumSamples`` (:func:`~sss_locus.experiments.observations.slant_range_from_sample`); a channel
  recorded with a ``TimeDelay`` is refused (not supported).

These become the rows of a sightings table and go through the same validation as a CSV file
(:func:`~sss_locus.experiments.observations.parse_sightings`), so CSV and XTF inputs of the
same sightings give the same numbers. Errors are one line naming the matches file's line and
column, or the XTF file and the byte offset of a truncated or malformed packet.
"""

from __future__ import annotations

import ctypes
import io
from pathlib import Path

import numpy as np
import pandas as pd

from .observations import ObservationError, line_of, parse_sightings

MATCH_COLUMNS = ("feature", "platform", "file", "ping", "channel", "sample")
_SONAR = 0  # XTFHeaderType.sonar
_NAV_UNITS = {0: ("east_m", "north_m"), 3: ("lon_deg", "lat_deg")}


def read_pings(path) -> tuple[object, dict[int, object]]:
    """The file header and the sonar pings by ``PingNumber`` of one XTF file (``pyxtf``
    structures); a truncated or malformed packet is refused naming its byte offset."""
    import pyxtf

    path = Path(path)
    if not path.is_file():
        raise ObservationError(f"XTF file {path} does not exist")
    data = path.read_bytes()
    size_header = ctypes.sizeof(pyxtf.XTFFileHeader)
    if len(data) < size_header:
        raise ObservationError(f"{path.name}: truncated at byte {len(data)}: the file header needs {size_header} bytes")
    header = pyxtf.XTFFileHeader.create_from_buffer(data[:size_header])
    if header.FileFormat != 0x7B:
        raise ObservationError(f"{path.name} byte 0: not an XTF file (format byte {header.FileFormat:#x}, expected 0x7b)")
    if header.NavUnits not in _NAV_UNITS:
        raise ObservationError(f"{path.name} byte 0: NavUnits {header.NavUnits} not supported (0 metres or 3 lon/lat)")
    pings: dict[int, object] = {}
    start_size = ctypes.sizeof(pyxtf.XTFPacketStart)
    pos = size_header
    while pos < len(data):
        if pos + start_size > len(data):
            raise ObservationError(f"{path.name}: truncated at byte {len(data)}: packet at byte {pos} has no complete header")
        start = pyxtf.XTFPacketStart.from_buffer_copy(data[pos:pos + start_size])
        if start.MagicNumber != 0xFACE:
            raise ObservationError(f"{path.name} byte {pos}: not an XTF packet (no 0xFACE)")
        end = pos + start.NumBytesThisRecord
        if start.NumBytesThisRecord < start_size or end > len(data):
            raise ObservationError(f"{path.name}: truncated at byte {len(data)}: the packet at byte {pos} "
                                   f"needs {start.NumBytesThisRecord} bytes")
        if start.HeaderType == _SONAR:
            try:
                ping = pyxtf.XTFPingHeader.create_from_buffer(io.BytesIO(data[pos:end]), file_header=header)
            except RuntimeError as exc:
                raise ObservationError(f"{path.name} byte {pos}: malformed sonar packet ({exc})") from None
            pings[int(ping.PingNumber)] = ping
        pos = end
    return header, pings


def read_xtf_sightings(matches_path, *, missing_attitude: str = "refuse",
                       range_sigma_m: float = 0.1) -> pd.DataFrame:
    """Sightings from XTF files and the user's matches (module docstring): the table of
    :func:`~sss_locus.experiments.observations.parse_sightings`."""
    matches_path = Path(matches_path)
    if not matches_path.is_file():
        raise ObservationError(f"matches file {matches_path} does not exist")
    from .observations import read_table

    raw = read_table(matches_path)
    src = matches_path.name
    for c in MATCH_COLUMNS:
        if c not in raw.columns:
            raise ObservationError(f"{src} line {raw.attrs.get('header_line', 1)}, column {c}: missing; an XTF matches file needs {list(MATCH_COLUMNS)}")
    files: dict[str, tuple] = {}
    rows = []
    for i in range(len(raw)):
        line = line_of(raw, i)
        name = str(raw["file"].iloc[i]).strip()
        if name not in files:
            files[name] = read_pings(matches_path.parent / name)
        header, pings = files[name]
        values = {}
        for col in ("ping", "channel"):
            text = str(raw[col].iloc[i]).strip()
            if not text.isdigit():
                raise ObservationError(f"{src} line {line}, column {col}: must be an integer >= 0; got {text!r}")
            values[col] = int(text)
        if values["ping"] not in pings:
            known = sorted(pings)
            span = f"its pings run {known[0]} to {known[-1]}" if known else "it has no sonar pings"
            raise ObservationError(f"{src} line {line}, column ping: ping {values['ping']} is not in {name} ({span})")
        ping = pings[values["ping"]]
        ch = values["channel"]
        if ch >= len(ping.ping_chan_headers):
            raise ObservationError(f"{src} line {line}, column channel: must be in [0, {len(ping.ping_chan_headers) - 1}] "
                                   f"for ping {values['ping']} of {name}; got {ch}")
        chan = ping.ping_chan_headers[ch]
        kind = header.sonar_info[ch].TypeOfChannel if ch < len(header.sonar_info) else -1
        if kind not in (1, 2):
            raise ObservationError(f"{src} line {line}, column channel: channel {ch} of {name} is not a port or starboard sidescan channel")
        if chan.TimeDelay != 0:
            raise ObservationError(f"{src} line {line}, column channel: channel {ch} of {name} was recorded with a "
                                   f"TimeDelay of {chan.TimeDelay:g} s (not supported: the sample-to-range rule assumes 0)")
        x, y = _NAV_UNITS[header.NavUnits]
        f = lambda v: repr(float(v))  # noqa: E731  exact: every float32/float64 as its double
        rows.append({
            "feature": raw["feature"].iloc[i], "platform": raw["platform"].iloc[i],
            "side": "port" if kind == 1 else "starboard",
            x: f(ping.SensorXcoordinate), y: f(ping.SensorYcoordinate),
            "depth_m": f(ping.SensorDepth), "altitude_m": f(ping.SensorPrimaryAltitude),
            "heading_deg": f(ping.SensorHeading), "pitch_deg": f(ping.SensorPitch), "roll_deg": f(ping.SensorRoll),
            "sample": raw["sample"].iloc[i], "range_setting_m": f(chan.SlantRange), "n_samples": str(chan.NumSamples),
            "range_sigma_m": raw["range_sigma_m"].iloc[i] if "range_sigma_m" in raw.columns else "",
            "time_s": f(ping_time_s(ping)),
        })
    table = pd.DataFrame(rows, dtype=object)
    table.attrs.update(raw.attrs)
    return parse_sightings(table, src, missing_attitude=missing_attitude, range_sigma_m=range_sigma_m)


def ping_time_s(ping) -> float:
    """Seconds since midnight of the ping's clock (hour, minute, second, hundredths)."""
    return 3600.0 * ping.Hour + 60.0 * ping.Minute + ping.Second + ping.HSeconds / 100.0


def write_xtf(path, pings: pd.DataFrame, *, nav_units: int = 3, note: str = "") -> None:
    """Write a small two-channel (port, starboard) XTF file with ``pyxtf``'s structures.

    ``pings`` has one row per ping: ``ping`` (``PingNumber``), the position (``lon_deg``,
    ``lat_deg`` for ``nav_units`` 3, ``east_m``, ``north_m`` for 0), ``depth_m``,
    ``altitude_m``, ``heading_deg``, ``pitch_deg``, ``roll_deg``, ``time_s`` (seconds of the
    day), ``range_setting_m``, ``n_samples`` and optionally ``echo_port``/``echo_starboard``
    (a sample index drawn bright; -1 none). Angles, depth and altitude are stored as float32
    (as XTF does), positions as float64.
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
        ping.SensorDepth, ping.SensorPrimaryAltitude = float(p["depth_m"]), float(p["altitude_m"])
        ping.SensorHeading, ping.SensorPitch, ping.SensorRoll = (float(p[c]) for c in ("heading_deg", "pitch_deg", "roll_deg"))
        n = int(p["n_samples"])
        ping.ping_chan_headers, ping.data = [], []
        for k, side in enumerate(("port", "starboard")):
            chan = pyxtf.XTFPingChanHeader()
            chan.ChannelNumber, chan.SlantRange, chan.NumSamples = k, float(p["range_setting_m"]), n
            samples = np.full(n, 200, np.uint16)
            echo = int(p.get(f"echo_{side}", -1))
            if 0 <= echo < n:
                samples[max(echo - 1, 0):echo + 2] = 60000
            ping.ping_chan_headers.append(chan)
            ping.data.append(samples)
        ping.NumBytesThisRecord = ctypes.sizeof(pyxtf.XTFPingHeader) + 2 * (ctypes.sizeof(pyxtf.XTFPingChanHeader) + 2 * n)
        out.append(ping.to_bytes())
    Path(path).write_bytes(b"".join(out))


def read_observations(path, **kw) -> pd.DataFrame:
    """A sightings CSV file, or an XTF matches file (a CSV with ``file`` and ``ping`` columns):
    the validated sightings table either way (keywords as :func:`read_xtf_sightings`)."""
    from .observations import read_sightings, read_table

    path = Path(path)
    if not path.is_file():
        raise ObservationError(f"observations file {path} does not exist")
    if path.suffix.lower() == ".xtf":
        raise ObservationError(f"{path.name}: give the matches CSV (feature, platform, file, ping, channel, "
                               "sample) that names the XTF file's pings, not the XTF file itself")
    cols = set(read_table(path).columns.str.strip())
    return read_xtf_sightings(path, **kw) if {"file", "ping"} <= cols else read_sightings(path, **kw)


def observation_files(path) -> list[Path]:
    """The files an observations file stands for: itself and, for an XTF matches file, the XTF
    files it names that exist (in order; a missing or unreadable file is left to the reader's
    one-line error). ``[]`` when ``path`` is not a file."""
    from .observations import read_table

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
