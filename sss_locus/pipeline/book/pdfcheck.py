"""Checks of the whole-book PDF (``make pdf``), read with poppler's command-line tools
(Debian/Ubuntu package ``poppler-utils``: ``pdftotext``, ``pdfimages``, ``pdftoppm``).

What a printed book must show, and :func:`problems` checks:

* **one page range per chapter**: every page of the book (its title, in book order, on the
  printed single page) opens a page of the PDF of its own (the print style breaks the page before
  each), in the same order, and no title opens two pages;
* **every figure embedded**: every image of a ``<figure>`` of the printed page is embedded at its
  own size (a PNG's width and height in pixels are those of an image of the PDF);
* **math typeset**: no math delimiter (:data:`RAW_MATH`: ``\\(``, ``\\[``, ``$``) is left in the
  extracted text beyond those the page shows in code blocks (a shell prompt, a BibTeX title);
* **pages not blank**: the pages a stray page break would leave blank (the first two, the last,
  the page before each page title) and the first page with a figure, rendered by ``pdftoppm``,
  each have at least :data:`MIN_INK` of their pixels inked;
* **every table's columns printed**: the column headers of each table a page prints (outside a
  closed ``<details>``) follow one another, in order, in the text of that page's range of the
  PDF (:func:`table_problems`). A column cut off at the page's or the table's edge is not drawn,
  and its header is missing from the text.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
import unicodedata
from html import unescape
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote

TOOLS = ("pdftotext", "pdfimages", "pdftoppm")
#: Math delimiters (MathJax's and Markdown's) that typeset math never leaves in the text.
RAW_MATH = ("\\(", "\\[", "$")
HEADINGS = ("h1", "h2", "h3", "h4", "h5", "h6")
MIN_FIGURE_PX = 200  # narrower images are icons, not figures
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MIN_INK = 0.0005  # share of a rendered page's pixels darker than light grey (one line: ~0.3 %)
RENDER_DPI = 30


def missing_tools() -> list[str]:
    """The poppler tools that are not on PATH."""
    return [tool for tool in TOOLS if shutil.which(tool) is None]


def _run(cmd: list[str], timeout_s: float = 300) -> str:
    result = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout_s)
    if result.returncode != 0:
        raise RuntimeError(f"{cmd[0]} failed (exit {result.returncode}): {result.stderr[-2000:]}")
    return result.stdout


class _PrintedPage(HTMLParser):
    """The page titles, the figure images, the code text and the tables' column headers of the
    printed single page.

    A page title is the first heading of the first section of the article (the root page) and of
    each section that follows a ``<span id="document-...">`` (where the ``singlehtml`` builder
    starts each other page of the book). A table belongs to the page whose title came last; tables
    inside a closed ``<details>`` (collapsed blocks, which print closed) are left out.
    """

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.titles: list[str] = []
        self.figure_images: list[str] = []
        self.code: list[str] = []
        self._expect_section = False  # the next section starts a page of the book
        self._expect_heading = False
        self._title: list[str] | None = None
        self._heading_tag = ""
        self._figure_depth = self._skip_depth = self._code_depth = 0
        self.tables: list[tuple[int, list[str]]] = []  # (index of the page's title, column headers)
        self._closed_depth = self._head_depth = 0  # inside a closed <details>, a <thead>
        self._header: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        attr = dict(attrs)
        classes = (attr.get("class") or "").split()
        if tag == "article" and "bd-article" in classes:
            self._expect_section = True
        elif tag == "span" and (attr.get("id") or "").startswith("document-"):
            self._expect_section = True
        elif tag == "section" and self._expect_section:
            self._expect_section, self._expect_heading = False, True
        elif tag in HEADINGS and self._expect_heading:
            self._expect_heading, self._title, self._heading_tag = False, [], tag
        elif tag == "a" and "headerlink" in classes and self._title is not None:
            self._skip_depth += 1
        elif tag == "figure":
            self._figure_depth += 1
        elif tag == "img" and self._figure_depth:
            self.figure_images.append(attr.get("src") or "")
        elif tag in ("pre", "code"):
            self._code_depth += 1
        elif tag == "details":
            self._closed_depth += 1 if self._closed_depth or "open" not in attr else 0
        elif tag == "table" and not self._closed_depth:
            self.tables.append((len(self.titles) - 1, []))
        elif tag == "thead" and self.tables and not self._closed_depth:
            self._head_depth += 1
        elif tag == "th" and self._head_depth:
            self._header = []

    def handle_endtag(self, tag: str) -> None:
        if tag == self._heading_tag and self._title is not None:
            self.titles.append(" ".join("".join(self._title).split()))
            self._title = None
        elif tag == "a" and self._skip_depth:
            self._skip_depth -= 1
        elif tag == "figure" and self._figure_depth:
            self._figure_depth -= 1
        elif tag in ("pre", "code") and self._code_depth:
            self._code_depth -= 1
        elif tag == "details" and self._closed_depth:
            self._closed_depth -= 1
        elif tag == "thead" and self._head_depth:
            self._head_depth -= 1
        elif tag == "th" and self._header is not None:
            self.tables[-1][1].append(" ".join("".join(self._header).split()))
            self._header = None

    def handle_data(self, data: str) -> None:
        if self._header is not None:
            self._header.append(data)
        if self._title is not None and not self._skip_depth:
            self._title.append(data)
        if self._code_depth:
            self.code.append(data)


def printed_page(html: Path) -> tuple[list[str], list[str], str]:
    """The page titles (in order), the sources of the figure images and the text of the code
    blocks (``<pre>``, ``<code>``) of a printed single page (or of one page of the site)."""
    parser = _parsed(html)
    return parser.titles, parser.figure_images, "".join(parser.code)


def _parsed(html: Path) -> _PrintedPage:
    parser = _PrintedPage()
    parser.feed(html.read_text(encoding="utf-8"))
    return parser


def printed_tables(html: Path) -> list[tuple[str, list[str]]]:
    """``(page title, column headers)`` of every table the printed single page ``html`` shows
    (in order; a header's text with its whitespace collapsed, empty for an unnamed column)."""
    parser = _parsed(html)
    return [(parser.titles[i] if i >= 0 else "", heads) for i, heads in parser.tables]


def png_size(path: Path) -> tuple[int, int] | None:
    """``(width, height)`` of a PNG file from its header, or ``None`` (missing, not a PNG)."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or not head.startswith(PNG_SIGNATURE):
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def page_texts(pdf: Path, mode: str = "-layout") -> list[str]:
    """The text of each page: ``pdftotext -layout`` (lines as laid out on the page), or with
    ``mode="-raw"`` in the order the text is drawn (a table cell's wrapped lines one after the
    other, the cells of a row in order)."""
    if mode not in ("-layout", "-raw"):
        raise ValueError(f"mode must be '-layout' or '-raw'; got {mode!r}")
    pages = _run(["pdftotext", mode, "-enc", "UTF-8", str(pdf), "-"]).split("\f")
    return pages[:-1] if pages and not pages[-1].strip() else pages


def image_sizes(pdf: Path) -> list[tuple[int, int, int]]:
    """``(page, width, height)`` of every raster image (``pdfimages -list``; soft masks left out)."""
    rows = _run(["pdfimages", "-list", str(pdf)]).splitlines()[2:]
    out = []
    for row in rows:
        cols = row.split()
        if len(cols) > 4 and cols[2] == "image":
            out.append((int(cols[0]), int(cols[3]), int(cols[4])))
    return out


def _norm(s: str) -> str:
    return " ".join(unescape(s).replace("\u00b6", " ").split())


def is_contents_page(text: str, titles: list[str], other_share: float = 0.2) -> bool:
    """Whether a page's text is (a part of) the printed contents: little else than the page titles
    (at most ``other_share`` of its characters left once every title is taken out). The contents
    run over several pages as the book grows, and a page of them may start with a title."""
    page = _norm(text)
    rest = page
    for title in sorted((_norm(t) for t in titles), key=len, reverse=True):
        rest = rest.replace(title, " ")
    return len(_norm(rest)) <= other_share * max(len(page), 1)


def chapter_starts(texts: list[str], titles: list[str], head_lines: int = 3) -> dict[str, list[int]]:
    """For each title, the (1-based) pages whose first lines are that title, alone on them (its
    first one to ``head_lines`` lines: a long title wraps; a sentence that merely begins with a
    chapter's name, a link in the text, does not count). Pages of the printed contents
    (:func:`is_contents_page`) after the first are left out: the first opens the book with its
    title, the book's first page title."""
    heads = [None if i > 0 and is_contents_page(text, titles)
             else {_norm(" ".join(lines[:k])) for k in range(1, head_lines + 1)}
             for i, text in enumerate(texts) for lines in [[line for line in text.splitlines() if line.strip()]]]
    return {t: [i + 1 for i, head in enumerate(heads) if head is not None and _norm(t) in head]
            for t in titles}


def squeezed(text: str) -> str:
    """``text`` as compared by the table check: compatibility-normalised (NFKC: a ligature is its
    letters), without zero-width spaces and soft hyphens (break opportunities the page adds) and
    without whitespace, so a header the PDF wraps over lines (after a space or a hyphen) reads as
    in the page. Every visible character stays, in order.

    >>> squeezed("perpendicular\\nextent (m)") == squeezed("perpendicular extent (m)") == "perpendicularextent(m)"
    True
    """
    text = unicodedata.normalize("NFKC", text).replace("\u200b", "").replace("\u00ad", "")
    return "".join(text.split())


def table_problems(texts: list[str], starts: dict[str, list[int]],
                   tables: list[tuple[str, list[str]]]) -> list[str]:
    """The tables whose columns are not all in the PDF's text of their page's range.

    ``texts``: each PDF page's text in drawing order (:func:`page_texts` with ``"-raw"``);
    ``starts``: the pages each page title opens (:func:`chapter_starts`; a title that does not open
    exactly one page is reported by :func:`problems` and its tables are not looked for);
    ``tables``: :func:`printed_tables`. A page's range runs from its first page to the page before
    the next page's. Each table's headers (the unnamed ones left out) must follow one another in
    order in that text (:func:`squeezed`): the headers of a row of short words ("n", "all") are
    found only where the row is. A table whose columns are cut off at its right edge is reported
    with the headers from the first one that does not follow on.
    """
    first = sorted((pages[0], title) for title, pages in starts.items() if len(pages) == 1)
    ranges = {title: (page, first[i + 1][0] - 1 if i + 1 < len(first) else len(texts))
              for i, (page, title) in enumerate(first)}
    found = []
    for number, (title, headers) in enumerate(tables, 1):
        if title not in ranges:
            continue
        lo, hi = ranges[title]
        text = squeezed(" ".join(texts[lo - 1:hi]))
        heads = [h for h in headers if squeezed(h)]
        shown = next((k for k in range(len(heads), 0, -1) if squeezed(" ".join(heads[:k])) in text), 0)
        if shown < len(heads):
            found.append(f"table {number} ({title!r}, pages {lo}-{hi}): columns {heads[shown:]} are not in the "
                         f"PDF's text after {heads[:shown]}")
    return found


def ink_fraction(pdf: Path, page: int, dpi: int = RENDER_DPI) -> float:
    """Share of the pixels of ``page`` rendered to a greyscale PNG by ``pdftoppm`` that are darker
    than light grey (224 of 255)."""
    import numpy as np
    from PIL import Image

    with tempfile.TemporaryDirectory() as tmp:
        stem = Path(tmp) / "page"
        _run(["pdftoppm", "-png", "-gray", "-r", str(dpi), "-f", str(page), "-l", str(page),
              "-singlefile", str(pdf), str(stem)])
        pixels = np.asarray(Image.open(stem.with_suffix(".png")).convert("L"))
    return float((pixels < 224).mean())


def problems(pdf: Path, html: Path) -> list[str]:
    """What is wrong with ``pdf``, printed from the single page ``html`` (empty: nothing)."""
    titles, sources, code = printed_page(html)
    texts = page_texts(pdf)
    found: list[str] = []
    previous = 0
    starts = chapter_starts(texts, titles)
    for title, pages in starts.items():
        if len(pages) != 1:
            found.append(f"page title {title!r} opens {len(pages)} pages ({pages}), not one")
        elif pages[0] <= previous:
            found.append(f"page title {title!r} opens page {pages[0]}, not after the previous title's {previous}")
        else:
            previous = pages[0]
    figures = [(p, w, h) for p, w, h in image_sizes(pdf) if w >= MIN_FIGURE_PX]
    embedded = {(w, h) for _, w, h in figures}
    for src in sources:
        size = png_size(html.parent / unquote(src))
        if size is None:
            found.append(f"figure image {src!r} is not a PNG file beside the page")
        elif size not in embedded:
            found.append(f"figure image {src} ({size[0]} x {size[1]} px) is not embedded")
    for token in RAW_MATH:  # more than the code blocks show: math left as source
        pages = [n for n, text in enumerate(texts, 1) if token in text]
        if text_count(texts, token) > code.count(token):
            found.append(f"math left as source: {text_count(texts, token)} {token!r} in the text "
                         f"(pages {pages}), {code.count(token)} in code blocks")
    found += table_problems(page_texts(pdf, "-raw"), starts, printed_tables(html))
    # the pages a stray page break would leave blank (before each page title), and a figure's
    sample = {1, 2, len(texts), figures[0][0] if figures else 1}
    sample |= {pages[0] - 1 for pages in starts.values() if pages and pages[0] > 1}
    sample = sorted(p for p in sample if 1 <= p <= len(texts))
    for page in sample:
        ink = ink_fraction(pdf, page)
        if ink < MIN_INK:
            found.append(f"page {page} rendered blank ({ink:.2%} of its pixels inked)")
    return found


def text_count(texts: list[str], token: str) -> int:
    return sum(text.count(token) for text in texts)
