"""What ``sss-locus book`` shows of jupyter-book's output."""

from __future__ import annotations

import re

ANSI = re.compile(r"\x1b\[[0-9;]*m")  # terminal colour codes


class StagingPathFilter:
    """Drops jupyter-book's closing lines that point at its staging site
    (``<build>/jupyter-book/_build/html``, moved to ``<build>/html`` afterwards): "The HTML pages
    are in ...", and the banner from "Finished generating HTML for book." to its closing rule.
    Every other line passes unchanged (the build prints where the book really is)."""

    def __init__(self) -> None:
        self.in_banner = False

    def keep(self, line: str) -> bool:
        text = ANSI.sub("", line).strip()
        if self.in_banner:
            if text.startswith("====="):
                self.in_banner = False
            return False
        if text == "Finished generating HTML for book.":
            self.in_banner = True
            return False
        return not text.startswith("The HTML pages are in ")
