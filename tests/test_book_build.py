"""The whole book from the `quick` profile: every registered notebook runs through papermill,
the site builds with warnings as errors, and the built HTML has no broken references.

The quick book is built in the background while the other tests run (``conftest.py``,
``book_support.py``); it goes to a temporary build area (``SSS_LOCUS_BUILD_DIR``), so the `book`-profile outputs
of ``make book`` in ``_build/`` are never overwritten.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from html import unescape
from pathlib import Path

import pytest

pytest.importorskip("jupyter_book")

from book_support import TIMEOUT_S  # noqa: E402  (the quick_book fixture is in conftest.py)
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline import bookbuild
from sss_locus.pipeline.export import load_manifests  # noqa: E402
from sss_locus.pipeline.registry import load_registry  # noqa: E402

pytestmark = pytest.mark.book  # deselect with `pytest -m "not book"` for a fast run

REGISTRY = load_registry()


def test_build_prints_the_index_path(quick_book):
    index = quick_book["html"] / "index.html"
    assert index.is_file()
    assert quick_book["stdout"].strip().splitlines()[-1] == str(index)
    closing = quick_book["stdout"].rsplit("build succeeded", 1)[-1]  # jupyter-book's closing lines
    assert "jupyter-book/_build/html" not in closing  # no pointer to its staging site (moved away)


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


def test_every_published_figure_is_readable_at_the_column_width(quick_book):
    """Every exported figure's smallest drawn text (tick labels, legends, colour bars,
    annotations, titles) is at least 9 CSS px when the figure is shown in the book's content
    column (660 px: an image in the main column of a built page in a 1280 px wide window,
    measured with headless Chromium; see :mod:`sss_locus.pipeline.readability`)."""
    from sss_locus.pipeline import readability

    manifests = load_manifests(quick_book["area"] / "source" / "_extra" / "figures")
    assert len(manifests) >= 10
    small = []
    for m in manifests:
        px = readability.smallest_text_px(m)
        if px is not None and px < readability.MIN_TEXT_PX:
            t = m["text"]
            small.append(f"{m['label']}: {t['min_text']!r} at {t['min_size_pt']:g} pt in a "
                         f"{t['width_in']:.1f} in wide picture is {px:.1f} px")
    assert not small, "text smaller than 9 px at the column width:\n" + "\n".join(small)


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


def test_each_figure_page_has_its_files_source_and_citation(quick_book):
    """Under each figure on its own page: files, data CSVs, a link to the code cell that drew it
    (an anchor in that cell's output), the executed notebook for download, and the BibTeX."""
    html = quick_book["html"]
    manifests = load_manifests(quick_book["area"] / "source" / "_extra" / "figures")
    by_notebook = {entry.source_relative: entry for entry in REGISTRY.values()}
    assert manifests
    for m in manifests:
        if m["notebook"] not in by_notebook:
            continue
        entry = by_notebook[m["notebook"]]
        page = html / Path(entry.executed).with_suffix(".html")
        text = unescape(page.read_text())
        label = m["label"]
        assert f'id="{label}-cite"' in text, (label, page)
        assert f'id="{label}-source"' in text and f'href="#{label}-source"' in text
        assert f"code cell [{m['cell']}]" in text and isinstance(m["cell"], int)
        for name in m["files"]:
            if name.endswith((".csv", ".png", ".pdf", ".svg")):
                assert f'href="../figures/{name}"' in text, (label, name)
        notebook = Path(entry.executed).name
        assert f'href="../notebooks/{notebook}"' in text
        assert (html / "notebooks" / notebook).is_file()
        assert f"@misc{{sss-locus:{label}," in re.sub(r"<[^>]+>", "", text)  # highlighted code


def test_every_figure_bibtex_entry_parses_and_compiles(quick_book, tmp_path):
    """One LaTeX document cites every figure's entry and the project's own (from CITATION.cff);
    pdflatex + bibtex compile it with no warning (``latex_check``)."""
    pybtex_database = pytest.importorskip("pybtex.database")
    import sss_locus
    from sss_locus.pipeline import citation

    figures = quick_book["area"] / "source" / "_extra" / "figures"
    bibs = sorted(figures.glob("fig-*.bib"))
    assert len(bibs) >= 10
    text = "\n".join(b.read_text(encoding="utf-8") for b in bibs)
    entries = pybtex_database.parse_string(text, "bibtex").entries
    assert len(entries) == len(bibs)
    for key, entry in entries.items():
        assert len(entry.fields["title"]) < 200, key
        for field in ("title", "year", "version", "note"):
            assert entry.fields.get(field), (key, field)
        assert entry.fields["version"] == sss_locus.__version__, key
        assert entry.persons["author"], key
    cite_page = unescape((quick_book["html"] / "book" / "cite.html").read_text())
    assert f"version {sss_locus.__version__}" in cite_page and "@misc{sss-locus," in re.sub(r"<[^>]+>", "", cite_page)
    if not (shutil.which("pdflatex") and shutil.which("bibtex")):
        pytest.skip("no TeX installation (pdflatex, bibtex) to compile the entries")
    from latex_check import compile_latex

    compile_latex(tmp_path, citation.project_bibtex() + "\n" + text, ["sss-locus", *entries])


def test_interactive_concept_view_is_served_locally(quick_book):
    html = quick_book["html"]
    page = (html / "executed" / "concept.html").read_text()
    assert 'id="fig-locus-concept-3d"' in page
    assert 'src="../plotly/plotly.min.js"' in page
    assert (html / "plotly" / "plotly.min.js").stat().st_size > 1_000_000
    for other in html.rglob("*.html"):
        assert "cdn.plot.ly" not in other.read_text(errors="replace"), other


def _chromium():
    import shutil

    return next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(n)), None)


