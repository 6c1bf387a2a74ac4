"""What hardware can exist: rules across tables, checked on the merged data (shipped
``data/*.toml``, ``--data`` files, ``--set`` overrides) before any work starts, after the data
model (:mod:`sss_locus.experiments.datamodel.models`) has checked each table's keys and ranges.

Physical rules (:func:`check_hardware`)
    Each refused in one line naming the rule and the values:

    * a transducer above the sea surface at the platform's shallowest depth
      (``depth_m.min + transducers.<side>.depth_m < 0``);
    * a survey envelope's pitch beyond the platform's attitude limit
      (``max(|pitch_min_deg|, |pitch_max_deg|) > attitude.pitch_max_deg``), or its bounds the
      wrong way round;
    * an envelope altitude at or beyond the sonar's range (``altitude_max_m >= max_range_m``:
      the seafloor would be out of reach);
    * a sonar's apertures that look like radians (the kernel's rule,
      :data:`sss_locus.geometry.aperture.RADIANS_FAN_DEG` and ``RADIANS_SHAPE_RATIO``);
    * a name the figures cannot draw (control characters, emoji and other pictographs).

    :func:`hardware_warnings` flags, without refusing, a transducer tilt that looks like radians
    (``0 < |tilt_deg| < pi/2`` with a fractional part), a sonar fan of at most ``pi`` "degrees"
    whose beam alone does not meet the radians rule, and a fan in degrees with a beam narrower
    than :data:`RADIANS_BEAM_DEG` (the beam alone in radians); given the survey envelopes, one
    whose highest altitude is below :data:`LOW_ALTITUDE_FRACTION` of the sonar's range (a range
    in mm or cm).
"""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Mapping
from typing import Any

from sss_locus.geometry.aperture import RADIANS_FAN_DEG, RADIANS_SHAPE_RATIO


def _drawable(text: str) -> bool:
    for char in text:
        category = unicodedata.category(char)
        if category.startswith("C") or ord(char) > 0xFFFF or "\u2600" <= char <= "\u27bf" \
                or char == "\ufe0f":
            return False
    return True


def check_hardware(platforms: Mapping[str, Any], envelopes: Mapping[str, Any]) -> None:
    """Refuse physically impossible hardware (see the module docstring).

    ``platforms``: :class:`~sss_locus.experiments.datamodel.platforms.Platform` by key; ``envelopes``:
    :class:`~sss_locus.experiments.datamodel.envelopes.SurveyEnvelope` by platform key.

    Parameters
    ----------
    platforms : Mapping of str to Platform
        Platforms by key (their sonars are checked once each).
    envelopes : Mapping of str to SurveyEnvelope
        Survey envelopes by platform key.

    Raises
    ------
    ValueError
        One line naming the data entry (e.g. ``sonars.<key>``, ``platforms.<key>...``) and what
        is impossible.
    """
    sonars = {p.sonar.key: p.sonar for p in platforms.values()}
    for key, sonar in sonars.items():
        if sonar.azimuth_deg <= RADIANS_FAN_DEG and sonar.elevation_deg <= sonar.azimuth_deg / RADIANS_SHAPE_RATIO:
            raise ValueError(
                f"sonars.{key}: azimuth_deg = {sonar.azimuth_deg:g} and elevation_deg = "
                f"{sonar.elevation_deg:g} look like radians (azimuth <= pi and elevation <= azimuth / "
                f"{RADIANS_SHAPE_RATIO:g}); give FULL apertures in degrees (did you mean "
                f"{math.degrees(sonar.azimuth_deg):.4g} x {math.degrees(sonar.elevation_deg):.4g} deg?)")
        if not _drawable(sonar.name):
            raise ValueError(f"sonars.{key}.name = {sonar.name!r}: use text the figures can draw "
                             "(no emoji, pictographs or control characters)")
    for key, p in platforms.items():
        if not _drawable(p.name):
            raise ValueError(f"platforms.{key}.name = {p.name!r}: use text the figures can draw "
                             "(no emoji, pictographs or control characters)")
        for side, t in p.transducers.items():
            if p.depth_min_m + t.depth_m < 0:
                raise ValueError(
                    f"platforms.{key}.transducers.{side}.depth_m = {t.depth_m:g}: the transducer is "
                    f"{-(p.depth_min_m + t.depth_m):g} m above the sea surface at the platform's "
                    f"shallowest depth (depth_m.min = {p.depth_min_m:g}); a sidescan works under water "
                    "(rule: depth_m.min + transducer depth_m >= 0)")
        env = envelopes.get(key)
        if env is None:
            continue
        where = f"envelopes.{key}"
        if env.pitch_min_deg > env.pitch_max_deg or env.altitude_min_m > env.altitude_max_m:
            raise ValueError(f"{where}: pitch_min_deg/altitude_min_m must not exceed pitch_max_deg/"
                             f"altitude_max_m; got pitch [{env.pitch_min_deg:g}, {env.pitch_max_deg:g}], "
                             f"altitude [{env.altitude_min_m:g}, {env.altitude_max_m:g}]")
        pitch = max(abs(env.pitch_min_deg), abs(env.pitch_max_deg))
        if pitch > p.pitch_max_deg:
            raise ValueError(
                f"{where}: pitch within [{env.pitch_min_deg:g}, {env.pitch_max_deg:g}] deg exceeds the "
                f"vehicle's limit platforms.{key}.attitude.pitch_max_deg = {p.pitch_max_deg:g} "
                "(rule: |pitch| <= the platform's pitch limit)")
        if env.altitude_max_m >= p.sonar.max_range_m:
            raise ValueError(
                f"{where}.altitude_max_m = {env.altitude_max_m:g} m is at or beyond the sonar's range "
                f"sonars.{p.sonar.key}.max_range_m = {p.sonar.max_range_m:g} m: the seafloor would be "
                "out of reach (rule: altitude_max_m < max_range_m)")


