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
