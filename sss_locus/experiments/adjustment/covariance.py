"""First-order covariances of an adjustment: ``(J^T J)^-1`` by the Schur complement.

``J`` is the weighted Jacobian at the optimum (columns: ``3 n`` feature coordinates, then ``c``
pass corrections). Every row touches at most one feature, so the feature block ``H_ff`` of
``H = J^T J`` is block diagonal (3 x 3 per feature) and the passes' block small (``c`` is five
per pass at most). With ``H_fc`` the off-diagonal block and ``B = H_ff^-1 H_fc``:

    S = H_cc - H_fc^T B                       (the reduced system of the passes)
    Cov_cc = S^-1,    Cov_f = H_f^-1 + B_f S^-1 B_f^T   (each feature's 3 x 3 marginal)

computed feature-chunk by feature-chunk (memory of a chunk, not of ``3 n x c``). A feature whose
3 x 3 block is singular gets an infinite covariance, never NaN.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

CHUNK_FEATURES = 4096


def feature_blocks(Jf, n_features: int) -> np.ndarray:
    """The 3 x 3 diagonal blocks of ``Jf^T Jf``, shape (n, 3, 3), for the feature columns ``Jf``
    (sparse, ``3 n`` columns, each row touching one feature).

    Parameters
    ----------
    Jf : scipy.sparse matrix
        Jacobian columns of the features, shape (rows, 3 n).
    n_features : int
        Number of features n.

    Returns
    -------
    numpy.ndarray
        Shape (n, 3, 3), in 1/m² (residuals in sigmas); zero blocks for unseen features.
    """
    H = sp.coo_matrix(Jf.T @ Jf)
    blocks = np.zeros((int(n_features), 3, 3))
    np.add.at(blocks, (H.row // 3, H.row % 3, H.col % 3), H.data)
    return blocks


def marginal_covariances(J, n_features: int) -> tuple[np.ndarray, np.ndarray]:
    """Per-feature 3 x 3 covariances and the passes' covariance from a weighted Jacobian.

    Parameters
    ----------
    J : scipy.sparse matrix, shape (rows, 3 n + c)
        Weighted Jacobian (residuals in units of their sigma); columns as the module docstring.
    n_features : int
        ``n``.

    Returns
    -------
    feature_cov : ndarray, shape (n, 3, 3)
        m^2; ``inf`` where a feature's block is singular.
    pass_cov : ndarray, shape (c, c)
        Covariance of the pass corrections (their units squared).
    """
    J = sp.csc_matrix(J)
    n3 = 3 * int(n_features)
    Jf, Jc = J[:, :n3], J[:, n3:]
    blocks = feature_blocks(Jf, n_features)
    det = np.linalg.det(blocks)
    scale = np.einsum("nii->n", blocks) ** 3
    singular = ~(np.abs(det) > 1e-12 * np.maximum(scale, 1e-300))
    inv = np.linalg.inv(np.where(singular[:, None, None], np.eye(3), blocks))
    c = Jc.shape[1]
    if c == 0:
        return np.where(singular[:, None, None], np.inf, inv), np.zeros((0, 0))
    Hfc = sp.csr_matrix(Jf.T @ Jc)
    Hinv = sp.bsr_matrix((np.where(singular[:, None, None], 0.0, inv), np.arange(n_features),
                          np.arange(n_features + 1)), shape=(n3, n3))
    B = sp.csr_matrix(Hinv @ Hfc)
    S = (Jc.T @ Jc).toarray() - (Hfc.T @ B).toarray()
    S_inv = np.linalg.inv(S)
    cov = inv.copy()
    for start in range(0, n_features, CHUNK_FEATURES):
        stop = min(start + CHUNK_FEATURES, n_features)
        Bd = B[3 * start:3 * stop].toarray().reshape(stop - start, 3, c)
        cov[start:stop] += np.einsum("mac,cd,mbd->mab", Bd, S_inv, Bd, optimize=True)
    return np.where(singular[:, None, None], np.inf, cov), S_inv
