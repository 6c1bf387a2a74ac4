"""Every public function outside ``pipeline/`` documents its parameters and what it
returns in numpydoc sections (``Parameters``, ``Returns``), each parameter by name.

A small parser of numpydoc sections (numpydoc itself is not in the environment): a section is
a title line followed by a line of dashes; a parameter entry is a line ``name : type`` (or
``name1, name2 : type``, or ``name`` alone) at the section's indentation. Functions that return
``None`` (annotated ``-> None``) need no ``Returns``; generators may have ``Yields`` instead.
"""

from __future__ import annotations

import importlib
import inspect
import re

import pytest

def _all_modules() -> tuple[str, ...]:
    """Every module of the package outside ``pipeline/`` (the issue's rule: numpydoc sections on
    every public function outside the pipeline), by dotted name."""
    from sss_locus import paths

    package = paths.PACKAGE_DIR
    out = []
    for f in sorted(package.rglob("*.py")):
        rel = f.relative_to(package.parent).with_suffix("")
        parts = list(rel.parts[:-1] if rel.name == "__init__" else rel.parts)
        if len(parts) > 1 and parts[1] == "pipeline":
            continue
        out.append(".".join(parts))
    return tuple(out)


MODULES = _all_modules()
"""Every module of ``sss_locus`` outside ``pipeline/``, held to the rule."""



def sections(doc: str) -> dict[str, list[str]]:
    """The numpydoc sections of a docstring: title -> its lines (dedented)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    out, title = {}, None
    for i, line in enumerate(lines):
        if i + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[i + 1].strip()) and line.strip():
            title = line.strip()
            out[title] = []
        elif title is not None and not re.fullmatch(r"-{3,}", line.strip()):
            out[title].append(line)
    return out


def documented_names(lines: list[str]) -> set[str]:
    """Parameter names of the entries of a Parameters section (lines not indented)."""
    names = set()
    for line in lines:
        if line and not line[0].isspace():
            head = line.split(" : ")[0]
            names.update(n.strip().lstrip("*") for n in head.split(","))
    return names


def public_functions(module):
    for name, fn in vars(module).items():
        if name.startswith("_") or not inspect.isfunction(fn) or fn.__module__ != module.__name__:
            continue
        yield name, fn
    for cname, cls in vars(module).items():
        if cname.startswith("_") or not inspect.isclass(cls) or cls.__module__ != module.__name__:
            continue
        for name, fn in vars(cls).items():
            fn = fn.__func__ if isinstance(fn, (classmethod, staticmethod)) else fn
            if not name.startswith("_") and inspect.isfunction(fn):
                yield f"{cname}.{name}", fn


def problems(fn) -> list[str]:
    sec = sections(fn.__doc__)
    sig = inspect.signature(fn)
    params = [p for p in sig.parameters if p not in ("self", "cls")]
    out = []
    if params:
        if "Parameters" not in sec:
            out.append("no Parameters section")
        else:
            missing = [p for p in params if p not in documented_names(sec["Parameters"])]
            if missing:
                out.append(f"Parameters lacks {missing}")
    returns_none = sig.return_annotation in (None, "None")
    if not returns_none and "Returns" not in sec and "Yields" not in sec:
        out.append("no Returns section")
    return out


@pytest.mark.parametrize("module", MODULES)
def test_public_functions_have_parameters_and_returns(module):
    mod = importlib.import_module(module)
    bad = {name: p for name, fn in public_functions(mod) if (p := problems(fn))}
    assert not bad, f"{module}: " + "; ".join(f"{n}: {', '.join(p)}" for n, p in bad.items())


def test_the_parser_reads_numpydoc_sections():
    def documented(a, b, *, c=1) -> int:
        """Summary.

        Parameters
        ----------
        a, b : float
            Two numbers.
        c : int
            A third.

        Returns
        -------
        int
        """

    def undocumented(a, b) -> int:
        """Summary only; ``a`` and ``b`` named in prose.

        Parameters
        ----------
        a : float
            described, ``b`` not
        """

    assert problems(documented) == []
    assert problems(undocumented) == ["Parameters lacks ['b']", "no Returns section"]
