"""Move the modules and tests into their rooms (issue 41) and rewrite every reference to them.

The mapping is ``tools/rooms.toml``. Run from the repository root, on a clean work tree::

    .venv/bin/python tools/rooms.py            # moves (git mv) and rewrites; prints what it did
    .venv/bin/python tools/rooms.py --check    # only reports what it would move, or refuses

What it does, in order:

1. refuses (exit 2, naming them) when a module or test of a flat folder (``checked``) is in
   neither ``[moves]`` nor ``stay``, when a target already exists while its source does too, or
   when a notebook does not round-trip byte for byte through ``json`` (its style unknown);
2. ``git mv``\\ s every listed file whose old path still exists (a second run finds none and does
   nothing: idempotent), and creates each new room's ``__init__.py`` from ``[rooms]`` where the
   room has none (an existing one, e.g. the data model's, is left alone);
3. rewrites every reference in the repository's text files (``exclude`` aside): relative imports
   that cross a moved module become absolute; ``from sss_locus.experiments import a, b`` is split
   per new location (``import ... as`` keeps each local name); dotted names anywhere
   (``sss_locus.experiments.noise`` -> ``sss_locus.experiments.noise.study``: imports, monkeypatch
   targets, ``python -m``, entry points), their short forms (``report.text``) in comments, strings
   and prose, file paths (``sss_locus/report/text.py``, ``tests/test_survey.py`` and a renamed
   test's bare file name), ``:mod:`.x``` references of a moved module, the quoted short module
   names of ``[short_names]`` files, imports of a renamed test module, and ``Path(__file__)``
   parents of a moved test; notebooks are edited as JSON (``indent=1``, each file's own
   ``ensure_ascii``);
4. replaces the docstring of each layer's ``__init__.py`` by the index of its rooms.
"""

from __future__ import annotations

import argparse
import ast
import io
import json
import re
import subprocess
import sys
import textwrap
import tokenize
import tomllib
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MAPPING = REPO / "tools" / "rooms.toml"
TEXT_SUFFIXES = {".py", ".md", ".toml", ".yml", ".yaml", ".ipynb", ".cfg", ".txt", ".ini", ".cff", ".json", ""}
LAYERS = ("experiments", "report", "pipeline")


def refuse(lines: list[str]) -> None:
    sys.stderr.write("tools/rooms.py: refused:\n" + "".join(f"  {line}\n" for line in lines))
    raise SystemExit(2)


def dotted(path: str) -> str:
    """``sss_locus/report/text.py`` -> ``sss_locus.report.text`` (a package's ``__init__`` -> the package)."""
    parts = path.removesuffix(".py").split("/")
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def git(*args: str) -> str:
    return subprocess.run(["git", *args], cwd=REPO, check=True, capture_output=True, text=True).stdout


