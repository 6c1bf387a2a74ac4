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

A recording cut short (logging stopped, a full disk) ends inside its last packet: when that
packet starts as a packet does (``0xFACE``, a length at least its packet start, a sonar ping
header and channel headers that agree with the file header as far as they go) and only its end
is missing, the complete pings before it are read and the file header's ``truncation`` says
what was lost (:class:`Truncation`, one line). A corrupt packet in the middle, a bad magic
number, or a file with no complete ping are still refused.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass
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


def _check_channel_count(path: Path, pos: int, ping, channels) -> None:
    """A ping's ``NumChansToFollow`` within the file header's sonar channels, or one line."""
    if not 1 <= ping.NumChansToFollow <= len(channels):
        raise ObservationError(f"{path.name} byte {pos}: ping {ping.PingNumber} has NumChansToFollow "
                               f"{ping.NumChansToFollow}; the file header declares {len(channels)} sonar channel(s)")


def _check_length(path: Path, pos: int, start, start_size: int) -> None:
    """A packet's ``NumBytesThisRecord`` at least its packet start, or one line."""
    if start.NumBytesThisRecord < start_size:
        raise ObservationError(f"{path.name} byte {pos}: packet of {start.NumBytesThisRecord} bytes "
                               f"(NumBytesThisRecord), shorter than its {start_size}-byte packet start")


def _sonar_packet(path: Path, data: bytes, pos: int, end: int, header, channels):
    """One sonar packet (bytes ``pos:end``) as ``pyxtf``'s ping header with ``ping_chan_headers``
    and ``data`` (one array per channel) and ``offset`` (its byte in the file)."""
    pyxtf, _ = _structures()
    hsize, csize = ctypes.sizeof(pyxtf.XTFPingHeader), ctypes.sizeof(pyxtf.XTFPingChanHeader)
    if end - pos < hsize:
        raise ObservationError(f"{path.name} byte {pos}: sonar packet of {end - pos} bytes (NumBytesThisRecord), "
                               f"shorter than its {hsize}-byte ping header")
    ping = pyxtf.XTFPingHeader.from_buffer_copy(data[pos:pos + hsize])
    _check_channel_count(path, pos, ping, channels)
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


@dataclass(frozen=True)
class Truncation:
    """A file that ends inside its last packet: ``file`` (name), ``offset`` (byte where the
    incomplete packet starts), ``missing_bytes`` (bytes it lacks; a lower bound when its
    length field itself is cut, ``length_known`` False), ``n_pings`` (complete pings read)."""

    file: str
    offset: int
    missing_bytes: int
    length_known: bool
    n_pings: int

    def message(self) -> str:
        """The one-line warning (file, byte offset, bytes missing, pings read).

        Returns
        -------
        str
            One line, starting with the file's name.
        """
        missing = f"{self.missing_bytes}" if self.length_known else f"at least {self.missing_bytes}"
        return (f"{self.file} is truncated: the packet at byte {self.offset} is incomplete ({missing} bytes "
                f"missing); read the {self.n_pings} complete pings before it, the rest of the recording is lost")


