"""What an XTF file holds, for a user about to write a matches file (numbers only): its channels
and their sides and sample orders, range settings, samples, navigation units, ping numbers,
time span and layback (:func:`summary`), and the pings of one channel as an image
(:func:`waterfall_data`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from sss_locus.experiments.sonar_files.observations_xtf import channel_order, ping_time_s
from sss_locus.experiments.sonar_files.towfish import xtf_layback
from sss_locus.experiments.sonar_files.xtf_packets import CHANNEL_TYPES, channel_types, read_pings

NAV_UNITS = {0: "metres (east, north)", 3: "degrees (longitude, latitude)"}


def summary(path, sample_order: str = "detect") -> dict:
    """One XTF file in numbers: ``file``, ``sonar``, ``nav_units``, ``n_pings``, ``ping_first``,
    ``ping_last``, ``ping_gaps`` (numbers missing between them), ``time_first_s``,
    ``time_last_s`` (seconds of the day), ``altitude_zero`` (pings with altitude 0),
    ``n_positions`` (distinct recorded sensor positions), ``layback_m``
    (min, max), ``layback_from``, ``layback_bad`` (pings whose ``Layback`` is negative or not a
    number: the reader refuses them), ``truncated`` (the one-line warning of a file cut short
    inside its last packet, whose complete pings alone are summarised; ``""`` for a whole file), ``truncated_at`` (the
    byte where its incomplete packet starts, else ``None``), and ``channels``: per channel ``channel``, ``type``, ``side``,
    ``n_samples`` (min, max), ``range_m`` (min, max), ``order`` and ``order_how`` (or
    ``order_error``, the reason the order cannot be detected).

    Parameters
    ----------
    path : str or os.PathLike
        The XTF file.
    sample_order : str
        How the channels' order is decided
        (:data:`~sss_locus.experiments.sonar_files.sample_order.CHOICES`).

    Returns
    -------
    dict
        The keys above; a file without sonar pings has only ``file``, ``sonar``, ``recorder``,
        ``nav_units``, ``n_pings`` (0), ``channels`` (empty), ``truncated`` and ``truncated_at``.
    """
    header, pings = read_pings(path)  # the path as given: an empty one is not the current folder
    path = Path(path)
    numbers = np.array(sorted(pings), dtype=np.int64)
    out = {"file": path.name, "sonar": header.SonarName.decode("latin-1", "replace").strip("\x00 "),
           "recorder": header.RecordingProgramName.decode("latin-1", "replace").strip("\x00 "),
           "nav_units": NAV_UNITS.get(int(header.NavUnits), f"{header.NavUnits} (not supported)"),
           "n_pings": len(pings), "channels": [],
           "truncated": header.truncation.message() if header.truncation else "",
           "truncated_at": header.truncation.offset if header.truncation else None}
    if not pings:
        return out
    times = np.array([ping_time_s(p) for p in pings.values()])
    lb = [xtf_layback(p, int(header.NavUnits))[:2] for p in pings.values()]
    out.update(ping_first=int(numbers[0]), ping_last=int(numbers[-1]),
               ping_gaps=int(numbers[-1] - numbers[0] + 1 - numbers.size),
               time_first_s=float(times.min()), time_last_s=float(times.max()),
               altitude_zero=int(sum(p.SensorPrimaryAltitude == 0 for p in pings.values())),
               n_positions=len({(p.SensorXcoordinate, p.SensorYcoordinate) for p in pings.values()}),
               layback_m=(min(v for v, _ in lb), max(v for v, _ in lb)),
               layback_from=sorted({s for _, s in lb if s}),
               layback_bad=int(sum(not (np.isfinite(p.Layback) and p.Layback >= 0) for p in pings.values())))
    for ch, kind in enumerate(channel_types(header)):
        have = [p for p in pings.values() if len(p.data) > ch]
        n = [len(p.data[ch]) for p in have]
        r = [float(p.ping_chan_headers[ch].SlantRange) for p in have]
        row = {"channel": ch, "type": kind, "side": CHANNEL_TYPES.get(kind, "?"),
               "n_samples": (min(n), max(n)) if n else (0, 0), "range_m": (min(r), max(r)) if r else (0.0, 0.0)}
        if kind in (1, 2) and have:
            try:
                row["order"], row["order_how"] = channel_order(pings, header, ch, sample_order, path.name)
            except ValueError as exc:
                row["order_error"] = str(exc)
        out["channels"].append(row)
    return out


def waterfall_data(path, channel: int) -> tuple[np.ndarray, np.ndarray]:
    """The ping numbers (file order) and the samples as stored of one channel of an XTF file,
    pings by samples (shorter pings padded with NaN).

    Parameters
    ----------
    path : str or os.PathLike
        The XTF file.
    channel : int
        Sonar channel index.

    Returns
    -------
    pings : numpy.ndarray
        Ping numbers, int, shape (p,).
    image : numpy.ndarray
        Samples as stored, shape (p, max samples), NaN padded.

    Raises
    ------
    ValueError
        ``channel`` out of range.
    """
    header, pings = read_pings(path)
    if not 0 <= channel < int(header.NumberOfSonarChannels):
        raise ValueError(f"channel must be in [0, {int(header.NumberOfSonarChannels) - 1}] for {Path(path).name}; got {channel}")
    rows = [p.data[channel] if len(p.data) > channel else np.zeros(0) for p in pings.values()]
    width = max((len(r) for r in rows), default=0)
    image = np.full((len(rows), width), np.nan)
    for i, r in enumerate(rows):
        image[i, :len(r)] = r
    return np.array(list(pings), dtype=np.int64), image
