"""Parameters of the chapter ``notebooks/survey_passes.ipynb`` (Survey passes: locus length against crossing angle (the paper's Fig. 5)).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``survey_passes.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedPlatforms = Field(["boat", "auv"], description='keys of data/platforms.toml and data/survey.toml')
    n_per_angle: int = Field(
        8000, ge=1, le=1_000_000, description='accepted pass pairs per crossing angle (main figure)')
    seed: Seed = Field(1, description='random seed')
    fine_step_deg: float = Field(1.0, gt=0.0, le=90.0, description='crossing-angle step from 0 to fine_max_deg')
    fine_max_deg: float = Field(40.0, ge=0.0, le=180.0, description='end of the fine part of the grid (deg)')
    coarse_step_deg: float = Field(5.0, gt=0.0, le=90.0, description='crossing-angle step beyond fine_max_deg')
    main_offset_model: str = Field(
        "independent", description='offset model of the main figure: "kind:jitter_m:side_rule"')
    sensitivity_models: list[str] = Field(
        ["matched:10:random", "matched:10:same", "matched:10:opposite", "matched:2:same", "matched:30:same"], min_length=1, description='offset models compared with the main one: "kind:jitter_m:side_rule"')
    n_sensitivity: int = Field(
        2000, ge=1, le=1_000_000, description='pass pairs per angle for the offset-model comparison')
    n_batches: int = Field(
        20, ge=3, le=10_000, description='independent replicate batches for the intervals of medians and ratios')
    n_resamples: int = Field(
        200, ge=1, le=100_000, description="bootstrap resamples for the peak angle's interval")
    prefer_below: float = Field(
        0.25, ge=0.0, le=1.0, description='band rule: prefer where the median is in the lowest quarter of its range')
    avoid_above: float = Field(
        0.5, ge=0.0, le=1.0, description='band rule: avoid where the median is in the upper half of its range')
    pitch_levels_deg: list[Annotated[float, Field(ge=0.0, le=90.0)]] = Field(
        [5.0, 10.0, 15.0], min_length=1, description='AUV pitch magnitudes compared nose-up vs nose-down')
    altitude_levels_m: list[Annotated[float, Field(gt=0.0, le=1000.0)]] = Field(
        [7.5, 15.0, 30.0], min_length=1, description='AUV altitudes (both passes) compared for the depth effect')
    n_band: int = Field(
        1000, ge=1, le=1_000_000, description='pass pairs per angle of the worst band (pitch and depth runs)')
    paper_band_deg: list[Annotated[float, Field(ge=0.0, le=180.0)]] = Field(
        [10.0, 40.0], min_length=2, max_length=2, description="the paper's band to avoid, where its pitch claim is also tested (deg)")
    near_window_deg: float = Field(
        10.0, gt=0.0, lt=90.0, description='"near" a repeat or anti-parallel pass: within this many degrees')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
