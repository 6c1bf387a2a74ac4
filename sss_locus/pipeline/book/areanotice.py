"""A named build area's book says what it was built from: on its front page and atop every page.

The reproduction (``_build/``) is the paper's book. A user's book (``sss-locus book --name NAME``)
has the same title, introduction and chapters, so without a word on it a reader could not tell
the two apart. :func:`area_summary` reads, from the executed copies, the build area's name, the
profile(s), the platforms and the data it was computed from (each user file by its name and
SHA-256, :func:`sss_locus.paths.public_path`); :func:`front_notice` is the admonition put under
the front page's title and :func:`announcement` the line shown at the top of every page
(``html.announcement``), chapters included. :func:`stage` applies both to a staged source.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from html import escape
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.run import outputs


def area_summary(entries: Sequence[Any]) -> dict[str, Any]:
    """What the executed copies of ``entries`` (registry entries) of the current build area were
    computed from: ``name``, ``profiles``, ``platforms``, ``files`` (``{public name: sha256}`` of
    the user's data files and of observations, truth and area files other than the shipped worked
    examples), ``overrides`` (``--set``) and ``chapters``
    (the number with an executed copy)."""
    profiles, platforms, files, overrides, chapters = [], [], {}, [], 0
    for entry in entries:
        nb = outputs.read_notebook(entry.executed_path()) if entry.executed_path().is_file() else None
        ours = ((nb or {}).get("metadata") or {}).get("sss_locus") or {}
        if not ours:
            continue
        chapters += 1
        profiles.append(ours.get("profile", "?"))
        params = ours.get("parameters") or {}
        platforms += [k for k in params.get("platforms", []) if isinstance(k, str)]
        for f in (ours.get("data") or {}).get("files", []):
            if f.get("role") != "shipped":
                files[paths.public_path(f["path"])] = f["sha256"]
        overrides += list((ours.get("data") or {}).get("overrides", []))
        declared = entry.parameters()
        for name in ("observations", "truth", "area"):  # a user's own file, not the shipped worked example
            value, default = params.get(name), getattr(declared.get(name), "default", None)
            full = paths.REPO_ROOT / str(value)
            if isinstance(value, str) and value and full.is_file() and (
                    default is None or paths.public_path(full) != paths.public_path(paths.REPO_ROOT / str(default))):
                from sss_locus.pipeline.publish.provenance import file_sha256

                files.setdefault(paths.public_path(full), file_sha256(full))
    return {"name": paths.build_name(), "profiles": list(dict.fromkeys(profiles)),
            "platforms": list(dict.fromkeys(platforms)), "files": files,
            "overrides": list(dict.fromkeys(overrides)), "chapters": chapters}


def _data_words(summary: Mapping[str, Any]) -> str:
    files = [f"`{name}` (SHA-256 `{sha[:12]}…`)" for name, sha in summary["files"].items()]
    files += [f"`--set {o}`" for o in summary["overrides"]]
    return ("the shipped `data/` with " + ", ".join(files)) if files else "the shipped `data/` only"


def front_notice(summary: Mapping[str, Any]) -> str:
    """The admonition under the front page's title of a named build (MyST)."""
    platforms = ", ".join(f"`{k}`" for k in summary["platforms"]) or "none"
    profiles = ", ".join(f"`{p}`" for p in summary["profiles"]) or "none"
    return ("```{important}\n**This is not the paper's reproduction: it is the build area "
            f"`{summary['name']}`**, built with the profile {profiles} for the platforms {platforms} from "
            f"{_data_words(summary)}. Its figures, tables and findings are computed from these inputs; "
            f"their BibTeX keys carry the area's name (`sss-locus:{summary['name']}:<label>`), and so is "
            "every chapter's text. The claims page says whether its verdicts, written for the paper's "
            "inputs, apply.\n```\n")


def announcement(summary: Mapping[str, Any]) -> str:
    """The one line atop every page of a named build (HTML text)."""
    data = ", ".join(f"{name} (sha256 {sha[:12]})" for name, sha in summary["files"].items()) or "shipped data/"
    return escape(f"Build area '{summary['name']}' — profile {', '.join(summary['profiles']) or '?'}, platforms "
                  f"{', '.join(summary['platforms']) or 'none'}, data: {data}. Not the paper's reproduction.")


def stage(root: Path, front_page: Path, config: dict[str, Any]) -> None:
    """In a named build area, put :func:`front_notice` under the first heading of the staged
    ``front_page`` and :func:`announcement` into ``config`` (the staged ``_config.yml`` as a
    dict, changed in place; the title names the area too). A no-op in the reproduction."""
    if paths.build_name() is None:
        return
    from sss_locus.pipeline.run.registry import load_registry

    summary = area_summary(list(load_registry().values()))
    config.setdefault("html", {})["announcement"] = announcement(summary)
    config["title"] = f"{config.get('title', 'sss-locus')} — build area {summary['name']}"
    lines = front_page.read_text(encoding="utf-8").splitlines(keepends=True)
    head = next((i for i, line in enumerate(lines) if line.startswith("# ")), -1)
    front_page.write_text("".join([*lines[:head + 1], "\n", front_notice(summary), *lines[head + 1:]]),
                          encoding="utf-8")
