"""One rule for where a run writes (issue 38, item 1): a side run (``--output``) writes only
beside its path, which lies outside the reproduction's build area and every named area, whatever
``--name`` and ``--replace-reproduction`` say; checked before any kernel starts.

The two data-loss commands of the issue come first: ``--name n024 --output
_build/source/executed/<chapter>.ipynb`` (the reproduction's executed chapter) and ``--name n025
--output _build/a010/source/executed/<chapter>.ipynb`` (another named area's)."""

from __future__ import annotations

import itertools
import os

import pytest

pytest.importorskip("papermill")

from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.cli import command as cli
from sss_locus.pipeline.run import preflight, runner  # noqa: E402

#: Where a side run might be pointed, relative to the reproduction's build area ``build``.
INSIDE = {
    "reproduction chapter": lambda build, tmp: build / "source" / "executed" / "concept.ipynb",
    "another named area": lambda build, tmp: build / "a010" / "source" / "executed" / "concept.ipynb",
    "this named area": lambda build, tmp: build / "n024" / "source" / "executed" / "concept.ipynb",
    "reproduction figures": lambda build, tmp: build / "source" / "_extra" / "x.ipynb",
    "build root": lambda build, tmp: build / "x.ipynb",
    "not yet existing area": lambda build, tmp: build / "zz" / "deep" / "x.ipynb",
    "result cache": lambda build, tmp: tmp / "cache" / "x.ipynb",
}
FLAGS = [([], "no flags"), (["--name", "n024"], "--name"), (["--replace-reproduction"], "--replace"),
         (["--name", "n024", "--replace-reproduction"], "--name --replace")]


@pytest.fixture
def no_kernel(monkeypatch):
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    return started


def _tree(build):
    """Results of the reproduction and of a named area, to check they are left byte for byte."""
    files = {}
    for path in [build / "source" / "executed" / "concept.ipynb", build / "a010" / "source" / "executed" / "concept.ipynb"]:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text('{"cells": []}', encoding="utf-8")
    for root, _, names in os.walk(build):
        for name in names:
            files[os.path.join(root, name)] = open(os.path.join(root, name), "rb").read()
    return files


def test_the_issues_two_data_loss_commands_are_refused(build_area, tmp_path, no_kernel, capsys):
    before = _tree(build_area)
    assert cli.main(["run", "concept", "--name", "n024", "--output",
                     str(build_area / "source" / "executed" / "concept.ipynb")]) == 2
    assert cli.main(["run", "concept", "--name", "n025", "--output",
                     str(build_area / "a010" / "source" / "executed" / "concept.ipynb")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("inside the build area" in line for line in err), err
    assert not no_kernel and _tree(build_area) == before
    assert not (build_area / "source" / "executed" / "figures").exists()


@pytest.mark.parametrize("where, flags", list(itertools.product(sorted(INSIDE), FLAGS)),
                         ids=lambda v: v if isinstance(v, str) else v[1])
def test_no_flag_combination_lets_a_side_run_into_a_build_area(build_area, tmp_path, no_kernel, capsys, where, flags):
    before = _tree(build_area)
    target = INSIDE[where](build_area, tmp_path)
    assert cli.main(["run", "concept", *flags[0], "--output", str(target)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert ("inside the build area" in err or "result cache" in err or "--replace-reproduction" in err), err
    assert not no_kernel and _tree(build_area) == before
    assert not (target.parent / "figures").exists() and (target.exists() == (str(target) in before))


def test_a_link_named_figures_into_the_build_area_is_followed(build_area, tmp_path, no_kernel, capsys):
    side = tmp_path / "side"
    side.mkdir()
    (build_area / "source" / "_extra" / "figures").mkdir(parents=True)
    (side / "figures").symlink_to(build_area / "source" / "_extra" / "figures")
    assert cli.main(["run", "concept", "--name", "n024", "--output", str(side / "x.ipynb")]) == 2
    assert "would put its figures inside the build area" in capsys.readouterr().err and not no_kernel


def test_a_linked_output_folder_is_resolved_before_the_check(build_area, tmp_path, no_kernel, capsys):
    (build_area / "source").mkdir(parents=True)
    (tmp_path / "link").symlink_to(build_area / "source")
    assert cli.main(["run", "concept", "--output", str(tmp_path / "link" / "x.ipynb")]) == 2
    assert "inside the build area" in capsys.readouterr().err and not no_kernel


@pytest.mark.parametrize("flags", [[], ["--name", "n024"]])
def test_outside_every_build_area_a_side_run_is_allowed(build_area, tmp_path, flags, monkeypatch):
    seen = []
    monkeypatch.setattr(runner, "run_notebook", lambda entry, *a, output=None, **k: seen.append(
        preflight.check_side_output(output, entry)))
    assert cli.main(["run", "concept", *flags, "--output", str(tmp_path / "side" / "x.ipynb")]) == 0
    assert seen == [(tmp_path / "side" / "x.ipynb").resolve()]


def test_replace_reproduction_with_output_is_refused_not_ignored(build_area, tmp_path, no_kernel, capsys):
    assert cli.main(["run", "concept", "--replace-reproduction", "--output", str(tmp_path / "s" / "x.ipynb")]) == 2
    err = capsys.readouterr().err
    assert "contradict" in err and len(err.strip().splitlines()) == 1 and not no_kernel


def test_the_repositorys_default_build_area_is_protected_when_another_is_in_use(build_area, no_kernel, capsys):
    assert paths.build_dir() != paths.REPO_ROOT / "_build"
    target = paths.REPO_ROOT / "_build" / "source" / "executed" / "never.ipynb"
    assert cli.main(["run", "concept", "--output", str(target)]) == 2
    assert "inside the build area" in capsys.readouterr().err and not target.exists()
