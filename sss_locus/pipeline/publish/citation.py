"""Citation metadata: figure BibTeX entries, the project's entry, the site's base URL, and
``.zenodo.json``.

One source for each fact:

* the project's title, authors, version and release date: ``CITATION.cff``;
* the public address of the built site: ``html.baseurl`` in ``_config.yml`` (empty until the
  site is published; figure entries get a ``url`` only when it is set);
* the repository (launch and source buttons): ``repository.url`` in ``_config.yml``.

``.zenodo.json`` (read by Zenodo when a GitHub release is archived, so that the release receives a
DOI) is generated from ``CITATION.cff``; regenerate it after editing the CFF file with::

    .venv/bin/python -m sss_locus.pipeline.publish.citation          # writes .zenodo.json
    .venv/bin/python -m sss_locus.pipeline.publish.citation --check  # exit 1 if it is out of date

Every BibTeX field is valid LaTeX: TeX specials outside ``$...$`` math are escaped, non-ASCII
characters become LaTeX commands (``latexcodec``, a dependency of ``sphinxcontrib-bibtex``), or, for
characters LaTeX has none for (a name in any script), ASCII
(:func:`sss_locus.pipeline.publish.latex_ascii.transliterate`), and
the Markdown emphasis of captions becomes ``\\emph``/``\\textbf``/``\\texttt``.
"""

from __future__ import annotations

import argparse
import codecs
import json
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.publish.latex_ascii import transliterate

ZENODO_FILE: Path = paths.REPO_ROOT / ".zenodo.json"
#: Site folder (``_extra/notebooks``) holding the executed notebooks offered for download.
NOTEBOOKS_SUBDIR = "notebooks"
#: Staged folder of the per-figure blocks (``<source>/_cite/<label>.md``).
CITE_SUBDIR = "_cite"
#: Longest short caption in a figure's BibTeX ``title`` (characters, before escaping).
SHORT_CAPTION_CHARS = 130
_SPECIALS = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "&": r"\&", "%": r"\%",
             "#": r"\#", "_": r"\_", "^": r"\^{}", "~": r"\~{}", "$": r"\$"}
_MARKDOWN = ((re.compile(r"\*\*(.+?)\*\*"), "textbf"), (re.compile(r"(?<![\w*])\*(?!\s)(.+?)\*"), "emph"),
             (re.compile(r"`([^`]+)`"), "texttt"))


def _escape_text(text: str) -> str:
    """Escape plain text (no math) for LaTeX."""
    import latexcodec  # noqa: F401  (registers the "ulatex" codecs)

    out = []
    for char in text:
        if char in _SPECIALS:
            out.append(_SPECIALS[char])
        elif ord(char) < 128:
            out.append(char)
        else:
            try:
                out.append("{" + codecs.encode(char, "ulatex+ascii") + "}")
            except UnicodeEncodeError:
                out.append(transliterate(char, _SPECIALS))
    return "".join(out)


def latex_escape(text: str, *, markdown: bool = False) -> str:
    """``text`` as LaTeX: specials escaped outside ``$...$`` (math kept as written when the
    dollars pair up and its braces balance), non-ASCII as LaTeX commands.

    With ``markdown=True``, ``**bold**``, ``*emphasis*`` and ```code``` become ``\\textbf``,
    ``\\emph`` and ``\\texttt``.

    >>> latex_escape("50% of width_m & 3° ($\\\\theta_1$)")
    '50\\\\% of width\\\\_m \\\\& 3{$^\\\\circ$} ($\\\\theta_1$)'
    """
    pieces = text.split("$")
    math_ok = len(pieces) % 2 == 1 and all(p.count("{") == p.count("}") for p in pieces[1::2])
    if not math_ok:
        pieces = [text]
    out = []
    for i, piece in enumerate(pieces):
        if i % 2:
            out.append("$" + piece + "$")
            continue
        if not markdown:
            out.append(_escape_text(piece))
            continue
        # Markdown spans first (on the raw text), then escape the pieces between and inside them.
        spans: list[tuple[int, int, str, str]] = []
        for pattern, command in _MARKDOWN:
            for m in pattern.finditer(piece):
                if not any(s < m.end() and m.start() < e for s, e, _, _ in spans):
                    spans.append((m.start(), m.end(), command, m.group(1)))
        pos, parts = 0, []
        for start, end, command, inner in sorted(spans):
            parts.append(_escape_text(piece[pos:start]))
            parts.append(f"\\{command}{{{_escape_text(inner)}}}")
            pos = end
        parts.append(_escape_text(piece[pos:]))
        out.append("".join(parts))
    return "".join(out)


