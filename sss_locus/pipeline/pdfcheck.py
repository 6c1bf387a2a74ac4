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
  each have at least :data:`MIN_INK` of their pixels inked.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
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
    """The page titles, the figure images and the code text of the printed single page.

    A page title is the first heading of the first section of the article (the root page) and of
    each section that follows a ``<span id="document-...">`` (where the ``singlehtml`` builder
    starts each other page of the book).
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

    def handle_data(self, data: str) -> None:
        if self._title is not None and not self._skip_depth:
            self._title.append(data)
        if self._code_depth:
            self.code.append(data)


def printed_page(html: Path) -> tuple[list[str], list[str], str]:
    """The page titles (in order), the sources of the figure images and the text of the code
    blocks (``<pre>``, ``<code>``) of a printed single page (or of one page of the site)."""
    parser = _PrintedPage()
    parser.feed(html.read_text(encoding="utf-8"))
    return parser.titles, parser.figure_images, "".join(parser.code)


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


def page_texts(pdf: Path) -> list[str]:
    """The text of each page (``pdftotext -layout``)."""
    pages = _run(["pdftotext", "-layout", "-enc", "UTF-8", str(pdf), "-"]).split("\f")
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
    """For each title, the (1-based) pages whose text starts with it (over at most ``head_lines``
    lines: a long title wraps). Pages of the printed contents (:func:`is_contents_page`) after the
    first are left out: the first opens the book with its title, the book's first page title."""
    heads = [None if i > 0 and is_contents_page(text, titles)
             else _norm(" ".join([line for line in text.splitlines() if line.strip()][:head_lines]))
             for i, text in enumerate(texts)]
    return {t: [i + 1 for i, head in enumerate(heads) if head is not None and head.startswith(_norm(t))]
            for t in titles}


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
