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
    return area


@pytest.fixture
def run_context():
    """``run_context(**changes)``: for the rest of the test, the run context
    (:func:`sss_locus.pipeline.run.context.current`) is the current one with ``changes``; calling it
    again replaces the previous changes, ``run_context()`` with none goes back to the default."""
    from contextlib import ExitStack

    from sss_locus.pipeline.run import context

    stack = ExitStack()

    def enter(**changes):
        stack.close()
        return stack.enter_context(context.use(context.current().replace(**changes))) if changes else None

    yield enter
    stack.close()


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


def _shared_fixtures(item) -> list[str]:
    """The project's own fixtures broader than one test (module or session scope) that ``item``
    uses, the quick book aside, each with its parameter's index where it has one
    (``comparison:2``; not in brackets, which xdist would read as a test's parameters): building
    one twice would double its cost."""
    defs = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    indices = getattr(getattr(item, "callspec", None), "indices", {})
    return sorted(f"{name}:{indices[name]}" if name in indices else name
                  for name, fixturedefs in defs.items()
                  if name != "quick_book" and fixturedefs and fixturedefs[-1].baseid
                  and fixturedefs[-1].scope != "function")


#: Fixtures on the run's longest chain: the quick book, then the your-hardware page's commands on
#: it (minutes). Their tests go first, so one worker waits for the book (asleep: the book gets its
#: core) and starts them the moment it is built, while the other worker runs everything else.
LONGEST_CHAIN = {"user_book"}


def pytest_configure(config):
    # pytest-xdist declares the mark; without it (`pytest -p no:xdist`, one process)
    # --strict-markers would refuse the marks pytest_collection_modifyitems adds
    config.addinivalue_line("markers", "xdist_group(name): tests sharing a fixture, run by one worker")


@pytest.hookimpl(tryfirst=True)  # before xdist's own, which reads the xdist_group marks
def pytest_collection_modifyitems(config, items):
    """Tests of the built book run last (the order is otherwise kept), so the background build
    overlaps everything else; under pytest-xdist those of :data:`LONGEST_CHAIN` run first instead.
    Among the others, those sharing an expensive fixture (the PDF) come first. Under pytest-xdist's
    ``--dist loadgroup`` the tests sharing a module or session fixture of the project (with one
    parameter) form one group each, so that fixture is built by one worker only."""
    parallel = bool(os.environ.get("PYTEST_XDIST_WORKER"))
    shared = {item.nodeid: _shared_fixtures(item) for item in items}

    def order(item):
        if parallel and _uses_quick_book(item) and set(shared[item.nodeid]) & LONGEST_CHAIN:
            return (0, 0)
        return (1, _uses_quick_book(item), not shared[item.nodeid])

    items.sort(key=order)
    for item in items:
        if shared[item.nodeid]:
            item.add_marker(pytest.mark.xdist_group("+".join(shared[item.nodeid])))


def _quick_book(config):
    from book_support import QuickBook, shared_root

    return QuickBook(shared_root(config._tmp_path_factory.getbasetemp()))


#: Niceness an xdist worker takes once the quick book has started: the book is the start of the
#: run's longest chain (the book, then the tests that read it), so it gets the cores first, the
#: other tests what it leaves (about a quarter each while it runs, not nothing: nothing times out).
WORKER_NICENESS = 5


def pytest_collection_finish(session):
    """Start the quick book (once per run, whichever process gets here first) if a collected,
    selected test uses it; then an xdist worker lowers its own priority (and its children's)
    below the book's."""
    if any(_uses_quick_book(item) for item in session.items):
        _quick_book(session.config).start()
        if os.environ.get("PYTEST_XDIST_WORKER") and hasattr(os, "nice"):
            os.nice(WORKER_NICENESS)


def pytest_sessionfinish(session):
    """The controller (or the only process) kills a build still running when the run ends; an
    xdist worker leaves it to the others."""
    if not os.environ.get("PYTEST_XDIST_WORKER") and hasattr(session.config, "_tmp_path_factory"):
        _quick_book(session.config).stop()


@pytest.fixture(scope="session")
def quick_book(request):
    """The whole book built from the ``quick`` profile into a temporary build area and its own cache
    (started in the background at collection): ``{"area", "html", "stdout", "env"}``."""
    try:
        return _quick_book(request.config).result()
    except RuntimeError as error:
        pytest.fail(str(error))
