"""Benchmark: exact two-view locus vs. a naive 0.1-degree sampling baseline.

Prints a Markdown table (for the README) for the EdgeTech 2205 aperture (Table I: 130 deg
azimuth, 0.27 deg elevation, 150 m) on both sensors, on random feature-seeded configurations
(a feature drawn inside aperture 1, a random orientation and a point inside aperture 2 for
sensor 2; see tests/reference_locus.py), so every locus is non-empty.

* exact kernel (``sss_locus.two_view_locus``), single thread, for batches of 1e4, 1e5 and
  ``--n`` configurations; the largest batch is streamed in chunks of 1e5 and the process's
  peak resident memory is reported after each row, to show it stays bounded;
* naive baseline: sample each circle every 0.1 deg (3,600 points), test each point with
  ``atan2`` / ``arcsin`` in both sensor frames, length = radius x 0.1 deg x (points inside);
* the speed ratio and the baseline's median and 95th-percentile relative length error against
  the exact kernel.

Timing excludes generating the configurations. This is a benchmark, not a test: nothing is
asserted.

Usage::

    python benchmarks/bench_locus.py [--n 1000000] [--seed 0] [--quick]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"  # single thread; must happen before numpy is imported

import argparse  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import shlex  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "tests"))

from reference_locus import EDGETECH, feature_seeded_configs  # noqa: E402
from sss_locus import Aperture, two_view_locus  # noqa: E402

CHUNK = 100_000
BASELINE_STEP_DEG = 0.1
BASELINE_BLOCK = 64  # configurations per vectorised baseline block (64 x 3600 points)


def peak_rss_mib() -> float:
    """Peak resident set size of this process so far (MiB; ru_maxrss is KiB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


class Clock:
    """Wall-clock and process CPU time of a block (CPU time is robust on a shared machine)."""

    def __enter__(self):
        self.wall0, self.cpu0 = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.wall = time.perf_counter() - self.wall0
        self.cpu = time.process_time() - self.cpu0


def time_kernel(cfg, ap, repeats: int) -> tuple[float, float]:
    """Best (wall, cpu) seconds of ``repeats`` kernel calls on one batch."""
    best = (np.inf, np.inf)
    for _ in range(repeats):
        with Clock() as c:
            two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], ap, ap)
        best = min(best, (c.wall, c.cpu), key=lambda wc: wc[1])
    return best


def time_kernel_streamed(rng, n: int, ap) -> tuple[float, float]:
    """(wall, cpu) seconds of the kernel over ``n`` configurations generated per chunk."""
    wall = cpu = 0.0
    done = 0
    while done < n:
        m = min(CHUNK, n - done)
        cfg = feature_seeded_configs(rng, m, EDGETECH, EDGETECH)
        with Clock() as c:
            res = two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], ap, ap)
        wall, cpu = wall + c.wall, cpu + c.cpu
        del res, cfg
        done += m
    return wall, cpu


def _inside(x, y, z, half_az, half_el):
    r = np.sqrt(x * x + y * y + z * z)
    return (np.abs(np.arctan2(y, x)) <= half_az) & (np.abs(np.arcsin(np.clip(z / r, -1, 1))) <= half_el)


