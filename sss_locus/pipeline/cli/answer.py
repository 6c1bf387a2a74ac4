"""``sss-locus answer``: the planning answer for one platform in the terminal, without a book.

For a platform of the shipped data or of ``--data`` files, prints the crossing angles to prefer
and to avoid between two straight passes (the planning chapter's bands,
:func:`sss_locus.experiments.survey_passes.planning.planning_bands`) for each of the planning chapter's offset
models, each with the way of flying it stands for (:data:`HOW_YOU_FLY`; ``--offsets`` picks one),
and the quantities that drive locus length most, named in words (:data:`QUANTITY_WORDS`; the
pose-space chapter's Spearman table, :func:`sss_locus.experiments.pose_space.stats.spearman_table`),
computed exactly as those chapters compute them, with their ``quick`` profile by default (a
minute or less; ``--profile book`` for the book's sample sizes), and names the data it used: the
data entries with their SHA-256 and the files that define them. Results are cached like the
chapters' (a later ``sss-locus book`` reuses them, and the other way round).
"""

from __future__ import annotations

import time
from typing import Any

import pandas as pd

from sss_locus.experiments.stats.significant import round_sig
from sss_locus.pipeline.run import budgets
from sss_locus.pipeline.run.registry import ParameterError, get_entry

#: The chapters whose computations the answer repeats, and the parameter naming the platform.
PLANNING, POSE_SPACE = "planning", "pose_space"

#: ``--offsets``: which of the planning chapter's offset models to answer for (readable names).
OFFSET_CHOICES = ("both", "independent", "matched")

#: Each offset model's kind in one plain sentence: which way of flying its bands apply to.
HOW_YOU_FLY = {
    "independent": "if you fly survey lines (a lawnmower pattern with cross-lines) without steering for the "
                   "feature, each pass sees it wherever it falls in its swath: read these bands",
    "matched": "if you go back to a feature you have seen and steer pass 2 to see it again at about the same "
               "distance across the swath, on the same side of the vehicle: read these bands",
}

#: The pose-space quantities (:data:`sss_locus.experiments.pose_space.stats.CANDIDATES`) in plain words,
#: with the paper's symbol, for a terminal.
QUANTITY_WORDS = {
    "r1_m": "range to the feature, view 1 (r1, m)",
    "r2_m": "range to the feature, view 2 (r2, m)",
    "mean_range_m": "mean range of the two views (m)",
    "baseline_m": "distance between the two sonars (baseline |t|, m)",
    "elevation_misalignment_deg": "elevation misalignment of the two views (deg)",
    "abs_psi1_deg": "sonar 2 above/below sonar 1's fan plane (|psi1|, deg)",
    "abs_psi2_deg": "sonar 1 above/below sonar 2's fan plane (|psi2|, deg)",
    "azimuth1_deg": "where the feature is across fan 1 (azimuth theta1, deg)",
    "azimuth2_deg": "where the feature is across fan 2 (azimuth theta2, deg)",
    "abs_elevation1_deg": "feature off beam 1's centre, along-track (|phi1|, deg)",
    "abs_elevation2_deg": "feature off beam 2's centre, along-track (|phi2|, deg)",
    "abs_yaw2_deg": "heading of vehicle 2 relative to vehicle 1 (|yaw|, deg)",
    "pitch2_deg": "pitch of vehicle 2, nose-up positive (deg)",
    "abs_pitch2_deg": "pitch of vehicle 2, either way (|pitch|, deg)",
}


def offset_specs(planning: dict[str, Any], offsets: str = "both") -> list[tuple[str, int]]:
    """The planning parameters' offset models (spec, pass pairs per angle) that ``offsets``
    (one of :data:`OFFSET_CHOICES`) selects: ``"both"`` every one, else those of that kind."""
    if offsets not in OFFSET_CHOICES:
        raise ValueError(f"--offsets must be one of {list(OFFSET_CHOICES)}; got {offsets!r}")
    pairs = list(zip(planning["offset_models"], planning["n_per_angle"]))
    chosen = [(s, n) for s, n in pairs if offsets == "both" or s.split(":")[0] == offsets]
    if not chosen:
        raise ValueError(f"--offsets {offsets}: none of the offset_models {planning['offset_models']} is {offsets}")
    return chosen


