"""Text written for the paper's inputs is never shown as if it applied to other inputs
(sss_locus.pipeline.book.paperinputs, the claims notice of the book build, data differences)."""

from __future__ import annotations

import json

import pytest

from sss_locus.experiments.datamodel import userdata
from sss_locus.paths import REPO_ROOT
from sss_locus.pipeline.book import bookbuild, paperinputs
from sss_locus.pipeline.run.registry import load_registry

EXAMPLE = REPO_ROOT / "data" / "examples" / "my_auv.toml"
REGISTRY = load_registry()
PLATFORM_NOTEBOOKS = [n for n, e in REGISTRY.items() if "platforms" in e.parameters()]


# Chapters whose platform is named by their input file, not chosen by a parameter.
PLATFORM_FROM_INPUT = {"your_pings": "each sighting of the observations file names its platform key"}


def test_every_notebook_that_takes_platforms_selects_them_with_one_parameter():
    for name, entry in REGISTRY.items():
        names = set(entry.parameters())
        assert "sonar_platform" not in names, name
        if names & {"data_files", "data_set"} and name not in PLATFORM_FROM_INPUT:  # reads the platform data
            assert "platforms" in names, f"{name} reads data but does not take `platforms`"
    assert "observations" in REGISTRY["your_pings"].parameters()
    assert {"concept", "rigs", "pose_space", "survey_passes", "planning", "three_views", "noise"} <= set(
        PLATFORM_NOTEBOOKS)


def test_changed_from_shipped_names_exactly_the_changed_entries(tmp_path):
    assert userdata.changed_from_shipped(["auv", "boat"]) == []
    only_new = userdata.make_inputs([EXAMPLE])
    assert userdata.changed_from_shipped(["auv", "boat"], only_new) == []  # adds my_auv, changes nothing shipped
    assert userdata.changed_from_shipped(["my_auv"], only_new) == ["platforms.my_auv"]
    tilt = userdata.make_inputs([], ["platforms.auv.transducers.port.tilt_deg=15"])
    assert userdata.changed_from_shipped(["boat"], tilt) == []
    assert userdata.changed_from_shipped(["auv"], tilt) == ["platforms.auv.transducers.port.tilt_deg"]
    sonar = tmp_path / "sonar.toml"
    sonar.write_text('[sonars.edgetech_2205.max_range_m]\nvalue = 80.0\nassumption = "test"\n')
    shared = userdata.make_inputs([sonar])
    assert userdata.changed_from_shipped(["auv"], shared) == ["sonars.edgetech_2205.max_range_m"]
    offsets = userdata.make_inputs([], ["offset_models.matched.jitter_m=3"])
    assert userdata.changed_from_shipped(["boat"], offsets) == ["offset_models.matched.jitter_m"]


def _record(name, parameters):
    return paperinputs.compare(REGISTRY[name], parameters)


def test_compare_reads_the_defaults_of_each_notebook():
    assert _record("derivation", {}) is None
    paper = _record("pose_space", {"platforms": ["auv", "boat"]})
    assert paper == {"paper": ["auv", "boat"], "missing": [], "changed": [], "added": []}
    assert paperinputs.is_paper(paper)
    added = _record("pose_space", {"platforms": ["auv", "boat", "my_auv"], "data_files": [str(EXAMPLE)]})
    assert paperinputs.is_paper(added) and added["added"] == ["my_auv"]
    replaced = _record("survey_passes", {"platforms": ["my_auv"], "data_files": [str(EXAMPLE)]})
    assert not paperinputs.is_paper(replaced) and replaced["missing"] == ["boat", "auv"]
    tilted = _record("rigs", {"platforms": ["boat", "auv"], "data_set": ["platforms.boat.transducers.port.tilt_deg=35"]})
    assert tilted["changed"] == ["platforms.boat.transducers.port.tilt_deg"] and not paperinputs.is_paper(tilted)
    relief = {"platforms": ["auv", "boat"], "data_set": ["terrain.random.rms_relief_m=3"]}
    assert paperinputs.is_paper(_record("reconstruction", relief))  # a run that read no terrain
    read = paperinputs.compare(REGISTRY["reconstruction"], relief, ["platforms.auv", "terrain", "survey"])
    assert read["changed"] == ["terrain.random.rms_relief_m"] and not paperinputs.is_paper(read)


def _notebook(tmp_path, cells):
    path = tmp_path / "nb.ipynb"
    path.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
    return path


def _md(text, tagged=False):
    return {"cell_type": "markdown", "metadata": {"tags": [paperinputs.PROSE_TAG]} if tagged else {}, "source": text}


