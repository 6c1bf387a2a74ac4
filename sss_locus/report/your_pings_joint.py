"""Sentences and captions of the joint adjustment on the your-pings page, from
:class:`~sss_locus.experiments.your_pings_joint.JointPings` (numbers in, prose out)."""

from __future__ import annotations

import numpy as np

from ..experiments.your_pings_joint import JUMP_ACROSS_M, TURN_DEG
from .text import fmt_sig

CLEAR_RATIO = 1.5
"""The mosaic's disagreement over the joint misfit from which the page calls the shape better."""


def joint_sentence(summary: dict) -> str:
    """What the joint adjustment did with the user's sightings: how many features and passes,
    how much better the lines agree than in the mosaic (from the user's residuals), what stays
    unobservable, and the sightings the robust loss down-weighted."""
    n, P = summary["n_adjusted"], summary["n_passes"]
    if n == 0:
        return (f"No feature was seen on two or more of the {P} passes, so there is no joint estimate: a range and a "
                "beam-plane angle from one pass leave a feature anywhere on a circle.")
    ratio = summary["shape_ratio"]
    text = (f"The joint adjustment estimated {n} features seen on two or more passes together with the navigation "
            f"corrections of the {P} passes"
            + ("" if summary["success"] else " (the solver stopped on its evaluation limit: treat it with care)")
            + f". In the mosaic, a feature's flat-seafloor positions lie a median {fmt_sig(summary['mosaic_disagreement_m'])} m "
            f"(RMS) from their mean: the disagreement between lines that the mosaic leaves in the map's shape. After "
            f"the adjustment, a feature's sightings miss it by a median {fmt_sig(summary['joint_misfit_m'])} m (RMS of "
            "range and beam-plane misfits)")
    if np.isfinite(ratio) and ratio >= CLEAR_RATIO:
        text += (f", {fmt_sig(ratio)} times less: the lines agree that much better about the map's shape (an optimistic "
                 "measure, since the fitted pass corrections absorb part of any error; the truth, where known, says "
                 "more).")
    else:
        text += (f": not clearly less than the mosaic's (less than {fmt_sig(CLEAR_RATIO)} times; the sightings may not "
                 "share a navigation error per pass that the adjustment could remove, or too few features tie the "
                 "passes together).")
    text += (f" What no range can see stays unobservable: a common shift of every pass and feature together, held "
             f"only by the navigation priors (1-sigma {fmt_sig(summary['common_shift_sigma_m'])} m per axis); the "
             "absolute positions are no better than the navigation, only their shape is.")
    k = summary["n_downweighted"]
    text += (f" The robust loss down-weighted {k} sighting{'s' if k != 1 else ''} (listed in the sightings file): "
             "check their data association." if k else " No sighting was down-weighted by the robust loss.")
    return text


def passes_caption(n_passes: int, names: str, platform_name: str, *, synthetic: bool) -> str:
    """Caption of the pass-correction table."""
    return (("Synthetic example (made by the project's simulator). " if synthetic else "")
            + f"Each of the {n_passes} passes of {names} ({platform_name}), found from the sightings (a new pass where "
            f"the heading turns by more than {fmt_sig(TURN_DEG)} deg or the track jumps more than "
            f"{fmt_sig(JUMP_ACROSS_M)} m across): its file lines, sightings and grid "
            "heading, and the navigation correction the joint adjustment estimated (true minus navigated: east and "
            "north offset, heading bias clockwise) with its 1-sigma. The offsets' common part is held by the priors "
            "only (see the text).")
