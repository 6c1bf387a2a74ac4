"""Benchmark: the joint adjustment at survey scale, scipy least_squares (the project's solver)
side by side with GTSAM on the same problem.

Workload (generated here, vectorised; not the chapter's simulator): a square area of side
``34 * n_passes`` m (3.4 km for 100 passes) with ``n_features`` features on a seafloor of 4 m
relief, 80 % of the passes north/south main lines and 20 % east/west cross lines, a sensor 25 m
above the mean seafloor seeing 8-110 m across track on both sides: about 6 sightings a feature
(300,000 for 100 passes and 50,000 features). Every pass has a navigation error: offset (2 m per
axis), heading bias (1 deg, turning the sonar only) and drift (2e-3 m/m); per-ping jitter 5 cm
and 0.05 deg; ranges 5 cm. Start: the flat-seafloor mosaic. Unknowns: every feature's position
and every pass's five corrections.

Measured, each in a fresh process on one thread (``OMP_NUM_THREADS=1`` etc.), after the problem
is built:

* ``scipy``: :func:`sss_locus.experiments.adjustment.adjust` (Gauss-Newton stage, then
  ``soft_l1``), without and then with the covariances (Schur complement);
* ``scipy-linear``: the same, quadratic loss only (what GTSAM is given);
* ``gtsam``: GTSAM 4.3 Levenberg-Marquardt on the same residuals as Python ``CustomFactor``s
  (range and beam-plane angle of a sighting, 2 x 3 and 2 x 5 Jacobians), a Gaussian prior on
  each pass's correction; ``pip install gtsam`` into ``--gtsam-path`` (not in the project's lock).

Wall time (``time.perf_counter``) and the peak resident memory of the process (``ru_maxrss``,
including the problem's own arrays). The map-shape and horizontal errors of each answer are
printed to show the solvers reach the same optimum.

With ``--robustness`` it measures instead the robust loss against wrong matches (0, 2, 5 and 10 %
of the sightings attributed to a random other feature): the map-shape errors with the robust and
the quadratic loss and of the mosaic, and the shares of wrong and right sightings down-weighted.

Usage::

    python benchmarks/bench_adjustment.py [--passes 100] [--features 50000] [--solvers scipy,scipy-linear,gtsam]
        [--gtsam-path DIR] [--seed 0] [--robustness]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"  # single thread; must happen before numpy is imported

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sss_locus.experiments.adjustment import NavigationPriors, Sightings, adjust, map_errors  # noqa: E402
from sss_locus.geometry.beam_plane import beam_plane_sigma_rad  # noqa: E402

RANGE_SIGMA, JITTER_M, JITTER_DEG = 0.05, 0.05, 0.05
OFFSET_SIGMA, HEADING_SIGMA_DEG, DRIFT_SIGMA = 2.0, 1.0, 2e-3


def seafloor(x, y):
    return -30.0 + 4.0 * np.sin(x / 37.0) * np.cos(y / 23.0)


def rotz(a):
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(np.shape(a) + (3, 3))
    R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1], R[..., 2, 2] = c, -s, s, c, 1.0
    return R


def survey(n_passes: int, n_features: int, seed: int, wrong_share: float = 0.0):
    """The sightings, priors, mosaic start, truth and true corrections (module docstring); with
    ``wrong_share``, that share of the sightings attributed to another feature (a wrong match),
    flagged in ``survey.wrong`` (set as a function attribute, for :func:`run_robustness`)."""
    rng = np.random.default_rng(seed)
    area = 34.0 * n_passes
    n_cross = max(1, n_passes // 5)
    n_main = n_passes - n_cross
    xy = rng.uniform(-area / 2, area / 2, (n_features, 2))
    truth = np.column_stack([xy, seafloor(xy[:, 0], xy[:, 1])])
    heading = np.concatenate([np.where(np.arange(n_main) % 2 == 0, np.pi / 2, -np.pi / 2),
                              np.where(np.arange(n_cross) % 2 == 0, 0.0, np.pi)])
    centre = np.concatenate([np.column_stack([np.linspace(-area / 2, area / 2, n_main), np.zeros(n_main)]),
                             np.column_stack([np.zeros(n_cross), np.linspace(-area / 2, area / 2, n_cross)])])
    e = np.column_stack([np.cos(heading), np.sin(heading)])
    nrm = np.column_stack([-np.sin(heading), np.cos(heading)])
    f_list, p_list = [], []
    for j in range(n_passes):
        across = (xy - centre[j]) @ nrm[j]
        seen = np.flatnonzero((np.abs(across) >= 8.0) & (np.abs(across) <= 110.0))
        f_list.append(seen)
        p_list.append(np.full(seen.size, j))
    f, p = np.concatenate(f_list), np.concatenate(p_list)
    m = f.size
    rel = xy[f] - centre[p]
    across, along = np.einsum("mi,mi->m", rel, nrm[p]), np.einsum("mi,mi->m", rel, e[p])
    side = np.sign(across)
    half = np.radians(0.5) / 2
    phi = rng.uniform(-half, half, m)
    sensor_z = -5.0
    s = along.copy()
    for _ in range(3):
        o = np.column_stack([centre[p] + s[:, None] * e[p], np.full(m, sensor_z)])
        s = along - np.linalg.norm(truth[f] - o, axis=1) * np.sin(phi)
    o_true = np.column_stack([centre[p] + s[:, None] * e[p], np.full(m, sensor_z)])
    tilt = np.radians(25.0)
    e3 = np.column_stack([e[p], np.zeros(m)])
    n3 = np.column_stack([nrm[p], np.zeros(m)])
    x_ax = np.cos(tilt) * side[:, None] * n3 - np.sin(tilt) * np.array([0, 0, 1.0])
    W_true = np.stack([x_ax, np.cross(e3, x_ax), e3], axis=-1)
    offsets = rng.normal(0, OFFSET_SIGMA, (n_passes, 2))
    hbias = rng.normal(0, np.radians(HEADING_SIGMA_DEG), n_passes)
    drift = rng.normal(0, DRIFT_SIGMA, (n_passes, 2))
    o_nav = o_true.copy()
    o_nav[:, :2] -= offsets[p] + s[:, None] * drift[p]
    o_nav += rng.normal(0, JITTER_M, (m, 3)) * np.array([1, 1, 0.5])
    W_nav = rotz(rng.normal(0, np.radians(JITTER_DEG), m)) @ rotz(-hbias[p]) @ W_true
    ranges = np.linalg.norm(truth[f] - o_true, axis=1) + rng.normal(0, RANGE_SIGMA, m)
    survey.wrong = np.zeros(m, bool)
    if wrong_share > 0:
        k = rng.choice(m, int(round(wrong_share * m)), replace=False)
        f = f.copy()
        f[k] = (f[k] + rng.integers(1, n_features, k.size)) % n_features
        survey.wrong[k] = True
    altimeter = o_true[:, 2] - seafloor(o_true[:, 0], o_true[:, 1])
    # the flat mosaic: slant-range corrected across the navigated track, averaged per feature
    fwd = W_nav[:, :2, 2] / np.linalg.norm(W_nav[:, :2, 2], axis=1, keepdims=True)
    g = np.sqrt(np.maximum(ranges ** 2 - altimeter ** 2, 0.0))
    pts = np.column_stack([o_nav[:, :2] + (side * g)[:, None] * np.column_stack([-fwd[:, 1], fwd[:, 0]]),
                           o_nav[:, 2] - altimeter])
    cnt = np.maximum(np.bincount(f, minlength=n_features), 1)
    mosaic = np.stack([np.bincount(f, pts[:, a], minlength=n_features) for a in range(3)], -1) / cnt[:, None]
    sig_phi = float(beam_plane_sigma_rad(0.5, JITTER_DEG, 0.0, 20.0))
    sightings = Sightings(feature=f, pass_index=p, origin_m=o_nav, W=W_nav, range_m=ranges,
                          range_sigma_m=np.full(m, np.hypot(RANGE_SIGMA, JITTER_M)),
                          beam_plane_sigma_rad=np.full(m, sig_phi), along_track_m=s)
    priors = NavigationPriors(offset_sigma_m=OFFSET_SIGMA, heading_sigma_deg=HEADING_SIGMA_DEG, drift_sigma=DRIFT_SIGMA,
                              reference_m=centre)
    true_corr = np.column_stack([offsets, hbias, drift])
    return sightings, priors, mosaic, truth, true_corr


def summary(point, adjusted, truth, mosaic) -> dict:
    j, mo = map_errors(point, truth, adjusted), map_errors(mosaic, truth, adjusted)
    med = lambda d, k: float(np.median(np.abs(d[k][adjusted])))  # noqa: E731
    return dict(adjusted=int(adjusted.sum()), shape_m=med(j, "shape_m"), horizontal_m=med(j, "horizontal_m"),
                vertical_m=med(j, "vertical_m"), mosaic_shape_m=med(mo, "shape_m"),
                mosaic_horizontal_m=med(mo, "horizontal_m"), mosaic_vertical_m=med(mo, "vertical_m"))


def run_scipy(args, loss: str) -> dict:
    sightings, priors, mosaic, truth, _ = survey(args.passes, args.features, args.seed)
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t, cpu = time.perf_counter(), time.process_time()
    res = adjust(sightings, priors, mosaic, loss=loss, covariance=False)
    solve, cpu = time.perf_counter() - t, time.process_time() - cpu
    t = time.perf_counter()
    adjust(sightings, priors, mosaic, loss=loss, covariance=True)
    with_cov = time.perf_counter() - t
    return dict(solver=f"scipy ({loss})", sightings=sightings.n, seconds=solve, cpu_seconds=cpu, seconds_with_covariance=with_cov,
                evaluations=res.n_evaluations, success=res.success, rss_before_mb=rss0 / 1024,
                peak_rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                **summary(res.point_m, res.adjusted, truth, mosaic))


def run_gtsam(args, lm: bool = False) -> dict:
    import gtsam

    sightings, priors, mosaic, truth, _ = survey(args.passes, args.features, args.seed)
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t0 = time.perf_counter()
    P = priors.n_passes
    pairs = np.unique(sightings.feature * P + sightings.pass_index)
    adjusted = np.bincount(pairs // P, minlength=len(mosaic)) >= 2
    F = lambda i: int(i)  # noqa: E731 (feature keys 0..N-1)
    C = lambda j: int(10_000_000 + j)  # noqa: E731 (pass keys)
    graph = gtsam.NonlinearFactorGraph()
    values = gtsam.Values()
    for i in np.flatnonzero(adjusted):
        values.insert(F(i), gtsam.Point3(*mosaic[i]))
    sig = priors.sigmas()
    for j in range(P):
        values.insert(C(j), np.zeros(5))
        graph.add(gtsam.PriorFactorVector(C(j), np.zeros(5), gtsam.noiseModel.Diagonal.Sigmas(sig[j])))
    use = np.flatnonzero(adjusted[sightings.feature])
    s = sightings
    noise = [gtsam.noiseModel.Diagonal.Sigmas(np.array([a, b])) for a, b in
             zip(s.range_sigma_m[use], s.beam_plane_sigma_rad[use])]

    def factor(o, W, rho, along):
        u = W[:, 2].copy()

        def error(this, v, H):
            fp = v.atPoint3(this.keys()[0])
            c = v.atVector(this.keys()[1])
            ch, sh = np.cos(c[2]), np.sin(c[2])
            ot = o + np.array([c[0] + along * c[3], c[1] + along * c[4], 0.0])
            ut = np.array([ch * u[0] - sh * u[1], sh * u[0] + ch * u[1], u[2]])
            d = fp - ot
            r = np.sqrt(d @ d)
            dh = d / r
            sp = ut @ dh
            cp = np.sqrt(max(1.0 - sp * sp, 1e-24))
            g = (ut - sp * dh) / (r * cp)
            if H is not None:
                du = np.array([-ut[1], ut[0], 0.0])
                Hf = np.vstack([dh, g])
                Hc = np.zeros((2, 5))
                Hc[:, 0:2] = -Hf[:, :2]
                Hc[1, 2] = du @ dh / cp
                Hc[:, 3:5] = -along * Hf[:, :2]
                H[0] = Hf
                H[1] = Hc
            return np.array([r - rho, np.arcsin(sp)])

        return error

    for k, i in enumerate(use):
        graph.add(gtsam.CustomFactor(noise[k], [F(s.feature[i]), C(s.pass_index[i])],
                                     factor(s.origin_m[i], s.W[i], s.range_m[i], s.along_track_m[i])))
    build = time.perf_counter() - t0
    t, cpu = time.perf_counter(), time.process_time()
    if lm:  # GTSAM's own Levenberg-Marquardt
        params = gtsam.LevenbergMarquardtParams()
        params.setRelativeErrorTol(1e-10)
        params.setAbsoluteErrorTol(1e-10)
        params.setMaxIterations(50)
        opt = gtsam.LevenbergMarquardtOptimizer(graph, values, params)
        result, iterations = opt.optimize(), int(opt.iterations())
    else:  # Gauss-Newton: GTSAM's linearisation and sparse elimination, called step by step
        result, error, iterations = values, graph.error(values), 0
        while iterations < 50:
            delta = graph.linearize(result).optimize()
            result, iterations = result.retract(delta), iterations + 1
            new = graph.error(result)
            if error - new <= 1e-10 * error:
                break
            error = new
    solve, cpu = time.perf_counter() - t, time.process_time() - cpu
    point = mosaic.copy()
    for i in np.flatnonzero(adjusted):
        point[i] = result.atPoint3(F(i))
    return dict(solver=f"gtsam ({'LM' if lm else 'Gauss-Newton'}, CustomFactor)", sightings=int(use.size),
                seconds=solve, cpu_seconds=cpu, build_seconds=build, iterations=iterations, rss_before_mb=rss0 / 1024,
                peak_rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                **summary(point, adjusted, truth, mosaic))


def run_robustness(args) -> list[dict]:
    """Wrong matches injected (0, 2, 5, 10 % of the sightings): the map-shape error of the joint
    estimate with the robust and the quadratic loss against the mosaic's, and the share of the
    wrong and of the right sightings the robust loss down-weights."""
    rows = []
    for share in (0.0, 0.02, 0.05, 0.10):
        sightings, priors, mosaic, truth, _ = survey(args.passes, args.features, args.seed, share)
        wrong = survey.wrong
        robust = adjust(sightings, priors, mosaic, loss="soft_l1", covariance=False)
        plain = adjust(sightings, priors, mosaic, loss="linear", covariance=False)
        ok = robust.adjusted & plain.adjusted
        used = np.isfinite(robust.weight)
        rows.append(dict(wrong_share=share, features=int(ok.sum()),
                         shape_robust_m=summary(robust.point_m, ok, truth, mosaic)["shape_m"],
                         shape_linear_m=summary(plain.point_m, ok, truth, mosaic)["shape_m"],
                         shape_mosaic_m=summary(robust.point_m, ok, truth, mosaic)["mosaic_shape_m"],
                         wrong_downweighted=float(robust.downweighted[wrong & used].mean()) if (wrong & used).any() else None,
                         right_downweighted=float(robust.downweighted[~wrong & used].mean())))
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--passes", type=int, default=100)
    ap.add_argument("--features", type=int, default=50_000)
    ap.add_argument("--solvers", default="scipy,scipy-linear,gtsam")
    ap.add_argument("--gtsam-path", default="")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--robustness", action="store_true", help="wrong matches injected, instead of the timing")
    ap.add_argument("--one", default="", help=argparse.SUPPRESS)  # run one solver in this process
    args = ap.parse_args()
    if args.one:
        out = run_gtsam(args, lm=args.one == "gtsam-lm") if args.one.startswith("gtsam") else run_scipy(args, "linear" if args.one == "scipy-linear" else "soft_l1")
        print(json.dumps(out))
        return
    print(f"command: {' '.join([Path(sys.argv[0]).name] + sys.argv[1:])}; load average {os.getloadavg()}")
    if args.robustness:
        for row in run_robustness(args):
            print(json.dumps(row))
        return
    for name in args.solvers.split(","):
        env = dict(os.environ)
        if name.startswith("gtsam") and args.gtsam_path:
            env["PYTHONPATH"] = args.gtsam_path + os.pathsep + env.get("PYTHONPATH", "")
        cmd = [sys.executable, __file__, "--one", name, "--passes", str(args.passes), "--features", str(args.features),
               "--seed", str(args.seed)]
        run = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if run.returncode:
            print(f"{name}: failed: {run.stderr.strip().splitlines()[-1] if run.stderr.strip() else run.returncode}")
            continue
        print(json.dumps(json.loads(run.stdout.strip().splitlines()[-1])))
    print(f"load average at the end {os.getloadavg()}")


if __name__ == "__main__":
    main()
