"""What the joint adjustment is given: the sightings, the passes' navigation priors, and how a
pass's navigation correction moves its sensor poses.

Frames and units: one local world frame for everything, ``x`` east (or any horizontal axis),
``y`` north, ``z`` up, metres; angles in radians inside the solver, degrees in names ending
``_deg``.

A *pass* is a stretch of navigation whose error is shared by its pings (a survey line). Its
*correction* (true minus navigated) has up to five parameters, in this order
(:data:`CORRECTION_NAMES`):

``offset_x_m``, ``offset_y_m``
    a horizontal shift of every ping of the pass;
``heading_rad``
    a heading bias: every ping's sensor axes turned by it about the vertical; with
    ``heading_moves_track`` the pass's origins turn with it about the pass's reference point
    (a dead-reckoned track drawn with a wrong heading), otherwise only the axes turn (a track
    fixed by GNSS, a wrong compass);
``drift_x``, ``drift_y``
    a shift growing linearly along the pass, metres per metre of along-track position
    (dead-reckoning drift); estimated only where its prior sigma is > 0.

For sighting ``i`` on pass ``j`` with navigated origin ``o``, axes ``W``, along-track position
``s`` and the pass's reference point ``c`` (horizontal, ``z`` ignored), with ``R = Rz(heading)``::

    o_true = o + (offset_x, offset_y, 0) + s (drift_x, drift_y, 0)
             + [heading_moves_track] (R - I) (o - c)
    W_true = R W

The vertical is not corrected: depth from a pressure sensor (and a boat's waterline) is
absolute, and the ranges cannot see a common vertical shift of a pass and its features apart
from the seafloor's own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...geometry.validation import as_float_array

CORRECTION_NAMES = ("offset_x_m", "offset_y_m", "heading_rad", "drift_x", "drift_y")


def _int_array(value, name, n, upper):
    a = np.asarray(value)
    if a.shape != (n,) or not np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"{name} must be an integer array of shape ({n},); got {a.dtype} {a.shape}")
    if n and (a.min() < 0 or (upper is not None and a.max() >= upper)):
        raise ValueError(f"{name} must lie in [0, {upper}); got values in [{a.min()}, {a.max()}]")
    return a.astype(np.int64)


@dataclass(frozen=True)
class Sightings:
    """``m`` sightings (one feature seen on one ping), navigated poses; see the module docstring.

    Attributes
    ----------
    feature : ndarray of int, shape (m,)
        Index of the sighted feature, in ``[0, n_features)`` (data association: the user's).
    pass_index : ndarray of int, shape (m,)
        Index of the pass of the ping, in ``[0, n_passes)``.
    origin_m : ndarray, shape (m, 3)
        Navigated sensor origin at the ping, world frame, metres.
    W : ndarray, shape (m, 3, 3)
        Navigated sensor axes in the world frame (columns: sensor ``x``, ``y``, ``z``; ``z`` the
        beam plane's normal, :mod:`sss_locus.geometry.beam_plane`).
    range_m : ndarray, shape (m,)
        Measured slant range, metres, > 0.
    range_sigma_m : ndarray, shape (m,)
        Its standard deviation, metres, > 0: the range error and any per-ping (not shared)
        position error along the line of sight.
    beam_plane_sigma_rad : ndarray, shape (m,)
        Standard deviation of the beam-plane angle, radians, > 0
        (:func:`~sss_locus.geometry.beam_plane.beam_plane_sigma_rad`); ``inf`` leaves the
        constraint out for that sighting (a range-only estimate).
    along_track_m : ndarray, shape (m,)
        The ping's along-track position from its pass's reference point, metres (the drift's
        lever); zeros when no drift is estimated.
    """

    feature: np.ndarray
    pass_index: np.ndarray
    origin_m: np.ndarray
    W: np.ndarray
    range_m: np.ndarray
    range_sigma_m: np.ndarray
    beam_plane_sigma_rad: np.ndarray
    along_track_m: np.ndarray

    def __post_init__(self) -> None:
        o = as_float_array(self.origin_m, "origin_m", tail=(3,))
        if o.ndim != 2:
            raise ValueError(f"origin_m must have shape (m, 3); got {o.shape}")
        m = o.shape[0]
        W = as_float_array(self.W, "W", tail=(3, 3))
        if W.shape != (m, 3, 3):
            raise ValueError(f"W must have shape ({m}, 3, 3); got {W.shape}")
        object.__setattr__(self, "origin_m", o)
        object.__setattr__(self, "W", W)
        object.__setattr__(self, "feature", _int_array(self.feature, "feature", m, None))
        object.__setattr__(self, "pass_index", _int_array(self.pass_index, "pass_index", m, None))
        for name in ("range_m", "range_sigma_m", "beam_plane_sigma_rad", "along_track_m"):
            a = as_float_array(getattr(self, name), name, finite=name != "beam_plane_sigma_rad")
            a = np.broadcast_to(a, (m,)).astype(float) if a.ndim == 0 else a
            if a.shape != (m,):
                raise ValueError(f"{name} must have shape ({m},); got {a.shape}")
            if name != "along_track_m" and np.any(~(a > 0)):
                i = int(np.flatnonzero(~(a > 0))[0])
                raise ValueError(f"{name} must be > 0 (sighting {i}: {a[i]!r})")
            object.__setattr__(self, name, a)

    @property
    def n(self) -> int:
        """Number of sightings."""
        return int(self.range_m.size)


@dataclass(frozen=True)
class NavigationPriors:
    """The navigation model of ``P`` passes: the prior standard deviations of each pass's
    correction (zero-mean; see the module docstring). Scalars apply to every pass.

    Attributes
    ----------
    offset_sigma_m : float or ndarray, shape (P,)
        Per horizontal axis, metres, > 0.
    heading_sigma_deg : float or ndarray, shape (P,)
        Degrees, >= 0 (0: the heading bias is not estimated).
    drift_sigma : float or ndarray, shape (P,)
        Metres per metre along track, per horizontal axis, >= 0 (0: no drift estimated).
    reference_m : ndarray, shape (P, 2)
        Each pass's reference point (east, north), metres: the heading bias turns the track about
        it (with ``heading_moves_track``); ``along_track_m`` is measured from it.
    heading_moves_track : bool
        Whether a heading bias turns the pass's origins too (dead reckoning) or only its sensor
        axes (GNSS positions).
    """

    offset_sigma_m: np.ndarray
    heading_sigma_deg: np.ndarray
    drift_sigma: np.ndarray
    reference_m: np.ndarray
    heading_moves_track: bool = False

    def __post_init__(self) -> None:
        ref = as_float_array(self.reference_m, "reference_m", tail=(2,))
        if ref.ndim != 2:
            raise ValueError(f"reference_m must have shape (P, 2); got {ref.shape}")
        object.__setattr__(self, "reference_m", ref)
        P = ref.shape[0]
        for name, strict in (("offset_sigma_m", True), ("heading_sigma_deg", False), ("drift_sigma", False)):
            a = as_float_array(getattr(self, name), name)
            try:
                a = np.broadcast_to(a, (P,)).astype(float)
            except ValueError:
                raise ValueError(f"{name} must be a number or have shape ({P},); got {a.shape}") from None
            if np.any(a <= 0) if strict else np.any(a < 0):
                raise ValueError(f"{name} must be {'>' if strict else '>='} 0; got {getattr(self, name)!r}")
            object.__setattr__(self, name, a)
        if not isinstance(self.heading_moves_track, (bool, np.bool_)):
            raise ValueError(f"heading_moves_track must be a bool; got {self.heading_moves_track!r}")

    @property
    def n_passes(self) -> int:
        return int(self.reference_m.shape[0])

    def sigmas(self) -> np.ndarray:
        """Prior standard deviations of the five corrections of every pass, shape (P, 5), in the
        solver's units (m, m, rad, m/m, m/m); 0 where a parameter is not estimated.

        Returns
        -------
        numpy.ndarray
            Shape (P, 5).
        """
        h = np.radians(self.heading_sigma_deg)
        return np.stack([self.offset_sigma_m, self.offset_sigma_m, h, self.drift_sigma, self.drift_sigma], -1)


def corrected_poses(sightings: Sightings, priors: NavigationPriors, corrections) -> tuple[np.ndarray, np.ndarray]:
    """The sightings' sensor origins and axes after each pass's correction (module docstring).

    Parameters
    ----------
    sightings : Sightings
    priors : NavigationPriors
        For the reference points and ``heading_moves_track``.
    corrections : array_like, shape (P, 5)
        Each pass's correction in :data:`CORRECTION_NAMES` order (m, m, rad, m/m, m/m).

    Returns
    -------
    origin_m : ndarray, shape (m, 3)
    W : ndarray, shape (m, 3, 3)
    """
    c = as_float_array(corrections, "corrections", tail=(5,))
    if c.shape != (priors.n_passes, 5):
        raise ValueError(f"corrections must have shape ({priors.n_passes}, 5); got {c.shape}")
    if sightings.n and sightings.pass_index.max() >= priors.n_passes:
        raise ValueError(f"pass_index must be < the number of passes of the priors ({priors.n_passes})")
    k = c[sightings.pass_index]
    cos, sin = np.cos(k[:, 2]), np.sin(k[:, 2])
    R = np.zeros((sightings.n, 3, 3))
    R[:, 0, 0], R[:, 0, 1], R[:, 1, 0], R[:, 1, 1], R[:, 2, 2] = cos, -sin, sin, cos, 1.0
    o = sightings.origin_m.copy()
    o[:, :2] += k[:, :2] + sightings.along_track_m[:, None] * k[:, 3:5]
    if priors.heading_moves_track:
        rel = sightings.origin_m[:, :2] - priors.reference_m[sightings.pass_index]
        o[:, 0] += (cos - 1) * rel[:, 0] - sin * rel[:, 1]
        o[:, 1] += sin * rel[:, 0] + (cos - 1) * rel[:, 1]
    return o, R @ sightings.W
