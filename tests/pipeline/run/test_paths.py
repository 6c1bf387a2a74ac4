"""Paths (sss_locus.paths): one place, overridable build and cache areas, all git-ignored."""

from __future__ import annotations

import shutil
import subprocess

import pytest

from sss_locus import paths
from sss_locus.pipeline.book import bookbuild


def test_repository_layout():
    for path in (paths.DATA_DIR, paths.NOTEBOOKS_DIR, paths.BOOK_DIR):
        assert path.is_dir(), path
    for path in (paths.REGISTRY_FILE, paths.CONFIG_FILE, paths.TOC_FILE, paths.LOCK_FILE,
                 paths.CITATION_FILE, paths.BOOK_DIR / "references.bib"):
        assert path.is_file(), path


def test_default_build_and_cache_areas(monkeypatch):
    monkeypatch.delenv(paths.BUILD_DIR_ENV, raising=False)
    monkeypatch.delenv(paths.CACHE_DIR_ENV, raising=False)
    assert paths.build_dir() == paths.REPO_ROOT / "_build"
    assert paths.cache_dir() == paths.REPO_ROOT / ".cache"
    assert paths.figures_dir() == paths.REPO_ROOT / "_build" / "source" / "_extra" / "figures"
    assert paths.executed_dir() == paths.REPO_ROOT / "_build" / "source" / "executed"
    # the site lands where Jupyter Book users look for it
    assert paths.index_html() == paths.REPO_ROOT / "_build" / "html" / "index.html"
    assert paths.site_url(paths.figures_dir() / "fig-x.png") == "figures/fig-x.png"


def test_environment_overrides(tmp_path, monkeypatch):
    monkeypatch.setenv(paths.BUILD_DIR_ENV, str(tmp_path / "b"))
    monkeypatch.setenv(paths.CACHE_DIR_ENV, str(tmp_path / "c"))
    for path in (paths.executed_dir(), paths.figures_dir(), paths.mathjax_dir(), paths.jupyter_dir(),
                 paths.html_dir(), paths.source_dir(), paths.jupyter_book_dir()):
        assert path.is_relative_to(tmp_path / "b")
    assert paths.cache_dir() == tmp_path / "c"


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
@pytest.mark.parametrize("generated", ["_build/html/index.html", "_build/source/executed/x.ipynb",
                                       ".cache/frames/ab/abc/data.parquet", ".venv/bin/python"])
def test_generated_files_are_git_ignored(generated):
    result = subprocess.run(["git", "check-ignore", "-q", generated], cwd=paths.REPO_ROOT)
    if result.returncode == 128:
        pytest.skip("not a git checkout")
    assert result.returncode == 0, f"{generated} is not git-ignored"


def test_missing_toc_files_are_reported(tmp_path):
    pytest.importorskip("yaml")
    (tmp_path / "_toc.yml").write_text(
        "format: jb-book\nroot: book/intro\nparts:\n  - caption: C\n    chapters:\n"
        "      - file: book/here\n      - file: executed/absent\n"
    )
    (tmp_path / "book").mkdir()
    (tmp_path / "book" / "intro.md").write_text("# I\n")
    (tmp_path / "book" / "here.md").write_text("# H\n")
    assert bookbuild.missing_toc_files(tmp_path) == ["executed/absent"]


def test_book_output_drops_only_jupyter_books_staging_path_lines():
    from sss_locus.pipeline.book.buildlog import StagingPathFilter

    rule = "\x1b[92m=====\x1b[0m\n"
    tail = ["\x1b[01mbuild succeeded.\x1b[39;49;00m\n", "\n", "The HTML pages are in ../jupyter-book/_build/html.\n",
            "\n", rule, "\n", "Finished generating HTML for book.\n",
            "Your book's HTML pages are here:\n", "    ../jupyter-book/_build/html/\n",
            "    file:///x/_build/jupyter-book/_build/html/index.html\n", "\n", rule,
            "WARNING: something after the banner\n", rule, "a rule that opens no banner stays\n", rule]
    shown = StagingPathFilter()
    kept = [out for line in tail for out in shown.feed(line)] + shown.flush()
    assert kept == [tail[0], "\n", "\n", tail[12], rule, tail[14], rule]


