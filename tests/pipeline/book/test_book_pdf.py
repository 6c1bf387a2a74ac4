"""The whole book as one PDF (``make pdf``), printed from the quick book and read back: a page
range per chapter, every figure embedded, the math typeset, rendered pages that are not blank, and
every table's column headers in the text of its chapter's pages.

Needs headless Chromium and poppler-utils (``.ci/install-tools`` installs both); without them the
tests are skipped and named at the end of the run, and in CI they fail (``conftest.py``).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("jupyter_book")
yaml = pytest.importorskip("yaml")

from book_support import TIMEOUT_S  # noqa: E402
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.book import bookpdf, pdfcheck  # noqa: E402
from sss_locus.pipeline.publish.export import load_manifests  # noqa: E402
from sss_locus.pipeline.run.registry import load_registry  # noqa: E402

pytestmark = pytest.mark.book


def _needs(*, browser: bool) -> None:
    missing = pdfcheck.missing_tools()
    if browser and not any(shutil.which(name) for name in bookpdf.BROWSERS):
        missing.append("headless Chromium")
    if missing:
        pytest.skip("needs " + ", ".join(missing) + " (poppler-utils, chromium: .ci/install-tools)")


@pytest.fixture(scope="module")
def quick_pdf(quick_book):
    """``make pdf`` (``python -m sss_locus.pipeline.book.bookpdf``) on the quick book's build area:
    ``{"pdf", "html"}`` (the PDF and the single page it was printed from)."""
    _needs(browser=True)
    result = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.book.bookpdf"], env=quick_book["env"],
                            capture_output=True, text=True, timeout=TIMEOUT_S, stdin=subprocess.DEVNULL)
    if result.returncode != 0:
        pytest.fail(f"make pdf failed:\n{result.stdout[-3000:]}\n{result.stderr[-6000:]}")
    pdf = Path(result.stdout.strip().splitlines()[-1])
    assert pdf == quick_book["area"] / "pdf" / bookpdf.PDF_NAME
    return {"pdf": pdf, "html": quick_book["area"] / "singlehtml" / "_build" / "singlehtml" / "book-print.html"}


def _toc_files() -> list[str]:
    toc = yaml.safe_load(paths.TOC_FILE.read_text(encoding="utf-8"))
    return [toc["root"], *(c["file"] for part in toc["parts"] for c in part["chapters"])]


def test_pdf_has_every_page_in_order_every_figure_and_typeset_math(quick_book, quick_pdf):
    # the printed page holds every page of the book, one title each, in the table of contents' order
    titles = [pdfcheck.printed_page(quick_book["html"] / f"{file}.html")[0][0] for file in _toc_files()]
    printed_titles, printed_figures, _ = pdfcheck.printed_page(quick_pdf["html"])
    assert printed_titles == titles
    registered = {entry.source_relative for entry in load_registry().values()}
    placed = [m for m in load_manifests(quick_book["area"] / "source" / "_extra" / "figures")
              if m["notebook"] in registered]
    assert len(placed) >= 10 and len(printed_figures) >= len(placed)
    assert "\\(" in quick_pdf["html"].read_text(encoding="utf-8")  # there is math to typeset
    # ... and the PDF shows them: a page range per title, the figures, the math typeset, ink, and
    # every table's columns (the chapters print tables: a check that looks at none would pass)
    assert sum(title in titles[1:] for title, _ in pdfcheck.printed_tables(quick_pdf["html"])) >= 30
    assert pdfcheck.problems(quick_pdf["pdf"], quick_pdf["html"]) == []
    texts = pdfcheck.page_texts(quick_pdf["pdf"])
    assert len(texts) > len(titles)


def test_pdf_works_when_sent_links_page_numbers_contents_and_cover(quick_book, quick_pdf):
    """Issue 37: 637 links of the PDF were file:// addresses of the build machine, none internal;
    no page numbers, a contents list without them, a cover with no version, commit or date."""
    from sss_locus.pipeline.publish import citation, provenance
    from sss_locus.pipeline.book import pdflinks

    assert pdflinks.link_problems(quick_pdf["pdf"], citation.base_url(), min_internal=100) == []
    internal, uris = pdflinks.pdf_links(quick_pdf["pdf"])
    base = citation.base_url()
    assert all(u.startswith(base) for u in uris if "/figures/" in u) if base else not any(
        "/figures/" in u for u in uris)
    texts = pdfcheck.page_texts(quick_pdf["pdf"])
    n = len(texts)
    # every page numbered: a line of its own "i / n" (math glyphs may be extracted after it)
    assert all(re.search(rf"^\s*{i} / {n}\s*$", text, re.M) for i, text in enumerate(texts, 1))
    cover = texts[0]
    assert provenance.package_version() in cover and "commit" in cover and "built 20" in cover
    titles = pdfcheck.printed_page(quick_pdf["html"])[0]
    starts = pdfcheck.chapter_starts(texts, titles)
    contents = " ".join(" ".join(t.split()) for t in texts[:3])
    for title in titles[1:4]:  # the contents list the page each page title opens
        assert f"{' '.join(title.split())} {starts[title][0]}" in contents, title


def test_pdf_check_finds_missing_pages_figures_raw_math_and_blank_pages(tmp_path):
    """The checks can fail: a PDF whose second title is missing, whose first opens two pages,
    with no image for either figure, math left as source on a page and a blank last page."""
    _needs(browser=False)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_pdf import PdfPages

    pdf = tmp_path / "bad.pdf"
    with PdfPages(pdf) as pages:
        for text in ("Alpha\nsome words", "Alpha\nthe length is \\(L\\) metres", ""):
            fig = plt.figure(figsize=(8.27, 11.69))
            fig.text(0.1, 0.9, text, fontsize=40, va="top")
            pages.savefig(fig)
            plt.close(fig)
    html = tmp_path / "page.html"
    fig = plt.figure(figsize=(3, 2), dpi=100)
    fig.savefig(tmp_path / "fig.png")  # 300 x 200 px, not in the PDF
    plt.close(fig)
    html.write_text('<article class="bd-article"><section><h1>Alpha<a class="headerlink" href="#a">#</a>'
                    '</h1><figure><img src="fig.png"></figure><figure><img src="gone.png"></figure>'
                    "<pre>$ make</pre></section></article>"
                    '<span id="document-beta"></span><section><h3>Beta</h3></section>', encoding="utf-8")
    assert pdfcheck.printed_page(html) == (["Alpha", "Beta"], ["fig.png", "gone.png"], "$ make")
    assert pdfcheck.problems(pdf, html) == [
        "page title 'Alpha' opens 2 pages ([1, 2]), not one",
        "page title 'Beta' opens 0 pages ([]), not one",
        "figure image fig.png (300 x 200 px) is not embedded",
        "figure image 'gone.png' is not a PNG file beside the page",
        "math left as source: 1 '\\\\(' in the text (pages [2]), 0 in code blocks",
        "page 3 rendered blank (0.00% of its pixels inked)",
    ]


def test_contents_running_onto_a_second_page_is_not_a_chapter_start():
    """A printed contents that runs over onto a page which starts with a title (the last entries)
    does not count as that page opening; a chapter page that names other titles in its prose does."""
    titles = ["Book", "Alpha", "Beta chapter", "Delta: a longer title of a chapter", "Gamma, the last one"]
    texts = ["Book\nContents\nAlpha\nBeta chapter\nDelta: a longer title\nof a chapter", "Gamma, the last one",
             "Alpha\nThe first chapter, before Beta chapter and Gamma, the last one, says a lot more here.",
             "Beta chapter\nIts own words, many of them, on its first page.",
             "Delta: a longer title of\na chapter\nwrapped over two lines, then its words.",
             "Gamma, the last one\nAnd the last words."]
    assert [pdfcheck.is_contents_page(t, titles) for t in texts] == [True, True, False, False, False, False]
    assert pdfcheck.chapter_starts(texts, titles) == {  # the first page opens the book's first page
        "Book": [1], "Alpha": [3], "Beta chapter": [4], "Delta: a longer title of a chapter": [5], "Gamma, the last one": [6]}


def test_table_check_finds_a_column_missing_from_its_pages_text():
    """Headers wrapped over lines are found; a header found only on another page's range, or a
    short header found elsewhere but not after the row's other headers, is not."""
    texts = ["Alpha\nThe table lists n and all of it.\nplatform ends\nextent (m) oblique-\nband\nauv 1.0 2.0",
             "Beta\nplatform\nvalue (m) n\nauv 3.0", "Gamma\nratio\nauv 4.0"]
    starts = {"Alpha": [1], "Beta": [2], "Gamma": [3], "Delta": []}
    tables = [("Alpha", ["platform", "ends extent (m)", "oblique-band"]), ("Beta", ["", "platform", "value (m)", "n"]),
              ("Alpha", ["platform", "ends extent (m)", "n"]), ("Gamma", ["ratio", "value (m)"]),
              ("Delta", ["anything"])]
    assert pdfcheck.table_problems(texts, starts, tables) == [
        "table 3 ('Alpha', pages 1-1): columns ['n'] are not in the PDF's text after ['platform', 'ends extent (m)']",
        "table 4 ('Gamma', pages 3-3): columns ['value (m)'] are not in the PDF's text after ['ratio']",
    ]


