"""Shared pytest setup for the sss_locus tests.

* Puts this directory on ``sys.path`` so the test-support module ``reference_locus`` imports
  the same way under every pytest import mode.
* ``build_area``: a fixture giving each test its own build area and cache (environment
  variables), so pipeline tests never touch ``_build/`` or ``.cache/``.
* Registers hypothesis profiles: ``default`` (no per-example deadline: the first call of a
  numpy kernel can be slow on a loaded machine, and speed is measured in ``benchmarks/``, not
  in tests) and ``thorough`` (more examples; select with ``--hypothesis-profile=thorough``).
* Skipped checks: on a developer's machine a check whose tool is missing (Chromium, poppler,
  pdflatex/bibtex, actionlint) is skipped and named at the end of the run; in CI (environment
  variable ``CI`` set to ``true`` or ``1``, as ``.ci/run`` and GitHub Actions run) every skip is
  reported as a failure instead, since ``.ci/install-tools`` provides the tools there.
"""

from __future__ import annotations

import os
import sys

import pytest

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

try:
    from hypothesis import HealthCheck, settings
except ImportError:  # hypothesis is a test extra; tests that need it importorskip it
    pass
else:
    settings.register_profile(
        "default",
        deadline=None,
        max_examples=100,
        suppress_health_check=[HealthCheck.too_slow],
    )
    settings.register_profile(
        "thorough",
        deadline=None,
        max_examples=2000,
        suppress_health_check=[HealthCheck.too_slow],
    )
    settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


@pytest.fixture
def build_area(tmp_path, monkeypatch):
    """A private build area (``<tmp>/build``) and cache for one test; returns the build area."""
    area = tmp_path / "build"
    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(area))
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("SSS_LOCUS_FIGURES_DIR", raising=False)
    return area


# -- skipped checks: named on a developer's machine, failures in CI ---------------------------------

def in_ci() -> bool:
    """Whether this run is CI's (``CI=true``/``1``): no check may be skipped there."""
    return os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")


def _skip_reason(report) -> str:
    longrepr = report.longrepr
    return str(longrepr[2] if isinstance(longrepr, tuple) and len(longrepr) == 3 else longrepr)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.skipped and not hasattr(report, "wasxfail") and in_ci():
        report.outcome = "failed"
        report.longrepr = f"skipped in CI (CI={os.environ['CI']}), where every check must run: {_skip_reason(report)}"


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    outcome = yield
    report = outcome.get_result()
    if report.skipped and in_ci():  # a module-level importorskip
        report.outcome = "failed"
        report.longrepr = f"skipped in CI (CI={os.environ['CI']}), where every check must run: {_skip_reason(report)}"


def pytest_terminal_summary(terminalreporter):
    skipped = terminalreporter.stats.get("skipped", [])
    if skipped:
        terminalreporter.section("checks that did not run on this machine")
        for report in skipped:
            terminalreporter.write_line(f"{report.nodeid}: {_skip_reason(report).removeprefix('Skipped: ')}")
        terminalreporter.write_line("(.ci/install-tools installs their tools as root; in CI a skip fails the run)")


# -- the shared quick book, built while the other tests run (see book_support) ----------------------

def _uses_quick_book(item) -> bool:
    return "quick_book" in getattr(item, "fixturenames", ())


def pytest_collection_modifyitems(config, items):
    """Tests of the built book run last (the order is otherwise kept), so the background build
    started by ``_background_quick_book`` overlaps everything else."""
    items.sort(key=_uses_quick_book)


@pytest.fixture(scope="session", autouse=True)
def _background_quick_book(request, tmp_path_factory):
    """Starts the quick book at the session's first test if any collected test uses it."""
    build = None
    if any(_uses_quick_book(item) for item in request.session.items):
        from book_support import QuickBook

        build = QuickBook(tmp_path_factory.mktemp("quick-book"))
    yield build
    if build is not None:
        build.stop()


@pytest.fixture(scope="session")
def quick_book(_background_quick_book):
    """The whole book built from the ``quick`` profile into a temporary build area and its own cache
    (started in the background at the session's start): ``{"area", "html", "stdout", "env"}``."""
    try:
        return _background_quick_book.result()
    except RuntimeError as error:
        pytest.fail(str(error))