def test_tagged_prose_gives_way_to_one_note_a_chapter(tmp_path):
    cells = [_md("intro"), _md("## Drivers\n\nAUV {glue:text}`x-auv`", True), _md("boat {glue:text}`x-boat`", True),
             _md("made {glue:md}"), _md("generic"), _md("## Summary\nmore AUV", True), _md("summary made")]
    for record in (_record("pose_space", {"platforms": ["auv", "boat"]}),
                   _record("pose_space", {"platforms": ["auv", "boat", "my_auv"]})):  # the paper's, or added beside
        path = _notebook(tmp_path, cells)
        assert paperinputs.adapt_prose(path, record) == 0
        assert json.loads(path.read_text())["cells"] == cells
    path = _notebook(tmp_path, cells)
    other = _record("pose_space", {"platforms": ["my_auv"], "data_files": [str(EXAMPLE)]})
    assert paperinputs.adapt_prose(path, other) == 3
    out = ["".join(c["source"]) for c in json.loads(path.read_text())["cells"]]
    assert out[0] == "intro" and out[2:5] == ["made {glue:md}", "generic", "## Summary\n"] and out[5] == "summary made"
    assert len(out) == 6 and sum("```{note}" in c for c in out) == 1  # one note a chapter
    note = out[1]
    assert note.startswith("## Drivers\n\n") and "{glue:text}" not in note  # the section keeps its heading
    assert "does not include `auv`, `boat`" in note and "Torpedo AUV" in note  # paper platforms by name
    assert "generated from this run's numbers" in note


def test_no_chapter_keeps_a_twin_of_generated_findings():
    """One source per sentence: a verdict generated for any platform is shown in the reproduction too,
    so no cell is tagged to be dropped from it (the tag of the retired twins)."""
    for name, entry in REGISTRY.items():
        for cell in json.loads(entry.source.read_text(encoding="utf-8"))["cells"]:
            assert "generated-findings" not in cell.get("metadata", {}).get("tags", []), name


def test_claims_notice_says_what_differs_and_when_the_table_cannot_be_shown(tmp_path):
    paper = {n: _record(n, {}) for n in REGISTRY}
    assert paperinputs.claims_notice(paper) == ("", False)
    added = {**paper, "pose_space": _record("pose_space", {"platforms": ["auv", "boat", "my_auv"]})}
    text, replace = paperinputs.claims_notice(added)
    assert not replace and "`my_auv`" in text and "paper's platforms only" in text
    tilted = {**paper, "rigs": _record("rigs", {"data_set": ["platforms.auv.transducers.port.tilt_deg=15"]})}
    text, replace = paperinputs.claims_notice(tilted)
    assert not replace and "does not use the paper's inputs" in text and "do not necessarily apply" in text
    assert "{doc}`/executed/rigs`" in text and "platforms.auv.transducers.port.tilt_deg" in text
    gone = {**paper, "noise": _record("noise", {"platforms": ["my_auv"], "data_files": [str(EXAMPLE)]})}
    text, replace = paperinputs.claims_notice(gone)
    assert replace and "not shown" in text and "does not include `auv`, `boat`" in text

    page = tmp_path / "claims.md"
    page.write_text("# The paper's claims, checked\n\nIntro {glue:text}`/executed/x.ipynb::k:s`\n\n| a | b |\n")
    body = page.read_text()
    for records, kept in ((paper, True), (tilted, True), (gone, False)):
        page.write_text(body)
        bookbuild.stage_claims_notice(page, records)
        staged = page.read_text()
        assert staged.startswith("# The paper's claims, checked\n")
        assert ("Intro {glue:text}" in staged) == kept
        assert ("```{warning}" in staged) == (records is not paper)


def test_claims_page_has_a_heading_for_the_notice():
    assert (REPO_ROOT / "book" / "claims.md").read_text(encoding="utf-8").startswith("# ")


@pytest.mark.parametrize("name", PLATFORM_NOTEBOOKS)
def test_tagged_cells_are_the_only_markdown_naming_per_platform_glue(name):
    """Untagged markdown never quotes a platform-keyed glue value or figure label of a shipped
    platform: with other platforms it would be an undefined key (the build stops) or a false text."""
    nb = json.loads(REGISTRY[name].source.read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        if cell["cell_type"] != "markdown" or paperinputs.PROSE_TAG in cell["metadata"].get("tags", []):
            continue
        text = "".join(cell["source"])
        for key in ("auv", "boat"):
            assert f"-{key}-" not in text and f"-{key}`" not in text, (name, text[:200])


def test_claims_note_never_calls_a_paper_platform_added():
    """Issue 37: with the user's boat beside the paper's boat, the note said "this build also ran
    the platform(s) boat, myboat" (concept's default is the AUV alone, so `boat` looked added)."""
    paper = {n: _record(n, {}) for n in REGISTRY}
    both = {**paper, **{n: _record(n, {"platforms": [*REGISTRY[n].parameters()["platforms"].default, "myboat"]})
                        for n in ("rigs", "planning")},
            "concept": _record("concept", {"platforms": ["auv", "boat"]})}
    text, replace = paperinputs.claims_notice(both)
    assert not replace and "`myboat`" in text
    assert "`boat`" not in text.split("platforms only")[0]
