"""Benchmark: end-to-end throughput of the Monte Carlo studies, against the kernel and a git ref.

For the pose-space study (sampling + kernel + Spearman bootstrap + heatmaps), the survey-pass
simulation alone (``survey_simulation``: sampling + kernel) and with its crossing-angle curve
(``survey_passes``: + bootstrap of the medians) and the noise Monte Carlo, prints samples per
second end to end and the share of that time spent in the exact kernel (``two_view_locus``,
timed by wrapping it where each study calls it; the end-to-end rate over the kernel-only rate on
the same configurations equals that share). Then (not with ``--quick``) the book profile's
compute time per notebook (``sss-locus run NAME --profile book`` into a scratch folder with an
empty cache; the trees take turns notebook by notebook), the speed-up of the pose-space sampler
with a local Dask cluster of 2 worker processes over in-process (with ``--quick`` on 200,000
samples instead of 1,000,000), the load average at start and end, and each target
with the measured value.

Last (also alone, with ``--reduce-only``), the pose-space study reduced on the workers
(``sss_locus.experiments.pose_space.reduce.reduce_pose_space``: rho table and heatmaps from
summaries): its end-to-end rate against the kernel-only rate, in-process against 2 local
worker processes (bit-identical?), and the bytes per sample the client receives against the
bytes per sample of the table that ``sample_pose_space`` sends back.

``--baseline REF`` runs the same measurements (not the Dask one) on a ``git worktree`` of
``REF`` with ``PYTHONPATH`` pointing there, in the same run, and prints both side by side.
This is a benchmark, not a test: nothing is asserted.

Usage::

    python benchmarks/bench_studies.py --baseline 71ed8ba          # everything (see README)
    python benchmarks/bench_studies.py --quick --baseline 71ed8ba  # small sizes, no notebooks
    python benchmarks/bench_studies.py --reduce-only               # the reduced pose-space study alone
"""

from __future__ import annotations

import argparse
import importlib
import inspect
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
    from sss_locus.experiments.noise import study as noise
    try:
        from sss_locus.experiments.datamodel.noise_model import load_noise_model
        from sss_locus.experiments.passes import propagation
    except ImportError:  # a baseline tree from before the noise model moved to the data model
        propagation, load_noise_model = noise, noise.load_noise_model
    from sss_locus.experiments.survey_passes import planning, study as survey_passes
    from sss_locus.experiments.pose_space import study as pose_space
    from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.stats import heatmaps, spearman_table, with_derived
    try:
        from sss_locus.experiments.pose_space.claims import claim_metrics
    except ImportError:  # a baseline tree from before pose_claims
        from sss_locus.experiments.pose_space.stats import claim_metrics

    spent = _timed_kernel([pose_space, survey_passes, propagation])
    out = {}
    n = 100_000 if quick else 600_000
    spec = pose_space.PoseSpaceSpec(load_platform("auv"))
    # warm-up (one-off imports and caches, the same in both trees), not timed
    # the tree measured may be one whose intervals are bootstrapped (today's main) or replicate
    # batches (no resamples to ask for)
    boot = "n_resamples" in inspect.signature(spearman_table).parameters
    spearman_table(with_derived(pose_space.sample_pose_space(spec, 2000, 9)),
                   **(dict(n_resamples=10, seed=9) if boot else {}))
    spent[0], start = 0.0, time.perf_counter()
    table = with_derived(pose_space.sample_pose_space(spec, n, 1))
    rho = spearman_table(table, **(dict(n_resamples=200, seed=1) if boot else {}))
    port = table[table["side2"] == "port"]
    claim_metrics(port, rho, heatmaps(port, spec.platform, n_bins=16), min_count=30)
    out["pose_space"] = dict(n=n, seconds=time.perf_counter() - start, kernel=spent[0])

    pf, env = load_platform("auv"), load_envelope("auv")
    grid = planning.crossing_angle_grid(2.0 if quick else 1.0, 40.0, 10.0 if quick else 5.0)
    per_angle = 500 if quick else 4000
    spent[0], start = 0.0, time.perf_counter()
    survey_passes.simulate_passes(pf, env, OffsetModel.parse("independent"), grid, per_angle, 1)
    out["survey_simulation"] = dict(n=per_angle * len(grid), seconds=time.perf_counter() - start,
                                    kernel=spent[0])
    spent[0], start = 0.0, time.perf_counter()
    planning.crossing_angle_curve(pf, env, OffsetModel.parse("independent"), crossing_angles_deg=grid,
                                  n_per_angle=per_angle, seed=1, n_resamples=200)
    out["survey_passes"] = dict(n=per_angle * len(grid), seconds=time.perf_counter() - start,
                                kernel=spent[0])

    samples, _ = survey_passes.simulate_passes(pf, env, OffsetModel("independent"), grid[::4], 50, 1)
    draws = 16 if quick else 64
    spent[0], start = 0.0, time.perf_counter()
    noise.survey_noise_table(pf, samples, {"x1": load_noise_model("auv")}, n_draws=draws, seed=1)
    out["noise"] = dict(n=len(samples) * draws, seconds=time.perf_counter() - start, kernel=spent[0])
    return out


