"""The results of runs in the build area: committing a finished run, and checking that the
executed copies and figures the book is about to render belong together.

Commit
------
A run writes into a private staging folder. :func:`commit_run` then, holding the build area's
lock (:func:`build_lock`) and with SIGINT/SIGTERM/SIGHUP held back until it is done:

1. checks the space the new files need and stages each of them beside its target under a
   unique temporary name (nothing old is touched yet),
2. then, by renames and unlinks only, replaces the figure files (each manifest after the files
   it lists), removes the notebook's figures the run no longer exported (manifest first) and
   puts the executed copy in place;

any failure (a full disk included) undoes every step: the last good results stay as they were
(:mod:`sss_locus.pipeline.run.transaction`).

Every figure manifest records the run key of the run that made it, and so does the executed
copy: :func:`problems` finds a copy and figures from different runs whatever happened.
"""

from __future__ import annotations

import hashlib
import json
import re
import signal
from collections import Counter
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.run import atomic, transaction
from sss_locus.pipeline.publish import export, provenance

_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_HELD = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP}


def build_lock_file() -> Path:
    """Lock file of the build area (taken by commits and by the book build)."""
    return paths.build_dir() / ".lock"


@contextmanager
def build_lock() -> Iterator[None]:
    """Exclusive lock on the build area: one commit or one book build at a time."""
    with atomic.file_lock(build_lock_file()):
        yield


@contextmanager
def signals_held() -> Iterator[None]:
    """Delay SIGINT/SIGTERM/SIGHUP until the block is over (a commit is never cut in half)."""
    old = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _manifests_of(folder: Path, notebook: str | None) -> dict[str, dict[str, Any]]:
    return {m["label"]: m for m in export.load_manifests(folder, export.KINDS)
            if notebook is None or m.get("notebook") == notebook}


def labels_of(folder: Path, notebook: str) -> list[str]:
    """The labels of the figures and tables in ``folder`` whose manifests name ``notebook`` (its
    source path): what a commit of that notebook's next run replaces or removes."""
    return sorted(_manifests_of(folder, notebook)) if folder.is_dir() else []


def _remove_figure(swap: transaction.FileSwap, folder: Path, manifest: dict[str, Any],
                   keep: set[str] = frozenset()) -> None:
    if not keep:
        swap.unlink(folder / f"{manifest['label']}.json")
    for name in manifest.get("files", {}):
        if name not in keep:
            swap.unlink(folder / name)


def commit_run(staged_notebook: Path, staged_figures: Path, executed: Path, figures: Path,
               notebook: str | None) -> list[str]:
    """Move a finished run into place (see the module docstring); return the exported labels.

    ``notebook`` is the source path recorded in the manifests: the notebook's earlier figures
    in ``figures`` are replaced (``None``: only same-label figures are replaced). Every new file
    is staged first (:class:`sss_locus.pipeline.run.transaction.FileSwap`): a failure, a full disk
    included, raises :class:`~sss_locus.pipeline.run.transaction.CommitFailed` and leaves the old
    figures, manifests and executed copy exactly as they were.
    """
    new = _manifests_of(staged_figures, None) if staged_figures.is_dir() else {}
    what = f"the run into {executed.name} and {figures}"
    with signals_held(), transaction.FileSwap(what) as swap:
        figures.mkdir(parents=True, exist_ok=True)
        executed.parent.mkdir(parents=True, exist_ok=True)
        swap.check_space(figures, [staged_figures / name for m in new.values()
                                   for name in [*m["files"], f"{m['label']}.json"]])
        old = _manifests_of(figures, notebook) if notebook is not None else {}
        for label, manifest in new.items():
            previous = old.pop(label, None) or _manifests_of(figures, None).get(label)
            swap.unlink(figures / f"{label}.json")  # incomplete while files change
            for name in manifest["files"]:
                swap.copy(staged_figures / name, figures / name)
            swap.copy(staged_figures / f"{label}.json", figures / f"{label}.json")
            if previous:
                _remove_figure(swap, figures, previous, keep=set(manifest["files"]) | {f"{label}.json"})
        for manifest in old.values():  # figures this notebook no longer draws
            _remove_figure(swap, figures, manifest)
        swap.move(staged_notebook, executed)
    return sorted(new)


