"""Studies a run skips because no platform of it has what they need, said on the chapter's page.

A chapter's study that needs a capability (a platform that pitches, say) is skipped, never run on
a platform that lacks it. Its code cells run nothing then, and one of them glues the reason under
the key ``skipped-study:<study>`` (:data:`GLUE_PREFIX`). The study's cells carry the cell tag
``study:<study>`` (:data:`TAG_PREFIX`). After the run, :func:`drop_skipped` keeps the leading
headings of the study's first tagged markdown cell with a note saying why it was skipped, and
removes its other tagged cells (whose glue references point at numbers never computed).
"""

from __future__ import annotations

import ast
import json
from pathlib import Path
from typing import Any

#: Glue key prefix of a skipped study's reason (``skipped-study:<study>``).
GLUE_PREFIX = "skipped-study:"
#: Cell tag prefix of a study's cells (``study:<study>``).
TAG_PREFIX = "study:"


def skipped(nb: dict[str, Any]) -> dict[str, str]:
    """``{study: reason}`` of the studies an executed notebook ``nb`` glued as skipped."""
    found = {}
    for cell in nb.get("cells", []):
        for out in cell.get("outputs", []):
            name = (out.get("metadata", {}).get("scrapbook") or {}).get("name", "")
            if name.startswith(GLUE_PREFIX):
                text = next(iter(out.get("data", {}).values()), "")
                try:
                    text = str(ast.literal_eval(text))
                except (ValueError, SyntaxError):
                    pass
                found[name[len(GLUE_PREFIX):]] = text
    return found


def drop_skipped(notebook: Path) -> list[str]:
    """Replace the cells of each skipped study of the executed ``notebook`` by one note; return
    the skipped studies' names (empty, file untouched, when none was skipped)."""
    nb = json.loads(notebook.read_text(encoding="utf-8"))
    reasons = skipped(nb)
    if not reasons:
        return []
    cells, noted = [], set()
    for cell in nb["cells"]:
        tags = cell.get("metadata", {}).get("tags", [])
        study = next((t[len(TAG_PREFIX):] for t in tags if t.startswith(TAG_PREFIX)
                      and t[len(TAG_PREFIX):] in reasons), None)
        if study is None:
            cells.append(cell)
        elif cell["cell_type"] == "markdown" and study not in noted:
            noted.add(study)
            lines = "".join(cell["source"]).splitlines(keepends=True)
            n = next((i for i, line in enumerate(lines) if not line.startswith("#")), len(lines))
            note = f"```{{note}}\n{reasons[study]}\n```\n"
            cells.append({**cell, "metadata": {**cell.get("metadata", {}), "tags": [
                t for t in tags if not t.startswith(TAG_PREFIX)]}, "source": "".join(lines[:n]) + "\n" + note})
    nb["cells"] = cells
    notebook.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return sorted(reasons)
