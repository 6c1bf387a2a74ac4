"""Parameters of the chapter ``notebooks/your_pings.ipynb`` (Your own pings).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, NotebookParams


class Params(NotebookParams):
    """The parameters of ``your_pings.ipynb``, their defaults and what each allows."""

    observations: str = Field(
        "data/examples/your_pings/example_sightings.csv", description='sightings CSV, or XTF matches CSV (file, ping, channel, sample)')
    observations_sha256: str = Field(
        "", description='set by the runner: SHA-256 of the observations (and XTF, truth) files')
    truth: str = Field(
        "data/examples/your_pings/example_truth.csv", description='known positions to compare with ("" for none)')
    origin: list = Field(  # checked with the observations: empty or [lon_deg, lat_deg] (frame_from_origin)
        [], description='[lon_deg, lat_deg] of the local frame (empty: the mean of the lon/lat sightings; none for local metres)')
    missing_attitude: Literal["refuse", "level"] = Field(
        "refuse", description='sightings without pitch/roll: refuse them, or take the vehicle as level')
    sample_order: Literal["detect", "near_first", "port_far_first"] = Field(
        "detect", description='XTF: which end of each channel is the near end: from the data, or set')
    towfish: Literal["auto", "recorded", "apply_layback"] = Field(
        "auto", description="XTF: SensorX/Y is the towfish's, or the tow point's to shift by the layback")
    range_sigma_m: float = Field(
        0.1, ge=1e-06, le=100.0, description='range standard deviation where the file gives none, m')
    aperture_margin_deg: float = Field(
        10.0, ge=0.0, le=90.0, description='N views: widening of the beams for navigation and attitude errors, deg')
    below_sensors: bool = Field(True, description='N views: admit only points below the sensors of the feature')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