class Plan:
    """The pending moves and every name and path they change."""

    def __init__(self, cfg: dict):
        self.cfg = cfg
        moves = cfg["moves"]
        self.pending = {old: new for old, new in moves.items() if (REPO / old).exists()}
        code = {o: n for o, n in self.pending.items() if o.startswith("sss_locus/") and n}
        self.modules = {dotted(o): dotted(n) for o, n in code.items()}
        for old, new in cfg.get("packages", {}).items():
            if (REPO / old).exists():
                self.modules[dotted(old)] = dotted(new)
        self.old_packages = {m.rpartition(".")[0] for m in self.modules}
        self.code_paths = {o: n for o, n in code.items()}
        self.code_paths.update({o + "/": n + "/" for o, n in cfg.get("packages", {}).items() if (REPO / o).exists()})
        tests = {o: n for o, n in self.pending.items() if o.startswith("tests/")}
        self.test_paths = tests
        self.test_names = {Path(o).stem: Path(n).stem for o, n in tests.items() if Path(o).stem != Path(n).stem}
        self.new_to_old = {n: o for o, n in self.pending.items() if n}
        # short forms: experiments.noise -> experiments.noise.study
        self.short = {m.removeprefix("sss_locus."): n.removeprefix("sss_locus.") for m, n in self.modules.items()
                      if m.count(".") >= 2}

    # -- checks --------------------------------------------------------------------------------
    def check(self) -> None:
        cfg = self.cfg
        listed = set(cfg["moves"]) | set(cfg["stay"])
        strays = sorted(str(p.relative_to(REPO)) for pattern in cfg["checked"] for p in REPO.glob(pattern)
                        if str(p.relative_to(REPO)) not in listed)
        if strays:
            refuse([f"{s}: not in tools/rooms.toml ([moves] or stay); give it a room" for s in strays])
        clashes = [f"{o} -> {n}: the target exists already" for o, n in self.pending.items()
                   if n and (REPO / n).exists()]
        names = defaultdict(list)
        for path in [*(n for o, n in cfg["moves"].items() if o.startswith("tests/")), *cfg["stay"]]:
            if path.startswith("tests/") and Path(path).name.startswith("test_"):
                names[Path(path).name].append(path)
        clashes += [f"{name}: two test files of that name ({', '.join(p)}); tests/ has no packages"
                    for name, p in names.items() if len(p) > 1]
        for old, new in self.pending.items():
            if not new:  # a package merged into a room: its __init__ may hold nothing but a docstring
                tree = ast.parse((REPO / old).read_text(encoding="utf-8"))
                if len(tree.body) > 1 or (tree.body and ast.get_docstring(tree) is None):
                    clashes.append(f"{old}: holds code besides its docstring; move it into the room by hand first")
        if clashes:
            refuse(clashes)

    # -- the moves -----------------------------------------------------------------------------
    def move(self) -> None:
        for old, new in self.pending.items():
            if not new:
                git("rm", "-q", old)
                continue
            (REPO / new).parent.mkdir(parents=True, exist_ok=True)
            git("mv", old, new)
        for room, text in self.cfg["rooms"].items():
            init = REPO / room / "__init__.py"
            if (REPO / room).is_dir() and not init.exists():
                init.write_text(f'"""{text}\n"""\n', encoding="utf-8")
                git("add", str(init.relative_to(REPO)))
        for old in self.cfg.get("packages", {}):
            folder = REPO / old
            if folder.is_dir() and not any(p.suffix == ".py" for p in folder.rglob("*")):
                for leftover in sorted(folder.rglob("*"), reverse=True):  # __pycache__ only
                    leftover.unlink() if leftover.is_file() else leftover.rmdir()
                folder.rmdir()

    # -- rewriting -----------------------------------------------------------------------------
    def old_module_of(self, path: str) -> str:
        """The dotted name a file had before the moves."""
        return dotted(self.new_to_old.get(path, path))

    def absolute_imports(self, text: str, path: str) -> str:
        """Relative imports of a moved file, or that reach a moved module, made absolute."""
        if not path.startswith("sss_locus/"):
            return text
        module = self.old_module_of(path)
        old_path = self.new_to_old.get(path, path)
        package = module if old_path.endswith("__init__.py") else module.rpartition(".")[0]
        moved_file = path in self.new_to_old
        tree = ast.parse(text)
        lines = text.splitlines(keepends=True)
        for node in sorted((n for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.level),
                           key=lambda n: n.lineno, reverse=True):
            base = package.split(".")
            base = base[: len(base) - (node.level - 1)]
            target = ".".join(base + ([node.module] if node.module else []))
            reaches = target in self.modules or target in self.old_packages and any(
                f"{target}.{a.name}" in self.modules for a in node.names)
            if not (moved_file or reaches):
                continue
            i = node.lineno - 1
            lines[i] = re.sub(r"\bfrom\s+\.+[\w.]*(\s+import)", lambda m: f"from {target}{m.group(1)}", lines[i], count=1)
        return "".join(lines)

    def split_imports(self, text: str) -> str:
        """``from <old package> import a, b`` split per new location of the moved modules."""
        try:
            tree = ast.parse(text)
        except SyntaxError:
            return text
        lines = text.splitlines(keepends=True)
        nodes = [n for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and not n.level
                 and n.module in self.old_packages
                 and any(f"{n.module}.{a.name}" in self.modules for a in n.names)]
        for node in sorted(nodes, key=lambda n: n.lineno, reverse=True):
            first, last = lines[node.lineno - 1], lines[node.end_lineno - 1]
            indent = first[: node.col_offset]
            if indent.strip():
                refuse([f"an import after other code on its line: {first.strip()}"])
            groups: dict[str, list[str]] = {}
            for alias in node.names:
                old = f"{node.module}.{alias.name}"
                local = alias.asname or alias.name
                if old in self.modules:
                    parent, _, leaf = self.modules[old].rpartition(".")
                else:
                    parent, leaf = node.module, alias.name
                groups.setdefault(parent, []).append(leaf if leaf == local else f"{leaf} as {local}")
            tail = last[node.end_col_offset:]
            new = "\n".join(f"{indent}from {parent} import {', '.join(names)}" for parent, names in groups.items())
            lines[node.lineno - 1: node.end_lineno] = [new + tail]
        return "".join(lines)

    def split_text_imports(self, text: str) -> str:
        """``from <old package> import a, b`` written in prose, a string or a comment (a ``-c``
        script, a README's example), split like :meth:`split_imports`: joined by ``; `` where the
        statement is followed by ``;``, else one line each at the same indentation."""
        if not self.old_packages:
            return text
        names = r"[A-Za-z_]\w*(?: as \w+)?(?:, *[A-Za-z_]\w*(?: as \w+)?)*"
        pattern = re.compile(r"(?<![\w.])from (" + "|".join(map(re.escape, sorted(self.old_packages, key=len, reverse=True)))
                             + r") import (" + names + r")(?![\w,(])(;?)")

        def repl(m):
            package, aliases, semicolon = m.group(1), m.group(2), m.group(3)
            if not any(f"{package}.{a.split(' as ')[0].strip()}" in self.modules for a in aliases.split(",")):
                return m.group(0)
            groups: dict[str, list[str]] = {}
            for alias in aliases.split(","):
                name, _, local = alias.strip().partition(" as ")
                local = local or name
                old = f"{package}.{name}"
                parent, leaf = self.modules[old].rpartition(".")[::2] if old in self.modules else (package, name)
                groups.setdefault(parent, []).append(leaf if leaf == local else f"{leaf} as {local}")
            line_start = text.rfind("\n", 0, m.start()) + 1
            indent = re.match(r"[ \t>]*", text[line_start:m.start()]).group(0) if text[line_start:m.start()].strip(" \t>") == "" else None
            sep = "; " if semicolon or indent is None else "\n" + indent
            return sep.join(f"from {p} import {', '.join(n)}" for p, n in groups.items()) + semicolon
        return pattern.sub(repl, text)

    def names_and_paths(self, text: str, python: bool) -> str:
        """Dotted names, their short forms and file paths rewritten (one pass each: no chains)."""
        if self.modules:
            pattern = re.compile(r"(?<![\w.])(" + "|".join(map(re.escape, sorted(self.modules, key=len, reverse=True)))
                                 + r")(?!\w)")
            text = pattern.sub(lambda m: self.modules[m.group(1)], text)
        if self.short:
            short = re.compile(r"(?<![\w./])(" + "|".join(map(re.escape, sorted(self.short, key=len, reverse=True)))
                               + r")(?!\w)")
            if python:
                text = _in_strings_and_comments(text, lambda s: short.sub(lambda m: self.short[m.group(1)], s))
            else:
                text = short.sub(lambda m: self.short[m.group(1)], text)
        code_paths = {}
        for old, new in self.code_paths.items():
            code_paths[old] = new
            code_paths[old.removeprefix("sss_locus/")] = new.removeprefix("sss_locus/")
        if code_paths:
            pattern = re.compile(r"(?<![\w/.])(" + "|".join(map(re.escape, sorted(code_paths, key=len, reverse=True)))
                                 + r")(?![\w])")
            text = pattern.sub(lambda m: code_paths[m.group(1)], text)
        if self.test_paths:
            pattern = re.compile(r"(?<![\w/.])(" + "|".join(map(re.escape, sorted(self.test_paths, key=len, reverse=True)))
                                 + r")(?!\w)")
            text = pattern.sub(lambda m: self.test_paths[m.group(1)], text)
        if self.test_names:
            bare = re.compile(r"(?<![\w/.])(" + "|".join(map(re.escape, self.test_names)) + r")\.py(?!\w)")
            text = bare.sub(lambda m: self.test_names[m.group(1)] + ".py", text)
            if python:
                imp = re.compile(r"^(\s*(?:from|import)\s+)(" + "|".join(map(re.escape, self.test_names)) + r")(?=\s|$)", re.M)
                text = imp.sub(lambda m: m.group(1) + self.test_names[m.group(2)], text)
        return text

    def sphinx_refs(self, text: str, path: str) -> str:
        """``:mod:`.x``` of a moved file: relative to its old package, rewritten to the new place."""
        if path not in self.new_to_old or not path.startswith("sss_locus/"):
            return text
        old_package = self.old_module_of(path).rpartition(".")[0]
        new_package = dotted(path).rpartition(".")[0]

        def repl(m):  # the old absolute name: the dotted rewrite that follows moves it
            old = f"{old_package}.{m.group(2)}"
            parent, _, leaf = self.modules.get(old, old).rpartition(".")
            return f"{m.group(1)}`.{leaf}`" if parent == new_package else f"{m.group(1)}`~{old}`"
        return re.sub(r"(:mod:)`\.(\w+)`", repl, text)

    def short_names(self, text: str, package: str) -> str:
        table = {m.removeprefix(package + "."): n.removeprefix(package + ".") for m, n in self.modules.items()
                 if m.startswith(package + ".") and n.startswith(package + ".")}
        pattern = re.compile(r"([\"'])(" + "|".join(map(re.escape, table)) + r")\1")
        return pattern.sub(lambda m: m.group(1) + table[m.group(2)] + m.group(1), text)

    def test_parents(self, text: str, path: str) -> str:
        old = self.new_to_old.get(path)
        if not (old and path.startswith("tests/")):
            return text
        depth = path.count("/") - old.count("/")
        if depth == 0:
            return text
        # a child process that imports the test module itself by putting tests/ on its path
        folder = str(Path(path).parent)
        text = re.sub(r"sys\.path\.insert\(0, (['\"])tests\1\)",
                      lambda m: f"sys.path[:0] = [{m.group(1)}{folder}{m.group(1)}, {m.group(1)}tests{m.group(1)}]", text)
        text = re.sub(r"(Path\(__file__\)(?:\.resolve\(\))?)\.parents\[(\d+)\]",
                      lambda m: f"{m.group(1)}.parents[{int(m.group(2)) + depth}]", text)
        return re.sub(r"(Path\(__file__\)(?:\.resolve\(\))?)\.parent(?![\w\[])",
                      lambda m: f"{m.group(1)}.parents[{depth}]", text)

    def rewrite_python(self, text: str, path: str) -> str:
        # dotted names before the split: the split's new lines name rooms that may share an old
        # module's name (``sss_locus.experiments.noise``), which must not be rewritten again
        text = _realign(text, self.absolute_imports(text, path))
        text = self.sphinx_refs(text, path)
        package = self.cfg.get("short_names", {}).get(self.new_to_old.get(path, path))
        if package:
            text = self.short_names(text, package)
        text = _realign(text, self.names_and_paths(text, python=True))
        text = self.split_imports(text)
        text = _in_strings_and_comments(text, self.split_text_imports)
        return self.test_parents(text, path)

    def rewrite_cell(self, text: str, code: bool) -> str:
        """A cell's source: names and paths (continuation lines realigned), imports split."""
        new = _realign(text, self.names_and_paths(text, python=False))
        return "".join(self.split_line(line, code) for line in new.splitlines(keepends=True))

    def split_line(self, line: str, code: bool) -> str:
        """One source line of a notebook cell with its imports split (code: parsed, else as text)."""
        new = self.split_imports(line) if code else line
        return self.split_text_imports(new) if new == line else new

    def rewrite_notebook(self, raw: str, path: str) -> str:
        """A notebook edited in its JSON text: each source line is one JSON string on its own line
        (nbformat's ``indent=1``); a changed line is re-encoded in that line's own style (``\\u``
        escapes or raw UTF-8: some notebooks mix both, so no single ``json.dumps`` call reproduces
        them), every other byte is kept. The result is checked against the same rewrite done on
        ``json.load``'s cells."""
        lines = raw.splitlines(keepends=True)
        out, kind, block = [], None, None  # block: (indent, literal, comma, end) of a source list

        def flush():
            texts = [json.loads(b[1]) for b in block]
            whole = "".join(texts)
            new_whole = _realign(whole, self.names_and_paths(whole, python=False))
            new_lines = new_whole.splitlines(keepends=True)
            if len(new_lines) != len(texts):
                refuse([f"{path}: a rewrite changed a cell's number of lines"])
            for (indent, literal, comma, end), text, new in zip(block, texts, new_lines):
                new = self.split_line(new, kind == "code")
                if new == text:
                    out.append(f"{indent}{literal}{comma}{end}")
                    continue
                ascii_only = "\\u" in literal
                parts = new.splitlines(keepends=True)
                for i, part in enumerate(parts):
                    out.append(f"{indent}{json.dumps(part, ensure_ascii=ascii_only)}"
                               f"{comma if i == len(parts) - 1 else ','}{end}")

        for line in lines:
            m_type = re.match(r'\s*"cell_type": "(\w+)"', line)
            if m_type:
                kind = m_type.group(1)
            if block is None and re.match(r'\s*"source": \[\s*$', line):
                block = []
                out.append(line)
                continue
            if block is not None:
                m = re.match(r'(\s*)("(?:[^"\\]|\\.)*")(,?)(\s*)$', line)
                if m:
                    block.append(m.groups())
                    continue
                flush()
                block = None
            out.append(line)
        new_raw = "".join(out)
        expected = json.loads(raw)
        for cell in expected["cells"]:
            src = cell["source"]
            src = "".join(src) if isinstance(src, list) else src
            cell["source"] = self.rewrite_cell(src, cell["cell_type"] == "code").splitlines(keepends=True)
        got = json.loads(new_raw)
        for cell in got["cells"]:
            src = cell["source"]
            cell["source"] = "".join(src).splitlines(keepends=True) if isinstance(src, list) else src.splitlines(keepends=True)
        if got != expected:
            refuse([f"{path}: the line-by-line edit differs from the edit of its parsed cells"])
        return new_raw

    def rewrite_all(self) -> list[str]:
        changed = []
        exclude = set(self.cfg["exclude"])
        for path in git("ls-files").splitlines():
            file = REPO / path
            if path in exclude or not file.is_file() or file.suffix not in TEXT_SUFFIXES:
                continue
            if file.suffix == "" and file.name not in ("Makefile", "run", "install-tools", ".gitignore"):
                continue
            try:
                raw = file.read_text(encoding="utf-8")
            except UnicodeDecodeError:
                continue
            if file.suffix == ".ipynb":
                new = self.rewrite_notebook(raw, path)
            elif file.suffix == ".py":
                new = self.rewrite_python(raw, path)
            else:
                new = self.split_text_imports(self.names_and_paths(raw, python=False))
            if new != raw:
                file.write_text(new, encoding="utf-8")
                changed.append(path)
        return changed

    def layer_indexes(self) -> list[str]:
        """Each layer's ``__init__`` docstring: its first paragraph, then the index of its rooms
        (in the order of ``[rooms]``: shared rooms, then the chapters in book order)."""
        changed = []
        order = list(self.cfg["rooms"])
        for layer in LAYERS:
            init = REPO / "sss_locus" / layer / "__init__.py"
            text = init.read_text(encoding="utf-8")
            tree = ast.parse(text)
            doc = ast.get_docstring(tree, clean=False)
            if doc is None:
                continue
            first = self.cfg.get("layers", {}).get(layer) or doc.strip().split("\n\n")[0]
            rooms = sorted((p.parent for p in (REPO / "sss_locus" / layer).glob("*/__init__.py")),
                           key=lambda r: (order.index(str(r.relative_to(REPO))) if str(r.relative_to(REPO)) in order
                                          else len(order), r.name))
            entries = []
            for room in rooms:
                rel = str(room.relative_to(REPO))
                own = ast.get_docstring(ast.parse((room / "__init__.py").read_text(encoding="utf-8"))) or ""
                desc = (self.cfg["rooms"].get(rel) or own).strip().split("\n\n")[0]
                mods = sorted(p.stem for p in room.glob("*.py") if p.stem != "__init__")
                mods += sorted(p.parent.name + "/" for p in room.glob("*/__init__.py"))
                body = " ".join(desc.split()) + " Modules: " + ", ".join(f"``{m}``" for m in mods) + "."
                entries.append(f"``{room.name}/``\n" + textwrap.fill(body, 96, initial_indent="    ",
                                                                     subsequent_indent="    "))
            kind = ("grouped by job" if layer == "pipeline"
                    else "shared rooms, then one per chapter of the book in ``_toc.yml`` order")
            index = (first.strip() + "\n\n" + textwrap.fill(f"Rooms ({kind}; CONTRIBUTING.md, \"Architecture\"):", 96)
                     + "\n\n" + "\n".join(entries) + "\n")
            node = tree.body[0]
            lines = text.splitlines(keepends=True)
            new = "".join(lines[: node.lineno - 1]) + f'"""{index}"""\n' + "".join(lines[node.end_lineno:])
            if new != text:
                init.write_text(new, encoding="utf-8")
                changed.append(str(init.relative_to(REPO)))
        return changed


