"""How a run's inputs differ from the paper's, recorded with each executed chapter and said on
the claims page.

Every chapter's prose is generated from its run's numbers for every platform of the run, the
paper's included (CONTRIBUTING.md, "One source per sentence"), so no chapter text needs to be
swapped when the inputs are not the paper's. The runner still records, in each executed copy's
metadata (``sss_locus.paper_inputs``), how the run's inputs differ from the paper's for that
notebook (:func:`compare`): a default platform not selected, a value one of them reads changed by
``--data``/``--set``, or a platform added beside them.

The claims page quotes the chapters' numbers beside verdicts written for the paper's inputs. At
every build, :func:`claims_notice` turns the recorded comparisons into a notice that
:mod:`sss_locus.pipeline.book.bookbuild` puts at the top of the staged page; when a paper platform is
missing from a chapter the page's table cannot be built at all and the notice replaces it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

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
