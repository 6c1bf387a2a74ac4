"""Citable tables: a table's manifest and BibTeX name exactly the platforms and data files it was
computed from, and a run commits, replaces and removes its tables like its figures."""

from __future__ import annotations

import hashlib
import json

import pandas as pd
import pytest

from sss_locus.experiments.datamodel import userdata
from sss_locus.paths import REPO_ROOT
from sss_locus.pipeline.publish import export
from sss_locus.pipeline.run import outputs
from sss_locus.pipeline.publish.table_export import export_table

EXAMPLE = REPO_ROOT / "data" / "examples" / "my_auv.toml"


def _table(out, label, notebook="notebooks/x.ipynb", platforms=None, value=1.0, input_files=()):
    frame = pd.DataFrame({"platform": ["my_auv"], "peak_deg": [value]})
    return export_table(frame, label, caption="Peak angles.", parameters={"platforms": ["auv", "my_auv"], "seed": 3},
                        notebook=notebook, out_dir=out, platforms=platforms, input_files=input_files)


def test_a_table_names_only_its_own_platforms_and_files(tmp_path):
    user = tmp_path / "my_auv.toml"
    user.write_bytes(EXAMPLE.read_bytes())
    userdata.use([str(user)], [])
    try:
        manifest = _table(tmp_path / "figures", "tab-peaks", platforms=["my_auv"])
    finally:
        userdata.use([], [])
    out = tmp_path / "figures"
    assert sorted(p.name for p in out.iterdir()) == ["tab-peaks.bib", "tab-peaks.csv", "tab-peaks.json"]
    assert json.loads((out / "tab-peaks.json").read_text()) == manifest
    inputs = manifest["data_inputs"]
    assert inputs["platforms"] == ["my_auv"] and "platforms.auv" not in inputs["entries"]
    assert [(f["path"], f["sha256"]) for f in inputs["files"]] == [
        (user.name, hashlib.sha256(user.read_bytes()).hexdigest())]  # its name, never a local path
    for name, entry in manifest["files"].items():
        assert entry["sha256"] == hashlib.sha256((out / name).read_bytes()).hexdigest()
    bib = (out / "tab-peaks.bib").read_text()
    assert bib.startswith("@misc{sss-locus:tab-peaks,") and "Table tab-peaks" in bib and "Figure" not in bib
    assert pd.read_csv(out / "tab-peaks.csv").to_dict("list") == {"platform": ["my_auv"], "peak_deg": [1.0]}
    assert export.load_manifests(out) == [] and [m["label"] for m in export.load_manifests(out, export.KINDS)] == [
        "tab-peaks"]  # the figure index and checks see figures only


def test_a_table_from_a_users_own_file_names_it_with_its_hash(tmp_path):
    """A table computed from a user's observations (the your-pings features table) names that
    file beside the platform's data entries, with the file's own SHA-256."""
    sightings = tmp_path / "my_sightings.csv"
    sightings.write_text("feature,ping\nF01,1\n", encoding="utf-8")
    manifest = _table(tmp_path / "figures", "tab-features", platforms=["auv"], input_files=[sightings])
    inputs = manifest["data_inputs"]
    assert inputs["platforms"] == ["auv"]
    assert {"path": "my_sightings.csv", "sha256": hashlib.sha256(sightings.read_bytes()).hexdigest(),
            "role": "observations"} in inputs["files"]
    digest = hashlib.sha256(sightings.read_bytes()).hexdigest()[:12]
    assert f"my\\_sightings.csv (sha256 {digest})" in (tmp_path / "figures" / "tab-features.bib").read_text()


def test_a_bad_table_label_is_refused(tmp_path):
    with pytest.raises(ValueError, match="tab-some-name"):
        _table(tmp_path, "fig-peaks")


def test_a_run_commits_its_tables_and_drops_those_it_no_longer_makes(tmp_path):
    figures, staged = tmp_path / "figures", tmp_path / "staged"
    _table(figures, "tab-old")
    _table(figures, "tab-kept", value=1.0)
    _table(figures, "tab-other", notebook="notebooks/y.ipynb")
    _table(staged, "tab-kept", value=2.0)
    nb = tmp_path / "run.ipynb"
    nb.write_text("{}")
    labels = outputs.commit_run(nb, staged, tmp_path / "executed" / "x.ipynb", figures, "notebooks/x.ipynb")
    assert labels == ["tab-kept"]
    assert sorted(p.name for p in figures.glob("*.json")) == ["tab-kept.json", "tab-other.json"]
    assert pd.read_csv(figures / "tab-kept.csv")["peak_deg"].tolist() == [2.0]  # the new values
