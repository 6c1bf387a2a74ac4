"""The four layers and their rooms, enforced on the source.

Layers: geometry <- experiments <- report <- pipeline (``paths`` is a leaf every layer may use);
the pipeline imports the report layer only in its chapter facades (``pipeline/chapters/``).
Inside ``experiments`` and ``report``, rooms follow the book (CONTRIBUTING.md, "Architecture"):
shared rooms (:data:`SHARED`, each importing only those before it) and one room per chapter,
which imports shared rooms and chapters before it in ``_toc.yml`` order, never a later one.

Reads every module of ``sss_locus`` with :mod:`ast` (no import side effects) and checks
- the import direction between layers and between rooms (a planted violation is reported:
  ``test_a_planted_violation_is_reported``), :data:`KNOWN_CROSSINGS` aside, each of which must
  still exist (fixing one means deleting it there),
- that every module of ``experiments``, ``report`` and ``pipeline`` sits in a room, and every test
  file in the tests' tree of the same rooms,
- that there is no import cycle between modules,
- that no module imports another module's ``_private`` name,
- which layers may import the heavy libraries (SymPy only in ``geometry/symbolic``, ``report``
  and the derivation chapter's facade; matplotlib and seaborn only in ``report``, the chapter
  facades and the pipeline's figure files; ``experiments`` never imports the cache or the
  pipeline),
- one job per module, with a smoke alarm at 800 lines besides docstrings,
and, in a fresh interpreter, that ``import sss_locus.geometry`` loads neither pandas,
matplotlib, SymPy nor ``scipy.stats``.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

from sss_locus import paths

PACKAGE = paths.REPO_ROOT / "sss_locus"
LAYERS = ("geometry", "experiments", "report", "pipeline")
#: Which layers each layer may import (besides itself and the leaf ``paths``).
ALLOWED = {
    "geometry": set(),
    "experiments": {"geometry"},
    "report": {"geometry", "experiments"},
    "pipeline": {"geometry", "experiments", "report"},
    "top": {"geometry"},  # sss_locus/__init__.py re-exports the geometry API
    "paths": set(),
}
#: Modules allowed to import matplotlib: the report layer, and the pipeline's figure files
#: (export writes a finished figure to PNG/SVG/PDF, publish closes it, readability measures the
#: drawn text while the PNG is saved).
MATPLOTLIB_OK = {"sss_locus.pipeline.publish.export", "sss_locus.pipeline.publish.publish",
                 "sss_locus.pipeline.publish.readability"}


#: Shared rooms of each layer, in order: each may import itself and those before it; every
#: chapter room may import all of them.
SHARED = {
    "experiments": ("stats", "datamodel", "sonar_files", "passes", "adjustment"),
    "report": ("common",),
}
#: Rooms of the pipeline, by job (no order among them; cycles are checked module by module).
PIPELINE_ROOMS = ("run", "publish", "book", "cli", "chapters")
#: A notebook whose code lives in another chapter's room (planning is the survey-pass chapter's
#: second notebook).
ROOM_OF_NOTEBOOK = {"planning": "survey_passes"}


def _chapters() -> tuple[str, ...]:
    """Chapter rooms in book order: the executed notebooks of ``_toc.yml``."""
    toc = (paths.REPO_ROOT / "_toc.yml").read_text(encoding="utf-8")
    out = []
    for name in re.findall(r"^\s*- file: executed/(\w+)\s*$", toc, flags=re.M):
        room = ROOM_OF_NOTEBOOK.get(name, name)
        if room not in out:
            out.append(room)
    return tuple(out)


CHAPTERS = _chapters()

#: Imports that cross the rooms' order today, each a module that mixes two jobs and went whole to
#: the room most of it belongs to (CONTRIBUTING.md, "Follow-ups"). Remove an entry when it is fixed.
KNOWN_CROSSINGS: set[tuple[str, str]] = set()  # none left: the noise propagation moved to passes/


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _layer(module: str) -> str:
    parts = module.split(".")
    if len(parts) == 1:
        return "top"
    return parts[1] if parts[1] in LAYERS else parts[1]


def _imports(module: str, path: Path) -> list[tuple[str, list[str]]]:
    """``(imported module, imported names)`` of every import statement, relative ones resolved."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, []) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            names = [a.name for a in node.names]
            # `from sss_locus.pipeline.publish import export` imports the module sss_locus.pipeline.publish.export
            subs = [f"{target}.{n}" for n in names if f"{target}.{n}" in MODULES]
            found += [(s, []) for s in subs] or [(target, names)]
    return found


