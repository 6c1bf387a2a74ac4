"""The visible parameters cell of an executed notebook shows the values its run used."""

from __future__ import annotations

import ast

import pytest

from sss_locus.pipeline.run import paramcell

CELL = ('platforms = ["auv", "boat"]           # keys of data/platforms.toml {keys of platforms}\n'
        "n_samples: int = 600_000               # Monte Carlo samples [100, 5_000_000]\n"
        'profile = "platform"                   # "platform" or "unconstrained"\n'
        "data_files = []  # user data files; set by --data\n")


@pytest.mark.parametrize("value", [["glider_x"], 60, 1.5e-3, "a \"quoted\" é", True, None, [[1, 2], []],
                                   {"k": [0.5]}, 123_456_789])
def test_literal_reads_back_as_the_value(value):
    assert ast.literal_eval(paramcell.literal(value)) == value


def test_the_run_values_replace_the_defaults_and_comments_stay():
    values = {"platforms": ["glider_x"], "n_samples": 2000, "profile": "platform",
              "data_files": ["/tmp/a very long path/to/the user's own file.toml"], "unused": 1}
    out = paramcell.with_values(CELL, values)
    got = {}
    exec(compile(out, "cell", "exec"), {}, got)  # what the reader would run
    got.pop("__annotations__", None)
    assert got == {k: v for k, v in values.items() if k != "unused"}
    old, new = CELL.splitlines(), out.splitlines()
    for a, b in zip(old, new):
        assert a[a.index("#"):] == b[b.index("  #") + 2:]  # each comment kept
    assert new[0].index("#") == old[0].index("#") and new[1].index("#") == old[1].index("#")  # same column
    assert paramcell.with_values(CELL, {}) == CELL


def test_only_the_parameters_cell_is_rewritten_once():
    cells = [{"cell_type": "markdown", "metadata": {}, "source": "x = 1\n"},
             {"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": list(CELL.splitlines(True))},
             {"cell_type": "code", "metadata": {"tags": ["injected-parameters"]}, "source": "n_samples = 5\n"}]
    header = "# This run's values\n"
    assert paramcell.show_run_values(cells, {"n_samples": 5}, header)
    assert paramcell.show_run_values(cells, {"n_samples": 5}, header)  # again: unchanged
    assert cells[1]["source"].count(header) == 1 and "n_samples: int = 5 " in cells[1]["source"]
    assert cells[0]["source"] == "x = 1\n" and cells[2]["source"] == "n_samples = 5\n"
    assert not paramcell.show_run_values(cells[:1], {"n_samples": 5}, header)
