"""The bytes of an XTF file, read strictly: every header and sonar packet checked before it is
used, anything malformed refused in one line naming the file and the byte offset (numbers only).

The structures are ``pyxtf``'s (``XTFFileHeader``, ``XTFPacketStart``, ``XTFPingHeader``,
``XTFPingChanHeader``, its sample formats); the packets are walked here, not by
``pyxtf.xtf_read``, because ``pyxtf`` trusts the bytes (a channel type it does not know or a
ping with more channels than the file header declares raise ``IndexError`` from inside it, a
record shorter than its header "Buffer size too small" without a file or offset).

The layout (Triton's XTF format description, ``XTF.H``): a 1024-byte file header with six
``CHANINFO`` structures of 128 bytes from byte 256 (the sonar channels' first, in the order of
the channels of a ping; more than six channels are refused, as ``pyxtf`` does), then packets,
each starting with ``0xFACE`` and its length (``NumBytesThisRecord``). A sonar packet
(``HeaderType`` 0) is a 256-byte ping header and, per channel (``NumChansToFollow``), a 64-byte
channel header and ``NumSamples`` samples of the channel's ``BytesPerSample`` (``SampleFormat``
where set). Other packets are skipped. A ``PingNumber`` repeated in one file is refused (a
reader keyed by it would silently keep only one of the pings).
"""

from __future__ import annotations

import ctypes
from pathlib import Path

import numpy as np

from sss_locus.experiments.datamodel.inputs import missing_file
from sss_locus.experiments.sonar_files.observations import ObservationError

_SONAR = 0  # XTFHeaderType.sonar
CHANNEL_TYPES = {0: "subbottom", 1: "port", 2: "starboard", 3: "bathymetry"}
_CHANINFO_AT = 256  # byte of ChanInfo[0] in the file header
_CHANINFO_SIZE = 128
_MAX_CHANNELS = 6


def _structures():
    import pyxtf
    from pyxtf import xtf_ctypes

    return pyxtf, xtf_ctypes


def _dtype(info, where: str):
    """The numpy dtype of a channel's samples (``SampleFormat`` where set, else ``BytesPerSample``)."""
    _, xc = _structures()
    by_size = xc.xtf_dtype.get(int(info.BytesPerSample))
    if by_size is None:
        raise ObservationError(f"{where}: BytesPerSample {info.BytesPerSample} (must be 1, 2, 4 or 8)")
    fmt = xc.sample_format_dtype.get(int(info.SampleFormat))
    if fmt is not None and np.dtype(fmt).itemsize != info.BytesPerSample:
        raise ObservationError(f"{where}: SampleFormat {info.SampleFormat} ({np.dtype(fmt).name}) does not fit "
                               f"BytesPerSample {info.BytesPerSample}")
    return np.dtype(fmt or by_size).newbyteorder("<")


def read_header(path: Path, data: bytes):
    """The checked file header of ``data`` (the bytes of ``path``) and its sonar channels'
    ``(TypeOfChannel, dtype)``.

    Parameters
    ----------
    path : pathlib.Path
        The file (named in the errors).
    data : bytes
        Its content.

    Returns
    -------
    header : pyxtf.XTFFileHeader
        The file header.
    channels : list of tuple
        ``(TypeOfChannel, numpy dtype)`` per sonar channel.

    Raises
    ------
    ObservationError
        Truncated, not XTF, too many channels or an unknown channel type, naming the byte.
    """
    pyxtf, _ = _structures()
    size = ctypes.sizeof(pyxtf.XTFFileHeader)
    if len(data) < size:
        raise ObservationError(f"{path.name}: truncated at byte {len(data)}: the file header needs {size} bytes")
    header = pyxtf.XTFFileHeader.from_buffer_copy(data[:size])
    if header.FileFormat != 0x7B:
        raise ObservationError(f"{path.name} byte 0: not an XTF file (format byte {header.FileFormat:#x}, expected 0x7b)")
    n = int(header.NumberOfSonarChannels)
    total = sum(int(getattr(header, f)) for f in ("NumberOfSonarChannels", "NumberOfBathymetryChannels",
                                                   "NumberOfSnippetChannels", "NumberOfForwardLookArrays",
                                                   "NumberOfEchoStrengthChannels", "NumberOfInterferometryChannels"))
    if total > _MAX_CHANNELS or n > _MAX_CHANNELS:
        at = pyxtf.XTFFileHeader.NumberOfSonarChannels.offset  # the channel counts follow it
        raise ObservationError(f"{path.name} byte {at}: the file header declares {total} channels ({n} sonar); "
                               f"at most {_MAX_CHANNELS} are supported")
    channels = []
    for k in range(n):
        at = _CHANINFO_AT + _CHANINFO_SIZE * k
        info = header.ChanInfo[k]
        if info.TypeOfChannel not in CHANNEL_TYPES:
            raise ObservationError(f"{path.name} byte {at}: sonar channel {k} has TypeOfChannel {info.TypeOfChannel} "
                                   f"(must be one of {sorted(CHANNEL_TYPES)}: {', '.join(CHANNEL_TYPES.values())})")
        channels.append((int(info.TypeOfChannel), _dtype(info, f"{path.name} byte {at}: sonar channel {k}")))
    return header, channels


