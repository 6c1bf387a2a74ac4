"""Stage the book source in the build area and build it with Jupyter Book.

The staged source (:func:`sss_locus.paths.source_dir`, ``<build>/source``) is the book's source
root: it receives copies of ``_config.yml``, ``_toc.yml`` and ``book/`` next to the executed
notebooks (``executed/``), the exported figures and a local MathJax (``_extra/``, copied verbatim
to the site root by ``html_extra_path``). The figures page is generated from the figure and
table manifests (:mod:`sss_locus.pipeline.book.figindex`); the claims page gets a notice at its top
when a chapter ran on other inputs than the paper's (:mod:`sss_locus.pipeline.book.paperinputs`). Jupyter Book writes into
``<build>/jupyter-book``; the finished site replaces ``<build>/html`` only when the build and the
site checks pass.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from importlib import metadata
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

from sss_locus import paths
from sss_locus.pipeline.book import areanotice, claimsindex, failedchapters, figindex, paperinputs
from sss_locus.pipeline.publish import citation, export, provenance
from sss_locus.pipeline.run import outputs
from sss_locus.pipeline.book.buildlog import ANSI, StagingPathFilter
from sss_locus.pipeline.run.kernels import hermetic_env

FIGURES_PAGE = "figures.md"
CLAIMS_PAGE = "claims.md"
FRONT_PAGE = "intro.md"
FIGURES_MARKER = "<!-- FIGURES-INDEX -->"
CITE_PAGE = "cite.md"
PROJECT_BIBTEX_MARKER = "<!-- PROJECT-BIBTEX -->"
MATHJAX_DIST = "sphinx-mathjax-offline"
#: The site folder (under ``_extra``) of plotly.js, served locally for the interactive views.
PLOTLY_SUBDIR = "plotly"
# --all: an incremental Sphinx build only re-reads changed pages, so a warning in an unchanged
# page would pass -W on the second try; the book is small, rebuild every page every time.
JB_FLAGS = ("-W", "-n", "--keep-going", "--all")


def copy_mathjax() -> Path:
    """Copy the MathJax 3 files shipped by ``sphinx-mathjax-offline`` to ``_extra/mathjax``."""
    dist = metadata.distribution(MATHJAX_DIST)
    source = Path(dist.locate_file("sphinx-mathjax-offline/static/mathjax"))
    if not (source / "tex-chtml.js").is_file():
        raise FileNotFoundError(f"MathJax files not found in {source} (package {MATHJAX_DIST} {dist.version})")
    target = paths.mathjax_dir()
    stamp = target / ".version"
    if stamp.is_file() and stamp.read_text() == dist.version:
        return target
    shutil.rmtree(target, ignore_errors=True)
    shutil.copytree(source, target)
    stamp.write_text(dist.version)
    return target


def copy_plotly() -> Path:
    """Copy ``plotly.min.js`` shipped by the ``plotly`` package to ``_extra/plotly`` (no CDN)."""
    dist = metadata.distribution("plotly")
    source = Path(dist.locate_file("plotly/package_data/plotly.min.js"))
    if not source.is_file():
        raise FileNotFoundError(f"plotly.min.js not found at {source} (package plotly {dist.version})")
    target = paths.extra_dir() / PLOTLY_SUBDIR
    target.mkdir(parents=True, exist_ok=True)
    if provenance.file_sha256(target / source.name) != provenance.file_sha256(source):
        shutil.copy2(source, target / source.name)
    return target


def stage_figure_pages(root: Path, manifests: list[dict[str, Any]]) -> None:
    """Write the block placed under each figure (``_cite/<label>.md``, see
    :func:`sss_locus.pipeline.publish.citation.cite_block`) and copy the executed notebooks to the site
    (``notebooks/<name>.ipynb``) for download, each local absolute path of their metadata (the
    user's files, papermill's paths) replaced by the file's name (:func:`sss_locus.paths.public_values`)."""
    cite_dir = root / citation.CITE_SUBDIR
    shutil.rmtree(cite_dir, ignore_errors=True)
    cite_dir.mkdir(parents=True)
    for m in manifests:
        bib = (paths.figures_dir() / f"{m['label']}.bib").read_text(encoding="utf-8")
        (cite_dir / f"{m['label']}.md").write_text(citation.cite_block(m, bib), encoding="utf-8")
    target = paths.extra_dir() / citation.NOTEBOOKS_SUBDIR
    shutil.rmtree(target, ignore_errors=True)
    target.mkdir(parents=True)
    for notebook in sorted(paths.executed_dir().glob("*.ipynb")):  # for download: no local paths
        public_notebook(notebook, target / notebook.name)


