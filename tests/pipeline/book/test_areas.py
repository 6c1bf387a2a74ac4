"""Runs add, the reproduction stays (sss_locus.pipeline.book.areas), figure by figure provenance
(sss_locus.experiments.datamodel.userdata.figure_record) and the quick answer (``sss-locus answer``).

The whole your-hardware page, run in order on a built book, is in ``test_book_build.py``.
"""

from __future__ import annotations

import hashlib
import re

import pytest

from sss_locus import paths
from sss_locus.experiments.datamodel import userdata
from sss_locus.pipeline.book import areas
from sss_locus.pipeline.cli import command as cli
from sss_locus.pipeline.run.registry import load_registry

EXAMPLE = paths.REPO_ROOT / "data" / "examples" / "my_auv.toml"
REGISTRY = load_registry()


@pytest.mark.parametrize("name", ["html", "source", "tmp", "My", "a/b", "../x", "", "-x", "x" * 65])
def test_bad_area_names_are_refused(name):
    with pytest.raises(ValueError, match="--name must match"):
        areas.check_name(name)


def test_a_named_area_is_a_folder_of_the_build_area_and_the_environment_is_restored(build_area):
    with areas.entered("my_auv"):
        assert paths.build_dir() == build_area.resolve() / "my_auv" and paths.build_name() == "my_auv"
        assert paths.html_dir() == build_area.resolve() / "my_auv" / "html"
        with pytest.raises(ValueError, match="already works in the build area"), areas.entered("other"):
            pass
    assert paths.build_dir() == build_area.resolve() and paths.build_name() is None


def test_the_paper_inputs_of_every_chapter_are_not_refused():
    for entry in REGISTRY.values():
        assert areas.differs_from_paper(entry, entry.resolve("quick")) == [], entry.name
        assert areas.differs_from_paper(entry, entry.resolve("book")) == [], entry.name


def test_user_inputs_and_other_platform_lists_differ_from_the_paper():
    entry = REGISTRY["survey_passes"]
    default = list(entry.parameters()["platforms"].default)
    assert areas.differs_from_paper(entry, entry.resolve("quick", {"platforms": default[::-1]}))  # other order
    assert areas.differs_from_paper(entry, {**entry.resolve("quick"), "data_files": [str(EXAMPLE)]})
    assert areas.differs_from_paper(entry, {**entry.resolve("quick"),
                                            "data_set": ["platforms.auv.transducers.port.tilt_deg=15"]})


def test_a_survey_area_of_ones_own_differs_from_the_paper(tmp_path, monkeypatch):
    """The survey-design chapter's area file is a user input like the observations of your_pings:
    the shipped example however it is written, another file never."""
    entry = REGISTRY["survey_design"]
    monkeypatch.chdir(paths.REPO_ROOT / "data")
    for same in ("examples/survey_area.toml", str(paths.REPO_ROOT / "data/examples/survey_area.toml")):
        assert areas.differs_from_paper(entry, entry.resolve("quick", {"area": same})) == [], same
    mine = tmp_path / "my_area.toml"
    mine.write_bytes((paths.REPO_ROOT / "data/examples/survey_area.toml").read_bytes())
    why = areas.differs_from_paper(entry, entry.resolve("quick", {"area": str(mine)}))
    assert why and "my_area.toml" in why[0]


def test_an_edited_area_file_makes_the_survey_design_run_stale(tmp_path, monkeypatch):
    """The area file's bytes are part of the run's key (as the observations' are), so a book
    never reuses a plan and mission files computed from another polygon."""
    from sss_locus.pipeline.run.outputs import run_key
    from sss_locus.pipeline.run.runner import resolve_parameters

    entry = REGISTRY["survey_design"]
    area = tmp_path / "my_area.toml"
    area.write_text('[area]\nvertices_m = [[0, 0], [900, 0], [900, 400], [0, 400]]\nwater_depth_m = 20.0\n')
    monkeypatch.chdir(tmp_path)
    first = resolve_parameters(entry, "quick", {"area": "my_area.toml"}, from_text=True)
    assert first["area"] == str(area)  # resolved where the command was typed
    assert first["area_sha256"] == hashlib.sha256(area.read_bytes()).hexdigest()
    area.write_text('[area]\nvertices_m = [[0, 0], [900, 0], [900, 500], [0, 400]]\nwater_depth_m = 20.0\n')
    second = resolve_parameters(entry, "quick", {"area": "my_area.toml"}, from_text=True)
    assert run_key(entry, "quick", second) != run_key(entry, "quick", first)


