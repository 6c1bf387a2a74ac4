"""The whole book as one PDF (``make pdf``): Jupyter Book's ``singlehtml`` build, printed by
headless Chromium.

Run after ``make book`` (it uses the executed notebooks and exported figures in the build area)::

    .venv/bin/python -m sss_locus.pipeline.book.bookpdf     # prints the path of the PDF

The single page is built into ``<build>/singlehtml`` and printed to ``<build>/pdf/sss-locus-book.pdf``
with Chromium from the operating system (Debian/Ubuntu package ``chromium``, or Google Chrome):
the figures are the book's own (embedded PNGs), math is typeset by the site's local MathJax, and
the interactive views and the "cite this figure" dropdowns are left out of the print. Its links
are internal (cross-references, figures, the contents) or go to the site's public address
(``html.baseurl``) for data and BibTeX files (:mod:`sss_locus.pipeline.book.pdflinks`); every page is
numbered, the cover names the version, commit and date, and, when poppler-utils is installed, the
contents list each page's number (a second print) and the PDF is read back and checked
(:mod:`sss_locus.pipeline.book.pdfcheck`).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from sss_locus import paths
from sss_locus.pipeline.book import bookbuild, pdfcheck, pdflinks
from sss_locus.pipeline.publish import citation, provenance
from sss_locus.pipeline.run.kernels import hermetic_env

PDF_NAME = "sss-locus-book.pdf"
BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome")
#: Printing rules added to the single page: no navigation, no interactive plots, no dropdowns.
#: The first page is the theme's title page (the book's title and contents; the theme hides the
#: root page's own title in print; no bottom margin, which would spill a blank page); the root
#: page's text and each other page of the book (a section the singlehtml builder places after a
#: ``<span id="document-...">``) start a new page. A caption keeps the width of its table in print
#: (the screen's line-wide caption of a narrow table left a blank page after the pose-space chapter).
PRINT_CSS = """
@media print {
  .bd-header, .bd-sidebar-primary, .bd-sidebar-secondary, .header-article, .prev-next-area,
  .bd-footer, .bd-footer-article, .bd-footer-content, .plotly-graph-div, .figure-cite details,
  .sd-dropdown, .toggle-details, button { display: none !important; }
  .bd-main, .bd-content, .bd-article-container { max-width: 100% !important; }
  figure, img, table { break-inside: avoid; }
  #jb-print-docs-body { break-after: page; }
  #jb-print-toc { margin-bottom: 0 !important; }
  span[id^="document-"] + section { break-before: page; }
  caption { min-width: 0 !important; }
  .bd-header-announcement { display: none !important; }
  #jb-print-toc li.toc-entry > a { display: inline !important; }
  .sss-locus-page { padding-left: 0.8em; font-weight: bold; }
}
@page {
  margin: 14mm 12mm 16mm 12mm;
  @bottom-center { content: counter(page) " / " counter(pages); font-size: 9pt; color: #555; }
}
"""


def public_url() -> str | None:
    """Where the PDF's data and BibTeX links point: the site's public address (``html.baseurl``)
    for the reproduction; none for a named build, whose files are not the public site's (a link
    there would open the paper's figure of the same label)."""
    return None if paths.build_name() else citation.base_url()


def find_browser() -> str:
    """Path of a Chromium-family browser, or a clear error saying how to install one."""
    override = os.environ.get("SSS_LOCUS_CHROMIUM")
    for name in ((override,) if override else ()) + BROWSERS:
        found = shutil.which(name)
        if found:
            return found
    raise FileNotFoundError(
        "make pdf prints the book with headless Chromium, and none was found on PATH (looked for "
        + ", ".join(BROWSERS) + "). Install it, e.g. `sudo apt-get install chromium` on Debian or "
        "Ubuntu, or set SSS_LOCUS_CHROMIUM to the browser's path."
    )


def build_singlehtml(log=print) -> Path:
    """Stage the book, build it with the ``singlehtml`` builder; return the page to print."""
    import yaml

    root = bookbuild.stage()
    missing = bookbuild.missing_toc_files(root)
    if missing:
        raise FileNotFoundError("the book has not been built yet (missing: " + ", ".join(missing)
                                + "); run `make book` first")
    out = paths.build_dir() / "singlehtml"
    cmd = [str(Path(sys.executable).with_name("jupyter-book")), "build", str(root), "--builder",
           "singlehtml", "--path-output", str(out), "--all"]
    log("$ " + " ".join(cmd))
    result = subprocess.run(cmd, env={**os.environ, **hermetic_env()}, cwd=root, text=True,
                            capture_output=True, errors="replace")
    if result.returncode != 0:
        raise RuntimeError(f"singlehtml build failed (exit {result.returncode}):\n{result.stdout[-4000:]}"
                           f"\n{result.stderr[-4000:]}")

    # Sphinx writes the single page as the root document (book/intro.html; index.html only
    # redirects to it) but with links relative to the site root, while the book's own HTML links
    # (figures, notebooks, plotly) are relative to a page one folder down. Print a copy at the
    # site root with those links made root-relative as well.
    root_doc = yaml.safe_load((root / paths.TOC_FILE.name).read_text(encoding="utf-8"))["root"]
    site = out / "_build" / "singlehtml"
    single = site / f"{root_doc}.html"
    if not single.is_file():
        raise RuntimeError(f"singlehtml build finished but {single} is missing")
    (site / "_static" / "sss-locus-print.css").write_text(PRINT_CSS, encoding="utf-8")
    html, counts = pdflinks.rewrite_links(single.read_text(encoding="utf-8"), f"{root_doc}.html", public_url())
    log(f"links: {counts['internal']} internal, {counts['public']} to the public site, {counts['external']} "
        f"external, {counts['unlinked']} left as text" + ("" if public_url() else " (no public address: html.baseurl "
                                                          "is empty, or this is a named build, not on the site)"))
    cover = pdflinks.cover_html(provenance.package_version(), provenance.short_commit(provenance.git_commit()),
                                provenance.utc_now()[:10], paths.build_name())
    cover_page = html.find('id="jb-print-docs-body"')  # the title page: the book's title, then contents
    title_end = html.find("</h1>", cover_page) if cover_page >= 0 else -1
    if title_end >= 0:
        html = html[:title_end + 5] + cover + html[title_end + 5:]
    for folder in ("figures", "notebooks", "plotly", "mathjax"):
        html = html.replace(f'"../{folder}/', f'"{folder}/')
    html = html.replace("</head>", '<link rel="stylesheet" href="_static/sss-locus-print.css">\n</head>', 1)
    index = site / "book-print.html"
    index.write_text(html, encoding="utf-8")
    return index


def print_pdf(index: Path, target: Path, browser: str, timeout_s: float = 300) -> Path:
    """Print ``index`` to ``target`` with headless ``browser``; return ``target``."""
    target.parent.mkdir(parents=True, exist_ok=True)
    target.unlink(missing_ok=True)
    profile = paths.build_dir() / "chromium-profile"
    # Offline on purpose: everything the page needs is in the build, and a page waiting for an
    # unreachable host would stall the print. The proxy address refuses every connection.
    cmd = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
           "--disable-background-networking", "--proxy-server=127.0.0.1:9",
           "--proxy-bypass-list=<-loopback>", f"--user-data-dir={profile}", "--no-pdf-header-footer",
           "--virtual-time-budget=30000",
           f"--print-to-pdf={target}", index.resolve().as_uri()]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout_s,
                            stdin=subprocess.DEVNULL)
    if not target.is_file() or not target.read_bytes().startswith(b"%PDF"):
        raise RuntimeError(f"{browser} did not write a PDF (exit {result.returncode}):\n{result.stderr[-3000:]}")
    return target