#: An along-track beam (``elevation_deg``) narrower than this many degrees is flagged (not
#: refused) as a likely radian value: it is the radian value of a 2 deg beam, while sidescan beams
#: are about 0.1 deg and wider (typical data-sheet figures, recalled): a 0.035 deg beam needs an
#: array about 1,600 wavelengths long (2.7 m at 900 kHz, 24 m at 100 kHz).
RADIANS_BEAM_DEG = math.radians(2.0)


#: A survey envelope whose highest altitude is below this fraction of the sonar's range is
#: flagged (not refused): survey altitudes are about 5-20 % of the range setting (the shipped
#: envelopes' rule of thumb, ``data/survey.toml``), and a range in mm or cm lands far below 1 %.
LOW_ALTITUDE_FRACTION = 0.01


def hardware_warnings(platforms: Mapping[str, Any], envelopes: Mapping[str, Any] | None = None) -> list[str]:
    """Values that are possible but look like a mistake (one line each; see the module docstring).

    Parameters
    ----------
    platforms : Mapping of str to Platform
        Platforms by key.
    envelopes : Mapping of str to SurveyEnvelope, optional
        Survey envelopes by platform key: one whose ``altitude_max_m`` is below
        :data:`LOW_ALTITUDE_FRACTION` of its sonar's ``max_range_m`` is flagged.

    Returns
    -------
    list of str
        Warnings naming the data entry: apertures (deg) that look like radians, tilts (deg)
        that look like radians, then the :func:`fan_warnings`; empty when nothing looks wrong.
    """
    found = []
    for key, sonar in {p.sonar.key: p.sonar for p in platforms.values()}.items():
        if sonar.azimuth_deg <= RADIANS_FAN_DEG:
            found.append(f"sonars.{key}.azimuth_deg = {sonar.azimuth_deg:g} looks like radians (a "
                         f"{math.degrees(sonar.azimuth_deg):.4g} deg fan?); apertures are FULL angles in degrees")
        elif sonar.elevation_deg < RADIANS_BEAM_DEG:  # the fan in degrees, its beam alone in radians
            found.append(f"sonars.{key}.elevation_deg = {sonar.elevation_deg:g} looks like radians (a "
                         f"{math.degrees(sonar.elevation_deg):.3g} deg beam?); apertures are FULL angles in degrees")
    for key, p in platforms.items():
        for side, t in p.transducers.items():
            tilt = abs(t.tilt_deg)
            if 0 < tilt < math.pi / 2 and not float(tilt).is_integer():
                found.append(f"platforms.{key}.transducers.{side}.tilt_deg = {t.tilt_deg:g} looks like "
                             f"radians (a look-down of {math.degrees(t.tilt_deg):.3g} deg?); tilts are in degrees")
        env = (envelopes or {}).get(key)
        if env is not None and env.altitude_max_m < LOW_ALTITUDE_FRACTION * p.sonar.max_range_m:
            found.append(f"envelopes.{key}.altitude_max_m = {env.altitude_max_m:g} m is "
                         f"{100 * env.altitude_max_m / p.sonar.max_range_m:.2g} % of sonars.{p.sonar.key}.max_range_m = "
                         f"{p.sonar.max_range_m:g} m (survey altitudes are about 5-20 % of the range): is the range "
                         "in mm or cm? max_range_m is in metres")
    return found + [line for _, line in fan_warnings(platforms)]


def fan_warnings(platforms: Mapping[str, Any]) -> list[tuple[tuple[str, str, str], str]]:
    """Transducers whose fan, on a level vehicle, reaches above the horizontal on a surface
    vessel (``depth_m.max == 0``) or past the vertical: possible, but a surface vessel's fan above
    the horizontal looks along the sea surface, not at the seafloor, and a fan past the vertical
    looks under the vehicle. (A submerged vehicle may look up on purpose.) Returns ``((platform, side,
    kind), line)`` pairs, ``kind`` "above" or "under", so a caller can leave out what the shipped
    platforms do already.

    Parameters
    ----------
    platforms : Mapping of str to Platform
        Platforms by key; tilts (look-down of the fan's centre) and full azimuth apertures in
        degrees, vehicle level.

    Returns
    -------
    list of ((str, str, str), str)
        ``((platform key, transducer side, kind), warning line)``; empty when every fan lies
        between the horizontal and the vertical.
    """
    found = []
    for key, p in platforms.items():
        half = p.sonar.azimuth_deg / 2
        for side, t in p.transducers.items():
            top, bottom = abs(t.tilt_deg) - half, abs(t.tilt_deg) + half  # look-down of the fan's edges
            where = (f"platforms.{key}.transducers.{side}.tilt_deg = {t.tilt_deg:g} with the "
                     f"{p.sonar.azimuth_deg:g} deg fan of sonars.{p.sonar.key}")
            if top < 0 and p.depth_max_m <= 0:
                found.append(((key, side, "above"), f"{where} points the fan's top {-top:.3g} deg ABOVE the horizontal "
                              "(on a surface boat that part looks along the sea surface, not at the seafloor); tilt_deg is the look-down of "
                              "the fan's centre, azimuth_deg the FULL fan: a tilt of at least half the fan keeps it "
                              "below the horizontal"))
            if bottom > 90:
                found.append(((key, side, "under"), f"{where} points the fan's bottom {bottom - 90:.3g} deg past "
                              "the vertical (under the vehicle, toward the other side)"))
    return found
