"""Benchmark: the user-visible wall time of ``sss-locus answer`` and of the pose-space chapter,
this tree against a git ref, side by side in one run.

Made to decide whether the studies' own copies of library functions (average ranks, binned
medians, the vehicle attitude; replaced by :func:`scipy.stats.rankdata`,
:func:`scipy.stats.binned_statistic_dd` and ``Rotation.from_euler``) save at least 20 % of a
wall time a user waits on. Each repetition runs, for each tree in turn (the order alternating
between repetitions, so a change of the machine's load falls on both alike):

- ``sss-locus answer -p platform auv`` (its default quick profile), and
- ``sss-locus run pose_space --profile book --output <scratch>`` (the chapter as the book runs it),

each with an empty cache and a private build folder, importing ``sss_locus`` from its tree
(``PYTHONPATH``; ``REF`` checked out with ``git worktree`` into a temporary folder). It prints
the wall and CPU seconds (the command and every process it waited for) of each run, their
medians per tree and command, and the ratio. This is a benchmark, not a test: nothing is
asserted.

Usage::

    python benchmarks/bench_libraries.py --baseline df45293              # 2 repetitions
    python benchmarks/bench_libraries.py --baseline df45293 --repeats 3 --profile quick
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd: list[str], tree: Path, scratch: Path) -> tuple[float, float]:
    """(wall s, CPU s) of ``cmd`` run in ``tree`` with an empty cache and build folder."""
    env = dict(os.environ, PYTHONPATH=str(tree), SSS_LOCUS_BUILD_DIR=str(scratch / "build"),
               SSS_LOCUS_CACHE_DIR=str(scratch / "cache"))
    env.pop("SSS_LOCUS_SCHEDULER", None)
    cpu, start = _children_cpu(), time.perf_counter()
    done = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} in {tree} failed (exit {done.returncode}):\n{done.stderr[-3000:]}")
    return wall, _children_cpu() - cpu


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--baseline", metavar="REF", required=True, help="git ref measured side by side")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--profile", default="book", help="profile of the pose-space run (default: book)")
    args = parser.parse_args()
    cli = [sys.executable, "-m", "sss_locus.pipeline.cli"]
    commands = {"answer -p platform auv": cli + ["answer", "-p", "platform", "auv"],
                f"run pose_space --profile {args.profile}": None}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        base = tmp / "baseline"
        subprocess.run(["git", "worktree", "add", "--detach", str(base), args.baseline], cwd=REPO, check=True,
                       capture_output=True)
        trees = {f"baseline {args.baseline}": base, "this tree": REPO}
        runs: dict[tuple[str, str], list[tuple[float, float]]] = {}
        print(f"load average at start: {os.getloadavg()[0]:.2f}", flush=True)
        start = time.perf_counter()
        try:
            for rep in range(args.repeats):
                order = list(trees.items())[:: 1 if rep % 2 == 0 else -1]
                for name, fixed in commands.items():
                    for label, tree in order:
                        scratch = tmp / f"{rep}-{label.split()[0]}-{name.split()[0]}"
                        cmd = fixed or cli + ["run", "pose_space", "--profile", args.profile, "--output",
                                              str(scratch / "out" / "pose_space.ipynb")]
                        wall, cpu = timed(cmd, tree, scratch)
                        runs.setdefault((name, label), []).append((wall, cpu))
                        print(f"rep {rep}: {label}: {name}: wall {wall:.1f} s, CPU {cpu:.1f} s", flush=True)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(base)], cwd=REPO, capture_output=True)
        print(f"\nload average at end: {os.getloadavg()[0]:.2f}; {time.perf_counter() - start:.0f} s\n")
        print("| Command | Tree | Wall s (median) | CPU s (median) |\n|---|---|---:|---:|")
        for (name, label), values in runs.items():
            print(f"| {name} | {label} | {statistics.median(w for w, _ in values):.1f} "
                  f"| {statistics.median(c for _, c in values):.1f} |")
        labels = list(trees)
        for name in commands:
            b, t = (statistics.median(w for w, _ in runs[(name, lb)]) for lb in labels)
            bc, tc = (statistics.median(c for _, c in runs[(name, lb)]) for lb in labels)
            print(f"\n{name}: this tree / baseline = {t / b:.2f} wall, {tc / bc:.2f} CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
