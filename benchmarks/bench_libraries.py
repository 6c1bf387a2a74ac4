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

``--variants`` also runs the pose-space chapter on this tree with ONE of the baseline's own
implementations put back (``ranks``: ``rowstats`` and ``pose_stats.column_rank_sets``;
``medians``: ``pose_stats.grouped_binned``/``grouped_binned_medians``; ``attitude``:
``straight_pass.vehicle_attitude``), each copied from ``REF``'s source by a ``sitecustomize``
module on ``PYTHONPATH`` that every process (the kernel too) runs at start: what each
replacement costs on its own, against ``none`` (the same start-up imports, nothing put back).

Usage::

    python benchmarks/bench_libraries.py --baseline df45293              # 2 repetitions
    python benchmarks/bench_libraries.py --baseline df45293 --repeats 0 --variants  # variants only
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


#: Per variant, the baseline's functions put back: (module, functions copied from REF's source
#: into the module, names re-bound in the modules that imported them by name).
OLD_PARTS = {
    "ranks": [("rowstats", None, {"pose_stats": ["average_ranks", "batch_average_ranks", "ranks_in_order",
                                                 "value_order"], "replicates": ["average_ranks"],
                                  "pose_reduce": ["average_ranks"]}),
              ("pose_stats", ["column_rank_sets"], {})],
    "medians": [("pose_stats", ["grouped_binned", "_stable_order", "grouped_binned_medians"],
                 {"pose_claims": ["grouped_binned", "grouped_binned_medians"]})],
    "attitude": [("straight_pass", ["_half_angle", "_compose_quat", "vehicle_attitude"],
                  {"pose_draw": ["vehicle_attitude"], "view_sets": ["vehicle_attitude"],
                   "choices": ["vehicle_attitude"], "terrain_survey": ["vehicle_attitude"]})],
    # the same start-up imports, nothing put back: the reference of the three
    "none": [(m, [], {}) for m in ("rowstats", "pose_stats", "pose_claims", "straight_pass", "pose_draw")],
}

SITECUSTOMIZE = """
import ast, importlib, collections
def _functions(src, names):
    lines, out = src.splitlines(), []
    for node in ast.parse(src).body:
        if isinstance(node, ast.FunctionDef) and node.name in names:
            out.append("\\n".join(lines[node.lineno - 1 - len(node.decorator_list):node.end_lineno]))
    assert len(out) == len(names), names
    return "\\n\\n".join(out)
for module, names, rebind in PARTS:
    mod = importlib.import_module("sss_locus.experiments." + module)
    src = SOURCES[module]
    mod.__dict__.setdefault("_order_memo", collections.OrderedDict())
    exec(compile(src if names is None else _functions(src, names), "baseline " + module, "exec"), mod.__dict__)
    for other, attrs in rebind.items():
        target = importlib.import_module("sss_locus.experiments." + other)
        for a in attrs:
            setattr(target, a, getattr(mod, a))
"""


def variant_dir(tmp: Path, ref: str, variant: str) -> Path:
    """A folder holding a ``sitecustomize.py`` that puts back ``variant``'s functions of ``ref``."""
    parts = OLD_PARTS[variant]
    sources = {m: subprocess.run(["git", "show", f"{ref}:sss_locus/experiments/{m}.py"], cwd=REPO, check=True,
                                 capture_output=True, text=True).stdout for m, _, _ in parts}
    folder = tmp / f"variant-{variant}"
    folder.mkdir()
    (folder / "sitecustomize.py").write_text(f"PARTS = {parts!r}\nSOURCES = {sources!r}\n" + SITECUSTOMIZE)
    return folder


def timed(cmd: list[str], tree: Path, scratch: Path, extra_path: Path | None = None) -> tuple[float, float]:
    """(wall s, CPU s) of ``cmd`` run in ``tree`` with an empty cache and build folder."""
    path = str(tree) if extra_path is None else f"{extra_path}{os.pathsep}{tree}"
    env = dict(os.environ, PYTHONPATH=path, SSS_LOCUS_BUILD_DIR=str(scratch / "build"),
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
    parser.add_argument("--variants", action="store_true",
                        help="also the pose-space run with each one of the baseline's implementations put back")
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
            if args.variants:
                for variant in OLD_PARTS:
                    name = f"run pose_space --profile {args.profile}"
                    scratch = tmp / f"variant-{variant}-run"
                    cmd = cli + ["run", "pose_space", "--profile", args.profile, "--output",
                                 str(scratch / "out" / "pose_space.ipynb")]
                    wall, cpu = timed(cmd, REPO, scratch, variant_dir(tmp, args.baseline, variant))
                    runs.setdefault((name, f"this tree, baseline's {variant}"), []).append((wall, cpu))
                    print(f"this tree with the baseline's {variant}: {name}: wall {wall:.1f} s, CPU {cpu:.1f} s",
                          flush=True)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(base)], cwd=REPO, capture_output=True)
        print(f"\nload average at end: {os.getloadavg()[0]:.2f}; {time.perf_counter() - start:.0f} s\n")
        print("| Command | Tree | Wall s (median) | CPU s (median) |\n|---|---|---:|---:|")
        for (name, label), values in runs.items():
            print(f"| {name} | {label} | {statistics.median(w for w, _ in values):.1f} "
                  f"| {statistics.median(c for _, c in values):.1f} |")
        labels = list(trees)
        name = f"run pose_space --profile {args.profile}"
        ref = (name, "this tree, baseline's none")
        base_cpu = statistics.median(c for _, c in runs.get(ref, runs.get((name, labels[1]), [(1.0, 1.0)])))
        for (cmd_name, label), values in runs.items():
            if cmd_name == name and label.startswith("this tree, ") and (cmd_name, label) != ref:
                cpu = statistics.median(c for _, c in values)
                print(f"\n{label}: {1 - cpu / base_cpu:.0%} less CPU than this tree's chapter (reference: none)")
        for name in (n for n in commands if all((n, lb) in runs for lb in labels)):
            b, t = (statistics.median(w for w, _ in runs[(name, lb)]) for lb in labels)
            bc, tc = (statistics.median(c for _, c in runs[(name, lb)]) for lb in labels)
            print(f"\n{name}: this tree / baseline = {t / b:.2f} wall, {tc / bc:.2f} CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
