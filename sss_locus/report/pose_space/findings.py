"""Verdicts of the pose-space chapter, generated from a run's own numbers, for any platform.

One function per verdict (CONTRIBUTING.md, "One source per sentence"): it turns the chapter's
computed tables into one paragraph per platform, the paper's AUV and boat included, which the
notebook glues (as Markdown, :func:`findings_markdown`) into one untagged markdown cell. Every
number in them comes from the arguments; nothing is typed for a particular platform.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from sss_locus.report.common.text import NO_BATCH_CI, fmt_ci, fmt_sig, fmt_span, plain_label

RAW, NORM = "locus_length_m", "locus_length_normalized"
"""The two targets of :func:`~sss_locus.experiments.pose_space.stats.spearman_table`."""


def platform_title(name: str, key: str) -> str:
    """How a generated paragraph names its platform: ``"Example AUV (`my_auv`)"``.

    Parameters
    ----------
    name : str
        The platform's display name.
    key : str
        Its data key.

    Returns
    -------
    str
        The name with the key in code quotes (Markdown).
    """
    return f"{name} (`{key}`)"


def findings_markdown(paragraphs: Mapping[str, str]) -> str:
    """Paragraphs keyed by platform title as one Markdown list, one item per platform.

    Parameters
    ----------
    paragraphs : mapping of str to str
        Platform title (:func:`platform_title`) -> its paragraph; at least one.

    Returns
    -------
    str
        The Markdown list, one line per item.

    Raises
    ------
    ValueError
        When ``paragraphs`` is empty.

    Examples
    --------
    >>> findings_markdown({"A (`a`)": "It is long.", "B (`b`)": "It is short."})
    '- **A (`a`)**: It is long.\\n- **B (`b`)**: It is short.\\n'
    """
    if not paragraphs:
        raise ValueError("findings_markdown needs at least one paragraph")
    return "".join(f"- **{title}**: {text}\n" for title, text in paragraphs.items())


def fmt_rho(rho: float) -> str:
    """A rank correlation to two decimals, without a negative zero.

    Parameters
    ----------
    rho : float
        Spearman's rank correlation (−1 to 1).

    Returns
    -------
    str
        The text.

    Examples
    --------
    >>> fmt_rho(0.456), fmt_rho(-0.001), fmt_rho(-0.3)
    ('0.46', '0.00', '-0.30')
    """
    text = f"{rho:.2f}"
    return "0.00" if text == "-0.00" else text


def _direction(rho: float) -> str:
    return "longer loci where it is larger" if rho > 0 else "shorter loci where it is larger"


def ranked(rho: pd.DataFrame, target: str, top: int) -> list[tuple[str, float]]:
    """The ``top`` quantities with the largest ``|rho|`` for ``target``, largest first.

    Parameters
    ----------
    rho : pandas.DataFrame
        A Spearman table (``target``, ``quantity``, ``rho``).
    target : str
        :data:`RAW` or :data:`NORM`.
    top : int
        Number of quantities.

    Returns
    -------
    list of (str, float)
        ``(quantity, rho)`` pairs, ties in table order.
    """
    tab = rho[rho["target"] == target].copy()
    tab = tab.assign(size=tab["rho"].abs()).sort_values("size", ascending=False, kind="stable")
    return [(q, float(r)) for q, r in zip(tab["quantity"].head(top), tab["rho"].head(top))]


def _listing(pairs: list[tuple[str, float]]) -> str:
    parts = [f"{plain_label(q)} (ρ = {fmt_rho(r)})" for q, r in pairs]
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def drivers_finding(rho: pd.DataFrame, top: int = 3) -> str:
    """What drives locus length for one platform, from its Spearman table.

    ``rho``: :func:`~sss_locus.experiments.pose_space.stats.spearman_table` (columns ``target``,
    ``quantity``, ``rho``, ``ci_low``, ``ci_high``; ``attrs["dropped"]`` the constant columns left
    out). Names the ``top`` quantities by ``|rho|`` for the raw and the range-normalised length,
    the direction of the first, whether its interval is clear of the second's, and the weakest
    quantity; when normalising changes the first, the raw first's two ρ; the azimuths'
    normalised ρ; and that pitch is out of the ranking when its column was constant. The one
    source of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    rho : pandas.DataFrame
        The Spearman table, as above.
    top : int
        Number of quantities named per target (at least 1).

    Returns
    -------
    str
        The paragraph.

    Raises
    ------
    ValueError
        When ``top < 1`` or ``rho`` has no rows of a target.
    """
    if top < 1:
        raise ValueError(f"top must be >= 1; got {top}")
    out = []
    for target, what in ((RAW, "The raw locus length"), (NORM, "Divided by the mean of the two ranges, the length")):
        pairs = ranked(rho, target, top)
        if not pairs:
            raise ValueError(f"rho has no rows for target {target!r}")
        tab = rho[rho["target"] == target].set_index("quantity")
        first, r1 = pairs[0]
        text = f"{what} is ranked first by {plain_label(first)} (ρ = {fmt_rho(r1)}, {_direction(r1)}"
        if len(pairs) > 1:
            a, b = tab.loc[first], tab.loc[pairs[1][0]]
            clear = (min(abs(a.ci_low), abs(a.ci_high)) > max(abs(b.ci_low), abs(b.ci_high))
                     and a.ci_low * a.ci_high > 0)
            text += ("; its 95 % interval is clear of the runner-up's" if clear
                     else "; its 95 % interval overlaps the runner-up's, so the order of the first two is not settled")
            text += f"), then by {_listing(pairs[1:])}"
        else:
            text += ")"
        weakest = tab["rho"].abs().idxmin()
        out.append(text + f"; the weakest is {plain_label(weakest)} (ρ = {fmt_rho(tab.loc[weakest, 'rho'])}).")
    raw, norm = rho[rho["target"] == RAW].set_index("quantity"), rho[rho["target"] == NORM].set_index("quantity")
    first = ranked(rho, RAW, 1)[0][0]
    if first != ranked(rho, NORM, 1)[0][0] and first in norm.index:
        out.append(f"Normalising moves {plain_label(first)} from ρ = {fmt_rho(raw.loc[first, 'rho'])} to "
                   f"{fmt_rho(norm.loc[first, 'rho'])}.")
    azimuths = [q for q in ("azimuth1_deg", "azimuth2_deg") if q in norm.index]
    if azimuths:
        out.append("The azimuths' normalised ρ: " + ", ".join(f"{plain_label(q)} {fmt_rho(norm.loc[q, 'rho'])}"
                                                               for q in azimuths) + ".")
    dropped = [q for q in rho.attrs.get("dropped", ()) if "pitch" in q]
    if dropped:
        out.append("Vehicle 2's pitch is constant here (the platform does not pitch), so it has no place in the ranking.")
    return " ".join(out)


def _ci(m: Mapping[str, float], name: str, percent: bool = False) -> str:
    return fmt_ci(m[name], m[f"{name}_ci_low"], m[f"{name}_ci_high"], percent=percent, no_ci=NO_BATCH_CI)


def _span(m: Mapping[str, float], name: str) -> str:
    return fmt_span(m[f"{name}_lo_deg"], m[f"{name}_hi_deg"])


def panels_finding(metrics: Mapping[str, float], azimuth_map: pd.DataFrame | None = None) -> str:
    """Where long loci occur for one platform: the heatmap panels read with their numbers; the
    one source of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    metrics : mapping
        :func:`~sss_locus.experiments.pose_space.claims.claim_metrics` of the platform (ratios and
        shares with their intervals, the yaw peaks and panel (e)'s peaks as the spans of their
        peak regions).
    azimuth_map : pandas.DataFrame, optional
        The azimuth heatmap (panel b: ``x_mid``, ``y_mid``, ``masked``): when the peak bin is the
        shown bin of smallest azimuth on both axes, the sentence says it sits at the upper edge of
        both fans (positive azimuth points down).

    Returns
    -------
    str
        One paragraph, "longer far out", "longer with the feature near the centre of both beams"
        and "at the upper edge of both fans" computed from the numbers.
    """
    m = metrics
    edge = ""
    if azimuth_map is not None:
        shown = azimuth_map[~azimuth_map["masked"]]
        if (np.isclose(m["azimuth_peak_theta1_deg"], shown["x_mid"].min())
                and np.isclose(m["azimuth_peak_theta2_deg"], shown["y_mid"].min())):
            edge = ", at the upper edge of both fans, the look direction closest to horizontal"
    far = m["range_far_over_near_ratio"]
    el = m["elevation_centre_over_corner_ratio"]
    return (
        f"with both ranges above half the maximum the median length is {_ci(m, 'range_far_over_near_ratio')} times "
        f"that with both below ({'longer far out' if far > 1 else 'shorter far out'}); the largest median over the "
        f"two azimuths sits at θ₁, θ₂ ≈ {m['azimuth_peak_theta1_deg']:.0f}°, {m['azimuth_peak_theta2_deg']:.0f}° (bin "
        f"centres, {m['azimuth_peak_count']:,.0f} samples in that bin{edge}); at the centre of the elevation square the "
        f"median is {_ci(m, 'elevation_centre_over_corner_ratio')} times the corners' "
        f"({'longer' if el > 1 else 'shorter'} with the feature near the centre of both beams); over vehicle 2's "
        f"yaw the median peaks at {_span(m, 'yaw_peak_neg')} and {_span(m, 'yaw_peak_pos')} (the bins whose 95 % "
        f"interval reaches that of each half's largest median), and is {_ci(m, 'yaw_near0_over_peak_ratio')} of the peak near "
        f"yaw 0 (parallel headings) and {_ci(m, 'yaw_near180_over_peak_ratio')} near ±180° (reciprocal); over "
        f"vehicle 2's yaw and azimuth (panel e) the largest medians sit at yaw {_span(m, 'azimuth2_yaw_peak_neg_yaw')} "
        f"with θ₂ {_span(m, 'azimuth2_yaw_peak_neg_theta2')} and at yaw {_span(m, 'azimuth2_yaw_peak_pos_yaw')} with "
        f"θ₂ {_span(m, 'azimuth2_yaw_peak_pos_theta2')}. "
        f"{_ci(m, 'multi_arc_fraction', percent=True)} of its port–port loci are fragmented (more than one arc).")


def yaw0_text(row: Mapping) -> str:
    """The yaw-0 dip of one modelling-choice row with its interval, or why it has none.

    Parameters
    ----------
    row : mapping
        A row of :func:`~sss_locus.report.pose_space.figures.check_row`: ``"yaw 0 / peak"`` and
        ``"yaw 0 / peak CI"`` (the interval's ends, or the words of a missing interval).

    Returns
    -------
    str
        E.g. ``"0.27 (95 % CI 0.050–0.48)"``, or the ratio with :data:`~sss_locus.report.common.text.NO_BATCH_CI`.

    >>> yaw0_text({"yaw 0 / peak": 0.46, "yaw 0 / peak CI": "none: too few samples"})
    '0.46 (no 95 % CI: too few samples, some replicate batches have no sample where it is measured)'
    """
    ci = row["yaw 0 / peak CI"]
    lo, hi = ci if isinstance(ci, tuple) else (float("nan"), float("nan"))
    return fmt_ci(row["yaw 0 / peak"], lo, hi, no_ci=NO_BATCH_CI)


def choices_finding(main: Mapping[str, float], checks: pd.DataFrame, key: str,
                    above: tuple[float, float] | None = None) -> str:
    """How the open modelling choices change one platform's headline numbers: the one source of
    this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    main : mapping
        :func:`~sss_locus.experiments.pose_space.claims.claim_metrics` of the main run.
    checks : pandas.DataFrame
        The modelling-choice table (rows of :func:`~sss_locus.report.pose_space.figures.check_row`,
        ``run`` labels starting with ``key + ", "``).
    key : str
        The platform's data key.
    above : (float, float), optional
        For a platform whose depth varies: the share of samples of the earlier depth rule with
        vehicle 2 above the sea surface, and vehicle 1's shallowest depth (m).

    Returns
    -------
    str
        Per check run the top normalised quantity, misalignment's ρ, the hotspot's peak region
        (and whether it holds equal azimuths) and the yaw-0 dip with its interval; with ``above``,
        how often the earlier rule put vehicle 2 above the surface and whether the top normalised
        quantity "is the same" or "differs" without those poses.
    """
    rows = checks[checks["run"].str.startswith(f"{key}, ")]
    if rows.empty:
        raise ValueError(f"checks has no run of platform {key!r}")
    parts = []
    for row in rows.to_dict("records"):
        (a1, b1), (a2, b2) = row["hotspot region theta1 (deg)"], row["hotspot region theta2 (deg)"]
        parts.append(f"{row['run'][len(key) + 2:]}: {plain_label(row['top normalised'])} first "
                     f"(misalignment ρ {fmt_rho(row['rho misalignment (norm.)'])}; hotspot region θ₁ {fmt_span(a1, b1)}, "
                     f"θ₂ {fmt_span(a2, b2)}, {'with' if row['hotspot region at equal azimuths'] else 'without'} equal "
                     f"azimuths; median near yaw 0 {yaw0_text(row)} of the peak)")
    text = (f"main run: {plain_label(str(main['top_norm']))} first (misalignment ρ "
            f"{fmt_rho(main['norm_elevation_misalignment_deg_rho'])}, hotspot "
            f"({main['azimuth_peak_theta1_deg']:.0f}°, {main['azimuth_peak_theta2_deg']:.0f}°)); "
            + "; ".join(parts) + ".")
    if above is None:
        return text
    earlier = rows[rows["run"].str.endswith("vehicle 2 may be above the surface")]
    same = len(earlier) and earlier["top normalised"].iloc[0] == plain_label(str(main["top_norm"]))
    return (text + f" The earlier depth rule (the two depths' difference alone) puts vehicle 2 above the sea surface "
            f"in {100 * above[0]:.0f} % of the samples with vehicle 1 at its shallowest {above[1]:g} m, a physically "
            "impossible pose; the top normalised quantity " + ("is the same" if same else "differs")
            + " with and without those poses.")


def reading_finding(effect: pd.DataFrame) -> str:
    """How the reading of max(ψ₁, ψ₂) changes one platform's ranking of elevation misalignment.

    ``effect``: :func:`~sss_locus.experiments.pose_space.choices.reading_effect` (columns ``reading``,
    ``target``, ``rho``, ``rank``, ``top``).

    Parameters
    ----------
    effect : pandas.DataFrame
        The reading effect table, as above, with the ``magnitude`` and ``signed`` rows of the
        normalised target (``target == "norm"``).

    Returns
    -------
    str
        The sentence.

    Raises
    ------
    ValueError
        When a reading is missing.
    """
    norm = effect[effect["target"] == "norm"].set_index("reading")
    if not {"magnitude", "signed"} <= set(norm.index):
        raise ValueError("effect needs the 'magnitude' and 'signed' readings of the normalised length")
    mag, sig = norm.loc["magnitude"], norm.loc["signed"]
    same = int(mag["rank"]) == int(sig["rank"])
    return (f"the normalised ρ of elevation misalignment is {fmt_rho(mag['rho'])} (rank {int(mag['rank'])}) "
            f"read as magnitudes and {fmt_rho(sig['rho'])} (rank {int(sig['rank'])}; "
            f"{plain_label(str(sig['top']))} first) read as signed angles: "
            + ("the reading does not change its rank." if same else "the reading changes its rank."))


def fan_finding(level: Mapping[str, float], pitched: list[Mapping[str, float]]) -> str:
    """The part of one platform's fan the feature-below rule removes
    (:func:`~sss_locus.experiments.pose_space.choices.fan_share_removed`, level and pitched).

    Parameters
    ----------
    level : mapping of str to float
        The level sensor's ``share`` removed (0–1) and ``theta_min_deg`` (deg).
    pitched : list of mapping of str to float
        The same for pitched sensors (each with ``share``); may be empty.

    Returns
    -------
    str
        The sentence(s); shares in percent, azimuths in degrees.
    """
    worst = max([level["share"]] + [p["share"] for p in pitched])
    text = f"the rule removes {100 * level['share']:.0f} % of the fan of a level sensor"
    if level["share"] > 0:
        text += f" (azimuths below {level['theta_min_deg']:.0f}° at zero elevation, the part above the horizontal)"
    else:
        text += " (the fan does not reach above the horizontal)"
    if pitched:
        text += f", at most {100 * worst:.0f} % for a pitched vehicle 2"
    if level["share"] > 0:
        text += (f". Its azimuth heatmap therefore has no samples left of θ₁ ≈ {level['theta_min_deg']:.0f}°, and its "
                 "bins at that edge are partly empty")
    return text + "."


def hotspot_finding(check: Mapping[str, float]) -> str:
    """The azimuth hotspot of one platform re-sampled
    (:func:`~sss_locus.experiments.pose_space.choices.hotspot_check`).

    Parameters
    ----------
    check : mapping of str to float
        The hotspot check: bin centres ``x_mid``/``y_mid`` and ``runner_up_x_mid``/``_y_mid``
        (deg), counts, medians and targeted interval (m), ``still_peak`` and optionally the
        runner-up's interval.

    Returns
    -------
    str
        The sentence; lengths in m, azimuths in degrees.
    """
    c = check
    verdict = ("its targeted interval lies above the runner-up, so the bin is still the peak" if c["still_peak"]
               else "its targeted interval does not lie above the runner-up, so the peak bin is not settled")
    runner = (fmt_ci(c["runner_up_median"], c["runner_up_ci_low"], c["runner_up_ci_high"], no_ci=NO_BATCH_CI).replace(" (", " m (", 1)
              .replace(")", " m)") if "runner_up_ci_low" in c else f"{fmt_sig(c['runner_up_median'], 2)} m")
    return (f"the peak bin ({c['x_mid']:.0f}°, {c['y_mid']:.0f}°) holds {c['count']:,.0f} samples of the main run "
            f"(median {fmt_sig(c['median'], 2)} m); {c['target_count']:,.0f} targeted samples give "
            f"{fmt_sig(c['target_median'], 2)} m (95 % CI {fmt_sig(c['target_ci_low'], 3)}–"
            f"{fmt_sig(c['target_ci_high'], 3)} m) against the runner-up's {runner} "
            f"at ({c['runner_up_x_mid']:.0f}°, {c['runner_up_y_mid']:.0f}°): {verdict}.")


def pose_summary(rho: pd.DataFrame, metrics: Mapping[str, float]) -> str:
    """One sentence per platform for the chapter's summary.

    Parameters
    ----------
    rho : pandas.DataFrame
        The platform's Spearman table (``target``, ``quantity``, ``rho``).
    metrics : mapping of str to float
        Its claim metrics (the azimuth peak and the yaw peaks' spans, deg).

    Returns
    -------
    str
        The sentence, without a capital or subject.
    """
    (raw, _), (norm, _) = ranked(rho, RAW, 1)[0], ranked(rho, NORM, 1)[0]
    return (f"the raw locus length ranks {plain_label(raw)} first and the range-normalised length "
            f"{plain_label(norm)}; the longest loci sit at azimuths θ₁, θ₂ ≈ {metrics['azimuth_peak_theta1_deg']:.0f}°, "
            f"{metrics['azimuth_peak_theta2_deg']:.0f}° and at vehicle-2 yaws of {_span(metrics, 'yaw_peak_neg')} "
            f"and {_span(metrics, 'yaw_peak_pos')}.")