def public_notebook(source: Path, target: Path) -> None:
    """Write the notebook ``source`` to ``target`` with each local absolute path of its metadata
    (the user's files, papermill's paths, the build area) replaced by the file's name or its
    repository path (:func:`sss_locus.paths.public_values`)."""
    nb = json.loads(source.read_text(encoding="utf-8"))
    nb["metadata"] = paths.public_values(nb.get("metadata") or {})
    target.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


def public_sources(html_dir: Path) -> None:
    """The built site's copies of its source notebooks (``_sources/**/*.ipynb``, which each page's
    download button links) made public in place, as the ``notebooks/`` copies are
    (:func:`public_notebook`): Sphinx copies the staged executed notebooks with their metadata."""
    for notebook in sorted((html_dir / "_sources").rglob("*.ipynb")):
        public_notebook(notebook, notebook)


def stage_config(root: Path, exclude: list[str] | None = None, front_page: Path | None = None) -> None:
    """Copy ``_config.yml``, turning the repository buttons on when ``repository.url`` is set,
    giving the pages the package's version as the substitution ``{{ version }}`` and leaving out
    the source files ``exclude`` (the executed copies of failed chapters). In a named build area
    the staged ``front_page`` and every page's header say what the book was built from
    (:mod:`sss_locus.pipeline.book.areanotice`)."""
    import yaml

    config = yaml.safe_load(paths.CONFIG_FILE.read_text(encoding="utf-8"))
    if exclude:
        config["exclude_patterns"] = [*config.get("exclude_patterns", []), *exclude]
    config.setdefault("parse", {}).setdefault("myst_substitutions", {})["version"] = provenance.package_version()
    if citation.repository_url():
        config.setdefault("html", {}).update(use_repository_button=True, use_issues_button=True)
    if front_page is not None:
        areanotice.stage(root, front_page, config)
    (root / paths.CONFIG_FILE.name).write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")


def paper_input_records() -> dict[str, Any]:
    """Each registered notebook's recorded comparison with the paper's inputs (``None`` when its
    executed copy has none), see :func:`sss_locus.pipeline.book.paperinputs.compare`."""
    from sss_locus.pipeline.run.registry import load_registry

    records = {}
    for entry in load_registry().values():
        nb = outputs.read_notebook(entry.executed_path()) if entry.executed_path().is_file() else None
        records[entry.name] = ((nb or {}).get("metadata", {}).get("sss_locus") or {}).get("paper_inputs")
    return records


def stage_claims_notice(page: Path, records: dict[str, Any] | None = None) -> None:
    """Put :func:`sss_locus.pipeline.book.paperinputs.claims_notice` of ``records`` (default: the
    executed copies', :func:`paper_input_records`) under the first heading of the staged claims
    ``page``; when a chapter lacks a paper platform, the notice replaces the rest of the page (its
    table quotes numbers those chapters did not compute)."""
    notice, replace = paperinputs.claims_notice(paper_input_records() if records is None else records)
    if not notice:
        return
    lines = page.read_text(encoding="utf-8").splitlines(keepends=True)
    head = next((i for i, line in enumerate(lines) if line.startswith("# ")), None)
    if head is None:
        raise ValueError(f"{page} must start with a '# ' heading (the claims notice goes under it)")
    rest = [] if replace else ["\n", *lines[head + 1:]]
    page.write_text("".join([*lines[:head + 1], "\n", notice, *rest]), encoding="utf-8")


def stage(failed: dict[str, str] | None = None) -> Path:
    """Copy the book source into the build area and generate the figures page; return the root.

    ``failed`` (``{chapter: problem}``, a named build only) chapters get a page saying so in place
    of their executed copy, and their figures are left out
    (:mod:`sss_locus.pipeline.book.failedchapters`)."""
    from sss_locus.pipeline.run.registry import load_registry

    failed, entries = failed or {}, load_registry()
    root = paths.source_dir()
    root.mkdir(parents=True, exist_ok=True)
    excluded = failedchapters.stage_stubs(root, failed, entries)

    def manifests(**kinds) -> list[dict[str, Any]]:
        return failedchapters.without_chapters(export.load_manifests(**kinds), failed, entries)

    shutil.copy2(paths.TOC_FILE, root / paths.TOC_FILE.name)
    staged_book = root / paths.BOOK_DIR.name
    shutil.rmtree(staged_book, ignore_errors=True)
    shutil.copytree(paths.BOOK_DIR, staged_book)
    stage_config(root, excluded, front_page=staged_book / FRONT_PAGE)
    paths.figures_dir().mkdir(parents=True, exist_ok=True)
    copy_mathjax()
    copy_plotly()
    stage_figure_pages(root, manifests())
    claimsindex.stage_claims_index(staged_book / CLAIMS_PAGE)  # the notice, if any, goes above it
    stage_claims_notice(staged_book / CLAIMS_PAGE)
    for name, marker, generated in (
            (FIGURES_PAGE, FIGURES_MARKER,
             lambda: figindex.figures_index(figindex.in_book_order(manifests(kinds=("fig", "tab"))))),
            (CITE_PAGE, PROJECT_BIBTEX_MARKER, lambda: f"```bibtex\n{citation.project_bibtex()}```")):
        text = (staged_book / name).read_text(encoding="utf-8")
        if marker not in text:
            raise ValueError(f"{paths.BOOK_DIR / name} must contain the line {marker}")
        (staged_book / name).write_text(text.replace(marker, generated()), encoding="utf-8")
    return root


