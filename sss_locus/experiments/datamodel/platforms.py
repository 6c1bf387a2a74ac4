"""Sonars, vehicles and transducer mountings, read from ``data/platforms.toml``.

Frames
------
Vehicle frame
    ``x`` forward (bow / nose), ``y`` to port (left), ``z`` up; origin at the platform's reference
    point (``reference_point`` in the TOML: the waterline on the centreline for the boat, the hull
    axis at mid-length for the AUV).
World frame
    ``x`` along vehicle 1's heading, ``y`` to its port, ``z`` up (vehicle 1 at zero yaw, pitch and
    roll). Vehicle attitude: ``R_world_vehicle = Rz(yaw) Ry(-pitch) Rx(roll)`` with yaw positive
    toward port (counter-clockwise seen from above) and **pitch positive nose-up** (a positive
    rotation about the port-pointing ``y`` axis would be nose-down, hence the minus sign).
Sensor (transducer) frame, the paper's (Sec. III-A)
    ``x`` along the boresight, which points outward (to port for the port transducer) and is
    tilted down from the horizontal by ``tilt_deg``; ``y`` lies in the vertical across-track plane
    (so the wide azimuth fan is across-track and vertical); ``z = x × y`` is along-track, so a
    sensor's *elevation* is its along-track angle. With ``azimuth_positive = "down"`` (the default
    of both shipped platforms, an assumption), ``+y`` points down and inboard, so a **positive
    azimuth is further below the boresight** (steeper, toward nadir) on both sides; then ``+z``
    points aft for the port transducer and forward for the starboard one (the two frames are
    mirror images). With ``"up"`` the signs of ``y`` and ``z`` flip.

The depression angle below the horizontal of a point at azimuth ``theta`` and elevation ``phi`` of
a level vehicle's transducer is ``tilt + theta`` (for ``"down"``) when ``phi = 0``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from sss_locus.paths import DATA_DIR
from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models
from sss_locus.experiments.datamodel.inputs import check_range

PLATFORMS_FILE: Path = DATA_DIR / "platforms.toml"
SIDES: tuple[str, str] = ("port", "starboard")


@dataclass(frozen=True)
class Sonar:
    """One sidescan transducer model (the paper's Table I). Angles are FULL apertures, degrees."""

    key: str
    name: str
    azimuth_deg: float
    elevation_deg: float
    max_range_m: float
    min_range_m: float = 0.0

    def aperture(self):
        """The kernel's :class:`sss_locus.geometry.aperture.Aperture` for this sonar.

        Returns
        -------
        sss_locus.geometry.aperture.Aperture
            Azimuth and elevation apertures (degrees) and maximum range (metres).
        """
        from sss_locus.geometry import Aperture

        return Aperture(self.azimuth_deg, self.elevation_deg, self.max_range_m, self.min_range_m)


@dataclass(frozen=True)
class Transducer:
    """Mounting of one transducer on its vehicle.

    Parameters
    ----------
    side : {"port", "starboard"}
    forward_offset_m : float
        Position along the vehicle ``x`` axis from the reference point, metres.
    lateral_offset_m : float
        Distance outboard of the centreline, metres (>= 0; to port for the port transducer).
    depth_m : float
        Distance below the reference point (waterline or hull axis), metres.
    tilt_deg : float
        Downward tilt of the boresight from the horizontal, degrees, in [-90, 90].
    azimuth_positive : {"down", "up"}
        Which way positive azimuth points within the vertical fan (see the module docstring).
    """

    side: str
    forward_offset_m: float
    lateral_offset_m: float
    depth_m: float
    tilt_deg: float
    azimuth_positive: str = "down"

    @property
    def position_m(self) -> np.ndarray:
        """Transducer origin in the vehicle frame, metres, shape (3,)."""
        s = 1.0 if self.side == "port" else -1.0
        return np.array([self.forward_offset_m, s * self.lateral_offset_m, -self.depth_m])

    @property
    def rotation(self) -> Rotation:
        """Sensor-to-vehicle rotation: ``p_vehicle = rotation.apply(p_sensor) + position_m``.

        The matrix columns are the sensor axes expressed in the vehicle frame: boresight
        ``x = (0, s cos(tilt), -sin(tilt))`` with ``s = +1`` (port) or ``-1`` (starboard);
        ``y = ±(0, -s sin(tilt), -cos(tilt))`` (``+`` for ``azimuth_positive == "down"``);
        ``z = x × y`` (along-track).
        """
        s = 1.0 if self.side == "port" else -1.0
        tau = math.radians(self.tilt_deg)
        x = np.array([0.0, s * math.cos(tau), -math.sin(tau)])
        y = np.array([0.0, -s * math.sin(tau), -math.cos(tau)])
        if self.azimuth_positive == "up":
            y = -y
        z = np.cross(x, y)
        return Rotation.from_matrix(np.column_stack([x, y, z]))


    def world_pose(self, position_m, yaw_deg, pitch_deg, roll_deg) -> tuple[np.ndarray, np.ndarray]:
        """The sensor's pose in the world from the vehicle's pose (batched).

        The arguments are broadcast together to a batch shape ``S``.

        Parameters
        ----------
        position_m : array_like, shape S + (3,)
            The vehicle reference point in the world frame (``x``, ``y`` horizontal, ``z`` up), m.
        yaw_deg, pitch_deg, roll_deg : array_like, shape S
            Vehicle attitude, degrees: ``R_world_vehicle = Rz(yaw) Ry(-pitch) Rx(roll)``, yaw
            positive toward port (counter-clockwise from above), pitch positive nose-up.

        Returns
        -------
        rotation : ndarray, shape S + (3, 3)
            Sensor-to-world rotation (columns: the sensor's ``x`` boresight, ``y`` across-track
            fan, ``z`` along-track axes in the world), as :func:`sss_locus.relative_pose` takes it.
        origin : ndarray, shape S + (3,)
            The transducer's origin in the world, m.

        ``sss_locus.relative_pose(*a.world_pose(...), *b.world_pose(...))`` gives the ``(R, t)``
        of :func:`sss_locus.two_view_locus` with no hand-built rotation.
        """
        pos = np.asarray(position_m, float)
        angles = np.broadcast_arrays(*(np.asarray(v, float) for v in (yaw_deg, pitch_deg, roll_deg)))
        shape = np.broadcast_shapes(pos.shape[:-1], angles[0].shape)
        if pos.shape[-1:] != (3,) or not all(np.all(np.isfinite(a)) for a in (pos, *angles)):
            raise ValueError(f"position_m must be finite with shape (..., 3) and the angles finite; got "
                             f"position_m of shape {pos.shape}")
        euler = np.stack([np.broadcast_to(a, shape).ravel() for a in
                          (angles[0], -angles[1], angles[2])], -1)
        Rv = Rotation.from_euler("ZYX", euler, degrees=True).as_matrix().reshape(shape + (3, 3))
        W = Rv @ self.rotation.as_matrix()
        origin = np.broadcast_to(pos, shape + (3,)) + Rv @ self.position_m
        return W, origin


@dataclass(frozen=True)
class Platform:
    """A vehicle with two side-looking transducers, its attitude limits and depth envelope.

    ``depth_min_m``/``depth_max_m`` bound the depth of the vehicle reference point below the sea
    surface; a platform with ``depth_min_m == depth_max_m`` (a surface vessel) keeps it fixed, so
    two poses of it share the same draft exactly. ``provenance`` maps each key path of the TOML
    (e.g. ``"platforms.auv.transducers.port.tilt_deg"``) to ``"source: ..."`` or
    ``"assumption: ..."``. ``turn_radius_m`` and ``speed_m_s`` (the ``mission`` table: minimum
    turning radius, m, and survey speed, m/s) are read by the survey design; ``None`` when the
    platform's file does not give them.
    """

    key: str
    name: str
    sonar: Sonar
    transducers: Mapping[str, Transducer]
    roll_max_deg: float
    pitch_max_deg: float
    depth_min_m: float
    depth_max_m: float
    length_m: float | None = None
    reference_point: str = ""
    altitude_fraction_of_range: float | None = None
    turn_radius_m: float | None = None
    speed_m_s: float | None = None
    provenance: Mapping[str, str] = field(default_factory=dict, compare=False, repr=False)

    @property
    def fixed_depth(self) -> bool:
        """True for a platform whose reference point stays at one depth (a surface vessel)."""
        return self.depth_min_m == self.depth_max_m

    def with_attitude_limits(self, *, pitch_max_deg: float | None = None,
                             roll_max_deg: float | None = None) -> "Platform":
        """A copy with other attitude limits (e.g. the +-15 deg survey envelope of Sec. IV-D).

        Parameters
        ----------
        pitch_max_deg, roll_max_deg : float, optional
            New limits, degrees; ``None`` keeps a limit.

        Returns
        -------
        Platform
            The copy.
        """
        changes = {}
        for name, value in (("pitch_max_deg", pitch_max_deg), ("roll_max_deg", roll_max_deg)):
            if value is not None:
                changes[name] = check_range(float(value), name, 0.0, 90.0)
        return dataclasses.replace(self, **changes)

    def with_tilt(self, tilt_deg: float) -> "Platform":
        """A copy with both transducers tilted down by ``tilt_deg`` degrees, in [-90, 90] (to
        probe an assumed tilt, such as the boat's Omniscan tilt).

        Parameters
        ----------
        tilt_deg : float
            Downward tilt of both transducers, degrees.

        Returns
        -------
        Platform
            The copy.
        """
        tilt = check_range(float(tilt_deg), "tilt_deg", -90.0, 90.0)
        return dataclasses.replace(self, transducers={
            side: dataclasses.replace(t, tilt_deg=tilt) for side, t in self.transducers.items()})


# --------------------------------------------------------------------------------------------
# Reading and validation
# --------------------------------------------------------------------------------------------
def _sonar(key: str, m: models.Sonar) -> Sonar:
    return Sonar(key=key, name=m.name, azimuth_deg=m.azimuth_deg.value, elevation_deg=m.elevation_deg.value,
                 max_range_m=m.max_range_m.value, min_range_m=m.min_range_m.value)


def _platform(key: str, m: models.Platform, sonars: Mapping[str, Sonar],
              sonar_provenance: Mapping[str, dict[str, str]]) -> Platform:
    """The :class:`Platform` of a validated ``[platforms.<key>]`` table."""

    def value(entry):
        return None if entry is None else entry.value

    transducers = {side: Transducer(side=side, forward_offset_m=t.forward_offset_m.value,
                                    lateral_offset_m=t.lateral_offset_m.value, depth_m=t.depth_m.value,
                                    tilt_deg=t.tilt_deg.value, azimuth_positive=m.azimuth_positive.value)
                   for side, t in (("port", m.transducers.port), ("starboard", m.transducers.starboard))}
    return Platform(
        key=key, name=m.name, sonar=sonars[m.sonar], transducers=transducers,
        roll_max_deg=m.attitude.roll_max_deg.value, pitch_max_deg=m.attitude.pitch_max_deg.value,
        depth_min_m=m.depth_m.min.value, depth_max_m=m.depth_m.max.value,
        length_m=value(m.length_m), reference_point=m.reference_point,
        altitude_fraction_of_range=value(m.survey.altitude_fraction_of_range),
        turn_radius_m=value(m.mission.turn_radius_m), speed_m_s=value(m.mission.speed_m_s),
        provenance={**sonar_provenance[m.sonar], **models.provenance(m, f"platforms.{key}")},
    )


def platforms_from(data: models.Data) -> dict[str, Platform]:
    """The platforms of a validated data document, by key, in document order.

    Parameters
    ----------
    data : sss_locus.experiments.datamodel.models.Data
        The validated document (its ``sonars`` and ``platforms``).

    Returns
    -------
    dict of str to Platform
        The platforms, each with its sonar and the provenance of its numbers.
    """
    if not data.platforms:
        raise ValueError("platforms must contain at least one [platforms.<key>] table")
    sonars = {k: _sonar(k, s) for k, s in data.sonars.items()}
    notes = {k: models.provenance(s, f"sonars.{k}") for k, s in data.sonars.items()}
    return {k: _platform(k, p, sonars, notes) for k, p in data.platforms.items()}


def parse_platforms(doc: Mapping[str, Any]) -> dict[str, Platform]:
    """Validate a parsed TOML document and return its platforms by key.

    Raises
    ------
    ValueError
        Naming the full key path of the first missing or malformed entry.

    Parameters
    ----------
    doc : mapping
        A parsed TOML document with ``[sonars]`` and ``[platforms]``.

    Returns
    -------
    dict of str to Platform
        The platforms by key, in document order.
    """
    return platforms_from(models.validate_document(doc, ("sonars", "platforms")))


def load_platforms(path: str | Path | None = None) -> dict[str, Platform]:
    """Read and validate the platforms; by key, in data order (shipped first, then new keys).

    Default: ``data/`` merged with the active user data (:mod:`sss_locus.experiments.datamodel.userdata`);
    ``path``: that one file only.

    Parameters
    ----------
    path : str or pathlib.Path, optional
        A TOML file read alone instead.

    Returns
    -------
    dict of str to Platform
        The platforms by key.
    """
    return datadoc.load_table(parse_platforms, path, "platforms", "sonars")


def load_platform(key: str, path: str | Path | None = None) -> Platform:
    """One platform by key (e.g. ``"boat"`` or ``"auv"``).

    Parameters
    ----------
    key : str
        Platform key.
    path : str or pathlib.Path, optional
        A TOML file read alone instead.

    Returns
    -------
    Platform
        The platform.
    """
    platforms = datadoc.load_table(parse_platforms, path)  # the entries it reads: noted below
    if key not in platforms:
        raise ValueError(f"platform must be one of {sorted(platforms)}; got {key!r}")
    if path is None:
        datadoc.note_read(f"platforms.{key}", f"sonars.{platforms[key].sonar.key}")
    return platforms[key]


def provenance_table(platform: Platform):
    """The platform's numbers with their sources / assumptions, as a pandas DataFrame.

    Parameters
    ----------
    platform : Platform
        The platform.

    Returns
    -------
    pandas.DataFrame
        One row per number: ``key``, ``kind`` (source or assumption) and ``note``.
    """
    import pandas as pd

    rows = []
    for key, note in platform.provenance.items():
        kind, _, text = note.partition(": ")
        rows.append({"key": key, "kind": kind, "note": text})
    return pd.DataFrame(rows)


def frustum_points(sonar: Sonar, transducer: Transducer, plot_range_m: float,
                   n: int = 25) -> np.ndarray:
    """Points outlining a transducer's aperture frustum, in the vehicle frame (for drawing).

    The frustum is the set of points within ``plot_range_m`` of the transducer inside its
    azimuth and elevation apertures; returned are its apex (the transducer origin) followed by
    an ``n`` x ``n`` grid over the far cap (azimuth x elevation at ``plot_range_m``). For
    apertures up to 180 deg in azimuth the frustum is the convex hull of these points.

    Parameters
    ----------
    sonar : Sonar
        The sonar (its apertures).
    transducer : Transducer
        The transducer (its mounting).
    plot_range_m : float
        Range of the far cap, metres.
    n : int
        Grid points per side of the cap.

    Returns
    -------
    numpy.ndarray, shape (1 + n * n, 3), metres.
    """
    if not (math.isfinite(plot_range_m) and plot_range_m > 0):
        raise ValueError(f"plot_range_m must be a positive number of metres; got {plot_range_m!r}")
    if int(n) < 2:
        raise ValueError(f"n must be >= 2; got {n}")
    th = np.radians(np.linspace(-sonar.azimuth_deg / 2, sonar.azimuth_deg / 2, int(n)))
    ph = np.radians(np.linspace(-sonar.elevation_deg / 2, sonar.elevation_deg / 2, int(n)))
    T, P = np.meshgrid(th, ph, indexing="ij")
    cap = plot_range_m * np.stack([np.cos(T) * np.cos(P), np.sin(T) * np.cos(P), np.sin(P)], -1)
    local = np.concatenate([np.zeros((1, 3)), cap.reshape(-1, 3)])
    return transducer.rotation.apply(local) + transducer.position_m
