"""The printed book's links and cover (``make pdf``): a PDF that works when it is sent.

Headless Chromium turns every relative link of the printed page into a ``file://`` address on
the build machine, dead anywhere else. :func:`rewrite_links` makes each link of the single page
either **internal** (``#id``: a cross-reference, a figure, a chapter — Chromium writes these as
links inside the PDF) or **public**: a file of the site (a figure's data, its BibTeX, an executed
notebook) at the site's public address ``html.baseurl`` (:func:`sss_locus.pipeline.publish.citation.
base_url`); while that address is not set, such a link is left as plain text rather than a dead
link. :func:`cover_html` is the line of the title page naming the version, commit and date of the
build (and a named build's area), :func:`contents_pages` adds the page numbers to the printed
contents, and :func:`link_problems` reads the links back out of the PDF (the check, tested).
"""

from __future__ import annotations

import posixpath
import re
import zlib
from collections.abc import Mapping
from html import escape, unescape
from pathlib import Path

#: An ``<a ...>`` start tag with an ``href`` (the attribute's value in group ``url``).
ANCHOR = re.compile(r'<a\b(?P<pre>[^>]*?)\shref="(?P<url>[^"]*)"(?P<post>[^>]*)>')
ID = re.compile(r'\sid="([^"]+)"')
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def rewrite_links(html: str, single: str, base_url: str | None) -> tuple[str, dict[str, int]]:
    """``html`` (the single page, printed from the site root) with every link internal or public.

    ``single`` is the single page's path from the site root (``book/intro.html``); its relative
    links are relative to its folder, except the builder's cross-references, written as links to
    ``single`` itself. A link into a page of the book becomes ``#id`` (the
    fragment when the single page has that id, else ``#document-<page>``, where the page starts);
    a link to another file of the site becomes ``<base_url>/<path>``, or loses its ``href`` when
    ``base_url`` is ``None``. External (``https:``, ``mailto:``) and ``#`` links stay. Returns the
    page and the number of links of each kind (``internal``, ``public``, ``unlinked``, ``external``).
    """
    ids = set(ID.findall(html))
    counts = {"internal": 0, "public": 0, "unlinked": 0, "external": 0}

    def fix(match: re.Match) -> str:
        url = unescape(match["url"])
        if url.startswith("#") or SCHEME.match(url):
            counts["internal" if url.startswith("#") else "external"] += 1
            return match[0]
        raw, _, fragment = url.partition("#")
        raw = raw.split("?")[0]
        # relative to the single page's folder; the builder writes its own name from the site root
        path = single if raw in ("", single) else posixpath.normpath(posixpath.join(posixpath.dirname(single), raw))
        page = path[:-len(".html")] if path.endswith(".html") else None
        target = fragment if fragment in ids else f"document-{page}"
        if (path == single or f"document-{page}" in ids) and target in ids:
            counts["internal"] += 1
            return f'<a{match["pre"]} href="#{escape(target)}"{match["post"]}>'
        if base_url and not path.startswith("../"):
            counts["public"] += 1
            return f'<a{match["pre"]} href="{escape(base_url + "/" + path.lstrip("/"))}"{match["post"]}>'
        counts["unlinked"] += 1
        return f'<a{match["pre"]}{match["post"]}>'

    return ANCHOR.sub(fix, html), counts


def cover_html(version: str, commit: str, date: str, area: str | None = None) -> str:
    """The title page's line: version, commit and date of the build, and a named build's area."""
    where = (f" — build area <strong>{escape(area)}</strong>, not the paper's reproduction" if area else "")
    return (f'<p class="sss-locus-cover">Version {escape(version)} · commit <code>{escape(commit)}</code> · '
            f'built {escape(date)}{where}</p>')


def contents_pages(html: str, pages: Mapping[str, int]) -> str:
    """``html`` with the page number of each entry of the printed contents (``#jb-print-toc``)
    whose link text is a key of ``pages`` (page title → first page), right-aligned after it."""
    start = html.find('id="jb-print-toc"')
    end = html.find("</nav>", start)
    if start < 0 or end < 0:
        return html
    head, toc, tail = html[:start], html[start:end], html[end:]

    def number(match: re.Match) -> str:
        text = " ".join(re.sub(r"<[^>]+>", "", unescape(match["text"])).split())
        page = pages.get(text)
        return match[0] if page is None else f'{match[0]}<span class="sss-locus-page">{page}</span>'

    toc = re.sub(r"<a\b[^>]*>(?P<text>.*?)</a>", number, toc, flags=re.S)
    return head + toc + tail


def pdf_links(pdf: Path) -> tuple[int, list[str]]:
    """The links of a PDF written by Chromium (Skia): the number of internal links (link
    annotations with a ``/Dest``) and the address of every external one (``/URI``), read from its
    objects, compressed object streams included."""
    data = Path(pdf).read_bytes()
    chunks = [data]
    for stream in re.finditer(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S):
        try:
            chunks.append(zlib.decompress(stream[1]))
        except zlib.error:
            continue
    internal, uris = 0, []
    for chunk in chunks:
        for annot in re.finditer(rb"/Subtype\s*/Link\b(.*?)(?=/Subtype\s*/Link\b|endobj|\Z)", chunk, re.S):
            body = annot[1]
            uri = re.search(rb"/URI\s*\(((?:\\.|[^\\)])*)\)", body)
            if uri:
                uris.append(re.sub(rb"\\(.)", rb"\1", uri[1]).decode("latin-1"))
            elif b"/Dest" in body:
                internal += 1
    return internal, uris


def link_problems(pdf: Path, base_url: str | None, min_internal: int = 1) -> list[str]:
    """What is wrong with the links of ``pdf``: any link to a local file (``file:``), to neither
    the web (``http(s):``, ``mailto:``) nor the site, to a figure or notebook of the site when
    ``base_url`` is ``None`` (no public site), and fewer than ``min_internal`` internal links."""
    internal, uris = pdf_links(pdf)
    found = [f"link to a local file: {u}" for u in uris if u.startswith("file:")]
    if base_url is None:  # no public site: the site's files must not be linked at all
        found += [f"link to a site file without a public address: {u}" for u in uris
                  if re.search(r"/(figures|notebooks)/[^/]+$", u)]
    found += [f"link to neither the web nor the site: {u}" for u in uris
              if not u.startswith(("file:", "http://", "https://", "mailto:"))]
    if internal < min_internal:
        found.append(f"{internal} internal links (cross-references, figures, contents), expected at least {min_internal}")
    return found
