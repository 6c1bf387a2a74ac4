"""Input validation and magnitude rescaling shared by the kernels.

Every public kernel converts its inputs through these helpers so that bad input fails early,
naming the argument and what is allowed, instead of surfacing later as a NaN or a traceback from
inside numpy:

* numeric arguments accept real numbers only (Python or NumPy ints and floats, and arrays of
  them). Booleans, complex numbers, strings and bytes, dates, datetimes and timedeltas, ``None``
  and object arrays (``Decimal``, ``Fraction``, integers beyond int64, lists mixing numbers
  with dates or ``None``) raise :class:`InputTypeError`, a ``TypeError`` that is also a
  ``ValueError``. The check is on the dtype NumPy gives the input, so a Python list mixing
  floats with ``True``/``False`` (which NumPy reads as floats) is not caught;
* values must be finite (``ValueError``);
* lengths whose squares a kernel returns (the two-view ``C``, m^2) must lie within
  [:data:`LENGTH_MIN`, :data:`LENGTH_MAX`] metres, so that every returned number is
  representable in float64 (``ValueError`` naming the range).

Inside that range the kernels are exact at any magnitude: they rescale each configuration by a
power of two (:func:`row_exponents`), which is exact in binary floating point, so no square or
fourth power overflows or underflows (the locus is scale-covariant: lengths scale with a common
factor, angles and statuses do not change).
"""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np

ROTATION_ATOL = 1e-9
"""Tolerance on ``max |R^T R - I|`` and ``|det R - 1|`` for a matrix to count as a rotation."""

LENGTH_MAX = 1e150
"""Largest range or translation component (m) :func:`~sss_locus.geometry.two_view_locus`
accepts: its ``C`` (m^2, a sum of squared lengths) must stay below the float64 maximum
(about 1.8e308)."""

LENGTH_MIN = 1e-150
"""Smallest range (m) :func:`~sss_locus.geometry.two_view_locus` accepts: the squares in ``C``
must stay above the smallest normal float64 (about 2.2e-308), where precision is lost."""

_REAL_KINDS = "iuf"  # signed and unsigned integers, floats
_SAFE_EXPONENT = 60
"""Batches whose configurations' largest lengths all lie within 2**-60 .. 2**60 are computed
without rescaling (see :func:`row_exponents`)."""


class InputTypeError(TypeError, ValueError):
    """An argument of the wrong type: a numeric argument that is not real numbers (bool,
    complex, str, date, object, ...), or an aperture that is not an :class:`Aperture`.

    A ``TypeError``; also a ``ValueError`` so that callers that catch the kernels' other input
    errors catch this one too.
    """


def _describe(value, arr: np.ndarray) -> str:
    if isinstance(value, np.ndarray) or arr.ndim:
        kinds = {"b": "booleans", "c": "complex numbers", "U": "strings", "S": "bytes",
                 "M": "datetimes", "m": "timedeltas", "O": "Python objects", "V": "records"}
        what = kinds.get(arr.dtype.kind, str(arr.dtype))
        return f"an array of {what} (dtype {arr.dtype})"
    return f"{type(value).__name__} {value!r}"


def as_real_array(value, name: str) -> np.ndarray:
    """Return ``value`` as a float64 array, refusing anything but real numbers.

    Raises :class:`InputTypeError` naming ``name`` for booleans, complex numbers, strings,
    dates and timedeltas, ``None`` and object arrays. NaN and infinity pass (see
    :func:`as_float_array` for the finite check).

    Parameters
    ----------
    value : array_like, any shape
        Real numbers (Python or NumPy ints and floats, arrays of them, or a masked array with
        nothing masked).
    name : str
        The argument's name, used in error messages.

    Returns
    -------
    numpy.ndarray of float64, shape of ``value``
        Not copied when ``value`` is already a float64 array.

    Raises
    ------
    InputTypeError
        Non-real input, or a masked array with masked entries.
    ValueError
        A ragged nested sequence.
    """
    if isinstance(value, np.ma.MaskedArray):
        if np.ma.getmaskarray(value).any():
            raise InputTypeError(f"{name} must be plain numbers; got a masked array with masked entries "
                                 "(drop them, or fill them with .filled(...), first)")
        value = value.data
    try:
        arr = value if isinstance(value, np.ndarray) else np.asarray(value)
    except ValueError:  # numpy refuses a ragged nested sequence
        raise ValueError(f"{name} must be a regular array of numbers; got a ragged sequence (rows of "
                         "different lengths)") from None
    if arr.dtype.kind not in _REAL_KINDS:
        raise InputTypeError(
            f"{name} must be real numbers (int or float); got {_describe(value, arr)}"
        )
    return arr.astype(np.float64, copy=False)


