"""The water column as a constraint on the locus: the sea surface and, optionally, the seafloor.

The paper crops the two range spheres' circle only to the sonars' apertures, so a locus may run
above the sea surface, where no feature can be. :class:`WaterColumn` is the named, off-by-default
option of the pose-space and survey-pass studies (``PoseSpaceSpec(water=...)``,
``simulate_passes(..., water=...)``) that also crops each locus to the water, exactly, through
the kernel's half-spaces (:mod:`sss_locus.geometry.halfspaces`). The samples are the same with
and without it (the same seed draws the same configurations): only the locus changes, so the
two tables compare row by row (:func:`sss_locus.experiments.water.study.crop_effect`).

Frames: world ``z`` up (:mod:`sss_locus.experiments.datamodel.platforms`). The sea surface is level; a
feature must have ``z_world <= z_surface`` and, with a seafloor, ``z_world >= z_surface - W``
for the greatest water depth ``W``.

The seafloor in the studies
---------------------------
``max_water_depth_m`` is a fixed ``W`` (a depth from a chart). The studies' samplers do not place
the feature above such a floor: the pose-space sampler draws it anywhere in sensor 1's fan (down
to ``max_range * sin(tilt + azimuth / 2)`` below the transducer, :func:`deepest_feature_m`), the
survey passes put it on the seafloor at the pass's altitude. A fixed ``W``
would put sampled features, which lie on their own locus, below the floor; the studies refuse
it (:meth:`WaterColumn.half_spaces` with ``feature_z``) and take ``seafloor_below_feature_m``
instead: the greatest water depth is each sample's feature depth plus this margin, so every
sampled feature is in the water, and the margin says how tight the known depth bound is
(0: the feature is at the greatest depth, e.g. on a flat floor).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sss_locus.geometry import max_depth_half_space, sea_surface_half_space
from sss_locus.experiments.datamodel.inputs import check_range
from sss_locus.experiments.datamodel.platforms import Platform


@dataclass(frozen=True)
class WaterColumn:
    """Where the water is, for cropping loci to it.

    Parameters
    ----------
    vehicle_depth_m : float or None
        Depth (m) of vehicle 1's reference point below the sea surface, within the platform's
        ``[depth_min_m, depth_max_m]``. ``None`` takes the fixed depth of a surface vessel
        (the boat's reference point is at the waterline); a platform whose depth varies (the
        AUV) needs a value.
    max_water_depth_m : float or None
        Greatest depth (m) below the surface a feature can have (a known water depth, the
        seafloor); ``None``: no fixed seafloor bound. Must exceed the sensors' depth.
    seafloor_below_feature_m : float or None
        The greatest water depth relative to each sample's feature: the feature's depth below
        the surface plus this margin (m, in [0, 11000]; module docstring). Excludes
        ``max_water_depth_m``. ``None``: no such bound.
    """

    vehicle_depth_m: float | None = None
    max_water_depth_m: float | None = None
    seafloor_below_feature_m: float | None = None

    def __post_init__(self) -> None:
        for name in ("vehicle_depth_m", "max_water_depth_m", "seafloor_below_feature_m"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, check_range(float(v), f"WaterColumn.{name}", 0.0, 11_000.0))
        if self.max_water_depth_m is not None and self.seafloor_below_feature_m is not None:
            raise ValueError("WaterColumn takes max_water_depth_m or seafloor_below_feature_m, not both; got "
                             f"{self.max_water_depth_m:g} and {self.seafloor_below_feature_m:g}")

    def depth_for(self, platform: Platform) -> float:
        """Vehicle 1's reference depth (m) for ``platform``; ``ValueError`` if it is unknown or
        outside the platform's depth range.

        Parameters
        ----------
        platform : Platform
            The platform.

        Returns
        -------
        float
            Depth below the surface, metres.
        """
        if self.vehicle_depth_m is None:
            if not platform.fixed_depth:
                raise ValueError(
                    f"WaterColumn.vehicle_depth_m is required for platform {platform.key!r}, whose "
                    f"depth varies in [{platform.depth_min_m:g}, {platform.depth_max_m:g}] m")
            return platform.depth_min_m
        if not platform.depth_min_m <= self.vehicle_depth_m <= platform.depth_max_m:
            raise ValueError(
                f"WaterColumn.vehicle_depth_m must lie in platform {platform.key!r}'s depth range "
                f"[{platform.depth_min_m:g}, {platform.depth_max_m:g}] m; got {self.vehicle_depth_m:g}")
        return self.vehicle_depth_m

    def half_spaces(self, rotation1, origin1_z, surface_z, feature_z=None) -> tuple[np.ndarray, np.ndarray]:
        """Half-spaces of sensor 1's frame for ``two_view_locus(half_space_normals=,
        half_space_offsets=)``.

        Parameters
        ----------
        rotation1 : ndarray, shape (n, 3, 3)
            Sensor 1's sensor-to-world rotations (world ``z`` up).
        origin1_z : ndarray, shape (n,)
            World ``z`` (m) of sensor 1's origin.
        surface_z : float or ndarray, shape (n,)
            World ``z`` (m) of the sea surface.
        feature_z : ndarray, shape (n,), or None
            World ``z`` (m) of each sample's feature (the true point on its locus). Needed with
            ``seafloor_below_feature_m``; with ``max_water_depth_m`` it is checked to lie in the
            water (``ValueError`` counting the features below the floor otherwise).

        Returns
        -------
        normals : ndarray, shape (n, K, 3); offsets : ndarray, shape (n, K)
            ``K`` = 1 (surface) or 2 (surface and seafloor).
        """
        depth1 = np.asarray(surface_z, float) - np.asarray(origin1_z, float)
        normals, offsets = sea_surface_half_space(depth1, rotation1)
        water_depth = self.max_water_depth_m
        if feature_z is not None:
            feature_depth = np.asarray(surface_z, float) - np.asarray(feature_z, float)
            if self.seafloor_below_feature_m is not None:
                water_depth = feature_depth + self.seafloor_below_feature_m
            elif water_depth is not None and np.any(feature_depth > water_depth):
                raise ValueError(
                    f"{int(np.sum(feature_depth > water_depth))} of {feature_depth.size} sampled features lie "
                    f"below WaterColumn.max_water_depth_m = {water_depth:g} m (deepest "
                    f"{feature_depth.max():.1f} m): the sampler does not place features above a fixed "
                    "seafloor; use seafloor_below_feature_m")
        elif self.seafloor_below_feature_m is not None:
            raise ValueError("WaterColumn.seafloor_below_feature_m needs feature_z (the features' world z)")
        if water_depth is not None:
            n2, d2 = max_depth_half_space(water_depth, depth1, rotation1)
            normals, offsets = np.concatenate([normals, n2], -2), np.concatenate([offsets, d2], -1)
        return normals, offsets

    def key(self) -> dict:
        """Plain-data description (for figure manifests).

        Returns
        -------
        dict
            Every field by name.
        """
        d = {"vehicle_depth_m": self.vehicle_depth_m, "max_water_depth_m": self.max_water_depth_m}
        if self.seafloor_below_feature_m is not None:  # absent when off: earlier keys unchanged
            d["seafloor_below_feature_m"] = self.seafloor_below_feature_m
        return d


def deepest_feature_m(platform: Platform) -> float:
    """Greatest depth (m) below the sea surface of a feature in sensor 1's fan, for a level
    vehicle 1 at the shallowest depth of ``platform``: reference depth plus transducer depth
    plus ``max_range * sin(min(tilt + azimuth / 2, 90 deg))``, the fan's lowest edge at full range.

    Parameters
    ----------
    platform : Platform
        The platform.

    Returns
    -------
    float
        Depth, metres.
    """
    t = platform.transducers["port"]
    down = np.radians(min(t.tilt_deg + platform.sonar.azimuth_deg / 2, 90.0))
    return float(platform.depth_min_m + t.depth_m + platform.sonar.max_range_m * np.sin(down))
