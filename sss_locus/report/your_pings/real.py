"""The your-pings chapter's real pass (the *Scotsman* recording, ``data/examples/your_pings/real/``):
its picks, the table of their flat-seafloor positions, the captions and what one pass can and
cannot tell, in sentences built from the run's numbers."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from sss_locus.experiments.your_pings.views import ONE_SIGHTING
from sss_locus.report.common.text import fmt_sig


def read_hits(path) -> pd.DataFrame:
    """An OpenSidescan ``.hits`` annotation (``channel x y`` per line: the sample as stored and
    the image row, the ping's index in file order) as ``channel``, ``sample``, ``row``.

    Parameters
    ----------
    path : str or path-like
        The ``.hits`` file (whitespace-separated integers, blank lines skipped).

    Returns
    -------
    pandas.DataFrame
        Columns ``channel``, ``sample``, ``row`` (ints), one row per line.
    """
    rows = [line.split() for line in Path(path).read_text().splitlines() if line.strip()]
    return pd.DataFrame([[int(v) for v in r[:3]] for r in rows], columns=["channel", "sample", "row"])


def marks(matches: pd.DataFrame, hits: pd.DataFrame, ping_numbers: np.ndarray) -> pd.DataFrame:
    """What the waterfall marks: every pick of the matches file and every annotated hit (its
    row turned into the ping's number); a pick on an annotated hit is marked once, saying so.

    Parameters
    ----------
    matches : pandas.DataFrame
        The matches file's picks: ``feature``, ``channel``, ``ping``, ``sample``.
    hits : pandas.DataFrame
        :func:`read_hits` of the annotation.
    ping_numbers : numpy.ndarray, shape (n_pings,)
        Ping number of each row of the file, in file order.

    Returns
    -------
    pandas.DataFrame
        Columns ``channel``, ``ping``, ``sample``, ``label``: the picks, then the hits no pick
        is on.
    """
    picks = matches.assign(label=matches["feature"])[["channel", "ping", "sample", "label"]]
    hit = pd.DataFrame({"channel": hits["channel"], "ping": ping_numbers[hits["row"].to_numpy()],
                        "sample": hits["sample"], "label": "annotated hit (.hits)"})
    key = ["channel", "ping", "sample"]
    same = picks.merge(hit[key], on=key, how="left", indicator=True)["_merge"].eq("both").to_numpy()
    picks.loc[same, "label"] = picks.loc[same, "label"] + " = annotated hit (.hits)"
    hit = hit[~hit.merge(picks[key], on=key, how="left", indicator=True)["_merge"].eq("both").to_numpy()]
    return pd.concat([picks, hit], ignore_index=True)


def positions_table(res) -> pd.DataFrame:
    """One row per pick: where in the file (the side's channel, ping, sample as stored, the
    channel's order), the slant range, the transducer's height, the flat-seafloor ground range and
    position (lon/lat) and the feature's status.

    Parameters
    ----------
    res : PingResults
        The pass's results (``sightings`` with the XTF columns, ``features``).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``feature``: ``side``, ``ping``, ``sample_stored``, ``sample_order``,
        ``slant_range_m``, ``transducer_height_m``, ``ground_range_m`` (m), ``flat_lon_deg``,
        ``flat_lat_deg`` (WGS 84, deg) and ``status``.
    """
    s = res.sightings
    ground = np.hypot(s["flat_east_m"] - s["sensor_east_m"], s["flat_north_m"] - s["sensor_north_m"])
    status = res.features.set_index("feature")["two_view_status"]
    return pd.DataFrame({"feature": s["feature"], "side": s["side"], "ping": s["ping"],
                         "sample_stored": s["sample_stored"], "sample_order": s["sample_order"],
                         "slant_range_m": s["slant_range_m"], "transducer_height_m": s["transducer_height_m"],
                         "ground_range_m": ground, "flat_lon_deg": s["flat_lon_deg"], "flat_lat_deg": s["flat_lat_deg"],
                         "status": s["feature"].map(status)}).set_index("feature")


def waterfall_caption(xtf_name: str, n_pings: int, orders: dict) -> str:
    """The real waterfall's caption (``orders``: side to the detected sample order).

    Parameters
    ----------
    xtf_name : str
        The XTF file's name.
    n_pings : int
        Number of pings drawn.
    orders : dict of str to str
        Side -> sample order (``"far_first"``, ``"near_first"`` or another word, shown as is).

    Returns
    -------
    str
        The caption (Markdown).
    """
    words = {"far_first": "far-to-near", "near_first": "near-to-far"}
    said = "; ".join(f"{side} stored {words.get(o, o)}" for side, o in orders.items())
    return (f"**Real data** (OpenSidescan, CIDCO, MIT licence): the {n_pings} pings of `{xtf_name}` as stored, one panel "
            f"per channel ({said}, detected from the transmit pulse and the water column), with the recording's own "
            "annotation of the wreck (`.hits`) and the picks of `scotsman_matches.csv` circled: read a matches "
            "file's `ping`, `channel` and `sample` off these axes.")


def one_pass_text(res, table: pd.DataFrame, n_fixes: int, n_pings: int, raise_m: float = 1.0) -> str:
    """What this one pass can and cannot tell, from its numbers: every feature seen once gets a
    flat-seafloor position and no locus; how far that position moves if the target stands
    ``raise_m`` above the flat seafloor (the pick with the shortest range, where it matters
    most); how coarse the navigation is.

    Parameters
    ----------
    res : PingResults
        The pass's results (``features`` with ``n_sightings``).
    table : pandas.DataFrame
        :func:`positions_table` of the pass (``slant_range_m``, ``transducer_height_m``, m).
    n_fixes : int
        Number of distinct navigation fixes in the file.
    n_pings : int
        Number of pings in the file.
    raise_m : float
        Height (m) of the supposed target above the flat seafloor.

    Returns
    -------
    str
        The paragraph (Markdown), lengths in m.
    """
    once = int((res.features["n_sightings"] == 1).sum())
    near = table.loc[table["slant_range_m"].idxmin()]
    r, h = float(near["slant_range_m"]), float(near["transducer_height_m"])
    moved = np.sqrt(max(r ** 2 - (h - raise_m) ** 2, 0.0)) - np.sqrt(max(r ** 2 - h ** 2, 0.0))
    return (f"One pass sees each target once: {once} of the {len(res.features)} picks are *{ONE_SIGHTING}*. "
            "Each gets its flat-seafloor position, the point of its range sphere (inside the beam) on a horizontal "
            "seafloor at the altimeter's height below the transducer — right only if the target lies on such a seafloor. "
            f"A wreck does not: were {near.name} ({fmt_sig(r)} m slant range, {fmt_sig(h)} m above the seafloor) "
            f"{fmt_sig(raise_m)} m above it, its ground range would be {fmt_sig(moved)} m longer than the flat position "
            "says, and one pass cannot tell which. A second pass that sees the same target from another line gives "
            "the two-view locus (where the target can be, in 3-D, inside both beams), and three give an N-view "
            f"position. Nor can one pass check the navigation: this file's {n_pings} pings carry only {n_fixes} "
            "distinct positions (an AUV's position under water is dead-reckoned and drifts), so the positions above "
            "are as good as that navigation, which only another pass over the same targets, or a known position, "
            "can measure.")