def numbered_contents(index: Path, pdf: Path, browser: str, rounds: int = 3) -> dict[str, int]:
    """Give the printed contents of ``index`` the page each page title opens in ``pdf`` (read
    back with poppler) and print again, until the numbers no longer move (at most ``rounds``
    prints); return the numbers."""
    titles = pdfcheck.printed_page(index)[0]
    base = index.read_text(encoding="utf-8")
    pages: dict[str, int] = {}
    for _ in range(rounds):
        starts = pdfcheck.chapter_starts(pdfcheck.page_texts(pdf), titles)
        found = {" ".join(t.split()): p[0] for t, p in starts.items() if len(p) == 1}
        if found == pages:
            break
        pages = found
        index.write_text(pdflinks.contents_pages(base, pages), encoding="utf-8")
        print_pdf(index, pdf, browser)
    return pages


def main(argv: list[str] | None = None) -> int:
    """Print the book; then, when poppler's tools are installed, read the PDF back and fail on
    any of :func:`sss_locus.pipeline.book.pdfcheck.problems`."""
    import argparse

    from sss_locus.pipeline.book import areas

    parser = argparse.ArgumentParser(description="Print the built book to one PDF and check it.")
    parser.add_argument("--name", help="the book of the build area _build/NAME (sss-locus book --name NAME)")
    args = parser.parse_args(argv)
    try:
        browser = find_browser()  # before any work: a missing tool is the common failure
        with areas.entered(args.name):
            index = build_singlehtml(log=lambda line: print(line, file=sys.stderr))
            pdf = print_pdf(index, paths.build_dir() / "pdf" / PDF_NAME, browser)
            missing = pdfcheck.missing_tools()
            if not missing:
                numbered_contents(index, pdf, browser)
            found = [] if missing else pdfcheck.problems(pdf, index) + pdflinks.link_problems(pdf, public_url())
    except (FileNotFoundError, RuntimeError, ValueError, subprocess.TimeoutExpired) as exc:
        print(f"make pdf: {exc}", file=sys.stderr)
        return 1
    if missing:
        print(f"make pdf: the PDF was not checked ({', '.join(missing)} not found: "
              "`apt-get install poppler-utils`)", file=sys.stderr)
    if found:
        print(f"make pdf: {pdf} was printed, but:\n  " + "\n  ".join(found), file=sys.stderr)
        return 1
    print(pdf)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
