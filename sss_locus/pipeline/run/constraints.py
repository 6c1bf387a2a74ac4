"""Constraints on notebook parameters, declared at the end of the parameter's comment.

A comment in a ``parameters`` cell may end with, in this order and each optional::

    n_per_arc = 200          # points drawn per locus arc [2, 1_000_000] ~190 B
    step_deg = 1.0           # grid step (deg) (0, 90]
    side = "port"            # sensor 2's side {"port", "either"}
    platforms = ["auv"]      # keys of data/platforms.toml {keys of platforms}

``[lo, hi]``
    A range; ``[``/``]`` include the bound, ``(``/``)`` exclude it, an empty bound is open
    (``[1, ]``). Bounds are Python number literals (``5_000_000``, ``1e-3``, ``-90``); brackets
    holding anything else are part of the description.
``{a, b, ...}``
    The allowed values (Python literals).
``{keys of <table>}``
    The keys of a data table (``platforms``, ``sonars``, ``envelopes``, ``noise``) of ``data/``
    merged with the active user data (``--data``, ``--set``;
    :mod:`sss_locus.experiments.datamodel.userdata`), read when the value is checked.
``len N`` (before the range)
    A list or tuple parameter must have exactly ``N`` elements (e.g. a band ``[lo, hi]``).
``~N B`` (or ``kB``, ``MB``, ``GB``)
    The memory one unit of the value costs (measured or estimated): the value times ``N`` must
    stay within the memory budget (:func:`memory_budget`), so a run that cannot fit is refused
    before it starts.

For a list or tuple parameter the constraints apply to every element, and every element must
have the type of the default's elements; a list whose default is not empty must not be empty.
Whatever the declaration, a float (or element) must be finite: ``1e999`` reads as ``inf`` and is
refused. The comment's text before the constraints is the
parameter's description.
"""

from __future__ import annotations

import ast
import math
import re
from dataclasses import dataclass
from typing import Any

from sss_locus.geometry import validation
from sss_locus.geometry.validation import MEMORY_BUDGET_ENV

_UNITS = {"B": 1, "kB": 10**3, "MB": 10**6, "GB": 10**9}
_TAIL = re.compile(
    r"(?:\blen\s+(?P<len>[0-9]+)\s*)?"
    r"(?P<range>[\[(]\s*[-+]?[0-9._eE+-]*\s*,\s*[-+]?[0-9._eE+-]*\s*[\])])?\s*"
    r"(?P<choices>\{[^{}]*\})?\s*"
    r"(?:~\s*(?P<mem>[0-9][0-9_.eE+]*)\s*(?P<unit>B|kB|MB|GB))?\s*\Z"
)


class ConstraintError(ValueError):
    """A constraint that cannot be parsed, or a value that breaks one."""


@dataclass(frozen=True)
class Constraint:
    """Range, allowed values, element type and memory cost of one parameter."""

    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple[Any, ...] | None = None
    bytes_each: float | None = None
    element_type: str | None = None  # "int", "float", "str", "bool" for list/tuple parameters
    data_table: str | None = None  # choices are the keys of this data table (``{keys of <table>}``)
    length: int | None = None  # a list's exact number of elements (``len N``)

    def allowed_choices(self) -> tuple[Any, ...] | None:
        """The allowed values: the declared ones, or the current keys of the data table."""
        if self.data_table is None:
            return self.choices
        from sss_locus.experiments.datamodel import userdata

        return tuple(userdata.document().get(self.data_table, {}))

    def describe(self) -> str:
        """What is allowed, e.g. ``[1, 5000000]``, ``one of 'auv', 'boat'``."""
        parts = []
        if self.element_type:
            parts.append(f"a non-empty list of {self.element_type}"
                         + (f" with exactly {self.length} values" if self.length else ""))
        if self.low is not None or self.high is not None:
            lo = "" if self.low is None else _number(self.low)
            hi = "" if self.high is None else _number(self.high)
            parts.append(f"{'(' if self.low_open else '['}{lo}, {hi}{')' if self.high_open else ']'}")
        if self.data_table is not None:
            parts.append(f"a key of [{self.data_table}] in data/ and --data files: one of "
                         + ", ".join(repr(c) for c in self.allowed_choices()))
        elif self.choices is not None:
            parts.append("one of " + ", ".join(repr(c) for c in self.choices))
        if self.bytes_each:
            parts.append(f"at most {_bytes(memory_budget())} of memory at ~{_bytes(self.bytes_each)} each")
        return "; ".join(parts)

    def is_empty(self) -> bool:
        return self == Constraint()


def _number(x: float) -> str:
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else repr(x)


def _bytes(n: float) -> str:
    for unit in ("GB", "MB", "kB"):
        if n >= _UNITS[unit]:
            return f"{n / _UNITS[unit]:.3g} {unit}"
    return f"{n:.0f} B"


