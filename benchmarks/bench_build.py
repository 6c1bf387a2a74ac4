"""`make test` and `make book` of two revisions, side by side in one run (wall and CPU time).

Each revision gets a fresh clone of this repository (``git clone -q <repo> DIR`` with the revision
checked out, detached) in its own folder under the work directory, with ``../shared`` beside it
(a symlink to the ``shared`` folder beside this repository: the tests read
``../shared/data/real-sidescan/``). Each clone's ``.venv`` is built first (``make venv``, one after
the other, timed but not compared); then ``make test`` runs for both revisions **at the same
time**, and then ``make book`` for both at the same time, so both meet the same machine load.

Per run: wall time, CPU time (user + system) of the ``make`` process and every descendant it
waited for (``os.wait4``'s resource usage of the child), exit code, pytest's counts (the summary
line ``== 3312 passed, 1 skipped in 812.3s ==``), the load average sampled every 5 s, and for the
book, each notebook's wall time (the build's ``ran NAME [book] in S s`` lines; the book runs two
notebooks at a time) and papermill's duration of each executed notebook. The environment is
``CI=true`` (as ``.ci/run``: a skipped test fails the run). The two runs share no writable place: each clone has its own
``_build/``, ``.cache/``, ``.venv/`` and, per run, its own ``TMPDIR`` (pytest's ``tmp_path``,
``tempfile``), ``XDG_CACHE_HOME``/``XDG_CONFIG_HOME``/``XDG_DATA_HOME`` (Chromium's profile,
fontconfig), ``MPLCONFIGDIR``, ``IPYTHONDIR`` and ``JUPYTER_*_DIR`` under ``<workdir>/<label>/home``.

    python benchmarks/bench_build.py 1ca624e main                  # both targets (an hour or more)
    python benchmarks/bench_build.py 1ca624e main --only test
    python benchmarks/bench_build.py 1ca624e main --workdir /tmp/bb --json /tmp/bb/result.json
    python benchmarks/bench_build.py --table test.json book.json   # one table from two runs

It prints a Markdown table (per target and revision: wall s, CPU s, exit code, tests passed) with
the ratios after/before, and writes the same to a JSON file (``<workdir>/bench_build.json``
unless ``--json``).
"""

from __future__ import annotations

import argparse
import json
import os
import platform as _platform
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGETS = ("test", "book")
#: pytest's closing line, e.g. ``==== 3312 passed, 1 skipped, 4 warnings in 812.31s (0:13:32) ====``.
SUMMARY = re.compile(r"^=+ (?P<counts>.*?) in (?P<secs>[\d.]+)s(?: \([\d:]+\))? =+$")
COUNT = re.compile(r"(\d+) (passed|failed|skipped|errors?|xfailed|xpassed|warnings?|deselected|rerun)")
ISOLATED_DIRS = ("tmp", "xdg-cache", "xdg-config", "xdg-data", "matplotlib", "ipython", "jupyter-config",
                 "jupyter-data", "jupyter-runtime")


def parse_pytest_summary(text: str) -> dict | None:
    """Counts from the last pytest summary line in ``text``.

    Parameters
    ----------
    text : str
        A ``make test`` log (pytest's output, possibly with ANSI colour codes).

    Returns
    -------
    dict or None
        ``{"passed": int, "failed": int, "skipped": int, "errors": int, ..., "pytest_s": float}``
        (keys for the kinds the line names; ``error``/``warning`` are stored plural), or None when
        the log has no summary line (the run did not reach the end).
    """
    plain = re.sub(r"\x1b\[[0-9;]*m", "", text)
    found = None
    for line in plain.splitlines():
        m = SUMMARY.match(line.strip())
        if m and COUNT.search(m.group("counts")):
            found = m
    if found is None:
        return None
    counts: dict = {"passed": 0, "failed": 0, "skipped": 0, "errors": 0}
    for n, kind in COUNT.findall(found.group("counts")):
        kind = {"error": "errors", "warning": "warnings"}.get(kind, kind)
        counts[kind] = counts.get(kind, 0) + int(n)
    counts["pytest_s"] = float(found.group("secs"))
    return counts