def book_values(tree: Path, names) -> dict:
    """The book profile's parameter values of each notebook as ``tree`` declares them."""
    code = ("import json, sys; from sss_locus.pipeline.run.registry import get_entry; "
            "print(json.dumps({n: get_entry(n).resolve('book') for n in sys.argv[1:]}, default=list))")
    out = subprocess.run([sys.executable, "-c", code, *names], cwd=tree, env=dict(os.environ, PYTHONPATH=str(tree)),
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def _parameter_args(values: dict) -> list[str]:
    args = []
    for key, value in values.items():
        args += ["-p", key, value if isinstance(value, str) else repr(value)]
    return args


def measure_notebooks(trees: dict, names) -> tuple[dict, dict]:
    """Wall seconds of each notebook's book profile per tree, each run with an empty cache.

    The trees take turns notebook by notebook (baseline, then this tree), so a change of the
    machine's load during the run falls on both alike. With a baseline, a notebook whose book
    profile differs between the trees (e.g. raised sample counts) is also run on this tree with
    the baseline's values (``-p``), labelled ``<tree> at baseline values``: the like-for-like time.
    Returns the times by label and notebook, and the differing values by notebook.
    """
    times = {label: {} for label in trees}
    labels = list(trees)
    here = labels[-1]
    differ = {}
    if len(labels) > 1:
        base, now = (book_values(trees[lb], names) for lb in (labels[0], here))
        differ = {n: {k: v for k, v in base[n].items() if k in now[n] and now[n][k] != v} for n in names}
        differ = {n: d for n, d in differ.items() if d}
        if differ:
            times[f"{here} at baseline values"] = {}  # filled for every notebook
    like = f"{here} at baseline values"
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            runs = [(label, tree, []) for label, tree in trees.items()]
            if name in differ:
                runs.append((like, trees[here], _parameter_args(differ[name])))
            for i, (label, tree, extra) in enumerate(runs):
                env = dict(os.environ, PYTHONPATH=str(tree), SSS_LOCUS_BUILD_DIR=f"{tmp}/build{i}",
                           SSS_LOCUS_CACHE_DIR=f"{tmp}/cache{i}")
                env.pop("SSS_LOCUS_SCHEDULER", None)
                start = time.perf_counter()
                done = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", "run", name, "--profile",
                                       "book", *extra, "--output", f"{tmp}/run{i}-{name}/{name}.ipynb"], cwd=tree, env=env,
                                      capture_output=True, text=True)
                if done.returncode != 0:
                    raise SystemExit(f"{label}: sss-locus run {name} {' '.join(extra)} failed "
                                     f"(exit {done.returncode}):\n{done.stderr[-3000:]}")
                times[label][name] = time.perf_counter() - start
            if differ and name not in differ:
                times[like][name] = times[here][name]  # the same values: the same run
    return times, differ


DASK_REPEATS = 3  # both sides timed as the best of this many runs (the first run of a worker grows its heap)


