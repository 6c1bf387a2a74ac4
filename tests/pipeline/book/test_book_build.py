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
from test_paperinputs import PLATFORM_FROM_INPUT  # noqa: E402
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.book import bookbuild, figindex
from sss_locus.pipeline.publish.export import load_manifests  # noqa: E402
from sss_locus.pipeline.run.registry import load_registry  # noqa: E402

pytestmark = pytest.mark.book  # deselect with `pytest -m "not book"` for a fast run

REGISTRY = load_registry()


def test_build_prints_the_index_path(quick_book):
    index = quick_book["html"] / "index.html"
    assert index.is_file()
    assert quick_book["stdout"].strip().splitlines()[-1] == str(index)
    closing = quick_book["stdout"].rsplit("build succeeded", 1)[-1]  # jupyter-book's closing lines
    assert "jupyter-book/_build/html" not in closing  # no pointer to its staging site (moved away)


def test_build_log_shows_each_notebook_without_terminal_codes(quick_book):
    """Not on a terminal (the build's stdout is a file): a start line with the time and an end
    line with the duration per notebook, a count of notebooks done, no terminal codes."""
    runs = quick_book["stdout"].split("\n$ ", 1)[0]  # the notebooks' part, before jupyter-book's output
    for name in REGISTRY:
        assert re.search(rf"^start {name} \[quick\] at \d\d:\d\d:\d\d UTC$", runs, re.M), name
        assert re.search(rf"^ran {name} \[quick\] in \d+\.\d s -> ", runs, re.M), name
    assert f"  {len(REGISTRY)}/{len(REGISTRY)} notebooks done" in runs
    assert "\x1b[" not in runs and "\r" not in runs


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
    if entry.parameters():  # the visible cell shows the run's values; the collapsed block its data files
        text = unescape(page.read_text())
        assert "The values this run used (profile 'quick')" in text and "Show the data files this run read" in text


def test_survey_design_noise_table_marks_the_recommended_plan_of_the_plans_table(quick_book):
    import pandas as pd

    figures = quick_book["area"] / "source" / "_extra" / "figures"
    plans = pd.read_csv(figures / "tab-survey-design-plans.csv")
    noise = pd.read_csv(figures / "tab-survey-design-noise.csv")
    for platform, rows in noise.groupby("platform"):
        rec = rows[rows.kind.str.endswith(" = recommended")]
        planned = plans[(plans.platform == platform) & plans.kind.str.endswith(" = recommended")]
        assert len(rec) == 1 and len(planned) == 1, platform
        assert rec.kind.iloc[0] == planned.kind.iloc[0]
        assert rec.total_m.iloc[0] / 1e3 == pytest.approx(planned.track_km.iloc[0], rel=1e-12)


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
    tables = load_manifests(quick_book["area"] / "source" / "_extra" / "figures", kinds=("tab",))
    assert len(tables) >= 20  # every chapter's published tables are indexed with their files
    for manifest in tables:
        assert f"sss-locus:{manifest['label']}" in figures_page, manifest["label"]
        assert f'href="../figures/{manifest["label"]}.csv"' in figures_page
    assert figures_page.index('id="tables"') > figures_page.index('id="figures"')


def test_every_published_figure_is_readable_at_the_column_width(quick_book):
    """Every exported figure's smallest drawn text (tick labels, legends, colour bars,
    annotations, titles) is at least 9 CSS px when the figure is shown in the book's content
    column (660 px: an image in the main column of a built page in a 1280 px wide window,
    measured with headless Chromium; see :mod:`sss_locus.pipeline.publish.readability`)."""
    from sss_locus.pipeline.publish import readability

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
    listed = [m["label"] for m in figindex.in_book_order(manifests)]
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
    """One LaTeX document cites every figure's and table's entry and the project's own (from
    CITATION.cff); pdflatex + bibtex compile it with no warning (``latex_check``)."""
    pybtex_database = pytest.importorskip("pybtex.database")
    import sss_locus
    from sss_locus.pipeline.publish import citation

    figures = quick_book["area"] / "source" / "_extra" / "figures"
    bibs = sorted(figures.glob("fig-*.bib"))
    assert len(bibs) >= 10
    tables = sorted(figures.glob("tab-*.bib"))
    assert len(tables) >= 20
    bibs += tables
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


# -- the your-hardware page, run in order on a built book ------------------------------------------

EXAMPLE = paths.REPO_ROOT / "data" / "examples" / "my_auv.toml"
PAGE = paths.BOOK_DIR / "your_hardware.md"


