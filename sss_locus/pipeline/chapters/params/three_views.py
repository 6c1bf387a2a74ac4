"""Parameters of the chapter ``notebooks/three_views.ipynb`` (Three views: when a third pass pins the feature down).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedNoisyPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``three_views.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedNoisyPlatforms = Field(
        ["auv", "boat"], description='keys of data/platforms.toml (and data/survey.toml, data/noise.toml)')
    n_per_pattern: int = Field(4000, ge=1, le=1_000_000, description='configurations per platform and pattern')
    sweep_step_deg: float = Field(
        15.0, gt=0.0, le=180.0, description='heading grid step of the sweep over passes 2 and 3 (deg)')
    n_per_cell: int = Field(1000, ge=1, le=100_000, description='configurations per heading pair in the sweep')
    range_sigma_m: float = Field(0.01, ge=0.0, le=10.0, description='range error (m) for the conditioning measure')
    surface_tilts_deg: list[Annotated[float, Field(gt=0.0, lt=90.0)]] = Field(
        [15.0, 35.0], min_length=1, description="other tilts of surface vessels' transducers (the pose-space tilt check, deg)")
    seed: Seed = Field(1, description='random seed')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
