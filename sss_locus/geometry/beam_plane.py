"""The beam-plane constraint: how far a feature lies out of the plane of the ping that saw it.

A sidescan beam is wide across track (the azimuth fan, the sensor frame's ``x``-``y`` plane of
:class:`~sss_locus.geometry.aperture.Aperture`) and narrow along track (the elevation beam,
0.27-0.5 deg full width). The ping that saw a feature therefore puts it, to within half that
width, in the plane through the sensor origin ``o`` spanned by the sensor's ``x`` and ``y`` axes,
whose normal is the sensor's ``z`` axis ``u`` (world frame, third column of the sensor axes
``W``). The measured quantity is the feature's *beam-plane angle*, its elevation in the sensor
frame,

    phi(p) = asin(u . (p - o) / |p - o|),        measured value 0,

with gradient ``d phi / d p = (u - sin(phi) d) / (|p - o| cos(phi))`` (``d`` the unit line of
sight ``(p - o) / |p - o|``), and ``d phi / d o = -d phi / d p``. The slant range alone leaves
the feature anywhere on a sphere; the range and the beam-plane angle leave it on a circle in
the beam plane: the constraint the flat-seafloor mosaic uses along track (it places the
feature in the ping's plane) and the range-only N-view least squares ignores.

Its standard deviation (:func:`beam_plane_sigma_rad`): the feature is anywhere inside the beam,
modelled as uniform over the full elevation width ``b`` (standard deviation ``b / sqrt(12)``,
i.e. the half width over ``sqrt(3)``), plus the attitude errors that tilt the plane: a heading
error turns ``u`` about the vertical, a pitch error about the across-track horizontal, a roll
error about ``u`` itself (it leaves the plane in place). For a feature seen at depression angle
``beta`` below the horizontal in the plane, a heading error ``dh`` moves ``phi`` by
``dh cos(beta)`` and a pitch error ``dp`` by ``dp sin(beta)``; the two add in quadrature.
"""

from __future__ import annotations

import numpy as np

from .validation import as_float_array


def beam_plane_angle(points, origins, W) -> tuple[np.ndarray, np.ndarray]:
    """Beam-plane angle of each feature in the sensor frame of its sighting, and its gradient.

    Parameters
    ----------
    points : array_like, shape (..., 3)
        Feature positions, world frame, metres.
    origins : array_like, shape (..., 3)
        Sensor origins of the sightings, same frame, metres.
    W : array_like, shape (..., 3, 3)
        Sensor axes in the world frame (columns: the sensor's ``x``, ``y``, ``z``; ``z`` is the
        normal of the beam plane, along track).

    Returns
    -------
    phi_rad : ndarray, shape (...)
        ``asin(u . (p - o) / |p - o|)``, radians, in [-pi/2, pi/2]; 0 where ``p = o``.
    gradient : ndarray, shape (..., 3)
        ``d phi / d p``, rad/m (the gradient with respect to the origin is its negative); zero
        where ``p = o`` and finite at ``|phi| = pi/2``.

    Raises
    ------
    ValueError
        Naming the argument: non-finite values or wrong trailing shapes.
    """
    p = as_float_array(points, "points", tail=(3,))
    o = as_float_array(origins, "origins", tail=(3,))
    u = as_float_array(W, "W", tail=(3, 3))[..., :, 2]
    d = p - o
    r = np.sqrt(np.sum(d * d, axis=-1))
    rs = np.where(r > 0, r, 1.0)
    s = np.clip(np.sum(u * d, axis=-1) / rs, -1.0, 1.0)
    c = np.sqrt(np.maximum(1.0 - s * s, 0.0))
    phi = np.where(r > 0, np.arcsin(s), 0.0)
    grad = (u - s[..., None] * d / rs[..., None]) / (rs * np.maximum(c, 1e-12))[..., None]
    return phi, np.where((r > 0)[..., None], grad, 0.0)


def beam_plane_sigma_rad(elevation_deg, heading_sigma_deg=0.0, pitch_sigma_deg=0.0, depression_deg=45.0) -> np.ndarray:
    """Standard deviation of the beam-plane angle (module docstring), radians.

    Parameters
    ----------
    elevation_deg : float or array_like
        FULL elevation (along-track) beam width, degrees, > 0 (``Aperture.elevation_deg``).
    heading_sigma_deg, pitch_sigma_deg : float or array_like
        Standard deviations of the per-ping heading and pitch errors, degrees, >= 0 (an error
        shared by a whole pass and estimated as an unknown belongs in neither).
    depression_deg : float or array_like
        Angle of the feature below the horizontal as seen from the sensor, degrees (``asin`` of
        height over slant range); default 45.

    Returns
    -------
    ndarray
        ``sqrt((elevation / sqrt(12))^2 + (heading cos(beta))^2 + (pitch sin(beta))^2)`` in
        radians, broadcast over the inputs.

    Raises
    ------
    ValueError
        Naming the argument: a beam width <= 0, a negative sigma, a non-finite value.
    """
    b = as_float_array(elevation_deg, "elevation_deg")
    if np.any(b <= 0):
        raise ValueError(f"elevation_deg must be > 0; got {elevation_deg!r}")
    h = as_float_array(heading_sigma_deg, "heading_sigma_deg")
    pt = as_float_array(pitch_sigma_deg, "pitch_sigma_deg")
    for name, a in (("heading_sigma_deg", h), ("pitch_sigma_deg", pt)):
        if np.any(a < 0):
            raise ValueError(f"{name} must be >= 0; got {a!r}")
    beta = np.radians(as_float_array(depression_deg, "depression_deg"))
    return np.radians(np.sqrt(b * b / 12.0 + (h * np.cos(beta)) ** 2 + (pt * np.sin(beta)) ** 2))
