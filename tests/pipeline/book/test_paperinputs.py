"""Text written for the paper's inputs is never shown as if it applied to other inputs: the
chapters' prose is generated for every platform of the run, and the claims page says when its
verdicts do not apply (sss_locus.pipeline.book.paperinputs, the claims notice of the book build,
data differences)."""

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


RETIRED_TAGS = ("generated-findings", "paper-inputs")
"""Tags of the retired twins: prose generated for other platforms, and prose written for the paper's
(the runner swapped the second for a note when the inputs were not the paper's)."""


def test_no_chapter_keeps_prose_written_for_one_set_of_inputs():
    """One source per sentence: every chapter's prose is generated for any platform and shown in the
    reproduction too, so no cell is tagged to be dropped from one or the other."""
    for name, entry in REGISTRY.items():
        for cell in json.loads(entry.source.read_text(encoding="utf-8"))["cells"]:
            assert not set(RETIRED_TAGS) & set(cell.get("metadata", {}).get("tags", [])), name


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
def test_no_markdown_names_per_platform_glue(name):
    """No markdown cell quotes a platform-keyed glue value or figure label of a shipped platform:
    with other platforms it would be an undefined key (the build stops) or a false text. Such
    numbers reach the page inside the findings generated for every platform of the run."""
    nb = json.loads(REGISTRY[name].source.read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        if cell["cell_type"] != "markdown":
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
