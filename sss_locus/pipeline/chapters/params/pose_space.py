"""Parameters of the chapter ``notebooks/pose_space.ipynb`` (What drives locus length: the pose-space Monte Carlo).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, MemoryPerUnit, NotebookParams, Platforms, Seed


class Params(NotebookParams):
    """The parameters of ``pose_space.ipynb``, their defaults and what each allows."""

    platforms: Platforms = Field(["auv", "boat"], description='keys of data/platforms.toml')
    n_samples: Annotated[int, MemoryPerUnit(2800)] = Field(
        1_200_000, ge=100, le=5_000_000, description='Monte Carlo samples per platform and seed')
    seed: Seed = Field(1, description='main random seed')
    check_seed: Seed = Field(2, description='second seed, to show the results are stable')
    profile: Literal["platform", "unconstrained"] = Field(
        "platform", description='"platform" (vehicle-grounded) or "unconstrained"')
    feature_distribution: Literal["angles", "volume"] = Field(
        "angles", description='"angles" (uniform r, theta, phi) or "volume"')
    pitch_max_deg: float = Field(
        -1.0, ge=-1.0, le=90.0, description='pitch limit override (deg); negative keeps the platform limit')
    heatmap_side2: Literal["port", "either"] = Field(
        "port", description='sensor 2\'s side in the heatmaps: "port" or "either"')
    n_bins: int = Field(16, ge=2, le=200, description='heatmap bins per axis')
    min_count: int = Field(30, ge=1, description='bins with fewer samples are masked')
    n_batches: int = Field(20, ge=3, le=10_000, description='independent replicate batches for the rho intervals')
    scatter_points: int = Field(6000, ge=0, le=1_000_000, description='points drawn in the scatter panel')
    boat_tilts_deg: list[Annotated[float, Field(gt=0.0, lt=90.0)]] = Field(
        [15.0, 25.0, 35.0], min_length=1, description='assumed Omniscan tilts to compare (deg)')
    n_check_samples: int = Field(
        150_000, ge=100, le=5_000_000, description='samples per run in the modelling-choice checks')
    vehicle_depths: Literal["in_water", "difference", "free"] = Field(
        "in_water", description='AUV depths: both in the water ("in_water"), depth difference only ("difference") or "free"')
    misalignment_reading: Literal["magnitude", "signed"] = Field(
        "magnitude", description="the paper's max(psi1, psi2) read as max(|psi1|, |psi2|) or signed")
    n_target_samples: int = Field(
        50_000, ge=100, le=5_000_000, description="targeted extra samples inside the azimuth heatmap's peak bin")
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
