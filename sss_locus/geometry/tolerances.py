"""Every tolerance the exact kernels use to classify degenerate geometry, in one place.

Each is relative (dimensionless) and named for the test it decides, so a reader never meets one
name with two meanings. All kernels stay exact away from these thresholds; the thresholds only
decide which :class:`~sss_locus.geometry.locus.LocusStatus` or
:class:`~sss_locus.geometry.three_view_points.ThreeViewStatus` a borderline configuration gets.
"""

COINCIDENT_ORIGINS_RTOL = 1e-12
"""Two sensor origins closer than ``COINCIDENT_ORIGINS_RTOL * (r1 + r2)`` coincide (two-view
locus and three-view points alike): no plane, status ``COINCIDENT_ORIGINS``."""

TANGENT_RTOL = 1e-13
"""Two-view: a circle with ``|radius**2| <= TANGENT_RTOL * min(r1, r2)**2`` (radius below about
3.2e-7 of the shorter range) is a tangent point; a negative ``radius**2`` beyond that means the
spheres do not meet. The test is symmetric in the two views."""

PARALLEL_PLANES_SIN_TOL = 1e-10
"""Three-view: the two radical planes whose normals make an angle with
``|sin| <= PARALLEL_PLANES_SIN_TOL`` are parallel (no line)."""

COINCIDENT_PLANES_RTOL = 1e-9
"""Three-view: parallel planes whose offsets from sensor 1 differ by at most
``COINCIDENT_PLANES_RTOL * r1`` coincide (a whole circle of candidates)."""

LINE_TANGENT_RTOL = 1e-13
"""Three-view: a line with ``|r1**2 - |p0|**2| <= LINE_TANGENT_RTOL * r1**2`` (half-chord below
about 3.2e-7 r1) touches sphere 1 in one point."""

RANGE_JACOBIAN_RANK_RTOL = 1e-10
"""N views (:mod:`sss_locus.geometry.multiview`): ``J^T J`` of the range residuals whose
smallest eigenvalue is at most ``RANGE_JACOBIAN_RANK_RTOL`` times its largest is singular (the
feature is not determined: collinear sensor origins, fewer than three views); status
``DEGENERATE``. Also the floor of the Marquardt damping's diagonal, relative to its trace."""