def missing_toc_files(root: Path) -> list[str]:
    """Files listed in the staged ``_toc.yml`` that do not exist (e.g. a notebook never run)."""
    import yaml

    toc = yaml.safe_load((root / paths.TOC_FILE.name).read_text(encoding="utf-8"))
    wanted: list[str] = []

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                if key in ("root", "file") and isinstance(value, str):
                    wanted.append(value)
                else:
                    walk(value)
        elif isinstance(node, list):
            for item in node:
                walk(item)

    walk(toc)
    return [f for f in wanted if not any((root / (f + ext)).is_file() for ext in ("", ".md", ".ipynb"))]


class _PageScan(HTMLParser):
    """Collect local resource references and visible text (outside code, scripts and styles)."""

    SKIP = {"pre", "code", "script", "style", "textarea"}

    def __init__(self) -> None:
        super().__init__()
        self.refs: list[tuple[str, str]] = []  # (tag.attr, url)
        self.text: list[str] = []
        self._skip = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        if tag in ("img", "script", "source") and values.get("src"):
            self.refs.append((f"{tag}.src", values["src"]))
        if tag == "link" and values.get("href") and values.get("rel") in ("stylesheet", "icon"):
            self.refs.append(("link.href", values["href"]))
        if tag == "a" and values.get("href") and any(
                f"/{folder}/" in "/" + values["href"] for folder in ("figures", "notebooks")):
            self.refs.append(("a.href", values["href"]))
        if tag in self.SKIP:
            self._skip += 1

    def handle_endtag(self, tag: str) -> None:
        if tag in self.SKIP and self._skip:
            self._skip -= 1

    def handle_data(self, data: str) -> None:
        if not self._skip:
            self.text.append(data)


def site_problems(html_dir: Path) -> list[str]:
    """Problems in a built site that ``-W`` does not catch.

    Reports every local ``<img>``/``<script>``/``<source>`` ``src``, stylesheet and link into
    ``figures/`` that points to a missing file (for instance a glued image whose notebook never
    displayed it), and every unresolved glue reference left as text (``{glue...}``).
    """
    problems = []
    for page in sorted(Path(html_dir).rglob("*.html")):
        if page.relative_to(html_dir).parts[0] in ("_static", "_sources", "mathjax", "figures", "plotly"):
            continue  # theme templates and copied assets, not pages
        scan = _PageScan()
        scan.feed(page.read_text(encoding="utf-8", errors="replace"))
        rel = page.relative_to(html_dir)
        for what, url in scan.refs:
            parts = urlsplit(url)
            if parts.scheme or parts.netloc or url.startswith("#"):
                continue
            target = (page.parent / unquote(parts.path)).resolve()
            if not target.is_file():
                problems.append(f"{rel}: {what} {url!r} does not exist")
        text = " ".join(scan.text)
        for marker in ("{glue", "glue:text", "glue:figure", "glue:any", "glue:math"):
            if marker in text:
                problems.append(f"{rel}: unresolved glue reference ({marker!r} in the page text)")
                break
    return problems


def check_executed(allow_failed: bool = False) -> dict[str, str]:
    """Refuse, in one message, executed copies that cannot make one book (see
    :func:`sss_locus.pipeline.run.outputs.problems`). With ``allow_failed`` (a named build), chapters
    whose copy failed or is missing are returned (``{name: problem}``) instead of refused."""
    from sss_locus.pipeline.run.registry import load_registry

    entries = list(load_registry().values())
    failed = failedchapters.failed_chapters(entries) if allow_failed else {}
    found = outputs.problems([e for e in entries if e.name not in failed])
    if found:
        raise ValueError(
            f"cannot build the book: {len(found)} executed cop{'y is' if len(found) == 1 else 'ies are'} "
            "not part of one consistent, successful set (rerun with `sss-locus run <name>` or "
            "`sss-locus book`):\n  " + "\n  ".join(found))
    return failed


