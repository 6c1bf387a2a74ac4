"""A user's sightings to per-feature results: the two-view locus, the N-view position and the
flat-seafloor (slant-range corrected) positions, batched over features (numbers only).

Frames: the local frame of :mod:`sss_locus.experiments.sonar_files.observations` (``x`` grid east, ``y``
grid north, ``z`` up, metres; ``z = -depth``). A sighting's vehicle pose is its reference point
``(east_m, north_m, -depth_m)`` with ``yaw = 90 deg - grid heading`` (the platforms' yaw is
counter-clockwise from ``+x``), ``pitch_deg`` and ``roll_deg``; its sensor pose is the
platform's transducer on that side (:meth:`~sss_locus.experiments.datamodel.platforms.Transducer.world_pose`),
and the transducer's height above the seafloor is ``altitude_m`` plus the transducer's height
above the reference point.

Per feature (sightings in file order; **data association is the user's**):

``flat``
    every sighting's slant-range corrected position on a flat seafloor at the transducer's
    height (:func:`~sss_locus.geometry.slant_range.flat_seafloor_points`), their mean, and their
    *spread*: the largest horizontal distance between two of them (what a mosaic of the lines
    would disagree by);
``two``
    with two or more sightings, the locus of the best pair
    (:func:`~sss_locus.experiments.your_pings.views.best_pairs`: the two lines of sight most
    different at the mean flat position; ``two_view_pair`` names the pair's sightings, 1-based
    in file order) (:func:`~sss_locus.geometry.locus.two_view_locus` with the platform's aperture and, with
    ``sea_surface``, cropped to the water below the sea surface ``z = 0``): its arcs
    as points, total length and number of arcs, and the point of it nearest the mean of the two
    flat positions (:func:`~sss_locus.geometry.slant_range.two_view_points`, as the
    reconstruction chapter's two-view estimator);
``nview``
    with three or more, :func:`~sss_locus.geometry.multiview_points.multiview_points` on all
    sightings (prior the mean flat position; apertures widened by ``aperture_margin_deg``;
    with ``below_sensors`` only points below the lowest sensor are admitted), its status and
    covariance ``(J^T J)^-1`` from the range standard deviations alone (navigation and attitude
    errors are not in it; columns ``cov_<a>_<b>_m2``), also as 1-sigma horizontal ellipse axes
    and a vertical sigma;
``flat_minus_estimate``
    the mean flat-seafloor position minus the best estimate (N views where estimated, else the
    two-view point where the locus is not empty; NaN otherwise), horizontal distance and height:
    how wrong the mosaic is, if the geometry is right.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from sss_locus.geometry import sea_surface_half_space
from sss_locus.geometry.multiview_points import multiview_points
from sss_locus.geometry.slant_range import flat_seafloor_points, two_view_points
from sss_locus.experiments.your_pings import views
from sss_locus.experiments.sonar_files.observations import LocalFrame
from sss_locus.experiments.reconstruction.estimators import STATUS_NAMES

TWO_VIEW_NAMES = ("locus", "empty locus: circle point", "empty locus: sphere point")
"""``two_view_status``: the point lies on the non-empty locus, or (the locus is empty: the two
sightings do not agree within the beams) the fallback point on the circle or sphere."""


@dataclass(frozen=True)
class PingResults:
    """What :func:`analyse` returns (tables in the local frame, metres; lon/lat when a frame)."""

    features: pd.DataFrame
    sightings: pd.DataFrame
    locus: pd.DataFrame
    frame: LocalFrame | None
    excluded: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(
        columns=["feature", "where", "slant_range_m", "transducer_height_m", "reason"]))
    """Sightings set aside, each named (:mod:`~sss_locus.experiments.your_pings.views`)."""


def sensor_poses(table: pd.DataFrame, platform) -> dict:
    """World sensor axes ``W`` (m, 3, 3), origins (m, 3), the ranges and the transducers' heights
    above the seafloor (m,) of every sighting (module docstring).

    Parameters
    ----------
    table : pandas.DataFrame
        Sightings in the local frame (``east_m``, ``north_m``, ``depth_m``, ``grid_heading_deg``,
        ``pitch_deg``, ``roll_deg``, ``side``, ``altitude_m``, ``slant_range_m``), m rows.
    platform : Platform
        The platform (its transducers' poses on the vehicle).

    Returns
    -------
    dict
        ``W`` (m, 3, 3) sensor-to-world rotations (world ENU, up = -depth), ``origin`` (m, 3)
        transducer positions in m, ``ranges`` (m,) slant ranges in m, ``height`` (m,) transducer
        heights above the seafloor in m (negative when the altitude puts it below).
    """
    ref = np.stack([table["east_m"], table["north_m"], -table["depth_m"].to_numpy(float)], -1).astype(float)
    yaw = 90.0 - table["grid_heading_deg"].to_numpy(float)
    W = np.empty((len(table), 3, 3))
    o = np.empty((len(table), 3))
    for side, tr in platform.transducers.items():
        rows = (table["side"] == side).to_numpy()
        W[rows], o[rows] = tr.world_pose(ref[rows], yaw[rows], table["pitch_deg"].to_numpy(float)[rows],
                                         table["roll_deg"].to_numpy(float)[rows])
    height = table["altitude_m"].to_numpy(float) + o[:, 2] - ref[:, 2]
    return dict(W=W, origin=o, ranges=table["slant_range_m"].to_numpy(float), height=height)


def _squeeze(loc):
    """A locus result of shape (n, 1) as one of shape (n,)."""
    import dataclasses

    return dataclasses.replace(loc, **{f.name: getattr(loc, f.name)[:, 0] for f in dataclasses.fields(loc)
                                        if isinstance(getattr(loc, f.name), np.ndarray)})


def ellipse_axes(cov):
    """1-sigma horizontal ellipse (semi-major, semi-minor, azimuth of the major axis clockwise
    from grid north, deg) and vertical sigma of covariances (n, 3, 3); NaN where not finite.

    Parameters
    ----------
    cov : numpy.ndarray
        Covariances, shape (n, 3, 3), m², world ENU.

    Returns
    -------
    major, minor : numpy.ndarray
        Semi-axes, m, shape (n,).
    azimuth : numpy.ndarray
        Major-axis azimuth, degrees clockwise from grid north in [0, 180), shape (n,).
    sigma_up : numpy.ndarray
        Vertical 1-sigma, m, shape (n,). NaN in all four where ``cov`` is not finite.
    """
    ok = np.all(np.isfinite(cov), axis=(1, 2))
    h = np.where(ok[:, None, None], cov[:, :2, :2], np.eye(2))
    val, vec = np.linalg.eigh(h)
    major = vec[:, :, 1]
    nan = lambda a: np.where(ok, a, np.nan)  # noqa: E731
    return (nan(np.sqrt(np.maximum(val[:, 1], 0))), nan(np.sqrt(np.maximum(val[:, 0], 0))),
            nan(np.mod(np.degrees(np.arctan2(major[:, 0], major[:, 1])), 180.0)),
            nan(np.sqrt(np.maximum(np.where(ok, cov[:, 2, 2], 0), 0))))


def analyse(table: pd.DataFrame, platform, frame: LocalFrame | None = None, *,
            aperture_margin_deg: float = 2.0, below_sensors: bool = True, sea_surface: bool = True,
            n_arc_points: int = 33) -> PingResults:
    """Per-feature results for a validated sightings table in the local frame
    (:func:`~sss_locus.experiments.sonar_files.observations.to_local_frame`); see the module docstring.

    Parameters
    ----------
    table : pandas.DataFrame
        Validated sightings in the local frame (east/north metres, grid headings).
    platform : Platform
        The platform that recorded them.
    frame : LocalFrame or None
        The local frame; given, longitude/latitude columns are added to the results.
    aperture_margin_deg : float
        Margin added to the beam aperture in the N-view estimate, degrees (>= 0).
    below_sensors : bool
        Keep the N-view estimate below the shallowest sensor of the feature.
    sea_surface : bool
        Crop the two-view locus to below the sea surface (z = 0).
    n_arc_points : int
        Points per locus arc in ``locus`` (>= 2).

    Returns
    -------
    PingResults
        ``features`` (one row per feature, world ENU metres), ``sightings`` (the table with sensor
        and flat-seafloor positions), ``locus`` (arc points), ``frame`` and ``excluded``
        (sightings set aside).

    Raises
    ------
    ValueError
        A bad keyword, or every sighting set aside.
    """
    if not (np.isfinite(aperture_margin_deg) and aperture_margin_deg >= 0):
        raise ValueError(f"aperture_margin_deg must be a finite number >= 0; got {aperture_margin_deg!r}")
    if int(n_arc_points) < 2:
        raise ValueError(f"n_arc_points must be an integer >= 2; got {n_arc_points!r}")
    pose = sensor_poses(table, platform)
    bad = views.impossible(pose["ranges"], pose["height"])
    excluded = views.excluded_table(table, pose["height"], bad)
    if bad.all():
        raise ValueError("no sighting left: " + views.excluded_sentence(excluded))
    if bad.any():
        table = table[~bad].reset_index(drop=True)
        pose = sensor_poses(table, platform)
    names, fid = np.unique(table["feature"].to_numpy(str), return_inverse=True)
    first = pd.Series(np.arange(len(table))).groupby(fid).min().to_numpy()
    order = np.argsort(first, kind="stable")  # features in order of their first sighting
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    fid = rank[fid]
    names = names[order]
    n = names.size
    slot = pd.Series(fid).groupby(fid).cumcount().to_numpy()
    K = max(int(slot.max()) + 1, 2)  # two view slots at least: the two-view step reads a pair
    mask = np.zeros((n, K), bool)
    mask[fid, slot] = True
    aperture = platform.sonar.aperture()

    def grid(a, fill=0.0):
        out = np.full((n, K) + a.shape[1:], fill, float)
        out[fid, slot] = a
        return out

    W = grid(pose["W"])
    W[~mask] = np.eye(3)
    o, r, sig = grid(pose["origin"]), grid(pose["ranges"], 1.0), grid(table["range_sigma_m"].to_numpy(float), 1.0)
    flat = flat_seafloor_points(pose["W"], pose["origin"], pose["ranges"], np.maximum(pose["height"], 0.0))
    fp = grid(flat["point"])
    count = mask.sum(axis=1)
    mean_flat = np.einsum("nki,nk->ni", fp, mask) / count[:, None]
    dh = np.linalg.norm(fp[:, :, None, :2] - fp[:, None, :, :2], axis=-1)
    spread = np.max(np.where(mask[:, :, None] & mask[:, None, :], dh, 0.0), axis=(1, 2))

    # two views: the best pair of each feature's sightings (your_pings_views.best_pairs)
    def pair_loci(i, j):  # the loci of the pairs of slots (i, j), cropped to the water
        Wi, oi = W[np.arange(n)[:, None], i], o[np.arange(n)[:, None], i]
        hs = {}
        if sea_surface:  # the locus is cropped to the water: below the sea surface z = 0
            normals, offsets = sea_surface_half_space(np.maximum(-oi[..., 2], 0.0), Wi)
            hs = dict(half_space_normals=normals, half_space_offsets=offsets)
        k = np.arange(n)[:, None]
        return Wi, oi, two_view_points(Wi, oi, W[k, j], o[k, j], r[k, i], r[k, j], 0.5 * (fp[k, i] + fp[k, j]),
                                       aperture, aperture, **hs)

    a, b = views.pair_slots(K)
    every = pair_loci(np.broadcast_to(a, (n, a.size)), np.broadcast_to(b, (n, b.size)))[2][0]
    pi, pj, has2 = views.best_pairs(o, mean_flat, mask, np.nan_to_num(every.length))
    W1, o1, (loc, near, two) = pair_loci(pi[:, None], pj[:, None])
    W1, o1, two = W1[:, 0], o1[:, 0], two[:, 0]
    loc, near = _squeeze(loc), {k: v[:, 0] for k, v in near.items()}

    # N views: every sighting of each feature with three or more
    res = multiview_points(W, o, r, sig, mask, aperture, prior=mean_flat, aperture_margin_deg=aperture_margin_deg,
                           ceiling_m=np.min(np.where(mask, o[..., 2], np.inf), axis=1) if below_sensors else np.inf)
    major, minor, azimuth, sigma_up = ellipse_axes(np.where(res.estimated[:, None, None], res.covariance, np.nan))
    nview = np.where(res.estimated[:, None], res.point, np.nan)

    feats = pd.DataFrame({"feature": names, "n_sightings": count,
                          "flat_east_m": mean_flat[:, 0], "flat_north_m": mean_flat[:, 1], "flat_up_m": mean_flat[:, 2],
                          "flat_spread_m": spread,
                          "two_view_status": np.where(has2, np.array(TWO_VIEW_NAMES)[near["status"]], views.ONE_SIGHTING),
                          "two_view_pair": np.where(has2, [f"{a + 1}+{b + 1}" for a, b in zip(pi, pj)], ""),
                          "locus_length_m": np.where(has2, loc.length, np.nan),
                          "locus_arcs": np.where(has2, loc.n_arcs, 0)})
    for j, axis in enumerate(("east", "north", "up")):
        feats[f"two_view_{axis}_m"] = np.where(has2, two[:, j], np.nan)
    feats["nview_status"] = np.where(count >= 2, [STATUS_NAMES[int(s)] for s in res.status], views.ONE_SIGHTING)
    for j, axis in enumerate(("east", "north", "up")):
        feats[f"nview_{axis}_m"] = nview[:, j]
    feats["nview_cost"] = np.where(res.estimated, res.cost, np.nan)
    cov = np.where(res.estimated[:, None, None], res.covariance, np.nan)
    for (i, a), (j, b) in ((ia, jb) for ia in enumerate(("east", "north", "up")) for jb in enumerate(("east", "north", "up"))):
        if j >= i:  # the covariance's six entries, m^2
            feats[f"cov_{a}_{b}_m2"] = cov[:, i, j]
    feats["ellipse_major_m"], feats["ellipse_minor_m"] = major, minor
    feats["ellipse_azimuth_deg"], feats["sigma_up_m"] = azimuth, sigma_up
    # the best estimate: N views where estimated, else the two-view point where it lies on a
    # non-empty locus (an empty locus means the two sightings do not agree within the beams)
    on_locus = has2 & (near["status"] == 0)
    best = np.where(res.estimated[:, None], nview, np.where(on_locus[:, None], two, np.nan))
    feats["flat_minus_estimate_h_m"] = np.hypot(*(mean_flat[:, :2] - best[:, :2]).T)
    feats["flat_minus_estimate_up_m"] = mean_flat[:, 2] - best[:, 2]

    sights = table.assign(feature_index=fid, view=slot, sensor_east_m=pose["origin"][:, 0],
                          sensor_north_m=pose["origin"][:, 1], sensor_up_m=pose["origin"][:, 2],
                          transducer_height_m=pose["height"], flat_east_m=flat["point"][:, 0],
                          flat_north_m=flat["point"][:, 1], flat_up_m=flat["point"][:, 2],
                          flat_below_altitude=flat["below_altitude"])
    locus = locus_points(loc, W1, o1, names, has2, int(n_arc_points))
    if frame is not None:
        for tab, pre in ((feats, "flat"), (feats, "two_view"), (feats, "nview"), (sights, "flat"), (sights, "sensor"),
                         (locus, "")):
            e, nn = (f"{pre}_east_m" if pre else "east_m"), (f"{pre}_north_m" if pre else "north_m")
            lon, lat = frame.to_lonlat(tab[e], tab[nn])
            tab[e.replace("east_m", "lon_deg")] = np.where(np.isfinite(tab[e]), lon, np.nan)
            tab[nn.replace("north_m", "lat_deg")] = np.where(np.isfinite(tab[nn]), lat, np.nan)
    return PingResults(features=feats, sightings=sights, locus=locus, frame=frame, excluded=excluded)


def read_checked(path, platform=None, *, missing_attitude: str = "refuse", range_sigma_m: float = 0.1,
                 sample_order: str = "detect", towfish: str = "auto"):
    """The validated sightings of a CSV or XTF matches file
    (:func:`~sss_locus.experiments.sonar_files.observations_xtf.read_observations`) and the platform they
    name (default: the file's platform key, from the data files); a slant range outside the
    sonar's range limits is refused naming its line. ``sample_order`` and ``towfish``: how an
    XTF file's channels and positions are read (:mod:`~sss_locus.experiments.sonar_files.sample_order`,
    :mod:`~sss_locus.experiments.sonar_files.towfish`). Returns ``(table, platform)``.

    Parameters
    ----------
    path : str or os.PathLike
        A sightings CSV or an XTF matches file.
    platform : Platform or None
        The platform; ``None`` loads the file's platform key.
    missing_attitude : str
        ``"refuse"`` or ``"level"``.
    range_sigma_m : float
        Default slant-range standard deviation, m.
    sample_order : str
        How XTF channels are ordered (``"detect"``, ...).
    towfish : str
        How XTF positions are read (``"auto"``, ...).

    Returns
    -------
    table : pandas.DataFrame
        The sightings (positions as in the file).
    platform : Platform
        The platform.

    Raises
    ------
    ValueError
        An unknown or mismatched platform, a slant range outside the sonar's limits, or no
        sighting with a flat-seafloor position.
    """
    from sss_locus.experiments.sonar_files.observations_xtf import read_observations

    table = read_observations(path, missing_attitude=missing_attitude, range_sigma_m=range_sigma_m,
                              sample_order=sample_order, towfish=towfish)
    key, where = table["platform"].iloc[0], f"{Path(path).name} line {table['line'].iloc[0]}, column platform"
    if platform is None:  # only this platform's data entries are read (a run is stale only when they change)
        from sss_locus.experiments.datamodel.platforms import load_platform

        try:
            platform = load_platform(key)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc} (add yours with --data)") from None
    elif key != platform.key:
        raise ValueError(f"{where}: the run's platform is {platform.key!r}; got {key!r}")
    sonar = platform.sonar
    out = table[(table["slant_range_m"] > sonar.max_range_m) | (table["slant_range_m"] < sonar.min_range_m)]
    if len(out):
        r = out.iloc[0]
        how = "beyond the sonar's maximum" if r["slant_range_m"] > sonar.max_range_m else "below the sonar's minimum"
        raise ValueError(f"{Path(path).name} line {r['line']}: slant range {r['slant_range_m']:.6g} m is {how} range: "
                         f"{platform.key!r} ({sonar.name}) sees [{sonar.min_range_m:g}, {sonar.max_range_m:g}] m "
                         f"(sonars.{sonar.key} in the data files)")
    from sss_locus.experiments.sonar_files.observations import to_local_frame

    pose = sensor_poses(to_local_frame(table)[0], platform)
    bad = views.impossible(pose["ranges"], pose["height"])
    if bad.all():
        raise ValueError(f"{Path(path).name}: no sighting left: "
                         + views.excluded_sentence(views.excluded_table(table, pose["height"], bad)))
    return table, platform


def run(path, platform=None, origin: LocalFrame | None = None, *, missing_attitude: str = "refuse",
        range_sigma_m: float = 0.1, sample_order: str = "detect", towfish: str = "auto", **kw) -> PingResults:
    """Read a sightings CSV or an XTF matches file and check it (:func:`read_checked`), put it in
    the local frame, move towed sensors back by their layback
    (:func:`~sss_locus.experiments.sonar_files.towfish.apply_layback`) and :func:`analyse` it with
    ``platform`` (default: the file's platform key).

    Parameters
    ----------
    path : str or os.PathLike
        A sightings CSV or an XTF matches file.
    platform : Platform or None
        The platform; ``None`` loads the file's platform key.
    origin : LocalFrame or None
        The local frame; ``None``: the sightings' mean position.
    missing_attitude : str
        ``"refuse"`` or ``"level"``.
    range_sigma_m : float
        Default slant-range standard deviation, m.
    sample_order : str
        How XTF channels are ordered.
    towfish : str
        How XTF positions are read.
    **kw
        Keywords of :func:`analyse`.

    Returns
    -------
    PingResults
        :func:`analyse`'s results.
    """
    from sss_locus.experiments.sonar_files.observations import to_local_frame
    from sss_locus.experiments.sonar_files.towfish import apply_layback

    table, platform = read_checked(path, platform, missing_attitude=missing_attitude, range_sigma_m=range_sigma_m,
                                   sample_order=sample_order, towfish=towfish)
    table, frame = to_local_frame(table, origin)
    table = apply_layback(table)
    return analyse(table, platform, frame, **kw)


def locus_points(loc, W1, o1, names, has2, n_points: int) -> pd.DataFrame:
    """Points along every arc of the loci (``n_points`` per arc, ends included), world frame:
    columns ``feature``, ``arc``, ``east_m``, ``north_m``, ``up_m``.

    Parameters
    ----------
    loc : Locus
        The best-pair loci, n features, arcs in the first sensor's frame.
    W1 : numpy.ndarray
        First sensor's rotation to world, shape (n, 3, 3).
    o1 : numpy.ndarray
        First sensor's origin, world, m, shape (n, 3).
    names : numpy.ndarray
        Feature names, shape (n,).
    has2 : numpy.ndarray
        Boolean (n,): the feature has a pair.
    n_points : int
        Points per arc (>= 2).

    Returns
    -------
    pandas.DataFrame
        ``n_points`` rows per arc, columns ``feature``, ``arc``, ``east_m``, ``north_m``,
        ``up_m`` (world ENU, m); empty when no locus has an arc.
    """
    s = np.linspace(0.0, 1.0, n_points)
    ok = ~np.isnan(loc.arc_start) & has2[:, None]
    start, end = np.where(ok, loc.arc_start, 0.0), np.where(ok, loc.arc_end, 0.0)
    alpha = start[..., None] + (end - start)[..., None] * s  # (n, W, P)
    p1 = loc.point_at(alpha.reshape(len(names), -1)).reshape(alpha.shape + (3,))
    pw = np.einsum("nij,nwpj->nwpi", W1, p1) + o1[:, None, None, :]
    f, a = np.nonzero(ok)
    pw = pw[f, a]
    return pd.DataFrame({"feature": np.repeat(names[f], n_points), "arc": np.repeat(a, n_points),
                         "east_m": pw[..., 0].ravel(), "north_m": pw[..., 1].ravel(), "up_m": pw[..., 2].ravel()})
