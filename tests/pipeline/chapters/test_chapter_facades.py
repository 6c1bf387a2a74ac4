"""Notebooks that read like chapters (issue 41): one facade import per notebook, a facade that
re-exports exactly what its notebook calls, and glue keys filled from declared templates.

Read from the notebooks' source with :mod:`ast` (no kernel): each notebook's ``ch.<name>``
attributes against its facade's ``__all__``, each ``glue(...)`` key against the facade's
``KEYS`` templates.
"""

from __future__ import annotations

import ast
import importlib
import json
import re

import pytest

from sss_locus import paths
from sss_locus.pipeline.chapters.common import key, templates

FACADE_IMPORT = re.compile(r"^from sss_locus\.pipeline\.chapters import (\w+) as ch$", re.M)
#: Chapters without a facade yet (every chapter has one since survey_design's, issue 41).
NOT_YET: set[str] = set()
NOTEBOOKS = sorted(p for p in paths.NOTEBOOKS_DIR.glob("*.ipynb") if p.stem not in NOT_YET)


def _code(nb) -> list[str]:
    cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
    return ["\n".join(l for l in "".join(c["source"]).splitlines() if not l.lstrip().startswith(("%", "!")))
            for c in cells if c["cell_type"] == "code"]


def _trees(nb) -> list[ast.Module]:
    return [ast.parse(src) for src in _code(nb)]


def _facade(nb):
    found = [m.group(1) for src in _code(nb) for m in FACADE_IMPORT.finditer(src)]
    assert found == [nb.stem], f"{nb.name}: one import of its facade expected; found {found}"
    return importlib.import_module(f"sss_locus.pipeline.chapters.{nb.stem}")


def _is_ch(node: ast.AST, attr: str | None = None) -> bool:
    return (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "ch"
            and (attr is None or node.attr == attr))


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_the_import_cell_is_one_line(nb):
    _facade(nb)
    imports = [ast.unparse(n) for t in _trees(nb) for n in ast.walk(t) if isinstance(n, (ast.Import, ast.ImportFrom))]
    assert imports == [f"from sss_locus.pipeline.chapters import {nb.stem} as ch"]


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_facade_exports_exactly_what_its_notebook_calls(nb):
    facade = _facade(nb)
    used = {n.attr for t in _trees(nb) for n in ast.walk(t) if _is_ch(n)}
    exported = set(facade.__all__) | ({"KEYS"} if hasattr(facade, "KEYS") else set())
    assert sorted(used - exported) == [], "called by the notebook, not exported by its facade"
    assert sorted(exported - used) == [], "exported by the facade, never called by its notebook"
    assert all(hasattr(facade, name) for name in exported)


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_published_tables_are_shown_by_one_call(nb):
    """``show_table`` publishes and shows; a notebook never calls ``publish_table`` itself."""
    calls = {n.func.attr for t in _trees(nb) for n in ast.walk(t) if isinstance(n, ast.Call) and _is_ch(n.func)}
    assert "publish_table" not in calls and "files_note" not in calls


def _glue_keys(nb):
    for tree in _trees(nb):
        for n in ast.walk(tree):
            if isinstance(n, ast.Call) and _is_ch(n.func, "glue"):
                yield n.args[0]


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_glue_keys_come_from_declared_templates(nb):
    """A glued key is a literal, ``ch.key(ch.KEYS.<template>, ...)`` of a template the facade
    declares, or a name bound by a loop over a report function's texts; never an f-string or a
    concatenation in the notebook (they cannot be searched for)."""
    facade = _facade(nb)
    declared = templates(facade.KEYS) if hasattr(facade, "KEYS") else {}
    bad = []
    for arg in _glue_keys(nb):
        if isinstance(arg, ast.Constant) and isinstance(arg.value, str) or isinstance(arg, ast.Name):
            continue
        if isinstance(arg, ast.Call) and _is_ch(arg.func, "key") and isinstance(arg.args[0], ast.Attribute) \
                and _is_ch(arg.args[0].value, "KEYS") and arg.args[0].attr in declared:
            continue
        bad.append(ast.unparse(arg))
    assert bad == []


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_declared_template_is_used_and_fills(nb):
    facade = _facade(nb)
    declared = templates(facade.KEYS) if hasattr(facade, "KEYS") else {}
    used = {a.args[0].attr for t in _trees(nb) for a in ast.walk(t)
            if isinstance(a, ast.Call) and _is_ch(a.func, "key")}
    assert sorted(set(declared) - used) == []
    for name, template in declared.items():  # a template a platform key of the shipped data fills
        fields = re.findall(r"\{(\w+)\}", template)
        assert key(template, **{f: "my_auv" if f == "platform" else "x1" for f in fields}), name


def test_key_fills_a_template_and_refuses_a_wrong_field():
    assert key("wa-{platform}-deepest-m", platform="my_auv") == "wa-my-auv-deepest-m"
    assert key("nz-check-{kind}-small", kind="range") == "nz-check-range-small"
    with pytest.raises(ValueError, match=r"needs the fields \['platform'\]"):
        key("wa-{platform}-deepest-m", plaform="auv")
    with pytest.raises(ValueError, match="is empty or holds characters"):
        key("wa-{kind}", kind="Two Words")
    with pytest.raises(ValueError, match="key must match"):
        key("wa-{platform}", platform="My-AUV")