#: ``sss-locus book``'s line for each executed notebook, e.g. ``ran noise [book] in 176.0 s -> ...``.
RAN = re.compile(r"^ran (?P<name>\S+) \[(?P<profile>[\w-]+)\] in (?P<secs>[\d.]+) s\b", re.M)


def parse_book_log(text: str) -> dict:
    """Wall seconds of each notebook a ``make book`` log says it ran (``ran NAME [PROFILE] in S s``).

    Parameters
    ----------
    text : str
        A ``make book`` log.

    Returns
    -------
    dict
        Notebook name -> seconds, in the order the log lists them (a notebook ran twice keeps its
        last time); empty when the log names none (taken from the cache, or the build failed early).
    """
    return {m.group("name"): float(m.group("secs")) for m in RAN.finditer(text)}


def ratio(after: float | None, before: float | None) -> float | None:
    """``after / before``, or None when either is missing or ``before`` is not positive."""
    if after is None or before is None or before <= 0:
        return None
    return after / before


def _fmt(x, spec: str) -> str:
    return "–" if x is None else format(x, spec)


def table(result: dict) -> str:
    """The Markdown table of a result (as written to the JSON file): one row per target and
    revision, then the ratio after/before of wall and CPU time, and the load average."""
    before, after = result["labels"]
    lines = ["| Target | Revision | Wall s | CPU s (user+sys) | Exit | Tests passed | Failed | Skipped | Load avg (min–max) |",
             "|---|---|---:|---:|---:|---:|---:|---:|---|"]
    for target in TARGETS:
        phase = result["phases"].get(target)
        if phase is None:
            continue
        load = phase["load"]
        load_s = f"{load['mean']:.1f} ({load['min']:.1f}–{load['max']:.1f})" if load else "–"
        for label in (before, after):
            r = phase["runs"][label]
            tests = r.get("tests") or {}
            lines.append(f"| make {target} | {label} ({result['revisions'][label][:7]}) | {_fmt(r['wall_s'], '.0f')} | "
                         f"{_fmt(r['cpu_s'], '.0f')} | {r['exit']} | {_fmt(tests.get('passed'), 'd')} | "
                         f"{_fmt(tests.get('failed', None) if tests else None, 'd')} | "
                         f"{_fmt(tests.get('skipped', None) if tests else None, 'd')} | {load_s} |")
        wall = ratio(phase["runs"][after]["wall_s"], phase["runs"][before]["wall_s"])
        cpu = ratio(phase["runs"][after]["cpu_s"], phase["runs"][before]["cpu_s"])
        lines.append(f"| make {target} | **after / before** | **{_fmt(wall, '.2f')}** | **{_fmt(cpu, '.2f')}** | | | | | |")
    return "\n".join(lines)


def merge_results(results: list[dict]) -> dict:
    """One result from several runs of the same two revisions (e.g. ``--only test`` and
    ``--only book``): the first one's fields, each target's phase from the last run that has it."""
    if len({tuple(r["revisions"].values()) for r in results}) != 1:
        raise SystemExit("bench_build: the result files compare different revisions")
    merged = dict(results[0], phases={})
    for r in results:
        merged["phases"].update(r["phases"])
    return merged


def _git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True, text=True).stdout.strip()


def _isolated_env(home: Path) -> dict:
    """The environment of one run: ``CI=true`` and every user-level cache or temporary folder
    the tools use (pytest, tempfile, matplotlib, IPython, Jupyter, Chromium/fontconfig via XDG)
    under ``home``, which belongs to this run only."""
    env = dict(os.environ)
    for var in ("SSS_LOCUS_BUILD_DIR", "SSS_LOCUS_CACHE_DIR", "SSS_LOCUS_RUN", "PYTHONPATH", "VIRTUAL_ENV",
                "PYTHONPYCACHEPREFIX", "PYTHONDONTWRITEBYTECODE", "PYTEST_ADDOPTS"):
        env.pop(var, None)
    dirs = {name: home / name for name in ISOLATED_DIRS}
    for d in dirs.values():
        d.mkdir(parents=True, exist_ok=True)
    env.update(CI="true", TMPDIR=str(dirs["tmp"]), XDG_CACHE_HOME=str(dirs["xdg-cache"]),
               XDG_CONFIG_HOME=str(dirs["xdg-config"]), XDG_DATA_HOME=str(dirs["xdg-data"]),
               MPLCONFIGDIR=str(dirs["matplotlib"]), IPYTHONDIR=str(dirs["ipython"]),
               JUPYTER_CONFIG_DIR=str(dirs["jupyter-config"]), JUPYTER_DATA_DIR=str(dirs["jupyter-data"]),
               JUPYTER_RUNTIME_DIR=str(dirs["jupyter-runtime"]))
    return env