def short_caption(caption: str, limit: int = SHORT_CAPTION_CHARS) -> str:
    """The caption's first sentence (or clause, at ``;``); when longer than ``limit`` characters,
    its longest run of whole clauses (ending before a ``,`` or ``:``) that fits, else cut at a
    word with an ellipsis. Sentences, clauses and cuts end only outside parentheses, brackets and
    ``$...$`` math, so a title never opens a bracket it does not close.

    >>> short_caption("Locus length vs. range; details. More.")
    'Locus length vs. range'
    >>> short_caption("Median length per bin, Torpedo AUV (REMUS-100, Iver3), dual sonar", limit=60)
    'Median length per bin, Torpedo AUV (REMUS-100, Iver3)'
    """
    text = " ".join(caption.split())
    depth, math, outside = 0, False, []  # outside[i]: character i is outside brackets and math
    for char in text:
        if char == "$":
            math = not math
        elif not math and char in "([":
            depth += 1
        elif not math and char in ")]":
            depth = max(0, depth - 1)
        outside.append(depth == 0 and not math and char not in ")]$")
    end = next((m.start() for m in re.finditer(r"(?<=[a-z0-9)\]$][.!?])\s+(?=[A-Z(])|;\s", text)
                if outside[m.start()]), len(text))
    head = text[:end].rstrip(".")
    if len(head) <= limit:
        return head
    clauses = [i for i in range(limit // 3, min(limit, len(head) - 1))
               if head[i] in ",:" and head[i + 1] == " " and outside[i]]
    if clauses:  # whole clauses that keep a useful title
        return head[:clauses[-1]]
    spaces = [i for i in range(1, limit) if head[i] == " " and outside[i]]
    cut = spaces[-1] if spaces else limit
    whole = head[cut:].lstrip().startswith("(")  # only a parenthesis left out: the phrase is whole
    return head[:cut].rstrip(",:;") + ("" if whole else "…")


def _load_yaml(path: Path) -> dict[str, Any]:
    import yaml

    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    if not isinstance(data, dict):
        raise ValueError(f"{path} must hold a YAML mapping")
    return data


def load_cff(path: Path | None = None) -> dict[str, Any]:
    """``CITATION.cff`` as a dict."""
    return _load_yaml(paths.CITATION_FILE if path is None else path)


def _config_value(section: str, key: str, config: Path | None = None) -> str | None:
    try:
        value = (_load_yaml(paths.CONFIG_FILE if config is None else config).get(section) or {}).get(key)
    except OSError:
        return None
    value = str(value or "").strip()
    return value or None


def base_url(config: Path | None = None) -> str | None:
    """The published site's address (``html.baseurl`` in ``_config.yml``), without a trailing
    slash; ``None`` while it is empty."""
    value = _config_value("html", "baseurl", config)
    if value and not re.match(r"^https?://[^\s/]+", value):
        raise ValueError(f"html.baseurl in _config.yml must be an http(s) URL or empty, got {value!r}")
    return value.rstrip("/") if value else None


def repository_url(config: Path | None = None) -> str | None:
    """The repository's address (``repository.url`` in ``_config.yml``), or ``None``."""
    return _config_value("repository", "url", config)


def _bibtex_authors(cff: Mapping[str, Any]) -> str:
    names = []
    for author in cff.get("authors") or []:
        if "family-names" in author:
            given = author.get("given-names", "")
            names.append(latex_escape(f"{author['family-names']}, {given}".strip(", ")))
        elif "name" in author:  # an entity: braces keep BibTeX from splitting it
            names.append("{" + latex_escape(str(author["name"])) + "}")
    return " and ".join(names) or "{sss-locus contributors}"


def figure_url(label: str, config: Path | None = None, suffix: str = "png") -> str | None:
    """Public address of a figure's PNG (a table's CSV: ``suffix``), when ``html.baseurl`` is set."""
    base = base_url(config)
    return f"{base}/{paths.FIGURES_SUBDIR}/{label}.{suffix}" if base else None


def data_note(manifest: Mapping[str, Any]) -> str:
    """``; computed for <platform> (<name>: <sonar>, <aperture>, <range>, tilt ...); data entries
    <entries>; data files <file> (sha256 ...), ...`` (LaTeX) from a manifest's ``data_inputs``:
    exactly the platforms, data entries and data files the figure was computed from (see
    :func:`sss_locus.experiments.datamodel.userdata.figure_record`); empty when it has none."""
    inputs = manifest.get("data_inputs") or {}
    parts = []
    for key, v in (inputs.get("values") or {}).items():
        s = v.get("sonar", {})
        tilts = "/".join(f"{t:g}" for t in dict.fromkeys((v.get("tilt_deg") or {}).values()))
        parts.append(f"{key} ({v.get('name', '')}: {s.get('name', '')}, {s.get('azimuth_deg', 0):g} x "
                     f"{s.get('elevation_deg', 0):g} deg, {s.get('max_range_m', 0):g} m, tilt {tilts} deg)")
    files = [f"{f['path'] if f.get('role') == 'shipped' else Path(f['path']).name} (sha256 {f['sha256'][:12]})"
             for f in inputs.get("files", [])]
    files += [f"--set {o}" for o in inputs.get("overrides", [])]
    note = ("; computed for " + "; ".join(parts)) if parts else ""
    note += ("; data entries " + ", ".join(inputs["entries"])) if inputs.get("entries") else ""
    note += ("; data files " + ", ".join(files)) if files else ""
    return latex_escape(note)


def figure_bibtex(manifest: Mapping[str, Any], *, cff: Mapping[str, Any] | None = None,
                  config: Path | None = None) -> str:
    """A ``@misc`` BibTeX entry citing one exported figure, from its manifest.

    Fields: ``title`` (label and short caption), ``author`` and ``howpublished`` (from
    ``CITATION.cff``), ``year`` (of the run), ``version`` (of the package), ``note`` (notebook,
    profile, commit, a named build's area) and ``url`` (``html.baseurl``, the reproduction's only).
    Key ``sss-locus:<label>``, in a named build area ``sss-locus:<area>:<label>`` (two entries).
    """
    from sss_locus.pipeline.publish.provenance import short_commit

    if cff is None:
        try:
            cff = load_cff()
        except (OSError, ValueError, ImportError):
            cff = {}
    label = manifest["label"]
    kind, area = "Table" if label.startswith("tab-") else "Figure", manifest.get("build_area")
    fields = {
        "title": "{" + latex_escape(f"{kind} {label}: ") + latex_escape(short_caption(manifest["caption"]),
                                                                       markdown=True) + "}",
        "author": _bibtex_authors(cff),
        "year": latex_escape(str(manifest["run_time_utc"])[:4]),
        "version": latex_escape(str(manifest["package_version"])),
        "howpublished": f"{kind} in \\emph{{" + latex_escape(str(cff.get("title", "sss-locus"))) + "}",
        "note": (f"Notebook \\texttt{{{latex_escape(str(manifest['notebook']))}}}, "
                 f"profile {latex_escape(str(manifest['profile']))}, "
                 f"commit \\texttt{{{latex_escape(short_commit(str(manifest['git_commit'])))}}}"
                 + (f", build area \\texttt{{{latex_escape(str(area))}}}" if area else "")
                 + data_note(manifest)),
    }
    url = None if area else figure_url(label, config, "csv" if kind == "Table" else "png")
    if url:
        fields["url"] = url.replace("%", r"\%").replace("#", r"\#")
    body = ",\n".join(f"  {key} = {{{value}}}" for key, value in fields.items())
    return f"@misc{{{':'.join(['sss-locus', *filter(None, [area]), label])},\n{body}\n}}\n"


def project_bibtex(cff: Mapping[str, Any] | None = None, *, config: Path | None = None) -> str:
    """The ``@misc`` BibTeX entry ``sss-locus`` citing this project, from ``CITATION.cff``: its
    title, authors, ``version``, the year of ``date-released``, and its ``doi`` and address
    (``url``, else ``repository-code``) when set."""
    cff = load_cff() if cff is None else cff
    fields = {
        "title": "{" + latex_escape(str(cff["title"])) + "}",
        "author": _bibtex_authors(cff),
        "year": latex_escape(str(cff["date-released"])[:4]),
        "version": latex_escape(str(cff["version"])),
        "howpublished": "Software and web book, version " + latex_escape(str(cff["version"])),
    }
    if cff.get("doi"):
        fields["doi"] = latex_escape(str(cff["doi"]))
    url = cff.get("url") or cff.get("repository-code")
    if url:
        fields["url"] = str(url).replace("%", r"\%").replace("#", r"\#")
    body = ",\n".join(f"  {key} = {{{value}}}" for key, value in fields.items())
    return f"@misc{{sss-locus,\n{body}\n}}\n"


def launch_links(notebook: str, config: Path | None = None) -> dict[str, str]:
    """Binder and Colab addresses of a source notebook (repository-relative path), when
    ``repository.url`` in ``_config.yml`` is a GitHub repository; otherwise ``{}``."""
    repo = repository_url(config)
    m = re.match(r"^https://github\.com/([^/\s]+)/([^/\s]+?)(?:\.git)?/?$", repo or "")
    if not m or not notebook.endswith(".ipynb"):
        return {}
    branch = _config_value("repository", "branch", config) or "main"
    org, name = m.groups()
    return {"Binder": f"https://mybinder.org/v2/gh/{org}/{name}/{branch}?labpath={notebook}",
            "Colab": f"https://colab.research.google.com/github/{org}/{name}/blob/{branch}/{notebook}"}


def cite_block(manifest: Mapping[str, Any], bibtex: str, *, site_root: str = "..",
               config: Path | None = None) -> str:
    """The MyST block placed under a figure on its own page (``{include}``-d there): its files and
    data, the code cell and notebook that made it, launch links, and its BibTeX entry.

    ``site_root`` is the site root relative to the page (notebook pages sit one folder down).
    """
    label = manifest["label"]
    kinds = {".png": "PNG", ".svg": "SVG", ".pdf": "PDF"}
    files = sorted(manifest["files"])
    images = [f'<a href="{site_root}/{manifest["files"][n]["url"]}">{kinds[Path(n).suffix]}</a>'
              for n in files if Path(n).suffix in kinds]
    # Link text: the part after the label ("circle.csv"); a whole name would meet smart dashes.
    data = [f'<a href="{site_root}/{manifest["files"][n]["url"]}" download>'
            f'{n.removeprefix(label).lstrip("-") if n != f"{label}.csv" else "CSV"}</a>'
            for n in files if n.endswith(".csv")]
    data += [f'<a href="{site_root}/{manifest["files"][n]["url"]}" download>{n.removeprefix(label).lstrip("-")}</a>'
             for n in files if Path(n).suffix not in (*kinds, ".csv", ".bib")]  # attachments (mission files)
    meta = [f'<a href="{site_root}/{paths.FIGURES_SUBDIR}/{label}.json">manifest</a>',
            f'<a href="{site_root}/{paths.FIGURES_SUBDIR}/{label}.bib" download>BibTeX</a>']
    notebook = str(manifest["notebook"])
    name = Path(notebook).name
    cell = manifest.get("cell")
    where = f'<a href="#{label}-source">code cell [{cell}]</a>' if cell else \
        f'<a href="#{label}-source">code cell</a>'
    source = (f"{where} of <code>{notebook}</code> · "
              f'<a href="{site_root}/{NOTEBOOKS_SUBDIR}/{name}" download>download the executed notebook</a>')
    launch = " · ".join(f'<a href="{url}">open in {k}</a>' for k, url in launch_links(notebook, config).items())
    lines = [
        f'<div class="figure-cite" id="{label}-cite">',
        "",
        f"**Figure <code>{label}</code>**: {' · '.join(images)} · data: {' · '.join(data) or 'none'} · "
        f"{' · '.join(meta)}<br>",
        f"**Made by** {source}{' · ' + launch if launch else ''}"
        f" (profile <code>{manifest['profile']}</code>, commit "
        f"<code>{str(manifest['git_commit'])[:12]}</code>)",
        "",
        ":::{dropdown} Cite this figure (BibTeX)",
        "```bibtex",
        bibtex.rstrip(),
        "```",
        ":::",
        "",
        "</div>",
        "",
    ]
    return "\n".join(lines)


def zenodo_metadata(cff: Mapping[str, Any]) -> dict[str, Any]:
    """Zenodo deposit metadata (``.zenodo.json``) from a CITATION.cff mapping."""
    creators = []
    for author in cff.get("authors") or []:
        if "family-names" in author:
            creator = {"name": f"{author['family-names']}, {author.get('given-names', '')}".strip(", ")}
        else:
            creator = {"name": str(author["name"])}
        if author.get("affiliation"):
            creator["affiliation"] = author["affiliation"]
        if author.get("orcid"):
            creator["orcid"] = str(author["orcid"]).rsplit("/", 1)[-1]
        creators.append(creator)
    meta: dict[str, Any] = {
        "title": cff["title"],
        "description": " ".join(str(cff.get("abstract", cff["title"])).split()),
        "upload_type": "software",
        "creators": creators,
        "version": str(cff["version"]),
        "license": {"id": str(cff["license"])},
        "keywords": list(cff.get("keywords") or []),
    }
    if cff.get("date-released"):
        meta["publication_date"] = str(cff["date-released"])
    related = [{"identifier": cff[key], "relation": "isSupplementTo", "scheme": "url"}
               for key in ("repository-code", "url") if cff.get(key)]
    if related:
        meta["related_identifiers"] = related
    return meta


def zenodo_json(cff: Mapping[str, Any] | None = None) -> str:
    """The text of ``.zenodo.json`` generated from ``CITATION.cff``."""
    return json.dumps(zenodo_metadata(load_cff() if cff is None else cff), indent=2,
                      ensure_ascii=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Generate .zenodo.json from CITATION.cff.")
    parser.add_argument("--check", action="store_true", help="only check that .zenodo.json is up to date")
    parser.add_argument("--bibtex", action="store_true", help="print the project's BibTeX entry instead")
    args = parser.parse_args(argv)
    if args.bibtex:
        print(project_bibtex(), end="")
        return 0
    text = zenodo_json()
    current = ZENODO_FILE.read_text(encoding="utf-8") if ZENODO_FILE.exists() else None
    if args.check:
        if current != text:
            print(f"{ZENODO_FILE.name} is out of date; run python -m sss_locus.pipeline.publish.citation",
                  file=sys.stderr)
            return 1
        return 0
    ZENODO_FILE.write_text(text, encoding="utf-8")
    print(ZENODO_FILE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