def _realign(old: str, new: str) -> str:
    """Continuation lines aligned under an opening parenthesis (``from x import (a,``) moved with
    it when a rewrite made the line before them longer or shorter."""
    old_lines, out = old.splitlines(keepends=True), new.splitlines(keepends=True)
    if len(old_lines) != len(out):
        return new
    for i, line in enumerate(old_lines):
        if line == out[i] or "(" not in line or line.count("(") <= line.count(")") or "(" not in out[i]:
            continue
        column, delta = line.index("("), out[i].index("(") - line.index("(")
        depth, j = line.count("(") - line.count(")"), i + 1
        while depth > 0 and j < len(out):
            lead = len(old_lines[j]) - len(old_lines[j].lstrip(" "))
            if delta and lead == column + 1:
                out[j] = " " * (lead + delta) + out[j].lstrip(" ")
            depth += old_lines[j].count("(") - old_lines[j].count(")")
            j += 1
    return "".join(out)


def _in_strings_and_comments(text: str, fn) -> str:
    """``fn`` applied to the string and comment tokens of Python source only."""
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO(text).readline))
    except (tokenize.TokenError, SyntaxError):
        return text
    kinds = {tokenize.STRING, tokenize.COMMENT}
    kinds |= {getattr(tokenize, n) for n in ("FSTRING_MIDDLE",) if hasattr(tokenize, n)}
    offsets = [0]
    for line in text.splitlines(keepends=True):
        offsets.append(offsets[-1] + len(line))
    spans = [(offsets[t.start[0] - 1] + t.start[1], offsets[t.end[0] - 1] + t.end[1])
             for t in tokens if t.type in kinds]
    out, pos = [], 0
    for start, end in spans:
        out += [text[pos:start], fn(text[start:end])]
        pos = end
    return "".join(out) + text[pos:]


