"""Notebook parameters as pydantic models (sss_locus.pipeline.run.params and
sss_locus.pipeline.chapters.params): every notebook's cell is its model, what papermill reads
equals the model's defaults, and a bad value is refused in one line at the declared bound."""

from __future__ import annotations

import ast
import json
import math

import papermill
import pytest
from annotated_types import Ge, Gt, Le, Lt

from sss_locus import paths
from sss_locus.experiments.datamodel import userdata
from sss_locus.pipeline.run import paramcell
from sss_locus.pipeline.run.params import NotebookParams
from sss_locus.pipeline.run.registry import ParameterError, get_entry, load_registry, params_model

REGISTRY = load_registry()


def test_every_registered_notebook_declares_a_params_model():
    assert all(issubclass(params_model(name) or object, NotebookParams) for name in REGISTRY)


@pytest.mark.parametrize("name", list(REGISTRY))
def test_papermill_reads_the_models_names_and_defaults_from_the_cell(name):
    """papermill's own inspection (what it injects after) finds exactly the model's parameters,
    in order, with the model's defaults."""
    model = params_model(name)
    seen = papermill.inspect_notebook(str(REGISTRY[name].source))
    assert list(seen) == list(model.model_fields)
    for key, found in seen.items():
        default = model.model_fields[key].default
        value = ast.literal_eval(found["default"])
        assert value == default and type(value) is type(default), key


@pytest.mark.parametrize("name", list(REGISTRY))
def test_the_cell_is_the_rendered_model(name):
    """The comment of each line (description and rule) comes from the model, not typed twice."""
    nb = json.loads(REGISTRY[name].source.read_text(encoding="utf-8"))
    cell = next(c for c in nb["cells"] if "parameters" in c["metadata"].get("tags", []))
    assert "".join(cell["source"]) == paramcell.parameters_cell(params_model(name)), \
        "run: python -m sss_locus.pipeline.run.paramcell --write"


def _bounded():
    """Every scalar float or int parameter of every chapter with a declared bound: (notebook,
    name, bound, inclusive, below?)."""
    for name in REGISTRY:
        for key, field in params_model(name).model_fields.items():
            if field.annotation not in (int, float) and "int" not in str(field.annotation):
                continue
            for m in field.metadata:
                if isinstance(m, (Ge, Gt, Le, Lt)):
                    bound = next(getattr(m, a) for a in ("ge", "gt", "le", "lt") if hasattr(m, a))
                    yield name, key, bound, isinstance(m, (Ge, Le)), isinstance(m, (Ge, Gt))


@pytest.mark.parametrize("notebook, name, bound, inclusive, lower", list(_bounded()))
def test_a_bound_is_enforced_where_declared_and_named_in_the_error(notebook, name, bound, inclusive, lower,
                                                                   monkeypatch):
    monkeypatch.setattr("sss_locus.geometry.validation.memory_budget_setting", lambda: str(10**15))
    entry = get_entry(notebook)
    is_int = isinstance(entry.parameters()[name].default, int)
    step = 1 if is_int else max(abs(bound) * 1e-9, 1e-9)
    outside = bound - step if lower else bound + step
    if inclusive:
        entry.resolve("quick", {name: str(bound)}, from_text=True)  # the bound itself is allowed
    else:
        outside = bound
    with pytest.raises(ParameterError) as info:
        entry.resolve("quick", {name: str(outside)}, from_text=True)
    message = str(info.value)
    shown = str(int(bound)) if float(bound).is_integer() else repr(bound)
    assert f"notebook '{notebook}': parameter '{name}' = " in message and "out of range" in message
    assert shown in message and "\n" not in message


@pytest.mark.parametrize("notebook, name, text, fragment", [
    ("pose_space", "profile", "vehicle", "is not allowed: one of 'platform', 'unconstrained'"),
    ("reconstruction", "navigation", '"per_ping"', "one of 'per_pass', 'per_view'"),
    ("survey_passes", "paper_band_deg", "[10.0, 20.0, 30.0]", "has 3 value(s): allowed a non-empty list of float "
                                                               "with exactly 2 values; [0, 180]"),
    ("planning", "n_per_angle", "[3000, 2.5]", "parameter 'n_per_angle[1]' = 2.5: must be int"),
    ("three_views", "seed", "true", "expected a value of type int"),
])
def test_choices_lengths_and_element_types_are_refused_in_one_line(notebook, name, text, fragment):
    with pytest.raises(ParameterError) as info:
        get_entry(notebook).resolve("quick", {name: text}, from_text=True)
    assert fragment in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("typed", ['-p platforms ["auv","boat"]', "-p platforms [auv,boat]", "-p platforms auv"])
