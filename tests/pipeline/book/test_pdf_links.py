"""Links of the printed book that work when the PDF is sent (sss_locus.pipeline.book.pdflinks), on a
page written for the test and, when Chromium is installed, on a PDF it prints from it."""

from __future__ import annotations

import shutil
import subprocess

import pytest

from sss_locus.pipeline.book import pdflinks

PAGE = """<html><body><div id="jb-print-toc"><div><h2>Contents</h2></div><nav><ul>
<li><a href="#document-executed/planning">Planning survey passes</a></li></ul></nav></div>
<span id="document-executed/planning"></span><section id="planning"><h1>Planning</h1>
<p>See <a class="reference internal" href="book/intro.html#fig-planning-bands">Fig. 3</a>,
<a href="../executed/planning.html">the chapter</a>, <a href="../executed/planning.html#near">near</a>,
<a href="../figures/fig-planning-bands.csv">CSV</a>, <a href="../figures/fig-planning-bands.bib">BibTeX</a>,
<a href="https://doi.org/10.1/x">DOI</a> and <a href="#planning">here</a>.</p>
<figure id="fig-planning-bands"><img src="x.png"></figure><p id="near">near</p></section></body></html>"""


def test_every_link_becomes_internal_public_or_plain_text():
    """Issue 37: the PDF's cross-reference, figure, data and BibTeX links were file:// addresses
    of the build machine."""
    html, counts = pdflinks.rewrite_links(PAGE, "book/intro.html", "https://example.org/sss-locus")
    assert 'href="#fig-planning-bands"' in html and 'href="#document-executed/planning"' in html
    assert 'href="#near"' in html and 'href="#planning"' in html
    assert 'href="https://example.org/sss-locus/figures/fig-planning-bands.csv"' in html
    assert 'href="https://example.org/sss-locus/figures/fig-planning-bands.bib"' in html
    assert 'href="https://doi.org/10.1/x"' in html and "../" not in html and "book/intro.html" not in html
    assert counts == {"internal": 5, "public": 2, "unlinked": 0, "external": 1}
    plain, counts = pdflinks.rewrite_links(PAGE, "book/intro.html", None)  # no public address yet
    assert "figures/" not in plain and ">CSV</a>" in plain and counts["unlinked"] == 2


def test_contents_get_their_page_numbers_and_the_cover_its_version():
    html = pdflinks.contents_pages(PAGE, {"Planning survey passes": 7})
    assert 'Planning survey passes</a><span class="sss-locus-page">7</span>' in html
    assert html.count("sss-locus-page") == 1  # only the contents, not the chapter's own links
    cover = pdflinks.cover_html("0.4.0", "abc1234", "2026-11-27", "myboat")
    assert "0.4.0" in cover and "abc1234" in cover and "2026-11-27" in cover and "myboat" in cover


BROWSER = next((b for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)


@pytest.mark.skipif(BROWSER is None, reason="no headless Chromium")
def test_a_printed_page_keeps_its_internal_links_and_no_local_ones(tmp_path):
    html, _ = pdflinks.rewrite_links(PAGE, "book/intro.html", "https://example.org/sss-locus")
    page = tmp_path / "book-print.html"
    page.write_text(html.replace("<section", '<div style="height:1400px"></div><section'))
    pdf = tmp_path / "page.pdf"
    subprocess.run([BROWSER, "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                    f"--user-data-dir={tmp_path / 'profile'}", f"--print-to-pdf={pdf}", page.as_uri()],
                   capture_output=True, timeout=120, stdin=subprocess.DEVNULL)
    internal, uris = pdflinks.pdf_links(pdf)
    assert internal >= 4 and "https://example.org/sss-locus/figures/fig-planning-bands.csv" in uris
    assert pdflinks.link_problems(pdf, "https://example.org/sss-locus") == []
    raw = tmp_path / "raw.pdf"  # the page as it was: its relative links print as file:// addresses
    page.write_text(PAGE)
    subprocess.run([BROWSER, "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                    f"--user-data-dir={tmp_path / 'profile'}", f"--print-to-pdf={raw}", page.as_uri()],
                   capture_output=True, timeout=120, stdin=subprocess.DEVNULL)
    assert any(p.startswith("link to a local file: file://") for p in pdflinks.link_problems(raw, None))
