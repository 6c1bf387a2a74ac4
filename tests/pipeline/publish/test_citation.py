"""Citation metadata: figure BibTeX entries that BibTeX and LaTeX accept, a valid CITATION.cff,
an up-to-date .zenodo.json, and the two configured addresses agreeing everywhere."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

yaml = pytest.importorskip("yaml")
pybtex_database = pytest.importorskip("pybtex.database")
jsonschema = pytest.importorskip("jsonschema")

from sss_locus import paths  # noqa: E402
from latex_check import compile_latex  # noqa: E402  (tests/ is on sys.path, see conftest)
from sss_locus.pipeline.publish import citation  # noqa: E402

CFF_SCHEMA = Path(__file__).parents[2] / "data" / "cff-1.2.0.schema.json"
NASTY = ("Locus of $\\theta_1$ & width_m at 50% of {range} #3, ~2^k \\ over 3° × 2 − 1 "
         "— **widened** *beam* of `two_view_locus`. Second sentence.")


def manifest(label="fig-demo", caption=NASTY, notebook="notebooks/pose_space.ipynb", **extra):
    return {"label": label, "caption": caption, "notebook": notebook, "profile": "quick",
            "git_commit": "0123456789abcdef0123+dirty", "package_version": "0.1.0",
            "run_time_utc": "2026-11-23T10:00:00+00:00", **extra}


def parse(bib: str):
    return pybtex_database.parse_string(bib, "bibtex")


@pytest.mark.parametrize("text, expected", [
    ("a_b & c% #1", r"a\_b \& c\% \#1"),
    ("{x} ~ ^ \\", r"\{x\} \~{} \^{} \textbackslash{}"),
    ("cost $5 only", r"cost \$5 only"),  # an unpaired dollar is text, not math
    ("angle $\\alpha_{1}$ of 3°", r"angle $\alpha_{1}$ of 3{$^\circ$}"),
    ("café", r"caf{\'e}"),
])
def test_latex_escape(text, expected):
    assert citation.latex_escape(text) == expected


def test_markdown_emphasis_becomes_latex():
    assert citation.latex_escape("**widened** *beam* `f_x`", markdown=True) == \
        r"\textbf{widened} \emph{beam} \texttt{f\_x}"


def test_a_name_in_any_script_becomes_ascii_latex_instead_of_an_error():
    """Issue 38: an area or file name in any script must reach BibTeX (it raised "has no LaTeX
    equivalent" and no such input could run): accented letters stay LaTeX accents, digits of any
    script become digits, characters without an ASCII form their code point, each distinct."""
    assert citation.latex_escape("港 Harbour á ١٢ wave \U0001F30A") == "U+6E2F Harbour {\\'a} 12 wave U+1F30A"
    assert citation.latex_escape("港口") != citation.latex_escape("港湾")
    assert all(ord(c) < 128 for c in citation.latex_escape("مرفأ 港 Ωmega"))


def test_short_caption_is_the_first_clause_and_short():
    assert citation.short_caption("Locus length vs. range, 3.5 m; with details. More.") == \
        "Locus length vs. range, 3.5 m"
    long = "word " * 60 + "end."
    short = citation.short_caption(long)
    assert len(short) <= citation.SHORT_CAPTION_CHARS + 1 and short.endswith("…")
    assert citation.short_caption("A $x$ " + "long " * 30, limit=5).count("$") % 2 == 0


def test_a_long_caption_gives_a_title_of_whole_clauses():
    caption = ("Median locus length per bin, Torpedo AUV (REMUS-100 / Iver3 class), dual EdgeTech 2205, feature "
               "on the port side of both vehicles (20,000 samples, seed 1): (a) range vs range.")
    title = citation.short_caption(caption)
    assert title == "Median locus length per bin, Torpedo AUV (REMUS-100 / Iver3 class), dual EdgeTech 2205"
    head = "Two range spheres $S_1, S_2$ meet in a circle of radius $r$ (no cut in math or brackets, here)"
    assert citation.short_caption(head + ", " + "x" * 200) == head


def test_figure_entry_fields(tmp_path):
    config = tmp_path / "_config.yml"
    config.write_text("html:\n  baseurl: https://example.org/book/\n")
    entry = parse(citation.figure_bibtex(manifest(), config=config)).entries["sss-locus:fig-demo"]
    fields = entry.fields
    assert fields["title"].startswith("{Figure fig-demo: Locus of $\\theta_1$ \\& width\\_m")
    assert "Second sentence" not in fields["title"]
    assert fields["year"] == "2026" and fields["version"] == "0.1.0"
    assert fields["url"] == "https://example.org/book/figures/fig-demo.png"
    assert "pose\\_space.ipynb" in fields["note"] and "0123456789ab+dirty" in fields["note"]
    config.write_text("html:\n  baseurl: ''\n")
    assert "url" not in parse(citation.figure_bibtex(manifest(), config=config)).entries["sss-locus:fig-demo"].fields


def test_bad_base_url_is_rejected(tmp_path):
    config = tmp_path / "_config.yml"
    config.write_text("html:\n  baseurl: example.org\n")
    with pytest.raises(ValueError, match="html.baseurl"):
        citation.base_url(config)


@pytest.mark.skipif(not (shutil.which("pdflatex") and shutil.which("bibtex")), reason="no TeX installation")
def test_entries_compile_with_latex(tmp_path):
    captions = [NASTY, "Plain caption.", "Width {in} m; 100% of \\alpha, café, ≈ 5 µm. Rest.",
                "Unbalanced $ dollar and }brace{. Rest.", "Plans over 港口 á ١٢ مرفأ Ωmega. Rest."]
    bib = "\n".join(citation.figure_bibtex(manifest(f"fig-n{i}", caption=c)) for i, c in enumerate(captions))
    keys = [f"sss-locus:fig-n{i}" for i in range(len(captions))]
    assert set(parse(bib).entries) == set(keys)
    compile_latex(tmp_path, bib, keys)


def test_the_old_unescaped_note_would_be_caught(tmp_path):
    """The checks above can fail: an unescaped '_' in a field stops LaTeX."""
    bad = "@misc{k,\n  title = {x},\n  note = {Notebook \\texttt{notebooks/pose_space.ipynb}},\n  year = {2026}\n}\n"
    parse(bad)  # BibTeX itself accepts it ...
    if not shutil.which("pdflatex"):
        pytest.skip("no TeX installation")
    with pytest.raises(AssertionError, match="pdflatex failed"):
        compile_latex(tmp_path, bad, ["k"])  # ... LaTeX does not


def load_cff():
    return yaml.safe_load(paths.CITATION_FILE.read_text(encoding="utf-8"))


def cff_errors(cff) -> list[str]:
    schema = json.loads(CFF_SCHEMA.read_text(encoding="utf-8"))
    validator = jsonschema.Draft7Validator(schema, format_checker=jsonschema.Draft7Validator.FORMAT_CHECKER)
    return [f"{'/'.join(map(str, e.path))}: {e.message}" for e in validator.iter_errors(cff)]


def test_citation_cff_is_valid_and_complete():
    cff = load_cff()
    assert cff_errors(cff) == []
    for key in ("title", "abstract", "authors", "version", "date-released", "license", "keywords",
                "preferred-citation"):
        assert cff.get(key), f"CITATION.cff lacks {key}"
    paper = cff["preferred-citation"]
    assert [a["family-names"] for a in paper["authors"]] == ["Norman", "Mangelson"]


def test_schema_rejects_a_broken_cff():
    cff = load_cff()
    del cff["authors"]
    cff["date-released"] = "21 November 2026"
    errors = cff_errors(cff)
    assert any("authors" in e for e in errors) and any("date-released" in e for e in errors)


def test_addresses_agree_between_cff_and_book_config():
    cff = load_cff()
    assert cff.get("url") == (citation.base_url() or None)
    assert cff.get("repository-code") == (citation.repository_url() or None)


def test_zenodo_json_is_generated_from_cff_and_up_to_date():
    committed = json.loads(citation.ZENODO_FILE.read_text(encoding="utf-8"))
    cff = load_cff()
    assert committed["title"] == cff["title"] and committed["version"] == str(cff["version"])
    assert committed["upload_type"] == "software" and committed["license"] == {"id": cff["license"]}
    assert committed["publication_date"] == cff["date-released"]
    assert citation.main(["--check"]) == 0, "regenerate with python -m sss_locus.pipeline.publish.citation"


def test_launch_links_need_a_github_repository(tmp_path):
    config = tmp_path / "_config.yml"
    config.write_text("repository:\n  url: ''\n")
    assert citation.launch_links("notebooks/concept.ipynb", config) == {}
    config.write_text("repository:\n  url: https://github.com/owner/sss-locus\n  branch: dev\n")
    links = citation.launch_links("notebooks/concept.ipynb", config)
    assert links == {
        "Binder": "https://mybinder.org/v2/gh/owner/sss-locus/dev?labpath=notebooks/concept.ipynb",
        "Colab": "https://colab.research.google.com/github/owner/sss-locus/blob/dev/notebooks/concept.ipynb",
    }


def test_a_figure_of_an_area_named_in_any_script_gets_an_entry(tmp_path):
    """The survey-design tables' captions name the area (issue 38: ``港``, ``á``, Arabic digits
    stopped publish_table); the entry parses and is ASCII."""
    config = tmp_path / "_config.yml"
    config.write_text("html:\n  baseurl: ''\n")
    bib = citation.figure_bibtex(manifest("tab-x", caption="Plans over 港口 á ١٢ مرفأ: headings."), config=config)
    assert bib.isascii()
    assert "U+6E2F" in parse(bib).entries["sss-locus:tab-x"].fields["title"]


def test_a_named_build_areas_keys_differ_from_the_reproductions_and_both_compile_in_one_document(tmp_path):
    """Issue 37: the user's fig-survey-front and the paper's shared the key sss-locus:fig-survey-front
    (bibtex: "Repeated entry", one number for two figures)."""
    paper = manifest()
    mine = {**manifest(), "build_area": "myboat"}
    a, b = citation.figure_bibtex(paper), citation.figure_bibtex(mine)
    entries = parse(a + b).entries
    assert set(entries) == {"sss-locus:fig-demo", "sss-locus:myboat:fig-demo"}
    assert "build area" in entries["sss-locus:myboat:fig-demo"].fields["note"]
    assert "build area" not in entries["sss-locus:fig-demo"].fields["note"]
    if shutil.which("pdflatex") and shutil.which("bibtex"):  # one LaTeX document cites both: two numbers
        log = compile_latex(tmp_path, a + b, list(entries))
        assert "Repeated entry" not in (tmp_path / "doc.blg").read_text() and log
