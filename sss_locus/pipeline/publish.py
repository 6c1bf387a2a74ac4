"""Publish a finished figure from a notebook: export it, glue it and its caption, close it.

One call per figure, in the notebook that drew it::

    from sss_locus.pipeline.publish import publish

    publish(fig, "fig-survey-passes", data=curves, caption=caption)

and, in a markdown cell of the same notebook, the caption is written nowhere else::

    ```{glue:figure} fig-survey-passes
    :name: fig-survey-passes

    {glue:md}`fig-survey-passes-caption:myst`
    ```

The run's parameters, profile and notebook come from the runner (``sss-locus run`` / ``book``
put them in the kernel's environment, :func:`run_parameters`); the notebook never retypes them.
Outside the runner (a plain ``papermill`` call or an interactive session) the manifest says so:
notebook ``"interactive"``, profile ``"none"``, parameters ``{}``.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Any

import pandas as pd

from sss_locus.pipeline import export, provenance


def run_parameters() -> dict[str, Any]:
    """The parameters of the current run, as resolved by the runner (``{}`` outside it)."""
    text = os.environ.get(provenance.PARAMETERS_ENV)
    if not text:
        return {}
    try:
        values = json.loads(text)
    except ValueError:
        return {}
    return values if isinstance(values, dict) else {}


def publish(fig: Any, label: str, data: pd.DataFrame | Mapping[str, pd.DataFrame], *,
            caption: str) -> None:
    """Export ``fig`` as a citable figure, glue it and its caption, and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    label : str
        ``fig-`` plus lower-case words joined by hyphens; also the figure's ``:name:``.
    data : pandas.DataFrame or dict of str to pandas.DataFrame
        The plotted values (written as CSV beside the images).
    caption : str
        MyST Markdown (``$...$`` math allowed). Glued as ``<label>-caption`` for the
        ``{glue:figure}`` block and recorded in the manifest and BibTeX entry.
    """
    import matplotlib.pyplot as plt
    from IPython.display import Markdown
    from myst_nb import glue

    export.export_figure(fig, label, data, caption=caption, parameters=run_parameters())
    glue(label, fig, display=False)
    glue(f"{label}-caption", Markdown(caption), display=False)
    plt.close(fig)