def _parameters(profile: str, key: str, pairs: list[list[str]]) -> tuple[dict[str, Any], dict[str, Any]]:
    """The planning and pose-space chapters' parameters of ``profile`` for platform ``key``, with
    the ``-p NAME VALUE`` overrides of the parameters each declares (validated like a run's)."""
    entries = [get_entry(PLANNING), get_entry(POSE_SPACE)]
    overrides = {name: value for name, value in pairs if name != "platform"}
    unknown = set(overrides) - {n for e in entries for n in e.parameters()} | (
        {"platforms", "data_files", "data_set"} & set(overrides))
    if unknown:
        raise ParameterError(f"answer: unknown parameter(s) {sorted(unknown)}; use -p platform KEY and the "
                             f"parameters of `sss-locus params {PLANNING}` / `{POSE_SPACE}`")
    out = []
    for entry in entries:
        mine = {n: v for n, v in overrides.items() if n in entry.parameters()}
        mine["platforms"] = f'["{key}"]'
        out.append(entry.resolve(profile, mine, from_text=True))
        budgets.check_parameters(out[-1])
    return out[0], out[1]


def compute(key: str, planning: dict[str, Any], pose: dict[str, Any], offsets: str = "both") -> dict[str, Any]:
    """Bands and Spearman table of platform ``key``, as the planning and pose-space chapters
    compute them with these parameters: ``bands``, a list of ``(offset model, pass pairs per
    angle, bands)``, one per offset model of ``planning`` that ``offsets`` selects
    (:func:`offset_specs`)."""
    from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.survey_passes.planning import crossing_angle_curve, crossing_angle_grid, planning_bands
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space
    from sss_locus.experiments.pose_space.stats import spearman_table, with_derived
    from sss_locus.experiments.survey_passes.study import simulate_passes
    from sss_locus.pipeline.run.cache import cached

    platform = load_platform(key)
    grid = crossing_angle_grid(planning["fine_step_deg"], 40.0, planning["coarse_step_deg"])
    bands = []
    for spec, n in offset_specs(planning, offsets):
        model = OffsetModel.parse(spec)
        curve = crossing_angle_curve(platform, load_envelope(key), model, crossing_angles_deg=grid,
                                     n_per_angle=n, seed=planning["seed"],
                                     n_resamples=planning["n_resamples"], simulate=cached(simulate_passes))
        bands.append((model, n, planning_bands(curve.curve, prefer_below=planning["prefer_below"],
                                               avoid_above=planning["avoid_above"])))
    limit = pose["pitch_max_deg"] if pose["pitch_max_deg"] >= 0 else None
    spec = PoseSpaceSpec(platform, profile=pose["profile"], feature_distribution=pose["feature_distribution"],
                         pitch_max_deg=limit, vehicle_depths=pose["vehicle_depths"])
    table = with_derived(cached(sample_pose_space)(spec, pose["n_samples"], pose["seed"]),
                         misalignment=pose["misalignment_reading"])
    rho = spearman_table(table, n_batches=pose["n_batches"])
    return {"platform": platform, "grid": grid, "bands": bands, "rho": rho, "n_pose": len(table)}


