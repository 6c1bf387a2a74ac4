"""Reconstruction of seafloor features from a noisy survey: flat-seafloor slant-range
correction against two views + a prior and N >= 3 views + least squares.

Per feature, the views that saw it (:func:`~sss_locus.experiments.reconstruction.terrain_survey.
observe_features`) are put in a random order (seeded; data association known), and the
estimates are computed from *estimated* poses and ranges (the noise chapter's model,
:func:`~sss_locus.experiments.passes.propagation.perturb`):

``flat``
    slant-range correction of every view on a flat seafloor at the transducer's measured
    altitude (:func:`~sss_locus.geometry.slant_range.flat_seafloor_points`; the altimeter is
    taken as exact, which favours the baseline), averaged over the feature's views (a mosaic
    that stacks every line);
``flat1``
    the same from the feature's first view alone;
``two``
    views 1 and 2: the point of their locus nearest the mean of their two flat-seafloor
    estimates (the stated prior), :func:`~sss_locus.geometry.slant_range.two_view_points`;
``n<N>``
    views 1..N (N >= 3), :func:`~sss_locus.geometry.multiview_points.multiview_points` with the
    flat estimate as prior, the cost limit the 99.9 % chi-square quantile with ``N - 3`` degrees
    of freedom (none for N = 3), and each view's aperture widened by ``margin_sigmas`` times
    the standard deviation of the feature's direction in that view (the largest attitude
    sigma and the position sigma over the range, in quadrature); with ``below_sensors`` (the
    default, an open choice) only points below the lowest sensor of the views are admitted,
    which rejects the mirror image of the feature above the (nearly coplanar) sensors; Range sigmas are effective: the range error plus the
    sensor-position error along the line of sight (attitude errors do not change a range);
``all``
    every view of the feature, as ``n<N>``.

Errors are those of the estimate against the true feature: 3-D, horizontal and vertical
(estimate minus truth, m). Estimators without an estimate for a feature (status other than
resolved or ambiguous; fewer views than N) have NaN errors in the table, and their status
tells why: the table is meant for statistics, its NaN are never silent.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import fields, replace

import numpy as np
import pandas as pd

from sss_locus.geometry import Aperture
from sss_locus.geometry.multiview_points import MultiViewStatus, multiview_points
from sss_locus.geometry.slant_range import flat_seafloor_points, two_view_points
from sss_locus.experiments.datamodel.noise_model import NoiseModel
from sss_locus.experiments.passes.propagation import noise_sigmas, perturb
from sss_locus.experiments.passes.pass_noise import PassNoise, view_errors
from sss_locus.experiments.passes.view_sets import Views

CHI2_LEVEL = 0.999
SOLVER_ROWS = 32_768
"""Most rows (features times N-view variants) :func:`reconstruct_many` gives one solver call: the
quick profile's cases (a few hundred rows each) share one call, the book profile's (8,000 rows
each) four at a time, larger cases go alone, so memory stays that of the largest case or this."""
STATUS_NAMES = {int(s): s.name.lower().replace("_", " ") for s in MultiViewStatus}


def _gather(a, order):
    return np.take_along_axis(a, order.reshape(order.shape + (1,) * (a.ndim - 2)), axis=1)


def _errors(est, truth, ok):
    d = np.where(ok[:, None], est - truth, np.nan)
    return dict(error_3d_m=np.linalg.norm(d, axis=1), error_h_m=np.hypot(d[:, 0], d[:, 1]),
                error_v_m=d[:, 2], error_x_m=d[:, 0], error_y_m=d[:, 1])


def _position_sigmas(sig, navigation, pass_noise, along_m):
    """Standard deviation of each horizontal coordinate of every view's sensor position (n, L)
    under the navigation model (per pass: offset, drift to the ping and jitter in quadrature)."""
    if navigation != "per_pass":
        return sig[..., 1]
    p = pass_noise
    return np.sqrt(p.pass_offset_sigma_m ** 2 + (p.drift_sigma_fraction * np.asarray(along_m, float)) ** 2
                   + p.ping_horizontal_sigma_m ** 2)


def _effective_sigmas(sig, horizontal, los):
    """Range sigma plus the sensor-position error along the line of sight ``los`` (n, L, 3)."""
    los = los / np.maximum(np.linalg.norm(los, axis=-1, keepdims=True), 1e-12)
    eff = np.sqrt(sig[..., 0] ** 2 + (horizontal * los[..., 0]) ** 2 + (horizontal * los[..., 1]) ** 2
                  + (sig[..., 3] * los[..., 2]) ** 2)
    return np.where(eff > 0, eff, 1e-6)


def reconstruct(views: Views, seen, sensor_height_m, noise: NoiseModel, aperture: Aperture, *,
                n_views=(3, 4, 6), seed: int = 0, margin_sigmas: float = 5.0,
                below_sensors: bool = True, navigation: str = "per_view", pass_noise: PassNoise | None = None,
                along_m=None, extra: Mapping | None = None) -> pd.DataFrame:
    """Every estimator on every feature (see the module docstring).

    Parameters
    ----------
    views : Views
        True poses, shapes (n, L, ...), and the true features.
    seen : array_like of bool, shape (n, L)
    sensor_height_m : array_like, shape (n, L)
        The transducer's height above the seafloor below it (altimeter), m.
    noise : NoiseModel
    aperture : Aperture
    n_views : sequence of int
        The N of the ``n<N>`` estimators, each >= 3.
    seed : int
        Seed of the view order and the noise draws.
    margin_sigmas : float
        Aperture widening in standard deviations of the feature's direction (default 5: up to
        nine views with two angles each are tested, and the estimate's own error adds to the
        direction error, so 3 would reject a few per cent of correct estimates).
    below_sensors : bool
        Admit only N-view points below the lowest (estimated) sensor of the feature's views
        (features lie on the seafloor under the survey; an open choice).
    navigation : {"per_view", "per_pass"}
        The navigation-error model (:mod:`~sss_locus.experiments.passes.pass_noise`): ``"per_view"``
        (the default, the earlier numbers) draws every view's errors independently;
        ``"per_pass"`` shares each pass's (column ``l`` of ``seen``) offset, drift and heading
        bias by every ping of the pass and needs ``pass_noise`` and ``along_m``.
    pass_noise : PassNoise
    along_m : array_like, shape (n, L)
        Distance travelled along each pass to the ping that sees the feature, m.
    extra : mapping of str to callable
        Further estimators: ``name -> fn(inputs) -> (point (n, 3), estimated (n,) bool)``, where
        ``inputs`` (a dict) holds the noisy survey in pass order: ``W`` (n, L, 3, 3),
        ``origin`` (n, L, 3), ``ranges`` (n, L), ``sigmas`` (n, L, 7) (per-view sigmas of
        :func:`~sss_locus.experiments.passes.propagation.noise_sigmas`), ``range_sigma_m`` (n, L) (effective,
        as the N-view estimator's), ``seen`` (n, L), ``flat`` (n, L, 3) (each view's
        flat-seafloor point), ``sensor_height_m``, ``along_m``, ``noise``, ``pass_noise``,
        ``navigation``, ``aperture``.

    Returns
    -------
    pandas.DataFrame
        One row per feature and estimator: ``feature``, ``estimator``, ``n_views`` (views used),
        ``n_seen``, ``status`` (``"estimated"``/``"resolved"``/...), ``estimated`` (bool),
        ``error_3d_m``, ``error_h_m``, ``error_v_m`` (signed, up), ``error_x_m``, ``error_y_m``,
        ``locus_length_m`` (``two`` only),
        ``predicted_3d_m`` (``sqrt(trace(covariance))``, N-view only).
    """
    return reconstruct_many([dict(views=views, seen=seen, sensor_height_m=sensor_height_m, noise=noise, seed=seed,
                                  below_sensors=below_sensors, navigation=navigation, pass_noise=pass_noise,
                                  along_m=along_m, extra=extra)], aperture, n_views=n_views,
                            margin_sigmas=margin_sigmas)[0]


def reconstruct_many(cases: Sequence[Mapping], aperture: Aperture, *, n_views=(3, 4, 6),
                     margin_sigmas: float = 5.0) -> list[pd.DataFrame]:
    """:func:`reconstruct` of each case (a mapping of its ``views``, ``seen``,
    ``sensor_height_m``, ``noise``, ``seed`` and ``below_sensors``, optionally ``navigation``,
    ``pass_noise``, ``along_m`` and ``extra``): the same tables, with one
    N-view solver call for consecutive cases with the same number of views, up to
    :data:`SOLVER_ROWS` rows (only their intermediate arrays are held at once). The solver's
    rows are independent, and its per-iteration overhead (its iterations run until the slowest
    row of the call stops) is paid once per call instead of once per case.

    Parameters
    ----------
    cases : sequence of Mapping
        The cases, each the keywords of :func:`reconstruct` (without ``aperture``, ``n_views``,
        ``margin_sigmas``).
    aperture : Aperture
        The sonar's beam aperture.
    n_views : sequence of int
        View counts of the N-view estimators (each >= 3).
    margin_sigmas : float
        Aperture margin of the N-view estimate, in noise sigmas.

    Returns
    -------
    list of pandas.DataFrame
        One table per case, in order (as :func:`reconstruct`); empty for no cases.

    Raises
    ------
    ValueError
        A view count below 3.
    """
    if any(int(k) < 3 for k in n_views):
        raise ValueError(f"n_views must be integers >= 3; got {list(n_views)}")
    tables: list[pd.DataFrame] = []
    run: list = []  # the (step, solver inputs) of consecutive cases solved together

    def solve() -> None:
        inputs = [x for _, x in run]
        res = multiview_points(aperture=aperture, **{key: np.concatenate([x[key] for x in inputs]) for key in inputs[0]})
        sizes = [len(x["mask"]) for x in inputs]
        for (step, _), end, size in zip(run, np.cumsum(sizes), sizes):
            try:
                step.send(replace(res, **{f.name: getattr(res, f.name)[end - size:end] for f in fields(res)}))
            except StopIteration as done:
                tables.append(done.value)
        run.clear()

    for case in cases:
        step = _estimates(aperture=aperture, n_views=n_views, margin_sigmas=margin_sigmas, **case)
        x = next(step)
        if run and (x["mask"].shape[1] != run[0][1]["mask"].shape[1]
                    or sum(len(y["mask"]) for _, y in run) + len(x["mask"]) > SOLVER_ROWS):
            solve()
        run.append((step, x))
    if run:
        solve()
    return tables


def _estimates(views: Views, seen, sensor_height_m, noise: NoiseModel, aperture: Aperture, *, n_views, seed: int,
               margin_sigmas: float, below_sensors: bool, navigation: str = "per_view",
               pass_noise: PassNoise | None = None, along_m=None, extra: Mapping | None = None):
    """:func:`reconstruct` of one case, in two steps: yields the N-view solver's inputs, is sent
    its result for them, and returns the table."""
    seen = np.asarray(seen, bool)
    n, L = seen.shape
    from scipy.stats import chi2

    rng = np.random.default_rng(seed)
    order = np.argsort(np.where(seen, rng.random((n, L)), 2.0), axis=1, kind="stable")
    n_seen = seen.sum(axis=1)
    sig = noise_sigmas(views, noise)
    errors = view_errors(sig, rng.standard_normal((n, L, 7)), model=navigation, pass_noise=pass_noise,
                         along_m=along_m, rng=rng)
    W_pass, o_pass, r_pass = perturb(views, np.ones_like(sig), errors)
    H_pass = np.asarray(sensor_height_m, float)
    flat_pass = flat_seafloor_points(W_pass, o_pass, r_pass, np.maximum(H_pass, 0.0))["point"]
    sig_pass = _effective_sigmas(sig, _position_sigmas(sig, navigation, pass_noise, along_m), flat_pass - o_pass)
    W_hat, o_hat, r_hat, flat, sig_eff = (_gather(a, order) for a in (W_pass, o_pass, r_pass, flat_pass, sig_pass))
    mask = _gather(seen, order)
    f = views.feature
    rows = []  # the columns of each estimator's rows, made into one table at the end

    def add(name, est, ok, status, used, **extra):
        rows.append(dict(feature=np.arange(n), estimator=np.full(n, name), n_views=used, n_seen=n_seen,
                         status=status, estimated=ok, **_errors(est, f, ok), **extra))

    any_seen = n_seen >= 1
    mean_flat = np.einsum("nki,nk->ni", flat, mask) / np.maximum(n_seen, 1)[:, None]
    add("flat", mean_flat, any_seen, np.where(any_seen, "estimated", "unseen"), n_seen)
    add("flat1", flat[:, 0], any_seen, np.where(any_seen, "estimated", "unseen"), np.minimum(n_seen, 1))

    # two views and the prior: the locus point nearest the mean of their flat estimates
    has2 = n_seen >= 2
    b = min(1, L - 1)  # the second view's slot; with one view slot no feature has two (all "too few views")
    r1, r2 = np.where(has2, r_hat[:, 0], 1.0), np.where(has2, r_hat[:, b], 1.0)
    _, near, two = two_view_points(W_hat[:, 0], o_hat[:, 0], W_hat[:, b], o_hat[:, b], r1, r2,
                                   0.5 * (flat[:, 0] + flat[:, b]), aperture, aperture)
    names = np.array(["locus", "circle", "sphere"])
    add("two", two, has2, np.where(has2, names[near["status"]], "too few views"), np.minimum(n_seen, 2),
        locus_length_m=np.where(has2, near["length_m"], np.nan))

    # angular error of the feature's direction in a view: attitude, and position across the ray
    heading = (np.hypot(pass_noise.pass_heading_bias_sigma_deg, pass_noise.ping_heading_sigma_deg)
               if navigation == "per_pass" else noise.heading_sigma_deg)
    att = max(noise.roll_sigma_deg, noise.pitch_sigma_deg, heading)
    horizontal = _gather(_position_sigmas(sig, navigation, pass_noise, along_m), order)
    pos = np.degrees(np.hypot(horizontal, noise.vertical_sigma_m) / np.maximum(r_hat, 1e-9))
    margin = margin_sigmas * np.hypot(att, pos)
    # every N-view variant in one batch (one solver call: its per-iteration overhead is shared)
    ks = [*sorted({int(x) for x in n_views}), None]
    uses = []
    for k in ks:
        use = mask & (np.arange(L)[None, :] < (k if k is not None else L))
        uses.append(use & (n_seen >= k)[:, None] if k is not None else use)
    use = np.concatenate(uses)
    tile = lambda a: np.concatenate([a] * len(ks))  # noqa: E731
    used = use.sum(axis=1)
    limit = np.where(used > 3, chi2.ppf(CHI2_LEVEL, np.maximum(used - 3, 1)), np.inf)
    o_all = tile(o_hat)
    res = yield dict(W=tile(W_hat), origin=o_all, ranges=np.where(use, tile(r_hat), 1.0), sigmas=tile(sig_eff),
                     mask=use, prior=tile(mean_flat), cost_limit=limit, aperture_margin_deg=tile(margin),
                     ceiling_m=np.min(np.where(use, o_all[..., 2], np.inf), axis=1) if below_sensors
                     else np.full(len(use), np.inf))
    inputs = dict(W=W_pass, origin=o_pass, ranges=r_pass, sigmas=sig, range_sigma_m=sig_pass, seen=seen,
                  flat=flat_pass, sensor_height_m=H_pass, along_m=along_m, noise=noise, pass_noise=pass_noise,
                  navigation=navigation, aperture=aperture)
    for name, fn in (extra or {}).items():
        point, ok = fn(inputs)
        ok = np.asarray(ok, bool) & (n_seen >= 1)
        add(name, np.asarray(point, float), ok, np.where(ok, "estimated", "not estimated"), n_seen)
    names = np.array([STATUS_NAMES[int(s)] for s in range(len(STATUS_NAMES))])
    tr = np.trace(np.where(res.estimated[:, None, None], res.covariance, 0.0), axis1=1, axis2=2)
    pred = np.sqrt(np.where(res.estimated, tr, np.nan))
    for i, k in enumerate(ks):
        part = slice(i * n, (i + 1) * n)
        add("all" if k is None else f"n{k}", res.point[part], res.estimated[part], names[res.status[part]],
            used[part], predicted_3d_m=pred[part])
    # a column an estimator lacks is NaN in its rows (as pandas.concat of one table per estimator)
    columns = list(dict.fromkeys(k for r in rows for k in r))
    return pd.DataFrame({c: np.concatenate([np.broadcast_to(r.get(c, np.nan), (n,)) for r in rows])
                         for c in columns})


def summarise(table: pd.DataFrame, by=("estimator",)) -> pd.DataFrame:
    """Median and 90th percentile of the 3-D, horizontal and |vertical| errors over estimated
    features, and the share estimated / resolved / ambiguous, per group.

    Parameters
    ----------
    table : pandas.DataFrame
        Per-feature rows of :func:`reconstruct` (errors in m).
    by : sequence of str
        Grouping columns.

    Returns
    -------
    pandas.DataFrame
        One row per group: ``n``, shares ``estimated``, ``resolved``, ``ambiguous``,
        ``n_views_median``, error medians and 90th percentile (m), ``locus_length_median_m``
        (NaN where no feature was estimated).
    """
    t = table.assign(abs_error_v_m=table.error_v_m.abs(),
                     resolved=table.status.isin(["resolved", "estimated", "locus"]),
                     ambiguous=table.status == "ambiguous")
    g = t.groupby(list(by), sort=False)
    out = g.agg(n=("feature", "size"), estimated=("estimated", "mean"), resolved=("resolved", "mean"),
                ambiguous=("ambiguous", "mean"), n_views_median=("n_views", "median"),
                error_3d_median_m=("error_3d_m", "median"), error_h_median_m=("error_h_m", "median"),
                error_v_median_m=("abs_error_v_m", "median"),
                error_3d_q90_m=("error_3d_m", lambda x: x.quantile(0.9)),
                locus_length_median_m=("locus_length_m", "median"))
    return out.reset_index()
