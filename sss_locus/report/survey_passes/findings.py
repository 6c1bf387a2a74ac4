"""Verdict sentences generated from computed flags, for any platform (prose only).

A chapter and the claims page must never state different verdicts on one claim. So a verdict is
never typed: one function here reads the computed flags (from :mod:`sss_locus.experiments.survey_passes.verdicts`)
and returns, in one dict of glue texts,

- ``<prefix>-<claim>-finding``: the sentence the chapter prints, naming every platform and
  offset model where the test fails and those where it holds;
- ``<prefix>-<claim>-finding-verdict``: the verdict word of the claims page's row
  (:func:`verdict_word` of the same flags);
- per curve, ``<prefix>-<platform>-<model tag>-<claim>``: what the test found for that curve.

The chapter glues the ``-finding`` key and the claims page the ``-finding-verdict`` key of the same
notebook (``tests/pipeline/book/test_claims_page.py`` checks that every ``-finding`` a chapter prints has its
verdict on the claims page and that such a row types no verdict of its own). Platforms are named
by their data key, so the sentences read the same for a user's platform as for the paper's.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import pandas as pd

from sss_locus.experiments.datamodel.datadoc import label_key
from sss_locus.report.survey_passes.figures import model_tag
from sss_locus.report.common.text import fmt_sig

VERDICT_WORDS = ("Reproduced", "Partly", "Not reproduced")
"""The claims page's verdict words, for a test that holds everywhere, somewhere, nowhere."""


def verdict_word(flags: Iterable[bool], words: tuple[str, str, str] = VERDICT_WORDS) -> str:
    """``"Reproduced"`` if every flag holds, ``"Not reproduced"`` if none does, else ``"Partly"``
    (``words``: the three words to use instead, in that order).

    Parameters
    ----------
    flags : iterable of bool
        The verdicts of the claim's cases; at least one.
    words : (str, str, str)
        The words for all, some and none holding.

    Returns
    -------
    str
        One of ``words``.

    Raises
    ------
    ValueError
        When ``flags`` is empty.

    Examples
    --------
    >>> verdict_word([True, True]), verdict_word([True, False]), verdict_word([False])
    ('Reproduced', 'Partly', 'Not reproduced')
    """
    flags = [bool(f) for f in flags]
    if not flags:
        raise ValueError("verdict_word needs at least one flag")
    return words[0] if all(flags) else words[2] if not any(flags) else words[1]


def preferred_span(bands: pd.DataFrame, angle_deg: float) -> str:
    """The preferred band of :func:`~sss_locus.experiments.survey_passes.planning.planning_bands` that holds
    ``angle_deg``, as text (``"0–4°"``, ``"180°"``), or ``"none"``.

    Parameters
    ----------
    bands : pandas.DataFrame
        The bands: ``kind``, ``lo_deg``, ``hi_deg`` (deg).
    angle_deg : float
        The crossing angle (deg).

    Returns
    -------
    str
        The band in whole degrees, or ``"none"``.
    """
    hit = bands[(bands["kind"] == "prefer") & (bands["lo_deg"] <= angle_deg + 1e-9)
                & (bands["hi_deg"] >= angle_deg - 1e-9)]
    if not len(hit):
        return "none"
    r = hit.iloc[0]
    return f"{r.lo_deg:.0f}°" if r.lo_deg == r.hi_deg else f"{r.lo_deg:.0f}–{r.hi_deg:.0f}°"


def _curve_label(key: str, spec_label: str) -> str:
    return f"{key}, {spec_label} offsets" if spec_label == "independent" else f"{key}, {spec_label}"


def _near_end_text(check: pd.DataFrame, bands: pd.DataFrame, window_deg: float) -> tuple[bool, str]:
    """Whether every angle near both ends is preferred, and what the test found (one clause)."""
    failed = []
    for r in check.sort_values("end_deg").itertuples():
        if r.all_preferred:
            continue
        span = preferred_span(bands, r.end_deg)
        text = (f"of the angles within {window_deg:g}° of {r.end_deg:.0f}° only {span} is preferred" if span != "none"
                else f"{r.end_deg:.0f}° itself is not preferred")
        if r.n_angles:
            text += (f" (median locus length {fmt_sig(r.worst_median, 3)} m at {r.worst_angle_deg:.0f}° "
                     f"against {fmt_sig(r.end_median, 3)} m at {r.end_deg:.0f}°)")
        failed.append(text)
    if not failed:
        return True, f"every angle within {window_deg:g}° of 0° and of 180° is preferred"
    return False, "; ".join(failed)


def near_end_findings(prefix: str, checks: Mapping[tuple[str, str], pd.DataFrame],
                      bands: Mapping[tuple[str, str], pd.DataFrame],
                      model_labels: Mapping[str, str], window_deg: float) -> dict[str, str]:
    """The paper's "prefer a near-repeat or a near-anti-parallel pass", from computed flags.

    Parameters
    ----------
    prefix : str
        Glue-key prefix of the chapter (``"pl"``).
    checks : mapping (platform key, offset-model spec) -> DataFrame
        :func:`~sss_locus.experiments.survey_passes.verdicts.near_end_check` of each curve (its
        ``all_preferred`` flags decide).
    bands : mapping (platform key, offset-model spec) -> DataFrame
        :func:`~sss_locus.experiments.survey_passes.planning.planning_bands` of the same curves.
    model_labels : mapping spec -> str
        Display label of each offset model (``OffsetModel.label``).
    window_deg : float
        The window ``checks`` were computed with (for the sentence).

    Returns
    -------
    dict of str
        ``<prefix>-near-ends-finding``, ``<prefix>-near-ends-finding-verdict`` and, per curve,
        ``<prefix>-<platform>-<model tag>-near-ends`` (module docstring).
    """
    if not checks:
        raise ValueError("near_end_findings needs at least one curve")
    out, held, failed = {}, [], []
    for (key, spec), check in checks.items():
        ok, text = _near_end_text(check, bands[(key, spec)], window_deg)
        out[f"{prefix}-{label_key(key)}-{model_tag(spec)}-near-ends"] = text
        (held if ok else failed).append((_curve_label(key, model_labels[spec]), text))
    out[f"{prefix}-near-ends-finding-verdict"] = verdict_word([True] * len(held) + [False] * len(failed))
    where = f"within {window_deg:g}° of a repeat (0°) or of an anti-parallel pass (180°)"
    if not failed:
        out[f"{prefix}-near-ends-finding"] = (f"Every crossing angle {where} falls in the preferred bands, "
                                             f"for every platform and offset model shown.")
        return out
    sentence = (f"A pass {where} is not preferred everywhere: for "
                + "; for ".join(f"{lab}, {text}" for lab, text in failed) + ".")
    if held:
        sentence += " Every angle near both ends is preferred for " + "; ".join(lab for lab, _ in held) + "."
    out[f"{prefix}-near-ends-finding"] = sentence
    return out


