"""Benchmark: end-to-end throughput of the Monte Carlo studies, against the kernel and a git ref.

For the pose-space study (sampling + kernel + Spearman bootstrap + heatmaps), the survey-pass
simulation (sampling + kernel + crossing-angle curve with bootstrap) and the noise Monte Carlo,
prints samples per second end to end and the share of that time spent in the exact kernel
(``two_view_locus``, timed by wrapping it where each study calls it; the end-to-end rate over
the kernel-only rate on the same configurations equals that share). Then the book profile's
compute time per notebook (``sss-locus run NAME --profile book`` into a scratch folder with an
empty cache), and the speed-up of the pose-space sampler with a local Dask cluster of 2
worker processes over in-process.

``--baseline REF`` runs the same measurements (not the Dask one) on a ``git worktree`` of
``REF`` with ``PYTHONPATH`` pointing there, in the same run, and prints both side by side.
This is a benchmark, not a test: nothing is asserted.

Usage::

    python benchmarks/bench_studies.py --baseline 71ed8ba          # everything (~15 min)
    python benchmarks/bench_studies.py --quick --baseline 71ed8ba  # studies only, small sizes
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
NOTEBOOKS = ("pose_space", "survey_passes", "planning", "three_views", "noise")


def _timed_kernel(modules):
    """Wrap ``two_view_locus`` in each module; returns the accumulated seconds (a list)."""
    import sss_locus

    spent = [0.0]
    kernel = sss_locus.two_view_locus

    def wrapped(*args, **kwargs):
        start = time.perf_counter()
        try:
            return kernel(*args, **kwargs)
        finally:
            spent[0] += time.perf_counter() - start

    for module in modules:
        module.two_view_locus = wrapped
    return spent


def measure_studies(quick: bool) -> dict:
    from sss_locus.experiments import noise, planning, pose_space, survey_passes
    from sss_locus.experiments.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.platforms import load_platform
    from sss_locus.experiments.pose_stats import claim_metrics, heatmaps, spearman_table, with_derived

    spent = _timed_kernel([pose_space, survey_passes, noise])
    out = {}
    n = 100_000 if quick else 600_000
    spec = pose_space.PoseSpaceSpec(load_platform("auv"))
    spent[0], start = 0.0, time.perf_counter()
    table = with_derived(pose_space.sample_pose_space(spec, n, 1))
    rho = spearman_table(table, n_resamples=200, seed=1)
    port = table[table["side2"] == "port"]
    claim_metrics(port, rho, heatmaps(port, spec.platform, n_bins=16), min_count=30)
    out["pose_space"] = dict(n=n, seconds=time.perf_counter() - start, kernel=spent[0])

    pf, env = load_platform("auv"), load_envelope("auv")
    grid = planning.crossing_angle_grid(2.0 if quick else 1.0, 40.0, 10.0 if quick else 5.0)
    per_angle = 500 if quick else 4000
    spent[0], start = 0.0, time.perf_counter()
    planning.crossing_angle_curve(pf, env, OffsetModel.parse("independent"), crossing_angles_deg=grid,
                                  n_per_angle=per_angle, seed=1, n_resamples=200)
    out["survey_passes"] = dict(n=per_angle * len(grid), seconds=time.perf_counter() - start,
                                kernel=spent[0])

    samples, _ = survey_passes.simulate_passes(pf, env, OffsetModel("independent"), grid[::4], 50, 1)
    draws = 16 if quick else 64
    spent[0], start = 0.0, time.perf_counter()
    noise.survey_noise_table(pf, samples, {"x1": noise.load_noise_model("auv")}, n_draws=draws, seed=1)
    out["noise"] = dict(n=len(samples) * draws, seconds=time.perf_counter() - start, kernel=spent[0])
    return out


def measure_notebooks(tree: Path, names) -> dict:
    """Wall seconds of each notebook's book profile, run from ``tree`` with an empty cache."""
    times = {}
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, PYTHONPATH=str(tree), SSS_LOCUS_BUILD_DIR=f"{tmp}/build",
                   SSS_LOCUS_CACHE_DIR=f"{tmp}/cache")
        env.pop("SSS_LOCUS_SCHEDULER", None)
        for name in names:
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli", "run", name, "--profile", "book",
                            "--output", f"{tmp}/{name}.ipynb"], cwd=tree, env=env, check=True,
                           capture_output=True)
            times[name] = time.perf_counter() - start
    return times


