"""The two-view ambiguity locus: closed-form circle, exactly cropped to both apertures.

Two range measurements ``r1``, ``r2`` of one feature, with the relative pose ``p2 = R p1 + t``
known, put the feature (in sensor 1's frame) on the sphere ``|p1| = r1`` and on the plane
``2 u . p1 = C`` with ``u = R^T t`` and ``C = r2^2 - r1^2 - |t|^2`` (Norman & Mangelson, Sec. III).
Sphere and plane meet in a circle; the part of it inside both sensors' apertures is the
ambiguity locus. Its length is computed here exactly (see :mod:`sss_locus.geometry.arcs`).
"""

from __future__ import annotations

import functools

import numpy as np

from .validation import (as_float_array, as_positive_array, as_rotation_matrices, broadcast_leading,
                         check_aperture, check_max_abs, row_exponents)
from .locus_result import MAX_ARCS, LocusResult, LocusStatus
from .aperture import Aperture
from .fastpath import cross_rows, rotate_rows, transpose_into
from .arcs import crop_circle
from .halfspaces import as_half_spaces
from .tolerances import COINCIDENT_ORIGINS_RTOL, TANGENT_RTOL

_CHUNK = 4096


@functools.lru_cache(maxsize=64)
def _bounds(ap: Aperture) -> tuple[np.ndarray, np.ndarray, bool]:
    """An aperture's four bounds as ``a . p + s r >= 0`` (see :meth:`Aperture.halfspace_normals`).

    Returns the normals ``a`` as rows of a C-contiguous (4, 3) array (two elevation bounds, then
    two azimuth bounds), the elevation offsets ``s`` as a (2, 1) column, and whether the azimuth
    wedge is the union (not the intersection) of its half-planes. Cached: apertures are frozen.
    """
    el, az, union = ap.halfspace_normals()
    normals = np.ascontiguousarray(np.concatenate([el[:, :3], az], axis=0))
    normals.flags.writeable = False
    s_el = el[:, 3:].copy()
    s_el.flags.writeable = False
    return normals, s_el, union


def _apply_normals(normals: np.ndarray, vectors: np.ndarray, out: np.ndarray) -> None:
    """``out[:, j] = normals[j] . vectors`` for component-major ``vectors`` (m, 3, n).

    Written out elementwise on purpose: a BLAS matrix product rounds differently depending on
    the batch size and a row's position in it (FMA kernels for full blocks, other loops at the
    edges, a matrix-vector routine for a single row), which would make one configuration's
    result depend on its neighbours. Each sum is ``a_x v_x + a_y v_y + a_z v_z`` in that order,
    rounded the same way for every row; zero components are skipped, and a product
    ``v_c |a_c|`` is formed once and then added or subtracted (sign changes are exact), so the
    two azimuth bounds share their products.
    """
    products = {}

    def product(c, a_c):  # v_c |a_c|, formed once
        key = (c, abs(a_c))
        if key not in products:
            products[key] = vectors[:, c] if key[1] == 1.0 else vectors[:, c] * key[1]
        return products[key]

    for j, a in enumerate(normals):
        acc = out[:, j]
        terms = [(product(c, a[c]), a[c] < 0.0) for c in np.flatnonzero(a)]
        if not terms:
            acc[...] = 0.0
        elif len(terms) == 1:
            p0, neg0 = terms[0]
            if neg0:
                np.negative(p0, out=acc)
            else:
                np.copyto(acc, p0)
        else:  # -p0 + p1 == -(p0 - p1) and -p0 - p1 == -(p0 + p1) exactly
            (p0, neg0), (p1, neg1) = terms[:2]
            (np.add if neg0 == neg1 else np.subtract)(p0, p1, out=acc)
            if neg0:
                np.negative(acc, out=acc)
            for p, neg in terms[2:]:
                (np.subtract if neg else np.add)(acc, p, out=acc)