def check_sources_and_tools() -> None:
    """Refuse, in one line and before any notebook runs, a book that cannot be built here: its
    sources (``_config.yml``, ``_toc.yml``, ``book/``: the checkout's, or the installed package's
    copies, :data:`sss_locus.paths.REPO_ROOT`) or Jupyter Book and the site's local assets (the
    package's ``book`` extra) missing."""
    missing = [p.name for p in (paths.CONFIG_FILE, paths.TOC_FILE) if not p.is_file()]
    missing += [] if (paths.BOOK_DIR / FRONT_PAGE).is_file() else [paths.BOOK_DIR.name + "/"]
    if missing:
        where = ("the checkout" if paths.IN_CHECKOUT else "the installed package (a wheel built without them)")
        advice = "" if paths.IN_CHECKOUT else ": build the book from a checkout of the repository"
        raise FileNotFoundError(f"the book's sources {', '.join(missing)} are missing from {where}, "
                                f"{paths.REPO_ROOT}{advice}")
    tools = [name for name in ("jupyter-book", MATHJAX_DIST, "plotly", "papermill") if not _installed(name)]
    if tools:
        raise RuntimeError(f"building the book needs {', '.join(tools)} (the package's book extra: "
                           "pip install 'sss-locus[book]')")


def _installed(distribution: str) -> bool:
    try:
        metadata.distribution(distribution)
    except metadata.PackageNotFoundError:
        return False
    return distribution != "jupyter-book" or Path(sys.executable).with_name("jupyter-book").is_file()


def build(log=print) -> Path:
    """Check the executed copies, stage and build the site with ``jupyter-book build -W -n
    --keep-going --all``; return index.html.

    In a named build area a failed chapter does not stop the book: its page says it failed
    (:mod:`sss_locus.pipeline.book.failedchapters`), the build runs without ``-W`` and the problems it
    causes on other pages are listed instead of refused. Holds the build area's lock throughout,
    so no run commits new results mid-build and two builds never share Jupyter Book's output folder.
    """
    with outputs.build_lock():
        failed = check_executed(allow_failed=paths.build_name() is not None)
        for name, problem in failed.items():
            log(f"warning: chapter {problem}; the book is built, and that chapter's page says so")
        return _build(log, failed)


def _build(log, failed: dict[str, str] | None = None) -> Path:
    root = stage(failed)
    missing = missing_toc_files(root)
    if missing:
        raise FileNotFoundError(
            "_toc.yml lists files that are not in the build area (run their notebooks first, "
            f"e.g. `sss-locus book`): {', '.join(missing)}"
        )
    jupyter_book = Path(sys.executable).with_name("jupyter-book")
    env = {**os.environ, **hermetic_env()}
    output = paths.jupyter_book_dir()
    flags = [f for f in JB_FLAGS if f != "-W"] if failed else list(JB_FLAGS)
    cmd = [str(jupyter_book), "build", str(root), "--path-output", str(output), *flags]
    log("$ " + " ".join(cmd))
    problems: list[str] = []
    with subprocess.Popen(cmd, env=env, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, errors="replace") as proc:
        assert proc.stdout is not None
        shown = StagingPathFilter(plain=not sys.stdout.isatty())
        for line in proc.stdout:
            sys.stdout.writelines(shown.feed(line))
            if "WARNING" in line or "ERROR" in line or "CRITICAL" in line:
                problems.append(ANSI.sub("", line).strip())
        sys.stdout.writelines(shown.flush())
    if proc.returncode != 0:
        listing = "\n  ".join(problems) or "(no WARNING/ERROR lines; see the output above)"
        raise RuntimeError(f"jupyter-book build failed (exit {proc.returncode}):\n  {listing}")
    built = output / "_build" / "html"
    if not (built / "index.html").is_file():
        raise RuntimeError(f"jupyter-book build finished but {built / 'index.html'} is missing")
    public_sources(built)
    problems = site_problems(built)
    if problems and failed:
        log("warning: pages that quote the failed chapter(s):\n  " + "\n  ".join(problems))
    elif problems:
        raise RuntimeError("the built site has broken references:\n  " + "\n  ".join(problems))
    publish_site(built, paths.html_dir())
    return paths.index_html()


def publish_site(built: Path, target: Path) -> None:
    """Move a checked site from ``built`` to ``target``, replacing the previous site only now.

    The old site is renamed aside first and removed after the new one is in place, so a reader
    of ``target`` sees the old site or the new one, never a half-copied mix.
    """
    target.parent.mkdir(parents=True, exist_ok=True)
    old = target.with_name(f".{target.name}.old-{os.getpid()}")
    if target.exists():
        os.replace(target, old)
    os.replace(built, target)
    shutil.rmtree(old, ignore_errors=True)