def naive_baseline(R, t, r1, r2, ap) -> np.ndarray:
    """Locus length by sampling each circle every 0.1 deg (the approach of public code)."""
    half_az, half_el = np.deg2rad(ap.azimuth_deg) / 2, np.deg2rad(ap.elevation_deg) / 2
    step = np.deg2rad(BASELINE_STEP_DEG)
    alpha = np.arange(int(round(360.0 / BASELINE_STEP_DEG))) * step
    ca, sa = np.cos(alpha), np.sin(alpha)
    out = np.zeros(len(r1))
    for lo in range(0, len(r1), BASELINE_BLOCK):
        sl = slice(lo, lo + BASELINE_BLOCK)
        Rb, tb, a1, a2 = R[sl], t[sl], r1[sl], r2[sl]
        s = -np.einsum("nji,nj->ni", Rb, tb)  # sensor 2's origin in frame 1
        d = np.linalg.norm(s, axis=1)
        n = s / d[:, None]
        a = (a1 * a1 - a2 * a2 + d * d) / (2 * d)
        rho = np.sqrt(np.maximum(a1 * a1 - a * a, 0.0))
        helper = np.eye(3)[np.argmin(np.abs(n), axis=1)]
        e1 = np.cross(n, helper)
        e1 /= np.linalg.norm(e1, axis=1)[:, None]
        e2 = np.cross(n, e1)
        p1 = (a[:, None] * n)[:, None, :] + rho[:, None, None] * (
            ca[None, :, None] * e1[:, None, :] + sa[None, :, None] * e2[:, None, :]
        )
        p2 = np.einsum("nij,nkj->nki", Rb, p1) + tb[:, None, :]
        ok = _inside(p1[..., 0], p1[..., 1], p1[..., 2], half_az, half_el)
        ok &= _inside(p2[..., 0], p2[..., 1], p2[..., 2], half_az, half_el)
        out[sl] = rho * step * ok.sum(axis=1)
    return out


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="largest (streamed) batch")
    parser.add_argument("--baseline-n", type=int, default=2000, help="configurations for the baseline")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--quick", action="store_true", help="n = 1e5, baseline 300, one repeat")
    args = parser.parse_args(argv)
    if args.quick:
        args.n, args.baseline_n = min(args.n, 100_000), min(args.baseline_n, 300)
    repeats = 1 if args.quick else 3

    load = os.getloadavg()
    ap = Aperture(*EDGETECH)
    rng = np.random.default_rng(args.seed)
    warm = feature_seeded_configs(rng, 1000, EDGETECH, EDGETECH)
    two_view_locus(warm["R"], warm["t"], warm["r1"], warm["r2"], ap, ap)  # warm-up

    rows = []
    for n in sorted({m for m in (10_000, 100_000) if m <= args.n} | {args.n}):
        if n <= CHUNK:
            cfg = feature_seeded_configs(rng, n, EDGETECH, EDGETECH)
            seconds = time_kernel(cfg, ap, repeats)
            note = f"one batch, best of {repeats}"
            del cfg
        else:
            seconds = time_kernel_streamed(rng, n, ap)
            note = f"streamed in chunks of {CHUNK:,}"
        rows.append(("exact kernel", n, seconds, peak_rss_mib(), note))

    cfg = feature_seeded_configs(rng, args.baseline_n, EDGETECH, EDGETECH)
    with Clock() as c:
        base = naive_baseline(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], ap)
    rows.append(
        ("naive 0.1 deg sampling", args.baseline_n, (c.wall, c.cpu), peak_rss_mib(),
         "3,600 points per circle, atan2/arcsin")
    )
    exact = two_view_locus(cfg["R"], cfg["t"], cfg["r1"], cfg["r2"], ap, ap).length
    nonempty = exact > 0
    rel = np.abs(base[nonempty] - exact[nonempty]) / exact[nonempty]
    def cpu_rate(row):
        return row[1] / row[2][1]

    kernel_rate = min(cpu_rate(r) for r in rows if r[0] == "exact kernel" and r[1] >= min(CHUNK, args.n))

    print(f"Command: `{shlex.join([Path(sys.executable).name] + sys.argv)}`  ")
    print(
        f"Machine: {cpu_model()}; Python {platform.python_version()}; numpy {np.__version__}; "
        f"single thread (OMP/OPENBLAS/MKL_NUM_THREADS=1); seed {args.seed}; "
        f"load average at start {load[0]:.2f}  "
    )
    print("Aperture: EdgeTech 2205 on both sensors (130 deg x 0.27 deg, 150 m); feature-seeded "
          "configurations (every locus non-empty)\n")
    print("| Method | Configurations | CPU time (s) | Configurations / CPU s | Wall time (s) "
          "| Configurations / wall s | Peak RSS (MiB) | Notes |")
    print("|---|---:|---:|---:|---:|---:|---:|---|")
    for name, n, (wall, cpu), rss, note in rows:
        print(f"| {name} | {n:,} | {cpu:.3f} | {n / cpu:,.0f} | {wall:.3f} | {n / wall:,.0f} "
              f"| {rss:.0f} | {note} |")
    print()
    print(f"Speed ratio (CPU time), exact kernel (slowest batch >= {min(CHUNK, args.n):,}) / "
          f"naive baseline: {kernel_rate / cpu_rate(rows[-1]):,.0f}x  ")
    print(f"Naive baseline relative length error vs exact ({nonempty.sum():,} non-empty loci): "
          f"median {np.median(rel):.3g}, 95th percentile {np.percentile(rel, 95):.3g}, "
          f"share with error > 10 %: {(rel > 0.1).mean():.1%}  ")
    print("Peak RSS is the process's running maximum (getrusage), read after each row. CPU time "
          "is this process's (time.process_time); wall time also counts waiting for a shared CPU.")


if __name__ == "__main__":
    main()
