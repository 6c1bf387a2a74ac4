"""The result files a user takes away from :func:`~sss_locus.experiments.your_pings.study.analyse`:
a GeoJSON document (RFC 7946: WGS 84 longitude, latitude; the third coordinate is height above
the sea surface, m, negative below) and the comparison with a known truth (the worked example).

GeoJSON features (``properties.kind``):

``locus``
    one LineString per arc of a feature's two-view locus (its best pair of sightings), with the
    feature's locus length and arc count;
``nview``
    the N-view position (where estimated), with its status, cost and the 1-sigma uncertainty
    ellipse: ``ellipse_major_m``, ``ellipse_minor_m`` (horizontal semi-axes) and
    ``ellipse_azimuth_deg`` (major axis, clockwise from grid north), ``sigma_up_m``;
``two_view``
    the point of the locus nearest the mean flat-seafloor position (two or more sightings);
``two_view_empty_locus``
    where that locus is empty (the pair does not agree within the beams): the fallback point on
    the circle or sphere, which is not a locus point;
``joint``
    the joint adjustment's position (where the chapter computed it and the feature was seen on
    two or more passes), with ``n_passes`` and its 1-sigma ellipse (``joint_ellipse_major_m``,
    ``joint_ellipse_minor_m``, ``joint_ellipse_azimuth_deg``, ``joint_sigma_up_m``);
``flat_mean`` and ``flat``
    the mean flat-seafloor position with the spread, and each sighting's.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.inputs import missing_file
from sss_locus.experiments.your_pings.study import PingResults

#: Decimal places of written coordinates: 1e-9 deg is about 0.1 mm; heights to 0.1 mm.
LONLAT_DECIMALS = 9
HEIGHT_DECIMALS = 4


def _num(v):
    v = float(v)
    return None if not np.isfinite(v) else v


def _point(lon, lat, up):
    return [round(float(lon), LONLAT_DECIMALS), round(float(lat), LONLAT_DECIMALS), round(float(up), HEIGHT_DECIMALS)]


def geojson(res: PingResults, *, notice: str = "") -> dict:
    """The results as a GeoJSON FeatureCollection (module docstring); ``notice`` (e.g. that the
    data are synthetic) is stored as the collection's ``description``. Refused (``ValueError``)
    for results without longitude/latitude (local metres without an origin).

    Parameters
    ----------
    res : PingResults
        The results, with a frame.
    notice : str
        Description stored in the collection (empty: none).

    Returns
    -------
    dict
        The GeoJSON FeatureCollection (coordinates longitude, latitude in degrees, up in m).

    Raises
    ------
    ValueError
        Results in local metres without a frame.
    """
    if res.frame is None:
        raise ValueError("GeoJSON needs longitude/latitude: the sightings are in local metres; give the "
                         "local frame's origin (origin_lon_deg, origin_lat_deg)")
    out = []

    def add(geometry, **props):
        out.append({"type": "Feature", "geometry": geometry,
                    "properties": {k: (_num(v) if isinstance(v, (float, np.floating)) else
                                       int(v) if isinstance(v, (np.integer,)) else v) for k, v in props.items()}})

    f = res.features.set_index("feature", drop=False)
    for (name, arc), part in res.locus.groupby(["feature", "arc"], sort=False):
        add({"type": "LineString", "coordinates": [_point(*p) for p in part[["lon_deg", "lat_deg", "up_m"]].to_numpy()]},
            kind="locus", feature=name, arc=int(arc), locus_length_m=f.loc[name, "locus_length_m"],
            locus_arcs=f.loc[name, "locus_arcs"])
    for _, r in res.features.iterrows():
        if np.isfinite(r["nview_east_m"]):
            add({"type": "Point", "coordinates": _point(r["nview_lon_deg"], r["nview_lat_deg"], r["nview_up_m"])},
                kind="nview", feature=r["feature"], status=r["nview_status"], n_sightings=int(r["n_sightings"]),
                cost=r["nview_cost"], ellipse_major_m=r["ellipse_major_m"], ellipse_minor_m=r["ellipse_minor_m"],
                ellipse_azimuth_deg=r["ellipse_azimuth_deg"], sigma_up_m=r["sigma_up_m"])
        if np.isfinite(r.get("joint_east_m", np.nan)):
            add({"type": "Point", "coordinates": _point(r["joint_lon_deg"], r["joint_lat_deg"], r["joint_up_m"])},
                kind="joint", feature=r["feature"], n_passes=int(r["n_passes"]),
                **{k: r[k] for k in ("joint_ellipse_major_m", "joint_ellipse_minor_m", "joint_ellipse_azimuth_deg",
                                     "joint_sigma_up_m")})
        if np.isfinite(r["two_view_east_m"]):
            add({"type": "Point", "coordinates": _point(r["two_view_lon_deg"], r["two_view_lat_deg"], r["two_view_up_m"])},
                kind="two_view" if r["two_view_status"] == "locus" else "two_view_empty_locus",
                feature=r["feature"], status=r["two_view_status"], locus_length_m=r["locus_length_m"])
        add({"type": "Point", "coordinates": _point(r["flat_lon_deg"], r["flat_lat_deg"], r["flat_up_m"])},
            kind="flat_mean", feature=r["feature"], n_sightings=int(r["n_sightings"]), flat_spread_m=r["flat_spread_m"])
    for _, s in res.sightings.iterrows():
        add({"type": "Point", "coordinates": _point(s["flat_lon_deg"], s["flat_lat_deg"], s["flat_up_m"])},
            kind="flat", feature=s["feature"], line=int(s["line"]), side=s["side"], slant_range_m=s["slant_range_m"])
    doc = {"type": "FeatureCollection", "features": out}
    if notice:
        doc["description"] = notice
    return doc


def geojson_text(res: PingResults, *, notice: str = "") -> str:
    """:func:`geojson` as JSON text (no NaN: missing values are ``null``).

    Parameters
    ----------
    res : PingResults
        The results, with a frame.
    notice : str
        Description stored in the collection.

    Returns
    -------
    str
        The JSON text, ending in a newline.
    """
    return json.dumps(geojson(res, notice=notice), indent=1, allow_nan=False) + "\n"


def against_truth(res: PingResults, truth: pd.DataFrame) -> pd.DataFrame:
    """Errors of each estimate against known feature positions (``truth``: ``feature``,
    ``east_m``, ``north_m``, ``up_m``): one row per feature and estimator (``flat`` mean,
    ``two_view``, ``nview``, ``joint`` where computed) with ``error_h_m`` and ``error_up_m`` (estimate minus truth); rows
    without an estimate are left out (their status is in the features table).

    Parameters
    ----------
    res : PingResults
        The results (local metres).
    truth : pandas.DataFrame
        True positions, local frame, m.

    Returns
    -------
    pandas.DataFrame
        ``feature``, ``estimator``, ``n_sightings``, ``error_h_m``, ``error_up_m``.
    """
    t = res.features.merge(truth, on="feature", how="inner", suffixes=("", "_true"))
    rows = []
    for est in [e for e in ("flat", "two_view", "nview", "joint") if f"{e}_east_m" in t]:
        d = t[[f"{est}_east_m", f"{est}_north_m", f"{est}_up_m"]].to_numpy() - t[["east_m", "north_m", "up_m"]].to_numpy()
        ok = np.isfinite(d).all(axis=1)
        if est == "two_view":  # an empty locus has no locus point (its fallback is not one)
            ok &= (t["two_view_status"] == "locus").to_numpy()
        rows.append(pd.DataFrame({"feature": t["feature"][ok], "estimator": est, "n_sightings": t["n_sightings"][ok],
                                  "error_h_m": np.hypot(d[ok, 0], d[ok, 1]), "error_up_m": d[ok, 2]}))
    return pd.concat(rows, ignore_index=True)


def read_truth(truth, observations) -> pd.DataFrame | None:
    """Known feature positions (a CSV with ``feature``, ``east_m``, ``north_m``, ``up_m``, in the
    local frame) to compare with, or ``None``: no ``truth`` given, or the shipped example's truth
    with observations that are not the shipped example's (a user's own survey).

    Parameters
    ----------
    truth : str or os.PathLike or None
        The truth CSV (empty or ``None``: none).
    observations : str or os.PathLike
        The observations file it goes with.

    Returns
    -------
    pandas.DataFrame or None
        ``feature`` (str), ``east_m``, ``north_m``, ``up_m`` (float, local frame); or ``None``.

    Raises
    ------
    ValueError
        A missing or unreadable file, a missing column, a non-finite value or a repeated feature.
    """
    from pathlib import Path

    from sss_locus.paths import DATA_DIR

    if not truth:
        return None
    truth, observations = Path(truth), Path(observations)
    example = (DATA_DIR / "examples" / "your_pings").resolve()
    if truth.resolve().parent == example and observations.resolve().parent != example:
        return None
    if not truth.is_file():
        raise ValueError(missing_file(truth, "truth file"))
    try:
        table = pd.read_csv(truth, comment="#", dtype={"feature": str})
    except UnicodeDecodeError as exc:
        raise ValueError(f"truth file {truth.name}: not UTF-8 text (byte {exc.start})") from None
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise ValueError(f"truth file {truth.name}: not a readable CSV file ({str(exc).strip().splitlines()[-1]})") from None
    missing = [c for c in ("feature", "east_m", "north_m", "up_m") if c not in table.columns]
    if missing:
        raise ValueError(f"truth file {truth.name}: missing column(s) {missing}; the header has {list(table.columns)}")
    for c in ("east_m", "north_m", "up_m"):
        values = pd.to_numeric(table[c], errors="coerce")
        bad = ~np.isfinite(values.to_numpy(float))
        if bad.any():
            raise ValueError(f"truth file {truth.name} row {int(np.flatnonzero(bad)[0]) + 1}, column {c}: "
                             f"must be a finite number of metres; got {table[c].iloc[int(np.flatnonzero(bad)[0])]!r}")
        table[c] = values.astype(float)
    if table["feature"].duplicated().any():
        raise ValueError(f"truth file {truth.name}: feature {table['feature'][table['feature'].duplicated()].iloc[0]!r} "
                         "appears twice")
    return table.astype({"feature": str})
