"""Parameters of the chapter ``notebooks/rigs.ipynb`` (The platforms and their transducer frames).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from sss_locus.pipeline.run.params import DATA_FILES_DOC, DATA_SET_DOC, NotebookParams, Platforms


class Params(NotebookParams):
    """The parameters of ``rigs.ipynb``, their defaults and what each allows."""

    platforms: Platforms = Field(["boat", "auv"], description='platforms drawn, one row each')
    plot_range_m: list[Annotated[float, Field(gt=0.0, le=100.0)]] = Field(
        [1.0, 0.6], min_length=1, description="range (m) to which each platform's frusta are drawn, in the order of platforms; the last value repeats (legibility only)")
    axis_length_m: list[Annotated[float, Field(gt=0.0, le=100.0)]] = Field(
        [0.25, 0.15], min_length=1, description='length (m) of the drawn sensor axes, per platform as plot_range_m')
    data_files: list[str] = Field([], description=DATA_FILES_DOC)
    data_set: list[str] = Field([], description=DATA_SET_DOC)
