"""Throwaway notebooks for the pipeline tests (imported like ``reference_locus``)."""

from __future__ import annotations

from pathlib import Path

import nbformat


def write_notebook(path: Path, parameters: str, body: str, markdown: str | None = None) -> Path:
    """Write a notebook with an optional markdown cell, a ``parameters``-tagged cell and a body
    cell, on the ``python3`` kernel; return ``path``."""
    nb = nbformat.v4.new_notebook()
    nb.cells = ([nbformat.v4.new_markdown_cell(markdown)] if markdown else []) + [
        nbformat.v4.new_code_cell(parameters, metadata={"tags": ["parameters"]}),
        nbformat.v4.new_code_cell(body),
    ]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, path)
    return path
