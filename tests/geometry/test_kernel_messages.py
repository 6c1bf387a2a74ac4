"""Kernel API messages (issue 27, items 7-9): each misuse is refused in one line that names the
argument and what is allowed, never a library error or a ``NoneType`` crash; an empty batch has
a defined empty result; requests whose arrays would not fit in memory are refused up front."""

from __future__ import annotations

import numpy as np
import pytest

from sss_locus import Aperture, two_view_locus
from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.passes.propagation import first_order, monte_carlo
from sss_locus.experiments.stats.gaussian_norm import gaussian_norm_quantile
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.three_views.patterns import PATTERNS
from sss_locus.experiments.passes.view_sets import draw_pattern

AP = Aperture(130.0, 20.0, 150.0)
T = np.array([0.0, -2.0, 1.0])


@pytest.fixture(scope="module")
def two_views():
    views, _ = draw_pattern(load_platform("auv"), load_envelope("auv"), PATTERNS["three headings 60 deg apart"],
                            4, seed=3)
    return views.select(0, 1)


def _one_line(error) -> str:
    message = str(error.value)
    assert "\n" not in message
    return message


@pytest.mark.parametrize("call", [lambda r: r.points(), lambda r: r.point_at(0.0), lambda r: r.angle_of([1.0, 0, 0])])
def test_a_lengths_only_result_says_it_keeps_no_geometry(call):
    result = two_view_locus(np.eye(3), T, 9.0, 9.5, AP, AP, outputs="lengths")
    assert result.length > 0  # the lengths are there
    with pytest.raises(ValueError) as info:
        call(result)
    assert "outputs='lengths'" in _one_line(info) and "outputs='all'" in str(info.value)


def test_points_beyond_memory_are_refused_in_one_line(monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_MEMORY_BUDGET", str(10**9))
    result = two_view_locus(np.eye(3), T, 9.0, 9.5, AP, AP)
    with pytest.raises(MemoryError) as info:
        result.points(10**9)  # 8 arcs x 1e9 points x 3 coordinates: hundreds of GB
    assert "points(n_per_arc=1000000000)" in _one_line(info) and "budget of 1 GB" in str(info.value)
    assert result.points(3).shape == (8, 3, 3)


def test_masked_and_ragged_arguments_are_named():
    masked = np.ma.masked_array([0.0, np.nan, 1.0], mask=[False, True, False])
    with pytest.raises(TypeError) as info:
        two_view_locus(np.eye(3), masked, 9.0, 9.5, AP, AP)
    assert _one_line(info).startswith("t must be plain numbers") and "masked" in str(info.value)
    plain = np.ma.masked_array(T, mask=False)  # no masked entry: its numbers are used
    assert two_view_locus(np.eye(3), plain, 9.0, 9.5, AP, AP).length == two_view_locus(np.eye(3), T, 9.0, 9.5, AP, AP).length
    with pytest.raises(ValueError) as info:
        two_view_locus(np.eye(3), [[0.0, 1.0, 2.0], [0.0, 1.0]], 9.0, 9.5, AP, AP)
    assert _one_line(info).startswith("t must be a regular array")


def test_the_determinant_message_says_what_is_wrong():
    with pytest.raises(ValueError) as info:
        two_view_locus(np.diag([1.0, 1.0, -1.0]), T, 9.0, 9.5, AP, AP)
    assert "determinant -1 (a reflection)" in _one_line(info)
    nearly = np.diag([1.0 + 4e-10] * 3)  # orthonormal within 1e-9, but det = 1 + 1.2e-9
    with pytest.raises(ValueError) as info:
        two_view_locus(nearly, T, 9.0, 9.5, AP, AP)
    message = _one_line(info)
    assert "reflection" not in message and "|det - 1| = 1.2e-09 > 1e-09" in message


def test_monte_carlo_and_first_order_name_their_arguments(two_views, monkeypatch):
    noise = load_noise_model("auv")
    with pytest.raises(ValueError, match=r"^seed must be a non-negative integer; got -1$"):
        monte_carlo(two_views, noise, AP, seed=-1)
    with pytest.raises(ValueError, match=r"^step must be a positive number; got 'a'$"):
        first_order(two_views, noise, AP, step="a")
    monkeypatch.setenv("SSS_LOCUS_MEMORY_BUDGET", str(10**9))
    with pytest.raises(MemoryError, match=r"monte_carlo\(n_draws=1000000000000\) would need"):
        monte_carlo(two_views, noise, AP, n_draws=10**12)


def test_monte_carlo_of_no_configuration_is_an_empty_table(two_views):
    noise = load_noise_model("auv")
    some = monte_carlo(two_views, noise, AP, n_draws=8, seed=1)
    none = monte_carlo(two_views.take(slice(0, 0)), noise, AP, n_draws=8, seed=1)
    assert len(none) == 0 and list(none.columns) == list(some.columns)


@pytest.mark.parametrize("cov", [[[1.0, 0.5], [0.0, 1.0]], [[1.0, 0.0], [0.5, 1.0]]])
def test_gaussian_norm_quantile_refuses_a_non_symmetric_matrix_either_way(cov):
    with pytest.raises(ValueError, match="cov must be symmetric"):
        gaussian_norm_quantile(np.array(cov))
    # the reference: |x| of a standard 2-D normal is Rayleigh, q95 = sqrt(-2 ln 0.05)
    assert gaussian_norm_quantile(np.eye(2)) == pytest.approx(np.sqrt(-2 * np.log(0.05)), rel=1e-6)
