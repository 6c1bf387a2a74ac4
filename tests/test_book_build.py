"""The whole book from the `quick` profile: every registered notebook runs through papermill,
the site builds with warnings as errors, and the built HTML has no broken references.

The build goes to a temporary build area (``SSS_LOCUS_BUILD_DIR``), so the `book`-profile outputs
of ``make book`` in ``_build/`` are never overwritten.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from html import unescape
from pathlib import Path

import pytest

pytest.importorskip("jupyter_book")

from sss_locus import paths  # noqa: E402
from sss_locus.pipeline import bookbuild
from sss_locus.pipeline.export import load_manifests  # noqa: E402
from sss_locus.pipeline.registry import load_registry  # noqa: E402

pytestmark = pytest.mark.book  # deselect with `pytest -m "not book"` for a fast run

REGISTRY = load_registry()
TIMEOUT_S = 480


@pytest.fixture(scope="module")
def quick_book(tmp_path_factory):
    area = tmp_path_factory.mktemp("quick-book")
    default_index = paths.REPO_ROOT / "_build" / "html" / "index.html"
    before = default_index.stat().st_mtime_ns if default_index.exists() else None
    env = {**os.environ, paths.BUILD_DIR_ENV: str(area)}
    result = subprocess.run(
        [sys.executable, "-m", "sss_locus.pipeline.cli", "book", "--profile", "quick"],
        env=env, capture_output=True, text=True, timeout=TIMEOUT_S, stdin=subprocess.DEVNULL,
    )
    if result.returncode != 0:
        pytest.fail(f"sss-locus book --profile quick failed:\n{result.stdout[-6000:]}\n{result.stderr[-6000:]}")
    after = default_index.stat().st_mtime_ns if default_index.exists() else None
    assert before == after, "the test build touched the default build area"
    html = area / "html"
    return {"area": area, "html": html, "stdout": result.stdout}


def test_build_prints_the_index_path(quick_book):
    index = quick_book["html"] / "index.html"
    assert index.is_file()
    assert quick_book["stdout"].strip().splitlines()[-1] == str(index)


@pytest.mark.parametrize("name", list(REGISTRY))
def test_notebook_ran_under_quick_profile(quick_book, name):
    entry = REGISTRY[name]
    executed = quick_book["area"] / "source" / entry.executed
    nb = json.loads(executed.read_text())
    assert nb["metadata"]["sss_locus"]["profile"] == "quick"
    assert nb["metadata"]["papermill"]["exception"] in (None, False)
    errors = [o for c in nb["cells"] for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    if entry.parameters():
        injected = [c for c in nb["cells"] if "injected-parameters" in c["metadata"].get("tags", [])]
        assert len(injected) == 1 and "hide-input" in injected[0]["metadata"]["tags"]
    page = quick_book["html"] / Path(entry.executed).with_suffix(".html")
    assert page.is_file()
    if entry.parameters():  # the collapsed block with this run's parameters
        assert "Show this run's parameters (profile 'quick')" in unescape(page.read_text())


def test_site_has_no_broken_images_or_unresolved_glue(quick_book):
    assert bookbuild.site_problems(quick_book["html"]) == []


def test_every_exported_figure_is_served_and_indexed(quick_book):
    manifests = load_manifests(quick_book["area"] / "source" / "_extra" / "figures")
    figures_page = (quick_book["html"] / "book" / "figures.html").read_text()
    for manifest in manifests:
        for entry in manifest["files"].values():
            assert (quick_book["html"] / entry["url"]).is_file()
        assert (quick_book["html"] / "figures" / f"{manifest['label']}.json").is_file()
        assert f"sss-locus:{manifest['label']}" in figures_page


def test_math_is_served_locally(quick_book):
    html = quick_book["html"]
    pages_with_math = 0
    for page in html.rglob("*.html"):
        if page.relative_to(html).parts[0] in ("_static", "mathjax", "_sources"):
            continue
        text = page.read_text()
        assert "cdn.jsdelivr.net/npm/mathjax" not in text, page
        if 'class="math' in text:
            pages_with_math += 1
            assert "mathjax/tex-chtml.js" in text, page
    assert pages_with_math >= 1  # the introduction has an equation
    assert (html / "mathjax" / "tex-chtml.js").is_file()
    assert (html / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()


def test_site_checker_reports_missing_images_and_unresolved_glue(tmp_path):
    (tmp_path / "ok.png").write_bytes(b"png")
    (tmp_path / "page.html").write_text(
        '<html><body><img src="ok.png"><img src="gone.png"><img src="data:image/png;base64,AA==">'
        '<img src="https://example.org/x.png"><a href="figures/fig-x.pdf">pdf</a>'
        '<pre>{glue:text}`shown as code`</pre></body></html>'
    )
    (tmp_path / "glue.html").write_text("<p>The length is {glue:text}`nb.ipynb::length:.2f` m.</p>")
    problems = bookbuild.site_problems(tmp_path)
    assert problems == [
        "glue.html: unresolved glue reference ('{glue' in the page text)",
        "page.html: img.src 'gone.png' does not exist",
        "page.html: a.href 'figures/fig-x.pdf' does not exist",
    ]


def test_figures_index_lists_only_registered_notebooks_in_book_order():
    registered = [entry.source_relative for entry in REGISTRY.values()]
    if not registered:
        pytest.skip("no registered notebooks")
    manifests = [
        {"label": "fig-b", "notebook": registered[-1]},
        {"label": "fig-z", "notebook": "interactive"},
        {"label": "fig-a", "notebook": registered[0]},
        {"label": "fig-c", "notebook": "notebooks/removed.ipynb"},
    ]
    listed = [m["label"] for m in bookbuild._in_book_order(manifests)]
    assert listed == ["fig-a", "fig-b"]