def _locus_chunk(R, t, r1, r2, ap1: Aperture, ap2: Aperture, out: dict, half=None) -> None:
    """Compute one chunk of rows into ``out`` (this chunk's slices of the result arrays).

    ``half`` is None or ``(normals (n, K, 3), offsets (n, K))``: extra half-spaces
    ``n . p1 <= d`` (validated by :func:`~sss_locus.geometry.halfspaces.as_half_spaces`, offsets
    at the chunk's scale), intersected with the apertures as conditions ``8 .. 8 + K - 1``.

    ``out["in_range"]`` is filled in already. Every length (``t``, ``r1``, ``r2``) may carry a
    per-row power-of-two scale: the chunk is homogeneous in them (angles, statuses and arcs do
    not change; lengths scale by the factor, ``C`` by its square).

    Vectors are handled component-major, shape (3, n) (row ``i`` is component ``i`` of every
    configuration), so each operation runs over contiguous rows instead of broadcasting over
    a short last axis; results are copied into the (n, 3) outputs at the end.
    """
    n = r1.shape[0]
    Rc = transpose_into(np.empty((9, n)), R.reshape(n, 9)).reshape(3, 3, n)  # Rc[i, j] = R[:, i, j]
    tc = transpose_into(np.empty((3, n)), t)
    u = Rc[0] * tc[0] + Rc[1] * tc[1] + Rc[2] * tc[2]  # R^T t: u_j = sum_i R_ij t_i
    tt = tc[0] * tc[0] + tc[1] * tc[1] + tc[2] * tc[2]
    C = r2 * r2 - r1 * r1 - tt
    unorm = np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
    b = np.sqrt(tt)
    coincident = b <= COINCIDENT_ORIGINS_RTOL * (r1 + r2)
    some_coincident = bool(coincident.any())
    safe = np.where(coincident, 1.0, unorm) if some_coincident else unorm
    normal = u / safe
    d = C / (2.0 * safe)
    if some_coincident:
        normal[:, coincident] = 0.0
        d[coincident] = 0.0
        b = np.where(coincident, 1.0, b)
    # radius^2 from the four-factor (Heron-type) form: accurate near tangency, unlike
    # r1^2 - d^2. The range difference is formed first (exact when r1 and r2 are within a factor
    # of 2), so a baseline b much shorter than the ranges keeps its digits: (b - r1) + r2 would
    # round b against r1. Swapping the views negates dr and swaps the last two factors, whose
    # product is formed first: the result is exactly symmetric.
    rsum, dr = r1 + r2, r1 - r2
    rho2 = (rsum - b) * (rsum + b) * ((b - dr) * (b + dr)) / (4.0 * b * b)
    rmin = np.minimum(r1, r2)
    tangent = ~coincident & (np.abs(rho2) <= TANGENT_RTOL * rmin * rmin)
    circle = ~coincident & ~tangent & (rho2 > 0.0)
    exists = circle | tangent
    radius = np.where(circle, np.sqrt(np.maximum(rho2, 0.0)), 0.0)
    center = normal * d

    # In-plane basis: e1 perpendicular to the normal and to the coordinate axis it is least
    # aligned with (well conditioned; first such axis on ties, as np.argmin), e2 = normal x e1.
    # The axis is a one-hot float vector, so axis x normal is np.cross's arithmetic exactly.
    mag = np.abs(normal)
    axis = np.empty((3, n))
    np.logical_and(mag[0] <= mag[1], mag[0] <= mag[2], out=axis[0], casting="unsafe")
    np.logical_and(axis[0] == 0.0, mag[1] <= mag[2], out=axis[1], casting="unsafe")
    np.subtract(1.0, axis[0] + axis[1], out=axis[2])
    e1 = cross_rows(axis, normal)
    e1_norm = np.sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2])
    zero = e1_norm == 0.0  # only where the normal is zero (coincident origins)
    if zero.any():
        e1_norm[zero] = 1.0
    e1 /= e1_norm
    if some_coincident:
        e1[:, coincident] = 0.0
    e2 = cross_rows(normal, e1)

    # Coefficients A, B, D (as coef[0], coef[1], coef[2], each (8, n): four bounds per sensor)
    # of the bounds on the circle. Sensor 1 sees the circle directly; sensor 2 through
    # p2 = R p1 + t. Each bound's normal a gives a . e1, a . e2 and a . c at once.
    normals1, s1, union1 = _bounds(ap1)
    normals2, s2, union2 = _bounds(ap2)
    K = 0 if half is None else half[1].shape[1]
    coef = np.empty((3, 8 + K, n))
    frame1 = np.stack([e1, e2, center])  # (3 vectors, 3 components, n)
    frame2 = rotate_rows(Rc, frame1)
    frame2[2] += tc
    _apply_normals(normals1, frame1, coef[:, :4])
    _apply_normals(normals2, frame2, coef[:, 4:8])
    for k in range(K):  # n . p1 <= d as (-n) . p1 + d >= 0: A, B from -n . e1, -n . e2
        hn = half[0][:, k, :]
        for j in range(3):
            coef[j, 8 + k] = -(hn[:, 0] * frame1[j, 0] + hn[:, 1] * frame1[j, 1] + hn[:, 2] * frame1[j, 2])
        coef[2, 8 + k] += half[1][:, k]
    coef[:2] *= radius  # A = rho a . e1, B = rho a . e2
    coef[2, 0:2] += s1 * r1  # elevation bounds: a . p + s r with |p| = r on the circle
    coef[2, 4:6] += s2 * r2
    if union1 or union2:  # a wedge wider than 180 deg is a union of its two half-planes
        groups = [
            ([0, 1, 4, 5] + list(range(8, 8 + K)), "all"),
            ([2, 3], "any" if union1 else "all"),
            ([6, 7], "any" if union2 else "all"),
        ]
    else:
        groups = [(list(range(8 + K)), "all")]
    start, end = out["arc_start"], out["arc_end"]
    angle, n_arcs, _, _ = crop_circle(coef[0], coef[1], coef[2], groups, MAX_ARCS + K, out=(start, end))

    in_range = out["in_range"]  # filled by the caller, from the unscaled ranges
    observable = exists & in_range
    measurable = circle & in_range
    length = out["length"]
    np.multiply(angle, radius, out=length)
    out["n_arcs"][...] = n_arcs
    if not measurable.all():
        length[~measurable] = 0.0
    if not observable.all():
        out["n_arcs"][~observable] = 0
        start[~observable] = np.nan
        end[~observable] = np.nan
    point = tangent & observable & (n_arcs > 0)
    if point.any():
        start[point, 0] = 0.0
        end[point, 0] = 0.0

    status = out["status"]
    status[...] = LocusStatus.CIRCLE
    status[tangent] = LocusStatus.TANGENT
    status[exists & ~in_range] = LocusStatus.OUT_OF_RANGE
    status[~exists] = LocusStatus.NO_INTERSECTION
    status[coincident] = LocusStatus.COINCIDENT_ORIGINS
    for name, value in (("u", u), ("center", center), ("normal", normal), ("basis1", e1), ("basis2", e2)):
        transpose_into(out[name], value)
    for name, value in (("C", C), ("radius", radius), ("exists", exists)):
        out[name][...] = value