def memory_budget() -> int:
    """Bytes a run may plan to use: ``$SSS_LOCUS_MEMORY_BUDGET`` or half the physical memory
    (:func:`sss_locus.geometry.validation.memory_budget`)."""
    try:
        return validation.memory_budget()
    except ValueError as exc:
        raise ConstraintError(str(exc)) from None


def split_comment(comment: str, name: str, default: Any) -> tuple[str, Constraint]:
    """``(description, constraint)`` of a parameter comment (see the module docstring)."""
    match = _TAIL.search(comment)
    element_type = None
    if isinstance(default, (list, tuple)) and default:
        kinds = {type(v).__name__ for v in default}
        if kinds == {"int", "float"}:
            kinds = {"float"}
        if len(kinds) == 1 and kinds <= {"int", "float", "str", "bool"}:
            element_type = kinds.pop()
    if not match or match.start() == match.end():
        return comment.strip(), Constraint(element_type=element_type)
    fields: dict[str, Any] = {"element_type": element_type}
    try:
        if match["range"]:
            lo, hi = (s.strip() for s in match["range"][1:-1].split(","))
            fields["low"] = float(ast.literal_eval(lo)) if lo else None
            fields["high"] = float(ast.literal_eval(hi)) if hi else None
            fields["low_open"], fields["high_open"] = match["range"][0] == "(", match["range"][-1] == ")"
        data_keys = re.fullmatch(r"\{\s*keys of ([a-z_]+)\s*\}", match["choices"] or "")
        if data_keys:
            fields["data_table"] = data_keys.group(1)
        elif match["choices"]:
            fields["choices"] = tuple(ast.literal_eval(match["choices"][1:-1] + ","))
        if match["len"]:
            fields["length"] = int(match["len"])
        if match["mem"]:
            fields["bytes_each"] = float(match["mem"]) * _UNITS[match["unit"]]
    except (ValueError, SyntaxError, TypeError):
        raise ConstraintError(
            f"parameter {name!r}: cannot read the constraint {comment[match.start():].strip()!r} "
            "(expected [lo, hi], {choices} and/or ~N B at the end of the comment)"
        ) from None
    return comment[: match.start()].strip(), Constraint(**fields)


def check(name: str, value: Any, constraint: Constraint) -> None:
    """Raise :class:`ConstraintError` (one line: parameter, value, what is allowed) if broken."""
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    allowed = constraint.describe()
    choices = constraint.allowed_choices()
    if isinstance(value, (list, tuple)) and constraint.element_type and not items:
        raise ConstraintError(f"parameter {name!r} = {value!r} is empty: allowed {allowed}")
    if isinstance(value, (list, tuple)) and constraint.length and len(items) != constraint.length:
        raise ConstraintError(f"parameter {name!r} = {value!r} has {len(items)} value(s): allowed {allowed}")
    for index, item in enumerate(items):
        where = f"{name}[{index}]" if isinstance(value, (list, tuple)) else name
        if isinstance(item, float) and not math.isfinite(item):
            raise ConstraintError(f"parameter {where!r} = {item!r} must be a finite number"
                                  + (f" (allowed: {allowed})" if allowed else ""))
        if constraint.element_type and isinstance(value, (list, tuple)):
            ok = {"int": isinstance(item, int) and not isinstance(item, bool),
                  "float": isinstance(item, (int, float)) and not isinstance(item, bool),
                  "str": isinstance(item, str), "bool": isinstance(item, bool)}[constraint.element_type]
            if not ok:
                raise ConstraintError(f"parameter {where!r} = {item!r}: must be {constraint.element_type} "
                                      f"(allowed: {allowed})")
        if choices is not None and item not in choices:
            raise ConstraintError(f"parameter {where!r} = {item!r} is not allowed: {allowed}")
        if constraint.low is not None or constraint.high is not None:
            if isinstance(item, bool) or not isinstance(item, (int, float)) or math.isnan(item):
                raise ConstraintError(f"parameter {where!r} = {item!r} must be a number in {allowed}")
            lo, hi = constraint.low, constraint.high
            if ((lo is not None and (item < lo or (constraint.low_open and item == lo)))
                    or (hi is not None and (item > hi or (constraint.high_open and item == hi)))):
                raise ConstraintError(f"parameter {where!r} = {item!r} is out of range: allowed {allowed}")
    if constraint.bytes_each:
        units = sum(abs(v) for v in items if isinstance(v, (int, float)) and not isinstance(v, bool))
        need, budget = units * constraint.bytes_each, memory_budget()
        if need > budget:
            raise ConstraintError(
                f"parameter {name!r} = {value!r} needs about {_bytes(need)} of memory "
                f"(~{_bytes(constraint.bytes_each)} each), more than the budget of {_bytes(budget)} "
                f"(half the RAM; set {MEMORY_BUDGET_ENV} to change it)"
            )
