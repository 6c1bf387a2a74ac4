"""Reading the project's input files: TOML parsing with one-line errors, why a path cannot be
read, and the nearest known name of a misspelt one. (What the data files may hold is the data
model, :mod:`sss_locus.experiments.datamodel.models`.)"""

from __future__ import annotations

import difflib
import math
import tomllib
from pathlib import Path
from typing import Any


def missing_file(path: str | Path, what: str) -> str:
    """Why ``path`` cannot be read as the input file ``what`` (e.g. ``"area file"``), in one
    line: an empty path, a directory, a FIFO, a device or socket, a broken link, or a path that
    does not exist. For a regular file: ``""``.

    Parameters
    ----------
    path : str or pathlib.Path
        The path given by the user.
    what : str
        What the file is, the start of the message (e.g. ``"area file"``).

    Returns
    -------
    str
        One line naming ``what`` and ``path``, or ``""`` for a readable regular file (a link to
        one included).
    """
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
    ``ValueError`` naming the file.

    Parameters
    ----------
    path : str or pathlib.Path

    Returns
    -------
    dict
        The parsed document (an empty file gives ``{}``).

    Raises
    ------
    ValueError
        A directory, text that is not UTF-8 (with the byte offset), or invalid TOML.
    OSError
        The file cannot be read (see :func:`missing_file` for a one-line reason).
    """
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
    """``"; did you mean `x`?"`` for the known name nearest to ``name``, or ``""``.

    Parameters
    ----------
    name : str
        The misspelt name (anything is converted with ``str``).
    known : iterable
        The valid names.

    Returns
    -------
    str
        The suffix for an error message, or ``""`` when no known name is close (``difflib``
        ratio below 0.6).
    """
    close = difflib.get_close_matches(str(name), [str(k) for k in known], n=1, cutoff=0.6)
    return f"; did you mean `{close[0]}`?" if close else ""


def check_range(value: float, path: str, lo: float, hi: float) -> float:
    """``value`` if it is a finite number in ``[lo, hi]``, else a ``ValueError`` naming ``path``
    (for function arguments; the data files' ranges are in the data model).

    Parameters
    ----------
    value : float
        The number to check (in the unit its name says).
    path : str
        Its name in the error message (e.g. ``"margin_deg"``).
    lo, hi : float
        Inclusive bounds, same unit.

    Returns
    -------
    float
        ``value`` unchanged.

    Raises
    ------
    ValueError
        NaN, infinite or outside ``[lo, hi]``.
    """
    if not (math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"{path} must be a finite number in [{lo}, {hi}]; got {value!r}")
    return value
