"""What ``sss-locus book`` shows of jupyter-book's output."""

from __future__ import annotations

import re

ANSI = re.compile(r"\x1b\[[0-9;]*m")  # terminal colour codes
#: Sphinx's per-file progress lines ("reading sources... [ 42%] executed/noise"); the 100 % one stays.
PROGRESS = re.compile(r"^[a-z][a-z ]+\.\.\. \[\s*(\d+)%\]")


class StagingPathFilter:
    """Drops jupyter-book's closing lines that point at its staging site
    (``<build>/jupyter-book/_build/html``, moved to ``<build>/html`` afterwards): "The HTML pages
    are in ...", and the banner "Finished generating HTML for book." with the rules around it.
    Every other line passes unchanged, in order (the build prints where the book really is).

    Sphinx's per-file progress lines are left out but for the last (100 %) of each kind; with
    ``plain`` (output that is not a terminal) the colour codes are removed from every line.

    Feed each line to :meth:`feed` and write what it returns; :meth:`flush` at the end."""

    def __init__(self, plain: bool = False) -> None:
        self.in_banner = False
        self.plain = plain
        self.pending: list[str] = []  # a rule and blank lines that may open the banner

    def feed(self, line: str) -> list[str]:
        text = ANSI.sub("", line).strip()
        if self.plain:
            line = ANSI.sub("", line)
        progress = PROGRESS.match(text)
        if progress and progress.group(1) != "100":
            return []
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
