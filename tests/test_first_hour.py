"""A new user's first hour with a surface boat of their own (issue 37): the BlueBoat example,
warnings for legal but odd hardware, the answer's readable names."""

from __future__ import annotations

import pytest

from sss_locus.experiments.datamodel import userdata
from sss_locus.paths import REPO_ROOT

BLUEBOAT = REPO_ROOT / "data" / "examples" / "my_blueboat.toml"


@pytest.fixture(autouse=True)
def _shipped_data_afterwards():
    yield
    userdata.use()


def test_the_blueboat_example_passes_every_check_and_is_a_surface_boat():
    from sss_locus.experiments.datamodel.envelopes import load_envelope
    from sss_locus.experiments.datamodel.platforms import load_platform

    inputs = userdata.use([BLUEBOAT])
    assert userdata.hardware_flags(inputs) == []
    boat, env = load_platform("my_blueboat"), load_envelope("my_blueboat")
    assert boat.depth_min_m == boat.depth_max_m == 0 and boat.pitch_max_deg == 0
    assert env.same_altitude and env.pitch_min_deg == env.pitch_max_deg == 0


def test_a_fan_reaching_above_the_horizontal_is_flagged_for_the_users_platform_only():
    """A 20° look-down with an 80° fan: the fan's top edge is 20 - 80/2 = -20°, 20° above the
    horizontal (the example of the issue). The paper's AUV (130° fan at 25.5°) does the same
    and is not flagged: only what the user's data adds or changes is."""
    wide = userdata.make_inputs([BLUEBOAT], ["sonars.omniscan_450_ss.azimuth_deg=80",
                                             "platforms.my_blueboat.transducers.port.tilt_deg=20"])
    flags = userdata.hardware_flags(wide)
    mine = [f for f in flags if f.startswith("platforms.my_blueboat.transducers.port.")]
    assert len(mine) == 1 and "top 20 deg ABOVE the horizontal" in mine[0]
    assert any(f.startswith("platforms.my_blueboat.transducers.starboard.") and "top 10 deg ABOVE" in f
               for f in flags)  # 30 - 40
    assert not any(f.startswith("platforms.auv.") for f in flags)
    assert userdata.hardware_flags(userdata.make_inputs([], [])) == []  # the shipped data: silent
    under = userdata.make_inputs([BLUEBOAT], ["platforms.my_blueboat.transducers.port.tilt_deg=70"])
    assert any("bottom 5 deg past the vertical" in f for f in userdata.hardware_flags(under))  # 70 + 25 - 90