def measure_dask(quick: bool) -> dict:
    from sss_locus.experiments import scale
    from sss_locus.experiments.platforms import load_platform
    from sss_locus.experiments.pose_space import PoseSpaceSpec, sample_pose_space

    spec, n = PoseSpaceSpec(load_platform("auv")), (200_000 if quick else 1_000_000)
    os.environ.pop(scale.SCHEDULER_ENV, None)
    start = time.perf_counter()
    serial = sample_pose_space(spec, n, 3)
    t_serial = time.perf_counter() - start
    os.environ[scale.SCHEDULER_ENV] = "local:2"
    sample_pose_space(spec, 2 * 65536, 4)  # start the cluster and import on the workers
    start = time.perf_counter()
    parallel = sample_pose_space(spec, n, 3)
    t_par = time.perf_counter() - start
    scale.close_clients()
    same = all(serial[c].to_numpy().tobytes() == parallel[c].to_numpy().tobytes()
               for c in serial.columns if serial[c].dtype.kind == "f")
    return dict(n=n, serial=t_serial, workers2=t_par, speedup=t_serial / t_par, identical=same)


def measure_tree(tree: Path, args) -> dict:
    """Run the measurements in a child process importing ``sss_locus`` from ``tree``."""
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child"] + (["--quick"] if args.quick else [])
    env = dict(os.environ, PYTHONPATH=str(tree))
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env.pop(var, None)  # the studies as the book runs them
    result = subprocess.run(cmd, cwd=tree, env=env, check=True, capture_output=True, text=True)
    data = json.loads(result.stdout.strip().splitlines()[-1])
    if not args.quick:
        data["notebooks"] = measure_notebooks(tree, args.notebooks)
    return data


def _rows(label: str, data: dict) -> list[str]:
    rows = []
    for study, d in data["studies"].items():
        rows.append(f"| {label} | {study} | {d['n']:,} | {d['n'] / d['seconds']:,.0f} | "
                    f"{d['n'] / d['kernel']:,.0f} | {100 * d['kernel'] / d['seconds']:.0f} % |")
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--baseline", metavar="REF", help="also measure this git ref, side by side")
    parser.add_argument("--quick", action="store_true", help="small sizes, no notebooks, no Dask")
    parser.add_argument("--notebooks", nargs="*", default=list(NOTEBOOKS))
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        print(json.dumps({"studies": measure_studies(args.quick)}))
        return 0
    trees = {"this tree": REPO}
    tmp = None
    if args.baseline:
        tmp = tempfile.mkdtemp(prefix="bench-baseline-")
        subprocess.run(["git", "worktree", "add", "--detach", tmp, args.baseline], cwd=REPO, check=True,
                       capture_output=True)
        trees = {f"baseline {args.baseline}": Path(tmp), **trees}
    try:
        results = {label: measure_tree(tree, args) for label, tree in trees.items()}
    finally:
        if tmp:
            subprocess.run(["git", "worktree", "remove", "--force", tmp], cwd=REPO, check=False)
    print(f"load average at end: {os.getloadavg()[0]:.2f}; {os.cpu_count()} CPUs\n")
    print("| Tree | Study | Samples | End-to-end samples/s | Kernel-only samples/s | Share in kernel |")
    print("|---|---|---:|---:|---:|---:|")
    for label, data in results.items():
        print("\n".join(_rows(label, data)))
    if not args.quick:
        print("\n| Notebook (book profile) | " + " | ".join(f"{lb} (s)" for lb in results) + " |")
        print("|---|" + "---:|" * len(results))
        for name in args.notebooks:
            print(f"| {name} | " + " | ".join(f"{d['notebooks'][name]:.0f}" for d in results.values()) + " |")
        print("| **total** | " + " | ".join(f"**{sum(d['notebooks'].values()):.0f}**"
                                         for d in results.values()) + " |")
        sys.path.insert(0, str(REPO))
        dask = measure_dask(args.quick)
        print(f"\nDask, pose-space sampler, {dask['n']:,} samples: in-process {dask['serial']:.1f} s, "
              f"2 local worker processes {dask['workers2']:.1f} s, speed-up {dask['speedup']:.2f}x, "
              f"bit-identical: {dask['identical']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
