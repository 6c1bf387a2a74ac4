"""Notebook registry and parameter validation (sss_locus.pipeline.run.registry)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from sss_locus import paths
from sss_locus.pipeline.run.registry import (
    ParameterError,
    get_entry,
    load_registry,
    parse_notebook_parameters,
    parse_parameters_source,
    validate_parameters,
)

CELL = '''\
n_points = 200          # Monte Carlo samples
scale: float = 1        # metres per unit
name = "auv"
flag = False
sizes = [1, 2]
extra = None
'''


def write_notebook(path: Path, parameters_source: str) -> Path:
    nb = {
        "cells": [
            {"cell_type": "markdown", "metadata": {}, "source": "# T"},
            {"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": parameters_source,
             "outputs": [], "execution_count": None},
        ],
        "metadata": {}, "nbformat": 4, "nbformat_minor": 5,
    }
    path.write_text(json.dumps(nb))
    return path


def test_parse_types_defaults_and_comments():
    spec = parse_parameters_source(CELL)
    assert list(spec) == ["n_points", "scale", "name", "flag", "sizes", "extra"]
    assert [p.type for p in spec.values()] == ["int", "float", "str", "bool", "list", "any"]
    assert spec["n_points"].default == 200 and spec["n_points"].doc == "Monte Carlo samples"
    assert spec["scale"].default == 1 and spec["scale"].doc == "metres per unit"


@pytest.mark.parametrize("source, fragment", [
    ("import numpy as np\n", "only simple assignments"),
    ("n = 2 * 3\n", "must be a literal"),
    ("n: numpy = 3\n", "annotation"),
    ("n: int = 1.5\n", "not a int"),
    ("n = (\n", "not valid Python"),
])
def test_parse_rejects_non_literal_cells(source, fragment):
    with pytest.raises(ParameterError, match=fragment):
        parse_parameters_source(source)


def test_unknown_name_lists_valid_parameters_with_types_and_defaults():
    spec = parse_parameters_source(CELL)
    with pytest.raises(ParameterError) as err:
        validate_parameters(spec, {"n_point": 3}, notebook="demo")
    message = str(err.value)
    assert "no parameter 'n_point'" in message
    for line in ("n_points: int = 200  # Monte Carlo samples", "scale: float = 1", "name: str = 'auv'",
                 "flag: bool = False", "sizes: list = [1, 2]", "extra: any = None"):
        assert line in message


@pytest.mark.parametrize("name, value", [
    ("n_points", 2.5), ("n_points", True), ("n_points", "7"), ("scale", "x"), ("flag", 1),
    ("name", 3), ("sizes", {"a": 1}),
])
def test_wrong_type_is_rejected(name, value):
    spec = parse_parameters_source(CELL)
    with pytest.raises(ParameterError, match=f"parameter '{name}' = .*expected a") as info:
        validate_parameters(spec, {name: value}, notebook="demo")
    assert "\n" not in str(info.value)  # one line: parameter, value, what is allowed


def test_values_of_the_right_type_are_kept_or_widened():
    spec = parse_parameters_source(CELL)
    checked = validate_parameters(spec, {"n_points": 5, "scale": 2, "flag": True, "extra": [1]}, notebook="d")
    assert checked == {"n_points": 5, "scale": 2.0, "flag": True, "extra": [1]}
    assert isinstance(checked["scale"], float)


@pytest.mark.parametrize("name, text, expected", [
    ("n_points", "12", 12), ("scale", "2", 2.0), ("scale", "1e-3", 1e-3), ("flag", "true", True),
    ("flag", "False", False), ("name", "boat", "boat"), ("name", "12", "12"), ("sizes", "[3, 4]", [3, 4]),
    ("extra", "hello", "hello"),
])
def test_command_line_text_is_converted_to_the_declared_type(name, text, expected):
    spec = parse_parameters_source(CELL)
    value = validate_parameters(spec, {name: text}, notebook="d", from_text=True)[name]
    assert value == expected and type(value) is type(expected)


@pytest.mark.parametrize("text", ['"boat"', "'boat'", ' "boat" '])
def test_a_quoted_string_on_the_command_line_is_the_string(text):
    """``-p name '"boat"'`` (a string literal, as the chapters write it for file names and
    choices) means ``boat``, like the unquoted form; quotes inside a value stay."""
    spec = parse_parameters_source(CELL)
    assert validate_parameters(spec, {"name": text}, notebook="d", from_text=True)["name"] == "boat"
    assert validate_parameters(spec, {"name": 'say "hi"'}, notebook="d", from_text=True)["name"] == 'say "hi"'


@pytest.mark.parametrize("name, text", [("n_points", "1.5"), ("n_points", "ten"), ("flag", "maybe"),
                                         ("sizes", "3")])
def test_command_line_text_of_the_wrong_type_is_rejected(name, text):
    spec = parse_parameters_source(CELL)
    with pytest.raises(ParameterError, match=f"parameter '{name}' = '?{text}'?.*expected a") as info:
        validate_parameters(spec, {name: text}, notebook="d", from_text=True)
    assert "\n" not in str(info.value)


def _registry(tmp_path: Path, body: str) -> Path:
    write_notebook(tmp_path / "nb.ipynb", CELL)
    path = tmp_path / "registry.toml"
    path.write_text(body)
    return path


def test_registry_entry_resolves_defaults_profile_and_overrides(tmp_path):
    reg = _registry(tmp_path, '[notebooks.demo]\nsource = "nb.ipynb"\nexecuted = "executed/demo.ipynb"\n'
                              '[notebooks.demo.profiles.book]\n[notebooks.demo.profiles.quick]\nn_points = 10\n')
    entry = load_registry(reg, root=tmp_path)["demo"]
    assert entry.resolve("book")["n_points"] == 200
    assert entry.resolve("quick")["n_points"] == 10
    resolved = entry.resolve("quick", {"scale": "3"}, from_text=True)
    assert resolved["n_points"] == 10 and resolved["scale"] == 3.0 and resolved["name"] == "auv"
    with pytest.raises(ParameterError, match="no profile 'fast'"):
        entry.resolve("fast")


@pytest.mark.parametrize("body, fragment", [
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "executed/d.ipynb"\n[notebooks.d.profiles.book]\n',
     "quick required"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nprofiles = {book = {}, quick = {}}\n', "missing key"),
    ('[notebooks.d]\nsource = "none.ipynb"\nexecuted = "e/d.ipynb"\nprofiles = {book = {}, quick = {}}\n',
     "no such notebook"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "../d.ipynb"\nprofiles = {book = {}, quick = {}}\n',
     "relative .ipynb path"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "e/d.ipynb"\nprofile = {}\nprofiles = {book = {}, quick = {}}\n',
     "unknown key"),
])
def test_malformed_registry_is_rejected(tmp_path, body, fragment):
    with pytest.raises(ValueError, match=fragment):
        load_registry(_registry(tmp_path, body), root=tmp_path)


def test_profile_with_unknown_parameter_is_rejected(tmp_path):
    reg = _registry(tmp_path, '[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "e/d.ipynb"\n'
                              'profiles = {book = {}, quick = {npoints = 3}}\n')
    entry = load_registry(reg, root=tmp_path)["d"]
    with pytest.raises(ParameterError, match="no parameter 'npoints'"):
        entry.resolve("quick")


def test_notebook_without_parameters_cell_has_no_parameters(tmp_path):
    path = write_notebook(tmp_path / "x.ipynb", "")
    nb = json.loads(path.read_text())
    nb["cells"][1]["metadata"] = {}
    path.write_text(json.dumps(nb))
    assert parse_notebook_parameters(path) == {}


# --- the project's own registry -------------------------------------------------------------

REGISTRY = load_registry()


@pytest.mark.parametrize("name", list(REGISTRY))
def test_every_registered_profile_matches_its_notebook(name):
    entry = REGISTRY[name]
    for profile in entry.profiles:
        entry.resolve(profile)  # raises on an unknown name or a wrong type


def test_toc_lists_every_registered_notebook_exactly_once():
    yaml = pytest.importorskip("yaml")
    toc = yaml.safe_load(paths.TOC_FILE.read_text())
    files = [c["file"] for part in toc["parts"] for c in part["chapters"]]
    executed = [f for f in files if f.startswith(paths.EXECUTED_SUBDIR + "/")]
    registered = [e.executed.removesuffix(".ipynb") for e in REGISTRY.values()]
    assert sorted(executed) == sorted(registered)
    assert len(set(files)) == len(files)


def test_get_entry_by_name_or_source_path():
    for entry in REGISTRY.values():
        assert get_entry(entry.name) == entry
        assert get_entry(entry.source_relative) == entry
    with pytest.raises(ValueError, match="unknown notebook 'no-such-notebook'"):
        get_entry("no-such-notebook")