def page_commands(kind: str = "bash", program: str = "sss-locus") -> list[list[str]]:
    """The ``program`` commands of the page's ``kind`` code blocks, in order, as argument lists
    (``text`` blocks: the commands after a ``$`` prompt, shown there with their refusal)."""
    import re
    import shlex

    out = []
    for block in re.findall(rf"```{kind}\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S):
        for line in block.replace("\\\n", " ").splitlines():
            if kind == "text" and not line.startswith("$ "):
                continue  # a command's output
            line = line.strip().removeprefix("$ ")
            if line.startswith(f"{program} "):
                out.append(shlex.split(line, comments=True))
    return out


def _snapshot(area: Path) -> dict[str, str]:
    """SHA-256 of every file of the reproduction: its staged source (executed chapters, figures,
    manifests, BibTeX, pages) and its site (the claims page among them)."""
    import hashlib

    return {p.relative_to(area).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for top in ("source", "html") for p in sorted((area / top).rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def user_book(quick_book, tmp_path_factory):
    """Every ``sss-locus`` command of the your-hardware page, in order (quick profile, the example
    file copied so a test may edit it), on a copy of ``quick_book``'s build area with its cache
    (the paper's platforms are cache hits): the reproduction's files before and after, each
    command's output, and the areas the commands named."""
    work = tmp_path_factory.mktemp("user-book")
    area = work / "build"
    shutil.copytree(quick_book["area"], area, ignore=shutil.ignore_patterns("jupyter-book"))
    user = work / "my_auv.toml"
    shutil.copy(EXAMPLE, user)
    for _, source, target in page_commands(program="cp"):  # the files the page has you copy
        shutil.copy(paths.REPO_ROOT / source, work / target)
    env = {**quick_book["env"], paths.BUILD_DIR_ENV: str(area)}
    before = _snapshot(area)

    def run(argv: list[str]) -> subprocess.CompletedProcess:
        argv = [str(user) if a == "data/examples/my_auv.toml" else
                str(shutil.copy(paths.REPO_ROOT / a, work)) if a.startswith("data/examples/") and a.endswith(".toml")
                else a for a in argv[1:]]
        if argv[0] in ("run", "book") and "--profile" not in argv:
            argv += ["--profile", "quick"]
        return subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", *argv], env=env, cwd=work,
                              capture_output=True, text=True, timeout=TIMEOUT_S, stdin=subprocess.DEVNULL)

    refused = [run(argv) for argv in page_commands("text")]
    outputs = []
    for argv in page_commands("bash"):
        result = run(argv)
        if result.returncode != 0:
            pytest.fail(f"`{' '.join(argv)}` failed:\n{result.stdout[-6000:]}\n{result.stderr[-6000:]}")
        outputs.append((argv, result.stdout))
    return {"area": area, "user": user, "env": env, "before": before, "after": _snapshot(area),
            "refused": refused, "outputs": outputs,
            "my_auv": area / "my_auv", "beside": area / "beside"}


def test_the_page_runs_a_quick_answer_runs_and_a_book_each_into_its_own_area(user_book, request):
    if getattr(request.config.option, "loadgroup", False):  # set in xdist's workers
        # under `make test` (pytest-xdist, --dist loadgroup) this module's user_book tests form one
        # group (conftest.py), so the page's commands run on one worker only, once
        assert request.node.nodeid.endswith("@user_book"), request.node.nodeid
    commands = [argv[:2] for argv, _ in user_book["outputs"]]
    assert ["sss-locus", "answer"] in commands and ["sss-locus", "book"] in commands
    assert all("--name" in argv for argv, _ in user_book["outputs"] if argv[1] in ("run", "book"))
    answers = [out for argv, out in user_book["outputs"] if argv[1] == "answer"]
    assert all("prefer" in a and "Top drivers" in a for a in answers)
    for name in ("my_auv.toml", "my_blueboat.toml"):  # the AUV and the surface-boat examples
        assert any(f"{name} (user, sha256" in a for a in answers), name
    assert user_book["refused"] and all(r.returncode == 2 and "add --name NAME" in r.stderr
                                        for r in user_book["refused"])  # the page's refused example is


def test_the_reproduction_is_byte_identical_after_the_pages_examples(user_book):
    """The paper's figures (images, data, manifests, BibTeX), executed chapters and glued numbers,
    and the built site with its claims table: not one file added, removed or changed."""
    before, after = user_book["before"], user_book["after"]
    assert any(k.startswith("source/_extra/figures/fig-") and k.endswith(".bib") for k in before)
    assert "html/book/claims.html" in before and "<table" in (user_book["area"] / "html/book/claims.html").read_text()
    assert after == before


def test_user_platform_book_builds_and_places_every_figure(user_book):
    html = user_book["my_auv"] / "html"
    assert bookbuild.site_problems(html) == []
    pose = unescape((html / "executed" / "pose_space.html").read_text())
    for label in ("fig-sensitivity-my-auv", "fig-heatmaps-my-auv"):
        assert f'id="{label}"' in pose
    assert "fig-heatmaps-boat" not in pose and "fig-heatmaps-auv" not in pose
    # every verdict of the chapter is generated for any platform (one source per sentence): no
    # passage written for the paper's platforms to leave out, the findings from the user's numbers
    assert "are left out here" not in pose and "The raw locus length is ranked first by" in pose
    figures = (html / "book" / "figures.html").read_text()
    assert "sss-locus:my_auv:fig-heatmaps-my-auv" in figures and "fig-heatmaps-boat" not in figures


def test_claims_page_says_the_inputs_are_not_the_papers(user_book):
    claims = unescape((html := user_book["my_auv"] / "html" / "book" / "claims.html").read_text())
    assert "This build does not use the paper" in claims and "does not include `auv`" in claims.replace(
        "<code class=\"docutils literal notranslate\"><span class=\"pre\">auv</span></code>", "`auv`")
    assert "<table" not in claims, html  # verdicts written for the paper's inputs are not shown


#: Whole tables of shipped data files a chapter reads, by entry, and their files.
SHIPPED_TABLES = {"terrain": "data/terrain.toml", "survey": "data/terrain.toml",
                  "survey_design": "data/survey_design.toml"}


def test_user_figures_and_tables_cite_only_the_users_platform_and_inputs(user_book):
    figures = user_book["my_auv"] / "source" / "_extra" / "figures"
    manifests = {m["label"]: m for m in load_manifests(figures, kinds=("fig", "tab"))}  # tables too
    assert {"fig-sensitivity-my-auv", "fig-survey-passes", "fig-noise-crossing", "fig-rigs"} <= set(manifests)
    for label, m in manifests.items():
        inputs = m["data_inputs"]
        if Path(m["notebook"]).stem in PLATFORM_FROM_INPUT:  # its platform is named by its input file
            assert any(f.get("role") == "observations" for f in inputs["files"]), label
            continue
        assert inputs["platforms"] == ["my_auv"] and list(inputs["values"]) == ["my_auv"], label
        values = inputs["values"]["my_auv"]
        assert values["sonar"]["azimuth_deg"] == 40.0 and values["tilt_deg"]["port"] == 15.0
        files = {f["path"] for f in inputs["files"] if f.get("role") != "area"}
        if Path(m["notebook"]).stem == "survey_design":  # the area it planned over is an input file too
            assert len([f for f in inputs["files"] if f.get("role") == "area"]) == 1, label
        assert user_book["user"].name in files, label
        # a shipped file only for a shipped entry the figure read: the survey's offset models, the
        # seafloors and survey layout of the reconstruction, the survey-design conditions
        shipped = {e for e in inputs["entries"] if not e.endswith(("my_auv", "narrow_fan_450"))}
        assert all(e.startswith("offset_models.") or e in SHIPPED_TABLES for e in shipped), (label, shipped)
        expected = {"data/survey.toml" if e.startswith("offset_models.") else SHIPPED_TABLES[e] for e in shipped}
        assert files - {user_book["user"].name} == expected, label
        bib = (figures / f"{label}.bib").read_text()
        assert "my\\_auv (Example AUV" in bib and "40 x 0.2 deg, 100 m, tilt 15 deg" in bib
        assert "edgetech" not in bib.lower() and "omniscan" not in bib.lower() and "platforms.toml" not in bib
    assert "Example AUV" in manifests["fig-sensitivity-my-auv"]["caption"]


def test_a_paper_figure_computed_beside_the_users_cites_what_the_papers_does(quick_book, user_book):
    """In the area `beside` (the AUV and the user's platform in one run), the AUV's pose-space
    figures have the reproduction's data files, data inputs and BibTeX entry, byte for byte."""
    paper = quick_book["area"] / "source" / "_extra" / "figures"
    beside = user_book["beside"] / "source" / "_extra" / "figures"
    for label in ("fig-sensitivity-auv", "fig-heatmaps-auv"):
        ours, theirs = json.loads((beside / f"{label}.json").read_text()), json.loads((paper / f"{label}.json").read_text())
        assert ours["data_inputs"] == theirs["data_inputs"] and ours["data_inputs"]["platforms"] == ["auv"]
        # the same entry but for the build area, which names itself in the key and the note (issue 37:
        # the two figures are two entries of one document)
        ours_bib, paper_bib = (beside / f"{label}.bib").read_text(), (paper / f"{label}.bib").read_text()
        assert ours_bib.startswith(f"@misc{{sss-locus:beside:{label},") and ", build area \\texttt{beside}" in ours_bib
        assert (ours_bib.replace("sss-locus:beside:", "sss-locus:").replace(", build area \\texttt{beside}", "")
                == paper_bib)
        for name in ours["files"]:
            if name.endswith(".csv"):
                assert (beside / name).read_bytes() == (paper / name).read_bytes(), name
        mine = json.loads((beside / f"{label.replace('-auv', '-my-auv')}.json").read_text())["data_inputs"]
        assert mine["platforms"] == ["my_auv"] and [f["role"] for f in mine["files"]] == ["user"]


def test_editing_one_user_value_makes_exactly_its_readers_stale(user_book):
    env = {**user_book["env"], paths.BUILD_DIR_ENV: str(user_book["my_auv"])}
    script = ("import json, sys; from sss_locus.pipeline.run import context, outputs, registry\n"
              "with context.use(context.current().replace(build_name='my_auv')):\n"
              "    print(json.dumps(sorted(e.name for e in registry.load_registry().values() "
              "if outputs.problems([e]))))")

    def stale():
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        return set(json.loads(out.stdout))

    assert stale() == set()
    user = user_book["user"]
    text = user.read_text()
    user.write_text(text.replace("roll_sigma_deg = { value = 0.1", "roll_sigma_deg = { value = 0.2"))
    # the chapters that read noise models (survey design re-evaluates its plans with noise)
    assert stale() == {"noise", "reconstruction", "survey_design", "three_views"}
    user.write_text(text.replace("max_range_m = { value = 100.0", "max_range_m = { value = 90.0"))
    readers = {n for n, e in REGISTRY.items() if "platforms" in e.parameters()}
    assert stale() == readers  # every chapter that reads the platform
    user.write_text(text)
    assert stale() == set()


# -- tables a reader can read, measured in a real browser -----------------------------------------

TABLE_CHECK = """<script>
(() => {  // at the end of the body: the stylesheets are loaded, the tables laid out
  const found = [];
  document.querySelectorAll("article table").forEach((table, i) => {
    const name = `table ${i + 1} (${(table.querySelector("th") || table).textContent.trim().slice(0, 30)})`;
    const box = table.parentElement.getBoundingClientRect(), own = table.getBoundingClientRect();
    if (own.right > box.right + 1 || table.scrollWidth > table.clientWidth + 1)
      found.push(`${name} is wider than the text column: ${table.scrollWidth} px in ${Math.round(box.width)} px`);
    const caption = table.querySelector("caption");
    if (caption && caption.textContent.trim().length > 120
        && caption.getBoundingClientRect().width < Math.min(400, box.width - 1))
      found.push(`${name}: its caption is squeezed to ${Math.round(caption.getBoundingClientRect().width)} px`);
    table.querySelectorAll("td, th").forEach(cell => {
      if (cell.scrollWidth > cell.clientWidth + 1)
        found.push(`${name}: cell "${cell.textContent.trim().slice(0, 40)}" is narrower than its text`);
    });
  });
  const out = document.createElement("pre");
  out.id = "table-check";
  out.textContent = JSON.stringify(found);
  document.body.appendChild(out);
})();
</script>"""


def test_chapter_tables_fit_the_text_column_in_a_browser(quick_book, tmp_path):
    """Every table of every chapter, rendered by headless Chromium in a 1280 px window: none wider
    than the text column, no cell narrower than its text, no long caption squeezed to the width
    of a narrow table's few columns."""
    import re
    from html import unescape as html_unescape

    browser = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if browser is None:
        pytest.skip("no Chromium to render the pages")
    problems, tables = [], 0
    for page in sorted(p for p in (quick_book["html"] / "executed").glob("*.html") if not p.name.startswith(".")):
        text = page.read_text(encoding="utf-8")
        tables += text.count("<table")
        probe = page.with_name(f".{page.stem}-table-check.html")
        probe.write_text(text.replace("</body>", TABLE_CHECK + "</body>", 1), encoding="utf-8")
        try:
            dom = subprocess.run(
                [browser, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--proxy-server=127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
                 f"--user-data-dir={tmp_path / 'chromium'}", "--window-size=1280,1600", "--virtual-time-budget=10000",
                 "--dump-dom", probe.as_uri()], capture_output=True, text=True, timeout=180).stdout
        finally:
            probe.unlink(missing_ok=True)
        found = re.search(r'<pre id="table-check"[^>]*>(.*?)</pre>', dom, re.S)
        assert found, f"{page.name}: the check did not run"
        problems += [f"{page.name}: {p}" for p in json.loads(html_unescape(found.group(1)))]
    assert tables >= 10
    assert not problems, "\n".join(problems)


def test_every_published_table_is_shown_served_and_names_its_platforms(quick_book):
    """Each citable table (``tab-`` label) is served with its CSV and BibTeX, its manifest names
    platforms of its own run only, and the chapter that made it shows it under the caption its
    manifest records (the table a reader cites is the table they read)."""
    figures = quick_book["area"] / "source" / "_extra" / "figures"
    tables = load_manifests(figures, ("tab",))
    by_notebook = {entry.source_relative: entry for entry in REGISTRY.values()}
    assert len(tables) >= 20 and {m["notebook"] for m in tables} <= set(by_notebook)
    for m in tables:
        label, inputs = m["label"], m["data_inputs"]
        for entry in m["files"].values():
            assert (quick_book["html"] / entry["url"]).is_file(), (label, entry)
        assert sorted(m["files"]) == [f"{label}.bib", f"{label}.csv"]
        if Path(m["notebook"]).stem in PLATFORM_FROM_INPUT:  # one platform, named by its input file
            roles = [f["role"] for f in inputs["files"]]
            # the data set's platform, or (the real pass: a platform file of its own) that file by role
            assert (len(inputs["platforms"]) == 1
                    or (not inputs["platforms"] and roles.count("platform data") == 1)), label
            assert "observations" in roles, label
        else:
            assert inputs["platforms"] and set(inputs["platforms"]) <= set(m["parameters"]["platforms"]), label
        assert f"figures/{label}.csv" in m["caption"]
        page = quick_book["html"] / Path(by_notebook[m["notebook"]].executed).with_suffix(".html")
        captions = [" ".join(unescape(re.sub(r"<[^>]+>", "", c)).split())  # its **bold** and `code` as HTML
                    for c in re.findall(r"<caption>(.*?)</caption>", page.read_text(), re.S)]
        assert " ".join(re.sub(r"\*\*|`", "", m["caption"]).split()) in " ".join(captions), (label, page.name)


def truth_cited(figures: Path) -> list[str]:
    """The your-pings figures of the reproduction that draw the truth (the map's distances, the
    features' panels) but whose manifest or BibTeX entry does not name the truth file (the shipped
    example's, by its repository path) with its SHA-256."""
    import hashlib

    missing = []
    for label in ("fig-your-pings-map", "fig-your-pings-features"):
        m = json.loads((figures / f"{label}.json").read_text())
        truth = m["parameters"]["truth"]
        digest = hashlib.sha256((paths.REPO_ROOT / truth).read_bytes()).hexdigest()
        bib = (figures / f"{label}.bib").read_text()
        if ({"path": truth, "sha256": digest, "role": "truth"} not in m["data_inputs"]["files"]
                or f"{Path(truth).name.replace('_', chr(92) + '_')} (sha256 {digest[:12]})" not in bib):
            missing.append(label)
    return missing


def test_the_your_pings_figures_that_draw_the_truth_cite_its_file(quick_book):
    """The map's right panel (each estimate's distance from the true position) and the features'
    panels draw the truth file, but their manifest and BibTeX entry named only the sightings."""
    assert truth_cited(quick_book["area"] / "source" / "_extra" / "figures") == []


def test_the_sites_notebook_downloads_carry_no_path_of_the_build_machine(quick_book):
    """The pages' download button links ``_sources/executed/<name>.ipynb``: its metadata held
    papermill's and the run's absolute paths (the build area's, a user's files)."""
    sources = sorted((quick_book["html"] / "_sources").rglob("*.ipynb"))
    assert sources
    for notebook in sources:
        assert str(quick_book["area"]) not in notebook.read_text(encoding="utf-8"), notebook.name
