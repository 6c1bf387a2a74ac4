"""The worked example of the your-pings chapter: SYNTHETIC sightings of features on a known
terrain, made by the project's own survey simulator
(:func:`~sss_locus.experiments.reconstruction.terrain_survey.observe_features`), written as a sightings CSV,
an XTF file with its matches, and the true positions.

The survey is the reconstruction chapter's layout (``data/terrain.toml``) over a terrain of
that file; every (feature, line) pair that sees the feature is one sighting at its exact in-beam
ping. The simulator's frame (``x`` east, ``y`` north, ``z`` up, mean seafloor ``z = 0``) is
taken as the grid of a local transverse-Mercator frame around ``origin`` and shifted down so
that the sea surface is ``z = 0`` (the water depth is ``surface_m`` above the mean seafloor).
Navigation is then perturbed with the platform's noise model (``data/noise.toml``; ``noise=False``
for exact sightings): the horizontal position and heading by the per-pass model of
:mod:`~sss_locus.experiments.passes.pass_noise` (an offset, a drift along the line and a heading bias
shared by every sighting of one line, plus a per-ping jitter), depth, pitch, roll and range per
sighting, the range is turned into a sample index of a ping of ``n_samples``
samples over the sonar's maximum range, and angles, depth and altitude are rounded to float32
as an XTF file stores them, so that the CSV and the XTF file hold the same numbers.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.sonar_files.observations import LocalFrame
from sss_locus.experiments.passes.straight_pass import attitude_angles
from sss_locus.experiments.datamodel.terrain import place_features
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features

NOTICE = ("SYNTHETIC example made by sss-locus (experiments/your_pings/example.py) over a known "
          "simulated terrain; not a real survey")


def simulate(platform, terrain, layout: SurveyLayout, *, n_features: int, altitude_m: float, seed: int,
             frame: LocalFrame, noise: bool = True, n_samples: int = 1000, surface_m: float | None = None,
             float32: bool = True):
    """Sightings (the CSV columns, numbers) and the truth of a simulated survey.

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    terrain : Terrain
        The seafloor (local metres).
    layout : SurveyLayout
        The survey's lines and area.
    n_features : int
        Features placed on the seafloor.
    altitude_m : float
        Altitude flown, m.
    seed : int
        Seed of features, observations and noise.
    frame : LocalFrame
        The local frame (gives longitude/latitude and the meridian convergence).
    noise : bool
        Add the platform's noise (navigation per line and per ping, attitude, range).
    n_samples : int
        Samples per ping (range quantisation).
    surface_m : float or None
        Height of the sea surface in the terrain's frame, m; ``None``: the shallowest vehicle
        position (plus the depth rating's minimum for a vehicle that dives).
    float32 : bool
        Round the recorded fields to float32 as XTF stores them.

    Returns
    -------
    sightings : pandas.DataFrame
        ``feature``, ``platform``, ``side``, ``lon_deg``, ``lat_deg``, ``depth_m``,
        ``altitude_m``, ``heading_deg``, ``pitch_deg``, ``roll_deg``, ``sample``,
        ``range_setting_m``, ``n_samples``, ``range_sigma_m``, ``time_s``; and, for checks, the
        grid ``east_m``, ``north_m`` and ``grid_heading_deg`` the longitude, latitude and
        heading were made from, and the ``slant_range_m`` before quantisation (with
        ``float32=False`` nothing is rounded to float32).
    truth : pandas.DataFrame
        ``feature``, ``east_m``, ``north_m``, ``up_m`` (local frame, sea surface ``up = 0``).
    """
    rng = np.random.default_rng(seed)
    feats = place_features(terrain, int(n_features), layout.area_m, seed)
    views, seen, info = observe_features(platform, terrain, feats, layout, altitude_m,
                                         platform.fixed_depth, seed)
    f, line = np.nonzero(seen)
    V = views.vehicle[f, line]
    W = views.W[f, line]
    port = np.einsum("mi,mi->m", W[:, :, 0], V[:, :, 1]) > 0  # boresight toward the vehicle's port
    tr = np.array([platform.transducers["port" if p else "starboard"].position_m for p in port])
    ref = views.origin[f, line] - np.einsum("mij,mj->mi", V, tr)
    yaw, pitch, roll = attitude_angles(_rotation(V))
    top = float(ref[:, 2].max()) if surface_m is None else float(surface_m)
    if surface_m is None and not platform.fixed_depth:
        top += platform.depth_min_m
    altitude = ref[:, 2] - terrain.height_m(ref[:, 0], ref[:, 1])
    r = r_true = np.linalg.norm(views.feature[f] - views.origin[f, line], axis=-1)
    m = f.size
    nm = load_noise_model(platform.key) if noise else None
    if nm is not None:  # navigation errors as a survey has them: shared by every ping of a line
        pn = load_pass_noise(platform.key)
        g = rng.standard_normal((seen.shape[1], 5))  # per line: offset (2), drift rate (2), heading bias
        along = info["along_m"][f, line]
        shared = g[line, 0:2] * pn.pass_offset_sigma_m + along[:, None] * g[line, 2:4] * pn.drift_sigma_fraction
        ref = ref + np.column_stack([shared + rng.standard_normal((m, 2)) * pn.ping_horizontal_sigma_m,
                                     rng.standard_normal(m) * nm.vertical_sigma_m])
        yaw = yaw + g[line, 4] * pn.pass_heading_bias_sigma_deg + rng.standard_normal(m) * pn.ping_heading_sigma_deg
        pitch = pitch + rng.standard_normal(m) * nm.pitch_sigma_deg
        roll = roll + rng.standard_normal(m) * nm.roll_sigma_deg
        r = r + rng.standard_normal(m) * nm.range_sigma_m(r)
    R = platform.sonar.max_range_m
    sample = np.clip(np.floor(r / R * n_samples), 0, n_samples - 1).astype(np.int64)
    # effective range sigma: the range error, the sample's quantisation and the navigation error
    # along the line of sight (as the reconstruction chapter's N-view estimator uses)
    los = (views.feature[f] - views.origin[f, line]) / r_true[:, None]
    nav = 0.0 if nm is None else np.sqrt((nm.horizontal_sigma_m ** 2) * (los[:, 0] ** 2 + los[:, 1] ** 2)
                                         + (nm.vertical_sigma_m * los[:, 2]) ** 2 + nm.range_sigma_m(r_true) ** 2)
    sigma = np.hypot(nav, R / n_samples / np.sqrt(12.0))
    grid = np.mod(90.0 - yaw, 360.0)
    lon, lat = frame.to_lonlat(ref[:, 0], ref[:, 1])
    f32 = (lambda a: np.asarray(a, np.float32).astype(float)) if float32 else (lambda a: np.asarray(a, float))  # noqa: E731
    names = np.array([f"F{k + 1:02d}" for k in range(len(feats))])
    sights = pd.DataFrame({
        "feature": names[f], "platform": platform.key, "side": np.where(port, "port", "starboard"),
        "lon_deg": lon, "lat_deg": lat, "depth_m": f32(top - ref[:, 2]), "altitude_m": f32(altitude),
        "heading_deg": f32(np.mod(grid + frame.convergence_deg(lon, lat), 360.0)), "pitch_deg": f32(pitch),
        "roll_deg": f32(roll), "sample": sample, "range_setting_m": f32(R), "n_samples": int(n_samples),
        "range_sigma_m": np.round(sigma, 4), "time_s": 36000.0 + 60.0 * line + f,
        "east_m": ref[:, 0], "north_m": ref[:, 1], "grid_heading_deg": grid, "slant_range_m": r})
    order = np.lexsort((names[f], sights["time_s"].to_numpy()))
    sights = sights.iloc[order].reset_index(drop=True)
    truth = pd.DataFrame({"feature": names, "east_m": feats[:, 0], "north_m": feats[:, 1], "up_m": feats[:, 2] - top})
    return sights, truth


def _rotation(V):
    from scipy.spatial.transform import Rotation

    return Rotation.from_matrix(V)


def xtf_tables(sights: pd.DataFrame, file_name: str, port_order: str = "far_first") -> tuple[pd.DataFrame, pd.DataFrame]:
    """One XTF ping per sighting (the return drawn at its sample on its side), and the matches
    table that names it: ``(pings, matches)`` for
    :func:`~sss_locus.experiments.sonar_files.observations_xtf.write_xtf` (with the same ``port_order``)
    and the matches CSV, whose ``sample`` is the index as stored (a port sample of a
    far-to-near channel counted from the far end).

    Parameters
    ----------
    sights : pandas.DataFrame
        :func:`simulate`'s sightings.
    file_name : str
        The XTF file's name written into the matches.
    port_order : str
        ``"far_first"`` or ``"near_first"``.

    Returns
    -------
    pings : pandas.DataFrame
        One row per ping for ``write_xtf``.
    matches : pandas.DataFrame
        ``feature``, ``platform``, ``file``, ``ping``, ``channel``, ``sample``, ``range_sigma_m``.
    """
    k = np.arange(len(sights))
    port = (sights["side"] == "port").to_numpy()
    pings = sights[["lon_deg", "lat_deg", "depth_m", "altitude_m", "heading_deg", "pitch_deg", "roll_deg",
                    "time_s", "range_setting_m", "n_samples"]].assign(
        ping=k, echo_port=np.where(port, sights["sample"], -1), echo_starboard=np.where(port, -1, sights["sample"]))
    matches = pd.DataFrame({"feature": sights["feature"], "platform": sights["platform"], "file": file_name,
                            "ping": k, "channel": np.where(port, 0, 1),
                            "sample": np.where(port & (port_order == "far_first"),
                                               sights["n_samples"] - 1 - sights["sample"], sights["sample"]),
                            "range_sigma_m": sights["range_sigma_m"]})
    return pings, matches


CHECK_COLUMNS = ("east_m", "north_m", "grid_heading_deg", "slant_range_m")
"""Columns of :func:`simulate` that a user's file does not have (the simulator's own values)."""


def write_csv(path, table: pd.DataFrame, notice: str = NOTICE) -> None:
    """A CSV file headed by a ``# notice`` comment line (floats written exactly).

    Parameters
    ----------
    path : str or os.PathLike
        The file written (overwritten).
    table : pandas.DataFrame
        The rows.
    notice : str
        The comment line's text.
    """
    from pathlib import Path

    Path(path).write_text(f"# {notice}\n" + table.to_csv(index=False))


def write_example(folder, platform, terrain, layout: SurveyLayout, *, frame: LocalFrame, name: str = "example",
                  **kw) -> dict:
    """Write the worked example into ``folder``: ``<name>_sightings.csv``, ``<name>.xtf``,
    ``<name>_xtf_matches.csv`` and ``<name>_truth.csv`` (each marked SYNTHETIC); return the
    paths. Keywords go to :func:`simulate`.

    Parameters
    ----------
    folder : str or os.PathLike
        Where the files go (created).
    platform : Platform
        The platform.
    terrain : Terrain
        The seafloor.
    layout : SurveyLayout
        The survey.
    frame : LocalFrame
        The local frame.
    name : str
        File name prefix.
    **kw
        Keywords of :func:`simulate`.

    Returns
    -------
    dict
        ``sightings``, ``xtf``, ``matches``, ``truth`` -> pathlib.Path.
    """
    from pathlib import Path

    from sss_locus.experiments.sonar_files.observations_xtf import write_xtf

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    sights, truth = simulate(platform, terrain, layout, frame=frame, **kw)
    paths = {k: folder / f"{name}{s}" for k, s in (("sightings", "_sightings.csv"), ("xtf", ".xtf"),
                                                    ("matches", "_xtf_matches.csv"), ("truth", "_truth.csv"))}
    write_csv(paths["sightings"], sights.drop(columns=list(CHECK_COLUMNS)))
    pings, matches = xtf_tables(sights, paths["xtf"].name)
    write_xtf(paths["xtf"], pings, note="SYNTHETIC: made by sss-locus over a simulated terrain")
    write_csv(paths["matches"], matches)
    write_csv(paths["truth"], truth, NOTICE + f"; true feature positions, local frame of lon0 {frame.lon0_deg} "
                                              f"lat0 {frame.lat0_deg}, up from the sea surface")
    return paths
