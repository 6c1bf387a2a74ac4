"""Parameters of the chapter ``notebooks/survey_design.ipynb`` (Survey design: which lines to run).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, NoisyPlatforms, NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``survey_design.ipynb``, their defaults and what each allows."""

    platforms: NoisyPlatforms = Field(["boat", "auv"], description='keys of data/platforms.toml with a [mission] table')
    area: str = Field(
        "data/examples/survey_area.toml", description='survey area file: TOML (vertices_m or vertices_lonlat; optional navigable water, bathymetry grid) or GeoJSON')
    area_sha256: str = Field("", description='set by the runner: SHA-256 of the area file')
    water_depth_m: float = Field(
        0.0, ge=0.0, le=12000.0, description="mean water depth over the area, m; 0: the area file's (water_depth_m or bathymetry grid)")
    ardupilot_platforms: list[str] = Field(
        ["boat"], min_length=1, description='platforms that run ArduPilot (they also get .plan and .waypoints files; other keys are ignored)')
    terrain: Literal["flat", "slope", "mound", "step", "random"] = Field(
        "flat", description='seafloor model of data/terrain.toml')
    objective: Literal["locus", "three_view", "reconstruction"] = Field(
        "locus", description='what the plans minimise')
    headings_deg: list[Annotated[float, Field(ge=0.0, le=360.0)]] = Field(
        [90.0, 45.0, 0.0], min_length=1, description='main-line compass headings searched, deg clockwise from north')
    spacing_fractions: list[Annotated[float, Field(gt=0.0, le=10.0)]] = Field(
        [0.8, 1.2, 1.6], min_length=1, description='main-line spacings searched, x the range scale')
    crossing_angles_deg: list[Annotated[float, Field(ge=0.0, le=180.0)]] = Field(
        [0.0, 20.0, 45.0, 90.0], min_length=1, description='second line set: 0 is an offset repeat, else cross lines, deg')
    no_cross_lines: bool = Field(True, description='also search plans of main lines only')
    cross_spacing_factors: list[Annotated[float, Field(gt=0.0, le=10.0)]] = Field(
        [1.0, 2.0], min_length=1, description='cross-line spacing searched, x the main spacing')
    altitude_fractions: list[Annotated[float, Field(gt=0.0, lt=1.0)]] = Field(
        [0.08, 0.14], min_length=1, description='altitudes searched, x the range scale (fixed-depth platforms: the water depth)')
    pitches_deg: list[Annotated[float, Field(ge=-90.0, le=90.0)]] = Field(
        [0.0], min_length=1, description="vehicle pitches searched, deg (kept within the platform's limit)")
    n_features: int = Field(200, ge=10, le=100_000, description='features per plan')
    grid_m: float = Field(20.0, gt=0.0, le=1000.0, description='coverage grid spacing, m')
    noise_seeds: list[Annotated[int, Field(ge=0, le=4_294_967_295)]] = Field(
        [1, 2, 3, 4, 5], min_length=1, description='independent seeds (simulated surveys) the plans are scored on with the joint adjustment (at least 3)')
    n_scored: int = Field(
        8, ge=0, le=1000, description="the search's leading plans scored with the joint adjustment (eligible, no longer than the standard plan, smallest objective)")
    decide_on: Literal["horizontal", "vertical", "shape"] = Field(
        "horizontal", description="the joint estimate's error the recommendation is decided on")
    seed: Seed = Field(1, description='random seed')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
