"""Publish a finished figure from a notebook: export it, glue it and its caption, close it.

One call per figure, in the notebook that drew it::

    from sss_locus.pipeline.publish.publish import publish

    publish(fig, "fig-survey-passes", data=curves, caption=caption)

and, in a markdown cell of the same notebook, the caption is written nowhere else::

    ```{glue:figure} fig-survey-passes
    :name: fig-survey-passes

    {glue:md}`fig-survey-passes-caption:myst`
    ```

    ```{include} ../_cite/fig-survey-passes.md
    ```

A notebook that draws one figure per platform of the run cannot name the labels in a markdown
cell (the platforms are a parameter). It publishes each figure as above and then glues the
blocks that place them, one after the other, under one key (:func:`place`)::

    place("ps-heatmaps-figures", [f"fig-heatmaps-{label_key(k)}" for k in platforms])

and the markdown cell pastes them, parsed as MyST so the figures get their numbers and labels::

    ```{glue:md} ps-heatmaps-figures
    :format: myst
    ```

The included block (written by :mod:`sss_locus.pipeline.book.bookbuild` at every build) sits under
the figure: its files, its data, a link to the code cell that drew it and to the notebook, and its
BibTeX entry. ``publish`` marks its own cell with an anchor (``#<label>-source``) for that link
and records the cell's execution count (``In [n]``) in the manifest.

The run's parameters, profile and notebook come from the runner (``sss-locus run`` / ``book``
put them in the kernel's environment, :func:`run_parameters`); the notebook never retypes them.
Outside the runner (a plain ``papermill`` call or an interactive session) the manifest says so:
notebook ``"interactive"``, profile ``"none"``, parameters ``{}``.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

import pandas as pd

from sss_locus import paths
from sss_locus.pipeline.run import context
from sss_locus.pipeline.publish import export, provenance


def run_parameters() -> dict[str, Any]:
    """The parameters of the current run, as resolved by the runner (``{}`` outside it)."""
    values = json.loads(json.dumps(dict(context.current().parameters), default=provenance.json_default))
    return paths.public_values(values)  # a user's file by its name


def publish(fig: Any, label: str, data: pd.DataFrame | Mapping[str, pd.DataFrame], *,
            caption: str, platforms: Sequence[str] | None = None, input_files: Sequence[Any] = (),
            attachments: Mapping[str, str] | None = None) -> None:
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
    platforms : sequence of str, optional
        The platforms the figure shows, when not every platform of the run (a figure per
        platform, or one drawn from the first platform only): its manifest and BibTeX name exactly
        these platforms and the data they read.
    input_files : sequence of path or of (path, role), optional
        A user's own input files (recorded with their SHA-256 and role,
        :func:`sss_locus.pipeline.publish.export.export_figure`).
    attachments : mapping of str to str, optional
        Files computed with the figure (name -> text, e.g. ``{"mission.plan": ...}``), published
        beside it as ``<label>--<name>`` under the same manifest and BibTeX entry.
    """
    import matplotlib.pyplot as plt
    from IPython.display import Markdown
    from myst_nb import glue

    from IPython import get_ipython
    from IPython.display import HTML, Image, display

    shell = get_ipython()
    cell = getattr(shell, "execution_count", None) if shell is not None else None
    shown: list[bytes] = []  # the chapter's picture, drawn from the exported files' layout
    export.export_figure(fig, label, data, caption=caption, parameters=run_parameters(), cell=cell,
                         shown=shown, platforms=platforms, input_files=input_files, attachments=attachments)
    display(HTML(f'<span id="{label}-source" class="figure-source-anchor"></span>'))
    glue(label, Image(data=shown[0], format="png"), display=False)
    glue(f"{label}-caption", Markdown(caption), display=False)
    plt.close(fig)


def figure_block(label: str) -> str:
    """The MyST that places the published figure ``label`` with its caption and citation block."""
    return (f"```{{glue:figure}} {label}\n:name: {label}\n\n{{glue:md}}`{label}-caption:myst`\n```\n\n"
            f"```{{include}} ../_cite/{label}.md\n```\n")


def place(key: str, labels: Sequence[str]) -> None:
    """Glue, as ``key``, the blocks placing each figure of ``labels`` (published by this notebook),
    in order; paste them with a ``{glue:md}`` directive of format ``myst`` (module docstring)."""
    from IPython.display import Markdown
    from myst_nb import glue

    if isinstance(labels, str) or not labels:
        raise ValueError(f"labels must be a non-empty list of figure labels; got {labels!r}")
    glue(key, Markdown("\n".join(figure_block(label) for label in labels)), display=False)


def publish_table(frame: pd.DataFrame, label: str, *, caption: str, platforms: Sequence[str] | None = None,
                  input_files: Sequence[Any] = ()) -> None:
    """Export a table the chapter shows as a citable table (``tab-`` label, its CSV, manifest and
    BibTeX beside the figures, :func:`sss_locus.pipeline.publish.table_export.export_table`) with the
    run's parameters; ``platforms``: those its rows come from, when not every platform of the run;
    ``input_files``: a user's own input files it was computed from (as for :func:`publish`)."""
    from sss_locus.pipeline.publish.table_export import export_table

    export_table(frame, label, caption=caption, parameters=run_parameters(), platforms=platforms,
                 input_files=input_files)