def test_table_check_fails_on_a_printed_table_cut_off_at_its_edge(tmp_path, monkeypatch):
    """A page printed by headless Chromium with a narrow table, a table too wide for the page
    (its right-hand columns are clipped and never drawn) and a table in a closed <details> (not
    printed, not looked for): the check names the wide table and the columns it lost, only those."""
    _needs(browser=True)
    import pandas as pd

    from sss_locus.report.common.tables import readable_table

    monkeypatch.setenv(paths.BUILD_DIR_ENV, str(tmp_path / "build"))  # the browser's profile folder
    narrow = pd.DataFrame({"platform": ["auv"], "peak_deg": [1.0]})
    wide = pd.DataFrame({f"quantity_{i}_longwordcolumnname_m": [1.0 + i] * 20 for i in range(14)})
    wide.insert(0, "platform", ["auv", "boat"] * 10)  # many rows: shown as it is, not turned
    html = tmp_path / "page.html"
    html.write_text('<html><body><article class="bd-article"><section><h1>Alpha</h1>'
                    + readable_table(narrow).to_html() + readable_table(wide).to_html()
                    + "<details><summary>more</summary><table><thead><tr><th>hidden</th></tr></thead></table></details>"
                    + "</section></article></body></html>", encoding="utf-8")
    pdf = bookpdf.print_pdf(html, tmp_path / "page.pdf", bookpdf.find_browser())
    tables = pdfcheck.printed_tables(html)
    headers = ["platform", *(f"quantity {i} longwordcolumnname (m)" for i in range(14))]
    assert tables == [("Alpha", ["platform", "peak (deg)"]), ("Alpha", headers)]
    starts = pdfcheck.chapter_starts(pdfcheck.page_texts(pdf), ["Alpha"])
    found = pdfcheck.table_problems(pdfcheck.page_texts(pdf, "-raw"), starts, tables)
    assert len(found) == 1 and found[0].startswith("table 2 ('Alpha', pages 1-1): columns ['quantity ")
    lost = headers[next(k for k in range(len(headers)) if f"columns [{headers[k]!r}" in found[0]):]
    assert 1 < len(lost) < len(headers) - 1 and f"columns {lost} are not" in found[0]
    assert pdfcheck.problems(pdf, html) == found  # and problems() reports it
