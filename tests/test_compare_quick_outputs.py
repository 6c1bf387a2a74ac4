"""tools/compare_quick_outputs.py: an empty build area is no evidence that outputs are identical."""

import importlib.util

from sss_locus.paths import REPO_ROOT

_spec = importlib.util.spec_from_file_location("compare_quick_outputs", REPO_ROOT / "tools" / "compare_quick_outputs.py")
tool = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(tool)

SAVED = {"csv": {"fig-a.csv": "h1"}, "notebooks": {"concept": {"glue": {"k": "1"}, "tables": []}}}


def test_an_empty_build_area_is_refused_not_called_identical(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(tool, "outputs_of_ref", lambda ref: SAVED)
    assert tool.main(["54e2e63", "--build", str(tmp_path)]) == 2
    assert "holds no executed notebook" in capsys.readouterr().err


def test_a_changed_glued_value_is_a_difference(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(tool, "outputs_of_ref", lambda ref: SAVED)
    changed = {"csv": {"fig-a.csv": "h1"}, "notebooks": {"concept": {"glue": {"k": "2"}, "tables": []}}}
    monkeypatch.setattr(tool, "extract", lambda build: changed)
    assert tool.main(["54e2e63", "--build", str(tmp_path)]) == 1
    assert "concept glue k: '1' -> '2'" in capsys.readouterr().out
