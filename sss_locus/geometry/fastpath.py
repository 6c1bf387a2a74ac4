"""Row-wise reductions over short rows of bytes, done eight bytes at a time (private).

The arc arrangement in :mod:`sss_locus.geometry.arcs` works on rows of 16 boundaries. NumPy reductions
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


def _fold(w: np.ndarray, op: np.ufunc) -> np.ndarray:
    """Combine the words of each row with a bytewise-safe ``op`` (add, and, or): (N,) uint64."""
    out = w[:, 0].copy()
    for k in range(1, w.shape[1]):
        op(out, w[:, k], out=out)
    return out


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
    """Number of true entries in each row of a C-contiguous bool array ``flags`` (N, G).

    Parameters
    ----------
    flags : ndarray of bool, shape (N, G)
        Any ``G`` (the byte trick needs ``G`` a multiple of 8 and C order, otherwise
        ``np.count_nonzero`` is used).

    Returns
    -------
    ndarray of int64, shape (N,)
        ``np.count_nonzero(flags, axis=1)``; 0 for an all-false row.
    """
    w = _words(flags)
    if w is None:
        return np.count_nonzero(flags, axis=1)
    total = _fold(w, np.add)  # bytewise add: each byte stays <= G / 8, no carries
    return ((total * _ONES) >> _SHIFT).astype(np.int64)


def rows_all(flags: np.ndarray) -> np.ndarray:
    """Whether every entry of each row of a C-contiguous bool array ``flags`` (N, G) is true.

    Parameters
    ----------
    flags : ndarray of bool, shape (N, G)

    Returns
    -------
    ndarray of bool, shape (N,)
        ``flags.all(axis=1)`` (True for ``G == 0``).
    """
    w = _words(flags)
    if w is None:
        return flags.all(axis=1)
    return _fold(w, np.bitwise_and) == _ONES  # bool bytes are 0 or 1: all ones when all true


def rows_any(flags: np.ndarray) -> np.ndarray:
    """Whether any entry of each row of a C-contiguous bool array ``flags`` (N, G) is true.

    Parameters
    ----------
    flags : ndarray of bool, shape (N, G)

    Returns
    -------
    ndarray of bool, shape (N,)
        ``flags.any(axis=1)`` (False for ``G == 0``).
    """
    w = _words(flags)
    if w is None:
        return flags.any(axis=1)
    return _fold(w, np.bitwise_or) != 0


def first_true(flags: np.ndarray) -> np.ndarray:
    """Column of the first true entry in each row of a C-contiguous bool array (N, G).

    The same as ``np.argmax(flags, axis=1)``, including 0 for a row with no true entry. In a
    word, ``w & -w`` keeps only the lowest set bit, and the popcount of that bit minus one is the
    number of trailing zero bits (64 for a zero word); a row's trailing zero bits over its
    words, divided by 8, is the column.

    Parameters
    ----------
    flags : ndarray of bool, shape (N, G)
        The word trick is used for ``G == 16``; any other ``G`` falls back to ``np.argmax``.

    Returns
    -------
    ndarray of int64, shape (N,)
        Column index in ``[0, G)``; 0 also for a row with no true entry.
    """
    w = _words(flags)
    if w is None or w.shape[1] != 2:
        return np.argmax(flags, axis=1)
    low = w & (~w + np.uint64(1))
    low -= np.uint64(1)
    zeros = np.bitwise_count(low)  # (N, 2) uint8: trailing zero bits of each word
    bits = zeros[:, 0].astype(np.int64)
    bits += (zeros[:, 0] == 64) * zeros[:, 1]  # the first word is empty: count on into the second
    bits >>= 3
    bits &= 15  # an empty row (128 bits) gives 16: make it 0, as argmax does
    return bits


def cyclic_edges(flags: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where runs of true entries start and end in each row of a bool array (N, G), cyclically.

    Returns ``(flags & ~np.roll(flags, 1, axis=1), flags & ~np.roll(flags, -1, axis=1))``. Rolling
    a row by one column shifts its words by one byte, with the byte that falls off one word
    entering the neighbouring word (the last and first words are neighbours).

    Parameters
    ----------
    flags : ndarray of bool, shape (N, G)

    Returns
    -------
    starts, ends : ndarray of bool, shape (N, G)
        True at the first and at the last column of each cyclic run of true entries; an
        all-true row has neither, an all-false row neither.
    """
    w = _words(flags)
    if w is None:
        return flags & ~np.roll(flags, 1, axis=1), flags & ~np.roll(flags, -1, axis=1)
    n_words = w.shape[1]
    starts = np.empty_like(w)
    ends = np.empty_like(w)
    eight = np.uint64(8)
    for k in range(n_words):
        word, before, after = w[:, k], w[:, k - 1], w[:, (k + 1) % n_words]
        previous = (word << eight) | (before >> _SHIFT)  # byte j holds column j - 1
        following = (word >> eight) | (after << _SHIFT)  # byte j holds column j + 1
        starts[:, k] = word & ~previous
        ends[:, k] = word & ~following
    return starts.view(bool), ends.view(bool)


