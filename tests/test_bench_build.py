"""The logic of ``benchmarks/bench_build.py`` on canned inputs (it never runs ``make`` here):
pytest's summary line, the ratio table, the isolation of the two runs' caches, and papermill's
notebook durations."""

from __future__ import annotations

import importlib.util
import json

import pytest

from sss_locus import paths

_SPEC = importlib.util.spec_from_file_location("bench_build", paths.REPO_ROOT / "benchmarks" / "bench_build.py")
bench = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(bench)

#: The end of a ``make test`` log as pytest 8 with xdist writes it (colour codes included); an
#: inner pytest run of a test printed its own summary earlier, which must not count.
LOG = """\
gw0 [3312] / gw1 [3312]
.......................................................................... [ 99%]
== 4 passed in 0.31s ==
============================= slowest 15 durations =============================
512.02s call     tests/pipeline/book/test_book_build.py::test_book_builds
=========================== short test summary info ============================
SKIPPED [1] tests/test_installed.py:12: no wheel
\x1b[33m========= \x1b[32m3310 passed\x1b[0m, \x1b[33m2 skipped\x1b[0m, \x1b[33m7 warnings\x1b[0m\x1b[33m in 812.31s (0:13:32)\x1b[0m\x1b[33m ==========\x1b[0m
"""


def test_the_last_summary_line_counts():
    got = bench.parse_pytest_summary(LOG)
    assert got == {"passed": 3310, "failed": 0, "skipped": 2, "errors": 0, "warnings": 7, "pytest_s": 812.31}


@pytest.mark.parametrize("line, expected", [
    ("==== 1 failed, 10 passed, 1 error in 3.00s ====", {"passed": 10, "failed": 1, "errors": 1, "skipped": 0}),
    ("= 2 errors, 5 xfailed, 3 deselected in 59.9s =", {"passed": 0, "errors": 2, "xfailed": 5, "deselected": 3}),
    ("=================== 2349 passed in 401.10s (0:06:41) ===================", {"passed": 2349, "failed": 0}),
])
def test_summary_kinds(line, expected):
    got = bench.parse_pytest_summary("collected\n" + line + "\n")
    assert {k: got[k] for k in expected} == expected


def test_a_log_without_a_summary_has_no_counts():
    assert bench.parse_pytest_summary("make: *** [Makefile:44: test] Interrupted\n") is None
    assert bench.parse_pytest_summary("====== short test summary info ======\nFAILED x\n") is None


def test_ratio():
    assert bench.ratio(500.0, 400.0) == 1.25
    assert bench.ratio(None, 400.0) is None and bench.ratio(1.0, 0.0) is None


def _run(wall, cpu, exit_code=0, passed=None):
    tests = None if passed is None else {"passed": passed, "failed": 0, "skipped": 0, "errors": 0}
    return {"wall_s": wall, "cpu_s": cpu, "exit": exit_code, "tests": tests}


def test_table_rows_and_ratios():
    result = {"labels": ["before", "after"], "revisions": {"before": "1ca624e" + "0" * 33, "after": "2bd5071" + "0" * 33},
              "phases": {"test": {"runs": {"before": _run(900.0, 420.0, passed=2349), "after": _run(1200.0, 630.0, passed=3300)},
                                  "load": {"mean": 6.0, "min": 4.25, "max": 9.0, "samples": 3}},
                         "book": {"runs": {"before": _run(1000.0, 660.0), "after": _run(1000.0, 0.0, exit_code=2)},
                                  "load": None}}}
    text = bench.table(result)
    rows = [r for r in text.splitlines() if r.startswith("| make")]
    assert len(rows) == 6  # two revisions and a ratio per target, tests first
    assert rows[0].split("|")[2].strip() == "before (1ca624e)" and "| 2349 |" in rows[0]
    assert "| 3300 |" in rows[1] and "| 6.0 (4.2–9.0) |" in rows[1]
    assert "**1.33**" in rows[2] and "**1.50**" in rows[2]  # 1200/900 wall, 630/420 CPU
    assert "| 2 |" in rows[4]  # the failed book's exit code is shown
    assert "**1.00**" in rows[5] and "**0.00**" in rows[5]


def test_the_two_runs_share_no_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", "/somewhere/shared")
    places = ("TMPDIR", "XDG_CACHE_HOME", "XDG_CONFIG_HOME", "XDG_DATA_HOME", "MPLCONFIGDIR", "IPYTHONDIR",
              "JUPYTER_CONFIG_DIR", "JUPYTER_DATA_DIR", "JUPYTER_RUNTIME_DIR")
    a, b = bench._isolated_env(tmp_path / "a"), bench._isolated_env(tmp_path / "b")
    for env, home in ((a, tmp_path / "a"), (b, tmp_path / "b")):
        assert env["CI"] == "true" and "SSS_LOCUS_CACHE_DIR" not in env
        for var in places:
            assert env[var].startswith(str(home) + "/"), var
            assert (home / env[var].rsplit("/", 1)[1]).is_dir()
    assert len({a[v] for v in places} | {b[v] for v in places}) == 2 * len(places)


def test_notebook_durations(tmp_path):
    executed = tmp_path / "_build" / "source" / "executed"
    executed.mkdir(parents=True)
    (executed / "noise.ipynb").write_text(json.dumps({"metadata": {"papermill": {"duration": 61.26}}}))
    (executed / "plain.ipynb").write_text(json.dumps({"metadata": {}}))
    (executed / "broken.ipynb").write_text("{not json")
    (tmp_path / "_build" / "html").mkdir()
    (tmp_path / "_build" / "html" / "noise.ipynb").write_text(json.dumps({"metadata": {"papermill": {"duration": 61.26}}}))
    assert bench.notebook_durations(tmp_path) == {"_build/source/executed/noise.ipynb": 61.3}


def test_book_log_notebook_times():
    log = ("start concept [book] at 21:55:48 UTC\n"
           "ran concept [book] in 35.4 s -> /x/_build/source/executed/concept.ipynb\n"
           "  figures and tables: fig-concept -> /x\n"
           "ran pose_space [book] in 885.7 s -> /x/pose_space.ipynb\n"
           "  5/12 notebooks done, 579 s elapsed\n"
           "ran survey_design [quick] in 12 s -> /x/survey_design.ipynb\n")
    assert bench.parse_book_log(log) == {"concept": 35.4, "pose_space": 885.7, "survey_design": 12.0}
    assert bench.parse_book_log("Built in 1900 s. Open the book:\n") == {}


def test_results_of_two_runs_merge_into_one_table():
    revs = {"before": "a" * 40, "after": "b" * 40}
    test_run = {"labels": ["before", "after"], "revisions": revs,
                "phases": {"test": {"runs": {"before": _run(1, 10.0, passed=5), "after": _run(1, 20.0, passed=6)}, "load": None}}}
    book_run = dict(test_run, phases={"book": {"runs": {"before": _run(1, 40.0), "after": _run(1, 30.0)}, "load": None}})
    rows = [r for r in bench.table(bench.merge_results([test_run, book_run])).splitlines() if "after / before" in r]
    assert ["**2.00**" in rows[0], "**0.75**" in rows[1]] == [True, True]
    with pytest.raises(SystemExit, match="different revisions"):
        bench.merge_results([test_run, dict(book_run, revisions={"before": "c" * 40, "after": "b" * 40})])