def prepare(repo: Path, shared: Path, workdir: Path, label: str, sha: str) -> Path:
    """A fresh clone of ``repo`` at ``sha`` in ``<workdir>/<label>/repo``, ``../shared`` beside it."""
    base = workdir / label
    if base.exists():
        shutil.rmtree(base)
    base.mkdir(parents=True)
    clone = base / "repo"
    subprocess.run(["git", "clone", "-q", str(repo), str(clone)], check=True)
    _git(clone, "checkout", "-q", "--detach", sha)
    (base / "shared").symlink_to(shared)
    return clone


def _start(clone: Path, target: str, log: Path, env: dict) -> tuple[subprocess.Popen, float]:
    fh = open(log, "w")
    proc = subprocess.Popen(["make", target], cwd=clone, env=env, stdout=fh, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, start_new_session=True)
    fh.close()
    return proc, time.perf_counter()


def run_side_by_side(jobs: dict, target: str, logdir: Path, sample_s: float = 5.0) -> dict:
    """``make target`` in every clone of ``jobs`` (label -> (clone, env)) at once; waits for all.

    CPU time is the ``ru_utime + ru_stime`` that ``os.wait4`` returns for each ``make``: its own
    and that of every descendant it (or a descendant) waited for."""
    started = {}
    for label, (clone, env) in jobs.items():
        started[label] = _start(clone, target, logdir / f"{target}-{label}.log", env)
    done: dict = {}
    loads = [os.getloadavg()[0]]
    last = time.perf_counter()
    try:
        while len(done) < len(started):
            for label, (proc, t0) in started.items():
                if label in done:
                    continue
                pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    proc.returncode = os.waitstatus_to_exitcode(status)
                    done[label] = {"wall_s": time.perf_counter() - t0, "cpu_s": usage.ru_utime + usage.ru_stime,
                                   "user_s": usage.ru_utime, "sys_s": usage.ru_stime, "exit": proc.returncode,
                                   "max_rss_mib": usage.ru_maxrss / 1024, "log": str(logdir / f"{target}-{label}.log")}
                    print(f"  make {target} [{label}] finished: exit {proc.returncode}, "
                          f"{done[label]['wall_s']:.0f} s wall, {done[label]['cpu_s']:.0f} s CPU", flush=True)
            if time.perf_counter() - last >= sample_s:
                loads.append(os.getloadavg()[0])
                last = time.perf_counter()
            time.sleep(0.5)
    except BaseException:
        for proc, _ in started.values():
            if proc.returncode is None:
                os.killpg(proc.pid, signal.SIGTERM)
        raise
    loads.append(os.getloadavg()[0])
    return {"runs": done, "load": {"min": min(loads), "max": max(loads), "mean": sum(loads) / len(loads),
                                   "samples": len(loads)}}


