"""Budgets estimated from a run's inputs and refused before any kernel starts (issue 38, items
2 and 3): the planning grid of ``fine_step_deg 1e-9`` (a 298 GiB allocation), a 20 km square
survey area (a kernel killed at 22 GB), a 100 km area (a grid message naming no parameter) and a
thin 200 km sliver (the feature sampler never filled). Each refusal is one line naming the
parameter to change; the book's and quick profiles fit."""

from __future__ import annotations

import math
import time

import pytest

pytest.importorskip("shapely")

from sss_locus.experiments.planning import crossing_angle_grid  # noqa: E402
from sss_locus.pipeline import budgets, cli  # noqa: E402
from sss_locus.pipeline.registry import get_entry  # noqa: E402
from sss_locus.pipeline.runner import resolve_parameters  # noqa: E402

GB = 1e9


@pytest.fixture
def machine_24gb(monkeypatch):
    """The issue's machine: 24 GB of RAM, half of it the budget."""
    monkeypatch.setenv("SSS_LOCUS_MEMORY_BUDGET", str(12 * GB))


def _area(tmp_path, vertices, name="big.toml"):
    path = tmp_path / name
    path.write_text(f"[area]\nname = '{name}'\nvertices_m = {vertices}\nwater_depth_m = 30.0\n", encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("fine, coarse", [(1.0, 5.0), (0.3, 7.0), (2.5, 0.7), (40.0, 90.0), (0.1, 0.1)])
def test_the_angle_count_is_the_grids_length(fine, coarse):
    assert abs(budgets.crossing_angle_count(fine, coarse) - len(crossing_angle_grid(fine, 40.0, coarse))) <= 2


def test_the_profiles_fit(machine_24gb):
    for name in ("planning", "survey_design", "pose_space"):
        for profile in ("book", "quick"):
            resolve_parameters(get_entry(name), profile)


def test_fine_step_1e_9_is_refused_up_front_by_run_and_answer(machine_24gb, capsys, monkeypatch):
    from sss_locus.pipeline import runner

    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    start = time.perf_counter()
    assert cli.main(["run", "planning", "--profile", "quick", "-p", "fine_step_deg", "1e-9", "--name", "b1"]) == 2
    assert cli.main(["answer", "-p", "platform", "auv", "-p", "fine_step_deg", "1e-9"]) == 2
    assert time.perf_counter() - start < 60 and not started
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("fine_step_deg" in line and "memory" in line for line in err), err


def test_a_20_km_square_area_is_refused_naming_grid_m(tmp_path, machine_24gb):
    with pytest.raises(ValueError) as info:
        resolve_parameters(get_entry("survey_design"), "quick",
                           {"area": _area(tmp_path, [[0, 0], [20000, 0], [20000, 20000], [0, 20000]])}, from_text=True)
    text = str(info.value)
    assert "grid_m" in text and "GB" in text and "\n" not in text


def test_a_100_km_area_names_grid_m_before_the_kernel(tmp_path, machine_24gb):
    with pytest.raises(ValueError, match="-p area: .* raise grid_m"):
        resolve_parameters(get_entry("survey_design"), "quick",
                           {"area": _area(tmp_path, [[0, 0], [100000, 0], [100000, 100000], [0, 100000]])},
                           from_text=True)


def test_the_coarser_grid_it_names_fits(tmp_path, machine_24gb):
    area = _area(tmp_path, [[0, 0], [20000, 0], [20000, 20000], [0, 20000]])
    with pytest.raises(ValueError) as info:
        resolve_parameters(get_entry("survey_design"), "quick", {"area": area}, from_text=True)
    named = float(str(info.value).split("to about ")[1].split(" m")[0].replace(",", ""))
    resolve_parameters(get_entry("survey_design"), "quick", {"area": area, "grid_m": str(math.ceil(named))},
                       from_text=True)


def test_a_thin_sliver_200_km_long_is_refused_not_hung(tmp_path, machine_24gb):
    # 120 m^2, 200 km along the diagonal: 0.6 mm wide, its bounding box ~2e10 m^2
    d, w = 200000 / math.sqrt(2), 0.0006 / math.sqrt(2)
    sliver = [[0, 0], [d, d], [d - w, d + w], [-w, w]]
    start = time.perf_counter()
    with pytest.raises(ValueError) as info:
        resolve_parameters(get_entry("survey_design"), "quick", {"area": _area(tmp_path, sliver)}, from_text=True)
    assert time.perf_counter() - start < 30
    assert "n_features" in str(info.value) or "narrow" in str(info.value)


def test_a_time_budget_refusal_names_the_time(monkeypatch):
    monkeypatch.setenv(budgets.TIME_BUDGET_ENV, "1")
    p = dict(get_entry("planning").resolve("quick"))
    with pytest.raises(budgets.BudgetError, match="would take about .* h, more than the budget"):
        budgets.check_parameters(dict(p, n_per_angle=[50_000, 50_000]))
    monkeypatch.setenv(budgets.TIME_BUDGET_ENV, "soon")
    with pytest.raises(budgets.BudgetError, match=budgets.TIME_BUDGET_ENV):
        budgets.check_parameters(p)
