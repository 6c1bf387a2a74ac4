"""Sentences and captions of the joint adjustment on the your-pings page, from
:class:`~sss_locus.experiments.your_pings.joint.JointPings` (numbers in, prose out)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.your_pings.joint import JUMP_ACROSS_M, TURN_DEG
from sss_locus.report.common.text import count_noun, fmt_sig

MANY_FLAGGED = 0.1
"""Above this share of flagged sightings the page questions the noise model, not the matches."""
CLEAR_RATIO = 1.5
"""The mosaic's disagreement over the joint misfit from which the page calls the shape better."""


def joint_sentence(summary: dict) -> str:
    """What the joint adjustment did with the user's sightings: how many features and passes,
    how much better the lines agree than in the mosaic (from the user's residuals), what stays
    unobservable, and the sightings the robust loss down-weighted.

    Parameters
    ----------
    summary : dict
        The joint adjustment's summary: ``n_adjusted``, ``n_passes``, ``success``,
        ``shape_ratio``, ``mosaic_disagreement_m``, ``joint_misfit_m``, ``common_shift_sigma_m``
        (m), ``n_downweighted``, ``n_gated``, ``n_used``, ``ping_position_sigma_m`` (m) and
        ``ping_attitude_sigma_deg`` (deg).

    Returns
    -------
    str
        The paragraph (Markdown); distances in m.
    """
    n, P = summary["n_adjusted"], summary["n_passes"]
    if n == 0:
        seen = ("The sightings form one pass, so no feature was seen on two passes" if P == 1 else
                f"No feature was seen on two or more of the {P} passes")
        return (f"{seen}, so there is no joint estimate: a range and a "
                "beam-plane angle from one pass leave a feature anywhere on a circle.")
    ratio = summary["shape_ratio"]
    text = (f"The joint adjustment estimated {count_noun(n, 'feature')} seen on two or more passes together with the navigation "
            f"corrections of the {P} passes"
            + ("" if summary["success"] else " (the solver stopped on its evaluation limit: treat it with care)")
            + f". In the mosaic, a feature's flat-seafloor positions lie a median {fmt_sig(summary['mosaic_disagreement_m'])} m "
            f"(RMS) from their mean: the disagreement between lines that the mosaic leaves in the map's shape. After "
            f"the adjustment, a feature's sightings miss it by a median {fmt_sig(summary['joint_misfit_m'])} m (RMS of "
            "range and beam-plane misfits)")
    if np.isfinite(ratio) and ratio >= CLEAR_RATIO:
        text += (f": the mosaic's disagreement divided by {fmt_sig(ratio)}. The two are different measures, a spread of positions and a fit's "
                 "misfit, and the pass corrections were fitted to these same sightings, which absorbs part of any "
                 "error: the ratio says the lines agree much better about the map's shape, and it is optimistic about "
                 "by how much; the errors against the truth, where it is known, say more.")
    else:
        text += (f": not clearly smaller than the mosaic's disagreement (the ratio of the two is under "
                 f"{fmt_sig(CLEAR_RATIO)}; the sightings may not share a navigation error per pass that the adjustment "
                 "could remove, or too few features tie the passes together).")
    text += (f" What no range can see stays unobservable: a common shift of every pass and feature together, held "
             f"only by the navigation priors (1-sigma {fmt_sig(summary['common_shift_sigma_m'])} m per axis); the "
             "absolute positions are no better than the navigation, only their shape is.")
    k, g = summary["n_downweighted"], summary["n_gated"]
    text += (f" {k} sighting{'s' if k != 1 else ''} {'were' if k != 1 else 'was'} left out or down-weighted as likely "
             f"wrong matches ({g} missing their feature by more than the gate, the rest by the robust loss; column "
             "`downweighted` of the sightings file): check their data association." if k
             else " No sighting was left out or down-weighted as a likely wrong match.")
    if k > MANY_FLAGGED * max(summary["n_used"], 1):
        text += (f" That is more than {fmt_sig(100 * MANY_FLAGGED)} % of the sightings used: more likely the noise "
                 "model than the matches is wrong, e.g. a per-ping navigation noise larger than the "
                 f"{fmt_sig(summary['ping_position_sigma_m'])} m and {fmt_sig(summary['ping_attitude_sigma_deg'])} deg "
                 "assumed, or navigation errors that are not shared by the pings of a pass.")
    return text