def as_float_array(value, name: str, *, tail: tuple[int, ...] = (), finite: bool = True) -> np.ndarray:
    """Return ``value`` as a float64 array of real numbers whose trailing dimensions are ``tail``.

    Non-real input raises :class:`InputTypeError`; a wrong shape, or (with ``finite``) NaN or
    infinity, a ``ValueError``; each message names ``name``.

    Parameters
    ----------
    value : array_like, shape (...,) + tail
        Real numbers.
    name : str
        The argument's name, used in error messages.
    tail : tuple of int
        Required trailing dimensions, e.g. ``(3,)`` for points or ``(3, 3)`` for rotations;
        ``()`` accepts any shape.
    finite : bool
        Refuse NaN and infinity (the message gives the first bad index).

    Returns
    -------
    numpy.ndarray of float64, shape (...,) + tail
    """
    arr = as_real_array(value, name)
    if tail and (arr.ndim < len(tail) or arr.shape[arr.ndim - len(tail):] != tail):
        want = "(..., " + ", ".join(str(n) for n in tail) + ")"
        raise ValueError(f"{name} must have shape {want}; got shape {arr.shape}")
    if finite and not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(
            f"{name} must be finite; found NaN or infinity at index {tuple(int(i) for i in bad)}"
        )
    return arr


def check_aperture(value, name: str, cls: type) -> None:
    """Refuse an aperture argument that is not a ``cls`` instance, naming ``name``.

    Parameters
    ----------
    value : object
        The argument to check.
    name : str
        The argument's name, used in the error message.
    cls : type
        The required class (:class:`~sss_locus.geometry.aperture.Aperture`; passed in to keep
        this module free of imports from the kernels).

    Raises
    ------
    InputTypeError
        ``value`` is not a ``cls`` instance.
    """
    if not isinstance(value, cls):
        raise InputTypeError(f"{name} must be an sss_locus.Aperture; got {type(value).__name__}")


def as_positive_array(value, name: str, *, bounded: bool = False) -> np.ndarray:
    """Return ``value`` as a finite float64 array of strictly positive numbers (ranges, m).

    With ``bounded``, values must also lie in [:data:`LENGTH_MIN`, :data:`LENGTH_MAX`].

    Parameters
    ----------
    value : array_like, any shape
        Real numbers, metres.
    name : str
        The argument's name, used in error messages.
    bounded : bool
        Also require every value within [:data:`LENGTH_MIN`, :data:`LENGTH_MAX`] m.

    Returns
    -------
    numpy.ndarray of float64, shape of ``value``
        An empty array is returned as is.

    Raises
    ------
    ValueError
        A value <= 0, not finite, or (with ``bounded``) out of range; the message names ``name``.
    """
    arr = as_float_array(value, name)
    if arr.size == 0:
        return arr
    lo = arr.min()
    if lo <= 0.0:
        raise ValueError(f"{name} must be > 0 (a measured range in metres); got min {lo:.6g}")
    if bounded:
        hi = arr.max()
        if lo < LENGTH_MIN or hi > LENGTH_MAX:
            raise ValueError(
                f"{name} must lie in [{LENGTH_MIN:g}, {LENGTH_MAX:g}] m (its square must be "
                f"representable in float64); got {lo if lo < LENGTH_MIN else hi:.6g}"
            )
    return arr


