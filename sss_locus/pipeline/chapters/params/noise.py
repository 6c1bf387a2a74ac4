"""Parameters of the chapter ``notebooks/noise.ipynb`` (Noise: does the crossing-angle advice survive?).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedNoisyPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``noise.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedNoisyPlatforms = Field(
        ["auv", "boat"], description='keys of data/platforms.toml, data/survey.toml, data/noise.toml')
    n_per_angle: int = Field(200, ge=1, le=100_000, description='pass pairs per crossing angle')
    fine_step_deg: float = Field(2.0, gt=0.0, le=90.0, description='crossing-angle step up to fine_max_deg')
    fine_max_deg: float = Field(40.0, ge=0.0, le=180.0, description='end of the fine part of the grid (deg)')
    coarse_step_deg: float = Field(10.0, gt=0.0, le=90.0, description='crossing-angle step beyond fine_max_deg')
    n_draws: int = Field(64, ge=2, le=100_000, description='noise draws per pass pair')
    noise_scales: list[Annotated[float, Field(gt=0.0, le=100.0)]] = Field(
        [1.0, 0.1], min_length=1, description='multiples of the data/noise.toml standard deviations; the first is the headline')
    other_offset_models: list[str] = Field(
        ["matched:10:same"], min_length=1, description='offset models also run with noise, at every level: "matched:<jitter_m>:<side_rule>"')
    n_resamples: int = Field(
        100, ge=1, le=100_000, description="bootstrap resamples for the peak angles' intervals")
    n_check: int = Field(40, ge=1, le=10_000, description='pass pairs for the Monte Carlo vs first-order check')
    n_check_draws: int = Field(2000, ge=2, le=1_000_000, description='noise draws per pass pair in that check')
    seed: Seed = Field(1, description='random seed')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
