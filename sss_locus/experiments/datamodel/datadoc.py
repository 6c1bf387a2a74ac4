"""Merging the shipped ``data/*.toml`` with a user's files and ``--set`` overrides (the
low-level half of :mod:`sss_locus.experiments.datamodel.userdata`, which documents the rules; the loaders
of platforms, envelopes, noise and terrain read :func:`document`)."""

from __future__ import annotations

import copy
import hashlib
import json
import re
import tomllib
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from sss_locus.paths import DATA_DIR
from sss_locus.experiments.datamodel.inputs import read_toml, suggestion

#: Platform, sonar, envelope and noise keys (``_`` becomes ``-`` in figure labels and glue keys).
KEY_PATTERN = re.compile(r"[a-z][a-z0-9_]*")
#: Shipped files, in merge order, and the top-level tables a user file may hold.
SHIPPED_FILES: tuple[str, ...] = ("platforms.toml", "survey.toml", "noise.toml", "terrain.toml", "survey_design.toml")
USER_TABLES: tuple[str, ...] = ("sonars", "platforms", "envelopes", "offset_models", "noise", "terrain", "survey",
                                 "survey_design")
#: Tables whose numbers sit one level down (``survey.area_m``), not two (``noise.auv.range_m``).
FLAT_TABLES: tuple[str, ...] = ("survey", "survey_design")
SET_NOTE = "user override: --set "
T = TypeVar("T")


@dataclass(frozen=True)
class DataInputs:
    """User data files (absolute paths) and ``KEY.PATH=VALUE`` overrides, in order."""

    files: tuple[str, ...] = ()
    sets: tuple[str, ...] = ()

    @property
    def is_default(self) -> bool:
        return not self.files and not self.sets


_ACTIVE = DataInputs()


def label_key(key: str) -> str:
    """A data key as it appears in figure labels and glue keys: ``my_auv`` -> ``my-auv``
    (injective on keys matching :data:`KEY_PATTERN`, which never contain ``-``).

    Parameters
    ----------
    key : str
        A platform, sonar, envelope or noise key matching :data:`KEY_PATTERN`.

    Returns
    -------
    str
        ``key`` with every ``_`` replaced by ``-``.

    Raises
    ------
    ValueError
        ``key`` is not a string matching :data:`KEY_PATTERN`.
    """
    if not isinstance(key, str) or not KEY_PATTERN.fullmatch(key):
        raise ValueError(f"key must match {KEY_PATTERN.pattern} (lower-case letter, then lower-case "
                         f"letters, digits or '_'); got {key!r}")
    return key.replace("_", "-")


def _is_number_entry(value: Any) -> bool:
    return isinstance(value, Mapping) and "value" in value


