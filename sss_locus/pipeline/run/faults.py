"""What a run that failed outside its cells says, and what it keeps.

* :func:`papermill_failure` turns the log of a papermill child that stopped without a failing
  cell into one line: "no space left" with the free space when the disk filled up (the log
  itself may then be cut off mid-line), else the log's last error line.
* :func:`keep_failed_notebook` keeps a failed run's notebook for reading only when it is a
  whole notebook (a full disk leaves truncated JSON, which is deleted instead).
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

from sss_locus.pipeline.run.transaction import SPACE_MARGIN_BYTES, free_bytes

_ERROR_LINE = re.compile(r"^(?:[\w.]+\.)?\w*(?:Error|Exception|Exit|Interrupt)\b:? ?.*$")
_NO_SPACE = ("No space left on device", "[Errno 28]", "ENOSPC")


def no_space(folder: Path) -> str:
    """The one-line reason of a full disk, with the free space of ``folder``."""
    return (f"no space left on the device of {folder} ({free_bytes(folder) / 1e6:.1f} MB free); "
            "free some space and run again")


def papermill_failure(log: str, folder: Path) -> str:
    """One line saying why papermill stopped without a failing cell (see the module docstring)."""
    if any(mark in log for mark in _NO_SPACE) or free_bytes(folder) < SPACE_MARGIN_BYTES:
        return no_space(folder)
    lines = [line.strip() for line in log.strip().splitlines() if line.strip()]
    errors = [line for line in lines if _ERROR_LINE.match(line)]
    return (errors or lines or ["papermill stopped without a message"])[-1][:300]


def keep_failed_notebook(staged: Path, kept: Path) -> Path | None:
    """Move a failed run's notebook ``staged`` to ``kept`` if it is a whole notebook; else delete
    it. Returns where it was kept, or None."""
    try:
        json.loads(staged.read_text(encoding="utf-8"))
        kept.parent.mkdir(parents=True, exist_ok=True)
        os.replace(staged, kept)
    except (OSError, ValueError):
        staged.unlink(missing_ok=True)
        return None
    return kept