def _internal(target: str) -> str | None:
    """The ``sss_locus`` module an import refers to (None for third-party imports)."""
    while target and target not in MODULES:
        target = target.rpartition(".")[0]
    return target or None


def test_every_module_is_in_a_layer():
    strays = [m for m in MODULES if _layer(m) not in ALLOWED]
    assert strays == [], f"modules outside the four layers and paths.py: {strays}"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_pipeline_imports_report_only_in_chapter_facades(module):
    """The chapter facades combine numbers, figures and publishing; the rest of the pipeline
    (running, caching, exporting, the book) never needs the report layer's plots or prose."""
    if _layer(module) != "pipeline" or module.startswith("sss_locus.pipeline.chapters"):
        return
    reports = sorted({i for t, _ in _imports(module, MODULES[module])
                      if (i := _internal(t)) and _layer(i) == "report"})
    assert reports == [], f"{module} imports the report layer ({reports}); only pipeline.chapters may"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_import_direction(module):
    layer = _layer(module)
    bad = []
    for target, _ in _imports(module, MODULES[module]):
        internal = _internal(target)
        if internal is None:
            continue
        other = _layer(internal)
        if other in (layer, "paths") or (other == "top" and internal == "sss_locus"
                                          and layer in ("experiments", "report", "pipeline")):
            continue
        if other not in ALLOWED[layer]:
            bad.append(f"{module} ({layer}) imports {internal} ({other})")
    assert bad == []


def _room(module: str) -> tuple[str, str] | None:
    """``(layer, room)`` of a module of ``experiments``, ``report`` or ``pipeline``; None for a
    layer's own ``__init__`` (the index of its rooms)."""
    parts = module.split(".")
    if len(parts) < 3 or parts[1] not in ("experiments", "report", "pipeline"):
        return None
    return parts[1], parts[2]


def room_violation(module: str, target: str) -> str | None:
    """Why ``module`` may not import ``target`` by the rooms' order (None if it may)."""
    a, b = _room(module), _room(target)
    if a is None or b is None or a == b or a[0] == "pipeline" or b[0] == "pipeline":
        return None
    (la, ra), (lb, rb) = a, b
    if rb in SHARED.get(lb, ()):
        if ra in CHAPTERS or la != lb or SHARED[lb].index(rb) < SHARED[la].index(ra):
            return None
        return f"{module} (shared room {la}/{ra}) imports {target} (shared room {lb}/{rb}, after it)"
    if ra in CHAPTERS and rb in CHAPTERS:
        if CHAPTERS.index(rb) <= CHAPTERS.index(ra):
            return None
        return f"{module} (chapter {ra}) imports {target} (chapter {rb}, later in the book)"
    if rb in CHAPTERS:
        return f"{module} (shared room {la}/{ra}) imports {target} (the chapter {rb})"
    return None


def room_violations(modules: dict[str, Path]) -> set[tuple[str, str, str]]:
    """``(module, target, why)`` of every import of ``modules`` that breaks the rooms' order."""
    out = set()
    for module, path in modules.items():
        for target, _ in _imports(module, path):
            internal = _internal(target)
            why = internal and room_violation(module, internal)
            if why:
                out.add((module, internal, why))
    return out


def test_every_module_is_in_a_room():
    known = {"experiments": set(SHARED["experiments"]) | set(CHAPTERS),
             "report": set(SHARED["report"]) | set(CHAPTERS), "pipeline": set(PIPELINE_ROOMS)}
    bad = []
    for module, path in MODULES.items():
        parts = module.split(".")
        if len(parts) >= 2 and parts[1] in known and not (len(parts) == 2 and path.name == "__init__.py"):
            if len(parts) < 3 or parts[2] not in known[parts[1]] or len(parts) == 3 and path.name != "__init__.py":
                bad.append(f"{module}: not in a room of {parts[1]}/ ({', '.join(sorted(known[parts[1]]))})")
    assert bad == [], "\n".join(bad)