def test_interactive_view_renders_with_the_network_blocked(quick_book):
    browser = _chromium()
    if browser is None:
        pytest.skip("no headless Chromium")
    page = quick_book["html"] / "executed" / "concept.html"
    common = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--disable-background-networking", "--proxy-server=127.0.0.1:9",
              "--proxy-bypass-list=<-loopback>", f"--user-data-dir={quick_book['area'] / 'chromium'}",
              "--virtual-time-budget=15000"]
    dom = subprocess.run([*common, "--dump-dom", page.as_uri()], capture_output=True, text=True,
                         timeout=180).stdout
    # plotly.js, once it has run, adds these to the figure's div (not in the served HTML).
    assert "js-plotly-plot" in dom and "modebar" in dom
    shot = quick_book["area"] / "concept-offline.png"
    subprocess.run([*common, "--window-size=1280,2400", f"--screenshot={shot}", page.as_uri()],
                   capture_output=True, timeout=180)
    assert shot.is_file() and shot.stat().st_size > 10_000


# -- a user's platform through the whole book -----------------------------------------------------

EXAMPLE = paths.REPO_ROOT / "data" / "examples" / "my_auv.toml"


@pytest.fixture(scope="module")
def user_book(quick_book, tmp_path_factory):
    """The quick book again, in a copy of ``quick_book``'s build area and with its cache (so the
    shipped platforms' studies are cache hits), with the example file's ``my_auv`` beside the
    paper's AUV and without the boat: a user platform added and a paper platform replaced."""
    work = tmp_path_factory.mktemp("user-book")
    area = work / "build"
    shutil.copytree(quick_book["area"], area, ignore=shutil.ignore_patterns("html", "jupyter-book"))
    user = work / "my_auv.toml"
    shutil.copy(EXAMPLE, user)
    env = {**quick_book["env"], paths.BUILD_DIR_ENV: str(area)}
    result = subprocess.run(
        [sys.executable, "-m", "sss_locus.pipeline.cli", "book", "--profile", "quick", "--data", str(user),
         "-p", "platforms", '["my_auv", "auv"]'],
        env=env, capture_output=True, text=True, timeout=TIMEOUT_S, stdin=subprocess.DEVNULL)
    if result.returncode != 0:
        pytest.fail(f"user-platform book failed:\n{result.stdout[-6000:]}\n{result.stderr[-6000:]}")
    return {"area": area, "html": area / "html", "user": user, "env": env}


