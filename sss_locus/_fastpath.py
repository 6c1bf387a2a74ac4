"""Row-wise reductions over short rows of bytes, done eight bytes at a time (private).

The arc arrangement in :mod:`sss_locus.arcs` works on rows of 16 boundaries. NumPy reductions
and scans along such a short last axis (``cumsum``, ``sum``, ``all`` with ``axis=1``) pay a
per-row overhead that dwarfs the arithmetic. Here each row of small non-negative integers
(``uint8`` or ``bool``, one byte each) is viewed as 64-bit words holding eight bytes, and the
per-row work becomes a few whole-array integer operations ("SIMD within a register"):

* multiplying a word by ``0x0101010101010101`` leaves in its byte ``j`` the sum of its bytes
  ``0 .. j`` (little-endian byte order), provided no partial sum exceeds 255, so no carry
  crosses into the next byte;
* byte 7 of that product is the sum of all eight bytes.

All results are exact integers; nothing here involves floating point.
"""

from __future__ import annotations

import sys

import numpy as np

_ONES = np.uint64(0x0101010101010101)
"""One in every byte of a 64-bit word."""

_SHIFT = np.uint64(56)

_NATIVE = sys.byteorder == "little"
"""The byte tricks assume byte ``j`` of a word is its bits ``8j .. 8j+7``; elsewhere the plain
NumPy reductions are used."""


def _words(a: np.ndarray) -> np.ndarray | None:
    """``a`` (N, G) of one-byte items viewed as (N, G // 8) uint64 words, or None if impossible."""
    if not _NATIVE or a.shape[1] % 8 or not a.flags.c_contiguous or a.itemsize != 1:
        return None
    return a.view(np.uint64)


def prefix_sums(codes: np.ndarray) -> np.ndarray:
    """Inclusive running sums along each row of ``codes``.

    Parameters
    ----------
    codes : ndarray of uint8, shape (N, G)
        Small non-negative integers whose row sums stay below 256 (for example codes 0, 1, 2
        with ``G`` <= 127).

    Returns
    -------
    ndarray of uint8, shape (N, G)
        ``out[i, j] = sum(codes[i, :j + 1])``, the same as ``np.cumsum(codes, axis=1)``.
    """
    w = _words(codes)
    if w is None:
        return np.cumsum(codes, axis=1, dtype=np.uint8)
    p = w * _ONES  # byte j of each word: sum of that word's bytes 0..j
    for k in range(1, p.shape[1]):  # carry the previous word's total into every byte
        p[:, k] += (p[:, k - 1] >> _SHIFT) * _ONES
    return p.view(np.uint8)


def row_sums(flags: np.ndarray) -> np.ndarray:
    """Number of true entries in each row of a C-contiguous bool array ``flags`` (N, G)."""
    w = _words(flags)
    if w is None:
        return np.count_nonzero(flags, axis=1)
    total = w[:, 0].copy()
    for k in range(1, w.shape[1]):  # bytewise add: each byte stays <= G / 8, no carries
        total += w[:, k]
    return ((total * _ONES) >> _SHIFT).astype(np.int64)


def rows_all(flags: np.ndarray) -> np.ndarray:
    """Whether every entry of each row of a C-contiguous bool array ``flags`` (N, G) is true."""
    w = _words(flags)
    if w is None:
        return flags.all(axis=1)
    both = w[:, 0].copy()
    for k in range(1, w.shape[1]):
        both &= w[:, k]
    return both == _ONES  # a bool byte is 0 or 1: all ones exactly when all are true
