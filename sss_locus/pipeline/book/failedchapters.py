"""A named book still builds when a chapter failed: the chapter's page says it failed and why.

The reproduction (``_build/``) never builds with a failed chapter (:func:`sss_locus.pipeline.
bookbuild.check_executed` refuses it). A user's named build area (``--name``) does: each chapter
whose executed copy is missing or failed (:func:`failed_chapters`) is replaced in the staged
source by a page of its own (:func:`stage_stubs`) — the chapter's title, the failing cell and
error line, the traceback of the kept notebook (``<build>/failed/<name>.ipynb``) and the command
that reruns it — while its last good executed copy, if any, stays untouched beside it and out of
the book (``exclude_patterns``). Its figures and tables are left out of the figure index and the
citation blocks (:func:`without_chapters`).
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.run import outputs

#: Suffix of the stand-in page of a failed chapter in the staged ``executed/`` folder.
STUB_SUFFIX = ".md"


def failed_chapters(entries: Sequence[Any]) -> dict[str, str]:
    """``{name: problem}`` of the registry ``entries`` whose executed copy failed, or is missing
    because its run failed (its notebook kept in ``<build>/failed/``); a chapter never run is not
    one of them (the book refuses it)."""
    found = {}
    for entry in entries:
        problem = outputs.problems([entry])
        kept = (paths.build_dir() / "failed" / f"{entry.name}.ipynb").is_file()
        if problem and any(": failed" in p for p in problem):
            found[entry.name] = problem[0]
        elif problem and kept and any(p.endswith("missing (never run)") for p in problem):
            found[entry.name] = f"{entry.name}: failed (its notebook is kept in failed/{entry.name}.ipynb)"
    return found


def _title(entry: Any) -> str:
    try:
        nb = json.loads(entry.source.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return entry.name
    for cell in nb.get("cells", []):
        for line in "".join(cell.get("source", "")).splitlines():
            if cell.get("cell_type") == "markdown" and line.startswith("# "):
                return line[2:].strip()
    return entry.name


def stub_page(entry: Any, problem: str) -> str:
    """The page standing in for the failed chapter ``entry`` (MyST): title, error, traceback."""
    kept = paths.build_dir() / "failed" / f"{entry.name}.ipynb"
    nb = outputs.read_notebook(kept) if kept.is_file() else None
    error = outputs.notebook_error(nb) if nb else None
    summary = error[0] if error else problem.split(": ", 1)[-1]
    area = paths.build_name()
    rerun = f"sss-locus run {entry.name} --name {area}" if area else f"sss-locus run {entry.name}"
    text = (f"# {_title(entry)}\n\n```{{error}}\n**This chapter failed in this build** "
            f"(build area `{area or 'reproduction'}`): {summary}. Its figures and tables are not in this "
            f"book, and other pages that quote its numbers show them as missing. The notebook as far as it "
            f"ran is kept as `failed/{entry.name}.ipynb` in the build area; rerun it with `{rerun}` and this "
            "build's `--data`/`--set`/`-p` options (`--verbose` prints the traceback).\n```\n")
    if error and error[1].strip():
        text += "\nThe error's traceback:\n\n```text\n" + error[1].strip() + "\n```\n"
    return text


def stage_stubs(root: Path, failed: Mapping[str, str], entries: Mapping[str, Any]) -> list[str]:
    """Write the stand-in page of each ``failed`` chapter into the staged source ``root`` (and
    remove those of earlier builds); return the patterns of the executed copies to exclude."""
    for old in (root / paths.EXECUTED_SUBDIR).glob(f"*{STUB_SUFFIX}"):
        old.unlink()
    excluded = []
    for name, problem in failed.items():
        entry = entries[name]
        executed = entry.executed_path()
        executed.parent.mkdir(parents=True, exist_ok=True)
        executed.with_suffix(STUB_SUFFIX).write_text(stub_page(entry, problem), encoding="utf-8")
        excluded.append(executed.relative_to(root).as_posix())
    return excluded


def without_chapters(manifests: Sequence[dict[str, Any]], failed: Mapping[str, str],
                     entries: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The ``manifests`` not made by a ``failed`` chapter (an earlier run's figures of it)."""
    sources = {entries[name].source_relative for name in failed}
    return [m for m in manifests if m.get("notebook") not in sources]
