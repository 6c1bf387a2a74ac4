"""The count of verdicts and the index of claims at the top of the staged claims page.

The claims page (``book/claims.md``) sets each claim of the paper in a table row whose last cell
starts with its verdict in bold: typed (``**Reproduced**``, ``**Partly**``, ``**Not
reproduced**``) or glued from a chapter's computed flags (``**{glue:text}`/executed/X.ipynb::K:s`**``,
see :mod:`sss_locus.report.survey_passes.findings`). At staging, :func:`stage_claims_index` reads every row,
resolves glued verdicts from the executed notebooks, and puts under the page's first heading

- the count of verdicts: reproduced, partly, not reproduced, and beyond the paper (rows under a
  "Beyond the paper" heading, whose claims the paper only names as future work); a row whose
  verdicts differ between the platforms ("reproduced for the boat, not for the AUV") counts as
  partly;
- a one-line index: each row numbered, linked to an anchor put into its first cell, marked by its
  verdict.

Rows of tables whose first header cell is not ``Claim (paper)`` (the open-choices table) are
not claims and are left alone.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Callable
from pathlib import Path

from sss_locus.pipeline.run import outputs
from sss_locus.pipeline.run.registry import load_registry

CLASSES = ("reproduced", "partly", "not reproduced", "beyond the paper")
"""The classes counted, in the order the summary lists them."""
MARKS = {"reproduced": "✓", "partly": "◐", "not reproduced": "✗", "beyond the paper": "+"}
"""The mark of each class in the index."""
GLUE = re.compile(r"\{glue:text\}`/executed/(?P<nb>[\w.]+)\.ipynb::(?P<key>[^`:]+)(?::[^`]*)?`")
BOLD = re.compile(r"\*\*(.+?)\*\*")
WORDS = (("not reproduced", "not reproduced"), ("reproduced", "reproduced"), ("partly", "partly"))


def glue_value(notebook: str, key: str, read: Callable[[str], dict | None] | None = None) -> str | None:
    """The text glued as ``key`` by the executed copy of ``notebook`` (``None`` if absent)."""
    nb = (read or _read_executed)(notebook)
    for cell in (nb or {}).get("cells", []):
        for out in cell.get("outputs", []):
            if (out.get("metadata", {}).get("scrapbook") or {}).get("name") == key:
                text = next(iter(out.get("data", {}).values()), None)
                try:
                    return str(ast.literal_eval(text)) if isinstance(text, str) else None
                except (ValueError, SyntaxError):
                    return text
    return None


def _read_executed(notebook: str) -> dict | None:
    entry = load_registry().get(notebook)
    return outputs.read_notebook(entry.executed_path()) if entry is not None else None


def classify(verdict_cell: str, beyond: bool, read: Callable[[str], dict | None] | None = None) -> str | None:
    """The class of one row's verdict cell (``None``: no verdict found, not counted)."""
    if beyond:
        return "beyond the paper"
    text = GLUE.sub(lambda m: glue_value(m["nb"], m["key"], read) or "", verdict_cell)
    found = []
    for bold in BOLD.findall(text):
        low = bold.strip().lower()
        hit = next((cls for word, cls in WORDS if low.startswith(word)), None)
        if hit and hit not in found:
            found.append(hit)
    if not found:
        return None
    return found[0] if len(found) == 1 else "partly"


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def claims_index(page: str, read: Callable[[str], dict | None] | None = None) -> tuple[str, str]:
    """``(page with an anchor in each claim row, markdown of the count and the index)``."""
    lines, out, rows = page.splitlines(keepends=True), [], []
    section, in_claims, header = "", False, False
    for line in lines:
        if line.startswith("## "):
            section = line[3:].strip()
        if not line.startswith("|"):
            in_claims = header = False
            out.append(line)
            continue
        if not in_claims and not header:  # a table's header row
            header, in_claims = True, _cells(line)[0] == "Claim (paper)"
            out.append(line)
            continue
        if not in_claims or set(line.strip()) <= set("|-: "):
            out.append(line)
            continue
        cls = classify(_cells(line)[-1], section.lower().startswith("beyond the paper"), read)
        if cls is None:
            out.append(line)
            continue
        rows.append((section, cls))
        anchor = f'<span id="claim-{len(rows)}"></span>'
        out.append(line.replace("| ", f"| {anchor}", 1))
    counts = {c: sum(1 for _, k in rows if k == c) for c in CLASSES}
    summary = ("**Verdicts in this build:** " + ", ".join(f"{counts[c]} {c}" for c in CLASSES)
               + f" ({len(rows)} claims; a row whose verdict differs between the platforms counts as partly).\n")
    parts, last = [], None
    for i, (sec, cls) in enumerate(rows, 1):
        head = f"<b>{sec.split(' (')[0]}</b> " if sec != last else ""
        last = sec
        parts.append(f'{head}<a href="#claim-{i}" title="{cls}">{i}&nbsp;{MARKS[cls]}</a>')
    legend = ", ".join(f"{m} {c}" for c, m in MARKS.items())
    index = f'<p class="claims-index">Claims: {" ".join(parts)} ({legend})</p>\n'
    return "".join(out), summary + "\n" + index


def stage_claims_index(page: Path, read: Callable[[str], dict | None] | None = None) -> None:
    """Put :func:`claims_index` under the first heading of the staged claims ``page`` (nothing
    if the page has no claim rows, e.g. when the claims notice replaced the table)."""
    text, block = claims_index(page.read_text(encoding="utf-8"), read)
    if "(0 claims" in block:
        return
    lines = text.splitlines(keepends=True)
    head = next((i for i, line in enumerate(lines) if line.startswith("# ")), None)
    if head is None:
        raise ValueError(f"{page} must start with a '# ' heading (the claims index goes under it)")
    page.write_text("".join([*lines[:head + 1], "\n", block, *lines[head + 1:]]), encoding="utf-8")