def notebook_durations(clone: Path) -> dict:
    """Papermill's wall time of each executed notebook of the book, ``<clone>/_build/source/executed``
    (seconds; the build copies them to other folders too)."""
    out = {}
    for nb in sorted((clone / "_build" / "source" / "executed").glob("*.ipynb")):
        try:
            meta = json.loads(nb.read_text()).get("metadata", {}).get("papermill", {})
        except (OSError, ValueError):
            continue
        if isinstance(meta.get("duration"), (int, float)):
            out[str(nb.relative_to(clone))] = round(meta["duration"], 1)
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("before", nargs="?", help="the earlier revision (e.g. 1ca624e)")
    p.add_argument("after", nargs="?", help="the later revision (e.g. main)")
    p.add_argument("--only", choices=TARGETS, help="run only this target")
    p.add_argument("--workdir", type=Path, default=None,
                   help="where the clones go, outside every repository as in CI (default: "
                        "<tmp>/sss-locus-bench-build; each revision's folder is emptied first)")
    p.add_argument("--json", type=Path, default=None, help="result file (default: <workdir>/bench_build.json)")
    p.add_argument("--table", type=Path, nargs="+", metavar="JSON",
                   help="print the table of earlier result files (their targets merged) and run nothing")
    args = p.parse_args(argv)
    if args.table:
        print(table(merge_results([json.loads(f.read_text()) for f in args.table])))
        return 0
    if not (args.before and args.after):
        p.error("give the two revisions: BEFORE AFTER")

    repo = Path(_git(Path(__file__).resolve().parent, "rev-parse", "--show-toplevel"))
    shared = (repo.parent / "shared").resolve()
    if not (shared / "data").is_dir():
        sys.exit(f"bench_build: {repo.parent / 'shared'} (the shared data beside the repository) has no data/ folder")
    workdir = (args.workdir or Path(tempfile.gettempdir()) / "sss-locus-bench-build").resolve()
    labels = ("before", "after")
    revs = {}
    for label, rev in zip(labels, (args.before, args.after)):
        try:
            revs[label] = _git(repo, "rev-parse", "--verify", "--quiet", f"{rev}^{{commit}}")
        except subprocess.CalledProcessError:
            sys.exit(f"bench_build: {label} revision {rev!r} is not a commit of {repo}")
    targets = [args.only] if args.only else list(TARGETS)
    workdir.mkdir(parents=True, exist_ok=True)
    logdir = workdir / "logs"
    logdir.mkdir(exist_ok=True)
    result = {"command": " ".join([os.path.relpath(sys.argv[0]) if argv is None else "bench_build.py", *(argv or sys.argv[1:])]),
              "date_utc": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
              "machine": f"{_platform.node()}, {os.cpu_count()} cores, {_platform.processor() or _platform.machine()}",
              "python": sys.version.split()[0], "labels": list(labels),
              "revisions": revs, "names": {"before": args.before, "after": args.after},
              "venv": {}, "phases": {}, "notebooks": {}, "papermill": {}}

    jobs = {}
    for label in labels:
        clone = prepare(repo, shared, workdir, label, revs[label])
        env = _isolated_env(workdir / label / "home")
        print(f"== {label}: {args.before if label == 'before' else args.after} = {revs[label][:10]} in {clone}", flush=True)
        # The venv is built with the user's own caches (uv's wheel cache): not part of the comparison.
        phase = run_side_by_side({label: (clone, dict(os.environ, CI="true"))}, "venv", logdir)
        result["venv"][label] = phase["runs"][label] | {"load": phase["load"]}
        if phase["runs"][label]["exit"] != 0:
            sys.exit(f"bench_build: make venv failed for {label}; see {logdir / f'venv-{label}.log'}")
        jobs[label] = (clone, env)

    for target in targets:
        print(f"== make {target}: both revisions at once (load average now {os.getloadavg()[0]:.2f})", flush=True)
        phase = run_side_by_side(jobs, target, logdir)
        for label, r in phase["runs"].items():
            r["tests"] = parse_pytest_summary(Path(r["log"]).read_text(errors="replace")) if target == "test" else None
        result["phases"][target] = phase
        if target == "book":
            result["notebooks"] = {label: parse_book_log(Path(phase["runs"][label]["log"]).read_text(errors="replace"))
                                   for label in labels}
            result["papermill"] = {label: notebook_durations(jobs[label][0]) for label in labels}
        (args.json or workdir / "bench_build.json").write_text(json.dumps(result, indent=2))

    print()
    print(f"{result['date_utc']}; {result['machine']}; `{result['command']}`")
    print(table(result))
    out = args.json or workdir / "bench_build.json"
    out.write_text(json.dumps(result, indent=2))
    print(f"\nwritten: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
