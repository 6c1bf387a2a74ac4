"""The book's index of every published figure and table, generated from their manifests.

:func:`figures_index` writes the Markdown (MyST) that replaces the marker of the figures page:
the figures first, then the tables, each in book order (:func:`in_book_order`), each with its
caption, its files at their stable addresses, the parameters, seed, commit and data it was
computed from, and its BibTeX entry.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.publish import provenance


def _file_links(manifest: dict[str, Any]) -> str:
    names = sorted(manifest["files"])
    kinds = {".png": "PNG", ".svg": "SVG", ".pdf": "PDF", ".bib": "BibTeX"}
    links = []
    for name in names:
        suffix = Path(name).suffix
        text = kinds.get(suffix) or ("data " + name.removeprefix(manifest["label"]).strip("-.") if suffix == ".csv" else name)
        links.append(f'<a href="../{manifest["files"][name]["url"]}">{text}</a>')
    links.append(f'<a href="../{paths.FIGURES_SUBDIR}/{manifest["label"]}.json">manifest (JSON)</a>')
    return " · ".join(links)


def _data_line(manifest: dict[str, Any]) -> str:
    """The data files (with SHA-256), overrides and platform values a figure was computed from."""
    inputs = manifest.get("data_inputs") or {}
    files = ", ".join(f"`{Path(f['path']).name if f.get('role') == 'user' else f['path']}` "
                      f"({f.get('role')}, sha256 `{f['sha256'][:12]}`)" for f in inputs.get("files", []))
    sets = "".join(f"; override `{o}`" for o in inputs.get("overrides", []))
    values = "".join(
        f"; {v['name']}: {v['sonar']['name']}, {v['sonar']['azimuth_deg']:g}° × "
        f"{v['sonar']['elevation_deg']:g}°, {v['sonar']['max_range_m']:g} m, tilt "
        + "/".join(f"{t:g}" for t in dict.fromkeys(v["tilt_deg"].values())) + "°"
        for v in (inputs.get("values") or {}).values())
    return (files or "not recorded") + sets + values + "."


def _is_table(manifest: dict[str, Any]) -> bool:
    return manifest.get("kind") == "table" or manifest["label"].startswith("tab-")


def _entry(m: dict[str, Any]) -> list[str]:
    """One figure's or table's section of the index."""
    label = m["label"]
    params = ", ".join(f"`{k} = {json.dumps(v)}`" for k, v in sorted(m["parameters"].items())) or "none"
    if _is_table(m):
        where = [f"A table of the notebook `{m['notebook']}` (profile `{m['profile']}`).", "", m["caption"]]
    else:
        where = [f"{{numref}}`Figure %s <{label}>` in the notebook `{m['notebook']}` (profile `{m['profile']}`).",
                 "", m["caption"], "",
                 f'<a href="../{paths.FIGURES_SUBDIR}/{label}.png"><img src="../{paths.FIGURES_SUBDIR}/{label}.png" '
                 f'alt="{label}" style="max-width: 28em; width: 100%;"></a>']
    return [
        f"### `{label}`",
        "",
        *where,
        "",
        f"<p>{_file_links(m)}</p>",
        "",
        f"Parameters: {params}; {_seed_text(m['seed'])}; commit `{provenance.short_commit(m['git_commit'])}`; "
        f"sss-locus {m['package_version']}; "
        + (f"environment.lock `{m['lock_sha256'][:12]}`; " if m["lock_sha256"] != "missing"
           else "no environment.lock; ") +
        f"run {m['run_time_utc']}.",
        "",
        f"Data: {_data_line(m)}",
        "",
        f"Cite this {'table' if _is_table(m) else 'figure'}:",
        "",
        "```bibtex",
        (paths.figures_dir() / f"{label}.bib").read_text(encoding="utf-8").rstrip(),
        "```",
        "",
    ]


def figures_index(manifests: list[dict[str, Any]]) -> str:
    """Markdown (MyST) listing every exported figure, then every published table, with its files,
    provenance and BibTeX (``manifests`` in the order to list them, :func:`in_book_order`)."""
    figures = [m for m in manifests if not _is_table(m)]
    tables = [m for m in manifests if _is_table(m)]
    out = ["## Figures", ""]
    out += [line for m in figures for line in _entry(m)] if figures else ["No figures have been exported yet.", ""]
    out += ["## Tables", ""]
    out += [line for m in tables for line in _entry(m)] if tables else ["No tables have been published yet.", ""]
    return "\n".join(out)


def _seed_text(seed) -> str:
    """The index's seed note: the seed, or that the run has none (no ``seed`` parameter: the
    notebook draws no random numbers, so the figure is the same on every run)."""
    if seed is None:
        return "no seed (deterministic: the notebook draws no random numbers)"
    return f"seed `{seed}`"


def in_book_order(manifests: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Figures and tables of registered notebooks, sorted by the notebook's place in the registry,
    then label.

    Figures exported by other runs (a plain papermill run, a notebook since removed from the
    registry) stay in the folder but are not indexed: their labels need not exist in the book.
    """
    from sss_locus.pipeline.run.registry import load_registry

    order = {entry.source_relative: i for i, entry in enumerate(load_registry().values())}
    listed = [m for m in manifests if m["notebook"] in order]
    return sorted(listed, key=lambda m: (order[m["notebook"]], m["label"]))
