"""The flat-seafloor error of one view on a sloping seafloor, in closed form, and the same error
from the chapter's simulated survey (the reconstruction chapter's slope sweep).

Derivation (one view, vehicle level, sensor ``H`` above the seafloor point directly below it,
as an altimeter reads it; the seafloor a plane whose height rises by ``tan(beta)`` per metre of
horizontal distance from the sensor toward the feature, ``beta`` signed: negative where it falls
toward the feature). The feature lies ``y`` (>= 0) across track and ``a`` along track from the
sensor, so ``y tan(beta)`` above the point below the sensor, at slant range

    r^2 = y^2 + a^2 + (H - y tan(beta))^2 .

Slant-range correction puts it in the sonar's zero-elevation plane (the vertical plane across
track for a level vehicle), on a flat seafloor ``H`` below the sensor, at ground range

    y_hat = sqrt(r^2 - H^2) = sqrt(y^2 (1 + tan^2 beta) - 2 H y tan(beta) + a^2) ,

so its errors are ``y_hat - y`` across track, ``-a`` along track and ``-y tan(beta)``
vertically. For ``a = 0`` and small slopes ``y_hat - y ~ -H tan(beta) + y tan^2(beta) / 2``:
the across-track error is of the order of the altitude times the slope, the vertical error of
the ground range times the slope, i.e. most of the 3-D error at sidescan ranges.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.terrain import place_features, slope_terrain
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features
from sss_locus.experiments.reconstruction.study import survey_altitude_m
from sss_locus.geometry.slant_range import flat_seafloor_points


def flat_slope_error(ground_range_m, height_m, slope_deg, along_m=0.0) -> dict:
    """The closed form of the module docstring (all arguments broadcast; m and deg).

    Returns ``across_m`` (``y_hat - y``), ``vertical_m`` (``-y tan(beta)``) and ``error_3d_m``
    (the length of the error vector, along-track part ``-a`` included).

    Parameters
    ----------
    ground_range_m : array_like
        True ground range across track, m.
    height_m : array_like
        Sensor height above the seafloor under it, m.
    slope_deg : array_like
        Signed slope across track, degrees.
    along_m : array_like
        Along-track offset of the feature, m.

    Returns
    -------
    dict
        ``across_m``, ``vertical_m``, ``error_3d_m`` (m), each the broadcast shape.
    """
    y, H, a = (np.asarray(v, float) for v in (ground_range_m, height_m, along_m))
    t = np.tan(np.radians(np.asarray(slope_deg, float)))
    y_hat = np.sqrt(np.maximum(y * y * (1 + t * t) - 2 * H * y * t + a * a, 0.0))
    across, vertical = y_hat - y, -y * t
    return dict(across_m=across, vertical_m=vertical, error_3d_m=np.sqrt(across ** 2 + a * a + vertical ** 2))


def slope_views(platform, envelope, config: dict, slopes_deg, layout: SurveyLayout, *, n_features: int,
                seed: int) -> pd.DataFrame:
    """Noise-free single views on the plane of ``config["slope"]`` at each slope: for every view
    from a line running across the slope's rise (heading perpendicular to its azimuth), the
    simulated flat-seafloor error (:func:`~sss_locus.geometry.slant_range.flat_seafloor_points`
    on the survey's exact views) and the closed form from the view's true geometry.

    Returns one row per view: ``slope_deg``, ``simulated_across_m``, ``simulated_vertical_m``,
    ``simulated_3d_m``, ``closed_across_m``, ``closed_vertical_m``, ``closed_3d_m``.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    envelope : Envelope
        Its operating envelope (altitude flown).
    config : dict
        The terrain configuration (``slope.azimuth_deg``).
    slopes_deg : sequence of float
        Slopes, degrees.
    layout : SurveyLayout
        The survey's lines and area.
    n_features : int
        Features per slope.
    seed : int
        Seed of features and observations.

    Returns
    -------
    pandas.DataFrame
        One row per view (columns above, m); no row for a slope with no such view.
    """
    az = np.radians(config["slope"]["azimuth_deg"])
    rise = np.array([np.cos(az), np.sin(az)])
    frames = []
    for slope in slopes_deg:
        terrain = slope_terrain(float(slope), config["slope"]["azimuth_deg"])
        f = place_features(terrain, n_features, layout.area_m, seed)
        views, seen, info = observe_features(platform, terrain, f, layout, survey_altitude_m(envelope),
                                             envelope.same_altitude, seed + 1)
        h = np.radians(info["heading_deg"])
        across_lines = np.abs(np.cos(h) * rise[0] + np.sin(h) * rise[1]) < 1e-9
        use = seen & across_lines[None, :] & (info["sensor_height_m"] > 0)  # a sensor above its seafloor
        i, j = np.nonzero(use)
        o, W, H = views.origin[i, j], views.W[i, j], info["sensor_height_m"][i, j]
        r = np.linalg.norm(f[i] - o, axis=1)
        est = flat_seafloor_points(W, o, r, np.maximum(H, 0.0))["point"]
        rel = f[i, :2] - o[:, :2]
        fwd = np.stack([np.cos(h[j]), np.sin(h[j])], axis=1)
        along = np.einsum("ki,ki->k", rel, fwd)
        side = rel - along[:, None] * fwd
        y = np.linalg.norm(side, axis=1)
        u = side / np.maximum(y, 1e-12)[:, None]
        signed = np.degrees(np.arctan(np.tan(np.radians(slope)) * (u @ rise)))
        closed = flat_slope_error(y, H, signed, along)
        err = est - f[i]
        frames.append(pd.DataFrame(dict(
            slope_deg=float(slope), simulated_across_m=np.einsum("ki,ki->k", err[:, :2], u),
            simulated_vertical_m=err[:, 2], simulated_3d_m=np.linalg.norm(err, axis=1),
            closed_across_m=closed["across_m"], closed_vertical_m=closed["vertical_m"],
            closed_3d_m=closed["error_3d_m"])))
    return pd.concat(frames, ignore_index=True)