def _csv_hashes(area: Path) -> dict[str, str]:
    import hashlib

    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest()
            for p in (area / "source" / "_extra" / "figures").glob("*.csv")}


def test_user_platform_book_builds_and_places_every_figure(user_book):
    html = user_book["html"]
    assert bookbuild.site_problems(html) == []
    pose = unescape((html / "executed" / "pose_space.html").read_text())
    for label in ("fig-sensitivity-my-auv", "fig-heatmaps-my-auv", "fig-sensitivity-auv", "fig-heatmaps-auv"):
        assert f'id="{label}"' in pose
    assert "fig-heatmaps-boat" not in pose
    assert "is left out here: this run does not include" in pose  # prose written for both
    figures = (html / "book" / "figures.html").read_text()
    assert "sss-locus:fig-heatmaps-my-auv" in figures and "sss-locus:fig-heatmaps-boat" not in figures


def test_claims_page_says_the_inputs_are_not_the_papers(user_book):
    claims = unescape((html := user_book["html"] / "book" / "claims.html").read_text())
    assert "This build does not use the paper" in claims and "does not include `boat`" in claims.replace(
        "<code class=\"docutils literal notranslate\"><span class=\"pre\">boat</span></code>", "`boat`")
    assert "<table" not in claims, html  # verdicts written for the paper's inputs are not shown


def test_user_figures_name_the_users_platform_and_values(user_book):
    manifests = {m["label"]: m for m in load_manifests(user_book["area"] / "source" / "_extra" / "figures")}
    for label in ("fig-sensitivity-my-auv", "fig-survey-passes", "fig-noise-crossing", "fig-rigs"):
        m = manifests[label]
        values = m["data_inputs"]["values"]["my_auv"]
        assert values["sonar"]["azimuth_deg"] == 40.0 and values["tilt_deg"]["port"] == 15.0
        assert any(f["role"] == "user" and f["path"] == str(user_book["user"]) for f in m["data_inputs"]["files"])
        bib = (user_book["area"] / "source" / "_extra" / "figures" / f"{label}.bib").read_text()
        assert "my\\_auv (Example AUV" in bib and "40 x 0.2 deg, 100 m, tilt 15 deg" in bib
        assert "Example AUV" in m["caption"]


def test_shipped_figures_keep_their_labels_and_data(quick_book, user_book):
    """Adding a platform changes no figure of a shipped one: each per-platform figure of the AUV
    has the same label and byte-identical data files as in the default build."""
    before, after = _csv_hashes(quick_book["area"]), _csv_hashes(user_book["area"])
    auv = {name: h for name, h in before.items() if name.startswith(("fig-sensitivity-auv", "fig-heatmaps-auv"))}
    assert auv and all(after.get(name) == h for name, h in auv.items())


def test_editing_one_user_value_makes_exactly_its_readers_stale(user_book):
    env = user_book["env"]
    script = ("import json, sys; from sss_locus.pipeline import outputs, registry; "
              "print(json.dumps(sorted(e.name for e in registry.load_registry().values() "
              "if outputs.problems([e]))))")

    def stale():
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        return set(json.loads(out.stdout))

    assert stale() == set()
    user = user_book["user"]
    text = user.read_text()
    user.write_text(text.replace("roll_sigma_deg = { value = 0.1", "roll_sigma_deg = { value = 0.2"))
    assert stale() == {"noise", "three_views"}  # the two chapters that read noise models
    user.write_text(text.replace("max_range_m = { value = 100.0", "max_range_m = { value = 90.0"))
    readers = {n for n, e in REGISTRY.items() if "platforms" in e.parameters()}
    assert stale() == readers  # every chapter that reads the platform
    user.write_text(text)
    assert stale() == set()
