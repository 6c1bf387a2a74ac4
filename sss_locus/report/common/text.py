"""Prose formatting of computed numbers, for glued text and tables (never computation).

Every number the book states in prose goes through one of these functions, so the same kind of
number reads the same way on every page: significant figures (:func:`fmt_sig`), a median with its
interval (:func:`fmt_interval`), fractions as percentages (:func:`fmt_percent`), ratios as
changes (:func:`fmt_change`), crossing-angle bands (:func:`fmt_bands`), quantity names
(:func:`plain_label`), counted nouns (:func:`count_noun`), lists (:func:`and_list`) and which
platforms a run holds beside the paper's (:func:`run_platforms_md`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import pandas as pd

from sss_locus.experiments.stats.significant import round_sig
from sss_locus.report.common.style import QUANTITY_LABELS

NO_VALUE = "not computable from this run's samples"
"""What :func:`fmt_ci` says of an estimate that is not a finite number."""

NO_CI = "no 95 % CI: it could not be computed from this run's samples"
"""What :func:`fmt_ci` says by default in place of an interval whose ends are not finite."""

NO_BATCH_CI = ("no 95 % CI: too few samples, some replicate batches have no sample where it is "
               "measured")
"""In place of a replicate-batch interval (:func:`~sss_locus.experiments.stats.replicates.replicate_interval`)
whose ends are not finite: the statistic is undefined in at least one batch, i.e. a batch has no
sample in a bin or subset the statistic needs."""


def fmt_sig(x: float, digits: int = 2) -> str:
    """``x`` to ``digits`` significant figures, e.g. ``fmt_sig(0.012345) == "0.012"``.

    Non-finite values read ``"n/a"``.

    Parameters
    ----------
    x : float
        The number.
    digits : int
        Significant figures.

    Returns
    -------
    str
        The number as text (trailing zeros kept: ``"2.0"``), or ``"n/a"``.

    Examples
    --------
    >>> fmt_sig(123.4), fmt_sig(2.0), fmt_sig(float("nan"))
    ('120', '2.0', 'n/a')
    """
    if not math.isfinite(x):
        return "n/a"
    decimals = max(0, digits - 1 - int(math.floor(math.log10(abs(x))))) if x else 0
    return f"{float(round_sig(x, digits)):.{decimals}f}"


def interval_digits(low: float, high: float, digits: int = 2, most: int = 4) -> int:
    """The significant figures to print an interval with: ``digits``, or more (up to ``most``)
    while its two ends would print the same, so a printed interval always shows its width.

    Parameters
    ----------
    low, high : float
        The interval's ends.
    digits : int
        The fewest significant figures.
    most : int
        The most significant figures.

    Returns
    -------
    int
        Significant figures, ``digits`` to ``most``.

    Examples
    --------
    >>> interval_digits(2.9, 3.41), interval_digits(2.10, 2.14), interval_digits(0.1799, 0.1801, most=4)
    (2, 3, 4)
    """
    d = digits
    while d < most and math.isfinite(low) and math.isfinite(high) and fmt_sig(low, d) == fmt_sig(high, d):
        d += 1
    return d


def fmt_interval(estimate: Mapping[str, float], unit: str, digits: int = 2, no_ci: str | None = None) -> str:
    """A median and its 95 % interval: ``"3.1 m (95 % CI 2.9–3.4 m)"``, with more significant
    figures where ``digits`` would print both ends alike (:func:`interval_digits`).

    ``estimate`` holds ``median``, ``ci_low`` and ``ci_high``; a degree sign is written without a
    space (``"20° (95 % CI 18°–22°)"``). A median that is not finite reads :data:`NO_VALUE`, an
    interval whose ends are not finite ``no_ci`` (default :data:`NO_CI`).

    Parameters
    ----------
    estimate : mapping of str to float
        ``median``, ``ci_low`` and ``ci_high``, in ``unit``.
    unit : str
        Unit written after each number (``"m"``, ``"°"``, ...).
    digits : int
        The fewest significant figures.
    no_ci : str, optional
        Said instead of the interval when an end is not finite (default :data:`NO_CI`).

    Returns
    -------
    str
        The median and its interval.

    Examples
    --------
    >>> fmt_interval({"median": 3.14, "ci_low": 2.9, "ci_high": 3.41}, "m")
    '3.1 m (95 % CI 2.9–3.4 m)'
    >>> fmt_interval({"median": 0.1812, "ci_low": 0.1794, "ci_high": 0.1833}, "m")
    '0.181 m (95 % CI 0.179–0.183 m)'
    """
    sep = "" if unit == "°" else " "
    if not math.isfinite(estimate["median"]):
        return NO_VALUE
    if not (math.isfinite(estimate["ci_low"]) and math.isfinite(estimate["ci_high"])):
        return f"{fmt_sig(estimate['median'], digits)}{sep}{unit} ({no_ci or NO_CI})"
    digits = interval_digits(estimate["ci_low"], estimate["ci_high"], digits)
    lo, hi = fmt_sig(estimate["ci_low"], digits), fmt_sig(estimate["ci_high"], digits)
    return f"{fmt_sig(estimate['median'], digits)}{sep}{unit} (95 % CI {lo}–{hi}{sep}{unit})"


def fmt_ci(value: float, low: float, high: float, digits: int = 2, percent: bool = False,
           no_ci: str = NO_CI) -> str:
    """A ratio or share with its 95 % interval, each to ``digits`` significant figures, or more
    where the ends would print alike (:func:`interval_digits`); with ``percent`` the numbers are
    percentages (a share of 0 with an interval of 0 reads ``"0 %"``). An interval whose ends are
    not finite is replaced by ``no_ci`` (in brackets), an estimate that is not finite by
    :data:`NO_VALUE`: no ``"nan"`` or ``"n/a–n/a"`` reaches the text.

    Parameters
    ----------
    value : float
        The estimate (a fraction with ``percent``).
    low, high : float
        The ends of its 95 % interval.
    digits : int
        The fewest significant figures.
    percent : bool
        Print the numbers as percentages (times 100, with ``" %"``).
    no_ci : str
        Said instead of the interval when an end is not finite: why it is missing
        (:data:`NO_CI`, :data:`NO_BATCH_CI`).

    Returns
    -------
    str
        The estimate and its interval, or the estimate and ``no_ci``, or :data:`NO_VALUE`.

    Examples
    --------
    >>> fmt_ci(4.1514, 4.110, 4.1927), fmt_ci(2.1245, 2.1012, 2.1439), fmt_ci(0.0088, 0.00853, 0.00908, percent=True)
    ('4.2 (95 % CI 4.1–4.2)', '2.12 (95 % CI 2.10–2.14)', '0.88 % (95 % CI 0.85–0.91 %)')
    >>> fmt_ci(0.0, 0.0, 0.0, percent=True)
    '0 %'
    >>> fmt_ci(0.46, float("nan"), float("nan"), no_ci="no 95 % CI: too few samples")
    '0.46 (no 95 % CI: too few samples)'
    """
    scale, unit = (100.0, " %") if percent else (1.0, "")
    if not math.isfinite(value):
        return NO_VALUE
    if not (math.isfinite(low) and math.isfinite(high)):
        return f"{fmt_sig(scale * value, digits)}{unit} ({no_ci})"
    if percent and value == low == high == 0:
        return "0 %"
    digits = interval_digits(scale * low, scale * high, digits)
    v, lo, hi = (fmt_sig(scale * x, digits) for x in (value, low, high))
    return f"{v}{unit} (95 % CI {lo}–{hi}{unit})"


def fmt_ci_cells(values, lows, highs, digits: int = 2, missing: str = "—") -> list[str]:
    """:func:`fmt_ci` of each value with its interval, for a table column; ``missing`` where any
    of the three is not finite.

    Parameters
    ----------
    values, lows, highs : array_like of float, shape (n,)
        The estimates and the ends of their 95 % intervals.
    digits : int
        Significant figures (:func:`fmt_ci`).
    missing : str
        The cell of a row without a finite estimate or interval.

    Returns
    -------
    list of str, length n

    >>> fmt_ci_cells([3.9, float("nan")], [3.6, 1.0], [4.2, 2.0])
    ['3.9 (95 % CI 3.6–4.2)', '—']
    """
    return [fmt_ci(v, lo, hi, digits) if all(map(math.isfinite, (v, lo, hi))) else missing
            for v, lo, hi in zip(*(map(float, a) for a in (values, lows, highs)))]


def fmt_span(low: float, high: float) -> str:
    """A span of bin centres in whole degrees, one angle if it is one bin.

    Parameters
    ----------
    low, high : float
        The first and last bin centres (deg).

    Returns
    -------
    str
        The span in whole degrees.

    Examples
    --------
    >>> fmt_span(-85.0, -75.0), fmt_span(78.75, 78.75)
    ('-85° to -75°', '79°')
    """
    def deg(x: float) -> str:
        return f"{x:.0f}°"

    return deg(low) if round(low) == round(high) else f"{deg(low)} to {deg(high)}"


def fmt_percent(fraction: float) -> str:
    """A fraction as a percentage with enough digits to tell it from 0 % and 100 %.

    Parameters
    ----------
    fraction : float
        A share, 0 to 1.

    Returns
    -------
    str
        The percentage with ``" %"``.

    Examples
    --------
    >>> fmt_percent(0.5), fmt_percent(0.0004), fmt_percent(0.9996), fmt_percent(1.0)
    ('50.0 %', '0.04 %', '99.96 %', '100.0 %')
    """
    x = float(fraction)
    if x in (0.0, 1.0) or 0.001 <= x <= 0.999:
        return f"{100 * x:.1f} %"
    return f"{100 * x:.2f} %" if x > 0.999 else f"{100 * x:.2g} %"


def fmt_change(ratio: float, ci_low: float, ci_high: float) -> str:
    """A ratio of medians as a signed change in whole percent with its interval.

    Parameters
    ----------
    ratio : float
        Ratio of two medians (1: no change).
    ci_low, ci_high : float
        The ends of its 95 % interval.

    Returns
    -------
    str
        The signed change in percent with its interval.

    Examples
    --------
    >>> fmt_change(0.52, 0.47, 0.58)
    '-48 % (95 % CI -53 % to -42 %)'
    """
    def one(x: float) -> str:
        v = int(round(100 * (x - 1)))
        return f"{v:+d} %" if v else "0 %"

    return f"{one(ratio)} (95 % CI {one(ci_low)} to {one(ci_high)})"


def fmt_bands(bands: pd.DataFrame, kind: str) -> str:
    """The ``kind`` ("prefer" or "avoid") bands of
    :func:`~sss_locus.experiments.survey_passes.planning.planning_bands` as text, ``"none"`` if there are none.

    Parameters
    ----------
    bands : pandas.DataFrame
        Rows ``kind``, ``lo_deg``, ``hi_deg`` (crossing angles, deg).
    kind : str
        ``"prefer"`` or ``"avoid"``.

    Returns
    -------
    str
        The bands in degrees, comma-separated, or ``"none"``.

    Examples
    --------
    >>> b = pd.DataFrame({"kind": ["prefer", "prefer", "avoid"], "lo_deg": [0.0, 170.0, 60.0],
    ...                   "hi_deg": [0.0, 180.0, 110.0]})
    >>> fmt_bands(b, "prefer"), fmt_bands(b, "avoid")
    ('0°, 170–180°', '60–110°')
    """
    rows = bands[bands["kind"] == kind]
    parts = [f"{r.lo_deg:.0f}°" if r.lo_deg == r.hi_deg else f"{r.lo_deg:.0f}–{r.hi_deg:.0f}°"
             for r in rows.itertuples()]
    return ", ".join(parts) if parts else "none"


def plain_label(quantity: str) -> str:
    """A quantity's display name as plain text (no LaTeX), e.g. ``"|ψ₂|"``.

    Parameters
    ----------
    quantity : str
        A column name (a key of :data:`~sss_locus.report.common.style.QUANTITY_LABELS`, or any).

    Returns
    -------
    str
        Its display name in Unicode, or ``quantity`` itself when it has none.

    Examples
    --------
    >>> plain_label("abs_psi2_deg"), plain_label("unknown_q")
    ('|ψ₂|', 'unknown_q')
    """
    text = QUANTITY_LABELS.get(quantity, quantity).replace("$", "")
    for tex, uni in (("\\psi", "ψ"), ("\\phi", "φ"), ("\\theta", "θ"), ("_1", "₁"), ("_2", "₂")):
        text = text.replace(tex, uni)
    return text


def count_noun(n: int, singular: str, plural: str | None = None) -> str:
    """A count with its noun in the right number: ``"1 pass"``, ``"3 passes"``.

    Parameters
    ----------
    n : int
        The count.
    singular : str
        The noun for one.
    plural : str, optional
        The noun for any other count; ``singular + "s"`` when not given.

    Returns
    -------
    str
        The count (with thousands separators) and the noun.

    Examples
    --------
    >>> count_noun(1, "pass", "passes"), count_noun(0, "seed"), count_noun(12000, "sample")
    ('1 pass', '0 seeds', '12,000 samples')
    """
    return f"{n:,} {singular if n == 1 else (plural or singular + 's')}"


def and_list(items: Sequence[str]) -> str:
    """Items joined by commas and a last "and" (by semicolons when an item holds a comma).

    Parameters
    ----------
    items : sequence of str
        At least one item.

    Returns
    -------
    str
        The list as text.

    Examples
    --------
    >>> and_list(["a"]), and_list(["a", "b"]), and_list(["a", "b", "c"]), and_list(["a, b", "c"])
    ('a', 'a and b', 'a, b and c', 'a, b and c')
    """
    items = list(items)
    sep = "; " if any("," in i for i in items) else ", "
    return items[0] if len(items) == 1 else sep.join(items[:-1]) + " and " + items[-1]


def run_platforms_md(keys: Sequence[str], paper_keys: Sequence[str]) -> str:
    """Which platforms a run holds, said against the paper's: the words a chapter puts in brackets
    after "for each platform of this run" (Markdown, data keys in code quotes).

    It names the paper's platforms as included only when the run holds them, names the run's
    others, and says which of the paper's the run does not hold.

    Parameters
    ----------
    keys : sequence of str
        The run's platform keys (the chapter's ``platforms``, or a subset such as its surface
        vessels).
    paper_keys : sequence of str
        The paper's platform keys of the same kind (the default of the chapter's ``platforms``).

    Returns
    -------
    str
        The phrase; ``"none"`` for a run without platforms of that kind.

    Examples
    --------
    >>> run_platforms_md(["auv", "boat"], ["auv", "boat"])
    "the paper's `auv` and `boat`"
    >>> run_platforms_md(["rov9"], ["auv", "boat"])
    "`rov9`; the paper's `auv` and `boat` are not in this run"
    >>> run_platforms_md(["boat", "rov9"], ["auv", "boat"])
    "`boat` and `rov9`; the paper's `auv` is not in this run"
    >>> run_platforms_md(["auv", "boat", "rov9"], ["auv", "boat"])
    "the paper's `auv` and `boat`, and `rov9`"
    """
    def code(ks: Sequence[str]) -> str:
        return and_list([f"`{k}`" for k in ks])

    missing, added = [k for k in paper_keys if k not in keys], [k for k in keys if k not in paper_keys]
    if not keys:
        return "none" if not paper_keys else f"none; the paper's {code(paper_keys)} {'is' if len(paper_keys) == 1 else 'are'} not in this run"
    if not paper_keys:
        return code(keys)
    if missing:
        return f"{code(keys)}; the paper's {code(missing)} {'is' if len(missing) == 1 else 'are'} not in this run"
    return f"the paper's {code(paper_keys)}" + (f", and {code(added)}" if added else "")
