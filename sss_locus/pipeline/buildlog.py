"""What ``sss-locus book`` shows of jupyter-book's output."""

from __future__ import annotations

import re

ANSI = re.compile(r"\x1b\[[0-9;]*m")  # terminal colour codes


class StagingPathFilter:
    """Drops jupyter-book's closing lines that point at its staging site
    (``<build>/jupyter-book/_build/html``, moved to ``<build>/html`` afterwards): "The HTML pages
    are in ...", and the banner "Finished generating HTML for book." with the rules around it.
    Every other line passes unchanged, in order (the build prints where the book really is).

    Feed each line to :meth:`feed` and write what it returns; :meth:`flush` at the end."""

    def __init__(self) -> None:
        self.in_banner = False
        self.pending: list[str] = []  # a rule and blank lines that may open the banner

    def feed(self, line: str) -> list[str]:
        text = ANSI.sub("", line).strip()
        if self.in_banner:
            if text.startswith("====="):
                self.in_banner = False
            return []
        if text == "Finished generating HTML for book.":
            self.in_banner, self.pending = True, []
            return []
        if text.startswith("=====") or (self.pending and not text):
            self.pending.append(line)
            return []
        out, self.pending = self.pending, []
        return out + ([] if text.startswith("The HTML pages are in ") else [line])

    def flush(self) -> list[str]:
        out, self.pending = self.pending, []
        return out