def test_rooms_import_in_book_order():
    found = room_violations(MODULES)
    new = sorted(why for module, target, why in found if (module, target) not in KNOWN_CROSSINGS)
    assert new == [], "\n".join(new)
    gone = sorted(KNOWN_CROSSINGS - {(m, t) for m, t, _ in found})
    assert gone == [], f"fixed, now delete from KNOWN_CROSSINGS: {gone}"


def test_a_planted_violation_is_reported(tmp_path):
    """The room check is not vacuous: a chapter importing a later chapter, a shared room importing
    a chapter and the report's common room importing a chapter's figures are each reported."""
    planted = {
        "sss_locus.experiments.pose_space.planted": "from sss_locus.experiments.water.study import crop_effects\n",
        "sss_locus.experiments.stats.planted": "from sss_locus.experiments.noise import study\n",
        "sss_locus.report.common.planted": "from ..pose_space.figures import plot_heatmaps\n",
        "sss_locus.report.water.planted": "from sss_locus.report.pose_space.figures import plot_heatmaps\n",
    }
    modules = {}
    for module, code in planted.items():
        path = tmp_path / (module.replace(".", "_") + ".py")
        path.write_text(code, encoding="utf-8")
        modules[module] = path
    found = {module: why for module, _, why in room_violations(modules)}
    assert "later in the book" in found["sss_locus.experiments.pose_space.planted"]
    assert "the chapter noise" in found["sss_locus.experiments.stats.planted"]
    assert "the chapter pose_space" in found["sss_locus.report.common.planted"]
    assert "sss_locus.report.water.planted" not in found  # an earlier chapter's figures: allowed
    assert CHAPTERS.index("pose_space") < CHAPTERS.index("survey_passes") < CHAPTERS.index("water")


#: Test files that stay at the top of ``tests/``: project-wide checks and test support.
TOP_TESTS = {"test_layers.py", "test_readme.py", "test_docstrings.py", "test_metadata.py",
             "test_first_hour.py", "test_installed.py", "test_bench_build.py", "test_compare_quick_outputs.py"}


def test_tests_follow_the_rooms():
    """Tests in ``tests/geometry/``, ``tests/experiments/<room>/``, ``tests/report/`` and
    ``tests/pipeline/<job>/`` (a few project-wide checks at the top), named ``test_<module>`` or
    ``test_<property>`` with no tracker number, each name once (``tests/`` has no packages)."""
    tests = paths.REPO_ROOT / "tests"
    rooms = {"experiments": set(SHARED["experiments"]) | set(CHAPTERS), "pipeline": set(PIPELINE_ROOMS)}
    bad, seen = [], {}
    for path in sorted(tests.rglob("test_*.py")):
        rel = path.relative_to(tests).parts
        if len(rel) == 1:
            ok = rel[0] in TOP_TESTS
        elif rel[0] in ("geometry", "report"):
            ok = len(rel) == 2
        elif rel[0] in rooms:
            ok = len(rel) == 3 and rel[1] in rooms[rel[0]] or rel[0] == "experiments" and len(rel) == 2
        else:
            ok = False
        if not ok:
            bad.append(f"tests/{'/'.join(rel)}: not in a room's folder")
        if re.search(r"(issue|_i)\d+|_\d+\.py$", path.name):
            bad.append(f"tests/{'/'.join(rel)}: a tracker number in its name")
        if path.name in seen:
            bad.append(f"tests/{'/'.join(rel)}: same name as {seen[path.name]}")
        seen[path.name] = f"tests/{'/'.join(rel)}"
    assert bad == [], "\n".join(bad)
    assert not (tests / "__init__.py").exists()


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_private_name_crosses_modules(module):
    bad = []
    for target, names in _imports(module, MODULES[module]):
        if _internal(target) is None:
            continue
        bad += [f"{module} imports {n} from {target}" for n in names if n.startswith("_")]
    assert bad == []