_FIELDS = {  # result arrays: trailing shape and dtype
    "u": ((3,), np.float64), "C": ((), np.float64), "center": ((3,), np.float64),
    "normal": ((3,), np.float64), "basis1": ((3,), np.float64), "basis2": ((3,), np.float64),
    "radius": ((), np.float64), "exists": ((), np.bool_), "status": ((), np.int8),
    "in_range": ((), np.bool_), "length": ((), np.float64), "n_arcs": ((), np.int64),
    "arc_start": ((MAX_ARCS,), np.float64), "arc_end": ((MAX_ARCS,), np.float64),
}
_VECTORS = ("u", "center", "normal", "basis1", "basis2", "arc_start", "arc_end")


def two_view_locus(R, t, r1, r2, aperture1: Aperture, aperture2: Aperture, *,
                   outputs: str = "all", half_space_normals=None,
                   half_space_offsets=None) -> LocusResult:
    """Ambiguity locus of a feature seen by two sidescan sensors with known relative pose.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3), or scipy.spatial.transform.Rotation
        Rotation taking sensor-1 coordinates to sensor-2 coordinates: ``p2 = R p1 + t``.
    t : array_like, shape (..., 3)
        Translation (m) of the same transform: sensor 1's origin expressed in frame 2. Each
        component in [-1e150, 1e150].
    r1, r2 : array_like, shape (...)
        Measured ranges (m) to the feature from sensor 1 and sensor 2, in
        [``LENGTH_MIN``, ``LENGTH_MAX``] = [1e-150, 1e150] (so that ``C``, m^2, is representable;
        see :mod:`sss_locus.geometry.validation`).
    aperture1, aperture2 : Aperture
        Fields of view of the two sensors, each in its own frame.
    outputs : {"all", "lengths"}
        ``"lengths"`` leaves out the per-row vectors and arcs (``u``, ``center``, ``normal``,
        ``basis1``, ``basis2``, ``arc_start``, ``arc_end`` are ``None``): the same lengths,
        counts and statuses with 4x less result memory.
    half_space_normals : array_like, shape (..., K, 3), optional
        Normals ``n`` of ``K`` extra half-spaces ``n . p1 <= d`` in sensor 1's frame (any
        length, dimensionless): physical constraints such as the sea surface and the seafloor
        (:func:`~sss_locus.geometry.halfspaces.sea_surface_half_space`,
        :func:`~sss_locus.geometry.halfspaces.max_depth_half_space`). The locus is the part of
        the circle inside both apertures AND every half-space. Given together with
        ``half_space_offsets``; ``K = 0`` (or both ``None``, the default) means none, and gives
        the same result bit for bit. At most 32. Degenerate half-spaces (``n = 0``, a plane
        tangent to or missing the circle) are defined in :mod:`sss_locus.geometry.halfspaces`.
    half_space_offsets : array_like, shape (..., K), optional
        Offsets ``d`` (m times ``|n|``; metres for a unit normal), each in [-1e150, 1e150]. A
        trailing axis of 1 broadcasts over the ``K`` normals (and vice versa).

    The batch shapes of ``R``, ``t``, ``r1``, ``r2`` (and of the half-space arguments, without
    their trailing ``(K, 3)`` and ``(K,)``) broadcast together to ``S`` (which may
    be empty, e.g. ``(0,)`` or ``(2, 0)``). Numeric arguments must be real numbers: Python or
    NumPy ints and floats, or arrays of them.

    Returns
    -------
    LocusResult
        Circle geometry, status flags, locus length, arc count and arcs, batch shape ``S``.
        With ``K`` half-spaces the arc arrays are ``MAX_ARCS + K`` wide (each condition can
        start at most one arc).

    Raises
    ------
    TypeError
        (:class:`~sss_locus.geometry.validation.InputTypeError`, also a ``ValueError``) naming
        the argument: a numeric argument given as booleans, complex numbers, strings, dates,
        datetimes or timedeltas, ``None`` or an object array; an aperture that is not an
        :class:`Aperture`.
    ValueError
        Naming the argument: ``R`` is not a proper rotation (orthonormal with determinant +1, to
        1e-9), an input is NaN or infinite or has the wrong trailing shape, a range is not
        positive, a length is outside the range above, or the batch shapes do not broadcast;
        only one of ``half_space_normals`` and ``half_space_offsets`` is given, or they have
        the wrong trailing shapes or different ``K`` (see
        :func:`~sss_locus.geometry.halfspaces.as_half_spaces`).

    Notes
    -----
    Exact: each aperture bound is an affine half-space on the circle (the elevation bound is
    affine because ``|p1| = r1`` on the circle), giving closed-form boundary angles; the locus is
    the arrangement of these arcs. Nothing samples the circle. Degenerate cases are reported
    through :class:`LocusStatus`, never as NaN lengths. Scale-covariant and exact at every
    accepted magnitude: configurations far from 1 m are computed at a power-of-two scale.

    Examples
    --------
    >>> import numpy as np
    >>> from sss_locus import Aperture, two_view_locus
    >>> ap = Aperture(130.0, 0.27, 150.0)
    >>> res = two_view_locus(np.eye(3), [0.0, 0.0, -1.0], 50.0, 50.0, ap, ap)
    >>> float(res.radius) > 0
    True
    """
    check_aperture(aperture1, "aperture1", Aperture)
    check_aperture(aperture2, "aperture2", Aperture)
    if outputs not in ("all", "lengths"):
        raise ValueError(f"outputs must be 'all' or 'lengths'; got {outputs!r}")
    R = as_rotation_matrices(R, "R")
    t = as_float_array(t, "t", tail=(3,))
    check_max_abs(t, "t")
    r1 = as_positive_array(r1, "r1", bounded=True)
    r2 = as_positive_array(r2, "r2", bounded=True)
    if (half_space_normals is None) != (half_space_offsets is None):
        raise ValueError("half_space_normals and half_space_offsets must be given together "
                         f"(got only {'half_space_normals' if half_space_offsets is None else 'half_space_offsets'})")
    shapes = {"R": R.shape[:-2], "t": t.shape[:-1], "r1": r1.shape, "r2": r2.shape}
    K = 0
    if half_space_normals is not None:
        hn, hd = as_half_spaces(half_space_normals, half_space_offsets)
        K = max(hn.shape[-2], hd.shape[-1])
        shapes.update(half_space_normals=hn.shape[:-2], half_space_offsets=hd.shape[:-1])
    shape = broadcast_leading(shapes)
    n = int(np.prod(shape, dtype=np.int64))
    Rf = np.broadcast_to(R, shape + (3, 3)).reshape(n, 3, 3)
    tf = np.broadcast_to(t, shape + (3,)).reshape(n, 3)
    r1f = np.broadcast_to(r1, shape).reshape(n)
    r2f = np.broadcast_to(r2, shape).reshape(n)

    # Chunks of _CHUNK rows keep every temporary in cache; each chunk writes its rows of the
    # result arrays directly. Outputs left out go to one chunk-sized scratch area instead.
    fields = dict(_FIELDS)
    if K:
        fields.update(arc_start=((MAX_ARCS + K,), np.float64), arc_end=((MAX_ARCS + K,), np.float64))
    kept = fields if outputs == "all" else {k: f for k, f in fields.items() if k not in _VECTORS}
    results = {k: np.empty((n,) + tail, dtype=dtype) for k, (tail, dtype) in kept.items()}
    scratch = {k: np.empty((min(n, _CHUNK),) + fields[k][0]) for k in fields if k not in kept}
    np.logical_and(aperture1.range_ok(r1f), aperture2.range_ok(r2f), out=results["in_range"])
    # Lengths far from 1 m: each configuration is computed at a power-of-two scale (exact) where
    # no square or fourth power overflows or underflows, and its lengths are scaled back.
    e = row_exponents(r1f, r2f, tf[:, 0], tf[:, 1], tf[:, 2])
    ts, r1s, r2s = (tf, r1f, r2f) if e is None else (
        np.ldexp(tf, -e[:, None]), np.ldexp(r1f, -e), np.ldexp(r2f, -e))
    if K:
        hn = np.broadcast_to(hn, shape + (K, 3)).reshape(n, K, 3)
        hd = np.broadcast_to(hd, shape + (K,)).reshape(n, K)
        if e is not None:
            with np.errstate(over="ignore"):  # an infinite offset stays all or nothing
                hd = np.ldexp(hd, -e[:, None])
    for i in range(0, n, _CHUNK):
        rows = slice(i, min(i + _CHUNK, n))
        out = {k: v[rows] for k, v in results.items()}
        out.update({k: v[:rows.stop - i] for k, v in scratch.items()})
        _locus_chunk(Rf[rows], ts[rows], r1s[rows], r2s[rows], aperture1, aperture2, out,
                     (hn[rows], hd[rows]) if K else None)
    if e is not None:
        for k in ("u", "center"):
            if k in results:
                results[k] = np.ldexp(results[k], e[:, None])
        for k, power in (("radius", 1), ("length", 1), ("C", 2)):
            results[k] = np.ldexp(results[k], power * e)
    results.update(dict.fromkeys(scratch))
    fields = {k: None if v is None else v.reshape(shape + v.shape[1:]) for k, v in results.items()}
    return LocusResult(R=Rf.reshape(shape + (3, 3)), t=tf.reshape(shape + (3,)), **fields)
