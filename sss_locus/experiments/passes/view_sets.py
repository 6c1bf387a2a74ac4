"""Sets of views: several straight passes over one feature, as world-frame sensor poses (the
inputs of the three-view and noise studies).

World frame as in :mod:`sss_locus.experiments.passes.straight_pass`: origin at the feature, ``x`` along heading 0, ``y`` to
its port, ``z`` up. Each pass is placed with :func:`sss_locus.experiments.passes.straight_pass.observe_pass` (the exact
in-beam ping), so a pattern of passes is a list of headings plus, per pass, the observing side,
ground offset, altitude, pitch and in-beam elevation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from sss_locus.geometry import relative_pose
from sss_locus.experiments.passes.straight_pass import observe_pass, swath_m, vehicle_attitude

@dataclass(frozen=True)
class Views:
    """``k`` sensors observing one feature, for ``n`` configurations (world frame, metres).

    Attributes
    ----------
    W : ndarray, shape (n, k, 3, 3)
        Sensor axes in the world (``p_world = W p_sensor + origin``).
    origin : ndarray, shape (n, k, 3)
    vehicle : ndarray, shape (n, k, 3, 3)
        Vehicle attitudes (vehicle-to-world), used for attitude errors.
    feature : ndarray, shape (n, 3)
    """

    W: np.ndarray
    origin: np.ndarray
    vehicle: np.ndarray
    feature: np.ndarray

    @property
    def ranges(self) -> np.ndarray:
        """True ranges, shape (n, k), m."""
        return np.linalg.norm(self.feature[:, None, :] - self.origin, axis=-1)

    def take(self, index) -> "Views":
        """A subset of the configurations (any numpy index on the first axis).

        Parameters
        ----------
        index : int, slice or array_like
            Index of the configurations kept.

        Returns
        -------
        Views
            The subset.
        """
        return Views(self.W[index], self.origin[index], self.vehicle[index], self.feature[index])

    def select(self, *views: int) -> "Views":
        """A subset of the views, in the order given (e.g. ``select(0, 1)``).

        Parameters
        ----------
        *views : int
            Indices of the views kept.

        Returns
        -------
        Views
            The subset.
        """
        v = list(views)
        return Views(self.W[:, v], self.origin[:, v], self.vehicle[:, v], self.feature)

    def relative(self, a: int = 0, b: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """``(R, t)`` with ``p_b = R p_a + t`` (the kernels' convention), shapes (n, 3, 3), (n, 3).

        Parameters
        ----------
        a, b : int
            Indices of the two views.

        Returns
        -------
        R : numpy.ndarray, shape (n, 3, 3)
            Rotation from view ``a``'s frame to view ``b``'s.
        t : numpy.ndarray, shape (n, 3)
            Translation, metres: ``p_b = R p_a + t``.
        """
        return relative_pose(self.W[:, a], self.origin[:, a], self.W[:, b], self.origin[:, b])


def views_from_passes(platform, headings_deg, is_port, ground_offset_m, altitude_m, pitch_deg,
                      elevation_rad) -> tuple[Views, np.ndarray]:
    """Straight passes over a feature at the world origin.

    All arguments after ``platform`` are arrays broadcast to ``(n, k)``, one column per pass
    (see :func:`sss_locus.experiments.passes.straight_pass.observe_pass` for their meaning and units). Returns the
    :class:`Views` and a boolean ``(n,)`` mask: every pass sees the feature (azimuth aperture,
    range, a unique in-beam ping).

    Parameters
    ----------
    platform : Platform
        The vehicle and its transducers.
    headings_deg : array_like, shape (n, k)
        Track headings, degrees, positive toward port.
    is_port : array_like of bool, shape (n, k)
        Observing transducer.
    ground_offset_m : array_like, shape (n, k)
        Across-track ground offset of the feature toward the observing side, metres.
    altitude_m : array_like, shape (n, k)
        Reference point above the feature, metres.
    pitch_deg : array_like, shape (n, k)
        Pitch, degrees, nose-up positive.
    elevation_rad : array_like, shape (n, k)
        In-beam elevation of the feature, radians.

    Returns
    -------
    views : Views
        The ``n`` configurations of ``k`` views.
    seen : numpy.ndarray of bool, shape (n,)
        Whether every pass sees the feature.
    """
    cols = np.broadcast_arrays(*(np.atleast_2d(np.asarray(a)) for a in (
        headings_deg, is_port, ground_offset_m, altitude_m, pitch_deg, elevation_rad)))
    n, k = cols[0].shape
    W, o, V, ok = [], [], [], np.ones(n, bool)
    for j in range(k):
        head, port, g, alt, pitch, phi = (np.asarray(c[:, j], float) for c in cols)
        ob = observe_pass(platform, port.astype(bool), head, g, alt, pitch, phi)
        W.append(ob["W"])
        o.append(ob["origin"])
        V.append(vehicle_attitude(head, pitch, np.zeros(n)).as_matrix().reshape(n, 3, 3))
        ok &= ob["reason"] < 0
    return Views(np.stack(W, 1), np.stack(o, 1), np.stack(V, 1), np.zeros((n, 3))), ok


def views_from_survey(platform, samples: pd.DataFrame) -> Views:
    """The two passes of each row of :func:`sss_locus.experiments.survey_passes.study.simulate_passes` (pass 1 at
    heading 0, pass 2 at ``crossing_angle_deg``), rebuilt from the row's draws.

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    samples : pandas.DataFrame
        Pass pairs of :func:`~sss_locus.experiments.survey_passes.study.simulate_passes`.

    Returns
    -------
    Views
        Two views per row, in the rows' order.
    """
    s = samples
    views, ok = views_from_passes(
        platform,
        np.stack([np.zeros(len(s)), s["crossing_angle_deg"].to_numpy(float)], 1),
        np.stack([(s["side1"] == "port").to_numpy(), (s["side2"] == "port").to_numpy()], 1),
        s[["ground_offset1_m", "ground_offset2_m"]].to_numpy(float),
        s[["altitude1_m", "altitude2_m"]].to_numpy(float),
        s[["pitch1_deg", "pitch2_deg"]].to_numpy(float),
        np.radians(s[["elevation1_deg", "elevation2_deg"]].to_numpy(float)))
    if not ok.all():
        raise ValueError("samples must come from simulate_passes (a row's passes do not all see "
                         "the feature when rebuilt)")
    return views


def draw_pattern(platform, envelope, headings_deg, n: int, seed: int) -> tuple[Views, pd.DataFrame]:
    """``n`` configurations of passes at ``headings_deg`` that all see one feature.

    Per pass, as in the survey study's ``"independent"`` offset model: the observing side is
    port or starboard with probability 1/2, the ground offset uniform over that side's swath,
    the pitch uniform in the envelope, the in-beam elevation uniform within the aperture; the
    altitude is drawn per pass (once for a platform with ``envelope.same_altitude``). Draws in
    which some pass does not see the feature are redrawn.

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    headings_deg : sequence of float
        Heading of each pass, degrees.
    n : int
        Configurations, ``>= 1``.
    seed : int
        Seed, ``>= 0``.

    Returns
    -------
    views : Views
    draws : pandas.DataFrame
        The draws, one row per configuration (``side<j>``, ``ground_offset<j>_m``,
        ``altitude<j>_m``, ``pitch<j>_deg``, ``elevation<j>_deg``, ``heading<j>_deg``, j from 1).
    """
    h = np.asarray(headings_deg, float)
    if h.ndim != 1 or h.size < 1 or not np.all(np.isfinite(h)):
        raise ValueError(f"headings_deg must be a 1-D list of finite angles; got {headings_deg!r}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be a positive integer; got {n!r}")
    k = h.size
    rng = np.random.default_rng(seed)
    half_el = math.radians(platform.sonar.elevation_deg / 2)
    got, have, tried = [], 0, 0
    while have < n:
        m = max(256, 2 * (n - have))
        port = rng.random((m, k)) < 0.5
        span = envelope.altitude_max_m - envelope.altitude_min_m
        alt = envelope.altitude_min_m + span * rng.random((m, 1 if envelope.same_altitude else k))
        alt = np.broadcast_to(alt, (m, k))
        near, far = swath_m(platform, port, alt)
        g = near + (far - near) * rng.random((m, k))
        pitch = envelope.pitch_min_deg + (envelope.pitch_max_deg - envelope.pitch_min_deg) * rng.random((m, k))
        phi = (2 * rng.random((m, k)) - 1) * half_el
        views, ok = views_from_passes(platform, h[None, :], port, g, alt, pitch, phi)
        got.append((views.take(ok), port[ok], g[ok], alt[ok], pitch[ok], phi[ok]))
        have += int(ok.sum())
        tried += m
        if tried > 50 * n + 10000 and have < 1e-3 * tried:
            raise ValueError(f"headings {h.tolist()} rarely see the feature with platform {platform.key!r}")
    cat = lambda i: np.concatenate([x[i] for x in got])[:n]  # noqa: E731
    views = Views(*(np.concatenate([getattr(x[0], f) for x in got])[:n]
                    for f in ("W", "origin", "vehicle", "feature")))
    port, g, alt, pitch, phi = (cat(i) for i in range(1, 6))
    draws = {}
    for j in range(k):
        draws.update({f"heading{j + 1}_deg": np.full(n, h[j]),
                      f"side{j + 1}": np.where(port[:, j], "port", "starboard"),
                      f"ground_offset{j + 1}_m": g[:, j], f"altitude{j + 1}_m": alt[:, j],
                      f"pitch{j + 1}_deg": pitch[:, j], f"elevation{j + 1}_deg": np.degrees(phi[:, j])})
    return views, pd.DataFrame(draws)