def test_a_list_whose_quotes_the_shell_removed_gets_the_command_that_keeps_them(typed):
    import shlex

    arrived = shlex.split(typed)[2]  # what the shell hands the command: no double quotes left
    with pytest.raises(ParameterError) as info:
        get_entry("pose_space").resolve("quick", {"platforms": arrived}, from_text=True)
    hint = str(info.value).split("for the shell: ")[-1]
    assert hint.startswith("-p platforms '") and "\n" not in str(info.value), info.value
    again = shlex.split(hint)[2]  # the suggested command, through the shell
    wanted = ["auv"] if typed.endswith("auv") else ["auv", "boat"]
    assert get_entry("pose_space").resolve("quick", {"platforms": again}, from_text=True)["platforms"] == wanted


def test_a_misspelt_notebook_or_profile_gets_the_closest_one():
    with pytest.raises(ValueError, match=r"unknown notebook 'pose_spaec' \(did you mean 'pose_space'\?\); registered"):
        get_entry("pose_spaec")
    with pytest.raises(ParameterError, match=r"no profile 'quik' \(did you mean 'quick'\?\); profiles: book, quick"):
        get_entry("pose_space").resolve("quik", {})


def test_an_unknown_name_gets_the_closest_one():
    with pytest.raises(ParameterError, match="no parameter 'n_sampels' \\(did you mean 'n_samples'\\?\\)"):
        get_entry("pose_space").resolve("quick", {"n_sampels": "5"}, from_text=True)


def test_a_count_that_cannot_fit_in_memory_is_refused_before_work(monkeypatch):
    """``MemoryPerUnit(2800)`` on pose_space's ``n_samples``: with a 100 MB budget 30000 samples
    (84 MB) pass and 40000 (112 MB) are refused, naming the need and the budget; a run that
    keeps the profile's 20000 samples is not refused for the default's 1.2 million."""
    monkeypatch.setattr("sss_locus.geometry.validation.memory_budget_setting", lambda: str(10**8))
    entry = get_entry("pose_space")
    assert entry.resolve("quick", {"n_samples": "30000"}, from_text=True)["n_samples"] == 30000
    assert entry.resolve("quick", {"seed": "2"}, from_text=True)["n_samples"] == 20000
    with pytest.raises(ParameterError) as info:
        entry.resolve("quick", {"n_samples": "40000"}, from_text=True)
    assert "parameter 'n_samples' = 40000 needs about 112 MB of memory" in str(info.value)
    assert "budget of 100 MB" in str(info.value)
    with pytest.raises(ParameterError, match="= 5000001 is out of range"):  # the declared range first
        entry.resolve("quick", {"n_samples": "5000001"}, from_text=True)


def test_a_data_key_is_read_when_checked_so_a_users_platform_is_allowed():
    entry = get_entry("water")
    with pytest.raises(ParameterError, match="'platforms\\[1\\]' = 'my_auv' is not allowed: a key of \\[platforms\\]"):
        entry.resolve("quick", {"platforms": '["auv", "my_auv"]'}, from_text=True)
    try:
        userdata.use([paths.REPO_ROOT / "data" / "examples" / "my_auv.toml"])
        assert entry.resolve("quick", {"platforms": '["auv", "my_auv"]'}, from_text=True)["platforms"] == \
            ["auv", "my_auv"]
        assert "'my_auv'" in entry.parameters()["platforms"].describe()
    finally:
        userdata.use()


def test_numbers_are_widened_not_coerced_and_never_infinite():
    entry = get_entry("water")
    values = entry.resolve("quick", {"crossing_step_deg": "5", "submerged_depths_m": "[2, 10]"}, from_text=True)
    assert values["crossing_step_deg"] == 5.0 and isinstance(values["crossing_step_deg"], float)
    assert all(isinstance(v, float) for v in values["submerged_depths_m"])
    with pytest.raises(ParameterError, match="must be a finite number"):
        entry.resolve("quick", {"crossing_step_deg": math.inf})
