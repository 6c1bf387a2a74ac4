"""The tests that decide the survey-pass verdicts of the claims page (numbers only).

Each function reads a computed median curve over the crossing-angle grid (the ``curve`` of
:class:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve`, or a
:func:`~sss_locus.experiments.survey_passes.planning.curve_summary` table) and answers one question the paper's
Sec. IV-D raises, by a rule stated here and fixed before the results were read:

- :func:`near_end_check`: is a pass *near* a repeat (0 deg) or an anti-parallel pass (180 deg) as
  good as the exact one? The largest median within ``window_deg`` of the end, over the median at
  the end; and whether every angle of that window is in the preferred band of
  :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`.
- :func:`peak_agreement`: do two curves (locus length and elevation misalignment) peak at the
  same angle? Their peak angles, the gap, and whether the two bootstrap intervals of the peak
  angle overlap (a lenient test: overlapping intervals do not prove equal peaks, disjoint ones
  show different peaks).
- :func:`advice_verdict`: does the paper's planning advice hold for a curve? The ends (the worse
  of 0 and 180 deg) must be no worse than the median over the paper's 10-40 deg band and no
  worse than a perpendicular crossing (90 deg).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_passes.planning import planning_bands
from sss_locus.experiments.stats.replicates import N_BATCHES, batch_count, replicate_interval

ENDS_DEG = (0.0, 180.0)
"""The two ends of the crossing-angle range: an exact repeat and an anti-parallel pass."""


def _column(curve: pd.DataFrame, value: str) -> tuple[np.ndarray, np.ndarray]:
    col = f"{value}_median"
    if col not in curve or "crossing_angle_deg" not in curve:
        raise ValueError(f"curve must have columns crossing_angle_deg and {col}")
    c = curve.sort_values("crossing_angle_deg")
    return c["crossing_angle_deg"].to_numpy(float), c[col].to_numpy(float)


def _at(g: np.ndarray, m: np.ndarray, angle: float) -> float:
    hit = np.isclose(g, angle)
    if not hit.any():
        raise ValueError(f"crossing angle {angle} deg is not on the curve's grid")
    return float(m[hit][0])


def near_end_check(curve: pd.DataFrame, value: str = "locus_length_m", *, window_deg: float = 10.0,
                   prefer_below: float = 0.25, avoid_above: float = 0.5) -> pd.DataFrame:
    """Whether passes near each end of the crossing-angle range are as good as the end itself.

    Parameters
    ----------
    curve : pandas.DataFrame
        ``crossing_angle_deg`` (degrees in [0, 180], both ends on the grid) and
        ``<value>_median``.
    value : str
        The column whose median curve is used.
    window_deg : float
        "Near" means within this many degrees of the end (exclusive of the end), > 0.
    prefer_below, avoid_above : float
        The band rule of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands`.

    Returns
    -------
    pandas.DataFrame
        One row per end (0 and 180 deg): ``end_deg``, ``end_median``, ``worst_angle_deg`` and
        ``worst_median`` (the largest median within the window), ``ratio`` (worst over end),
        ``n_angles`` (grid angles in the window) and ``all_preferred`` (every angle of the
        window, and the end, in a preferred band).
    """
    if not (isinstance(window_deg, (int, float)) and 0 < window_deg < 90):
        raise ValueError(f"window_deg must be in (0, 90) degrees; got {window_deg!r}")
    g, m = _column(curve, value)
    bands = planning_bands(curve, value, prefer_below=prefer_below, avoid_above=avoid_above)
    prefer = bands[bands["kind"] == "prefer"]
    preferred = np.zeros(g.shape, bool)
    for r in prefer.itertuples():
        preferred |= (g >= r.lo_deg - 1e-9) & (g <= r.hi_deg + 1e-9)
    rows = []
    for end in ENDS_DEG:
        end_median = _at(g, m, end)
        near = (np.abs(g - end) > 1e-9) & (np.abs(g - end) <= window_deg + 1e-9)
        if not near.any():  # a coarse grid: nothing to test near this end (NaN, n_angles 0)
            rows.append({"end_deg": end, "end_median": end_median, "worst_angle_deg": float("nan"),
                         "worst_median": float("nan"), "ratio": float("nan"), "n_angles": 0,
                         "all_preferred": bool(preferred[np.isclose(g, end)].all())})
            continue
        i = np.flatnonzero(near)[np.argmax(m[near])]
        rows.append({"end_deg": end, "end_median": end_median, "worst_angle_deg": float(g[i]),
                     "worst_median": float(m[i]),
                     "ratio": float(m[i] / end_median) if end_median > 0 else float("inf"),
                     "n_angles": int(near.sum()),
                     "all_preferred": bool(preferred[near].all() and preferred[np.isclose(g, end)].all())})
    return pd.DataFrame(rows)


def peak_agreement(peak_a: dict, peak_b: dict) -> dict[str, float | bool]:
    """Peak angles of two curves (each ``{angle_deg, ci_low_deg, ci_high_deg}``, as in
    :attr:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve.peak`): ``gap_deg`` (b minus a)
    and ``intervals_overlap`` (the two bootstrap intervals share at least one angle).

    Parameters
    ----------
    peak_a, peak_b : dict
        Peak angles with their intervals, degrees.

    Returns
    -------
    dict of str to float or bool
        ``gap_deg`` and ``intervals_overlap``.
    """
    for name, p in (("peak_a", peak_a), ("peak_b", peak_b)):
        if not {"angle_deg", "ci_low_deg", "ci_high_deg"} <= set(p):
            raise ValueError(f"{name} needs angle_deg, ci_low_deg and ci_high_deg; got {sorted(p)}")
    overlap = max(peak_a["ci_low_deg"], peak_b["ci_low_deg"]) <= min(peak_a["ci_high_deg"], peak_b["ci_high_deg"])
    return {"angle_a_deg": float(peak_a["angle_deg"]), "angle_b_deg": float(peak_b["angle_deg"]),
            "gap_deg": float(peak_b["angle_deg"] - peak_a["angle_deg"]), "intervals_overlap": bool(overlap)}


def advice_verdict(curve: pd.DataFrame, value: str = "locus_length_m", *,
                   oblique_band_deg: tuple[float, float] = (10.0, 40.0)) -> dict[str, float | bool]:
    """The paper's advice (prefer ~0 or ~180 deg over oblique crossings and a cross-line) tested
    on one median curve.

    Parameters
    ----------
    curve : pandas.DataFrame
        A median curve (``crossing_angle_deg``, ``<value>_median``).
    value : str
        The column used.
    oblique_band_deg : (float, float)
        The oblique band, degrees.

    Returns
    -------
    dict
        ``ends`` (the larger median of 0 and 180 deg), ``oblique`` (median of the medians at the
        grid angles in ``oblique_band_deg``, inclusive), ``perpendicular`` (median at 90 deg)
        and ``holds`` (``ends <= oblique`` and ``ends <= perpendicular``; False when no grid
        angle lies in the band, ``oblique`` then NaN).
    """
    g, m = _column(curve, value)
    lo, hi = oblique_band_deg
    band = (g >= lo - 1e-9) & (g <= hi + 1e-9)
    ends = max(_at(g, m, 0.0), _at(g, m, 180.0))
    # a grid with no angle in the band (a coarse user grid) leaves the test undecided: NaN, not held
    oblique, perp = (float(np.median(m[band])) if band.any() else float("nan")), _at(g, m, 90.0)
    return {"ends": ends, "oblique": oblique, "perpendicular": perp,
            "holds": bool(ends <= oblique and ends <= perp)}


def over_peak(cur, gamma_deg: float, value: str = "locus_length_m", *, n_batches: int = N_BATCHES,
              confidence_level: float = 0.95) -> dict[str, float]:
    """The median of ``value`` at grid angle ``gamma_deg`` over the largest median of the curve
    (the peak angle chosen on the whole curve), with its 95 % replicate-batch interval: each
    batch (every angle's rows dealt ``i mod k``) gives the ratio of its medians at the two
    angles. ``cur`` is a :class:`~sss_locus.experiments.survey_passes.planning.CrossingAngleCurve` (its
    ``curve`` and ``samples``). Returns ``median`` (the ratio), ``ci_low``, ``ci_high``.

    Parameters
    ----------
    cur : CrossingAngleCurve
        The curve and its samples.
    gamma_deg : float
        A grid angle, degrees.
    value : str
        The column used.
    n_batches : int
        Replicate batches.
    confidence_level : float
        Level, in (0, 1).

    Returns
    -------
    dict of str to float
        ``median``, ``ci_low``, ``ci_high``.
    """
    c, s = cur.curve, cur.samples
    angles = c["crossing_angle_deg"].to_numpy()
    peak = float(angles[int(np.argmax(c[f"{value}_median"].to_numpy()))])
    if not np.isclose(angles, gamma_deg).any():
        raise ValueError(f"gamma_deg {gamma_deg} is not on the grid")

    def rows(g: float) -> np.ndarray:
        return s.loc[np.isclose(s["crossing_angle_deg"], g), value].to_numpy(float)

    at, top = rows(gamma_deg), rows(peak)
    k = batch_count(min(at.size, top.size), n_batches)
    ratio = float(np.median(at) / np.median(top))
    per_batch = [np.median(at[j::k]) / np.median(top[j::k]) for j in range(k)]
    lo, hi = replicate_interval(ratio, per_batch, confidence_level, bounds=(0.0, np.inf))
    return {"median": ratio, "ci_low": float(lo), "ci_high": float(hi)}