def test_no_import_cycles():
    graph = {m: set() for m in MODULES}
    for module, path in MODULES.items():
        for target, _ in _imports(module, path):
            internal = _internal(target)
            if internal and internal != module and not module.startswith(internal + "."):
                graph[module].add(internal)
    state: dict[str, int] = {}
    cycles = []

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append(stack[stack.index(nxt):] + [nxt] if nxt in stack else [node, nxt])
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for module in sorted(graph):
        if module not in state:
            visit(module, [module])
    # a package __init__ importing its own submodules is not a cycle of logic
    cycles = [c for c in cycles if not any(b.startswith(a + ".") for a, b in zip(c, c[1:]))]
    assert cycles == []


@pytest.mark.parametrize("module", sorted(MODULES))
def test_heavy_libraries_stay_in_their_layer(module):
    layer = _layer(module)
    roots = {t.split(".")[0] for t, _ in _imports(module, MODULES[module])}
    full = {t for t, _ in _imports(module, MODULES[module])}
    if "sympy" in roots:  # a chapter facade re-exports it for the derivation chapter's notebook
        assert module.startswith(("sss_locus.geometry.symbolic", "sss_locus.pipeline.chapters.derivation")) \
            or layer == "report", module
    if roots & {"matplotlib", "seaborn", "mpl_toolkits"}:
        assert layer == "report" or module in MATPLOTLIB_OK, module
    if layer == "experiments":
        assert not any(t.startswith("sss_locus.pipeline") for t in full), module
    if layer == "geometry" and not module.startswith("sss_locus.geometry.symbolic"):
        assert not roots & {"pandas", "matplotlib", "sympy", "seaborn"}, module
        assert "scipy.stats" not in full, module


def test_geometry_import_is_light():
    code = ("import sys, sss_locus.geometry, sss_locus; "
            "print(sorted(m for m in ('pandas', 'matplotlib', 'sympy', 'scipy.stats', 'seaborn') "
            "if m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"


def test_package_exports_the_geometry_api():
    import sss_locus
    import sss_locus.geometry as geometry

    for name in ("two_view_locus", "Aperture", "LocusResult", "LocusStatus", "relative_pose",
                 "elevation_misalignment", "three_view_points", "ThreeViewResult", "ThreeViewStatus"):
        assert getattr(sss_locus, name) is getattr(geometry, name), name


#: One job per module, checked in review; this ceiling (lines besides docstrings) is only a smoke
#: alarm for a module that has grown several jobs.
SMOKE_ALARM_LINES = 800


@pytest.mark.parametrize("module", sorted(MODULES))
def test_modules_stay_small(module):
    """One job per module: at most 800 lines besides docstrings (numpydoc sections never count)."""
    text = MODULES[module].read_text(encoding="utf-8")
    docs = set()
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            docs.update(range(body[0].lineno, body[0].end_lineno + 1))
    lines = len(text.splitlines()) - len(docs)
    assert lines <= SMOKE_ALARM_LINES, (f"{module} has {lines} lines besides docstrings (smoke alarm at "
                                        f"{SMOKE_ALARM_LINES}): it has grown more than one job; split it by job")


def test_notebook_cells_read_like_chapters():
    """Code cells of at most 30 lines and no function definitions: logic lives in the package."""
    import json

    problems = []
    for nb in sorted(paths.NOTEBOOKS_DIR.glob("*.ipynb")):
        for i, cell in enumerate(json.loads(nb.read_text(encoding="utf-8"))["cells"]):
            if cell["cell_type"] != "code":
                continue
            lines = "".join(cell["source"]).splitlines()
            if len(lines) > 30:
                problems.append(f"{nb.name} cell {i}: {len(lines)} lines")
            tree = ast.parse("\n".join(l for l in lines if not l.lstrip().startswith(("%", "!"))))
            if any(isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
                   for n in ast.walk(tree)):
                problems.append(f"{nb.name} cell {i}: defines a function or class")
    assert problems == []
