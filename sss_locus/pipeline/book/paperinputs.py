"""Where a run's inputs differ from the paper's, said wherever the book shows text written for them.

The chapters' figures, captions, tables and glued numbers follow the run for any platform. Their
prose cannot always: a paragraph that compares the AUV with the boat is written for the paper's
platforms (each notebook's default ``platforms`` parameter) with the shipped ``data/``. Such a
markdown cell carries the cell tag :data:`PROSE_TAG` (chapters whose verdicts are generated for
any platform by their findings functions have none: CONTRIBUTING.md, "One source per
sentence"). When a run's inputs differ from the paper's for that notebook — a default platform not selected, or a value one of them reads changed by
``--data``/``--set`` — the runner replaces the tagged cells of the executed copy by one note per
block of consecutive tagged cells saying why (:func:`adapt_prose`), and records the comparison in
the copy's metadata (``sss_locus.paper_inputs``, :func:`compare`).

The claims page quotes the chapters' numbers beside verdicts written for the paper's inputs. At
every build, :func:`claims_notice` turns the recorded comparisons into a notice that
:mod:`sss_locus.pipeline.book.bookbuild` puts at the top of the staged page; when a paper platform is
missing from a chapter the page's table cannot be built at all and the notice replaces it.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

#: Cell tag of a markdown cell written for the paper's platforms with the shipped data.
PROSE_TAG = "paper-inputs"
#: Data tables not keyed by platform that only some chapters read (their changes count for those).
SHARED_TABLES = ("terrain", "survey")


def compare(entry: Any, parameters: Mapping[str, Any],
            reads: Sequence[str] = ()) -> dict[str, list[str]] | None:
    """How a run of ``entry`` (a registry entry) with ``parameters`` differs from the paper's inputs.

    Returns ``None`` for a notebook without a ``platforms`` parameter, else a dict with
    ``paper`` (the default platforms), ``missing`` (default platforms not selected), ``changed``
    (data entries they read that the run's data files and overrides change, see
    :func:`sss_locus.experiments.datamodel.userdata.changed_from_shipped`; of the tables every platform
    shares, such as ``terrain``, only those in ``reads``, the entries the run's loaders read)
    and ``added`` (selected platforms the defaults do not have).
    """
    from sss_locus.experiments.datamodel import userdata

    declared = entry.parameters()
    if "platforms" not in declared:
        return None
    paper = list(declared["platforms"].default)
    used = list(parameters.get("platforms", paper))
    inputs = userdata.make_inputs(parameters.get("data_files") or [], parameters.get("data_set") or [])
    return {"paper": paper, "missing": [k for k in paper if k not in used],
            "changed": userdata.changed_from_shipped([k for k in paper if k in used], inputs,
                                                     [t for t in SHARED_TABLES if t in reads]),
            "added": [k for k in used if k not in paper]}


def is_paper(record: Mapping[str, Any] | None) -> bool:
    """True for a run on the paper's inputs (or a notebook that takes no platforms)."""
    return not record or not (record.get("missing") or record.get("changed"))


def _names(keys: Sequence[str]) -> str:
    from sss_locus.experiments.datamodel.datadoc import shipped_document

    shipped = shipped_document().get("platforms", {})
    return "; ".join(f"{shipped[k]['name']} (`{k}`)" if k in shipped else f"`{k}`" for k in keys)


def _reasons(record: Mapping[str, Any]) -> str:
    out = []
    if record.get("missing"):
        out.append("does not include " + ", ".join(f"`{k}`" for k in record["missing"]))
    if record.get("changed"):
        out.append("changes " + ", ".join(f"`{c}`" for c in record["changed"]))
    return " and ".join(out)


def prose_note(record: Mapping[str, Any]) -> str:
    """The note that stands in for prose written for the paper's inputs (MyST), once a chapter."""
    return ("```{note}\nThe passages written for the paper's platforms with the shipped data — "
            f"{_names(record['paper'])} — are left out here: this run {_reasons(record)}. The figures, "
            "captions and tables of this chapter show the values this run used, and its findings outside "
            "those passages are generated from this run's numbers.\n```\n")


def _tags(cell: Mapping[str, Any]) -> list[str]:
    return cell.get("metadata", {}).get("tags", []) if cell["cell_type"] == "markdown" else []


def adapt_prose(notebook: Path, record: Mapping[str, Any] | None) -> int:
    """Fit an executed ``notebook``'s prose to its run's inputs (``record`` from :func:`compare`).

    When the inputs are not the paper's the :data:`PROSE_TAG` cells go: each block of
    consecutive tagged cells keeps only the leading headings of its first cell, and the first
    block of the chapter is followed by :func:`prose_note` (one note a chapter). Returns the
    number of cells replaced or dropped."""
    if is_paper(record):
        return 0
    nb = json.loads(notebook.read_text(encoding="utf-8"))
    cells, changed, previous_tagged, noted = [], 0, False, False
    for cell in nb["cells"]:
        tagged = PROSE_TAG in _tags(cell)
        if tagged:
            changed += 1
            if not previous_tagged:  # keep the block's leading headings; the note once a chapter
                lines = "".join(cell["source"]).splitlines(keepends=True)
                n = next((i for i, line in enumerate(lines) if not line.startswith("#")), len(lines))
                heads = "".join(lines[:n]) + ("\n" if n and not noted else "")
                if heads or not noted:
                    cells.append({**cell, "source": heads + ("" if noted else prose_note(record))})
                noted = True
        else:
            cells.append(cell)
        previous_tagged = tagged
    if changed:
        nb["cells"] = cells
        notebook.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return changed


def claims_notice(records: Mapping[str, Mapping[str, Any] | None]) -> tuple[str, bool]:
    """The notice for the top of the claims page, from each chapter's recorded comparison.

    ``records`` maps a notebook name to its ``sss_locus.paper_inputs`` record (``None`` when it
    takes no platforms). Returns ``(markdown, replace_table)``: empty markdown when every chapter
    ran on the paper's inputs (platforms added beside the paper's are noted only), and
    ``replace_table`` True when a paper platform is missing from a chapter, whose numbers the
    page's table then cannot show.
    """
    off = {name: r for name, r in records.items() if not is_paper(r)}
    paper_keys = {k for r in records.values() if r for k in r.get("paper", [])}  # any chapter's paper platform
    added = sorted({k for r in records.values() if r for k in r.get("added", []) if k not in paper_keys})
    if not off:
        if not added:
            return "", False
        return ("```{note}\nThis build also ran the platform(s) " + ", ".join(f"`{k}`" for k in added)
                + ". The claims below are about the paper's platforms only and quote their numbers; "
                "the chapters show the added platforms beside them.\n```\n"), False
    missing = any(r.get("missing") for r in off.values())
    lines = "\n".join(f"- {{doc}}`/executed/{name}`: this run {_reasons(r)}." for name, r in off.items())
    what = ("The table of claims is therefore not shown: its numbers are those of the paper's platforms, "
            "which these chapters did not compute." if missing else
            "The numbers below are this build's; the verdicts beside them were written for the paper's "
            "inputs and **do not necessarily apply** to these numbers.")
    return ("```{warning}\n**This build does not use the paper's inputs.** The verdicts on this page "
            "were written for the paper's platforms with the shipped data "
            f"({_names(list(dict.fromkeys(k for r in off.values() for k in r['paper'])))}), but\n\n{lines}\n\n{what} Rebuild without "
            "`--data`, `--set` and `-p platforms` to check the paper's claims.\n```\n"), missing
