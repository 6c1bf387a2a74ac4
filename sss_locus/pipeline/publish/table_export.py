"""Citable tables: a table a chapter shows, exported with the same provenance as a figure.

:func:`export_table` writes ``<label>.csv`` (the computed values), ``<label>.bib`` and the
manifest ``<label>.json`` beside the figures (``tab-`` labels): the notebook, profile,
parameters, commit, environment, run key and exactly the platforms, data entries and data files
(with SHA-256) the table was computed from (:func:`sss_locus.pipeline.publish.export.data_inputs`). A run
commits, replaces and removes its tables with its figures (:func:`sss_locus.pipeline.run.outputs.commit_run`);
the site serves them at ``figures/<label>.csv`` (``.json``, ``.bib``). In a notebook::

    publish_table(table, "tab-pose-space-choices", caption=caption, platforms=[...])
    readable_table(table, caption=caption)
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from sss_locus import paths
from sss_locus.pipeline.run import atomic, context
from sss_locus.pipeline.publish import citation, export, provenance


def export_table(frame: pd.DataFrame, label: str, *, caption: str, parameters: Mapping[str, Any],
                 notebook: str | None = None, out_dir: Path | None = None,
                 platforms: Sequence[str] | None = None, input_files: Sequence[Path] = ()) -> dict[str, Any]:
    """Export one table with its manifest and BibTeX entry; return the manifest.

    ``label``: ``tab-`` and lower-case words joined by hyphens; ``platforms``: the platforms
    the table's rows come from (default: every platform of ``parameters["platforms"]``);
    ``input_files``: a user's own input files it was computed from (recorded with their SHA-256);
    the other arguments as for :func:`sss_locus.pipeline.publish.export.export_figure`.
    """
    if not isinstance(label, str) or not export.TABLE_LABEL_PATTERN.fullmatch(label):
        raise ValueError(f"label must look like 'tab-some-name' (lower-case letters, digits, single hyphens); "
                         f"got {label!r}")
    if not isinstance(frame, pd.DataFrame):
        raise ValueError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    if not isinstance(caption, str) or not caption.strip():
        raise ValueError("caption must be a non-empty string")
    params = json.loads(json.dumps(dict(parameters), default=provenance.json_default))
    out = export.default_out_dir() if out_dir is None else Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    manifest_path = out / f"{label}.json"
    manifest_path.unlink(missing_ok=True)  # incomplete until the new manifest is written
    csv = out / f"{label}.csv"
    tmp = atomic.temp_name(csv)
    try:
        frame.to_csv(tmp, index=not isinstance(frame.index, pd.RangeIndex))
        os.replace(tmp, csv)
    finally:
        tmp.unlink(missing_ok=True)
    manifest: dict[str, Any] = {
        "label": label, "kind": "table", "caption": caption.strip(),
        "notebook": notebook or context.current().notebook, "profile": context.current().profile,
        "parameters": params, "seed": params.get("seed"), "git_commit": provenance.git_commit(),
        "lock_sha256": provenance.lock_sha256(), "package_version": provenance.package_version(),
        "run_time_utc": provenance.utc_now(), "run_key": context.current().run_key,
        "build_area": paths.build_name(),
        "data_inputs": export.with_files(export.data_inputs(params, platforms), input_files),
    }
    bib = out / f"{label}.bib"
    atomic.write_atomic(bib, citation.figure_bibtex(manifest))
    manifest["files"] = {p.name: {"url": f"{paths.FIGURES_SUBDIR}/{p.name}", "sha256": provenance.file_sha256(p)}
                         for p in (csv, bib)}
    atomic.write_atomic(manifest_path, json.dumps(manifest, indent=2, sort_keys=True) + "\n")
    return manifest