def test_book_output_to_a_file_has_no_colour_codes_and_no_per_file_progress():
    from sss_locus.pipeline.book.buildlog import ANSI, StagingPathFilter

    lines = ["\x1b[01mreading sources... \x1b[39;49;00m[  5%] \x1b[35mbook/chapters\x1b[39;49;00m\n",
             "\x1b[01mreading sources... \x1b[39;49;00m[100%] \x1b[35mexecuted/water\x1b[39;49;00m\n",
             "\x1b[01mwriting output... \x1b[39;49;00m[ 50%] \x1b[32mbook/intro\x1b[39;49;00m\n",
             "\x1b[91mWARNING: a real warning [ 50%]\x1b[39;49;00m\n", "\x1b[01mbuild succeeded.\x1b[39;49;00m\n"]
    plain = StagingPathFilter(plain=True)
    kept = [out for line in lines for out in plain.feed(line)] + plain.flush()
    assert kept == ["reading sources... [100%] executed/water\n", "WARNING: a real warning [ 50%]\n",
                    "build succeeded.\n"]
    coloured = StagingPathFilter()  # a terminal keeps the colours
    assert [out for line in lines for out in coloured.feed(line)] == [lines[1], lines[3], lines[4]]
    assert all(not ANSI.search(line) for line in kept)


def test_an_installed_packages_run_key_follows_its_installed_libraries(monkeypatch):
    """Outside a checkout there is no environment.lock: the run key holds the installed
    distributions instead, so upgrading one makes the runs stale (in a checkout: the lock's hash)."""
    from importlib import metadata
    from types import SimpleNamespace

    from sss_locus.pipeline.publish import provenance
    from sss_locus.pipeline.run import outputs
    from sss_locus.pipeline.run.registry import get_entry

    def environment(*dists):
        monkeypatch.setattr(metadata, "distributions",
                            lambda: [SimpleNamespace(metadata={"Name": n}, version=v) for n, v in dists])
        provenance.installed_distributions_sha256.cache_clear()
        return outputs.run_key(get_entry("concept"), "quick", {}), provenance.environment_sha256()

    in_checkout = environment(("numpy", "2.4.0"))
    assert in_checkout[1] == provenance.lock_sha256() != "missing"
    monkeypatch.setattr(paths, "IN_CHECKOUT", False)
    old = environment(("numpy", "2.4.0"), ("scipy", "1.16.0"))
    assert environment(("scipy", "1.16.0"), ("numpy", "2.4.0")) == old  # the same libraries
    new = environment(("numpy", "2.4.1"), ("scipy", "1.16.0"))
    assert new[0] != old[0] and new[1] != old[1] and in_checkout[0] not in (old[0], new[0])
    provenance.installed_distributions_sha256.cache_clear()


def test_a_book_without_its_sources_is_refused_in_one_line_before_any_run(tmp_path, monkeypatch, capsys):
    """An installed package built without the book's sources: ``sss-locus book`` names them and
    where it looked, and runs nothing."""
    from sss_locus.pipeline.cli import command

    monkeypatch.setattr(paths, "IN_CHECKOUT", False)
    monkeypatch.setattr(paths, "CONFIG_FILE", tmp_path / "_shipped" / "_config.yml")
    monkeypatch.setattr(paths, "BOOK_DIR", tmp_path / "_shipped" / "book")
    monkeypatch.setenv(paths.BUILD_DIR_ENV, str(tmp_path / "build"))
    monkeypatch.setenv(paths.CACHE_DIR_ENV, str(tmp_path / "cache"))
    assert command.main(["book", "--profile", "quick"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "the book's sources _config.yml, book/ are missing from the installed package" in err
    assert not (tmp_path / "build").exists()