def check_max_abs(arr: np.ndarray, name: str, limit: float = LENGTH_MAX) -> None:
    """Refuse any ``|component|`` of ``arr`` above ``limit`` (m), naming ``name``.

    Parameters
    ----------
    arr : numpy.ndarray, any shape
        Lengths or coordinates, metres (an empty array passes).
    name : str
        The argument's name, used in the error message.
    limit : float
        Largest allowed absolute value, metres (default :data:`LENGTH_MAX`).

    Raises
    ------
    ValueError
        Some ``|component|`` exceeds ``limit``; the message gives the worst value.
    """
    if arr.size and np.abs(arr).max() > limit:
        raise ValueError(
            f"{name} components must lie in [-{limit:g}, {limit:g}] m (their squares must be "
            f"representable in float64); got {arr.flat[np.argmax(np.abs(arr))]:.6g}"
        )


def as_rotation_matrices(value, name: str = "R") -> np.ndarray:
    """Return rotation matrices of shape ``(..., 3, 3)``.

    Accepts a ``scipy.spatial.transform.Rotation`` (single or stacked) or an array. A matrix must
    be orthonormal with determinant +1 to within :data:`ROTATION_ATOL`.

    Parameters
    ----------
    value : array_like, shape (..., 3, 3), or scipy.spatial.transform.Rotation
        Rotation matrices (e.g. sensor-to-world, or frame 2 to frame 1).
    name : str
        The argument's name, used in error messages.

    Returns
    -------
    numpy.ndarray of float64, shape (..., 3, 3)
        The matrices, unchanged (not re-orthonormalised).

    Raises
    ------
    ValueError
        A matrix not orthonormal, or a reflection (determinant -1), beyond :data:`ROTATION_ATOL`.
    """
    if hasattr(value, "as_matrix") and callable(value.as_matrix):
        value = value.as_matrix()
    R = as_float_array(value, name, tail=(3, 3))
    # Entries as nine contiguous rows, m[3 * row + column], so every product below runs over
    # one long row (much faster than matmul or einsum on stacks of 3x3 matrices).
    m = np.ascontiguousarray(R.reshape(-1, 9).T)
    orth_err = np.zeros(m.shape[1])
    for i in range(3):  # entries (i, j) of R^T R: dot products of columns i and j
        for j in range(i, 3):
            dot = m[i] * m[j] + m[3 + i] * m[3 + j] + m[6 + i] * m[6 + j]
            np.maximum(orth_err, np.abs(dot - (1.0 if i == j else 0.0)), out=orth_err)
    if np.any(orth_err > ROTATION_ATOL):
        raise ValueError(
            f"{name} must be a rotation matrix (orthonormal): max |{name}^T {name} - I| is "
            f"{orth_err.max():.3g}, allowed {ROTATION_ATOL:g}"
        )
    det = (m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6])
           + m[2] * (m[3] * m[7] - m[4] * m[6]))
    if np.any(np.abs(det - 1.0) > ROTATION_ATOL):
        worst = det[np.argmax(np.abs(det - 1.0))]
        why = "a reflection" if worst < 0 else f"|det - 1| = {abs(worst - 1.0):.3g} > {ROTATION_ATOL:g}"
        raise ValueError(
            f"{name} must be a proper rotation (determinant +1); found determinant {worst:.12g} ({why})"
        )
    return R


#: Overrides the memory budget (bytes) of :func:`memory_budget`.
MEMORY_BUDGET_ENV = "SSS_LOCUS_MEMORY_BUDGET"


def _environment_memory_budget() -> str:
    """The memory budget of a script, as set: the environment variable :data:`MEMORY_BUDGET_ENV`.

    Returns
    -------
    str
        Bytes as text, or ``""`` (half the physical memory).
    """
    return os.environ.get(MEMORY_BUDGET_ENV, "")


