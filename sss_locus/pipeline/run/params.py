"""Notebook parameters as typed pydantic models: the base model, its markers and its errors.

Every chapter declares its parameters once, as a :class:`NotebookParams` subclass named
``Params`` in :mod:`sss_locus.pipeline.chapters.params` (one module per notebook, named after
it): a type per field (``int``, ``float``, ``str``, ``bool``, ``list[...]``, ``Literal[...]``
for a choice), bounds (``Field(ge=, gt=, le=, lt=)``, on a list's elements inside
``list[Annotated[float, Field(...)]]``), a list's length (``min_length``/``max_length``) and a
description with the unit. Two markers add what a type cannot say:

:class:`DataKeys`
    ``Annotated[str, DataKeys("platforms")]``: a key of a data table (``platforms``, ``sonars``,
    ``envelopes``, ``noise``) of ``data/`` merged with the active user data (``--data``,
    ``--set``; :mod:`sss_locus.experiments.datamodel.userdata`), read when the value is checked;
    ``DataKeys("platforms", ("noise",))`` also needs the key's ``[noise.<key>]`` table, which the
    chapter reads (``EnvelopedPlatforms``, ``NoisyPlatforms``, ``EnvelopedNoisyPlatforms``).
:class:`MemoryPerUnit`
    ``Annotated[int, MemoryPerUnit(2.8e3)]``: the bytes one unit of the value costs (measured
    or estimated); the value times that must stay within :func:`memory_budget`, so a run that
    cannot fit is refused before it starts.

The model is strict (no ``"7"`` for an int, no ``1`` for a bool; an int is widened to a float),
forbids unknown names and refuses infinite or NaN numbers. The notebook's ``parameters`` cell is
the model rendered as plain assignments
(:func:`sss_locus.pipeline.run.paramcell.parameters_cell`; papermill injects after it),
and a test checks every notebook's cell against its model. :func:`error_line` turns a
:class:`pydantic.ValidationError` into one line naming the parameter, the value and what is
allowed (:func:`allowed`).
"""

from __future__ import annotations

import json
import typing
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from annotated_types import Ge, Gt, Le, Lt, MaxLen, MinLen
from pydantic import BaseModel, ConfigDict, Field, ValidationError
from pydantic.fields import FieldInfo
from pydantic_core import core_schema

from sss_locus.geometry import validation
from sss_locus.geometry.validation import MEMORY_BUDGET_ENV

_UNITS = {"B": 1, "kB": 10**3, "MB": 10**6, "GB": 10**9}
#: Type names shown to users (``sss-locus params``) and used to read command-line text.
TYPE_NAMES = {int: "int", float: "float", bool: "bool", str: "str", list: "list", tuple: "tuple", dict: "dict"}


class NotebookParams(BaseModel):
    """Base of every chapter's ``Params``: strict, frozen, no unknown names, finite numbers."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False,
                              validate_default=True)


@dataclass(frozen=True)
class DataKeys:
    """Marker: a string must be a key of the data table ``table`` (shipped data and user data)."""

    table: str
    #: Other tables the chapter reads for the same key (``("envelopes", "noise")``): a key
    #: without one of them is refused before the run, naming the missing table.
    needs: tuple[str, ...] = ()

    def keys(self, table: str | None = None) -> tuple[str, ...]:
        """The table's current keys (``data/`` merged with ``--data`` and ``--set``)."""
        from sss_locus.experiments.datamodel import userdata

        return tuple(userdata.document().get(table or self.table, {}))

    def describe(self) -> str:
        needs = "".join(f" with a [{t}.<key>] table" for t in self.needs)
        return f"a key of [{self.table}] in data/ and --data files{needs}: one of " + ", ".join(
            map(repr, [k for k in self.keys() if all(k in self.keys(t) for t in self.needs)]))

    def _check(self, value: str) -> str:
        from sss_locus.experiments.datamodel.models import missing_table

        if value not in self.keys():
            raise ValueError(f"is not allowed: {self.describe()}")
        for table in self.needs:
            if value not in self.keys(table):
                raise ValueError(f"is a platform this chapter cannot run: {missing_table(table, value, self.keys(table))}")
        return value

    def __get_pydantic_core_schema__(self, source: Any, handler: Any) -> core_schema.CoreSchema:
        return core_schema.no_info_after_validator_function(self._check, handler(source))


