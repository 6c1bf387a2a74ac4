"""Reading and validating the project's TOML inputs (``data/*.toml`` and users' files).

Every number in those files is a small table ``{value = ..., source = "..."}`` or
``{value = ..., assumption = "..."}``; :func:`sourced` reads one, records its provenance and
checks its range. Every error names the full key path of the offending entry (for example
``platforms.auv.transducers.port.tilt_deg.value must be a finite number in [-90.0, 90.0]``).
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any


def missing_file(path: str | Path, what: str) -> str:
    """Why ``path`` cannot be read as the input file ``what`` (e.g. ``"area file"``), in one
    line: an empty path, a directory, a FIFO, a device or socket, a broken link, or a path that
    does not exist. For a regular file: ``""``."""
    import stat

    if not str(path).strip():
        return f"{what}: the path is empty; give the file's name"
    p = Path(path)
    try:
        mode = p.stat().st_mode
    except OSError:
        return f"{what} {path} is a broken link" if p.is_symlink() else f"{what} {path} does not exist"
    kinds = [(stat.S_ISREG, ""), (stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
             (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket")]
    kind = next((name for test, name in kinds if test(mode)), "not a regular file")
    return f"{what} {path} is {kind}, not a file" if kind else ""


def read_toml(path: str | Path) -> dict[str, Any]:
    """Parse a TOML file (UTF-8, a byte-order mark allowed); a syntax error becomes a
    ``ValueError`` naming the file."""
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"data file {path} is a directory, not a TOML file")
    raw = path.read_bytes()
    try:
        return tomllib.loads(raw.decode("utf-8-sig"))
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path} is not UTF-8 text (byte {exc.start}); save it as UTF-8") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path} is not valid TOML: {exc}") from exc


def suggestion(name: str, known: Any) -> str:
    """``"; did you mean `x`?"`` for the known name nearest to ``name``, or ``""``."""
    close = difflib.get_close_matches(str(name), [str(k) for k in known], n=1, cutoff=0.6)
    return f"; did you mean `{close[0]}`?" if close else ""


def platform_table(doc: Mapping[str, Any], section: str,
                   platform_key: str) -> tuple[Mapping[str, Any], str]:
    """The ``[<section>.<platform_key>]`` table of a parsed document and its key path; an unknown
    ``platform_key`` is refused naming the keys the section has."""
    tables = table(doc, section, "")
    if platform_key not in tables:
        raise ValueError(f"platform_key must be one of {sorted(tables)}; got {platform_key!r}")
    return table(tables, platform_key, section), f"{section}.{platform_key}"


def check_range(value: float, path: str, lo: float, hi: float) -> float:
    if not (math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"{path} must be a finite number in [{lo}, {hi}]; got {value!r}")
    return value


def table(doc: Mapping[str, Any], key: str, path: str) -> Mapping[str, Any]:
    full = f"{path}.{key}" if path else key
    if key not in doc:
        raise ValueError(f"missing table {full}")
    value = doc[key]
    if not isinstance(value, Mapping):
        raise ValueError(f"{full} must be a table; got {type(value).__name__}")
    return value


def string(doc: Mapping[str, Any], key: str, path: str) -> str:
    full = f"{path}.{key}"
    if key not in doc:
        raise ValueError(f"missing key {full}")
    if not isinstance(doc[key], str) or not doc[key].strip():
        raise ValueError(f"{full} must be a non-empty string; got {doc[key]!r}")
    return doc[key]


def sourced(doc: Mapping[str, Any], key: str, path: str, provenance: dict[str, str], *,
             lo: float | None = None, hi: float | None = None, choices: tuple[str, ...] = ()):
    """Read ``{value = ..., source|assumption = "..."}``; record the provenance; check the range."""
    entry = table(doc, key, path)
    full = f"{path}.{key}"
    unknown = set(entry) - {"value", "source", "assumption"}
    if unknown:
        first = sorted(unknown)[0]
        raise ValueError(f"{full} has unknown keys {sorted(unknown)}{suggestion(first, ('value', 'source', 'assumption'))}"
                         " (allowed: value, source, assumption)")
    if "value" not in entry:
        raise ValueError(f"missing key {full}.value")
    notes = [k for k in ("source", "assumption") if k in entry]
    if len(notes) != 1:
        raise ValueError(f"{full} needs exactly one of 'source' or 'assumption'; found {notes or 'none'}")
    note = entry[notes[0]]
    if not isinstance(note, str) or not note.strip():
        raise ValueError(f"{full}.{notes[0]} must be a non-empty string; got {note!r}")
    provenance[full] = f"{notes[0]}: {note}"
    value = entry["value"]
    if choices:
        if value not in choices:
            raise ValueError(f"{full}.value must be one of {list(choices)}; got {value!r}")
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{full}.value must be a number; got {value!r}")
    return check_range(float(value), f"{full}.value",
                        -math.inf if lo is None else lo, math.inf if hi is None else hi)
