"""The visible parameters cell of an executed notebook shows the run's values, not the defaults.

Papermill runs a notebook by adding an injected-parameters cell after the cell tagged
``parameters``; the original cell, with the notebook's defaults, stays and is what a reader of
the book sees first. After a run with other values (``--profile``, ``-p``, ``--data``) that cell
would show values the run did not use. :func:`show_run_values` rewrites each assignment of the
original cell whose name the run set, keeping its comment (meaning and allowed range) and
column, and heads the cell with a line saying so; the injected cell stays in the notebook, as
the record papermill made.

:func:`parameters_cell` renders a chapter's ``Params`` model as that cell, and
``python -m sss_locus.pipeline.run.paramcell --write`` rewrites every notebook's cell from its
model (without ``--write``: lists the notebooks whose cell differs).
"""

from __future__ import annotations

import ast
import json
from collections.abc import Mapping
from typing import Any

from sss_locus.pipeline.run.params import NotebookParams, allowed

PARAMETERS_TAG = "parameters"


def literal(value: Any) -> str:
    """``value`` as Python source in the notebooks' style (double-quoted strings, ``_`` in
    large integers).

    >>> literal(["auv", "boat"]), literal(600000), literal(0.25), literal(True), literal({"a": [1, 2.5]})
    ('["auv", "boat"]', '600_000', '0.25', 'True', '{"a": [1, 2.5]}')
    """
    if isinstance(value, bool) or value is None:
        return repr(value)
    if isinstance(value, int):
        return f"{value:_}" if abs(value) >= 10_000 else str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(literal(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{literal(str(k))}: {literal(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"parameter value of type {type(value).__name__} has no literal form: {value!r}")


def with_values(source: str, values: Mapping[str, Any]) -> str:
    """``source`` (a parameters cell) with the value of every single-line assignment (annotated or
    not) to a name
    in ``values`` replaced by that value, its comment kept at its column when the value fits."""
    lines = source.splitlines(keepends=True)
    for node in ast.parse(source).body:
        target = (node.targets[0] if isinstance(node, ast.Assign) and len(node.targets) == 1 else
                  node.target if isinstance(node, ast.AnnAssign) and node.value is not None else None)
        if not (isinstance(target, ast.Name) and target.id in values and node.lineno == node.end_lineno):
            continue
        i, value = node.lineno - 1, node.value
        line = lines[i]
        body, end = line.rstrip("\n"), line[len(line.rstrip("\n")):]
        head, tail = body[:value.col_offset], body[value.end_col_offset:]
        new = head + literal(values[target.id])
        rest = tail.lstrip()
        if rest:  # the comment at its column, or two spaces after a longer value
            column = len(body) - len(rest)
            new = (new.ljust(column) if len(new) + 2 <= column else new + "  ") + rest
        lines[i] = new + end
    return "".join(lines)


def show_run_values(cells: list[dict], values: Mapping[str, Any], header: str) -> bool:
    """Rewrite the first cell tagged ``parameters`` of ``cells`` with the run's ``values``
    (:func:`with_values`) under the comment line ``header``; True if there was one."""
    for cell in cells:
        if cell.get("cell_type") == "code" and PARAMETERS_TAG in cell.get("metadata", {}).get("tags", []):
            source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
            if source.startswith(header):
                return True
            cell["source"] = header.rstrip("\n") + "\n" + with_values(source, values)
            return True
    return False


def parameters_cell(model: type[NotebookParams]) -> str:
    """The notebook's ``parameters`` cell: one ``name = default  # description rule`` line per
    field, in the model's order (what papermill inspects and injects after; defaults written by
    :func:`sss_locus.pipeline.run.paramcell.literal`)."""
    heads = [f"{name} = {literal(field.default)}" for name, field in model.model_fields.items()]
    column = max((len(h) for h in heads if len(h) <= 40), default=0) + 2
    lines = []
    for head, field in zip(heads, model.model_fields.values()):
        comment = " ".join(x for x in (field.description or "", allowed(field, static=True)) if x)
        lines.append(f"{head.ljust(column) if len(head) + 2 <= column else head + '  '}# {comment}" if comment else head)
    return "\n".join(lines)


def write_cells(check: bool = False) -> list[str]:
    """Rewrite (or with ``check`` only list) every registered notebook whose ``parameters`` cell
    differs from :func:`parameters_cell` of its model; returns the notebooks' names. Only that
    cell changes; the file keeps its JSON style (indent 1, and ``ensure_ascii`` where it is set)."""
    from sss_locus.pipeline.run.registry import load_registry, params_model

    changed = []
    for name, entry in load_registry().items():
        model = params_model(name)
        if model is None:
            continue
        text = entry.source.read_text(encoding="utf-8")
        nb = json.loads(text)
        cell = next(c for c in nb["cells"] if "parameters" in c.get("metadata", {}).get("tags", []))
        source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        wanted = parameters_cell(model)
        if source == wanted:
            continue
        changed.append(name)
        if not check:
            cell["source"] = wanted.splitlines(keepends=True)
            ascii_only = text.isascii()
            entry.source.write_text(json.dumps(nb, indent=1, ensure_ascii=ascii_only) + "\n", encoding="utf-8")
    return changed


if __name__ == "__main__":
    import sys

    from sss_locus.pipeline.run import paramcell  # the module itself, not this __main__ copy

    stale = paramcell.write_cells(check="--write" not in sys.argv)
    print(("rewrote " if "--write" in sys.argv else "differ from their model: ") + (", ".join(stale) or "none"))