def notebook_error(nb: dict[str, Any]) -> tuple[str, str] | None:
    """``(summary, traceback)`` of the first failing cell of an executed notebook, or None.

    The summary is one line: the cell (its number among code cells and execution count), the
    cell's first line of code, and the last line of the error.
    """
    number = 0
    for cell in nb.get("cells", []):
        if cell.get("cell_type") != "code" or "injected-parameters" in cell.get("metadata", {}).get("tags", []):
            continue
        number += 1  # the code cell's number in the source notebook
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                source = "".join(cell.get("source", "")).strip().splitlines() or [""]
                count = cell.get("execution_count")
                last = (str(output.get("evalue", "")).strip().splitlines() or [""])[-1]
                trace = _ANSI.sub("", "\n".join(output.get("traceback", [])))
                # the cell's own failing line: the first "---->" of the traceback
                marked = re.search(r"^-*> *\d+ (.*)$", trace, re.M)
                line = (marked.group(1) if marked else source[0]).strip()[:80]
                summary = (f"cell {number}{f' (In [{count}])' if count else ''} at `{line}`: "
                           f"{output.get('ename', 'Error')}: {last}")
                return summary, trace
    return None


def read_notebook(path: Path) -> dict[str, Any] | None:
    try:
        nb = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return nb if isinstance(nb, dict) and isinstance(nb.get("metadata"), dict) else None


def run_key(entry: Any, profile: str, parameters: dict[str, Any]) -> str:
    """Hash of everything an executed copy depends on (see the module docstring) except the
    contents of the user's data files, which :func:`data_read_changed` checks entry by entry."""
    payload = json.dumps(
        {"source": provenance.file_sha256(entry.source), "profile": profile, "parameters": parameters,
         "code": provenance.code_sha256(), "lock": provenance.environment_sha256()},
        sort_keys=True, default=provenance.json_default,
    )
    return hashlib.sha256(payload.encode()).hexdigest()


def data_read_changed(record: dict[str, Any]) -> bool:
    """True when a data entry the run read (``sss_locus.data_read`` of its executed copy: dotted
    entries of the merged data with their SHA-256) differs now, or its data files cannot be read.

    A run with ``--data`` files records the entries its loaders read
    (:func:`sss_locus.experiments.datamodel.datadoc.note_read`); an edit of a user file then makes stale
    exactly the runs that read an edited entry (e.g. ``noise.my_auv``: the noise and three-view
    chapters) and no others.
    """
    read = record.get("data_read")
    if not read:
        return False
    from sss_locus.experiments.datamodel import userdata

    parameters = record.get("parameters", {})
    try:
        inputs = userdata.make_inputs(parameters.get("data_files") or [], parameters.get("data_set") or [])
        return userdata.datadoc.entries_sha256(read, inputs) != read
    except (OSError, ValueError):
        return True


def problems(entries: Sequence[Any]) -> list[str]:
    """Why the executed copies of ``entries`` (registry entries) cannot make one book.

    Names each copy that is missing, failed, not made by ``sss-locus run``, stale (its notebook,
    the code, ``data/`` or the environment changed since it ran), whose figures or tables are
    missing or from another run, or that was computed from another profile than the rest.
    """
    found: list[str] = []
    profiles: dict[str, str] = {}
    figures = _manifests_of(paths.figures_dir(), None)
    for entry in entries:
        path = entry.executed_path()
        name = f"{entry.name} ({path})"
        if not path.is_file():
            found.append(f"{name}: missing (never run)")
            continue
        nb = read_notebook(path)
        if nb is None:
            found.append(f"{name}: not a readable notebook")
            continue
        error = notebook_error(nb)
        if nb["metadata"].get("papermill", {}).get("exception") or error:
            found.append(f"{name}: failed" + (f" in {error[0]}" if error else ""))
            continue
        ours = nb["metadata"].get("sss_locus")
        if not isinstance(ours, dict) or "run_key" not in ours:
            found.append(f"{name}: not made by `sss-locus run` (no run record)")
            continue
        profiles[entry.name] = ours.get("profile", "?")
        try:
            current = run_key(entry, ours.get("profile", ""), ours.get("parameters", {}))
        except (OSError, ValueError):
            current = None
        if current != ours["run_key"] or data_read_changed(ours):
            found.append(f"{name}: stale (the notebook, code, data/, its --data files or environment.lock changed since it ran)")
            continue
        mine = {label: m for label, m in figures.items() if m.get("notebook") == entry.source_relative}
        absent = [label for label in ours.get("figures", []) if label not in mine]
        other = [label for label, m in mine.items() if m.get("run_key") != ours["run_key"]]
        if absent:
            found.append(f"{name}: figure(s) or table(s) {', '.join(absent)} missing or modified")
        if other:
            found.append(f"{name}: figure(s) or table(s) {', '.join(sorted(other))} come from another run")
    if len(set(profiles.values())) > 1:
        ranked = Counter(profiles.values()).most_common()
        tie = ranked[0][1] == ranked[1][1]
        usual = ranked[0][0]
        mix = ", ".join(f"{count} with {profile!r}" for profile, count in ranked)
        for nb_name, profile in profiles.items():
            if tie or profile != usual:
                found.append(f"{nb_name}: computed with profile {profile!r}, not like the rest ({mix})")
    return found