def merge(base: Mapping[str, Any], over: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` with ``over`` merged in by key (tables recursively; numbers replaced whole).

    Parameters
    ----------
    base : Mapping
        A data document (parsed TOML).
    over : Mapping
        The document merged on top. A number entry (a table with a ``value`` key, with its
        unit, source and assumption) replaces the one in ``base`` whole; other tables merge key
        by key; anything else replaces.

    Returns
    -------
    dict
        A new document (deep copies; neither argument is changed).
    """
    out = copy.deepcopy(dict(base))
    for key, value in over.items():
        if isinstance(value, Mapping) and not _is_number_entry(value) and isinstance(out.get(key), Mapping) \
                and not _is_number_entry(out.get(key)):
            out[key] = merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def check_user_document(doc: Mapping[str, Any], where: str) -> None:
    """Only the known top-level tables, and keys of the form :data:`KEY_PATTERN`.

    Parameters
    ----------
    doc : Mapping
        A user's data file, parsed.
    where : str
        The file's name, the start of every error message.

    Raises
    ------
    ValueError
        An unknown top-level key (with the nearest known one suggested), a top-level entry
        that is not a table, or a key not matching :data:`KEY_PATTERN`.
    """
    unknown = set(doc) - set(USER_TABLES) - {"schema_version"}
    if unknown:
        first = sorted(unknown)[0]
        raise ValueError(f"{where}: unknown top-level keys {sorted(unknown)}{suggestion(first, USER_TABLES)} "
                         f"(allowed: {list(USER_TABLES)})")
    for name in USER_TABLES:
        tables = doc.get(name, {})
        if not isinstance(tables, Mapping):
            raise ValueError(f"{where}: {name} must be a table; got {type(tables).__name__}")
        for key in tables:
            if not KEY_PATTERN.fullmatch(key):
                raise ValueError(f"{where}: {name}.{key}: keys must match {KEY_PATTERN.pattern} "
                                 "(lower-case letter, then lower-case letters, digits or '_')")


def parse_set(text: str, base: Mapping[str, Any]) -> dict[str, Any]:
    """The override document of one ``KEY.PATH=VALUE`` (VALUE read as TOML, else a string).

    Parameters
    ----------
    text : str
        One ``--set`` argument, e.g. ``platforms.auv.transducers.port.tilt_deg=15`` (units as the
        field's name says). A path must start with one of :data:`USER_TABLES`, then a key and a
        field (only the field for the :data:`FLAT_TABLES`).
    base : Mapping
        The document merged so far: a number field there (or a new field given a number)
        becomes a number entry ``{"value", "assumption": "user override: --set ..."}``.

    Returns
    -------
    dict
        A document holding only the override, to :func:`merge` onto ``base``.

    Raises
    ------
    ValueError
        No ``=``, a path too short or outside :data:`USER_TABLES`, or a path ending in ``.value``.
    """
    if not isinstance(text, str) or "=" not in text:
        raise ValueError(f"--set expects KEY.PATH=VALUE (e.g. platforms.auv.transducers.port.tilt_deg=15); "
                         f"got {text!r}")
    path, _, raw = (s.strip() for s in text.partition("="))
    parts = path.split(".")
    if len(parts) < (2 if parts[0] in FLAT_TABLES else 3) or parts[0] not in USER_TABLES or not all(parts):
        raise ValueError(f"--set {text!r}: KEY.PATH must start with one of {list(USER_TABLES)}, then a key "
                         "and a field (e.g. platforms.auv.transducers.port.tilt_deg, "
                         "terrain.random.rms_relief_m; survey.area_m)"
                         + suggestion(parts[0], USER_TABLES))
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    target: Any = base
    for part in parts:
        target = target.get(part) if isinstance(target, Mapping) else None
    if parts[-1] == "value":
        raise ValueError(f"--set {text!r}: name the field, not its .value (drop the trailing '.value')")
    if _is_number_entry(target) or (target is None and isinstance(value, (int, float))
                                    and not isinstance(value, bool)):
        value = {"value": value, "assumption": f"{SET_NOTE}{path}={raw}"}
    doc: dict[str, Any] = {}
    node = doc
    for part in parts[:-1]:
        node = node.setdefault(part, {})
    node[parts[-1]] = value
    return doc


def shipped_document() -> dict[str, Any]:
    """The shipped data files (:data:`SHIPPED_FILES` under ``data/``), merged in order.

    Returns
    -------
    dict
        The merged document, read afresh on each call.
    """
    doc: dict[str, Any] = {}
    for name in SHIPPED_FILES:
        doc = merge(doc, read_toml(DATA_DIR / name))
    return doc


def document(inputs: DataInputs | None = None) -> dict[str, Any]:
    """The merged data document of ``inputs`` (default: the active inputs, :func:`use`).

    Parameters
    ----------
    inputs : DataInputs, optional
        User files (merged in order after the shipped ones, each checked by
        :func:`check_user_document`) and ``--set`` overrides (merged last, in order).

    Returns
    -------
    dict
        The merged document; the shipped one for default inputs.
    """
    inputs = _ACTIVE if inputs is None else inputs
    shipped = doc = shipped_document()
    for path in inputs.files:
        user = read_toml(path)
        check_user_document(user, str(path))
        doc = merge(doc, user)
    named = doc  # the entries as named: shipped ones as shipped, a user's as their file has them
    for text in inputs.sets:
        doc = merge(doc, parse_set(text, doc))
    if not (inputs.files or inputs.sets):
        return doc
    reference = {t: {**named.get(t, {}), **shipped.get(t, {})} for t in NAMED_TABLES}
    return mark_changed_names(doc, reference)


#: The tables whose entries' ``name`` says what a figure shows (a caption or a panel title).
NAMED_TABLES: tuple[str, ...] = ("sonars", "platforms")


def changed_fields(entry: Any, shipped: Any, prefix: str = "") -> list[str]:
    """Dotted fields of a data entry whose values differ from the shipped entry's, ``name``
    left out; a number entry compares its ``value`` only (a new source text is no new value).

    Parameters
    ----------
    entry, shipped : Any
        An entry of the merged and of the shipped document (e.g. ``doc["sonars"]["x"]``).
    prefix : str
        Prepended to every field (used by the recursion).

    Returns
    -------
    list of str
        E.g. ``["azimuth_deg", "transducers.port.tilt_deg"]``, sorted by key; empty when the
        values are the shipped ones.
    """
    if _is_number_entry(entry) and _is_number_entry(shipped):
        return [] if entry["value"] == shipped["value"] else [prefix.rstrip(".")]
    if isinstance(entry, Mapping) and isinstance(shipped, Mapping) and not _is_number_entry(entry) \
            and not _is_number_entry(shipped):
        return [f for k in sorted(set(entry) | set(shipped)) if not (k == "name" and not prefix)
                for f in changed_fields(entry.get(k), shipped.get(k), f"{prefix}{k}.")]
    return [] if entry == shipped else [prefix.rstrip(".")]


def changed_name(shipped_name: str, fields: Iterable[str]) -> str:
    """A shipped entry's name for an entry whose values a user changed but whose name they kept:
    ``"<name> (changed: <fields>)"``, so no figure names shipped hardware for other values.

    Parameters
    ----------
    shipped_name : str
        The shipped entry's ``name``.
    fields : iterable of str
        The changed fields (:func:`changed_fields`), at least one.

    Returns
    -------
    str
        The marked name.
    """
    return f"{shipped_name}{CHANGED_MARK}{', '.join(fields)})"


#: What :func:`changed_name` puts between a shipped name and the fields changed.
CHANGED_MARK = " (changed: "


def is_changed_name(name: str, shipped_name: str) -> bool:
    """Whether ``name`` is ``shipped_name`` marked by :func:`changed_name`.

    Parameters
    ----------
    name, shipped_name : str
        An entry's name in the merged data and in the shipped data.

    Returns
    -------
    bool
        True for ``"<shipped_name> (changed: ...)"``.
    """
    return name.startswith(shipped_name + CHANGED_MARK) and name.endswith(")")


def mark_changed_names(doc: Mapping[str, Any], shipped: Mapping[str, Any]) -> dict[str, Any]:
    """``doc`` with the name of every sonar and platform whose values differ from the reference
    entry of the same key, but whose name does not, marked by :func:`changed_name`; a platform
    also counts its sonar's changes (``"sonar azimuth_deg"``).

    Parameters
    ----------
    doc : Mapping
        A merged data document (shipped data, user files, overrides).
    shipped : Mapping
        The reference entries by table (:data:`NAMED_TABLES`): the shipped ones, and for an
        entry a user's file adds, that entry as the file names it (so a ``--set`` that changes
        it marks its name too).

    Returns
    -------
    dict
        A copy of ``doc``; entries renamed, without a reference, or as their reference are
        unchanged.
    """
    out = copy.deepcopy(dict(doc))
    changed: dict[str, dict[str, list[str]]] = {t: {} for t in NAMED_TABLES}
    for table in NAMED_TABLES:
        for key, entry in doc.get(table, {}).items():
            ship = shipped.get(table, {}).get(key)
            if isinstance(entry, Mapping) and isinstance(ship, Mapping):
                changed[table][key] = changed_fields(entry, ship)
    for key, fields in changed["platforms"].items():
        sonar = doc["platforms"][key].get("sonar")
        if isinstance(sonar, str) and sonar == shipped["platforms"][key].get("sonar"):  # a renamed sonar too
            fields += [f"sonar {f}" for f in changed["sonars"].get(sonar, [])]
    for table in NAMED_TABLES:
        for key, fields in changed[table].items():
            if fields and doc[table][key].get("name") == shipped[table][key].get("name"):
                out[table][key]["name"] = changed_name(shipped[table][key]["name"], fields)
    return out


def make_inputs(files: Iterable[str | Path] = (), sets: Iterable[str] = ()) -> DataInputs:
    """Absolute paths of ``files`` and the overrides, as :class:`DataInputs` (not validated).

    Parameters
    ----------
    files : iterable of str or pathlib.Path
        User data files (``~`` expanded, made absolute; not opened here).
    sets : iterable of str
        ``KEY.PATH=VALUE`` overrides, kept as given.

    Returns
    -------
    DataInputs

    Raises
    ------
    ValueError
        An item of ``files`` (``data_files``) or ``sets`` (``data_set``) is not a string.
    """
    files, sets = list(files or ()), list(sets or ())
    for name, items, kind in (("data_files", files, (str, Path)), ("data_set", sets, str)):
        for item in items:
            if not isinstance(item, kind):
                raise ValueError(f"{name} must be a list of strings; got {item!r}")
    return DataInputs(tuple(str(Path(f).expanduser().resolve()) for f in files), tuple(sets))


def activate(inputs: DataInputs) -> None:
    """Make ``inputs`` the active inputs (validate them first: :func:`sss_locus.experiments.datamodel.userdata.use`).

    Parameters
    ----------
    inputs : DataInputs
        Used by every later load that passes no inputs of its own (this process only).
    """
    global _ACTIVE
    _ACTIVE = inputs


def active() -> DataInputs:
    """The active inputs (:func:`activate`).

    Returns
    -------
    DataInputs
        The default (shipped data only) until something is activated.
    """
    return _ACTIVE


def file_sha256(path: str | Path) -> str:
    """SHA-256 of a file's bytes.

    Parameters
    ----------
    path : str or pathlib.Path

    Returns
    -------
    str
        64 lower-case hex digits.
    """
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def files_read(inputs: DataInputs | None = None) -> list[dict[str, str]]:
    """Every data file a load reads, shipped then the user's: ``{"path", "sha256", "role"}``.

    Parameters
    ----------
    inputs : DataInputs, optional
        Default: the active inputs.

    Returns
    -------
    list of dict
        One row per file: ``path`` (``data/<name>`` for shipped files, the absolute path for a
        user's), ``sha256`` and ``role`` (``"shipped"`` or ``"user"``).
    """
    inputs = _ACTIVE if inputs is None else inputs
    rows = [{"path": f"data/{name}", "sha256": file_sha256(DATA_DIR / name), "role": "shipped"}
            for name in SHIPPED_FILES]
    rows += [{"path": path, "sha256": file_sha256(path), "role": "user"} for path in inputs.files]
    return rows


#: The open recordings of data entries read (:func:`recording`), innermost last; none: not recorded.
_RECORDINGS: list[set[str]] = []


def note_read(*entries: str) -> None:
    """Report that the data entries ``entries`` (dotted key paths such as ``platforms.auv`` or a
    whole table ``platforms``) were read: kept in memory by the open :func:`recording`, if any.

    Who records is the caller's business (the pipeline records a run's reads and hashes exactly
    these entries of the run's merged data into its executed copy, so an edit to a user file makes
    stale the runs that read the edited entries, and no others); this module writes nothing.

    Parameters
    ----------
    *entries : str
        Dotted key paths of the merged document.
    """
    if _RECORDINGS:
        _RECORDINGS[-1].update(entries)


def load_table(parse: Callable[[dict[str, Any]], T], path: str | Path | None = None, *entries: str,
               doc: Mapping[str, Any] | None = None) -> T:
    """What every loader of the data does: ``parse`` (validate one table and build its object) of
    the run's merged data, noting ``entries`` as read (:func:`note_read`); or of the one TOML
    file ``path`` (nothing noted); or of the parsed document ``doc``.

    Parameters
    ----------
    parse : callable
        ``parse(document) -> object``: validates the table(s) it needs
        (:func:`sss_locus.experiments.datamodel.models.validate_document`).
    path : str or pathlib.Path, optional
        A TOML file read alone instead of the run's data.
    *entries : str
        Dotted key paths of the run's data that ``parse`` reads (e.g. ``noise.auv``).
    doc : mapping, optional
        A parsed document used instead of any file (nothing noted).

    Returns
    -------
    object
        ``parse``'s result.
    """
    if doc is not None:
        return parse(doc)
    if path is not None:
        return parse(read_toml(path))
    note_read(*entries)
    return parse(document())


def reads_so_far() -> set[str] | None:
    """The data entries read since the outermost open :func:`recording` began, ``None`` when
    nothing records them.

    Returns
    -------
    set of str or None
        A new set (the union over the open recordings).
    """
    return set().union(*_RECORDINGS) if _RECORDINGS else None


@contextmanager
def recording() -> Iterator[set[str]]:
    """Within the block, record the data entries read (:func:`note_read`) into the set it gives;
    on leaving, an enclosing recording gets them too (a computation inside a run).

    Yields
    ------
    set of str
        The dotted entries read inside the block, filled in as they are read.
    """
    reads: set[str] = set()
    depth = len(_RECORDINGS)
    _RECORDINGS.append(reads)
    try:
        yield reads
    finally:
        del _RECORDINGS[depth:]
        if _RECORDINGS:
            _RECORDINGS[-1].update(reads)


def entries_sha256(entries: Iterable[str], inputs: DataInputs | None = None) -> dict[str, str]:
    """SHA-256 of each dotted entry of the merged document of ``inputs`` (``null`` if absent).

    Parameters
    ----------
    entries : iterable of str
        Dotted key paths (duplicates are hashed once).
    inputs : DataInputs, optional
        Default: the active inputs.

    Returns
    -------
    dict of str to str
        Entry -> SHA-256 of its value as sorted-key JSON, in sorted order; an absent entry
        hashes the JSON ``null``.
    """
    doc = document(inputs)
    out = {}
    for entry in sorted(set(entries)):
        node: Any = doc
        for part in entry.split("."):
            node = node.get(part) if isinstance(node, Mapping) else None
        out[entry] = hashlib.sha256(json.dumps(node, sort_keys=True, default=str).encode()).hexdigest()
    return out