def passes_caption(n_passes: int, names: str, platform_name: str, *, synthetic: bool) -> str:
    """Caption of the pass-correction table.

    Parameters
    ----------
    n_passes : int
        Number of passes found.
    names : str
        The sightings files, as shown.
    platform_name : str
        The platform's display name.
    synthetic : bool
        Whether the data is the synthetic worked example.

    Returns
    -------
    str
        The caption.
    """
    return (("Synthetic example (made by the project's simulator). " if synthetic else "")
            + (f"Each of the {n_passes} passes" if n_passes != 1 else "The one pass")
            + f" of {names} ({platform_name}), found from the sightings (a new pass where "
            f"the heading turns by more than {fmt_sig(TURN_DEG)} deg or the track jumps more than "
            f"{fmt_sig(JUMP_ACROSS_M)} m across): its file lines, sightings and grid "
            "heading, and the navigation correction the joint adjustment estimated (true minus navigated: east and "
            "north offset, heading bias clockwise) with its 1-sigma. "
            + ("The offsets' common part is held by the priors only (see the text)." if n_passes != 1 else
               "With one pass, its offsets are the common shift of the whole survey, which no range can see: they "
               "are held by the priors only (see the text)."))


def passes_shown(passes: pd.DataFrame) -> pd.DataFrame:
    """The pass-correction table as a reader reads it: one row a pass, each correction with its 1-sigma.

    Parameters
    ----------
    passes : pandas.DataFrame
        :attr:`~sss_locus.experiments.your_pings.joint.JointPings.passes`: ``pass``, ``source``,
        ``first_line``, ``last_line``, ``n_sightings``, ``heading_deg`` and the corrections
        ``offset_east_m``, ``offset_north_m`` (m), ``heading_bias_deg`` (deg), each with its
        ``..._sigma_...``.

    Returns
    -------
    pandas.DataFrame
        Indexed by ``pass``: ``source``, ``lines`` (``"first–last"``), ``n_sightings``,
        ``heading_deg`` and, as text ``"value ± sigma"``, ``offset_east_m``, ``offset_north_m``
        and ``heading_bias_deg``.

    >>> p = pd.DataFrame({"pass": [0], "source": ["a.csv"], "first_line": [3], "last_line": [9],
    ...     "n_sightings": [5], "heading_deg": [90.0], "offset_east_m": [1.234], "offset_east_sigma_m": [0.5],
    ...     "offset_north_m": [-0.2], "offset_north_sigma_m": [0.51], "heading_bias_deg": [0.8],
    ...     "heading_bias_sigma_deg": [0.3]})
    >>> [str(v) for v in passes_shown(p).iloc[0]]
    ['a.csv', '3–9', '5', '90.0', '1.2 ± 0.50', '-0.20 ± 0.51', '0.80 ± 0.30']
    """
    def pm(value, sigma):
        return [f"{fmt_sig(v, 2)} ± {fmt_sig(s, 2)}" for v, s in zip(passes[value], passes[sigma])]

    return pd.DataFrame({"pass": passes["pass"], "source": passes["source"],
                         "lines": [f"{a}–{b}" for a, b in zip(passes["first_line"], passes["last_line"])],
                         "n_sightings": passes["n_sightings"], "heading_deg": passes["heading_deg"],
                         "offset_east_m": pm("offset_east_m", "offset_east_sigma_m"),
                         "offset_north_m": pm("offset_north_m", "offset_north_sigma_m"),
                         "heading_bias_deg": pm("heading_bias_deg", "heading_bias_sigma_deg")}).set_index("pass")
