"""Parameters of the chapter ``notebooks/derivation.ipynb`` (The locus, derived symbolically).

Its ``parameters`` cell is :func:`sss_locus.pipeline.run.paramcell.parameters_cell` of :class:`Params`.
"""

from __future__ import annotations

from pydantic import Field

from sss_locus.pipeline.run.params import NotebookParams, Seed


class Params(NotebookParams):
    """The parameters of ``derivation.ipynb``, their defaults and what each allows."""

    seed: Seed = Field(0, description='random seed of the numeric cross-check')
    n_check: int = Field(
        2000, ge=1, le=1_000_000, description='number of random configurations in the cross-check')
    elevation_check_deg: float = Field(
        10.0, gt=0.0, le=90.0, description="sensor 1's full elevation aperture in the cross-check (deg)")