def _cut_packet(path: Path, data: bytes, pos: int, header, channels) -> tuple[int, bool]:
    """The bytes missing from the packet at ``pos`` that runs past the end of ``data``, and
    whether its length is known; a packet that does not start as one is refused (one line)."""
    pyxtf, _ = _structures()
    have, start_size = len(data) - pos, ctypes.sizeof(pyxtf.XTFPacketStart)
    if have >= 2 and int.from_bytes(data[pos:pos + 2], "little") != 0xFACE:
        raise ObservationError(f"{path.name} byte {pos}: not an XTF packet (no 0xFACE)")
    if have < start_size:
        return start_size - have, False
    start = pyxtf.XTFPacketStart.from_buffer_copy(data[pos:pos + start_size])
    _check_length(path, pos, start, start_size)
    hsize, csize = ctypes.sizeof(pyxtf.XTFPingHeader), ctypes.sizeof(pyxtf.XTFPingChanHeader)
    if start.HeaderType == _SONAR and have >= hsize:  # what is there must agree with the file header
        ping = pyxtf.XTFPingHeader.from_buffer_copy(data[pos:pos + hsize])
        _check_channel_count(path, pos, ping, channels)
        at, end = pos + hsize, pos + start.NumBytesThisRecord
        for k in range(ping.NumChansToFollow):
            if at + csize > len(data):
                break
            chan = pyxtf.XTFPingChanHeader.from_buffer_copy(data[at:at + csize])
            at += csize + (int(chan.NumSamples) or int(header.ChanInfo[k].Reserved)) * channels[k][1].itemsize
            if at > end:
                raise ObservationError(f"{path.name} byte {pos}: ping {ping.PingNumber}'s channel {k} runs past the end "
                                       f"of its packet (byte {end}): a corrupt packet, not a recording cut short")
        else:  # every channel is there: a packet following its samples means a corrupt length
            if at + 2 <= len(data) and int.from_bytes(data[at:at + 2], "little") == 0xFACE:
                raise ObservationError(f"{path.name} byte {pos}: ping {ping.PingNumber}'s NumBytesThisRecord "
                                       f"{start.NumBytesThisRecord} runs past the end of the file, but its channels "
                                       f"end at byte {at} where another packet starts: a corrupt length")
    return pos + start.NumBytesThisRecord - len(data), True


def read_pings(path) -> tuple[object, dict[int, object]]:
    """The file header and the sonar pings by ``PingNumber`` of one XTF file (``pyxtf``
    structures; each ping with ``ping_chan_headers``, ``data`` and its byte ``offset``), in file
    order. Anything malformed is refused (:class:`ObservationError`) naming the file and byte; a
    file cut short inside its last packet gives the complete pings before it, and the header's
    ``truncation`` (a :class:`Truncation`, else ``None``) says what was lost.

    Parameters
    ----------
    path : str or os.PathLike
        The XTF file.

    Returns
    -------
    header : pyxtf.XTFFileHeader
        The file header, with ``truncation`` (:class:`Truncation` or ``None``).
    pings : dict
        ``PingNumber`` -> ping, in file order (empty for a file without sonar pings).

    Raises
    ------
    ObservationError
        A missing file, a malformed packet, or a cut file without a complete ping, naming the byte.
    """
    pyxtf, _ = _structures()
    problem = missing_file(path, "XTF file")  # empty path, directory, device, FIFO, missing
    if problem:
        raise ObservationError(problem)
    path = Path(path)
    data = path.read_bytes()
    header, channels = read_header(path, data)
    header.truncation = None
    pings: dict[int, object] = {}
    start_size = ctypes.sizeof(pyxtf.XTFPacketStart)
    pos = ctypes.sizeof(pyxtf.XTFFileHeader)
    while pos < len(data):
        start = pyxtf.XTFPacketStart.from_buffer_copy(data[pos:pos + start_size].ljust(start_size, b"\0"))
        if pos + start_size > len(data) or pos + start.NumBytesThisRecord > len(data):
            missing, known = _cut_packet(path, data, pos, header, channels)
            if not pings:
                raise ObservationError(f"{path.name}: truncated at byte {len(data)}: the packet at byte {pos} is "
                                       f"incomplete and no complete sonar ping precedes it")
            header.truncation = Truncation(path.name, pos, missing, known, len(pings))
            break
        if start.MagicNumber != 0xFACE:
            raise ObservationError(f"{path.name} byte {pos}: not an XTF packet (no 0xFACE)")
        end = pos + start.NumBytesThisRecord
        _check_length(path, pos, start, start_size)
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


def truncation_note(path) -> str:
    """The one-line warning of an XTF file cut short (:class:`Truncation`), ``""`` for a whole
    file (a malformed file raises the reader's one-line error).

    Parameters
    ----------
    path : str or os.PathLike
        The XTF file.

    Returns
    -------
    str
        The warning, or ``""``.
    """
    header, _ = read_pings(path)
    return header.truncation.message() if header.truncation else ""


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
