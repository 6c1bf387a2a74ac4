"""The notebook registry (``notebooks/registry.toml``) and notebook-parameter validation.

Registry format
---------------
One table per notebook, in book order; append a block to add a notebook::

    [notebooks.concept]
    source = "notebooks/concept.ipynb"        # repository-relative
    executed = "executed/concept.ipynb"       # relative to the build area (see paths.py);
                                              # _toc.yml lists it as `executed/concept`
    [notebooks.concept.profiles.book]         # the published figures ({} = notebook defaults)
    [notebooks.concept.profiles.quick]        # seconds; used by the tests
    n_points = 200

Profiles ``book`` and ``quick`` are required; more are allowed. Every profile value must name a
parameter of the notebook's ``parameters``-tagged cell with a value of the right type.

Parameters
----------
A chapter declares its parameters once, as the pydantic model ``Params`` of
``sss_locus/pipeline/chapters/params/<name>.py`` (types, bounds, choices, descriptions; see
:mod:`sss_locus.pipeline.run.params`); its notebook's cell tagged ``parameters`` is that model
rendered as plain assignments (papermill inspects it and injects after it), and every value of a
profile, ``-p`` or the runner goes through ``Params.model_validate`` before any kernel starts.

A notebook without such a module (a user's own, a test's) has its parameters read from the cell:
one assignment per line, of a literal, optionally annotated and commented (the comment is the
description); the type is the annotation if present, otherwise the type of the default (``int``,
``float``, ``bool``, ``str``, ``list``, ``tuple``, ``dict``; a default of ``None`` accepts any
literal), turned into a model of the same kind (:func:`model_from_cell`)::

    n_points = 2000        # Monte Carlo samples per platform
    seed: int = 1          # random seed
"""

from __future__ import annotations

import ast
import difflib
import importlib
import importlib.util
import re
import io
import json
import tokenize
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import Field, ValidationError, create_model
from pydantic.fields import FieldInfo

from sss_locus import paths
from sss_locus.pipeline.run.params import NotebookParams, allowed, error_line, type_name

#: The package holding one module of parameters per registered notebook, named after it.
PARAMS_PACKAGE = "sss_locus.pipeline.chapters.params"

REQUIRED_PROFILES = ("book", "quick")
#: Registry names: lower-case words joined by underscores (used with fullmatch).
NAME_PATTERN = re.compile(r"[a-z][a-z0-9_]*")
_TYPES: dict[str, type] = {
    "int": int, "float": float, "bool": bool, "str": str,
    "list": list, "tuple": tuple, "dict": dict,
}


class ParameterError(ValueError):
    """An unknown notebook parameter, or a value of the wrong type."""


@dataclass(frozen=True)
class Parameter:
    """One notebook parameter: name, type name (``"any"`` for a ``None`` default), default, doc."""

    name: str
    type: str
    default: Any
    doc: str = ""
    field_info: FieldInfo | None = field(default=None, compare=False, repr=False)  # the model's field

    def allowed(self) -> str:
        """What the parameter allows (read now: a data table's keys include the user's)."""
        return "" if self.field_info is None else allowed(self.field_info)

    def describe(self) -> str:
        line = f"{self.name}: {self.type} = {self.default!r}"
        rule = self.allowed()
        doc = "; ".join(x for x in (self.doc, f"allowed: {rule}" if rule else "") if x)
        return f"{line}  # {doc}" if doc else line


def _comments_by_line(source: str) -> dict[int, str]:
    comments: dict[int, str] = {}
    try:
        for tok in tokenize.generate_tokens(io.StringIO(source).readline):
            if tok.type == tokenize.COMMENT:
                comments[tok.start[0]] = tok.string.lstrip("#").strip()
    except (tokenize.TokenError, IndentationError):
        pass
    return comments