@dataclass(frozen=True)
class MemoryPerUnit:
    """Marker: each unit of a count costs about ``bytes_each`` bytes of memory."""

    bytes_each: float

    def describe(self) -> str:
        return f"at most {_bytes(memory_budget())} of memory at ~{_bytes(self.bytes_each)} each"

    def _check(self, value: int) -> int:
        need, budget = abs(value) * self.bytes_each, memory_budget()
        if need > budget:
            raise ValueError(f"needs about {_bytes(need)} of memory (~{_bytes(self.bytes_each)} each), more than "
                             f"the budget of {_bytes(budget)} (half the RAM; set {MEMORY_BUDGET_ENV} to change it)")
        return value

    def __get_pydantic_core_schema__(self, source: Any, handler: Any) -> core_schema.CoreSchema:
        return core_schema.no_info_after_validator_function(self._check, handler(source))


#: Common fields: the platforms a chapter runs for (data keys, at least one).
Platforms = Annotated[list[Annotated[str, DataKeys("platforms")]], Field(min_length=1)]
#: ... for a chapter that also reads their survey envelopes (``[envelopes.<key>]``),
EnvelopedPlatforms = Annotated[list[Annotated[str, DataKeys("platforms", ("envelopes",))]], Field(min_length=1)]
#: ... their noise models (``[noise.<key>]``),
NoisyPlatforms = Annotated[list[Annotated[str, DataKeys("platforms", ("noise",))]], Field(min_length=1)]
#: ... or both.
EnvelopedNoisyPlatforms = Annotated[list[Annotated[str, DataKeys("platforms", ("envelopes", "noise"))]],
                                    Field(min_length=1)]
#: A random seed (numpy's ``SeedSequence`` accepts any, the runs use 32 bits).
Seed = Annotated[int, Field(ge=0, le=4_294_967_295)]
DATA_FILES_DOC = "user data files (TOML, schema of data/*.toml) merged into data/; set by --data"
DATA_SET_DOC = "overrides of single data values, each KEY.PATH set to a value; set by --set"


def _bytes(n: float) -> str:
    for unit in ("GB", "MB", "kB"):
        if n >= _UNITS[unit]:
            return f"{n / _UNITS[unit]:.3g} {unit}"
    return f"{n:.0f} B"


def _number(x: float) -> str:
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else repr(x)


def _literal_number(x: float) -> str:
    return f"{int(x):_}" if float(x).is_integer() and abs(x) < 1e15 else repr(x)


def memory_budget() -> int:
    """Bytes a run may plan to use: ``$SSS_LOCUS_MEMORY_BUDGET`` or half the physical memory
    (:func:`sss_locus.geometry.validation.memory_budget`)."""
    return validation.memory_budget()


def _parts(annotation: Any, metadata: list) -> tuple[Any, list]:
    """``(bare type, metadata)`` of an annotation, ``Annotated`` and ``FieldInfo`` unwrapped."""
    metadata = list(metadata)
    while typing.get_origin(annotation) is Annotated:
        annotation, *extra = typing.get_args(annotation)
        metadata += extra
    flat = []
    for item in metadata:
        if isinstance(item, FieldInfo):
            inner, more = _parts(item.annotation, item.metadata) if item.annotation not in (None, type(None)) \
                else (None, item.metadata)
            flat += more
        else:
            flat.append(item)
    return annotation, flat


def type_name(field: FieldInfo) -> str:
    """``int``, ``float``, ``bool``, ``str``, ``list``, ``tuple``, ``dict`` or ``any``: how a
    value is read from the command line and shown."""
    bare, _ = _parts(field.annotation, [])
    if typing.get_origin(bare) is Literal:
        bare = type(typing.get_args(bare)[0])
    return TYPE_NAMES.get(typing.get_origin(bare) or bare, "any")


