"""An independent sidescan survey simulation for the joint-adjustment tests (not the chapter's
simulator: its own terrain, lines, pings, navigation errors and flat mosaic, written from the
physics, sharing no code with ``sss_locus.experiments``).

World: ``x`` east, ``y`` north, ``z`` up, metres. The seafloor is ``z = -depth + relief *
sin(x / 37) cos(y / 23) + slope * x``. Lines run north/south (main) and east/west (cross) at a
constant height; every line's ping sees features on both sides within ``[min_ground, max_ground]``
across track. Each pass has a navigation error: the navigated position is the true one minus an
offset (per pass), minus a drift times the along-track position, and the navigated heading is the
true one minus a heading bias (the positions come from GNSS: the bias turns only the sonar).
Each ping also has a small independent position and attitude jitter.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def seafloor(x, y, depth, relief, slope):
    return -depth + relief * np.sin(x / 37.0) * np.cos(y / 23.0) + slope * x


def rotz(a):
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(np.shape(a) + (3, 3))
    R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1], R[..., 2, 2] = c, -s, s, c, 1.0
    return R


@dataclass
class Survey:
    truth: np.ndarray          # (n, 3) true features
    feature: np.ndarray        # (m,) sighting -> feature
    pass_index: np.ndarray     # (m,)
    origin_nav: np.ndarray     # (m, 3) navigated sensor origins
    W_nav: np.ndarray          # (m, 3, 3) navigated sensor axes
    range_m: np.ndarray        # (m,)
    along_m: np.ndarray        # (m,) along-track position from the pass reference
    altimeter_m: np.ndarray    # (m,) true height of the sensor above the seafloor below it
    side: np.ndarray           # (m,) +1 port, -1 starboard
    reference: np.ndarray      # (P, 2)
    offsets: np.ndarray        # (P, 2) true corrections (true minus navigated)
    heading_bias: np.ndarray   # (P,) rad
    drift: np.ndarray          # (P, 2) m/m


def simulate(seed, *, n_features=400, area=300.0, spacing=60.0, n_cross=3, depth=30.0, relief=4.0, slope=0.02,
             sensor_z=-5.0, min_ground=8.0, max_ground=110.0, tilt_deg=25.0, beam_deg=0.5,
             offset_sigma=2.0, heading_sigma_deg=1.0, drift_sigma=0.0, range_sigma=0.05,
             jitter_m=0.05, jitter_deg=0.05, wrong_share=0.0) -> Survey:
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-area / 2, area / 2, (n_features, 2))
    truth = np.column_stack([xy, seafloor(xy[:, 0], xy[:, 1], depth, relief, slope)])
    lines = []  # (heading, point)
    for j, x in enumerate(np.arange(-area / 2, area / 2 + 1e-9, spacing)):
        lines.append((np.pi / 2 if j % 2 == 0 else -np.pi / 2, np.array([x, 0.0])))
    for j, y in enumerate(np.linspace(-area / 3, area / 3, n_cross)):
        lines.append((0.0 if j % 2 == 0 else np.pi, np.array([0.0, y])))
    P = len(lines)
    offsets = rng.normal(0, offset_sigma, (P, 2))
    hbias = rng.normal(0, np.radians(heading_sigma_deg), P)
    drift = rng.normal(0, drift_sigma, (P, 2)) if drift_sigma > 0 else np.zeros((P, 2))
    tilt, half = np.radians(tilt_deg), np.radians(beam_deg) / 2
    rows = {k: [] for k in ("f", "p", "o", "W", "r", "s", "alt", "side")}
    for j, (h, c) in enumerate(lines):
        e = np.array([np.cos(h), np.sin(h), 0.0])
        nrm = np.array([-np.sin(h), np.cos(h), 0.0])  # port
        rel = truth[:, :2] - c
        across, along = rel @ nrm[:2], rel @ e[:2]
        seen = (np.abs(across) >= min_ground) & (np.abs(across) <= max_ground) & (np.abs(along) <= area / 2 + 20)
        for i in np.flatnonzero(seen):
            side = 1.0 if across[i] > 0 else -1.0
            # the ping: the feature at elevation phi ~ U(-half, half) in the true beam plane
            phi = rng.uniform(-half, half)
            s = along[i]
            for _ in range(3):
                o = np.array([*(c + s * e[:2]), sensor_z])
                r = np.linalg.norm(truth[i] - o)
                s = along[i] - r * np.sin(phi)
            o = np.array([*(c + s * e[:2]), sensor_z])
            x_ax = np.cos(tilt) * side * nrm - np.sin(tilt) * np.array([0, 0, 1.0])
            z_ax = e
            W = np.column_stack([x_ax, np.cross(z_ax, x_ax), z_ax])
            rows["f"].append(i), rows["p"].append(j), rows["o"].append(o), rows["W"].append(W)
            rows["r"].append(np.linalg.norm(truth[i] - o)), rows["s"].append(s)
            rows["alt"].append(o[2] - seafloor(o[0], o[1], depth, relief, slope)), rows["side"].append(side)
    f, p = np.array(rows["f"]), np.array(rows["p"])
    o_true, W_true, s = np.array(rows["o"]), np.array(rows["W"]), np.array(rows["s"])
    m = f.size
    rng2 = np.random.default_rng(seed + 1000)
    # navigated = true minus the pass's error, plus per-ping jitter
    o_nav = o_true.copy()
    o_nav[:, :2] -= offsets[p] + s[:, None] * drift[p]
    o_nav += rng2.normal(0, jitter_m, (m, 3)) * np.array([1, 1, 0.5])
    jit = rotz(rng2.normal(0, np.radians(jitter_deg), m))
    W_nav = jit @ rotz(-hbias[p]) @ W_true
    rng_m = np.linalg.norm(truth[f] - o_true, axis=1) + rng2.normal(0, range_sigma, m)
    if wrong_share > 0:  # wrong data association: a sighting attributed to another feature
        k = rng2.choice(m, int(round(wrong_share * m)), replace=False)
        f = f.copy()
        f[k] = (f[k] + rng2.integers(1, n_features, k.size)) % n_features
    ref = np.array([c for _, c in lines])
    return Survey(truth=truth, feature=f, pass_index=p, origin_nav=o_nav, W_nav=W_nav, range_m=rng_m, along_m=s,
                  altimeter_m=np.array(rows["alt"]), side=np.array(rows["side"]), reference=ref, offsets=offsets,
                  heading_bias=hbias, drift=drift)


def flat_mosaic(sv: Survey) -> np.ndarray:
    """Each sighting slant-range corrected on a flat seafloor at the altimeter's height, placed
    across the navigated track in the navigated beam plane; averaged per feature."""
    g = np.sqrt(np.maximum(sv.range_m ** 2 - sv.altimeter_m ** 2, 0.0))
    fwd = sv.W_nav[:, :, 2].copy()
    fwd[:, 2] = 0
    fwd /= np.linalg.norm(fwd, axis=1, keepdims=True)
    port = np.column_stack([-fwd[:, 1], fwd[:, 0]])
    pts = np.column_stack([sv.origin_nav[:, :2] + (sv.side * g)[:, None] * port, sv.origin_nav[:, 2] - sv.altimeter_m])
    n = sv.truth.shape[0]
    cnt = np.bincount(sv.feature, minlength=n)
    out = np.stack([np.bincount(sv.feature, pts[:, a], minlength=n) for a in range(3)], -1)
    return out / np.maximum(cnt, 1)[:, None]