def parse_parameters_source(source: str, where: str = "parameters cell") -> dict[str, Parameter]:
    """Parse the source of a ``parameters`` cell into :class:`Parameter` objects, in order."""
    try:
        tree = ast.parse(source)
    except SyntaxError as exc:
        raise ParameterError(f"{where}: not valid Python ({exc.msg}, line {exc.lineno})") from None
    comments = _comments_by_line(source)
    params: dict[str, Parameter] = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            name, value_node, annotation = node.targets[0].id, node.value, None
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and node.value is not None:
            name, value_node, annotation = node.target.id, node.value, ast.unparse(node.annotation)
        else:
            raise ParameterError(
                f"{where}, line {node.lineno}: only simple assignments `name = literal` are allowed "
                f"in a parameters cell, got `{ast.unparse(node)}`"
            )
        try:
            default = ast.literal_eval(value_node)
        except ValueError:
            raise ParameterError(
                f"{where}, line {node.lineno}: the default of {name!r} must be a literal "
                f"(number, string, bool, None, list, tuple or dict), got `{ast.unparse(value_node)}`"
            ) from None
        if annotation is not None:
            if annotation not in _TYPES:
                raise ParameterError(
                    f"{where}, line {node.lineno}: annotation of {name!r} must be one of "
                    f"{', '.join(_TYPES)}, got {annotation!r}"
                )
            type_name = annotation
            if type_name == "float" and isinstance(default, int) and not isinstance(default, bool):
                default = float(default)
            expected = _TYPES[type_name]
            if default is not None and (not isinstance(default, expected)
                                        or (expected is not bool and isinstance(default, bool))):
                raise ParameterError(
                    f"{where}, line {node.lineno}: default of {name!r} is not a {type_name}: {default!r}"
                )
        else:
            type_name = "any" if default is None else type(default).__name__
            if type_name not in _TYPES and type_name != "any":
                type_name = "any"
        params[name] = Parameter(name, type_name, default, comments.get(node.lineno, ""))
    return params


def model_from_cell(spec: dict[str, Parameter]) -> type[NotebookParams]:
    """A parameters model of a notebook without a ``Params`` module: its cell's names, types and
    defaults (``any`` accepts any value), its comments as descriptions."""
    fields = {p.name: (Any if p.type == "any" else _TYPES[p.type], Field(p.default, description=p.doc))
              for p in spec.values()}
    return create_model("Params", __base__=NotebookParams, **fields)


def params_model(name: str) -> type[NotebookParams] | None:
    """The ``Params`` model of the registered notebook ``name``, or None if it declares none."""
    module = f"{PARAMS_PACKAGE}.{name}"
    if importlib.util.find_spec(module) is None:
        return None
    return importlib.import_module(module).Params


def parameters_of(model: type[NotebookParams]) -> dict[str, Parameter]:
    """The model's fields as :class:`Parameter` objects, in order."""
    return {name: Parameter(name, type_name(f), f.default, f.description or "", f)
            for name, f in model.model_fields.items()}


def parse_notebook_parameters(notebook: Path) -> dict[str, Parameter]:
    """Parameters declared by the ``parameters``-tagged cell of a notebook file."""
    nb = json.loads(Path(notebook).read_text(encoding="utf-8"))
    cells = [c for c in nb.get("cells", []) if "parameters" in c.get("metadata", {}).get("tags", [])]
    if not cells:
        return {}
    if len(cells) > 1:
        raise ParameterError(f"{notebook}: more than one cell is tagged 'parameters'")
    source = cells[0]["source"]
    source = "".join(source) if isinstance(source, list) else source
    return parse_parameters_source(source, where=f"{notebook} (parameters cell)")


def _convert(param: Parameter, value: Any, from_text: bool) -> Any:
    """Command-line text converted to the parameter's type; a list for a tuple parameter made a
    tuple (TOML and ``-p`` have only lists). The model checks the result."""
    if from_text:
        value = _from_text(param, str(value))
    if param.type == "tuple" and isinstance(value, list):
        value = tuple(value)
    return value


def _from_text(param: Parameter, text: str) -> Any:
    """Command-line text converted to the parameter's type (checked by the caller)."""
    if param.type == "str":  # a string literal (``-p area '"my.toml"'``) means the string itself
        try:
            literal = ast.literal_eval(text.strip())
        except (ValueError, SyntaxError):
            return text
        return literal if isinstance(literal, str) else text
    if param.type == "bool":
        lowered = text.strip().lower()
        if lowered in ("true", "1", "yes"):
            return True
        if lowered in ("false", "0", "no"):
            return False
        raise ParameterError(f"parameter {param.name!r} = {text!r}: expected a bool (true/false)")
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        if param.type == "any":
            return text
        try:  # JSON's spellings (true, false, null) are values too, checked as any other; NaN is not
            return json.loads(text, parse_constant=_not_finite)
        except ValueError:
            pass
        word = re.search(r"(?i)\b(nan|inf|infinity)\b", text)
        if word:
            raise ParameterError(f"parameter {param.name!r} = {text!r}: {word.group(0)!r} is not a number here; "
                                 f"every number must be finite{_allowed(param)}") from None
        raise ParameterError(f"parameter {param.name!r} = {text!r}: expected a value of type "
                             f"{param.type}{_allowed(param)}{_quoting_hint(param, text)}") from None


