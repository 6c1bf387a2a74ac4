"""Parameters of the chapter ``notebooks/planning.ipynb`` (Planning survey passes: crossing angles to prefer and to avoid).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``planning.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedPlatforms = Field(["boat", "auv"], description='keys of data/platforms.toml and data/survey.toml')
    offset_models: list[str] = Field(
        ["independent", "matched:10:same"], min_length=1, description='"independent" or "matched:<jitter_m>:<side_rule>"')
    n_per_angle: list[Annotated[int, Field(ge=3, le=1_000_000)]] = Field(
        [8000, 2000], min_length=1, description='pass pairs per angle, one per offset model (an interval needs three)')
    seed: Seed = Field(1, description='random seed')
    prefer_below: float = Field(
        0.25, ge=0.0, le=1.0, description='prefer where the median is in this lowest fraction of its range')
    avoid_above: float = Field(
        0.5, ge=0.0, le=1.0, description='avoid where the median is above this fraction of its range')
    n_resamples: int = Field(
        100, ge=1, le=100_000, description="bootstrap resamples for the peak angle's interval")
    fine_step_deg: float = Field(1.0, gt=0.0, le=90.0, description='grid step up to 40 deg')
    coarse_step_deg: float = Field(5.0, gt=0.0, le=90.0, description='grid step beyond 40 deg')
    near_window_deg: float = Field(
        10.0, gt=0.0, lt=90.0, description='"near" a repeat or anti-parallel pass: within this many degrees')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
