"""The building blocks of the data model: a table that refuses unknown keys (naming the nearest
declared one), a sourced value ``{value, source | assumption}`` with its bounds, and the one-line
message of a validation error (:func:`validation_message`: key path, what is wrong, value, rule).
The tables themselves: :mod:`sss_locus.experiments.datamodel.models`."""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Annotated, Any, Generic, Literal, TypeVar, get_args, get_origin

from annotated_types import Ge, Gt, Le, Lt
from pydantic import (AfterValidator, BaseModel, ConfigDict, Field, StringConstraints, TypeAdapter, ValidationError,
                      WrapValidator, field_validator, model_validator)
from pydantic_core import PydanticCustomError

from sss_locus.experiments.datamodel.datadoc import KEY_PATTERN
from sss_locus.experiments.datamodel.inputs import suggestion


#: A key of sonars, platforms, envelopes and noise models (``_`` becomes ``-`` in figure labels).
Key = Annotated[str, StringConstraints(pattern=f"^{KEY_PATTERN.pattern}$")]


def _non_empty(text: str) -> str:
    if not text.strip():
        raise PydanticCustomError("non_empty", "must be a non-empty string; got {got}", {"got": repr(text)})
    return text


#: A non-empty text (a name, a source, an assumption).
Text = Annotated[str, Field(strict=True), AfterValidator(_non_empty)]


class Table(BaseModel):
    """A TOML table: frozen, only its declared keys (an unknown key names the nearest one)."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)

    @model_validator(mode="wrap")
    @classmethod
    def _known_keys(cls, data: Any, handler):
        if isinstance(data, Mapping):
            for name in data:
                if name not in cls.model_fields:
                    known = sorted(cls.model_fields)
                    raise PydanticCustomError(
                        "unknown_key", "unknown key {name}{hint} (keys here: {known})",
                        {"key": str(name), "name": repr(name), "hint": suggestion(name, known),
                         "known": ", ".join(known)})
        return handler(data)


T = TypeVar("T")


def _rule(field) -> str:
    """The valid values of a :class:`Sourced` value's declaration, in words."""
    annotation = field.annotation
    if get_origin(annotation) is Literal:
        return f"one of {list(get_args(annotation))}"
    if annotation is bool:
        return "true or false"
    return _range_rule(field.metadata)


def _range_rule(metadata) -> str:
    """``"a finite number in [lo, hi]"`` (``(``/``)`` for an open end) of a number's constraints."""
    lo, hi, lo_open, hi_open = -math.inf, math.inf, True, True
    for m in metadata:
        if isinstance(m, (Ge, Gt)):
            lo, lo_open = float(m.ge if isinstance(m, Ge) else m.gt), isinstance(m, Gt)
        elif isinstance(m, (Le, Lt)):
            hi, hi_open = float(m.le if isinstance(m, Le) else m.lt), isinstance(m, Lt)
    if math.isinf(lo) and math.isinf(hi):
        return "a finite number"
    return f"a finite number in {'(' if lo_open else '['}{lo}, {hi}{')' if hi_open else ']'}"


def described(kind: Any, rule: str, *, whole: bool = True) -> Any:
    """``kind`` whose refusal reads ``must be <rule>; got <value>`` (the value's first 80
    characters) instead of pydantic's per-item errors.

    Parameters
    ----------
    kind : type
        A type pydantic validates (e.g. ``list[tuple[float, float]]``).
    rule : str
        The valid values in words.
    whole : bool
        ``True``: any error inside the value is reported as the whole value's; ``False``: only a
        value of the wrong kind itself (errors of its items keep their own key path and message).

    Returns
    -------
    type
        ``Annotated[kind, WrapValidator(...)]``.
    """
    def rephrase(value: Any, handler):
        try:
            return handler(value)
        except ValidationError as exc:
            if not whole and any(e["loc"] for e in exc.errors()):
                raise
            raise PydanticCustomError("value_range", "must be {rule}; got {got}",
                                      {"rule": rule, "got": f"{value!r:.80}"}) from None

    return Annotated[kind, WrapValidator(rephrase)]


def bounded(ge: float | None = None, le: float | None = None, *, gt: float | None = None) -> Any:
    """The type of a plain (not sourced) finite number within bounds, refused in the words of
    :func:`number` (an area file's numbers).

    Parameters
    ----------
    ge, le, gt : float, optional
        Lower bound (included), upper bound (included), lower bound (excluded); ``None``:
        unbounded.

    Returns
    -------
    type
        ``Annotated[float, Field(...)]``, strict (no ``"15"``, no ``true``), finite; a refusal
        reads ``must be a finite number in [ge, le]; got <value>``.
    """
    field = Field(strict=True, allow_inf_nan=False, ge=ge, le=le, gt=gt)
    return described(Annotated[float, field], _range_rule(field.metadata))