def element_type_name(field: FieldInfo) -> str | None:
    """The element type name of a list field (``None`` for other fields)."""
    bare, _ = _parts(field.annotation, [])
    if typing.get_origin(bare) not in (list, tuple) or not typing.get_args(bare):
        return None
    inner, _ = _parts(typing.get_args(bare)[0], [])
    if typing.get_origin(inner) is Literal:
        inner = type(typing.get_args(inner)[0])
    return TYPE_NAMES.get(inner, "any")


def allowed(field: FieldInfo, static: bool = False) -> str:
    """What a field allows, e.g. ``[100, 5000000]``, ``one of 'port', 'either'``, ``a non-empty
    list of float with exactly 2 values; [0, 180]`` ("" when any value of the type is).
    ``static``: only what the declaration says (no list phrase, no data keys or memory budget
    read now), for the notebook's cell."""
    bare, meta = _parts(field.annotation, field.metadata)
    parts = []
    element = element_type_name(field)
    if element is not None and static:
        bare, meta = _parts(typing.get_args(bare)[0], [])
    elif element is not None:
        low = next((m.min_length for m in meta if isinstance(m, MinLen)), 0)
        high = next((m.max_length for m in meta if isinstance(m, MaxLen)), None)
        if low:
            parts.append(f"a non-empty list of {element}" + (f" with exactly {high} values" if high == low else ""))
        bare, meta = _parts(typing.get_args(bare)[0], [])
    lo = next(((m.ge, "[") for m in meta if isinstance(m, Ge)), None) or next(
        ((m.gt, "(") for m in meta if isinstance(m, Gt)), None)
    hi = next(((m.le, "]") for m in meta if isinstance(m, Le)), None) or next(
        ((m.lt, ")") for m in meta if isinstance(m, Lt)), None)
    if lo or hi:
        number = _literal_number if static else _number
        parts.append(f"{lo[1] if lo else '['}{number(lo[0]) if lo else ''}, "
                     f"{number(hi[0]) if hi else ''}{hi[1] if hi else ']'}")
    if typing.get_origin(bare) is Literal and static:
        parts.append("{" + ", ".join(json.dumps(v, ensure_ascii=False) if isinstance(v, str) else repr(v)
                                     for v in typing.get_args(bare)) + "}")
    elif typing.get_origin(bare) is Literal:
        parts.append("one of " + ", ".join(map(repr, typing.get_args(bare))))
    if static:
        parts += [f"{{keys of {m.table}}}" for m in meta if isinstance(m, DataKeys)]
    else:
        parts += [m.describe() for m in meta if isinstance(m, (DataKeys, MemoryPerUnit))]
    return "; ".join(parts)


def error_line(exc: ValidationError, model: type[BaseModel]) -> str:
    """The first error of ``exc`` in one line: ``parameter 'n[1]' = 5 is out of range: allowed [0, 3]``."""
    err = exc.errors()[0]
    name, rest = str(err["loc"][0]), err["loc"][1:]
    where = name + "".join(f"[{i}]" for i in rest)
    value, kind = err["input"], err["type"]
    field = model.model_fields[name]
    rule = allowed(field)
    also = f" (allowed: {rule})" if rule else ""
    head = f"parameter {where!r} = {value!r}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"{head} is out of range: allowed {rule}"
    if kind == "finite_number":
        return f"{head} must be a finite number{also}"
    if kind == "literal_error":
        return f"{head} is not allowed: {rule}"
    if kind in ("too_short", "too_long"):
        count = len(value)
        return f"{head} is empty: allowed {rule}" if count == 0 else f"{head} has {count} value(s): allowed {rule}"
    if kind == "value_error":
        return f"{head} {err['ctx']['error']}"
    if rest:  # an element of the wrong type
        return f"{head}: must be {element_type_name(field)}{also}"
    return f"{head} ({type(value).__name__}): expected a value of type {type_name(field)}{also}"