def check_notebooks() -> None:
    """Every notebook must be nbformat's ``indent=1`` JSON (one source line per JSON line), which the
    line-by-line edit relies on: an unchanged notebook must come back byte for byte from
    ``json.dumps(indent=1)`` with ``\\u`` escapes or raw UTF-8 in each string as the file has it."""
    bad = []
    for path in git("ls-files", "*.ipynb").splitlines():
        raw = (REPO / path).read_text(encoding="utf-8")
        nb = json.loads(raw)
        both = {json.dumps(nb, indent=1, ensure_ascii=a) + "\n" for a in (True, False)}
        if raw not in both and not _mixed_style(raw, nb):
            bad.append(f"{path}: not nbformat's indent=1 JSON; edit it by hand")
    if bad:
        refuse(bad)


def _mixed_style(raw: str, nb: dict) -> bool:
    """Whether ``raw`` is ``indent=1`` JSON whose strings mix ``\\u`` escapes and raw UTF-8: the
    escaped dump and the raw one then have the same lines, each line equal to one of the two."""
    escaped = (json.dumps(nb, indent=1, ensure_ascii=True) + "\n").splitlines()
    plain = (json.dumps(nb, indent=1, ensure_ascii=False) + "\n").splitlines()
    lines = raw.splitlines()
    return len(lines) == len(escaped) == len(plain) and all(x in (e, p) for x, e, p in zip(lines, escaped, plain))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="only report the pending moves")
    args = parser.parse_args(argv)
    cfg = tomllib.loads(MAPPING.read_text(encoding="utf-8"))
    plan = Plan(cfg)
    plan.check()
    check_notebooks()
    if not plan.pending:
        print("tools/rooms.py: every file is in its room; nothing to do")
        return 0
    print(f"tools/rooms.py: {len(plan.pending)} files to move")
    if args.check:
        for old, new in plan.pending.items():
            print(f"  {old} -> {new or '(removed)'}")
        return 0
    plan.move()
    changed = plan.rewrite_all()
    changed += plan.layer_indexes()
    print(f"tools/rooms.py: moved {len(plan.pending)} files, rewrote {len(set(changed))} files")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
