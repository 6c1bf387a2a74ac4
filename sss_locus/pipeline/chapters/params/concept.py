"""Parameters of the chapter ``notebooks/concept.ipynb`` (Two ranges, one circle, a short locus).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, MemoryPerUnit, NotebookParams, Platforms


class Params(NotebookParams):
    """The parameters of ``concept.ipynb``, their defaults and what each allows."""

    platforms: Platforms = Field(
        ["auv"], description="the first platform's sonar sets the azimuth aperture and the real beam")
    elevation_illustrative_deg: float = Field(
        20.0, gt=0.0, le=90.0, description='widened FULL elevation aperture used for the drawing (deg)')
    feature_x_m: float = Field(9.0, ge=-1000.0, le=1000.0, description="feature position in sensor 1's frame (m)")
    feature_y_m: float = Field(3.0, ge=-1000.0, le=1000.0, description='feature position, y (m)')
    feature_z_m: float = Field(0.0, ge=-1000.0, le=1000.0, description='feature position, z (m)')
    sensor2_x_m: float = Field(
        -1.0, ge=-1000.0, le=1000.0, description="sensor 2's origin in sensor 1's frame (m)")
    sensor2_y_m: float = Field(-2.0, ge=-1000.0, le=1000.0, description='sensor 2 origin, y (m)')
    sensor2_z_m: float = Field(5.0, ge=-1000.0, le=1000.0, description='sensor 2 origin, z (m)')
    sensor2_yaw_deg: float = Field(
        -10.0, ge=-180.0, le=180.0, description="sensor 2's axes in sensor 1's frame: intrinsic Z-Y-X angles (deg)")
    sensor2_pitch_deg: float = Field(25.0, ge=-90.0, le=90.0, description='sensor 2 pitch (deg)')
    sensor2_roll_deg: float = Field(0.0, ge=-180.0, le=180.0, description='sensor 2 roll (deg)')
    view_elev_deg: float = Field(20.0, ge=-90.0, le=90.0, description='camera elevation (deg)')
    view_azim_deg: float = Field(-80.0, ge=-360.0, le=360.0, description='camera azimuth (deg)')
    n_per_arc: Annotated[int, MemoryPerUnit(190)] = Field(
        200, ge=2, le=1_000_000, description='points drawn per locus arc')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