def _paper_figure(label: str, notebook: str):
    """A real exported figure in the reproduction's figures folder, made by ``notebook``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    from sss_locus.pipeline.publish.export import export_figure

    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, 1])
    export_figure(fig, label, pd.DataFrame({"x_m": [0, 1]}), caption="A paper figure.", parameters={},
                  notebook=notebook, out_dir=paths.figures_dir())
    plt.close(fig)
    return {p.name: p.read_bytes() for p in paths.figures_dir().iterdir()}


def test_a_user_run_into_the_reproduction_is_refused_before_it_starts(build_area, capsys):
    before = _paper_figure("fig-heatmaps-auv", "notebooks/pose_space.ipynb")
    code = cli.main(["run", "pose_space", "--profile", "quick", "--data", str(EXAMPLE),
                     "-p", "platforms", '["my_auv"]'])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("sss-locus run: error: add --name NAME (e.g. --name my_auv)")  # the way out, first
    assert len(err.strip().splitlines()) == 1  # in one line
    assert "would replace fig-heatmaps-auv" in err and "--replace-reproduction" in err
    assert {p.name: p.read_bytes() for p in paths.figures_dir().iterdir()} == before
    assert not paths.executed_dir().exists() and not (build_area / "tmp").exists()  # nothing started
    code = cli.main(["book", "--profile", "quick", "--set", "platforms.auv.transducers.port.tilt_deg=15"])
    assert code == 2 and "overrides platforms.auv.transducers.port.tilt_deg=15" in capsys.readouterr().err
    assert not paths.executed_dir().exists()


# -- figure by figure provenance ------------------------------------------------------------------

def test_a_figure_names_only_its_own_platforms_entries_and_files(tmp_path):
    user = tmp_path / "my_auv.toml"
    user.write_bytes(EXAMPLE.read_bytes())
    inputs = userdata.make_inputs([user], ["platforms.auv.transducers.port.tilt_deg=15"])
    mine = userdata.figure_record(["my_auv"], inputs, read=set())
    assert mine["platforms"] == ["my_auv"] and list(mine["values"]) == ["my_auv"]
    assert set(mine["entries"]) == {"platforms.my_auv", "sonars.narrow_fan_450"}  # nothing else read
    assert [(f["path"], f["sha256"]) for f in mine["files"]] == [
        (user.name, hashlib.sha256(user.read_bytes()).hexdigest())]
    assert mine["overrides"] == []  # the --set changes the AUV, not this platform
    auv = userdata.figure_record(["auv"], inputs, read={"envelopes.auv", "offset_models.matched"})
    assert set(auv["entries"]) == {"platforms.auv", "sonars.edgetech_2205", "envelopes.auv",
                                   "offset_models.matched"}
    assert [f["path"] for f in auv["files"]] == ["data/platforms.toml", "data/survey.toml"]
    assert auv["overrides"] == ["platforms.auv.transducers.port.tilt_deg=15"]
    both = userdata.figure_record(["auv", "my_auv"], inputs, read={"noise.my_auv"})
    assert set(both["entries"]) == {"platforms.auv", "sonars.edgetech_2205", "platforms.my_auv",
                                    "sonars.narrow_fan_450", "noise.my_auv"}
    assert [f["path"] for f in both["files"]] == ["data/platforms.toml", user.name]  # by name, never a local path


def test_the_rig_caption_names_the_files_its_platforms_come_from(tmp_path):
    from sss_locus.report.rigs.figures import data_sources

    user = tmp_path / "my_auv.toml"
    user.write_bytes(EXAMPLE.read_bytes())
    tilt = tmp_path / "tilt.toml"
    tilt.write_text('[platforms.auv.transducers.port.tilt_deg]\nvalue = 15.0\nassumption = "bracket"\n')
    inputs = userdata.make_inputs([user, tilt])
    assert data_sources(["my_auv"], inputs) == "my_auv.toml"  # defined there alone: no shipped file
    assert data_sources(["auv", "my_auv"], inputs) == "data/platforms.toml and my_auv.toml and tilt.toml"
    assert data_sources(["auv"], userdata.make_inputs([user])) == "data/platforms.toml"


def test_an_entry_hash_changes_exactly_with_its_value(tmp_path):
    user = tmp_path / "my_auv.toml"
    user.write_bytes(EXAMPLE.read_bytes())
    plain = userdata.figure_record(["auv", "my_auv"], userdata.make_inputs([user]), read=set())["entries"]
    tilted = userdata.figure_record(["auv", "my_auv"], userdata.make_inputs(
        [user], ["platforms.auv.transducers.port.tilt_deg=15"]), read=set())["entries"]
    assert {e for e in plain if plain[e] != tilted[e]} == {"platforms.auv"}


# -- the quick answer -----------------------------------------------------------------------------

def test_answer_prints_bands_and_drivers_and_names_the_data(build_area, capsys):
    code = cli.main(["answer", "--data", str(EXAMPLE), "-p", "platform", "my_auv"])
    out = capsys.readouterr().out
    assert code == 0, out
    sha = hashlib.sha256(EXAMPLE.read_bytes()).hexdigest()[:12]
    assert f"my_auv.toml (user, sha256 {sha})" in out and "data/platforms.toml" not in out
    assert "platforms.my_auv" in out and "sonars.narrow_fan_450" in out
    bands = re.findall(r"^  (prefer|avoid) +(\d+)(?:–(\d+))? ", out, re.M)
    assert {b[0] for b in bands} == {"prefer", "avoid"}
    assert all(0 <= int(lo) <= int(hi or lo) <= 180 for _, lo, hi in bands)
    drivers = re.findall(r"^  (\d) +(.+?) +(-?\d\.\d\d) +(-?\d\.\d\d) to (-?\d\.\d\d)$", out, re.M)
    assert [int(d[0]) for d in drivers] == [1, 2, 3, 4, 5]
    rho = [abs(float(d[2])) for d in drivers]
    assert rho == sorted(rho, reverse=True)  # the top drivers, strongest first
    assert all(float(lo) <= float(r) <= float(hi) for _, _, r, lo, hi in drivers)
    assert not paths.executed_dir().exists()  # no chapter ran, no book


def test_answer_needs_one_known_platform(build_area, capsys):
    assert cli.main(["answer"]) == 2 and "exactly one -p platform KEY" in capsys.readouterr().err
    assert cli.main(["answer", "-p", "platform", "my_auv"]) == 2  # not in the shipped data
    assert "'my_auv' is not allowed" in capsys.readouterr().err
    assert cli.main(["answer", "-p", "platform", "auv", "-p", "n_sampels", "5"]) == 2
    assert "unknown parameter(s) ['n_sampels']" in capsys.readouterr().err


# -- a user's own files, read before a kernel starts ---------------------------------------------

BAD_AREAS = {  # file name, contents, what the one-line refusal says
    "bowtie.toml": ("[area]\nvertices_m = [[0, 0], [900, 400], [900, 0], [0, 400]]\n", "the polygon is not valid"),
    "nodepth.toml": ("[area]\nvertices_m = [[0, 0], [400, 0], [400, 200], [0, 200]]\n", "no water depth"),
    "baddepth.toml": ("[area]\nvertices_m = [[0, 0], [400, 0], [400, 200], [0, 200]]\nwater_depth_m = -4\n",
                      "area.water_depth_m must be a finite number in (0.0, 12000.0]; got -4"),
    "bowtie.geojson": ('{"type": "Polygon", "coordinates": [[[-70.67, 41.51], [-70.66, 41.52], [-70.66, 41.51], '
                       '[-70.67, 41.52], [-70.67, 41.51]]]}', "the polygon is not valid"),
    "missing.toml": (None, "does not exist"),
}


@pytest.mark.parametrize("name", BAD_AREAS)
def test_a_bad_area_is_refused_in_one_line_before_a_kernel_starts(name, build_area, tmp_path, capsys, monkeypatch):
    text, message = BAD_AREAS[name]
    if text is not None:
        (tmp_path / name).write_text(text)
    monkeypatch.chdir(tmp_path)
    code = cli.main(["run", "survey_design", "--profile", "quick", "-p", "area", name, "--name", "mine"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert err.startswith("sss-locus run: error: -p area") and err.count(name) == 1 and message in err, err
    assert not (build_area / "mine").exists()  # nothing started: no staging, no failed notebook


BAD_SIGHTINGS = {  # a change to the worked example's sightings, what the refusal names
    "missing column": (lambda t: "\n".join(",".join(c for i, c in enumerate(line.split(",")) if i != 9)
                                           if not line.startswith("#") else line for line in t.splitlines()),
                       "line 2, column roll_deg: missing"),  # line 1 is a comment
    "wrong unit": (lambda t: t.replace("depth_m,", "depth_ft,"), "column depth_ft: wrong unit"),
    "NaN": (lambda t: "\n".join(",".join("NaN" if (n == 3 and i == 7) else c for i, c in enumerate(line.split(",")))
                                 for n, line in enumerate(t.splitlines(), 1)),  # line 3's heading_deg
            "line 3, column heading_deg: must be a finite"),
    "beyond the range": (lambda t: t.replace(",459,150.0,1000,", ",999,150.0,1000,").replace("150.0,", "300.0,"),
                         "beyond the sonar's maximum range"),
}


@pytest.mark.parametrize("case", BAD_SIGHTINGS)
def test_bad_sightings_are_refused_in_one_line_before_a_kernel_starts(case, build_area, tmp_path, capsys):
    edit, message = BAD_SIGHTINGS[case]
    shipped = (paths.REPO_ROOT / "data/examples/your_pings/example_sightings.csv").read_text()
    bad = tmp_path / "my_sightings.csv"
    bad.write_text(edit(shipped))
    assert bad.read_text() != shipped
    code = cli.main(["run", "your_pings", "-p", "observations", f'"{bad}"', "--name", "mine"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert err.startswith("sss-locus run: error: -p observations: my_sightings.csv line ") and message in err, err
    assert not (build_area / "mine").exists()
