"""Project metadata agrees with itself: one version, everywhere it is stated."""

from __future__ import annotations

import re
import tomllib

import sss_locus
from sss_locus import paths


def test_pyproject_takes_the_version_from_the_package():
    project = tomllib.loads((paths.REPO_ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert "version" not in project and "version" in project["dynamic"]


def test_citation_cff_version_matches_the_package():
    text = (paths.REPO_ROOT / "CITATION.cff").read_text(encoding="utf-8")
    match = re.search(r"^version:\s*\"?([^\"\s]+)\"?\s*$", text, re.M)
    assert match, "CITATION.cff has no top-level version"
    assert match.group(1) == sss_locus.__version__


def test_every_statement_of_the_version_takes_the_package_version(tmp_path):
    """.zenodo.json, the project's BibTeX entry, figure manifests (and so their BibTeX) and the
    book's pages all state ``sss_locus.__version__``."""
    import json

    import pytest
    import yaml

    pybtex_database = pytest.importorskip("pybtex.database")
    from sss_locus.pipeline.book import bookbuild
    from sss_locus.pipeline.publish import citation, provenance

    version = sss_locus.__version__
    assert json.loads(citation.ZENODO_FILE.read_text(encoding="utf-8"))["version"] == version
    entry = pybtex_database.parse_string(citation.project_bibtex(), "bibtex").entries["sss-locus"]
    cff = citation.load_cff()
    assert entry.fields["version"] == version and entry.fields["year"] == str(cff["date-released"])[:4]
    assert entry.fields["title"] == "{" + cff["title"] + "}"
    assert provenance.package_version() == version
    bookbuild.stage_config(tmp_path)
    staged = yaml.safe_load((tmp_path / "_config.yml").read_text(encoding="utf-8"))
    assert staged["parse"]["myst_substitutions"]["version"] == version
    assert "{{ version }}" in (paths.BOOK_DIR / bookbuild.CITE_PAGE).read_text(encoding="utf-8")


def test_project_entry_carries_the_cff_address_and_doi():
    import pytest

    pybtex_database = pytest.importorskip("pybtex.database")
    from sss_locus.pipeline.publish import citation

    cff = {**citation.load_cff(), "doi": "10.5281/zenodo.123", "repository-code": "https://example.org/r#x"}
    fields = pybtex_database.parse_string(citation.project_bibtex(cff), "bibtex").entries["sss-locus"].fields
    assert fields["doi"] == "10.5281/zenodo.123" and fields["url"] == r"https://example.org/r\#x"


def test_the_made_environment_carries_bytecode_for_what_notebooks_import():
    """``make`` installs site-packages with their bytecode (``uv --compile-bytecode``): where
    ``PYTHONDONTWRITEBYTECODE`` is set, Python never writes it, and each of the many processes of
    a book or test run (CLI, papermill, kernel) would compile every module it imports again."""
    import importlib
    import importlib.util
    import sys
    from pathlib import Path

    import pytest

    if not list(Path(sys.prefix).glob(".installed-*")):
        pytest.skip("this environment was not built by make from environment.lock")
    missing = []
    for name in ("numpy", "pandas", "scipy.stats", "matplotlib.pyplot", "seaborn", "papermill", "ipykernel.kernelapp"):
        module = importlib.import_module(name)
        if not Path(importlib.util.cache_from_source(module.__file__)).is_file():
            missing.append(name)
    assert not missing, f"no bytecode installed for {missing}"