class Sourced(Table, Generic[T]):
    """A value with where it comes from: exactly one of ``source`` (a citation) and
    ``assumption`` (what was assumed, and why)."""

    value: T
    source: Text | None = None
    assumption: Text | None = None

    @field_validator("value", mode="wrap")
    @classmethod
    def _in_range(cls, value: Any, handler):
        try:
            return handler(value)
        except ValidationError:
            raise PydanticCustomError("value_range", "must be {rule}; got {got}",
                                      {"rule": _rule(cls.model_fields["value"]), "got": repr(value)}) from None

    @model_validator(mode="after")
    def _one_note(self):
        notes = [k for k in ("source", "assumption") if getattr(self, k) is not None]
        if len(notes) != 1:
            raise PydanticCustomError("one_note", "needs exactly one of 'source' or 'assumption'; found {found}",
                                      {"found": str(notes or "none")})
        return self

    @property
    def note(self) -> str:
        """``"source: ..."`` or ``"assumption: ..."`` (the provenance of the value)."""
        return f"source: {self.source}" if self.source is not None else f"assumption: {self.assumption}"


def number(ge: float | None = None, le: float | None = None, *, gt: float | None = None):
    """The type of a sourced finite number within bounds: ``Sourced[bounded(ge, le, gt=gt)]``
    (:func:`bounded`).

    Parameters
    ----------
    ge, le, gt : float, optional
        As :func:`bounded`.

    Returns
    -------
    type
        ``Sourced[...]`` of a strict, finite number within the bounds.
    """
    return Sourced[bounded(ge, le, gt=gt)]


def validation_message(exc: ValidationError, where: str = "") -> str:
    """The first error of a validation in one line.

    Parameters
    ----------
    exc : pydantic.ValidationError
        The error of a model's validation.
    where : str
        The dotted key path of the validated data (``""``: the document's top).

    Returns
    -------
    str
        The key path, what is wrong, the value and the rule (the valid range, the known keys).
    """
    error = exc.errors(include_url=False)[0]
    kind, ctx, got, loc = error["type"], error.get("ctx") or {}, error.get("input"), list(error["loc"])
    if loc and loc[-1] == "[key]":
        kind, loc = "bad_key", loc[:-1]
    if kind in ("unknown_key", "order") or (kind == "rule" and "field" in ctx):
        loc.append(ctx["key" if kind == "unknown_key" else "field"])
    path = ".".join(str(part) for part in [where, *loc] if part != "")
    msg = error["msg"].removeprefix("Value error, ")
    if kind == "unknown_sonar":
        return msg
    if kind in ("unknown_key", "bad_key"):
        return f"{path}: " + (msg if kind == "unknown_key" else f"keys must match {KEY_PATTERN.pattern} (a "
                              "lower-case letter, then lower-case letters, digits or '_')")
    if kind == "missing":
        return f"{path} is missing"
    if kind in ("model_type", "dict_type", "model_attributes_type"):
        return f"{path} must be a table; got {type(got).__name__}"
    if kind == "string_type":
        return f"{path} must be a string; got {got!r}"
    if kind in ("value_range", "one_note", "non_empty", "order") or (kind == "rule" and "field" in ctx):
        return f"{path} {msg}"
    if kind == "rule":
        return f"{path}: {msg}" if path else msg
    return f"{path}: {msg.replace('Input should be', 'must be')}; got {got!r}"


def validated(model: type[BaseModel], doc: Any, where: str = "") -> Any:
    """``model.model_validate(doc)``, an error as a one-line ``ValueError``.

    Parameters
    ----------
    model : type of pydantic.BaseModel
        The model.
    doc : Any
        The parsed data.
    where : str
        The dotted key path of ``doc``, prefixed to the error's key path.

    Returns
    -------
    pydantic.BaseModel
        The validated model.
    """
    try:
        return model.model_validate(doc)
    except ValidationError as exc:
        raise ValueError(validation_message(exc, where)) from None


@functools.lru_cache(maxsize=None)
def _adapter(kind: Any) -> TypeAdapter:
    return TypeAdapter(kind)


def checked(kind: Any, value: Any, where: str) -> Any:
    """``value`` validated as ``kind`` (a declared type of the data model, e.g. a
    :func:`bounded` number), a refusal as a one-line ``ValueError`` starting with ``where``.

    Parameters
    ----------
    kind : type
        The type.
    value : Any
        The value.
    where : str
        What the value is (a key, ``-p water_depth_m``), prefixed to the message.

    Returns
    -------
    Any
        The validated value.
    """
    try:
        return _adapter(kind).validate_python(value)
    except ValidationError as exc:
        raise ValueError(validation_message(exc, where)) from None
