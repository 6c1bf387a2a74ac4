"""Tables a reader can read, in the web book and its PDF: :func:`readable_table`.

A chapter shows a computed table through :func:`readable_table` instead of the raw DataFrame:

* no index column (a meaningful index, such as a platform key, becomes an ordinary first column);
* headers in words with units: ``median_locus_length_m`` reads ``median locus length (m)``,
  ``ci_low_deg`` ``ci low (deg)``; multi-level columns are joined;
* numbers to the significant digits the prose prints (three by default), thousands separated;
  ``True``/``False`` as ``yes``/``no``;
* an explicit mark, :data:`NOT_APPLICABLE`, instead of ``NaN``/``None``, explained in the
  table's caption;
* a wide table of few rows (more than :data:`WIDE` columns) is turned a quarter, one row per
  quantity;
* text cells wrap at spaces (and after the ``_`` of long names) and numbers never wrap, at 80 %
  of the text size, so a column is never squeezed below its longest word and wide tables fit the
  text column (one that cannot scrolls inside it rather than overflow).

The styles are carried by the table itself (no site CSS), so the PDF printed from the single-page
build shows the same table.
"""

from __future__ import annotations

import hashlib
import html
import math
import re
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from sss_locus.report.common.text import fmt_sig

#: The mark of a cell with no value for its row.
NOT_APPLICABLE = "–"
#: More columns than this, and fewer rows than columns, and the table is shown turned a quarter.
WIDE = 7
#: Unit suffixes of column names, and how the header writes them.
UNITS = (("_deg", "deg"), ("_rad", "rad"), ("_pct", "%"), ("_km", "km"), ("_m", "m"), ("_h", "h"), ("_s", "s"))


def header(name: object) -> str:
    """A column name in words with its unit: ``"median_length_m"`` -> ``"median length (m)"``.

    Parameters
    ----------
    name : object
        A column name: a string, or a tuple (a column of a MultiIndex) whose parts are joined.

    Returns
    -------
    str
        The header; a name ending in a unit suffix of :data:`UNITS` gets the unit in brackets.

    Examples
    --------
    >>> header("ci_low_deg"), header("platform"), header(("rho", "seed 1")), header("track_km"), header("time_h")
    ('ci low (deg)', 'platform', 'rho seed 1', 'track (km)', 'time (h)')
    """
    if isinstance(name, tuple):
        return " ".join(header(part) for part in name if str(part))
    text = str(name)
    for suffix, unit in UNITS:
        if text.endswith(suffix) and len(text) > len(suffix) and " " not in text:
            return f"{text[:-len(suffix)].replace('_', ' ')} ({unit})"
    return text.replace("_", " ") if " " not in text else text


def cell(value: object, digits: int = 3) -> str:
    """One cell as text: numbers to ``digits`` significant figures (whole numbers of 10**digits
    and more with thousands separators, below 0.001 in scientific notation), booleans as yes/no,
    missing as :data:`NOT_APPLICABLE`.

    Parameters
    ----------
    value : object
        The cell's value.
    digits : int
        Significant figures of a floating-point value.

    Returns
    -------
    str
        The cell's text.

    Examples
    --------
    >>> [cell(v) for v in (0.012345, 8.08e-12, 123456.7, 7, True, None, float("nan"), "auv")]
    ['0.0123', '8.08e-12', '123,457', '7', 'yes', '–', '–', 'auv']
    """
    if value is None or (isinstance(value, (float, np.floating)) and not math.isfinite(value)):
        return NOT_APPLICABLE if value is None or math.isnan(value) else str(value)
    if value is pd.NA or value is pd.NaT:
        return NOT_APPLICABLE
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return f"{int(value):,}"
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if x != 0 and abs(x) < 1e-3:  # a long row of zeros would widen the column
            return f"{x:.{digits - 1}e}"
        return f"{x:,.0f}" if abs(x) >= 10 ** digits else fmt_sig(x, digits)
    return str(value).replace("_", "_\u200b")  # long names may break after an underscore


def _transposed(shown: pd.DataFrame, row_labels=None) -> pd.DataFrame:
    """A wide table of few rows turned a quarter: one row per column, one column per row, headed
    by the row's labels (``row_labels``, default its leading text columns, at most two), as they
    are (a platform key stays a key)."""
    labels = list(row_labels) if row_labels is not None else \
        [c for c in shown.columns[:2] if not pd.api.types.is_numeric_dtype(shown[c])]
    heads = [", ".join(str(v) for v in row) for row in shown[labels].itertuples(index=False)] if labels \
        else [str(i + 1) for i in range(len(shown))]
    out = shown.drop(columns=labels).astype(object).T  # as objects: a count stays a whole number
    out.columns = pd.Index(heads)
    out.index = pd.Index([header(c) for c in out.index], name="quantity")
    return _index_as_columns(out)


def _index_as_columns(frame: pd.DataFrame) -> pd.DataFrame:
    """``frame`` with its index levels as leading columns, but for unnamed integer levels (row
    numbers, which say nothing); an unnamed level of labels becomes a column without a header."""
    if isinstance(frame.index, pd.RangeIndex):
        return frame
    keep = [i for i, level in enumerate(frame.index.levels if isinstance(frame.index, pd.MultiIndex)
                                        else [frame.index])
            if frame.index.names[i] is not None or not pd.api.types.is_integer_dtype(level)]
    names = [frame.index.names[i] if frame.index.names[i] is not None else "" for i in keep]
    out = frame.reset_index(drop=True)
    for position, (i, name) in enumerate(zip(keep, names)):
        out.insert(position, name if name not in out.columns else f"{name} ", frame.index.get_level_values(i))
    return out


