"""Which end of a sidescan channel is the near end (numbers only).

XTF does not say in which order a channel's samples are stored. Recorders differ: many store
the port channel far-to-near (so that port and starboard side by side make the usual image
with the nadir in the middle; ``pyxtf.concatenate_channel`` pads port pings on the left for
this reason), others store every channel near-to-far. A reader that assumes one order gets
every range of the other wrong (a target at 26 m read as 3.8 m). So the order is decided per
file and channel:

``"detect"`` (default)
    from the data, by two independent signs, each a log-ratio over the file's pings:

    * the **transmit pulse**: the first ``k`` samples against the last ``k``
      (``k = max(4, n // 128)``; the outermost sample is left out, recorders mark it); the
      near end holds the pulse;
    * the **water column**: with the ping's altitude ``a`` (``SensorPrimaryAltitude``) the
      first seafloor return is near the sample ``a / range * n`` from the near end, and the
      samples before it (water) are dark: the ratio of the median of the samples just past
      that sample to the median of those before it, for both orders.

    An order is taken when one sign is decisive (a ratio of at least :data:`DECISIVE`) and
    the other does not contradict it; otherwise the file is refused with a message saying how
    to set the order.
``"near_first"``
    every channel stored near-to-far (sample 0 at the transducer);
``"port_far_first"``
    port channels far-to-near, starboard near-to-far.
"""

from __future__ import annotations

import numpy as np

ORDERS = ("near_first", "far_first")
CHOICES = ("detect", "near_first", "port_far_first")
DECISIVE = 3.0
"""A sign is decisive when its ratio (one order against the other) is at least this."""


def end_block(n: int) -> int:
    """Samples at each end compared for the transmit pulse.

    Parameters
    ----------
    n : int
        Samples per ping.

    Returns
    -------
    int
        Block length, at least 4.
    """
    return max(4, n // 128)


def _median_rows(rows):
    return float(np.median(rows)) if rows.size else np.nan


def pulse_ratio(samples: np.ndarray) -> float:
    """Median over pings of (first block + 1) / (last block + 1): > 1 when the pulse is at
    sample 0 (``samples``: pings by samples, as stored).

    Parameters
    ----------
    samples : numpy.ndarray
        Intensities, shape (pings, samples), as stored.

    Returns
    -------
    float
        The ratio; NaN when a ping has too few samples to compare its ends.
    """
    n = samples.shape[1]
    k = end_block(n)
    if n < 2 * k + 4:
        return np.nan
    first = np.median(samples[:, 1:k + 1], axis=1)
    last = np.median(samples[:, n - k - 1:n - 1], axis=1)
    return float(np.median((first + 1.0) / (last + 1.0)))


def water_ratio(samples: np.ndarray, bottom_sample: np.ndarray) -> float:
    """Median over pings of the seafloor-to-water contrast read near-first divided by the same
    read far-first: > 1 when sample 0 is the near end. ``bottom_sample``: each ping's
    altitude as a sample count from the near end (NaN: no altitude).

    Parameters
    ----------
    samples : numpy.ndarray
        Intensities, shape (pings, samples), as stored.
    bottom_sample : numpy.ndarray
        Altitude per ping in samples from the near end, shape (pings,).

    Returns
    -------
    float
        The ratio; NaN when no ping has its altitude within the usable range.
    """
    n = samples.shape[1]
    k = end_block(n)
    out = []
    for row, b in zip(samples, bottom_sample):
        if not (np.isfinite(b) and 2 * k < b < 0.7 * n):
            continue
        b = int(b)
        w = max(b // 2, 4)
        contrast = []
        for x in (row, row[::-1]):
            water = _median_rows(x[k + 1:max(int(0.8 * b), k + 2)])
            floor = _median_rows(x[int(1.2 * b) + 1:int(1.2 * b) + 1 + w])
            contrast.append((floor + 1.0) / (water + 1.0))
        out.append(contrast[0] / contrast[1])
    return float(np.median(out)) if out else np.nan


def detect(samples: np.ndarray, bottom_sample: np.ndarray) -> tuple[str | None, str]:
    """The order of one channel from its pings (rows as stored, non-negative intensities) and
    each ping's altitude in samples (module docstring): ``(order, evidence)``, ``order`` ``None``
    when the data cannot tell.

    Parameters
    ----------
    samples : numpy.ndarray
        Intensities, shape (pings, samples), as stored.
    bottom_sample : numpy.ndarray
        Altitude per ping in samples from the near end, shape (pings,) (NaN: none).

    Returns
    -------
    order : str or None
        ``"near_first"``, ``"far_first"``, or ``None`` (no decisive agreeing evidence, or no ping
        with data).
    evidence : str
        The ratios measured, in words.
    """
    samples = np.asarray(samples, float)
    keep = samples.max(axis=1) > 0 if samples.size else np.zeros(0, bool)  # all-zero pings say nothing
    samples, bottom_sample = samples[keep], np.asarray(bottom_sample, float)[keep]
    if samples.shape[0] == 0:
        return None, "no ping with data"
    p, w = pulse_ratio(samples), water_ratio(samples, bottom_sample)
    votes = []
    for name, r in (("transmit pulse", p), ("water column", w)):
        if np.isfinite(r) and max(r, 1.0 / r) >= DECISIVE:
            votes.append((name, "near_first" if r > 1 else "far_first"))
    text = (f"transmit pulse {'near the first sample' if p > 1 else 'near the last sample'} (ratio {max(p, 1 / p):.3g}), "
            if np.isfinite(p) and p > 0 else "transmit pulse not measurable, ")
    text += (f"water column {'after the first sample' if w > 1 else 'before the last sample'} (ratio {max(w, 1 / w):.3g})"
             if np.isfinite(w) and w > 0 else "water column not measurable (no altitude in range)")
    orders = {o for _, o in votes}
    if len(orders) != 1:
        return None, text
    return orders.pop(), text


def chosen(choice: str, kind: int) -> str:
    """The order a fixed ``choice`` gives a channel of ``TypeOfChannel`` ``kind`` (1 port, 2 starboard).

    Parameters
    ----------
    choice : str
        ``"near_first"`` or ``"port_far_first"``.
    kind : int
        The channel's ``TypeOfChannel`` (1 port, 2 starboard).

    Returns
    -------
    str
        ``"near_first"`` or ``"far_first"``.

    Raises
    ------
    ValueError
        Any other ``choice``.
    """
    if choice == "near_first" or (choice == "port_far_first" and kind != 1):
        return "near_first"
    if choice == "port_far_first":
        return "far_first"
    raise ValueError(f"sample_order must be one of {list(CHOICES[1:])} here; got {choice!r}")


def from_near(sample, n_samples, order: str):
    """The sample index counted from the near end: ``sample`` or ``n_samples - 1 - sample``.

    Parameters
    ----------
    sample : int or array_like
        Sample index as stored.
    n_samples : int or array_like
        Samples per ping.
    order : str
        ``"near_first"`` or ``"far_first"``.

    Returns
    -------
    int or numpy.ndarray
        Index from the near end, in [0, n_samples - 1] for a valid ``sample``.
    """
    return sample if order == "near_first" else n_samples - 1 - sample