def test_answer_names_every_driver_in_words_and_reads_both_offset_models(build_area, capsys):
    """Issue 37: the drivers were printed as column names (``abs_psi2_deg``, ``r1_m``) and only the
    independent-offsets answer was shown (the matched one needed an undocumented
    ``-p offset_models '["matched:10:same"]'``)."""
    import re

    from sss_locus.experiments.pose_space.stats import CANDIDATES
    from sss_locus.pipeline.cli import answer, command as cli

    assert set(answer.QUANTITY_WORDS) == set(CANDIDATES)  # a word for every quantity ranked
    code = cli.main(["answer", "--data", str(BLUEBOAT), "-p", "platform", "my_blueboat", "--top", "14"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert not any(re.search(rf"\b{q}\b", out) for q in CANDIDATES), out  # no column name left
    drivers = re.findall(r"^  (\d+) +(.+?) +(-?\d\.\d\d) +(-?\d\.\d\d) to (-?\d\.\d\d)$", out, re.M)
    assert drivers and all(d[1] in answer.QUANTITY_WORDS.values() for d in drivers)
    assert "- independent offsets" in out and "- matched ±10 m, same side offsets" in out
    assert "lawnmower" in out and "steer pass 2" in out  # which way of flying each answer is for
    assert cli.main(["answer", "--data", str(BLUEBOAT), "-p", "platform", "my_blueboat",
                     "--offsets", "matched"]) == 0
    out = capsys.readouterr().out
    assert "- matched" in out and "- independent" not in out


def test_a_users_file_is_published_by_name_and_sha256_never_by_its_local_path(tmp_path, monkeypatch, run_context):
    """Issue 37: manifests carried the absolute local path of the user's data file."""
    import hashlib
    import json

    from sss_locus import paths
    from sss_locus.pipeline.publish import publish

    mine = tmp_path / "home" / "me" / "myboat.toml"
    mine.parent.mkdir(parents=True)
    mine.write_bytes(BLUEBOAT.read_bytes())
    assert paths.public_path(mine) == "myboat.toml"
    assert paths.public_path(BLUEBOAT) == "data/examples/my_blueboat.toml"
    run_context(parameters={"data_files": [str(mine)], "area": str(mine), "platforms": ["my_blueboat"], "seed": 1})
    params = publish.run_parameters()
    assert params == {"data_files": ["myboat.toml"], "area": "myboat.toml", "platforms": ["my_blueboat"], "seed": 1}
    userdata.use([mine])
    record = userdata.figure_record(["my_blueboat"])
    user = [f for f in record["files"] if f["role"] == "user"]
    assert user == [{"path": "myboat.toml", "sha256": hashlib.sha256(mine.read_bytes()).hexdigest(), "role": "user"}]
    assert str(tmp_path) not in json.dumps(record)


def test_a_named_books_front_page_and_every_page_say_what_it_was_built_from(build_area, monkeypatch, tmp_path, run_context):
    """Issue 37: a user's book had the reproduction's title and introduction, nothing naming the
    build area, the profile or the data."""
    import hashlib
    import json

    import yaml

    from sss_locus import paths
    from sss_locus.pipeline.book import areanotice, bookbuild
    from sss_locus.pipeline.run.registry import load_registry

    run_context(build_name="myboat")
    mine = tmp_path / "home" / "myboat.toml"
    mine.parent.mkdir()
    mine.write_bytes(BLUEBOAT.read_bytes())
    sha = hashlib.sha256(mine.read_bytes()).hexdigest()
    entries = load_registry()
    for name in ("rigs", "planning"):
        path = entries[name].executed_path()
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps({"cells": [], "metadata": {"sss_locus": {
            "profile": "quick", "parameters": {"platforms": ["boat", "my_blueboat"], "data_files": [str(mine)]},
            "data": {"files": [{"path": "data/platforms.toml", "sha256": "0" * 64, "role": "shipped"},
                               {"path": str(mine), "sha256": sha, "role": "user"}], "overrides": []}}}}))
    path = entries["survey_design"].executed_path()  # the shipped example area is not the user's data
    path.write_text(json.dumps({"cells": [], "metadata": {"sss_locus": {
        "profile": "quick", "parameters": {"platforms": ["boat"], "area": "data/examples/survey_area.toml"}}}}))
    summary = areanotice.area_summary(list(entries.values()))
    assert summary == {"name": "myboat", "profiles": ["quick"], "platforms": ["boat", "my_blueboat"],
                       "files": {"myboat.toml": sha}, "overrides": [], "chapters": 3}
    area = tmp_path / "home" / "bay.toml"
    area.write_text("[area]\n")
    path.write_text(path.read_text().replace("data/examples/survey_area.toml", str(area)))
    assert areanotice.area_summary(list(entries.values()))["files"] == {
        "myboat.toml": sha, "bay.toml": hashlib.sha256(area.read_bytes()).hexdigest()}
    root = paths.source_dir()
    front = tmp_path / "intro.md"
    front.write_text("# Two sidescan views of one feature\n\nA sidescan sonar ping ...\n")
    bookbuild.stage_config(root, [], front_page=front)
    page = front.read_text()
    assert page.startswith("# Two sidescan views of one feature\n\n```{important}\n")
    assert "build area `myboat`" in page and "`quick`" in page and "`my_blueboat`" in page
    assert f"`myboat.toml` (SHA-256 `{sha[:12]}…`)" in page and str(tmp_path) not in page
    config = yaml.safe_load((root / "_config.yml").read_text())
    assert "myboat" in config["title"]
    assert "Build area &#x27;myboat&#x27;" in config["html"]["announcement"]
    assert "myboat.toml" in config["html"]["announcement"] and str(tmp_path) not in config["html"]["announcement"]
    run_context()  # the reproduction: nothing added
    front.write_text("# T\n")
    bookbuild.stage_config(root, [], front_page=front)
    assert front.read_text() == "# T\n" and "announcement" not in (yaml.safe_load(
        (root / "_config.yml").read_text()).get("html") or {}) or not yaml.safe_load(
        (root / "_config.yml").read_text())["html"].get("announcement")


def test_a_shipped_file_keeps_its_repository_path_whatever_the_working_folder(tmp_path, monkeypatch):
    """A kernel runs in the executed copies' folder: the shipped data/platforms.toml must not be
    resolved against it (a first version published _build/source/executed/data/platforms.toml)."""
    from sss_locus import paths

    monkeypatch.chdir(tmp_path)
    assert paths.public_path("data/platforms.toml") == "data/platforms.toml"
    userdata.use([])
    files = userdata.figure_record(["boat"])["files"]
    assert files and all(f["path"] == f"data/{(paths.DATA_DIR / f['path'][5:]).name}" for f in files)
    assert all((paths.REPO_ROOT / f["path"]).is_file() for f in files)


def test_the_downloadable_notebooks_carry_no_local_path(build_area, tmp_path):
    """The site's copies of the executed notebooks (``notebooks/<name>.ipynb``) kept the user's
    file and papermill's paths in their metadata."""
    import json

    from sss_locus import paths
    from sss_locus.pipeline.book import bookbuild

    mine = tmp_path / "home" / "myboat.toml"
    executed = paths.executed_dir() / "rigs.ipynb"
    executed.parent.mkdir(parents=True)
    executed.write_text(json.dumps({"cells": [], "metadata": {
        "papermill": {"input_path": str(tmp_path / "stage" / "rigs.ipynb"), "parameters": {"data_files": [str(mine)]}},
        "sss_locus": {"parameters": {"data_files": [str(mine)], "platforms": ["boat"]}}}}))
    bookbuild.stage_figure_pages(paths.source_dir(), [])
    published = (paths.extra_dir() / "notebooks" / "rigs.ipynb").read_text()
    assert str(tmp_path) not in published and "myboat.toml" in published
    assert str(tmp_path) in executed.read_text()  # the build area's own copy keeps them (staleness checks)


def test_a_users_area_file_is_named_by_its_name_in_captions_and_the_injected_cell(tmp_path):
    """A user's area outside the repository: the plan's caption ("water depth 8.5 m
    (/home/me/harbour.toml: water_depth_m)", "Area file `/home/me/...`"), the tables' notes and
    the page's injected-parameters cell carried its local absolute path."""
    import json

    from sss_locus.experiments.survey_design.area import load_area
    from sss_locus.pipeline.run import runner

    mine = tmp_path / "home" / "me" / "harbour.toml"
    mine.parent.mkdir(parents=True)
    mine.write_text('[area]\nname = "Cove"\nvertices_m = [[0, 0], [400, 0], [400, 300], [0, 300]]\n'
                    'water_depth_m = 8.5\n')
    area = load_area(mine)
    assert (area.source, area.water_depth_source) == ("harbour.toml", "harbour.toml: water_depth_m")
    assert str(tmp_path) not in json.dumps(area.key()) and area.path == str(mine.resolve())
    shipped = load_area(REPO_ROOT / "data" / "examples" / "survey_area.toml")
    assert shipped.source == "data/examples/survey_area.toml"  # as the reproduction's runs give it
    executed = tmp_path / "run.ipynb"
    executed.write_text(json.dumps({"cells": [{"cell_type": "code", "metadata": {"tags": ["injected-parameters"]},
                                               "source": f'# Parameters\narea = "{mine}"\n', "outputs": []}],
                                    "metadata": {}}))
    runner._label_injected_cell(executed, "quick", {"area": str(mine), "seed": 1}, {})
    cell = json.loads(executed.read_text())["cells"][0]
    assert str(tmp_path) not in "".join(cell["source"]) and 'area = "harbour.toml"' in "".join(cell["source"])


def test_a_named_books_notice_names_the_users_truth_file(build_area, monkeypatch, tmp_path, run_context):
    """The your-pings chapter run on a user's sightings with a truth file of their own (its map
    draws each estimate's distance from it): the front page and the line atop every page named
    the sightings but not the truth file; the shipped example's truth stays unnamed."""
    import hashlib
    import json

    from sss_locus import paths
    from sss_locus.pipeline.book import areanotice
    from sss_locus.pipeline.run.registry import load_registry

    run_context(build_name="harbour")
    sightings, truth = tmp_path / "home" / "my_sightings.csv", tmp_path / "home" / "my_truth.csv"
    sightings.parent.mkdir()
    sightings.write_text("feature\n")
    truth.write_text("feature,east_m,north_m,up_m\n")
    entries = load_registry()
    path = entries["your_pings"].executed_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    meta = {"profile": "quick", "parameters": {"observations": str(sightings), "truth": str(truth)}}
    path.write_text(json.dumps({"cells": [], "metadata": {"sss_locus": meta}}))
    files = areanotice.area_summary(list(entries.values()))["files"]
    assert files == {"my_sightings.csv": hashlib.sha256(sightings.read_bytes()).hexdigest(),
                     "my_truth.csv": hashlib.sha256(truth.read_bytes()).hexdigest()}
    meta["parameters"]["truth"] = "data/examples/your_pings/example_truth.csv"  # the shipped example's
    path.write_text(json.dumps({"cells": [], "metadata": {"sss_locus": meta}}))
    assert list(areanotice.area_summary(list(entries.values()))["files"]) == ["my_sightings.csv"]


def test_the_sites_source_copies_of_the_notebooks_carry_no_local_path(tmp_path):
    """Each page's download button links ``_sources/executed/<name>.ipynb``, Sphinx's copy of the
    staged executed notebook, whose metadata kept the user's files and the build area's absolute
    paths (only the ``notebooks/`` copies were made public)."""
    import json

    from sss_locus.pipeline.book import bookbuild

    mine = tmp_path / "home" / "me" / "harbour.toml"
    source = tmp_path / "html" / "_sources" / "executed" / "survey_design.ipynb"
    source.parent.mkdir(parents=True)
    cells = [{"cell_type": "markdown", "metadata": {}, "source": "# Survey design\n"}]
    source.write_text(json.dumps({"cells": cells, "metadata": {
        "papermill": {"input_path": str(tmp_path / "stage" / "survey_design.ipynb"), "parameters": {"area": str(mine)}},
        "sss_locus": {"parameters": {"area": str(mine), "data_files": [str(tmp_path / "ranger.toml")]}}}}))
    bookbuild.public_sources(tmp_path / "html")
    published = json.loads(source.read_text())
    assert str(tmp_path) not in json.dumps(published) and published["cells"] == cells
    assert published["metadata"]["sss_locus"]["parameters"] == {"area": "harbour.toml", "data_files": ["ranger.toml"]}