def _best_of(repeats: int, run):
    """(shortest wall time, result) of ``repeats`` calls of ``run``."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return min(times), result


def measure_dask(quick: bool) -> dict:
    from sss_locus.experiments.stats import scale
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space

    spec, n = PoseSpaceSpec(load_platform("auv")), (200_000 if quick else 1_000_000)
    os.environ.pop(scale.SCHEDULER_ENV, None)
    t_serial, serial = _best_of(DASK_REPEATS, lambda: sample_pose_space(spec, n, 3))
    os.environ[scale.SCHEDULER_ENV] = "local:2"
    # start the cluster, import the studies on EVERY worker (a task may not reach both) and warm up
    scale.client("local:2").run(importlib.import_module, "sss_locus.experiments.pose_space.study")
    sample_pose_space(spec, 4 * 65536, 4)
    t_par, parallel = _best_of(DASK_REPEATS, lambda: sample_pose_space(spec, n, 3))
    scale.close_clients()
    same = all(serial[c].to_numpy().tobytes() == parallel[c].to_numpy().tobytes()
               for c in serial.columns if serial[c].dtype.kind == "f")
    return dict(n=n, serial=t_serial, workers2=t_par, speedup=t_serial / t_par, identical=same)


def measure_reduce(quick: bool) -> dict:
    """The pose-space study reduced on the workers (``experiments/pose_space/reduce.py``: Spearman rho
    table with replicate intervals and the five heatmaps' exact per-bin medians): end to end
    in-process against the kernel's share of it, in-process against 2 local worker processes
    (best of :data:`DASK_REPEATS` each, bit-identical?), and the bytes per sample the client
    receives, against the bytes per sample of the table ``sample_pose_space`` sends back."""
    import pickle

    from sss_locus.experiments.pose_space import study as pose_space
    from sss_locus.experiments.stats import scale
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.reduce import reduce_pose_space

    spec, n = pose_space.PoseSpaceSpec(load_platform("auv")), (200_000 if quick else 1_000_000)
    run = lambda: reduce_pose_space(spec, n, 3, n_bins=16, min_count=30)  # the book's bins
    os.environ.pop(scale.SCHEDULER_ENV, None)
    reduce_pose_space(spec, 20_000, 9)  # warm-up (imports), not timed
    spent = _timed_kernel([pose_space])
    spent[0] = 0.0
    t_serial, serial = _best_of(DASK_REPEATS, run)
    kernel = spent[0] / DASK_REPEATS
    chunk = pose_space.sample_pose_space(spec, 65536, 3)  # one chunk of the table path
    table_bytes = len(pickle.dumps(chunk)) / len(chunk)
    os.environ[scale.SCHEDULER_ENV] = "local:2"
    scale.client("local:2").run(importlib.import_module, "sss_locus.experiments.pose_space.reduce")
    reduce_pose_space(spec, 200_000, 4)  # warm-up on the workers
    t_par, parallel = _best_of(DASK_REPEATS, run)
    scale.close_clients()
    os.environ.pop(scale.SCHEDULER_ENV, None)
    frames = [(serial.rho, parallel.rho)] + [(serial.maps[p], parallel.maps[p]) for p in serial.maps]
    same = serial.batch_rho.tobytes() == parallel.batch_rho.tobytes() and all(
        a[c].to_numpy().tobytes() == b[c].to_numpy().tobytes() for a, b in frames for c in a.columns
        if a[c].dtype.kind == "f")
    return dict(n=n, serial=t_serial, kernel=kernel, workers2=t_par, speedup=t_serial / t_par, identical=same,
                client_bytes=serial.bytes_to_client / n, worker_bytes=serial.bytes_between_workers / n,
                table_bytes=table_bytes)


def print_reduce(r: dict) -> None:
    print(f"\nPose space reduced on the workers (rho table + 5 heatmaps, 16 bins), {r['n']:,} samples, "
          f"best of {DASK_REPEATS}:\n"
          f"- in-process: {r['n'] / r['serial']:,.0f} samples/s end to end, kernel-only {r['n'] / r['kernel']:,.0f}"
          f" samples/s: end to end {100 * r['kernel'] / r['serial']:.0f} % of the kernel-only rate (target >= 40 %)\n"
          f"- 2 local worker processes: {r['workers2']:.1f} s against {r['serial']:.1f} s in-process, speed-up "
          f"{r['speedup']:.2f}x (target >= 1.6x); bit-identical: {r['identical']}\n"
          f"- bytes to the client per sample: {r['client_bytes']:.3f} (the table: {r['table_bytes']:.0f}; "
          f"{r['table_bytes'] / r['client_bytes']:,.0f}x less, target >= 50x); between workers (heatmap rows "
          f"to the per-panel reduce tasks): {r['worker_bytes']:.1f}")


def measure_tree(tree: Path, args) -> dict:
    """Run the study measurements in a child process importing ``sss_locus`` from ``tree``."""
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child"] + (["--quick"] if args.quick else [])
    env = dict(os.environ, PYTHONPATH=str(tree))
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"  # both trees as the book's kernels now run them (runner.KERNEL_BLAS_THREADS)
    result = subprocess.run(cmd, cwd=tree, env=env, check=True, capture_output=True, text=True)
    return json.loads(result.stdout.strip().splitlines()[-1])


def _rows(label: str, data: dict) -> list[str]:
    rows = []
    for study, d in data["studies"].items():
        rows.append(f"| {label} | {study} | {d['n']:,} | {d['n'] / d['seconds']:,.0f} | "
                    f"{d['n'] / d['kernel']:,.0f} | {100 * d['kernel'] / d['seconds']:.0f} % |")
    return rows


def _targets(results: dict, dask: dict) -> list[str]:
    """The issue's targets, each with the measured value (the tree labelled "this tree"; the
    compute target at the baseline's parameter values, like for like)."""
    labels = [lb for lb in results if not lb.endswith(" at baseline values")]
    here = results[labels[-1]]
    lines = []
    for study in ("pose_space", "survey_simulation", "survey_passes"):
        d = here["studies"][study]
        share = 100 * d["kernel"] / d["seconds"]
        lines.append(f"- {study}: end-to-end {share:.0f} % of the kernel-only rate (target >= 40 %): "
                     f"{'met' if share >= 40 else 'NOT met'}")
    if len(labels) > 1 and "notebooks" in here:
        like = results.get(f"{labels[-1]} at baseline values", here)
        base, now = (sum(d["notebooks"].values()) for d in (results[labels[0]], like))
        lines.append(f"- book profile compute at the baseline's values: {now:.0f} s = {100 * now / base:.0f} % "
                     f"of {labels[0]}'s {base:.0f} s (target <= 50 %): {'met' if now <= 0.5 * base else 'NOT met'}")
        if like is not here:
            lines.append(f"- book profile compute with this tree's own values (raised sample counts): "
                         f"{sum(here['notebooks'].values()):.0f} s")
    lines.append(f"- Dask, 2 local workers: {dask['speedup']:.2f}x (target >= 1.6x): "
                 f"{'met' if dask['speedup'] >= 1.6 else 'NOT met'}; bit-identical: {dask['identical']}")
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--baseline", metavar="REF", help="also measure this git ref, side by side")
    parser.add_argument("--quick", action="store_true", help="small sizes, no notebooks, a small Dask run")
    parser.add_argument("--notebooks", nargs="*", default=list(NOTEBOOKS))
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--reduce-only", action="store_true",
                        help="only the pose-space study reduced on the workers (in-process and 2 workers)")
    args = parser.parse_args()
    if args.reduce_only:
        started, load_start = time.perf_counter(), os.getloadavg()
        sys.path.insert(0, str(REPO))
        result = measure_reduce(args.quick)
        print(f"{os.cpu_count()} CPUs; load average at start {load_start[0]:.2f}, at end {os.getloadavg()[0]:.2f}; "
              f"run took {time.perf_counter() - started:.0f} s")
        print_reduce(result)
        return 0
    if args.child:
        print(json.dumps({"studies": measure_studies(args.quick)}))
        return 0
    started, load_start = time.perf_counter(), os.getloadavg()
    trees = {"this tree": REPO}
    tmp = None
    if args.baseline:
        tmp = tempfile.mkdtemp(prefix="bench-baseline-")
        subprocess.run(["git", "worktree", "add", "--detach", tmp, args.baseline], cwd=REPO, check=True,
                       capture_output=True)
        trees = {f"baseline {args.baseline}": Path(tmp), **trees}
    try:
        results = {label: measure_tree(tree, args) for label, tree in trees.items()}
        if not args.quick:
            notebook_times, differ = measure_notebooks(trees, args.notebooks)
            for label, times in notebook_times.items():
                results.setdefault(label, {"studies": {}})["notebooks"] = times
    finally:
        if tmp:
            subprocess.run(["git", "worktree", "remove", "--force", tmp], cwd=REPO, check=False)
    sys.path.insert(0, str(REPO))
    dask = measure_dask(args.quick)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True,
                            text=True).stdout.strip()
    print(f"this tree: {commit}; {os.cpu_count()} CPUs; load average (1, 5, 15 min) at start "
          f"{', '.join(f'{x:.2f}' for x in load_start)}, at end "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}; run took {time.perf_counter() - started:.0f} s\n")
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
        for name, values in differ.items():
            print(f"\n{name}: book profile differs from the baseline's in {values} (the baseline's values)")
    print(f"\nDask, pose-space sampler, {dask['n']:,} samples, best of {DASK_REPEATS}: in-process {dask['serial']:.1f} s, "
          f"2 local worker processes {dask['workers2']:.1f} s, speed-up {dask['speedup']:.2f}x, "
          f"bit-identical: {dask['identical']}")
    print("\nTargets, this tree:\n" + "\n".join(_targets(results, dask)))
    print_reduce(measure_reduce(args.quick))
    return 0


if __name__ == "__main__":
    sys.exit(main())
