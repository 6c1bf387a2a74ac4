"""Parameters of the chapter ``notebooks/reconstruction.ipynb`` (Beyond the flat seafloor, measured).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, EnvelopedNoisyPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``reconstruction.ipynb``, their defaults and what each allows."""

    platforms: EnvelopedNoisyPlatforms = Field(
        ["auv", "boat"], description='keys of data/platforms.toml, data/survey.toml, data/noise.toml')
    n_features: int = Field(200, ge=10, le=20_000, description='features per survey')
    n_seeds: int = Field(20, ge=3, le=1000, description='independent simulated surveys per case')
    rms_reliefs_m: list[Annotated[float, Field(ge=0.0, le=100.0)]] = Field(
        [0.0, 1.0, 4.0], min_length=1, description='RMS relief of the random seafloor, m')
    slopes_deg: list[Annotated[float, Field(ge=0.0, le=60.0)]] = Field(
        [0.0, 5.0, 10.0, 20.0], min_length=1, description='seafloor slopes across the main lines, deg')
    dense_spacing_fractions: list[Annotated[float, Field(gt=0.0, le=10.0)]] = Field(
        [0.4], min_length=1, description="denser main-line spacings beside the routine one, multiples of the sonar's range")
    navigation: Literal["per_pass", "per_view"] = Field("per_pass", description='navigation-error model')
    shadowing: Literal["off", "on"] = Field("off", description='drop views whose ray the terrain blocks')
    seed: Seed = Field(1, description="first survey's seed")
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
