"""Which sightings of a feature the your-pings estimates use (numbers only): sightings without
a flat-seafloor position are set aside and named, and the two-view locus takes the best pair.

* A sighting whose slant range is shorter than its transducer's height above the seafloor has
  no flat-seafloor ground range (the sphere of that range does not reach a seafloor at that
  height); it is never placed. :func:`impossible` finds them, :func:`excluded_table` names each
  (feature, file and ping or line, range, height) for the page, the summary and the results.
* The **best pair** of a feature's sightings (:func:`best_pairs`): of the pairs whose locus is
  not empty, the one with the shortest locus (the tightest constraint two of its sightings
  give); where every pair's locus is empty, the pair whose sensors see the mean flat-seafloor
  position from the most different directions (the largest ``sin^2`` of the angle between the
  two lines of sight there; two views along one line of sight confine the feature least).
  Ties go to the earlier pair in file order.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

ONE_SIGHTING = "one sighting: no locus"
"""The status of a feature seen once, in every table and figure."""


def impossible(ranges_m: np.ndarray, height_m: np.ndarray) -> np.ndarray:
    """Sightings whose slant range is below the transducer's height above the seafloor (no
    flat-seafloor ground range).

    Parameters
    ----------
    ranges_m : numpy.ndarray
        Slant ranges, m, shape (m,).
    height_m : numpy.ndarray
        Transducer heights above the seafloor, m, shape (m,).

    Returns
    -------
    numpy.ndarray
        Boolean, shape (m,).
    """
    return np.asarray(ranges_m, float) < np.asarray(height_m, float)


def where(table: pd.DataFrame) -> pd.Series:
    """Each sighting's place in the user's files: ``<xtf file> ping <n>`` for XTF sightings,
    else ``<file> line <n>``.

    Parameters
    ----------
    table : pandas.DataFrame
        Sightings (``source``, ``line``; ``xtf_file``, ``ping`` for XTF).

    Returns
    -------
    pandas.Series
        One string per row.
    """
    text = table["source"].astype(str) + " line " + table["line"].astype(str)
    if "xtf_file" in table.columns:
        text = table["xtf_file"].astype(str) + " ping " + table["ping"].astype(str) + " (" + text + ")"
    return text


def excluded_table(table: pd.DataFrame, height_m: np.ndarray, bad: np.ndarray) -> pd.DataFrame:
    """The sightings set aside: ``feature``, ``where``, ``slant_range_m``, ``transducer_height_m``, ``reason``.

    Parameters
    ----------
    table : pandas.DataFrame
        Sightings, m rows.
    height_m : numpy.ndarray
        Transducer heights above the seafloor, m, shape (m,).
    bad : numpy.ndarray
        Boolean (m,): set aside.

    Returns
    -------
    pandas.DataFrame
        One row per sighting set aside (empty when none).
    """
    t = table[bad]
    return pd.DataFrame({"feature": t["feature"].to_numpy(), "where": where(t).to_numpy(),
                         "slant_range_m": t["slant_range_m"].to_numpy(float),
                         "transducer_height_m": np.asarray(height_m, float)[bad],
                         "reason": "slant range below the transducer's height: no flat-seafloor position"})


def excluded_sentence(excluded: pd.DataFrame) -> str:
    """One sentence naming every sighting set aside ("" when none).

    Parameters
    ----------
    excluded : pandas.DataFrame
        :func:`excluded_table`'s result.

    Returns
    -------
    str
        The sentence, or ``""``.
    """
    if not len(excluded):
        return ""
    items = "; ".join(f"{r.feature} ({r.where}: {r.slant_range_m:.3g} m below {r.transducer_height_m:.3g} m)"
                      for r in excluded.itertuples())
    return (f"{len(excluded)} sighting(s) set aside, their slant range shorter than the transducer's height above "
            f"the seafloor (no flat-seafloor position; a wrong sample order or altitude is the usual cause): {items}.")


def pair_slots(K: int) -> tuple[np.ndarray, np.ndarray]:
    """Every pair ``(a, b)``, ``a < b``, of ``K`` slots, in file order.

    Parameters
    ----------
    K : int
        Number of slots.

    Returns
    -------
    a, b : numpy.ndarray
        Slot indices, each shape (K (K - 1) / 2,); empty when K < 2.
    """
    a, b = np.triu_indices(K, 1)
    return a, b


def best_pairs(origin: np.ndarray, point: np.ndarray, mask: np.ndarray,
               length_m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per feature, the slots ``(i, j)`` of its best pair of sightings (module docstring) and
    whether it has one (two or more sightings). ``origin``: (n, K, 3) sensor origins;
    ``point``: (n, 3) the mean flat-seafloor positions; ``mask``: (n, K) sightings present;
    ``length_m``: (n, P) the locus length of every pair of :func:`pair_slots` (0: empty).

    Parameters
    ----------
    origin : numpy.ndarray
        Sensor origins, world, m, shape (n, K, 3).
    point : numpy.ndarray
        Mean flat-seafloor positions, world, m, shape (n, 3).
    mask : numpy.ndarray
        Boolean (n, K): sightings present.
    length_m : numpy.ndarray
        Locus length of every pair, m, shape (n, P).

    Returns
    -------
    i, j : numpy.ndarray
        Slots of the best pair, shape (n,) (0, 1 when the feature has none).
    has : numpy.ndarray
        Boolean (n,): two or more sightings.
    """
    n, K = mask.shape
    a, b = pair_slots(K)
    u = origin - point[:, None, :]
    u = u / np.maximum(np.linalg.norm(u, axis=-1, keepdims=True), 1e-300)
    sin2 = 1.0 - np.clip(np.einsum("npi,npi->np", u[:, a], u[:, b]), -1.0, 1.0) ** 2
    ok = mask[:, a] & mask[:, b]
    nonempty = ok & (np.asarray(length_m, float) > 0)
    by_length = np.argmin(np.where(nonempty, length_m, np.inf), axis=1)
    by_angle = np.argmax(np.where(ok, np.round(sin2, 12), -1.0), axis=1)
    best = np.where(nonempty.any(axis=1), by_length, by_angle)
    has = ok.any(axis=1)
    return np.where(has, a[best], 0), np.where(has, b[best], 1), has
