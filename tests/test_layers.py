"""The four layers: geometry <- experiments <- report <- pipeline, enforced on the source.

Reads every module of ``sss_locus`` with :mod:`ast` (no import side effects) and checks
- the import direction between layers (``paths`` is a leaf every layer may use),
- that there is no import cycle between modules,
- that no module imports another module's ``_private`` name,
- which layers may import the heavy libraries (SymPy only in ``geometry/symbolic``, ``report``
  and the derivation chapter's facade; matplotlib
  and seaborn only in ``report`` and in the pipeline's figure files; ``experiments`` never
  imports the cache or the pipeline),
and, in a fresh interpreter, that ``import sss_locus.geometry`` loads neither pandas,
matplotlib, SymPy nor ``scipy.stats``.
"""

from __future__ import annotations

import ast
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


@pytest.mark.parametrize("module", sorted(MODULES))
def test_modules_stay_small(module):
    """At most 400 lines besides docstrings (numpydoc sections must never force a split)."""
    text = MODULES[module].read_text(encoding="utf-8")
    docs = set()
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            docs.update(range(body[0].lineno, body[0].end_lineno + 1))
    lines = len(text.splitlines()) - len(docs)
    assert lines <= 400, f"{module} has {lines} lines besides docstrings (limit 400: split it by job)"


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