def _sonar_packet(path: Path, data: bytes, pos: int, end: int, header, channels):
    """One sonar packet (bytes ``pos:end``) as ``pyxtf``'s ping header with ``ping_chan_headers``
    and ``data`` (one array per channel) and ``offset`` (its byte in the file)."""
    pyxtf, _ = _structures()
    hsize, csize = ctypes.sizeof(pyxtf.XTFPingHeader), ctypes.sizeof(pyxtf.XTFPingChanHeader)
    if end - pos < hsize:
        raise ObservationError(f"{path.name} byte {pos}: sonar packet of {end - pos} bytes (NumBytesThisRecord), "
                               f"shorter than its {hsize}-byte ping header")
    ping = pyxtf.XTFPingHeader.from_buffer_copy(data[pos:pos + hsize])
    if not 1 <= ping.NumChansToFollow <= len(channels):
        raise ObservationError(f"{path.name} byte {pos}: ping {ping.PingNumber} has NumChansToFollow "
                               f"{ping.NumChansToFollow}; the file header declares {len(channels)} sonar channel(s)")
    ping.ping_chan_headers, ping.data, ping.offset = [], [], pos
    at = pos + hsize
    for k in range(ping.NumChansToFollow):
        if at + csize > end:
            raise ObservationError(f"{path.name} byte {at}: ping {ping.PingNumber}'s channel {k} header runs past the "
                                   f"end of its packet (byte {end})")
        chan = pyxtf.XTFPingChanHeader.from_buffer_copy(data[at:at + csize])
        n = int(chan.NumSamples) or int(header.ChanInfo[k].Reserved)  # as pyxtf: the old field when 0
        dtype = channels[k][1]
        stop = at + csize + n * dtype.itemsize
        if stop > end:
            raise ObservationError(f"{path.name} byte {at}: ping {ping.PingNumber}'s channel {k} has {n} samples of "
                                   f"{dtype.itemsize} bytes, past the end of its packet (byte {end})")
        if not (np.isfinite(chan.SlantRange) and chan.SlantRange >= 0 and np.isfinite(chan.TimeDelay)):
            raise ObservationError(f"{path.name} byte {at}: ping {ping.PingNumber}'s channel {k} has SlantRange "
                                   f"{chan.SlantRange!r}, TimeDelay {chan.TimeDelay!r} (must be finite, range >= 0)")
        chan.NumSamples = n
        ping.ping_chan_headers.append(chan)
        ping.data.append(np.frombuffer(data, dtype, n, at + csize))
        at = stop
    return ping


def read_pings(path) -> tuple[object, dict[int, object]]:
    """The file header and the sonar pings by ``PingNumber`` of one XTF file (``pyxtf``
    structures; each ping with ``ping_chan_headers``, ``data`` and its byte ``offset``), in file
    order. Anything malformed is refused (:class:`ObservationError`) naming the file and byte.

    Parameters
    ----------
    path : str or os.PathLike
        The XTF file.

    Returns
    -------
    header : pyxtf.XTFFileHeader
        The file header.
    pings : dict
        ``PingNumber`` -> ping, in file order (empty for a file without sonar pings).

    Raises
    ------
    ObservationError
        A missing file or a malformed packet, naming the byte.
    """
    pyxtf, _ = _structures()
    problem = missing_file(path, "XTF file")  # empty path, directory, device, FIFO, missing
    if problem:
        raise ObservationError(problem)
    path = Path(path)
    data = path.read_bytes()
    header, channels = read_header(path, data)
    pings: dict[int, object] = {}
    start_size = ctypes.sizeof(pyxtf.XTFPacketStart)
    pos = ctypes.sizeof(pyxtf.XTFFileHeader)
    while pos < len(data):
        if pos + start_size > len(data):
            raise ObservationError(f"{path.name}: truncated at byte {len(data)}: packet at byte {pos} has no complete header")
        start = pyxtf.XTFPacketStart.from_buffer_copy(data[pos:pos + start_size])
        if start.MagicNumber != 0xFACE:
            raise ObservationError(f"{path.name} byte {pos}: not an XTF packet (no 0xFACE)")
        end = pos + start.NumBytesThisRecord
        if start.NumBytesThisRecord < start_size:
            raise ObservationError(f"{path.name} byte {pos}: packet of {start.NumBytesThisRecord} bytes "
                                   f"(NumBytesThisRecord), shorter than its {start_size}-byte packet start")
        if end > len(data):
            raise ObservationError(f"{path.name}: truncated at byte {len(data)}: the packet at byte {pos} "
                                   f"needs {start.NumBytesThisRecord} bytes")
        if start.HeaderType == _SONAR:
            try:
                ping = _sonar_packet(path, data, pos, end, header, channels)
            except (ValueError, RuntimeError, IndexError, KeyError, TypeError, OverflowError) as exc:
                if isinstance(exc, ObservationError):
                    raise
                raise ObservationError(f"{path.name} byte {pos}: malformed sonar packet ({exc})") from None
            number = int(ping.PingNumber)
            if number in pings:
                raise ObservationError(f"{path.name}: PingNumber {number} is repeated (the pings at byte "
                                       f"{pings[number].offset} and byte {pos}); a ping must be named by one number")
            pings[number] = ping
        pos = end
    return header, pings


def channel_types(header) -> list[int]:
    """``TypeOfChannel`` of each sonar channel, in the order of a ping's channels.

    Parameters
    ----------
    header : pyxtf.XTFFileHeader
        The file header.

    Returns
    -------
    list of int
        ``TypeOfChannel`` per sonar channel (1 port, 2 starboard, ...).
    """
    return [int(header.ChanInfo[k].TypeOfChannel) for k in range(int(header.NumberOfSonarChannels))]