def answer(key: str, profile: str = "quick", pairs: list[list[str]] | None = None, top: int = 5,
           log=print, offsets: str = "both") -> dict[str, Any]:
    """Compute and print the answer for platform ``key`` (the data inputs must be active,
    :func:`sss_locus.experiments.datamodel.userdata.use`); return what :func:`compute` returned plus the
    data record (``data``, :func:`sss_locus.experiments.datamodel.userdata.figure_record`)."""
    from sss_locus.experiments.datamodel import userdata

    if not isinstance(top, int) or top < 1:
        raise ValueError(f"--top must be a positive integer; got {top!r}")
    planning, pose = _parameters(profile, key, pairs or [])
    offset_specs(planning, offsets)  # a bad --offsets before any work
    start = time.perf_counter()
    with userdata.datadoc.recording() as reads:  # the data entries the computation reads
        result = compute(key, planning, pose, offsets)
    result["data"] = userdata.figure_record([key], read=reads)
    data, grid = result["data"], result["grid"]
    log(f"platform `{key}`: {userdata.describe_platform(key)}; profile {profile!r}")
    log("data: " + ", ".join(f"{f['path']} ({f['role']}, sha256 {f['sha256'][:12]})" for f in data["files"])
        + "".join(f"; --set {o}" for o in data["overrides"]))
    log("entries: " + ", ".join(f"{e} ({h[:12]})" for e, h in data["entries"].items()))
    log("")
    log(f"Which crossing angles between two straight passes over a feature? ({grid[0]:g}–{grid[-1]:g}°, "
        f"seed {planning['seed']}. Prefer: median locus length in the lowest {100 * planning['prefer_below']:g} % "
        f"of its range; avoid: in the top {100 * (1 - planning['avoid_above']):g} %.)")
    for model, n, bands in result["bands"]:
        log("")
        log(f"- {model.label} offsets, {n:,} pass pairs per angle: {HOW_YOU_FLY.get(model.kind, 'read these bands')}.")
        log(text_table(bands_rows(bands)) if len(bands) else "  (no bands: the curve is flat)")
    log("")
    log(f"Top drivers of locus length (Spearman rho over {result['n_pose']:,} pose-space samples, "
        f"sampling profile {pose['profile']!r}, seed {pose['seed']}; 95 % interval from {_batches(result, pose)}):")
    log(text_table(driver_rows(result["rho"], top)))
    log("")
    log(f"computed in {time.perf_counter() - start:.1f} s (planning and pose_space chapters' code, profile "
        f"{profile!r}; `sss-locus book --name NAME` draws the figures)")
    return result


def _batches(result: dict[str, Any], pose: dict[str, Any]) -> str:
    """The replicate batches the interval used (fewer than asked when there are too few samples
    for batches of three rows), said as such."""
    used = int(result["rho"].attrs.get("n_batches", pose["n_batches"]))
    if used == pose["n_batches"]:
        return f"{used} replicate batches"
    return (f"{used} replicate batches (n_batches = {pose['n_batches']} asked; {result['n_pose']:,} samples "
            "make at most one batch of three rows per three samples)")


def _sig(x: float) -> str:
    """Two significant figures (the chapters' precision for lengths)."""
    return f"{float(round_sig(x, 2)):g}"


def bands_rows(bands: pd.DataFrame) -> pd.DataFrame:
    """The prefer/avoid bands (:func:`sss_locus.experiments.survey_passes.planning.planning_bands`) as rows to
    print: band, angles (deg) and the median locus length (m) within it."""
    return pd.DataFrame({
        "band": bands["kind"],
        "crossing angle (deg)": [f"{lo:g}–{hi:g}" if lo != hi else f"{lo:g}"
                                 for lo, hi in zip(bands["lo_deg"], bands["hi_deg"])],
        "median locus length (m)": [f"{_sig(a)}–{_sig(b)}" if _sig(a) != _sig(b) else _sig(a)
                                    for a, b in zip(bands["median_min"], bands["median_max"])],
    })


def driver_rows(rho: pd.DataFrame, top: int = 5, target: str = "locus_length_m") -> pd.DataFrame:
    """The ``top`` quantities with the largest Spearman |rho| with ``target``
    (:func:`sss_locus.experiments.pose_space.stats.spearman_table`, sorted so), as rows to print."""
    rows = rho[rho["target"] == target].head(top)
    return pd.DataFrame({
        "rank": range(1, len(rows) + 1),
        "quantity": [QUANTITY_WORDS.get(q, q) for q in rows["quantity"]],
        "Spearman rho": [f"{r:.2f}" for r in rows["rho"]],
        "95 % interval": [f"{lo:.2f} to {hi:.2f}" for lo, hi in zip(rows["ci_low"], rows["ci_high"])],
    })


def text_table(rows: pd.DataFrame, indent: int = 2) -> str:
    """``rows`` as an aligned plain-text table (header, rule, one line a row; no index)."""
    columns = [str(c) for c in rows.columns]
    cells = [[str(v) for v in row] for row in rows.itertuples(index=False)]
    widths = [max([len(c)] + [len(r[i]) for r in cells]) for i, c in enumerate(columns)]
    lines = [columns, ["-" * w for w in widths], *cells]
    return "\n".join((" " * indent + "  ".join(v.ljust(w) for v, w in zip(line, widths))).rstrip()
                     for line in lines)