def _quoting_hint(param: Parameter, text: str) -> str:
    """How to write a list of strings for the shell, when ``text`` looks like one whose quotes the
    shell removed (``-p platforms ["my_auv"]`` arrives as ``[my_auv]``), or a bare name."""
    words = re.fullmatch(r"\s*\[?\s*([A-Za-z_][\w.-]*(?:\s*,\s*[A-Za-z_][\w.-]*)*)\s*\]?\s*", text)
    if param.type != "list" or not words:
        return ""
    items = ", ".join(f'"{w.strip()}"' for w in words.group(1).split(","))
    return f"; quote each item and the whole list for the shell: -p {param.name} '[{items}]'"


def _not_finite(word: str):
    raise ValueError(f"{word} is not finite")


def _allowed(param: Parameter) -> str:
    rule = param.allowed()
    return f" (allowed: {rule})" if rule else ""


#: Former parameter names and the parameter that replaced them (named in the error for the old name).
RENAMED = {"sonar_platform": "platforms"}


def validate_parameters(
    spec: dict[str, Parameter], values: dict[str, Any], *, notebook: str, from_text: bool = False,
    model: type[NotebookParams] | None = None, base: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Check parameter values against a notebook's parameters; return the converted values.

    ``from_text=True`` converts command-line strings to the declared types first; the values,
    with the others' values (``base``, else the defaults), then go through
    ``model.model_validate`` (``model``: the notebook's ``Params``, or :func:`model_from_cell`
    of ``spec``). Raises
    :class:`ParameterError` (a ``ValueError``): an unknown name lists every valid parameter with
    its type and default (and the closest name); a bad value is one line naming the parameter,
    the value and what is allowed.
    """
    converted: dict[str, Any] = {}
    for name, value in values.items():
        if name not in spec:
            renamed = RENAMED.get(name)
            if renamed in spec:
                raise ParameterError(f"notebook {notebook!r}: parameter {name!r} is now {renamed!r} "
                                     f"({spec[renamed].describe()})")
            hint = _closest(name, spec)
            listing = "\n".join("  " + p.describe() for p in spec.values()) or "  (none)"
            raise ParameterError(f"notebook {notebook!r} has no parameter {name!r}{hint}\n"
                                 f"Valid parameters of {notebook!r}:\n{listing}")
        try:
            converted[name] = _convert(spec[name], value, from_text)
        except ParameterError as exc:
            raise ParameterError(f"notebook {notebook!r}: {exc}") from None
    model = model_from_cell(spec) if model is None else model
    try:
        checked = model.model_validate({**{n: p.default for n, p in spec.items()}, **(base or {}), **converted})
    except ValidationError as exc:
        raise ParameterError(f"notebook {notebook!r}: {error_line(exc, model)}") from None
    return {name: getattr(checked, name) for name in converted}


@dataclass(frozen=True)
class NotebookEntry:
    """One notebook of the registry."""

    name: str
    source: Path  # absolute
    executed: str  # relative to the build area, e.g. "executed/concept.ipynb"
    profiles: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def source_relative(self) -> str:
        """Repository-relative source path (used as the notebook's identity in manifests):
        ``notebooks/<name>.ipynb``, in a checkout or installed."""
        try:
            return self.source.relative_to(paths.NOTEBOOKS_DIR.parent).as_posix()
        except ValueError:
            return self.source.as_posix()

    def executed_path(self) -> Path:
        """Absolute path of the executed copy in the current build area."""
        return paths.source_dir() / self.executed

    def model(self) -> type[NotebookParams]:
        """The notebook's parameters model: its ``Params`` module's, else one read from its cell."""
        return params_model(self.name) or model_from_cell(parse_notebook_parameters(self.source))

    def parameters(self) -> dict[str, Parameter]:
        """The notebook's parameters, in order (from its ``Params`` model when it has one)."""
        model = params_model(self.name)
        return parse_notebook_parameters(self.source) if model is None else parameters_of(model)

    def resolve(self, profile: str = "book", overrides: dict[str, Any] | None = None,
                from_text: bool = False) -> dict[str, Any]:
        """Full parameter values for a run: defaults, then the profile, then ``overrides``."""
        if profile not in self.profiles:
            raise ParameterError(
                f"notebook {self.name!r} has no profile {profile!r}{_closest(profile, self.profiles)}; "
                f"profiles: {', '.join(self.profiles)}"
            )
        spec, model = self.parameters(), self.model()
        values = {name: p.default for name, p in spec.items()}
        values.update(validate_parameters(spec, self.profiles[profile], notebook=self.name, model=model))
        values.update(validate_parameters(spec, overrides or {}, notebook=self.name, from_text=from_text,
                                          model=model, base=values))
        return values


def load_registry(registry_file: Path | None = None, root: Path | None = None) -> dict[str, NotebookEntry]:
    """Read and check the registry; entries in file order.

    ``root`` is the folder that ``source`` paths are relative to (default: the repository, or the
    installed package's copy of ``notebooks/``'s parent).
    Every malformed shape raises ``ValueError`` naming the file and the key.
    """
    registry_file = paths.REGISTRY_FILE if registry_file is None else Path(registry_file)
    root = paths.NOTEBOOKS_DIR.parent if root is None else Path(root)
    try:
        with open(registry_file, "rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{registry_file}: not valid TOML ({exc})") from None
    notebooks = data.get("notebooks", {})
    unknown_top = set(data) - {"notebooks"}
    if unknown_top:
        raise ValueError(f"{registry_file}: unknown top-level key(s) {', '.join(sorted(unknown_top))} "
                         "(only [notebooks.<name>] tables)")
    if not isinstance(notebooks, dict):
        raise ValueError(f"{registry_file}: notebooks must be a table of [notebooks.<name>] tables, "
                         f"got {type(notebooks).__name__}")
    entries: dict[str, NotebookEntry] = {}
    seen_executed: dict[str, str] = {}
    for name, table in notebooks.items():
        where = f"{registry_file}: notebooks.{name}"
        if not NAME_PATTERN.fullmatch(name):
            raise ValueError(f"{where}: notebook names must be lower-case letters, digits and '_', "
                             f"starting with a letter (pattern {NAME_PATTERN.pattern}), got {name!r}")
        if not isinstance(table, dict):
            raise ValueError(f"{where} must be a table, got {type(table).__name__}")
        missing = [k for k in ("source", "executed", "profiles") if k not in table]
        if missing:
            raise ValueError(f"{where}: missing key(s) {', '.join(missing)}")
        unknown = set(table) - {"source", "executed", "profiles", "title"}
        if unknown:
            raise ValueError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}")
        for key in ("source", "executed", "title"):
            if key in table and not (isinstance(table[key], str) and table[key].strip()):
                raise ValueError(f"{where}.{key} must be a non-empty string, got {table[key]!r}")
        profiles = table["profiles"]
        if not isinstance(profiles, dict):
            raise ValueError(f"{where}.profiles must be a table of profiles, got {type(profiles).__name__}")
        for profile, values in profiles.items():
            if not isinstance(values, dict):
                raise ValueError(f"{where}.profiles.{profile} must be a table of parameter values, "
                                 f"got {type(values).__name__}")
        absent = [p for p in REQUIRED_PROFILES if p not in profiles]
        if absent:
            raise ValueError(f"{where}: profile(s) {', '.join(absent)} required")
        executed = table["executed"]
        parts = Path(executed).parts
        if not executed.endswith(".ipynb") or Path(executed).is_absolute() or ".." in parts:
            raise ValueError(f"{where}.executed must be a relative .ipynb path inside the "
                             f"build area, got {executed!r}")
        normal = Path(executed).as_posix().lower()
        if normal in seen_executed:
            raise ValueError(f"{where}.executed: {executed!r} is already the executed copy of "
                             f"notebooks.{seen_executed[normal]}; every notebook needs its own")
        seen_executed[normal] = name
        source = root / table["source"]
        if not source.is_file():
            raise ValueError(f"{where}.source: no such notebook {source}")
        entries[name] = NotebookEntry(name, source, executed, {k: dict(v) for k, v in profiles.items()})
    return entries


def get_entry(name: str, registry_file: Path | None = None) -> NotebookEntry:
    """Look a notebook up by registry name or by its source path (``notebooks/x.ipynb``)."""
    entries = load_registry(registry_file)
    if name in entries:
        return entries[name]
    for entry in entries.values():
        if entry.source_relative == name or entry.source.name == Path(name).name:
            return entry
    raise ValueError(f"unknown notebook {name!r}{_closest(name, entries)}; registered notebooks: "
                     f"{', '.join(entries) or '(none)'}")


def _closest(name: str, known) -> str:
    """``" (did you mean 'x'?)"`` for the known name nearest ``name``, or ``""``."""
    close = difflib.get_close_matches(str(name), list(known), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""