#: ``() -> str``: the memory budget as set. A script's is ``$SSS_LOCUS_MEMORY_BUDGET``; a process
#: of the pipeline answers from its run context (:mod:`sss_locus.pipeline.run.context` installs itself).
memory_budget_setting: Callable[[], str] = _environment_memory_budget


def memory_budget() -> int:
    """Bytes one request may plan to use: the setting (``$SSS_LOCUS_MEMORY_BUDGET``, or the run
    context's) or half the physical memory.

    Returns
    -------
    int
        Bytes; 4e9 where the physical memory cannot be read.

    Raises
    ------
    ValueError
        The setting is not a number.
    """
    text = memory_budget_setting()
    if text:
        try:
            return int(float(text))
        except ValueError:
            raise ValueError(f"{MEMORY_BUDGET_ENV} must be a number of bytes, got {text!r}") from None
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") // 2
    except (ValueError, OSError, AttributeError):
        return 4 * 10**9


def check_memory(n_bytes: float, what: str) -> None:
    """Refuse, in one line, a request whose arrays (``n_bytes``) exceed :func:`memory_budget`.

    Parameters
    ----------
    n_bytes : float
        Estimated memory the request's arrays need, bytes.
    what : str
        What is requested, the start of the error message (e.g. ``"monte_carlo(n_draws=...)"``).

    Raises
    ------
    MemoryError
        ``n_bytes`` exceeds the budget; the message gives both in GB and how to change it.
    """
    budget = memory_budget()
    if n_bytes > budget:
        raise MemoryError(f"{what} would need about {n_bytes / 1e9:.3g} GB of memory, more than the budget "
                          f"of {budget / 1e9:.3g} GB (half the RAM; set {MEMORY_BUDGET_ENV} to change it)")


def broadcast_leading(named_shapes: dict[str, tuple[int, ...]]) -> tuple[int, ...]:
    """Broadcast the leading (batch) shapes of several arguments, naming them on failure.

    Parameters
    ----------
    named_shapes : dict of str to tuple of int
        Argument name -> its batch shape (its shape without trailing vector/matrix dimensions).

    Returns
    -------
    tuple of int
        The broadcast batch shape ``S``.

    Raises
    ------
    ValueError
        The shapes do not broadcast; the message lists every argument with its shape.
    """
    try:
        return np.broadcast_shapes(*named_shapes.values())
    except ValueError:
        desc = ", ".join(f"{k} {v}" for k, v in named_shapes.items())
        raise ValueError(
            f"the batch shapes of the arguments do not broadcast together: {desc} "
            "(batch shape = shape without the trailing vector/matrix dimensions)"
        ) from None


def row_exponents(*columns: np.ndarray) -> np.ndarray | None:
    """Per-row powers of two that bring each configuration's lengths to about 1, or None.

    ``columns`` are same-shape arrays of lengths (m), one per scalar length of a configuration
    (ranges, translation components). Returns ``e`` (int, that shape) with ``max |row| * 2**-e``
    in [0.5, 1) (``e = 0`` for an all-zero row), or None when every row's largest length lies
    within ``2**-60 .. 2**60``, where no intermediate of the kernels (at most a fourth power of a
    length) overflows or underflows and rescaling would not change the results.

    Parameters
    ----------
    *columns : numpy.ndarray, all of one shape
        Lengths, metres (ranges, translation components), one array per scalar length.

    Returns
    -------
    numpy.ndarray of int, shape of the columns, or None
        The exponents ``e``; None when no rescaling is needed (also for empty input).
    """
    big = np.abs(columns[0])
    for c in columns[1:]:
        big = np.maximum(big, np.abs(c))
    if big.size == 0:
        return None
    hi = big.max()
    lo = np.where(big > 0.0, big, hi).min()  # smallest non-zero row (all-zero rows need nothing)
    if 2.0 ** -_SAFE_EXPONENT <= lo and hi <= 2.0 ** _SAFE_EXPONENT or hi == 0.0:
        return None
    return np.frexp(big)[1]