def diagonal_matches(sums: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Where ``sums[:, j] == target + j``, for running sums from :func:`prefix_sums`.

    Parameters
    ----------
    sums : ndarray of uint8, shape (N, G)
        Values in ``[0, 2 G]``.
    target : ndarray of int, shape (N,)
        Values in ``[-2 G, 3 G]``.

    Returns
    -------
    ndarray of bool, shape (N, G)

    Notes
    -----
    With ``G <= 16`` every byte ``sums_j - j + 64`` and ``target + 64`` lies in [0, 127], so
    both are formed bytewise without carries; XOR leaves a zero byte exactly where they agree,
    and adding 0x7F to a byte below 0x80 sets its top bit exactly when it is non-zero.
    """
    N, G = sums.shape
    w = _words(sums)
    if w is None or G > 16:
        return sums.astype(np.int64) == target[:, None] + np.arange(G)
    want = (target + 64).astype(np.uint64) * _ONES
    out = np.empty_like(w)
    for k in range(w.shape[1]):
        # byte j of this word gets 64 - (column number) added: sums_j - j + 64
        bias = np.uint64(int.from_bytes(bytes(64 - 8 * k - j for j in range(8)), "little"))
        differ = (w[:, k] + bias) ^ want
        nonzero = (differ + np.uint64(0x7F7F7F7F7F7F7F7F)) & np.uint64(0x8080808080808080)
        out[:, k] = (nonzero >> np.uint64(7)) ^ _ONES
    return out.view(bool)


def transpose_into(dst: np.ndarray, src: np.ndarray) -> np.ndarray:
    """``dst[...] = src.T`` for 2-D arrays with a short axis, one row/column at a time.

    NumPy's general transposing copy walks the short axis innermost; copying whole columns
    (strided) from whole rows (contiguous), or back, is several times faster when one of the two
    axes has only a few entries.

    Parameters
    ----------
    dst : ndarray, shape (A, B)
        Written in place.
    src : ndarray, shape (B, A)

    Returns
    -------
    ndarray, shape (A, B)
        ``dst`` itself, now holding ``src.T``.
    """
    if dst.shape[1] <= dst.shape[0]:  # few columns in dst: fill column by column
        for j in range(dst.shape[1]):
            dst[:, j] = src[j]
    else:
        for i in range(dst.shape[0]):
            dst[i] = src[:, i]
    return dst


def rotate_rows(Rc: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``R @ v`` for stacks of component-major vectors.

    ``Rc`` (3, 3, n) holds ``R[:, i, j]`` at ``[i, j]``; ``v`` (..., 3, n) holds vector
    components along its second-last axis. Summed in the order ``R_i0 v_0 + R_i1 v_1 + R_i2 v_2``.

    Parameters
    ----------
    Rc : ndarray, shape (3, 3, n)
        Rotation matrices, component-major (``Rc[i, j]`` is entry ``(i, j)`` of each).
    v : ndarray, shape (..., 3, n)
        Vectors, component-major (any unit; the frame they are rotated from is the one ``R``
        maps from).

    Returns
    -------
    ndarray, shape (..., 3, n)
        The rotated vectors, component-major, in the same unit.
    """
    return Rc[:, 0] * v[..., 0:1, :] + Rc[:, 1] * v[..., 1:2, :] + Rc[:, 2] * v[..., 2:3, :]


def cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of component-major vectors (3, n), in the operation order of ``np.cross``.

    Parameters
    ----------
    a, b : ndarray, shape (3, n)
        Vectors, component-major.

    Returns
    -------
    ndarray, shape (3, n)
        ``a x b``, component-major (bitwise equal to ``np.cross(a.T, b.T).T``).
    """
    return np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])
