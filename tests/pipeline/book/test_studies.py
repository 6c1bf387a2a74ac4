"""A study no platform of a run can fly becomes a note on its chapter's page
(sss_locus.pipeline.book.studies), checked on a notebook written for the test."""

from __future__ import annotations

import json

from sss_locus.pipeline.book import studies


def _md(text, *tags):
    return {"cell_type": "markdown", "metadata": {"tags": list(tags)}, "source": text}


def _glue(key, text):
    return {"cell_type": "code", "metadata": {"tags": []}, "source": "glue(...)", "outputs": [
        {"output_type": "display_data", "metadata": {"scrapbook": {"name": key, "mime_prefix": ""}},
         "data": {"text/plain": repr(text)}}]}


def _notebook(tmp_path, *cells):
    path = tmp_path / "nb.ipynb"
    path.write_text(json.dumps({"cells": list(cells), "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
    return path


def test_a_skipped_study_keeps_its_heading_and_says_why(tmp_path):
    path = _notebook(tmp_path, _md("# Chapter\n\nintro"),
                     _glue("skipped-study:pitch", "No platform of this run pitches."),
                     _md("## Pitch\n### and depth\nUses {glue:text}`sp-pitch-platform`.", "study:pitch"),
                     {"cell_type": "code", "metadata": {"tags": ["study:pitch"]}, "source": "if pk:", "outputs": []},
                     _md("```{glue:figure} fig-survey-pitch-depth\n```", "study:pitch", "hide-input"),
                     _md("## Summary", "study:other"))
    assert studies.drop_skipped(path) == ["pitch"]
    cells = json.loads(path.read_text())["cells"]
    text = ["".join(c["source"]) for c in cells]
    assert text[0] == "# Chapter\n\nintro" and text[-1] == "## Summary"  # other cells and studies stay
    assert text[2].startswith("## Pitch\n### and depth\n") and "No platform of this run pitches." in text[2]
    assert not any("glue:text" in t or "fig-survey-pitch-depth" in t for t in text)
    assert len(cells) == 4 and not any(t.startswith("study:") for t in cells[2]["metadata"]["tags"])


def test_nothing_changes_when_no_study_is_skipped(tmp_path):
    path = _notebook(tmp_path, _md("## Pitch", "study:pitch"), _glue("sp-x", "1"))
    before = path.read_text()
    assert studies.drop_skipped(path) == [] and path.read_text() == before


def test_a_failed_chapter_gets_a_page_with_its_error_and_its_figures_leave_the_book(build_area, monkeypatch, run_context):
    """Issue 37: one failed chapter meant no site at all for a named book. Its page now says it
    failed, with the failing cell, the error and the traceback of the kept notebook."""
    from sss_locus import paths
    from sss_locus.pipeline.book import bookbuild, failedchapters
    from sss_locus.pipeline.run.registry import load_registry

    run_context(build_name="myboat")
    entries = load_registry()
    entry = entries["survey_passes"]
    error = {"output_type": "error", "ename": "ValueError", "evalue": "envelope pitch exceeds the limit",
             "traceback": ["Traceback (most recent call last)", "----> 3 up = band_samples(auv)",
                           "ValueError: envelope pitch exceeds the limit"]}
    nb = {"cells": [{"cell_type": "code", "metadata": {}, "source": "up = band_samples(auv)",
                     "execution_count": 3, "outputs": [error]}], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
    (paths.build_dir() / "failed").mkdir(parents=True)
    (paths.build_dir() / "failed" / "survey_passes.ipynb").write_text(json.dumps(nb))
    failed = failedchapters.failed_chapters([entry, entries["concept"]])
    assert set(failed) == {"survey_passes"}  # failed before ever succeeding; concept: never run, refused
    root = paths.source_dir()
    excluded = failedchapters.stage_stubs(root, {"survey_passes": failed["survey_passes"]}, entries)
    assert excluded == ["executed/survey_passes.ipynb"]
    page = (root / "executed" / "survey_passes.md").read_text()
    assert page.startswith("# Survey passes: locus length against crossing angle")
    assert "This chapter failed in this build" in page and "`myboat`" in page
    assert "ValueError: envelope pitch exceeds the limit" in page and "up = band_samples(auv)" in page
    assert str(paths.build_dir()) not in page  # no local absolute path on a page
    assert failedchapters.stage_stubs(root, {}, entries) == [] and not (root / "executed" / "survey_passes.md").exists()
    manifests = [{"notebook": entry.source_relative, "label": "fig-survey-passes"},
                 {"notebook": entries["concept"].source_relative, "label": "fig-concept"}]
    assert [m["label"] for m in failedchapters.without_chapters(manifests, {"survey_passes": ""}, entries)] == [
        "fig-concept"]
    bookbuild.stage_config(root, excluded)
    import yaml
    assert "executed/survey_passes.ipynb" in yaml.safe_load((root / "_config.yml").read_text())["exclude_patterns"]
