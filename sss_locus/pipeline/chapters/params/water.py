"""Parameters of the chapter ``notebooks/water.ipynb`` (The sea surface as a constraint).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``water.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedPlatforms = Field(["auv", "boat"], description='keys of data/platforms.toml')
    n_samples: int = Field(200_000, ge=1000, le=5_000_000, description='pose-space samples per run')
    n_per_angle: int = Field(1000, ge=1, le=1_000_000, description='survey pass pairs per crossing angle')
    crossing_step_deg: float = Field(10.0, gt=0.0, le=90.0, description='crossing-angle step of the survey passes')
    seed: Seed = Field(1, description='random seed of the samplers')
    surface_tilts_deg: list[Annotated[float, Field(gt=0.0, lt=90.0)]] = Field(
        [15.0], min_length=1, description='extra tilts of surface vessels (the pose-space tilt check)')
    submerged_depths_m: list[Annotated[float, Field(ge=0.0, le=11000.0)]] = Field(
        [2.0, 10.0, 50.0], min_length=1, description='depths of vehicle 1 below the surface, submerged platforms (m)')
    seafloor_margins_m: list[Annotated[float, Field(ge=0.0, le=11000.0)]] = Field(
        [1.0, 10.0], min_length=1, description='known water depth: this far below each feature (m), the seafloor section')
    n_batches: int = Field(20, ge=3, le=10_000, description='independent replicate batches for the intervals')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
