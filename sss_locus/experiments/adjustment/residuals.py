"""The joint adjustment's weighted residuals and their sparse Jacobian.

Unknowns ``x`` (:class:`JointProblem`): the 3-D position of every adjusted feature (world frame,
m; features in :attr:`JointProblem.features` order), then the free corrections of every pass
(:data:`~sss_locus.experiments.adjustment.model.CORRECTION_NAMES` order, only those whose prior
sigma is > 0; m, rad, m/m). Residuals, each in units of its standard deviation, in this order:

1. every sighting's slant range: ``(|f - o_true| - rho) / sigma_rho``;
2. every sighting with a finite beam-plane sigma: ``phi(f; o_true, W_true) / sigma_phi``
   (:func:`~sss_locus.geometry.beam_plane.beam_plane_angle`);
3. every free pass correction: ``c / sigma_prior`` (the navigation prior);
4. every feature with a height prior: ``(f_z - z_prior) / sigma_z``.

A range row has 3 feature entries and one per free correction of its pass; so has a beam-plane
row. The Jacobian is assembled as a ``scipy.sparse.csr_matrix`` with a structure fixed at
construction (:meth:`JointProblem.sparsity`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...geometry.beam_plane import beam_plane_angle
from .model import NavigationPriors, Sightings, corrected_poses


class JointProblem:
    """The residuals of one adjustment (module docstring).

    Parameters
    ----------
    sightings : Sightings
        Only sightings of the adjusted ``features`` are used.
    priors : NavigationPriors
    features : ndarray of int, shape (n,)
        The feature indices adjusted (unknowns), sorted, unique.
    height_prior_m, height_sigma_m : ndarray, shape (n,), optional
        A prior on each adjusted feature's ``z`` (m) and its sigma (m, ``inf`` or NaN: none).
    estimate_passes : bool
        With False the pass corrections are held at zero (a per-feature estimate from the
        navigated poses).
    use : ndarray of bool, shape (m,), optional
        The sightings to use (default all of the adjusted features').
    """

    def __init__(self, sightings: Sightings, priors: NavigationPriors, features: np.ndarray, *,
                 height_prior_m=None, height_sigma_m=None, estimate_passes: bool = True, use=None) -> None:
        self.priors = priors
        self.features = np.asarray(features, np.int64)
        slot = np.full(int(max(sightings.feature.max(initial=-1), self.features.max(initial=-1))) + 1, -1, np.int64)
        slot[self.features] = np.arange(self.features.size)
        keep = np.flatnonzero((slot[sightings.feature] >= 0) & (True if use is None else np.asarray(use, bool)))
        keep = keep[np.argsort(slot[sightings.feature[keep]], kind="stable")]  # rows by feature: local access
        self.rows = keep  # indices of the sightings used
        self.s = sightings
        self.used = Sightings(feature=sightings.feature[keep], pass_index=sightings.pass_index[keep],
                              origin_m=sightings.origin_m[keep], W=sightings.W[keep], range_m=sightings.range_m[keep],
                              range_sigma_m=sightings.range_sigma_m[keep],
                              beam_plane_sigma_rad=sightings.beam_plane_sigma_rad[keep],
                              along_track_m=sightings.along_track_m[keep])
        self.fslot = slot[sightings.feature[keep]]
        self.pidx = sightings.pass_index[keep]
        n, P = self.features.size, priors.n_passes
        sig = priors.sigmas()
        free = (sig > 0) & bool(estimate_passes)
        self.free = free
        self.prior_sigma = sig[free]
        col = np.full((P, 5), -1, np.int64)
        col[free] = 3 * n + np.arange(int(free.sum()))
        self.col = col
        self.n_params = 3 * n + int(free.sum())
        self.beam = np.isfinite(sightings.beam_plane_sigma_rad[keep])
        self.n_meas = keep.size + int(self.beam.sum())
        hs = np.full(n, np.inf) if height_sigma_m is None else np.asarray(height_sigma_m, float)
        self.height_rows = np.flatnonzero(np.isfinite(hs) & (hs > 0))
        self.height_prior = (np.zeros(n) if height_prior_m is None else np.asarray(height_prior_m, float))[self.height_rows]
        self.height_sigma = hs[self.height_rows]
        self.n_residuals = self.n_meas + self.prior_sigma.size + self.height_rows.size
        # the fixed structure: per measurement row its feature's 3 columns and its pass's 5
        fcols = 3 * self.fslot[:, None] + np.arange(3)
        pcols = col[self.pidx]
        self.mcols = np.concatenate([fcols, pcols], axis=1)  # (k, 8), -1 where not free
        self.mcols = np.concatenate([self.mcols, self.mcols[self.beam]])
        r = np.repeat(np.arange(self.n_meas), 8).reshape(-1, 8)
        self.mkeep = self.mcols >= 0
        prow = self.n_meas + np.arange(self.prior_sigma.size)
        hrow = self.n_meas + self.prior_sigma.size + np.arange(self.height_rows.size)
        self.jrows = np.concatenate([r[self.mkeep], prow, hrow])
        self.jcols = np.concatenate([self.mcols[self.mkeep], col[free],
                                     3 * self.height_rows + 2])

    def split(self, x) -> tuple[np.ndarray, np.ndarray]:
        """Feature positions (n, 3) and pass corrections (P, 5) (zeros where not free) of ``x``.

        Parameters
        ----------
        x : numpy.ndarray
            Parameter vector, shape (:attr:`n_params`,).

        Returns
        -------
        points : numpy.ndarray
            Feature positions, world ENU, m, shape (n, 3).
        corrections : numpy.ndarray
            Pass corrections, shape (P, 5) (m and radians as in the module docstring).
        """
        c = np.zeros((self.priors.n_passes, 5))
        c[self.free] = x[3 * self.features.size:]
        return x[:3 * self.features.size].reshape(-1, 3), c

    def pack(self, points, corrections) -> np.ndarray:
        """``x`` from feature positions (n, 3) and pass corrections (P, 5).

        Parameters
        ----------
        points : array_like
            Feature positions, world ENU, m, shape (n, 3).
        corrections : array_like
            Pass corrections, shape (P, 5); only the free entries are kept.

        Returns
        -------
        numpy.ndarray
            Parameter vector, shape (:attr:`n_params`,).
        """
        return np.concatenate([np.asarray(points, float).ravel(), np.asarray(corrections, float)[self.free]])

    def _geometry(self, x):
        f, c = self.split(x)
        o, W = corrected_poses(self.used, self.priors, c)
        return f[self.fslot], o, W, c

    def residuals(self, x) -> np.ndarray:
        """The weighted residuals (module docstring), shape (:attr:`n_residuals`,).

        Parameters
        ----------
        x : numpy.ndarray
            Parameter vector, shape (:attr:`n_params`,).

        Returns
        -------
        numpy.ndarray
            Dimensionless residuals (each divided by its sigma).
        """
        p, o, W, c = self._geometry(x)
        return self._residuals(p, o, W, c)

    def _residuals(self, p, o, W, c):
        k = self.rows
        d = p - o
        r = np.sqrt(np.sum(d * d, axis=1))
        e_r = (r - self.s.range_m[k]) / self.s.range_sigma_m[k]
        b = self.beam
        phi, _ = beam_plane_angle(p[b], o[b], W[b])
        e_b = phi / self.s.beam_plane_sigma_rad[k][b]
        e_p = c[self.free] / self.prior_sigma
        return np.concatenate([e_r, e_b, e_p, self._height_residuals(p)])

    def _height_residuals(self, p):
        if not self.height_rows.size:
            return np.zeros(0)
        z = np.zeros(self.features.size)
        z[self.fslot] = p[:, 2]
        return (z[self.height_rows] - self.height_prior) / self.height_sigma

    def jacobian(self, x) -> sp.csr_matrix:
        """The residuals' Jacobian at ``x``, ``(n_residuals, n_params)`` sparse.

        Parameters
        ----------
        x : numpy.ndarray
            Parameter vector, shape (:attr:`n_params`,).

        Returns
        -------
        scipy.sparse.csr_matrix
            Shape (:attr:`n_residuals`, :attr:`n_params`).
        """
        p, o, W, c = self._geometry(x)
        k, pi = self.rows, self.pidx
        d = p - o
        r = np.sqrt(np.sum(d * d, axis=1))
        dh = d / np.where(r > 0, r, 1.0)[:, None]
        # d o_true / d heading (zero unless the heading moves the track)
        do_dh = np.zeros_like(o)
        if self.priors.heading_moves_track:
            h = c[pi, 2]
            rel = self.s.origin_m[k, :2] - self.priors.reference_m[pi]
            cos, sin = np.cos(h), np.sin(h)
            do_dh[:, 0] = -sin * rel[:, 0] - cos * rel[:, 1]
            do_dh[:, 1] = cos * rel[:, 0] - sin * rel[:, 1]
        s = self.s.along_track_m[k]
        blocks = [self._rows(dh, np.zeros(k.size), do_dh, s, 1.0 / self.s.range_sigma_m[k])]
        b = self.beam
        phi, grad = beam_plane_angle(p[b], o[b], W[b])
        # d phi / d heading through the axes: (Rz'(h) u) . d_hat / cos(phi), Rz' u = (-u_y, u_x, 0) after R
        u = W[b][:, :, 2]
        du = np.stack([-u[:, 1], u[:, 0], np.zeros(u.shape[0])], -1)
        extra = np.sum(du * dh[b], axis=1) / np.maximum(np.cos(phi), 1e-12)
        blocks.append(self._rows(grad, extra, do_dh[b], s[b], 1.0 / self.s.beam_plane_sigma_rad[k][b]))
        data = np.concatenate(blocks)[self.mkeep]
        data = np.concatenate([data, 1.0 / self.prior_sigma, 1.0 / self.height_sigma])
        return sp.csr_matrix((data, (self.jrows, self.jcols)), shape=(self.n_residuals, self.n_params))

    @staticmethod
    def _rows(g, extra, do_dh, s, w):
        """The 8 entries of measurement rows with gradient ``g`` (k, 3) w.r.t. the feature:
        feature (3), offsets (2), heading, drifts (2); each times the weight ``w``."""
        out = np.empty((g.shape[0], 8))
        out[:, :3] = g
        out[:, 3:5] = -g[:, :2]
        out[:, 5] = extra - np.sum(g * do_dh, axis=1)
        out[:, 6:8] = -s[:, None] * g[:, :2]
        return out * np.asarray(w)[:, None]

    def sparsity(self) -> sp.csr_matrix:
        """The Jacobian's structure (ones), for ``least_squares(jac_sparsity=...)``.

        Returns
        -------
        scipy.sparse.csr_matrix
            Shape (:attr:`n_residuals`, :attr:`n_params`), ones where the Jacobian may be non-zero.
        """
        return sp.csr_matrix((np.ones(self.jrows.size), (self.jrows, self.jcols)), shape=(self.n_residuals, self.n_params))