def readable_table(frame: pd.DataFrame, *, caption: str = "", digits: int = 3,
                   headers: Mapping[str, str] | None = None, row_labels: Sequence[str] | None = None):
    """``frame`` as a table a reader can read (module docstring); a pandas ``Styler`` to show.

    Parameters
    ----------
    frame : pandas.DataFrame
        The computed table (not changed).
    caption : str
        Shown above the table; a note explaining :data:`NOT_APPLICABLE` is added when a cell has
        no value.
    digits : int
        Significant figures of floating-point cells.
    headers : mapping, optional
        Headers to use instead of :func:`header` for some columns (by original name).
    row_labels : sequence of str, optional
        The columns that name a row, when a wide table is turned a quarter (default: its leading
        text columns, at most two); their values head the turned table's columns.

    Returns
    -------
    pandas.io.formats.style.Styler
        The table as text cells (numbers right-aligned), headers in words with units, index
        hidden, caption (HTML) above; its id is a hash of its content (the same table, the same
        HTML).

    Raises
    ------
    ValueError
        When ``frame`` is not a DataFrame or ``row_labels`` are not its columns.
    """
    if not isinstance(frame, pd.DataFrame):
        raise ValueError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    shown = _index_as_columns(frame).infer_objects()  # numbers held as objects (a transposed dict) are numbers
    if row_labels is not None and not set(row_labels) <= set(shown.columns):
        raise ValueError(f"row_labels must be columns of frame ({list(shown.columns)}); got {list(row_labels)}")
    turned = shown.shape[1] > WIDE and shown.shape[0] < shown.shape[1] - 1  # few rows, many columns
    if turned:
        shown = _transposed(shown, row_labels)
    names = [str(c) if turned else (headers or {}).get(c, header(c)) if not isinstance(c, tuple) else header(c)
             for c in shown.columns]
    numeric = [pd.api.types.is_numeric_dtype(shown[c]) and not pd.api.types.is_bool_dtype(shown[c])
               for c in shown.columns]
    body = pd.DataFrame({i: [cell(v, digits) for v in shown.iloc[:, i]] for i in range(shown.shape[1])})
    body.columns = pd.Index(names)
    missing = bool((body == NOT_APPLICABLE).to_numpy().any())
    note = f"{NOT_APPLICABLE}: no value for this row." if missing else ""
    text = " ".join(t for t in (caption.strip(), note) if t)
    uuid = hashlib.sha256("\0".join([*names, text, *body.to_numpy().ravel()]).encode()).hexdigest()[:10]  # stable ids
    styler = body.style.hide(axis="index").format(escape="html").format_index(escape="html", axis=1)
    styler.set_uuid(uuid)
    styles = [
        {"selector": "", "props": "font-size: 0.8em; border-collapse: collapse; max-width: 100%; margin-bottom: 1em; "
                                  "display: block; overflow-x: auto;"},
        # a narrow table's caption as wide as a line of text, not as its few columns
        {"selector": "caption", "props": "caption-side: top; text-align: left; font-size: 0.95em; "
                                         "min-width: min(36em, 90vw);"},
        {"selector": "th", "props": "text-align: left; vertical-align: bottom; white-space: normal; "
                                    "word-break: normal; overflow-wrap: normal; padding: 0.2em 0.5em;"},
        {"selector": "td", "props": "vertical-align: top; white-space: normal; word-break: normal; "
                                    "overflow-wrap: normal; padding: 0.2em 0.5em;"},
    ]
    styles += [{"selector": f"td.col{i}", "props": "white-space: nowrap; text-align: right;"}
               for i, is_number in enumerate(numeric) if is_number]
    styler.set_table_styles(styles)
    if text:
        styler.set_caption(caption_html(text))
    return styler


def caption_html(text: str) -> str:
    """A caption in the chapters' inline Markdown as HTML: ``**bold**`` and ```code``` marked up,
    everything else escaped (a user's file or feature name is text, never markup).

    Parameters
    ----------
    text : str
        The caption (inline Markdown: ``**bold**`` and backquoted code only).

    Returns
    -------
    str
        HTML.

    Examples
    --------
    >>> caption_html("**Real data**: `a<b.csv` & more")
    '<strong>Real data</strong>: <code>a&lt;b.csv</code> &amp; more'
    """
    out = html.escape(text, quote=False)
    out = re.sub(r"`([^`]+)`", r"<code>\1</code>", out)
    return re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", out)


def key_caption(names: Mapping[str, str]) -> str:
    """The caption line that names the platforms a table labels by key only (short row labels
    instead of long names wrapping into tall rows).

    Parameters
    ----------
    names : mapping of str to str
        Platform key -> display name; at least one.

    Returns
    -------
    str
        The caption line.

    Raises
    ------
    ValueError
        When ``names`` is empty.

    Examples
    --------
    >>> key_caption({"auv": "Torpedo AUV", "boat": "Surface boat"})
    'Platforms by key: auv, Torpedo AUV; boat, Surface boat.'
    """
    if not names:
        raise ValueError("key_caption needs at least one platform")
    return "Platforms by key: " + "; ".join(f"{k}, {n}" for k, n in names.items()) + "."


def files_note(label: str) -> str:
    """The caption sentence that points to a published table's files (served beside the figures).

    Parameters
    ----------
    label : str
        The table's label (its files' stem).

    Returns
    -------
    str
        The sentence.

    Examples
    --------
    >>> files_note("tab-survey-peaks")
    'Cite it with its files: figures/tab-survey-peaks.csv (values), .json (what it was computed from), .bib.'
    """
    return f"Cite it with its files: figures/{label}.csv (values), .json (what it was computed from), .bib."
