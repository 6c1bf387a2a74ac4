"""A study no platform of a run can fly becomes a note on its chapter's page
(sss_locus.pipeline.studies), checked on a notebook written for the test."""

from __future__ import annotations

import json

from sss_locus.pipeline import studies


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
                     _md("```{glue:figure} fig-survey-pitch-depth\n```", "study:pitch", "paper-inputs"),
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
